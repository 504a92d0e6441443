//! The hexapod (`src/host/hexapod`): kinematics, dynamics, commands and the
//! parallel card's program.

mod card;
mod commands;
mod dynamics;
mod kinematics;
