//! The plant models (`src/sim/plant`).

mod spindle_motor;
