//! `step_output`: RTL against the model, an independent monitor of the
//! output pins for every timing rule and the net step count in each mode,
//! saturation, and cross-simulation.

use motion_hdl::blocks::step_output::model::{
    pending_limits, StepOutputInputs, StepOutputModel, StepOutputOutputs, PENDING_MAX, PENDING_MIN,
};
use motion_hdl::blocks::step_output::StepOutput;
use motion_hdl::sim::{stepper, Backend, Harness, Stepper};
use motion_hdl::tools::cosim::{cross_simulate, cross_simulate_generated, CosimDesign};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// One clock of the RTL with `inputs` applied.
fn rtl_clock(rtl: &mut dyn Stepper, inputs: &StepOutputInputs) -> StepOutputOutputs {
    StepOutputOutputs::from_vector(&rtl.step_vector(&inputs.to_vector()).unwrap())
}

/// The exported configuration for the million-clock runs, on the backend
/// `MOTION_HDL_BACKEND` names (default: Verilator, for speed).
fn long_run_rtl() -> Box<dyn Stepper> {
    let backend = Backend::from_env_or(Backend::Verilator).unwrap();
    stepper(backend, "step_output", StepOutput::<16, 16>::default(), None).unwrap_or_else(|e| panic!("{e}"))
}

/// Runs of requests, each with one mode and one set of timings: bursts of
/// random density, direction reversals at random points (so they land at
/// every point of the timing sequence), then a drain until the stage is idle,
/// when the next run may change the mode and timings. `busy` comes from
/// the caller, so the same driver runs against the model or the RTL.
struct Driver {
    rng: StdRng,
    settings: StepOutputInputs,
    burst_left: u32,
    density: f64,
    forward_bias: f64,
    runs: u32,
    modes: Vec<u8>,
}

impl Driver {
    fn new(seed: u64, modes: Vec<u8>) -> Self {
        Self {
            rng: StdRng::seed_from_u64(seed),
            settings: StepOutputInputs::default(),
            burst_left: 0,
            density: 0.5,
            forward_bias: 0.5,
            runs: 0,
            modes,
        }
    }

    fn timer(rng: &mut StdRng) -> u64 {
        match rng.gen_range(0..10) {
            0 => 0,
            1 => rng.gen_range(10..60),
            _ => rng.gen_range(1..6),
        }
    }

    fn next(&mut self, busy: bool) -> StepOutputInputs {
        let rng = &mut self.rng;
        if self.burst_left == 0 && !busy && rng.gen_ratio(1, 3) {
            // A new run: settings change only while idle.
            self.runs += 1;
            self.settings = StepOutputInputs {
                mode: self.modes[rng.gen_range(0..self.modes.len())],
                step_len: Self::timer(rng),
                step_space: Self::timer(rng),
                dir_setup: Self::timer(rng),
                dir_hold: Self::timer(rng),
                ..Default::default()
            };
            self.burst_left = rng.gen_range(1..400);
            self.density = [1.0, 0.5, 0.1, 0.02][rng.gen_range(0..4)];
            self.forward_bias = [1.0, 0.0, 0.5, 0.8][rng.gen_range(0..4)];
        }
        let mut inputs = self.settings;
        inputs.clear_overrun = rng.gen_ratio(1, 300);
        if self.burst_left > 0 {
            self.burst_left -= 1;
            inputs.step = rng.gen_bool(self.density);
            inputs.dir = rng.gen_bool(self.forward_bias);
            if rng.gen_ratio(1, 50) {
                self.forward_bias = 1.0 - self.forward_bias; // reversal
            }
        }
        inputs
    }
}

#[test]
fn rtl_matches_model_cycle_by_cycle_in_every_mode() {
    let mut driver = Driver::new(0x57e9, vec![0, 1, 2, 3]);
    let mut dut = long_run_rtl();
    let mut model = StepOutputModel::new(16, 16);
    let mut busy = false;
    for cycle in 0..1_000_000 {
        let mut inputs = driver.next(busy);
        inputs.reset = cycle % 250_000 == 249_999;
        let rtl = rtl_clock(dut.as_mut(), &inputs);
        assert_eq!(rtl, model.step(inputs), "cycle {cycle}: {inputs:?}");
        busy = rtl.busy;
    }
    assert!(driver.runs > 500, "only {} runs", driver.runs);
}

