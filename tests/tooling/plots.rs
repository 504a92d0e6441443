//! The pulse-generator figures: written as SVG by the library and the CLI,
//! with their figures of merit, and bad settings refused with a message.

use std::process::Command;

use motion_hdl::plots::{plot_pulse_trains, plot_unevenness, PlotError};

#[test]
fn pulse_trains_figure_shows_the_single_period_idle_time() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("trains.svg");
    let mu = plot_pulse_trains(400, 130, &path).unwrap();
    assert!((mu - 0.35).abs() < 1e-12, "mu {mu}");
    let svg = std::fs::read_to_string(&path).unwrap();
    assert!(svg.starts_with("<svg"), "not an SVG");
    for text in [
        "mu = 0.3500",
        "N1 = 60",
        "N2 = 70",
        "idle: 140 ticks",
        "paper order",
        "interleaved",
    ] {
        assert!(svg.contains(text), "figure lacks {text:?}");
    }
}

/// The background's figure: with T = 4000, mu reaches almost one half.
#[test]
fn unevenness_figure_finds_the_worst_n() {
    let dir = tempfile::tempdir().unwrap();
    let (worst, at) = plot_unevenness(4000, &dir.path().join("mu.svg")).unwrap();
    assert_eq!(at, 1001);
    assert!((worst - (1.0 - 1001.0 * 2.0 / 4000.0)).abs() < 1e-12);
}

#[test]
fn bad_settings_are_errors_naming_the_problem() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("x.svg");
    assert!(matches!(
        plot_pulse_trains(401, 10, &path),
        Err(PlotError::BadPeriod(401))
    ));
    assert!(matches!(
        plot_pulse_trains(0, 0, &path),
        Err(PlotError::BadPeriod(0))
    ));
    assert!(matches!(
        plot_pulse_trains(400, 201, &path),
        Err(PlotError::BadCount {
            count: 201,
            half: 200
        })
    ));
    assert!(matches!(
        plot_pulse_trains(1 << 40, 1, &path),
        Err(PlotError::PeriodTooLong { .. })
    ));
    let missing = dir.path().join("no/such/dir/x.svg");
    assert!(matches!(
        plot_pulse_trains(400, 10, &missing),
        Err(PlotError::Draw { .. })
    ));
}

#[test]
fn cli_writes_both_figures_and_refuses_bad_input() {
    let dir = tempfile::tempdir().unwrap();
    let cli = env!("CARGO_BIN_EXE_motion-hdl");
    let ok = Command::new(cli)
        .args([
            "plot-pulses",
            "--period",
            "4000",
            "--count",
            "1300",
            "--out-dir",
        ])
        .arg(dir.path())
        .output()
        .unwrap();
    assert!(
        ok.status.success(),
        "{}",
        String::from_utf8_lossy(&ok.stderr)
    );
    assert!(dir.path().join("pulse-trains-T4000-N1300.svg").exists());
    assert!(dir.path().join("unevenness-T4000.svg").exists());
    let bad = Command::new(cli)
        .args([
            "plot-pulses",
            "--period",
            "4000",
            "--count",
            "2001",
            "--out-dir",
        ])
        .arg(dir.path())
        .output()
        .unwrap();
    assert!(!bad.status.success());
    let message = String::from_utf8_lossy(&bad.stderr);
    assert!(
        message.contains("N = 2001 must be at most T/2 = 2000"),
        "{message}"
    );
}
