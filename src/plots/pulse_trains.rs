//! The figures of the dual-period uniform pulse generator: one period's
//! pulse train in the single-period, paper-order and interleaved forms, and
//! the single-period unevenness mu against N.

use std::path::Path;

use plotters::prelude::*;

use crate::blocks::uniform_pulse_gen::model::{
    single_period_train, single_period_unevenness, PulsePlan,
};

/// The largest T drawn tick by tick in the pulse-train figure.
pub const MAX_TRAIN_PERIOD: u64 = 200_000;
/// The largest T for the unevenness figure (one point per N up to T/2).
pub const MAX_UNEVENNESS_PERIOD: u64 = 20_000_000;

/// Why a figure could not be drawn.
#[derive(Debug, thiserror::Error)]
pub enum PlotError {
    /// T is not an even number of at least 2 ticks.
    #[error("period T = {0} must be even and at least 2 ticks")]
    BadPeriod(u64),
    /// T is too long to draw.
    #[error("period T = {period} is too long for this figure (at most {max} ticks)")]
    PeriodTooLong {
        /// The requested T.
        period: u64,
        /// The limit.
        max: u64,
    },
    /// N is outside 0..=T/2.
    #[error("count N = {count} must be at most T/2 = {half}")]
    BadCount {
        /// The requested N.
        count: u64,
        /// T/2.
        half: u64,
    },
    /// Drawing or writing the SVG failed.
    #[error("could not draw {path}: {message}")]
    Draw {
        /// The figure file.
        path: String,
        /// What plotters reported.
        message: String,
    },
}

fn check_period(period: u64, max: u64) -> Result<(), PlotError> {
    if period < 2 || period % 2 == 1 {
        return Err(PlotError::BadPeriod(period));
    }
    if period > max {
        return Err(PlotError::PeriodTooLong { period, max });
    }
    Ok(())
}

pub(crate) fn draw_error(path: &Path) -> impl Fn(String) -> PlotError + '_ {
    move |message| PlotError::Draw {
        path: path.display().to_string(),
        message,
    }
}

/// The waveform of a per-tick level sequence as (tick, level) corners.
fn waveform(levels: &[bool], base: f64) -> Vec<(f64, f64)> {
    let mut points = Vec::with_capacity(levels.len() / 2 + 2);
    let mut last = None;
    for (t, &level) in levels.iter().enumerate() {
        if last != Some(level) {
            let y = base + if level { 0.8 } else { 0.0 };
            if let Some(previous) = last {
                points.push((t as f64, base + if previous { 0.8 } else { 0.0 }));
            }
            points.push((t as f64, y));
            last = Some(level);
        }
    }
    if let Some(level) = last {
        points.push((levels.len() as f64, base + if level { 0.8 } else { 0.0 }));
    }
    points
}

/// Draws one period of (T, N) as three pulse trains, one above the other:
/// the single-period algorithm with its idle tail shaded, the paper order
/// and the interleaved order. Returns mu of the single-period form.
pub fn plot_pulse_trains(period: u64, count: u64, path: &Path) -> Result<f64, PlotError> {
    check_period(period, MAX_TRAIN_PERIOD)?;
    if count > period / 2 {
        return Err(PlotError::BadCount {
            count,
            half: period / 2,
        });
    }
    let (plan, _) = PulsePlan::new(period, count);
    let mu = single_period_unevenness(period, count);
    let err = draw_error(path);
    let root = SVGBackend::new(path, (1200, 420)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| err(e.to_string()))?;
    let title = format!(
        "T = {period} ticks, N = {count}: Tp1 = {}, N1 = {}, N2 = {}; single-period mu = {mu:.4}",
        plan.short_period(),
        plan.short_pulses,
        plan.long_pulses
    );
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 18))
        .margin(12)
        .x_label_area_size(36)
        .y_label_area_size(140)
        .build_cartesian_2d(0f64..period as f64, -0.2f64..3.0)
        .map_err(|e| err(e.to_string()))?;
    chart
        .configure_mesh()
        .disable_y_mesh()
        // Labels every 0.1; only the middle of each train is named.
        .y_labels(33)
        .y_label_formatter(&|y| {
            let name = ["interleaved", "paper order", "single period"]
                .iter()
                .enumerate()
                .find(|(row, _)| (y - (*row as f64 + 0.4)).abs() < 0.05);
            name.map(|(_, name)| name.to_string()).unwrap_or_default()
        })
        .x_desc("tick")
        .draw()
        .map_err(|e| err(e.to_string()))?;
    let single = single_period_train(period, count);
    let busy = plan.count * plan.short_period();
    chart
        .draw_series(std::iter::once(Rectangle::new(
            [(busy as f64, 1.9), (period as f64, 2.9)],
            RGBColor(255, 210, 210).filled(),
        )))
        .map_err(|e| err(e.to_string()))?
        .label(format!("idle: {} ticks", period - busy))
        .legend(|(x, y)| {
            Rectangle::new(
                [(x, y - 5), (x + 14, y + 5)],
                RGBColor(255, 210, 210).filled(),
            )
        });
    for (levels, base, color) in [
        (single, 2.0, RED),
        (plan.train(false), 1.0, BLUE),
        (plan.train(true), 0.0, GREEN),
    ] {
        chart
            .draw_series(LineSeries::new(
                waveform(&levels, base),
                color.stroke_width(1),
            ))
            .map_err(|e| err(e.to_string()))?;
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()
        .map_err(|e| err(e.to_string()))?;
    root.present().map_err(|e| err(e.to_string()))?;
    Ok(mu)
}

/// Draws mu = 1 - N * Tp / T of the single-period algorithm for N = 1 to
/// T/2. Returns the largest mu and the N where it occurs.
pub fn plot_unevenness(period: u64, path: &Path) -> Result<(f64, u64), PlotError> {
    check_period(period, MAX_UNEVENNESS_PERIOD)?;
    let points: Vec<(f64, f64)> = (1..=period / 2)
        .map(|n| (n as f64, single_period_unevenness(period, n)))
        .collect();
    let (worst_n, worst_mu) =
        points.iter().fold(
            (1.0, 0.0),
            |best, &(n, mu)| if mu > best.1 { (n, mu) } else { best },
        );
    let err = draw_error(path);
    let root = SVGBackend::new(path, (1000, 500)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| err(e.to_string()))?;
    let mut chart = ChartBuilder::on(&root)
        .caption(
            format!(
                "Single-period unevenness, T = {period} ticks (worst mu = {worst_mu:.4} at N = {worst_n}); dual-period: 0 for every N"
            ),
            ("sans-serif", 18),
        )
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d(0f64..(period / 2) as f64, 0f64..0.55)
        .map_err(|e| err(e.to_string()))?;
    chart
        .configure_mesh()
        .x_desc("N (pulses per period)")
        .y_desc("mu = 1 - N*Tp/T")
        .draw()
        .map_err(|e| err(e.to_string()))?;
    chart
        .draw_series(LineSeries::new(points, BLUE.stroke_width(1)))
        .map_err(|e| err(e.to_string()))?;
    root.present().map_err(|e| err(e.to_string()))?;
    Ok((worst_mu, worst_n as u64))
}