/// A 4-bit pending count (-8..7) saturates often under the same stimulus:
/// drops, `overrun` and `clear_overrun` against the model.
#[test]
fn narrow_pending_count_saturates_and_clears_like_the_model() {
    let mut driver = Driver::new(0x4a7, vec![0, 1, 2]);
    let mut harness = Harness::new("step_output", StepOutput::<16, 4>::default()).unwrap();
    let mut model = StepOutputModel::new(16, 4);
    let (mut busy, mut before, mut overruns, mut clears) = (false, false, 0, 0);
    for cycle in 0..300_000 {
        let inputs = driver.next(busy);
        let rtl = rtl_clock(&mut harness, &inputs);
        let expected = model.step(inputs);
        assert_eq!(rtl, expected, "cycle {cycle}: {inputs:?}");
        overruns += (!before && rtl.overrun) as u32;
        clears += (before && inputs.clear_overrun && !rtl.overrun) as u32;
        busy = rtl.busy;
        before = rtl.overrun;
    }
    assert!(overruns > 50 && clears > 50, "{overruns} overruns, {clears} clears");
}

/// Checks the output pins against the port contract of one mode, knowing
/// only the settings, the requests and the pins (not the model).
struct PinMonitor {
    mode: u8,
    len: u64,
    space: u64,
    setup: u64,
    hold: u64,
    last: (bool, bool),
    last_rise: Option<u64>,
    last_fall: Option<u64>,
    last_dir_change: Option<u64>,
    last_state_change: Option<u64>,
    emitted: i64,
    /// Net steps signalled on `emitted` / `emitted_forward`.
    strobed: i64,
    requested: i64,
    checks: u64,
}

impl PinMonitor {
    fn new(s: &StepOutputInputs, pins: (bool, bool)) -> Self {
        let at_least_one = |x: u64| x.max(1);
        Self {
            mode: if s.mode == 3 { 0 } else { s.mode },
            len: at_least_one(s.step_len),
            space: at_least_one(s.step_space),
            setup: at_least_one(s.dir_setup),
            hold: at_least_one(s.dir_hold),
            last: pins,
            last_rise: None,
            last_fall: None,
            last_dir_change: None,
            last_state_change: None,
            emitted: 0,
            strobed: 0,
            requested: 0,
            checks: 0,
        }
    }

    /// The `emitted` strobe must mark each step seen at the pins, in the
    /// same clock and with its direction.
    fn strobe(&mut self, out: &StepOutputOutputs) {
        if out.emitted {
            self.strobed += if out.emitted_forward { 1 } else { -1 };
        }
        assert_eq!(self.strobed, self.emitted, "emitted strobes disagree with the pins");
    }

