//! The laser's energy per millimetre along each burn, measured at the
//! pins, against the programmed value.

use std::path::Path;

use plotters::prelude::*;

use super::pulse_trains::{draw_error, PlotError};
use crate::host::laser_log::BurnEnergy;

/// Draws every burn's windows (full-power ms per mm) one after another
/// along the x axis (mm of burn, the trims and the gaps between burns
/// left out), each with its programmed value as a line.
pub fn plot_energy(burns: &[BurnEnergy], path: &Path) -> Result<(), PlotError> {
    let err = draw_error(path);
    let ms = 1e3;
    let total: f64 = burns.iter().map(|b| b.length_mm).sum::<f64>().max(1e-3);
    let top = burns
        .iter()
        .flat_map(|b| b.windows.iter().map(|w| w.energy).chain([b.programmed]))
        .fold(0.0, f64::max)
        * ms
        * 1.2;
    let root = SVGBackend::new(path, (1000, 450)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| err(e.to_string()))?;
    let mut chart = ChartBuilder::on(&root)
        .caption(
            "Laser energy per mm at the pins, per burn",
            ("sans-serif", 18),
        )
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(70)
        .build_cartesian_2d(0f64..total, 0f64..top.max(1e-9))
        .map_err(|e| err(e.to_string()))?;
    chart
        .configure_mesh()
        .x_desc("mm of burn (burns one after another)")
        .y_desc("full-power ms per mm")
        .draw()
        .map_err(|e| err(e.to_string()))?;
    let mut offset = 0.0;
    for (k, burn) in burns.iter().enumerate() {
        let programmed = burn.programmed * ms;
        let line = chart
            .draw_series(LineSeries::new(
                [(offset, programmed), (offset + burn.length_mm, programmed)],
                BLUE.stroke_width(1),
            ))
            .map_err(|e| err(e.to_string()))?;
        if k == 0 {
            line.label("programmed: S / laser_s_max / F")
                .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLUE));
        }
        let points = chart
            .draw_series(LineSeries::new(
                burn.windows
                    .iter()
                    .map(|w| (offset + w.at_mm, w.energy * ms)),
                RED.stroke_width(1),
            ))
            .map_err(|e| err(e.to_string()))?;
        if k == 0 {
            points
                .label("at the pins (windows of 0.5 mm)")
                .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], RED));
        }
        offset += burn.length_mm;
    }
    if !burns.is_empty() {
        chart
            .configure_series_labels()
            .border_style(BLACK)
            .draw()
            .map_err(|e| err(e.to_string()))?;
    }
    root.present().map_err(|e| err(e.to_string()))
}
