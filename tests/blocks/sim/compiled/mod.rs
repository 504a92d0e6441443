//! The compiled backend (`src/sim/compiled`).

mod build;