    fn sample(&mut self, cycle: u64, (a, b): (bool, bool)) {
        let (pa, pb) = self.last;
        self.last = (a, b);
        match self.mode {
            0 => {
                if b != pb {
                    assert!(!pa && !a, "cycle {cycle}: dir changed while step was high");
                    if let Some(fall) = self.last_fall {
                        assert!(
                            cycle - fall >= self.hold,
                            "cycle {cycle}: dir hold {} < {}",
                            cycle - fall,
                            self.hold
                        );
                    }
                    self.last_dir_change = Some(cycle);
                    self.checks += 1;
                }
                self.pulse_edges(cycle, pa, a, if b { 1 } else { -1 });
                if a && !pa {
                    if let Some(change) = self.last_dir_change {
                        let setup = cycle - change;
                        assert!(
                            setup >= self.setup,
                            "cycle {cycle}: dir setup {setup} < {}",
                            self.setup
                        );
                    }
                }
            }
            1 => {
                assert!(!(a && b), "cycle {cycle}: up and down both high");
                let (was, is) = (pa || pb, a || b);
                let sign = if a { 1 } else { -1 };
                if is && was && (a != pa || b != pb) {
                    panic!("cycle {cycle}: up/down switched without a low gap");
                }
                self.pulse_edges(cycle, was, is, sign);
            }
            _ => {
                if (a, b) != (pa, pb) {
                    let forward = (a, b) == (!pb, pa);
                    let backward = (a, b) == (pb, !pa);
                    assert!(
                        forward || backward,
                        "cycle {cycle}: not a Gray step {:?} -> {:?}",
                        (pa, pb),
                        (a, b)
                    );
                    if let Some(change) = self.last_state_change {
                        assert!(
                            cycle - change >= self.len,
                            "cycle {cycle}: state held {} < {}",
                            cycle - change,
                            self.len
                        );
                    }
                    self.last_state_change = Some(cycle);
                    self.emitted += if forward { 1 } else { -1 };
                    self.checks += 1;
                }
            }
        }
    }

    /// A pulse output (mode 0 step, or mode 1 up/down combined).
    fn pulse_edges(&mut self, cycle: u64, was: bool, is: bool, sign: i64) {
        if is && !was {
            if let Some(fall) = self.last_fall {
                assert!(
                    cycle - fall >= self.space,
                    "cycle {cycle}: space {} < {}",
                    cycle - fall,
                    self.space
                );
            }
            self.last_rise = Some(cycle);
            self.emitted += sign;
            self.checks += 1;
        }
        if was && !is {
            let rise = self.last_rise.expect("fall without a rise");
            assert_eq!(cycle - rise, self.len, "cycle {cycle}: pulse length");
            self.last_fall = Some(cycle);
            self.checks += 1;
        }
    }
}

#[test]
fn pins_keep_every_timing_rule_and_the_net_count_in_each_mode() {
    for mode in 0..4u8 {
        let mut driver = Driver::new(0x9e0 + mode as u64, vec![mode]);
        let mut dut = long_run_rtl();
        let mut monitor: Option<PinMonitor> = None;
        let mut busy = false;
        let mut checks = 0;
        let mut runs_checked = 0;
        for cycle in 0..1_000_000u64 {
            let inputs = driver.next(busy);
            let out = rtl_clock(dut.as_mut(), &inputs);
            let pins = (out.out_a, out.out_b);
            // A new run starts when the settings change; the stage takes the
            // mode while idle, so the previous run must be complete.
            let same = monitor.as_ref().is_some_and(|m| {
                (m.len, m.space, m.setup, m.hold)
                    == (
                        inputs.step_len.max(1),
                        inputs.step_space.max(1),
                        inputs.dir_setup.max(1),
                        inputs.dir_hold.max(1),
                    )
            });
            if !same {
                if let Some(m) = monitor.take() {
                    assert!(!busy, "settings changed while busy");
                    assert_eq!(
                        m.emitted, m.requested,
                        "mode {mode}: net emitted steps != net requested"
                    );
                    checks += m.checks;
                    runs_checked += 1;
                }
                monitor = Some(PinMonitor::new(&inputs, pins));
            }
            let m = monitor.as_mut().unwrap();
            if inputs.step {
                m.requested += if inputs.dir { 1 } else { -1 };
            }
            m.sample(cycle, pins);
            m.strobe(&out);
            assert!(!out.overrun, "mode {mode}: overrun without saturation");
            assert_eq!(out.mode_invalid, mode == 3);
            busy = out.busy;
        }
        // The last run: drain it with its own settings and check it too.
        let mut m = monitor.take().unwrap();
        let idle = StepOutputInputs {
            step: false,
            ..driver.settings
        };
        for cycle in 1_000_000..1_300_000u64 {
            let out = rtl_clock(dut.as_mut(), &idle);
            m.sample(cycle, (out.out_a, out.out_b));
            m.strobe(&out);
            if !out.busy {
                break;
            }
        }
        assert_eq!(
            m.emitted, m.requested,
            "mode {mode}: the last run's net count"
        );
        assert!(
            runs_checked > 300 && checks > 50_000,
            "mode {mode}: {runs_checked} runs, {checks} checks"
        );
    }
}

