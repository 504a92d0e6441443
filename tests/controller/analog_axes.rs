//! Analog axes of `motion_controller_servo` (`ANALOG` = true) at the pins:
//! a behavioral bank of AD669s on the DAC pins, against what the FIFOs
//! were given. Per period every analog axis's code leaves in one update
//! with one LDAC, at a fixed lag after the boundary; the step axes keep
//! stepping; RUN falling (underrun) sets 0 V; an E-stop forces 0 V within
//! the stated bound; a code toward an active limit never reaches an output.

use crate::bench::Bench;
use crate::motion_controller::configure;
use motion_hdl::blocks::dac_interface::safe_latency;
use motion_hdl::blocks::motion_controller::latency;
use motion_hdl::blocks::motion_controller::model::DacPins;
use motion_hdl::blocks::motion_controller::registers::StopCause;
use motion_hdl::sim::Ad669Bank;

/// The exported analog build.
type Analog3 = Bench<3, 4, 5, false, true, true, false>;

/// DAC_TIMING at reset: S, Wd, H, L.
const TIMING: (u64, u64, u64, u64) = (1, 5, 2, 5);

/// One clock of the controller's DAC pins into a bank of AD669s; true on
/// an LDAC rise.
fn clock_bank(bank: &mut Ad669Bank, pins: &DacPins) -> bool {
    bank.clock(pins.data, pins.cs_n, pins.l1_n, pins.ldac)
}

/// The code an entry becomes: saturated to 16 bits signed.
fn saturated(entry: i64) -> i64 {
    entry.clamp(i16::MIN as i64, i16::MAX as i64)
}

/// What the pins must show for a run that starts with the RUN write in
/// clock 0 of `trace`: period j's codes at every output from
/// `first + j * period` (its LDAC rise, exactly then), then 0 after the
/// underrun. Returns the LDAC rises seen.
fn check_periods(
    trace: &[DacPins],
    period: u64,
    first: u64,
    codes: &[[i64; 3]],
    analog: [bool; 3],
) -> Result<Vec<u64>, String> {
    let mut bank = Ad669Bank::new(3);
    let mut rises = Vec::new();
    for (clock, pins) in trace.iter().enumerate() {
        if clock_bank(&mut bank, pins) {
            rises.push(clock as u64);
        }
        // After a whole LDAC pulse, the outputs hold one period's codes.
        if !pins.ldac && clock > 0 && trace[clock - 1].ldac {
            let n = rises.len() - 1;
            let expected: [i64; 3] = match codes.get(n) {
                Some(c) => std::array::from_fn(|k| if analog[k] { saturated(c[k]) } else { 0 }),
                None => [0; 3],
            };
            let got: [i64; 3] = std::array::from_fn(|k| bank.code(k));
            if got != expected {
                return Err(format!(
                    "clock {clock}: update {n} left {got:?} at the outputs, not {expected:?}"
                ));
            }
        }
    }
    if rises.len() != codes.len() + 1 {
        return Err(format!(
            "{} LDAC pulses for {} periods and the stop",
            rises.len(),
            codes.len()
        ));
    }
    for (j, &rise) in rises.iter().take(codes.len()).enumerate() {
        let due = first + j as u64 * period;
        if rise != due {
            return Err(format!("period {j}'s LDAC rose at clock {rise}, not {due}"));
        }
    }
    Ok(rises)
}

fn configure_analog(b: &mut Analog3, period: u32, analog: [bool; 3]) {
    b.reset();
    configure(b, period, [false; 3]);
    for (axis, on) in analog.iter().enumerate() {
        let config = b.pack("AXIS_CONFIG", &[("ANALOG", *on as u64)]);
        b.write("AXIS_CONFIG", axis as u32, config);
    }
}

/// Queues one entry per axis for each period of `codes`.
fn queue_periods(b: &mut Analog3, codes: &[[i64; 3]]) {
    for c in codes {
        for (axis, &n) in c.iter().enumerate() {
            b.write("FIFO_WRITE", axis as u32, n as u32);
        }
    }
}

/// Runs `codes` (one entry per axis and period; a step count on the step
/// axes) from a RUN write; returns the DAC pins of each clock from that
/// write until `clocks` later.
fn run_codes(b: &mut Analog3, codes: &[[i64; 3]], clocks: u64) -> Vec<DacPins> {
    queue_periods(b, codes);
    let mut trace = vec![b.write_then_pins("CONTROL", 0, 1)];
    for _ in 1..clocks {
        b.idle(1);
        trace.push(b.last.dac);
    }
    trace
}

