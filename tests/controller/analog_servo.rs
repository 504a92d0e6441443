//! An analog servo axis from its parts, ahead of the controller's analog
//! mode (#18): the host's position loop writes a code and an update into
//! `dac_interface` (RTL) once per period, an AD669 turns the code into a
//! voltage on its LDAC, the simulated drive and motor turn, and the
//! motor's encoder feeds `quadrature_decoder` (RTL), whose count closes
//! the loop. Clock 1 MHz, period 1 ms.

use motion_hdl::blocks::dac_interface::model::{DacInputs, DacOutputs};
use motion_hdl::blocks::dac_interface::registers::register_map;
use motion_hdl::blocks::dac_interface::DacInterface3;
use motion_hdl::blocks::quadrature_decoder::model::{
    QuadratureDecoderInputs, QuadratureDecoderOutputs,
};
use motion_hdl::blocks::quadrature_decoder::QuadratureDecoder;
use motion_hdl::host::{DriveScale, FollowingError, PositionLoop, ServoGains};
use motion_hdl::sim::plant::{quadrature_state, Ad669Bank, ServoMotor};
use motion_hdl::sim::Harness;

#[test]
fn a_dac_servo_axis_closed_through_the_rtl_ends_within_a_count() {
    const CLOCKS_PER_PERIOD: u64 = 1000;
    let clock_s = 1.0e-6;
    let map = register_map(3, 16).unwrap();
    let code0 = map.address_of("CODE", 0).unwrap() as u64;
    let mut dac = Harness::new("dac_interface", DacInterface3::default()).unwrap();
    let mut decoder = Harness::new(
        "quadrature_decoder",
        QuadratureDecoder::<32, 8, 16>::default(),
    )
    .unwrap();
    let scale = DriveScale::default();
    let mut servo = PositionLoop::new(
        ServoGains::default(),
        scale,
        CLOCKS_PER_PERIOD as f64 * clock_s,
    )
    .unwrap();
    let mut motor = ServoMotor::default();
    let mut figures = FollowingError::default();

    // The move: 20 000 counts at up to 40 000 counts/s, ramps of 0.1 s,
    // then 0.3 s to settle.
    let (distance, v, a): (f64, f64, f64) = (20_000.0, 40_000.0, 400_000.0);
    let ramp = v / a;
    let total = 2.0 * ramp + (distance - v * ramp) / v;
    let command = |t: f64| -> (f64, f64) {
        let t = t.min(total);
        if t < ramp {
            (0.5 * a * t * t, a * t)
        } else if t < total - ramp {
            (0.5 * v * ramp + v * (t - ramp), v)
        } else {
            let d = total - t;
            (distance - 0.5 * a * d * d, a * d)
        }
    };
    let periods = ((total + 0.3) * 1000.0) as u64;

    // The AD669 on channel 0.
    let mut bank = Ad669Bank::new(1);
    let mut count = 0i64;
    let mut ldacs = 0;
    for clock in 0..periods * CLOCKS_PER_PERIOD {
        let mut inputs = DacInputs {
            reset: clock == 0,
            ..Default::default()
        };
        let phase = clock % CLOCKS_PER_PERIOD;
        if clock > 0 && phase == 0 {
            let (position, velocity) = command(clock as f64 * clock_s);
            let out = servo.step(position, velocity, count);
            figures.add(out.following_error);
            inputs.bus_write = true;
            inputs.bus_address = code0;
            inputs.bus_write_data = scale.register_value(out.code) as u64;
        }
        inputs.update = clock > 0 && phase == 1;
        let pins = DacOutputs::from_vector(&dac.step_vector(&inputs.to_vector()).unwrap());
        let before = bank.code(0);
        bank.clock(pins.dac_data, pins.dac_cs_n, pins.dac_l1_n, pins.dac_ldac);
        ldacs += (bank.code(0) != before) as u32;
        let volts = scale.volts(bank.code(0));
        motor.advance(volts, clock_s);
        let (a, b) = quadrature_state(motor.counts());
        let encoder = QuadratureDecoderInputs {
            reset: clock == 0,
            a,
            b,
            ..Default::default()
        };
        let decoded = QuadratureDecoderOutputs::from_vector(
            &decoder.step_vector(&encoder.to_vector()).unwrap(),
        );
        count = decoded.count as u32 as i32 as i64;
    }
    println!(
        "{} periods, {ldacs} output changes; following error max {:.1}, RMS {:.2} counts; ended at {count}",
        figures.periods, figures.max, figures.rms
    );
    assert!(
        (count - 20_000).abs() <= 1,
        "the axis ended at {count}, not within a count of 20000"
    );
    assert_eq!(
        count,
        motor.counts(),
        "the decoder counted every count the motor turned"
    );
    assert!(
        figures.max < 50.0,
        "following error peaked at {:.1} counts",
        figures.max
    );
    assert!(ldacs > 100, "{ldacs} output changes");
}

