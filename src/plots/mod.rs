//! Report figures, drawn with `plotters` as SVG.

pub mod pulse_trains;

pub use pulse_trains::{plot_pulse_trains, plot_unevenness, PlotError};
