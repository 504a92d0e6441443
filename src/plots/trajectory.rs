//! Figures of a simulated trajectory: the path in the XY plane (planned
//! and as the encoders measured it) and the path speed over time.

use std::path::Path;

use plotters::prelude::*;

use super::pulse_trains::{draw_error, PlotError};

fn bounds(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values.fold((f64::MAX, f64::MIN), |(lo, hi), v| (lo.min(v), hi.max(v)));
    if lo > hi {
        return (0.0, 1.0);
    }
    // 5 % on each side; a flat series gets a unit of room.
    let pad = if hi > lo { (hi - lo) * 0.05 } else { 1.0 };
    (lo - pad, hi + pad)
}

/// Draws the XY path: `planned` positions (one per period) and `measured`
/// ones (sampled from the encoders), in `unit` ("mm", "steps").
pub fn plot_path_xy(
    planned: &[[f64; 3]],
    measured: &[[f64; 3]],
    unit: &str,
    path: &Path,
) -> Result<(), PlotError> {
    let err = draw_error(path);
    let all = || planned.iter().chain(measured);
    let (x0, x1) = bounds(all().map(|p| p[0]));
    let (y0, y1) = bounds(all().map(|p| p[1]));
    let caption = format!("Path in the XY plane ({unit}): planned, and measured by the encoders");
    let root = SVGBackend::new(path, (800, 800)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| err(e.to_string()))?;
    let mut chart = ChartBuilder::on(&root)
        .caption(caption, ("sans-serif", 18))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(|e| err(e.to_string()))?;
    chart
        .configure_mesh()
        .x_desc(format!("X ({unit})"))
        .y_desc(format!("Y ({unit})"))
        .draw()
        .map_err(|e| err(e.to_string()))?;
    chart
        .draw_series(LineSeries::new(
            planned.iter().map(|p| (p[0], p[1])),
            BLUE.stroke_width(3),
        ))
        .map_err(|e| err(e.to_string()))?
        .label("planned")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLUE));
    chart
        .draw_series(LineSeries::new(
            measured.iter().map(|p| (p[0], p[1])),
            RED.stroke_width(1),
        ))
        .map_err(|e| err(e.to_string()))?
        .label("encoders")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], RED));
    chart
        .configure_series_labels()
        .border_style(BLACK)
        .draw()
        .map_err(|e| err(e.to_string()))?;
    root.present().map_err(|e| err(e.to_string()))
}

/// Draws the planned path speed (in `unit`, e.g. "mm/s") at the end of
/// each period of `period_s`, and with `measured` the speed at the pins
/// (one value per period from power-up, labelled `measured.0`): a run
/// through a feed hold, whose time the plan does not know.
pub fn plot_speed(
    speeds: &[f64],
    measured: Option<(&str, &[f64])>,
    period_s: f64,
    unit: &str,
    path: &Path,
) -> Result<(), PlotError> {
    let err = draw_error(path);
    let periods = speeds.len().max(measured.map_or(0, |m| m.1.len()));
    let end = (periods as f64 * period_s).max(period_s);
    let all = speeds.iter().chain(measured.map_or(&[][..], |m| m.1));
    let (_, top) = bounds(all.copied().chain([0.0]));
    let root = SVGBackend::new(path, (1000, 450)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| err(e.to_string()))?;
    let mut chart = ChartBuilder::on(&root)
        .caption(
            "Path speed over time (trapezoidal profile with look-ahead)",
            ("sans-serif", 18),
        )
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(70)
        .build_cartesian_2d(0f64..end, 0f64..top)
        .map_err(|e| err(e.to_string()))?;
    chart
        .configure_mesh()
        .x_desc("time (s)")
        .y_desc(unit)
        .draw()
        .map_err(|e| err(e.to_string()))?;
    let at_period = |k: usize, v: &f64| ((k + 1) as f64 * period_s, *v);
    chart
        .draw_series(LineSeries::new(
            speeds.iter().enumerate().map(|(k, v)| at_period(k, v)),
            BLUE.stroke_width(1),
        ))
        .map_err(|e| err(e.to_string()))?
        .label("planned")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLUE));
    if let Some((label, measured)) = measured {
        chart
            .draw_series(LineSeries::new(
                measured.iter().enumerate().map(|(k, v)| at_period(k, v)),
                RED.stroke_width(1),
            ))
            .map_err(|e| err(e.to_string()))?
            .label(label)
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], RED));
        chart
            .configure_series_labels()
            .border_style(BLACK)
            .draw()
            .map_err(|e| err(e.to_string()))?;
    }
    root.present().map_err(|e| err(e.to_string()))
}

/// Draws each axis's following error (counts) per period under `title`:
/// `errors` holds one value per axis and period; `axes` names the axes
/// drawn.
pub fn plot_following_error<const N: usize>(
    errors: &[[f64; N]],
    axes: &[(usize, &str)],
    title: &str,
    period_s: f64,
    path: &Path,
) -> Result<(), PlotError> {
    let err = draw_error(path);
    let end = (errors.len() as f64 * period_s).max(period_s);
    let (low, high) = bounds(
        errors
            .iter()
            .flat_map(|e| axes.iter().map(|&(k, _)| e[k]))
            .chain([0.0]),
    );
    let root = SVGBackend::new(path, (1000, 450)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| err(e.to_string()))?;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 18))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(70)
        .build_cartesian_2d(0f64..end, low..high)
        .map_err(|e| err(e.to_string()))?;
    chart
        .configure_mesh()
        .x_desc("time (s)")
        .y_desc("commanded - actual (counts)")
        .draw()
        .map_err(|e| err(e.to_string()))?;
    for (i, &(k, name)) in axes.iter().enumerate() {
        let color = Palette99::pick(i).to_rgba();
        chart
            .draw_series(LineSeries::new(
                errors
                    .iter()
                    .enumerate()
                    .map(|(j, e)| ((j + 1) as f64 * period_s, e[k])),
                color.stroke_width(1),
            ))
            .map_err(|e| err(e.to_string()))?
            .label(name.to_string())
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], color));
    }
    chart
        .configure_series_labels()
        .border_style(BLACK)
        .draw()
        .map_err(|e| err(e.to_string()))?;
    root.present().map_err(|e| err(e.to_string()))
}