impl Analog3 {
    /// Writes a register; the DAC pins after that clock.
    fn write_then_pins(&mut self, name: &str, index: u32, value: u32) -> DacPins {
        self.write(name, index, value);
        self.last.dac
    }
}

#[test]
fn each_period_s_codes_leave_in_one_update_at_a_fixed_lag_and_an_underrun_sets_0v() {
    let mut b = Analog3::new().with_loopback();
    let period = 100;
    let analog = [true, false, true];
    configure_analog(&mut b, period, analog);
    // Axis 1 steps; axes 0 and 2 are analog, with codes at and beyond the
    // 16-bit range (saturated and flagged).
    let codes: Vec<[i64; 3]> = vec![
        [1000, 3, -7],
        [-2000, 3, 70_000],
        [32767, -3, -70_000],
        [-32768, 3, 12],
        [5, 0, 13],
        [0, 3, -1],
    ];
    let trace = run_codes(
        &mut b,
        &codes,
        (codes.len() as u64 + 1) * period as u64 + 60,
    );
    // The RUN write's clock is 0; the first boundary pops in clock 1.
    let (s, w, h, _) = TIMING;
    let first = 1 + latency::analog_ldac(3, s, w, h);
    let rises = check_periods(&trace, period as u64, first, &codes, analog)
        .unwrap_or_else(|e| panic!("{e}"));
    let underrun = 1 + codes.len() as u64 * period as u64;
    let zero = rises.last().unwrap() - underrun;
    println!(
        "LDAC {} clocks after each boundary; the underrun's 0 V LDAC {zero} clocks after it",
        first - 1
    );
    assert_eq!(
        zero,
        3 + 3 * (s + w + h),
        "the 0 V update after the underrun"
    );

    crate::motion_controller::drain(&mut b);
    assert_eq!(b.pin_steps(1), 9, "the step axis took its steps");
    assert_eq!(
        b.pin_steps(0) + b.pin_steps(2),
        0,
        "no step on an analog axis"
    );
    let cause = b.read("STOP_CAUSE", 0);
    assert_eq!(
        b.field("STOP_CAUSE", "CAUSE", cause),
        StopCause::Underrun as u64
    );
    for axis in 0..3 {
        assert_eq!(
            b.read("DAC_APPLIED", axis),
            0,
            "axis {axis}: 0 V after the underrun"
        );
        let status = b.read("AXIS_STATUS", axis);
        let flagged = b.field("AXIS_STATUS", "INTERP_OVERRANGE", status);
        assert_eq!(
            flagged,
            (axis == 2) as u64,
            "axis {axis}: only axis 2's codes were saturated"
        );
    }
}

/// The pin check above, shown able to fail: an LDAC pulse dropped, one a
/// clock late, and a code bit flipped while its first rank is open.
#[test]
fn the_period_check_catches_a_dropped_late_or_torn_update() {
    let mut b = Analog3::new();
    let period = 100;
    let analog = [true, true, true];
    configure_analog(&mut b, period, analog);
    let codes: Vec<[i64; 3]> = vec![[100, -200, 300], [-400, 500, -600], [700, -800, 900]];
    let trace = run_codes(&mut b, &codes, 4 * period as u64 + 60);
    let (s, w, h, _) = TIMING;
    let first = 1 + latency::analog_ldac(3, s, w, h);
    check_periods(&trace, period as u64, first, &codes, analog).unwrap_or_else(|e| panic!("{e}"));

    let ldac_clocks: Vec<usize> = (0..trace.len()).filter(|&c| trace[c].ldac).collect();
    let second_pulse: Vec<usize> = ldac_clocks
        .iter()
        .copied()
        .filter(|&c| c > first as usize + 50 && c < first as usize + 150)
        .collect();
    let mut dropped = trace.clone();
    for &c in &second_pulse {
        dropped[c].ldac = false;
    }
    let mut late = trace.clone();
    late[second_pulse[0]].ldac = false;
    late[*second_pulse.last().unwrap() + 1].ldac = true;
    let mut torn = trace.clone();
    // The last clock channel 1's first rank is open: what it latches.
    let open = (first as usize + 50..trace.len())
        .take_while(|&c| c < first as usize + 150)
        .filter(|&c| !trace[c].l1_n && trace[c].cs_n == 0b101)
        .last()
        .unwrap();
    torn[open].data ^= 0x10;
    for (name, mutant, rule) in [
        ("an LDAC dropped", dropped, "update 1 left"),
        ("an LDAC a clock late", late, "not"),
        ("a torn code", torn, "at the outputs"),
    ] {
        let verdict = check_periods(&mutant, period as u64, first, &codes, analog);
        let message = verdict
            .err()
            .unwrap_or_else(|| panic!("{name}: not caught"));
        assert!(message.contains(rule), "{name}: caught, but by `{message}`");
    }
}

