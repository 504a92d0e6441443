//! The controller behind `spi_bus_adapter`: `simulate --bus spi` runs a
//! program through the SPI link to the same end as on the parallel bus and
//! reports the frames' share of the period; the CLI names a bad SCLK; the
//! master's timing from a rate.

use motion_hdl::host::simulation::{simulate, SimulationOptions};
use motion_hdl::host::spi::{SpiTiming, SpiTimingError};

/// A 1.2 mm diagonal with a Z step, 1 ms periods: about 80 periods.
const PROGRAM: &str = "units mm
steps_per_mm 80 80 400
feed 40
accel 1000
contour_error 0.05
period_us 1000
start 0 0 0
line 1 0.7 0.1
";

fn options(dir: &std::path::Path, spi_sclk_hz: Option<f64>) -> SimulationOptions {
    SimulationOptions {
        clock_hz: 8e6,
        spi_sclk_hz,
        ..crate::gcode::options(dir)
    }
}

#[test]
fn a_program_runs_through_the_spi_adapter_to_the_end_the_parallel_bus_reaches() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("diagonal.path");
    std::fs::write(&file, PROGRAM).unwrap();
    let parallel = simulate(&file, &options(dir.path(), None)).unwrap();
    let spi = simulate(&file, &options(dir.path(), Some(2e6))).unwrap();
    assert!(parallel.spi.is_none());
    for r in [&parallel, &spi] {
        assert_eq!(r.underruns, 0);
        assert_eq!(r.commanded.map(i64::from), r.target);
        assert_eq!(r.actual.map(i64::from), r.target);
    }
    assert_eq!(spi.periods, parallel.periods);
    let link = spi.spi.expect("the SPI run reports its link");
    assert_eq!(link.sclk_hz, 2e6);
    // Every driver access is a frame: at least the FIFO entries of each
    // period, each of at least 9 bytes.
    assert!(link.stats.frames >= 3 * spi.periods as u64, "{link}");
    assert!(link.stats.bytes >= 9 * link.stats.frames, "{link}");
    assert!(
        link.period_share() > 0.0 && link.period_share() < 1.0,
        "{link}"
    );
    // The frames' clocks are part of the run: the SPI run is longer.
    assert!(spi.cycles > parallel.cycles);
}

#[test]
fn simulate_names_a_bad_bus_or_sclk() {
    let square = motion_hdl::tools::repo_root().join("examples/square.path");
    let run = |args: &[&str]| {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_motion-hdl"))
            .arg("simulate")
            .arg(&square)
            .args(args)
            .output()
            .unwrap();
        assert!(!out.status.success(), "{args:?} succeeded");
        let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
        assert!(!stderr.contains("panicked"), "{stderr}");
        stderr
    };
    let stderr = run(&["--bus", "spi", "--clock-mhz", "8", "--sclk-mhz", "3"]);
    assert!(
        stderr.contains("SCLK of 3000000 Hz: the SPI adapter takes at most a quarter of the 8000000 Hz FPGA clock, 2000000 Hz"),
        "{stderr}"
    );
    let stderr = run(&["--sclk-mhz", "1"]);
    assert!(
        stderr.contains("--sclk-mhz sets the SPI clock: it needs --bus spi"),
        "{stderr}"
    );
    let stderr = run(&["--bus", "usb"]);
    assert!(
        stderr.contains("--bus: unknown bus `usb` (parallel or spi)"),
        "{stderr}"
    );
}

#[test]
fn the_master_timing_rounds_sclk_down_to_whole_clocks() {
    assert_eq!(SpiTiming::at(48e6, 12e6).unwrap(), SpiTiming::FASTEST);
    let t = SpiTiming::at(48e6, 10e6).unwrap();
    assert_eq!((t.high, t.low), (3, 3));
    assert_eq!(t.sclk_hz(48e6), 8e6);
    for bad in [12.5e6, 0.0, -1.0, f64::NAN] {
        assert!(matches!(
            SpiTiming::at(48e6, bad),
            Err(SpiTimingError::TooFast { .. })
        ));
    }
}

/// Bursts through the adapter against the real controller: `ID`,
/// `VERSION` and `CONFIG` in one frame; an unknown address reads 0 and
/// ignores a write, as on the parallel bus, also in a burst after the
/// `SNAPSHOT` write.
#[test]
fn bursts_reach_the_controller_registers_in_one_frame() {
    use motion_hdl::blocks::motion_controller::registers::{global, ID_VALUE, VERSION_VALUE};
    use motion_hdl::host::bus::{ControllerBus, RtlBus};
    use motion_hdl::sim::Backend;
    let backend = Backend::from_env_or(Backend::Verilator).unwrap();
    let mut parallel = RtlBus::new(backend, None).unwrap();
    let config = parallel.read(global::CONFIG);
    let mut bus = RtlBus::new(backend, None).unwrap();
    bus.use_spi(backend, SpiTiming::FASTEST).unwrap();
    let words = bus
        .spi_read_burst(global::ID as u8, 3, false)
        .unwrap()
        .unwrap();
    assert_eq!(words, [ID_VALUE, VERSION_VALUE, config]);
    // 0x1c..0x1f: no register in the 3-axis build.
    bus.write(0x1c, 0x1234_5678);
    assert_eq!(bus.read(0x1c), 0);
    let burst = bus.spi_read_burst(0x1c, 4, true).unwrap().unwrap();
    assert_eq!(burst, [0; 4]);
    assert_eq!(bus.spi_stats().unwrap().frames, 4);
}

/// `SpiBus` in front of the controller's model: the driver's accesses and
/// bursts as frames, the same answers as the bus behind it gives.
#[test]
fn spi_bus_carries_the_driver_accesses_to_any_bus() {
    use motion_hdl::blocks::motion_controller::registers::{global, ID_VALUE, VERSION_VALUE};
    use motion_hdl::host::bus::{ControllerBus, ModelBus};
    use motion_hdl::host::spi::SpiBus;
    use motion_hdl::sim::Backend;
    let mut bus = SpiBus::new(ModelBus::new(), Backend::RustHdl, SpiTiming::FASTEST).unwrap();
    assert_eq!(bus.read(global::ID), ID_VALUE);
    bus.write_burst(global::IRQ_ENABLE as u8, &[0x3, 0x40])
        .unwrap();
    assert_eq!(
        bus.read_burst(global::ID as u8, 2, false).unwrap(),
        [ID_VALUE, VERSION_VALUE]
    );
    assert_eq!(bus.read(global::TICK_DIVISOR), 0x40);
    assert_eq!(bus.inner_mut().read(global::TICK_DIVISOR), 0x40);
    assert_eq!(bus.stats().frames, 4);
}