/// Fills the pending count in one direction while very long timing holds
/// the output back, keeps requesting after `overrun`, then drains with short
/// timing: exactly the count's capacity in that direction comes out, plus
/// any pulse that started during the fill; the requests beyond the capacity
/// are dropped.
fn saturate_and_drain<const P: usize>(dir: bool, capacity: i64) {
    let mut harness = Harness::new("step_output", StepOutput::<16, P>::default()).unwrap();
    let slow = StepOutputInputs {
        step: true,
        dir,
        step_len: 60_000,
        step_space: 60_000,
        ..Default::default()
    };
    let mut rises: i64 = 0;
    let mut last_a = false;
    let count = |out: StepOutputOutputs, last_a: &mut bool| {
        let rise = out.out_a && !*last_a;
        *last_a = out.out_a;
        rise as i64
    };
    let mut after_overrun = 0;
    while after_overrun < 100 {
        let out = rtl_clock(&mut harness, &slow);
        rises += count(out, &mut last_a);
        if out.overrun {
            after_overrun += 1;
        }
        assert!(
            rises <= 1,
            "a second pulse started inside a 60000-clock pulse"
        );
    }
    let started_during_fill = rises;
    let fast = StepOutputInputs::default();
    for _ in 0..200_000 {
        let out = rtl_clock(&mut harness, &fast);
        rises += count(out, &mut last_a);
        if !out.busy {
            break;
        }
    }
    assert_eq!(
        rises,
        capacity + started_during_fill,
        "steps emitted after saturation (dir {dir})"
    );
}

#[test]
fn a_saturated_count_drops_requests_and_flags_overrun_forward() {
    saturate_and_drain::<16>(true, PENDING_MAX.into());
}

#[test]
fn a_saturated_count_drops_requests_and_flags_overrun_backward() {
    saturate_and_drain::<16>(false, (-PENDING_MIN).into());
}

/// A closed-loop run of the driver against the model, as input vectors.
fn cosim_stimulus(
    seed: u64,
    modes: Vec<u8>,
    timer_bits: u32,
    pending_bits: u32,
    cycles: usize,
) -> Vec<Vec<u64>> {
    let mut driver = Driver::new(seed, modes);
    let mut model = StepOutputModel::new(timer_bits, pending_bits);
    let mut busy = false;
    (0..cycles)
        .map(|_| {
            let inputs = driver.next(busy);
            busy = model.step(inputs).busy;
            inputs.to_vector()
        })
        .collect()
}