/// End to end: `examples/square.path` with X as an analog servo on the
/// exported `motion_controller_servo` (compiled), Y and Z stepping. The host
/// closes X's loop once per period through the controller's FIFO, DAC and
/// encoder; X ends within a count of the path's end, Y and Z exactly, and
/// the following error is reported.
#[test]
fn square_path_with_x_as_an_analog_servo_ends_within_a_count() {
    use motion_hdl::host::simulation::{simulate, SimulationOptions};
    let square = motion_hdl::tools::repo_root().join("examples/square.path");
    let dir = tempfile::tempdir().unwrap();
    let options = SimulationOptions {
        format: None,
        machine: None,
        tools: None,
        clock_hz: 4e6,
        uniform: [false; 3],
        servo: [true, false, false],
        step_len: 2,
        step_space: 2,
        out_dir: Some(dir.path().to_path_buf()),
        vcd: None,
        progress: false,
        backend: motion_hdl::sim::Backend::from_env_or(motion_hdl::sim::Backend::Verilator)
            .unwrap(),
        trips: Vec::new(),
        hold: None,
        probe_plane: None,
        soft_limits: [None; 3],
        spindle: Default::default(),
        spi_sclk_hz: None,
    };
    let r = simulate(&square, &options).unwrap_or_else(|e| panic!("{e}"));
    let fe = r.following[0].expect("X's following error");
    println!(
        "X servo: following error max {:.1}, RMS {:.2} counts over {} periods; settled {} periods after the path; ended at {:?} for {:?}",
        fe.max, fe.rms, fe.periods, r.settle_periods, r.actual, r.target
    );
    assert!(
        (r.actual[0] as i64 - r.target[0]).abs() <= 1,
        "X ended at {}, target {}",
        r.actual[0],
        r.target[0]
    );
    for k in 1..3 {
        assert_eq!(r.commanded[k] as i64, r.target[k], "axis {k} commanded");
        assert_eq!(r.actual[k] as i64, r.target[k], "axis {k} actual");
    }
    assert_eq!(r.underruns, 0);
    assert_eq!(r.commanded[0], 0, "the analog axis took no steps");
    assert!(fe.periods as usize >= r.periods, "one figure per period");
    assert!(r
        .figures
        .iter()
        .any(|f| f.ends_with("square-following-error.svg")));
}

/// The same run held at 0.3 s and released at 0.6 s: the controller
/// scales X's velocity codes with the hold's factor, so X slows along the
/// path with Y and stands while held; the run still ends with X within a
/// count of the end, and Y and Z exactly.
#[test]
fn square_path_with_an_analog_x_holds_and_resumes_and_ends_within_a_count() {
    use motion_hdl::host::hold_window::HoldWindow;
    use motion_hdl::host::simulation::{simulate, SimulationOptions};
    let square = motion_hdl::tools::repo_root().join("examples/square.path");
    let options = SimulationOptions {
        format: None,
        machine: None,
        tools: None,
        clock_hz: 4e6,
        uniform: [false; 3],
        servo: [true, false, false],
        step_len: 2,
        step_space: 2,
        out_dir: None,
        vcd: None,
        progress: false,
        backend: motion_hdl::sim::Backend::from_env_or(motion_hdl::sim::Backend::Verilator)
            .unwrap(),
        trips: Vec::new(),
        hold: Some(HoldWindow {
            hold_at_s: 0.3,
            resume_at_s: 0.6,
            rate: None,
        }),
        probe_plane: None,
        soft_limits: [None; 3],
        spindle: Default::default(),
        spi_sclk_hz: None,
    };
    let r = simulate(&square, &options).unwrap_or_else(|e| panic!("{e}"));
    let hold = r.hold.as_ref().expect("the hold's report");
    println!("{hold:?}; ended at {:?} for {:?}", r.actual, r.target);
    assert!(hold.stood_s.is_some(), "the path never stood: {hold:?}");
    assert!(
        (r.actual[0] as i64 - r.target[0]).abs() <= 1,
        "X ended at {}, target {}",
        r.actual[0],
        r.target[0]
    );
    for k in 1..3 {
        assert_eq!(r.commanded[k] as i64, r.target[k], "axis {k} commanded");
        assert_eq!(r.actual[k] as i64, r.target[k], "axis {k} actual");
    }
    assert_eq!(r.underruns, 0);
}

/// The CLI names a bad `--servo` axis and a servo axis asked for the
/// uniform generator (which the analog build does not have), and exits
/// non-zero.
#[test]
fn simulate_names_a_bad_servo_option() {
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
    let stderr = run(&["--servo", "w"]);
    assert!(
        stderr.contains("--servo: unknown axis `w` (x, y or z)"),
        "{stderr}"
    );
    let stderr = run(&["--servo", "x", "--uniform", "x"]);
    assert!(
        stderr.contains("axis x cannot be both uniform and an analog servo"),
        "{stderr}"
    );
    let stderr = run(&["--servo", "x", "--uniform", "y"]);
    assert!(stderr.contains("--uniform needs the motion_controller build, --servo the motion_controller_servo build"), "{stderr}");
}