/// An E-stop at each clock of a period's update: every analog output is
/// 0 V at most `latency::switch` + 1 + `safe_latency` clocks after the pin
/// rises; the worst case is printed.
#[test]
fn an_estop_at_any_clock_of_an_update_reaches_0v_within_the_bound() {
    let mut b = Analog3::new();
    let period = 100u64;
    let (s, w, h, l) = TIMING;
    let bound = latency::switch(4, 0) + 1 + safe_latency(3, s, w, h, l);
    let mut worst = 0;
    for offset in 0..40 {
        // The last E-stop released and filtered out before the reset.
        b.pins = Default::default();
        b.idle(20);
        configure_analog(&mut b, period as u32, [true, true, true]);
        queue_periods(&mut b, &[[20_000, -20_000, 12_345]; 4]);
        let mut bank = Ad669Bank::new(3);
        b.write("CONTROL", 0, 1);
        clock_bank(&mut bank, &b.last.dac);
        // The second period's update runs from clock 101 + 3: the E-stop
        // lands `offset` clocks into it (the first period's codes are out).
        let estop_at = period + 4 + offset;
        let mut zero_at = None;
        for clock in 1..estop_at + 200 {
            if clock == estop_at {
                b.pins.estop = true;
            }
            b.idle(1);
            clock_bank(&mut bank, &b.last.dac);
            if clock == estop_at - 1 {
                assert_eq!(
                    bank.code(0),
                    20_000,
                    "offset {offset}: the first period's code is out"
                );
            }
            if clock >= estop_at && zero_at.is_none() && (0..3).all(|k| bank.code(k) == 0) {
                zero_at = Some(clock - estop_at);
            }
        }
        let took =
            zero_at.unwrap_or_else(|| panic!("offset {offset}: the outputs never reached 0 V"));
        assert!(
            took <= bound,
            "offset {offset}: 0 V after {took} clocks, bound {bound}"
        );
        worst = worst.max(took);
        let status = b.read("DAC_STATUS", 0);
        assert_eq!(
            b.field("DAC_STATUS", "FORCE_SAFE", status),
            1,
            "the abort holds the DAC safe"
        );
        assert_eq!(b.field("DAC_STATUS", "SAFE", status), 1);
    }
    println!("E-stop pin to 0 V at every output: at most {worst} clocks (bound {bound})");
}

/// A code toward an active, enabled limit is cut like a step: it never
/// reaches the output, the limit trips and everything stops. After
/// CLEAR_LIMITS a code away from the limit runs.
#[test]
fn a_code_toward_an_active_limit_never_reaches_the_output() {
    let mut b = Analog3::new();
    let period = 100u64;
    configure_analog(&mut b, period as u32, [true, false, false]);
    b.pins.limit_pos = 0b001;
    b.idle(20);
    queue_periods(&mut b, &[[5000, 0, 0]; 3]);
    let mut bank = Ad669Bank::new(3);
    b.write("CONTROL", 0, 1);
    for _ in 0..3 * period {
        b.idle(1);
        clock_bank(&mut bank, &b.last.dac);
        assert_eq!(
            bank.code(0),
            0,
            "the code toward the limit reached the output"
        );
    }
    let io = b.read("IO_STATUS", 0);
    assert_eq!(
        b.field("IO_STATUS", "LIMIT_POS_TRIPPED", io),
        1,
        "the limit tripped"
    );
    let cause = b.read("STOP_CAUSE", 0);
    assert_eq!(
        b.field("STOP_CAUSE", "CAUSE", cause),
        StopCause::Limit as u64
    );

    // Back off: away from the limit, still active.
    b.write(
        "IO_COMMAND",
        0,
        b.pack("IO_COMMAND", &[("CLEAR_LIMITS", 1)]),
    );
    b.write("CONTROL", 0, b.pack("CONTROL", &[("FLUSH", 1)]));
    queue_periods(&mut b, &[[-3000, 0, 0]; 2]);
    b.write("CONTROL", 0, 1);
    let mut seen = false;
    for _ in 0..period + 60 {
        b.idle(1);
        clock_bank(&mut bank, &b.last.dac);
        seen |= bank.code(0) == -3000;
    }
    assert!(seen, "the code away from the limit reached the output");
}