#[test]
fn exported_verilog_matches_rust_in_icarus_and_verilator() {
    let stimulus = cosim_stimulus(0xc059, vec![0, 1, 2, 3], 16, 16, 40_000);
    cross_simulate(
        &CosimDesign::exported("step_output"),
        StepOutput::<16, 16>::default(),
        &stimulus,
    )
    .unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn narrow_6_bit_timers_match_rust_in_icarus_and_verilator() {
    let stimulus = cosim_stimulus(0xc05a, vec![0, 1, 2], 6, 16, 30_000);
    cross_simulate_generated("step_output_t6", StepOutput::<6, 16>::default(), &stimulus)
        .unwrap_or_else(|e| panic!("{e}"));
}

/// The timing diagram in the datasheet (`src/blocks/step_output/timing.txt`,
/// included into the rustdoc) is this simulation, not a drawing: step/dir,
/// step_len 2, step_space 3, dir_setup 2, dir_hold 2, after a reset; three
/// forward steps requested on clocks 1 to 3, then two backward steps on
/// clocks 14 and 15.
fn timing_diagram() -> String {
    let mut harness = Harness::new("step_output", StepOutput::<16, 16>::default()).unwrap();
    let settings = StepOutputInputs {
        step_len: 2,
        step_space: 3,
        dir_setup: 2,
        dir_hold: 2,
        ..Default::default()
    };
    // Clock 0 is the reset the diagram starts after.
    rtl_clock(&mut harness, &StepOutputInputs { reset: true, ..settings });
    let (mut a, mut b, mut req) = (String::new(), String::new(), String::new());
    for clock in 1..=36 {
        let mut inputs = settings;
        inputs.step = clock <= 3 || clock == 14 || clock == 15;
        inputs.dir = clock <= 3;
        let out = rtl_clock(&mut harness, &inputs);
        req.push(if inputs.step {
            if inputs.dir {
                '+'
            } else {
                '-'
            }
        } else {
            ' '
        });
        a.push(if out.out_a { '#' } else { '_' });
        b.push(if out.out_b { '#' } else { '_' });
    }
    let ruler: String = (1..=36)
        .map(|c| char::from_digit(c % 10, 10).unwrap())
        .collect();
    format!(
        "```text\nclock    {ruler}\nrequest  {}\nout_a    {a}   (step)\nout_b    {b}   (dir)\n```\n",
        req.trim_end()
    )
}

#[test]
fn datasheet_timing_diagram_is_the_simulation() {
    let path = motion_hdl::tools::repo_root().join("src/blocks/step_output/timing.txt");
    let drawn = std::fs::read_to_string(&path).unwrap_or_default();
    let simulated = timing_diagram();
    if std::env::var_os("UPDATE_TIMING_DIAGRAM").is_some() {
        std::fs::write(&path, &simulated).unwrap();
    }
    assert_eq!(
        drawn, simulated,
        "timing.txt differs from the simulation (rerun with UPDATE_TIMING_DIAGRAM=1)"
    );
}

/// The pending width is a parameter: an 8-bit count saturates at +127 and
/// -128 with the same rules.
#[test]
fn an_8_bit_pending_count_saturates_at_its_own_limits() {
    let (min, max) = pending_limits(8);
    saturate_and_drain::<8>(true, max);
    saturate_and_drain::<8>(false, -min);
}

#[test]
fn an_8_bit_pending_count_matches_its_model_and_verilog() {
    let stimulus = cosim_stimulus(0x8b17, vec![0, 1, 2], 16, 8, 30_000);
    cross_simulate_generated("step_output_p8", StepOutput::<16, 8>::default(), &stimulus)
        .unwrap_or_else(|e| panic!("{e}"));
}

/// How a stage reaches the clock from which one step is requested.
#[derive(Clone, Copy, Debug)]
enum Start {
    /// Power-up state, no reset pulse.
    PowerUp,
    /// Three idle clocks, then a one-clock reset.
    Reset,
    /// A burst of steps in another mode, then a reset mid-pulse with the
    /// mode input changing to this run's mode at the reset.
    ResetMidPulseInAnotherMode,
}

/// Pin transitions of one run: rising edges of `out_a` and `out_b`, the
/// level of `out_b` at each `out_a` rise, and every (a, b) change.
#[derive(Debug, Default, PartialEq, Eq)]
struct PinLog {
    a_rises: u32,
    b_rises: u32,
    b_at_a_rise: Vec<bool>,
    changes: Vec<(bool, bool)>,
}

/// The issue-24 scenario: `mode` tied from time 0 (step_len 4, step_space 4,
/// dir_setup 6, dir_hold 2), one step requested `delay` clocks after the
/// start. Returns the pins seen from the start on; RTL and model are
/// compared on every clock as well.
fn one_early_step(mode: u8, forward: bool, start: Start, delay: u32) -> PinLog {
    let mut harness = Harness::new("step_output", StepOutput::<16, 16>::default()).unwrap();
    let mut model = StepOutputModel::new(16, 16);
    let tied = StepOutputInputs {
        mode,
        step_len: 4,
        step_space: 4,
        dir_setup: 6,
        dir_hold: 2,
        ..Default::default()
    };
    let mut clock = |inputs: StepOutputInputs| {
        let rtl = rtl_clock(&mut harness, &inputs);
        assert_eq!(rtl, model.step(inputs), "{start:?} mode {mode}: {inputs:?}");
        rtl
    };
    match start {
        Start::PowerUp => {}
        Start::Reset => {
            for _ in 0..3 {
                clock(tied);
            }
            clock(StepOutputInputs { reset: true, ..tied });
        }
        Start::ResetMidPulseInAnotherMode => {
            let other = StepOutputInputs {
                mode: (mode + 1) % 3,
                step_len: 4,
                step_space: 1,
                dir_setup: 1,
                dir_hold: 1,
                ..Default::default()
            };
            // Reset on the first clock a pin is high in the other mode.
            let in_pulse = (0..60).any(|_| {
                let out = clock(StepOutputInputs { step: true, dir: true, ..other });
                out.out_a || out.out_b
            });
            assert!(in_pulse, "the other mode never drove a pin");
            clock(StepOutputInputs { reset: true, ..tied });
        }
    }
    let mut log = PinLog::default();
    let mut last = (false, false);
    for clk in 1..=120u32 {
        let request = clk == delay;
        let out = clock(StepOutputInputs {
            step: request,
            dir: forward,
            ..tied
        });
        let pins = (out.out_a, out.out_b);
        if pins != last {
            log.changes.push(pins);
            if pins.0 && !last.0 {
                log.a_rises += 1;
                log.b_at_a_rise.push(pins.1);
            }
            if pins.1 && !last.1 {
                log.b_rises += 1;
            }
        }
        last = pins;
    }
    assert!(!clock(tied).busy, "still busy after 120 clocks");
    log
}

/// What one step looks like at the pins in each mode, from outputs low.
fn one_step_pins(mode: u8, forward: bool) -> PinLog {
    match (mode, forward) {
        // Step/dir: dir turns first (forward only), then one step pulse.
        (0 | 3, true) => PinLog {
            a_rises: 1,
            b_rises: 1,
            b_at_a_rise: vec![true],
            changes: vec![(false, true), (true, true), (false, true)],
        },
        (0 | 3, false) => PinLog {
            a_rises: 1,
            b_rises: 0,
            b_at_a_rise: vec![false],
            changes: vec![(true, false), (false, false)],
        },
        // Up/down: one pulse on up or on down, the other pin quiet.
        (1, true) => PinLog {
            a_rises: 1,
            b_rises: 0,
            b_at_a_rise: vec![false],
            changes: vec![(true, false), (false, false)],
        },
        (1, false) => PinLog {
            a_rises: 0,
            b_rises: 1,
            b_at_a_rise: vec![],
            changes: vec![(false, true), (false, false)],
        },
        // Quadrature: one Gray state, 00 -> 10 forward, 00 -> 01 backward.
        (_, true) => PinLog {
            a_rises: 1,
            b_rises: 0,
            b_at_a_rise: vec![false],
            changes: vec![(true, false)],
        },
        (_, false) => PinLog {
            a_rises: 0,
            b_rises: 1,
            b_at_a_rise: vec![],
            changes: vec![(false, true)],
        },
    }
}

/// Issue 24: `mode` held from time 0 applies to the first step, whichever
/// of the first 20 clocks after power-up or reset requests it, and a reset
/// takes the mode input even in the middle of another mode's pulse.
#[test]
fn a_mode_tied_from_time_0_holds_for_a_step_on_each_of_the_first_20_clocks() {
    let mut runs = 0;
    for mode in 0..4u8 {
        for forward in [true, false] {
            for start in [Start::PowerUp, Start::Reset, Start::ResetMidPulseInAnotherMode] {
                for delay in 1..=20 {
                    let seen = one_early_step(mode, forward, start, delay);
                    assert_eq!(
                        seen,
                        one_step_pins(mode, forward),
                        "mode {mode}, forward {forward}, {start:?}, step on clock {delay}"
                    );
                    runs += 1;
                }
            }
        }
    }
    assert_eq!(runs, 4 * 2 * 3 * 20);
}
