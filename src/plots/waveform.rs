//! Waveforms of a stepped simulation: chosen signals of a VCD as an SVG.

use std::path::Path;

use crate::sim::CLOCK_PERIOD_PS;

/// The SVG could not be rendered (unknown signal name, unreadable VCD, ...).
#[derive(Debug, thiserror::Error)]
#[error("waveform rendering failed: {0}")]
pub struct WaveformError(pub String);

/// Renders chosen signals of a VCD written by [`crate::sim::Harness::record_vcd`]
/// as an SVG waveform, between `from_cycle` and `to_cycle`.
///
/// Signal names are hierarchical paths starting at `uut`, for example
/// `uut.clock` or `uut.counter.q`.
pub fn render_svg(
    vcd: &Path,
    svg: &Path,
    signals: &[&str],
    from_cycle: u64,
    to_cycle: u64,
) -> Result<(), WaveformError> {
    let period = CLOCK_PERIOD_PS;
    rust_hdl::prelude::vcd_to_svg(
        &vcd.display().to_string(),
        &svg.display().to_string(),
        signals,
        from_cycle * period,
        to_cycle * period,
    )
    .map_err(|e| WaveformError(e.to_string()))
}