/// 3 x 10^5 clocks of the chaos traffic (random ANALOG bits, DAC_TIMING,
/// DAC_CONTROL and DAC_STATUS writes, DAC_APPLIED reads among the rest) on
/// the exported `motion_controller_servo` compiled by Verilator, in
/// lockstep with the model built the same way (about 1 s).
#[test]
fn servo_build_matches_its_model_under_random_traffic() {
    let backend =
        motion_hdl::sim::Backend::from_env_or(motion_hdl::sim::Backend::Verilator).unwrap();
    let run = crate::motion_controller::chaos_run_on(Analog3::on(backend), 0xdda_0009, 300_000);
    assert_eq!(
        run.status_seen,
        crate::motion_controller::ALL_STATUS
            & !(1 << motion_hdl::blocks::motion_controller::registers::irq::SOFT_LIMIT),
        "every STATUS bit but SOFT_LIMIT (not in this build) seen set: {:#x}",
        run.status_seen
    );
    // 2 000 steps, not 3 000: the chaos traffic's feed holds slow the
    // path (about 2 500 steps with them where 3 400 ran without).
    run.assert_busy("K=3 servo", 60_000, 2_000, 75);
}

/// Both build options at once (`MotionController3UniformServo`: uniform
/// generators and analog outputs, not exported, measured on the seed card
/// in the scaling report): 3 x 10^5 clocks of the chaos traffic, its
/// Verilog compiled by Verilator, in lockstep with the model built the
/// same way.
#[test]
fn uniform_servo_build_matches_its_model_under_random_traffic() {
    let backend =
        motion_hdl::sim::Backend::from_env_or(motion_hdl::sim::Backend::Verilator).unwrap();
    let run = crate::motion_controller::chaos_run_on(
        crate::bench::Bench::<3, 4, 5, true, true, true, false>::on(backend),
        0x0f_0011,
        300_000,
    );
    assert_eq!(
        run.status_seen,
        crate::motion_controller::ALL_STATUS
            & !(1 << motion_hdl::blocks::motion_controller::registers::irq::SOFT_LIMIT),
        "every STATUS bit but SOFT_LIMIT (not in this build) seen set: {:#x}",
        run.status_seen
    );
    // 2 000 steps, not 3 000: the chaos traffic's feed holds slow the
    // path (about 2 500 steps with them where 3 400 ran without).
    run.assert_busy("K=3 uniform servo", 60_000, 2_000, 75);
}

/// The exported `motion_controller_servo.v` in Icarus and Verilator, cycle
/// for cycle against the Rust simulation.
#[test]
fn exported_servo_verilog_matches_rust_in_icarus_and_verilator() {
    crate::motion_controller::cross_simulate_exported::<false, true, true, false>(
        "motion_controller_servo",
        crate::motion_controller::SUITE_CHAOS_CLOCKS,
        crate::motion_controller::SUITE_ICARUS_CLOCKS,
    );
}

/// The controller converts each written entry once, before the FIFOs, into
/// a 16-bit magnitude and flags, and puts the sign back for the DAC: every
/// edge of 16 bits signed, 16 bits unsigned and 32 bits leaves the pins as
/// the saturated code (checked at the AD669 pins, and every clock against
/// the model by the bench).
#[test]
fn entries_at_every_width_edge_leave_as_their_saturated_codes() {
    let edges = crate::motion_controller::ENTRY_EDGES.map(i64::from);
    let mut b = Analog3::new().with_loopback();
    let period = 100;
    let analog = [true, false, true];
    configure_analog(&mut b, period, analog);
    // Axis 0 takes the edges in order, axis 2 in reverse; axis 1 steps.
    let codes: Vec<[i64; 3]> = (0..edges.len())
        .map(|i| [edges[i], 1, edges[edges.len() - 1 - i]])
        .collect();
    let trace = run_codes(
        &mut b,
        &codes,
        (codes.len() as u64 + 1) * period as u64 + 60,
    );
    let (s, w, h, _) = TIMING;
    let first = 1 + latency::analog_ldac(3, s, w, h);
    check_periods(&trace, period as u64, first, &codes, analog).unwrap_or_else(|e| panic!("{e}"));
}
