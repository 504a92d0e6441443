//! Report figures, drawn with `plotters` as SVG, and simulation waveforms
//! rendered as SVG.

pub mod energy;
pub mod pulse_trains;
pub mod trajectory;
pub mod waveform;

pub use energy::plot_energy;
pub use pulse_trains::{plot_pulse_trains, plot_unevenness, PlotError};
pub use trajectory::{plot_following_error, plot_path_xy, plot_speed};
pub use waveform::{render_svg, WaveformError};
