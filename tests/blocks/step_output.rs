//! `step_output`: RTL against the model, an independent monitor of the
//! output pins for every timing rule and the net step count in each mode
//! (with random flushes), flush, saturation, and cross-simulation.

use motion_hdl::blocks::step_output::model::{
    pending_limits, StepOutputInputs, StepOutputModel, StepOutputOutputs, PENDING_MAX, PENDING_MIN,
};
use motion_hdl::blocks::step_output::StepOutput;
use motion_hdl::sim::{stepper, Backend, Harness, Lockstep, Stepper};
use motion_hdl::tools::cosim::{check_instance, Instance};
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
    stepper(
        backend,
        "step_output",
        StepOutput::<16, 16>::default(),
        None,
    )
    .unwrap_or_else(|e| panic!("{e}"))
}

/// Runs of requests, each with one mode and one set of timings: bursts of
/// random density, direction reversals at random points (so they land at
/// every point of the timing sequence), then a drain until the stage is idle,
/// when the next run may change the mode and timings. A `flush` comes about
/// once in 200 clocks, more often while a pulse is high. The last outputs
/// come from the caller, so the same driver runs against the model or the
/// RTL.
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

    fn next(&mut self, last: &StepOutputOutputs) -> StepOutputInputs {
        let rng = &mut self.rng;
        if self.burst_left == 0 && !last.busy && rng.gen_ratio(1, 3) {
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
        inputs.flush =
            rng.gen_ratio(1, 200) || (pulse_high(inputs.mode, last) && rng.gen_ratio(1, 60));
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

/// A step pulse is high at the pins (step/dir: step; up/down: either).
fn pulse_high(mode: u8, out: &StepOutputOutputs) -> bool {
    match mode {
        0 | 3 => out.out_a,
        1 => out.out_a || out.out_b,
        _ => false,
    }
}

/// Where the flushes of a run landed, so a run that never flushes at an
/// interesting point cannot pass.
#[derive(Debug, Default)]
struct Flushes {
    total: u32,
    /// While a step pulse was high.
    in_pulse: u32,
    /// With a request on the same clock.
    with_request: u32,
    /// With steps pending.
    with_pending: u32,
    /// On the clock a step left.
    with_emit: u32,
}

impl Flushes {
    fn count(
        &mut self,
        inputs: &StepOutputInputs,
        before: &StepOutputOutputs,
        after: &StepOutputOutputs,
    ) {
        if inputs.flush {
            self.total += 1;
            self.in_pulse += pulse_high(inputs.mode, before) as u32;
            self.with_request += inputs.step as u32;
            self.with_pending += (before.pending_forward || before.pending_backward) as u32;
            self.with_emit += after.emitted as u32;
        }
    }

    /// Each kind of flush came at least `n` times (`in_pulse` only where
    /// the mode has pulses).
    fn assert_at_least(&self, n: u32, pulses: bool) {
        println!("flushes: {self:?}");
        assert!(
            (self.in_pulse >= n || !pulses)
                && self.with_request >= n
                && self.with_pending >= n
                && self.with_emit >= n,
            "flushes: {self:?}"
        );
    }
}

#[test]
fn rtl_matches_model_cycle_by_cycle_in_every_mode() {
    let mut driver = Driver::new(0x57e9, vec![0, 1, 2, 3]);
    let mut pair = Lockstep::new(long_run_rtl(), StepOutputModel::new(16, 16));
    let mut last = StepOutputOutputs::default();
    let mut flushes = Flushes::default();
    let mut pending_flags = (0, 0);
    for cycle in 0..1_000_000 {
        let mut inputs = driver.next(&last);
        inputs.reset = cycle % 250_000 == 249_999;
        let rtl = pair.step(&inputs).unwrap_or_else(|e| panic!("{e}"));
        flushes.count(&inputs, &last, &rtl);
        pending_flags.0 += rtl.pending_forward as u32;
        pending_flags.1 += rtl.pending_backward as u32;
        last = rtl;
    }
    assert!(driver.runs > 500, "only {} runs", driver.runs);
    flushes.assert_at_least(100, true);
    assert!(
        pending_flags.0 > 10_000 && pending_flags.1 > 10_000,
        "{pending_flags:?}"
    );
}

/// A 4-bit pending count (-8..7) saturates often under the same stimulus:
/// drops, `overrun` and `clear_overrun` against the model.
#[test]
fn narrow_pending_count_saturates_and_clears_like_the_model() {
    let mut driver = Driver::new(0x4a7, vec![0, 1, 2]);
    let mut pair = Lockstep::harness(
        "step_output",
        StepOutput::<16, 4>::default(),
        StepOutputModel::new(16, 4),
    );
    let (mut last, mut overruns, mut clears) = (StepOutputOutputs::default(), 0, 0);
    let mut flushes = Flushes::default();
    let mut saturated_flushes = 0;
    for _ in 0..300_000 {
        let before = pair.model().pending();
        let inputs = driver.next(&last);
        let rtl = pair.step(&inputs).unwrap_or_else(|e| panic!("{e}"));
        overruns += (!last.overrun && rtl.overrun) as u32;
        clears += (last.overrun && inputs.clear_overrun && !rtl.overrun) as u32;
        flushes.count(&inputs, &last, &rtl);
        saturated_flushes += (inputs.flush && (before == 7 || before == -8)) as u32;
        last = rtl;
    }
    assert!(
        overruns > 50 && clears > 50,
        "{overruns} overruns, {clears} clears"
    );
    flushes.assert_at_least(20, true);
    assert!(
        saturated_flushes > 20,
        "{saturated_flushes} flushes of a saturated count"
    );
}

/// Checks the output pins against the port contract of one mode, knowing
/// only the settings, the requests, the flushes and the pins (not the
/// model).
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
    /// Net requested steps a flush dropped before they left.
    flushed: i64,
    /// Requested, not yet emitted, not flushed (signed).
    pending: i64,
    /// A flush came and no request since: no step may leave.
    flushed_idle: bool,
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
            flushed: 0,
            pending: 0,
            flushed_idle: false,
            checks: 0,
        }
    }

    /// Counts the request and flush of one clock against the step that
    /// left at its edge (`out.emitted`): the steps still pending, which
    /// `pending_forward`/`pending_backward` must show; a flush drops them
    /// and this clock's request, and then no step leaves until a new
    /// request. The stage is never saturated here.
    fn count(&mut self, cycle: u64, inputs: &StepOutputInputs, out: &StepOutputOutputs) {
        let sign = |forward: bool| if forward { 1 } else { -1 };
        if out.emitted {
            assert!(
                !self.flushed_idle,
                "cycle {cycle}: a step left after a flush with no request since"
            );
        }
        let requested = if inputs.step { sign(inputs.dir) } else { 0 };
        let left = if out.emitted {
            sign(out.emitted_forward)
        } else {
            0
        };
        self.requested += requested;
        self.pending += requested - left;
        if inputs.flush {
            self.flushed += self.pending;
            self.pending = 0;
            self.flushed_idle = true;
        } else if inputs.step {
            self.flushed_idle = false;
        }
        assert_eq!(
            (out.pending_forward, out.pending_backward),
            (self.pending > 0, self.pending < 0),
            "cycle {cycle}: pending flags with {} steps pending",
            self.pending
        );
    }

    /// At the end of a run, idle: every step requested and not flushed
    /// came out at the pins, net.
    fn assert_net_count(&self, what: &str) {
        assert_eq!(self.pending, 0, "{what}: steps still pending when idle");
        assert_eq!(
            self.emitted,
            self.requested - self.flushed,
            "{what}: net emitted steps != net requested - net flushed"
        );
    }

    /// The `emitted` strobe must mark each step seen at the pins, in the
    /// same clock and with its direction.
    fn strobe(&mut self, out: &StepOutputOutputs) {
        if out.emitted {
            self.strobed += if out.emitted_forward { 1 } else { -1 };
        }
        assert_eq!(
            self.strobed, self.emitted,
            "emitted strobes disagree with the pins"
        );
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
        let mut last = StepOutputOutputs::default();
        let mut checks = 0;
        let mut runs_checked = 0;
        let mut flushes = Flushes::default();
        let mut flushed_steps = 0;
        for cycle in 0..1_000_000u64 {
            let inputs = driver.next(&last);
            let out = rtl_clock(dut.as_mut(), &inputs);
            flushes.count(&inputs, &last, &out);
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
                    assert!(!last.busy, "settings changed while busy");
                    m.assert_net_count(&format!("mode {mode}, cycle {cycle}"));
                    checks += m.checks;
                    runs_checked += 1;
                    flushed_steps += m.flushed.abs();
                }
                monitor = Some(PinMonitor::new(&inputs, pins));
            }
            let m = monitor.as_mut().unwrap();
            m.sample(cycle, pins);
            m.strobe(&out);
            m.count(cycle, &inputs, &out);
            assert!(!out.overrun, "mode {mode}: overrun without saturation");
            assert_eq!(out.mode_invalid, mode == 3);
            last = out;
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
            m.count(cycle, &idle, &out);
            if !out.busy {
                break;
            }
        }
        m.assert_net_count(&format!("mode {mode}: the last run"));
        assert!(
            runs_checked > 300 && checks > 50_000,
            "mode {mode}: {runs_checked} runs, {checks} checks"
        );
        // Quadrature has no pulse to flush in.
        flushes.assert_at_least(100, mode != 2);
        println!(
            "mode {mode}: {runs_checked} runs, {checks} checks, {flushed_steps} steps flushed"
        );
        assert!(
            flushed_steps > 1000,
            "mode {mode}: {flushed_steps} steps flushed"
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
    let mut last = StepOutputOutputs::default();
    (0..cycles)
        .map(|_| {
            let inputs = driver.next(&last);
            last = model.step(inputs);
            inputs.to_vector()
        })
        .collect()
}

#[test]
fn exported_verilog_matches_rust_in_icarus_and_verilator() {
    let stimulus = cosim_stimulus(0xc059, vec![0, 1, 2, 3], 16, 16, 40_000);
    check_instance::<StepOutput<16, 16>>(Instance::Exported("step_output"), stimulus);
}

#[test]
fn narrow_6_bit_timers_match_rust_in_icarus_and_verilator() {
    let stimulus = cosim_stimulus(0xc05a, vec![0, 1, 2], 6, 16, 30_000);
    check_instance::<StepOutput<6, 16>>(Instance::Generated("step_output_t6"), stimulus);
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
    rtl_clock(
        &mut harness,
        &StepOutputInputs {
            reset: true,
            ..settings
        },
    );
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
    crate::support::timing_diagram::assert_timing_diagram_is("step_output", &timing_diagram());
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
    check_instance::<StepOutput<16, 8>>(Instance::Generated("step_output_p8"), stimulus);
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
    let mut pair = Lockstep::harness(
        "step_output",
        StepOutput::<16, 16>::default(),
        StepOutputModel::new(16, 16),
    );
    let tied = StepOutputInputs {
        mode,
        step_len: 4,
        step_space: 4,
        dir_setup: 6,
        dir_hold: 2,
        ..Default::default()
    };
    let mut clock = |inputs: StepOutputInputs| {
        pair.step(&inputs)
            .unwrap_or_else(|e| panic!("{start:?} mode {mode}: {e}"))
    };
    match start {
        Start::PowerUp => {}
        Start::Reset => {
            for _ in 0..3 {
                clock(tied);
            }
            clock(StepOutputInputs {
                reset: true,
                ..tied
            });
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
                let out = clock(StepOutputInputs {
                    step: true,
                    dir: true,
                    ..other
                });
                out.out_a || out.out_b
            });
            assert!(in_pulse, "the other mode never drove a pin");
            clock(StepOutputInputs {
                reset: true,
                ..tied
            });
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
            for start in [
                Start::PowerUp,
                Start::Reset,
                Start::ResetMidPulseInAnotherMode,
            ] {
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

/// Where a flush landed in a directed run.
#[derive(Debug, Default)]
struct FlushLanding {
    in_pulse: u32,
    on_emit: u32,
    between_pulses: u32,
    after_the_steps: u32,
}

/// Forward steps requested on clocks 1 to 3 after a reset (up to the flush),
/// a flush on clock `flush_at`, and one more step (`forward_after`) requested `gap`
/// clocks after the flush, against the model and the pin monitor: the pulse
/// the flush meets keeps its full `step_len` (the monitor checks every
/// pulse length), nothing leaves from the flush until the new request, the
/// new step leaves, alone, and its pulse keeps step_space, dir_hold and
/// dir_setup after the last pulse (the monitor's rules).
fn flush_then_one_step(
    mode: u8,
    flush_at: u64,
    gap: u64,
    forward_after: bool,
    landing: &mut FlushLanding,
) {
    let mut harness = Harness::new("step_output", StepOutput::<16, 16>::default()).unwrap();
    let mut model = StepOutputModel::new(16, 16);
    let settings = StepOutputInputs {
        mode,
        step_len: 5,
        step_space: 7,
        dir_setup: 4,
        dir_hold: 3,
        ..Default::default()
    };
    let what = format!(
        "mode {mode}, flush on clock {flush_at}, step {gap} later (forward {forward_after})"
    );
    let reset = StepOutputInputs {
        reset: true,
        ..settings
    };
    let mut last = rtl_clock(&mut harness, &reset);
    assert_eq!(last, model.step(reset), "{what}: reset");
    let mut m = PinMonitor::new(&settings, (false, false));
    // The model is compared after the run, so that the checks here, which
    // do not use it, are the ones that catch a broken flush.
    let mut model_differs = None;
    let mut left_before_flush = 0;
    let mut left_after_request = Vec::new();
    for clock in 1..=150u64 {
        let mut inputs = settings;
        if clock <= 3.min(flush_at) {
            (inputs.step, inputs.dir) = (true, true);
        }
        if clock == flush_at + gap {
            (inputs.step, inputs.dir) = (true, forward_after);
        }
        inputs.flush = clock == flush_at;
        let out = rtl_clock(&mut harness, &inputs);
        let expected = model.step(inputs);
        if out != expected && model_differs.is_none() {
            model_differs = Some(format!("clock {clock}: RTL {out:?}, model {expected:?}"));
        }
        m.sample(clock, (out.out_a, out.out_b));
        m.strobe(&out);
        m.count(clock, &inputs, &out);
        if inputs.flush {
            let pending = last.pending_forward || last.pending_backward;
            if pulse_high(mode, &last) {
                landing.in_pulse += 1;
            } else if out.emitted {
                landing.on_emit += 1;
            } else if pending {
                landing.between_pulses += 1;
            } else {
                landing.after_the_steps += 1;
            }
        }
        if out.emitted {
            if clock <= flush_at {
                left_before_flush += 1;
                assert!(out.emitted_forward, "{what}: clock {clock}");
            } else {
                assert!(
                    clock > flush_at + gap,
                    "{what}: a step left on clock {clock}, after the flush, before the request"
                );
                left_after_request.push(out.emitted_forward);
            }
        }
        last = out;
    }
    assert!(!last.busy, "{what}: still busy");
    let requested = 3.min(flush_at) as i64;
    assert!(
        left_before_flush <= requested,
        "{what}: {left_before_flush} left"
    );
    assert_eq!(
        left_after_request,
        vec![forward_after],
        "{what}: the step after the flush"
    );
    assert_eq!(
        m.flushed,
        requested - left_before_flush,
        "{what}: steps flushed"
    );
    m.assert_net_count(&what);
    assert_eq!(model_differs, None, "{what}: RTL and model");
}

#[test]
fn a_flush_completes_the_pulse_it_meets_and_the_next_step_keeps_every_interval() {
    let mut landing = FlushLanding::default();
    for mode in 0..3u8 {
        for flush_at in 1..=45 {
            for gap in [1, 2, 3, 4, 6, 9, 14] {
                for forward_after in [true, false] {
                    flush_then_one_step(mode, flush_at, gap, forward_after, &mut landing);
                }
            }
        }
    }
    println!("{landing:?}");
    assert!(
        landing.in_pulse >= 100
            && landing.on_emit >= 10
            && landing.between_pulses >= 100
            && landing.after_the_steps >= 100,
        "{landing:?}"
    );
}

/// A request on the flush clock is dropped with the pending steps (and is
/// an overrun only if it met a saturated count); one on the next clock is
/// kept.
#[test]
fn a_flush_drops_the_request_of_its_own_clock() {
    for mode in 0..3u8 {
        for pending_before in [0u32, 1, 5] {
            for forward in [true, false] {
                let what = format!("mode {mode}, {pending_before} pending, forward {forward}");
                let mut harness =
                    Harness::new("step_output", StepOutput::<16, 16>::default()).unwrap();
                let mut model = StepOutputModel::new(16, 16);
                let mut model_differs = None;
                // Long enough that the requested steps are still pending.
                let settings = StepOutputInputs {
                    mode,
                    dir: forward,
                    step_len: 30,
                    step_space: 30,
                    dir_setup: 2,
                    dir_hold: 2,
                    ..Default::default()
                };
                // The model is compared last, after the checks that do not use it.
                let mut clock = |inputs: StepOutputInputs| {
                    let out = rtl_clock(&mut harness, &inputs);
                    let expected = model.step(inputs);
                    if out != expected && model_differs.is_none() {
                        model_differs =
                            Some(format!("{inputs:?}: RTL {out:?}, model {expected:?}"));
                    }
                    out
                };
                let mut emitted = 0;
                for _ in 0..pending_before {
                    emitted += clock(StepOutputInputs {
                        step: true,
                        ..settings
                    })
                    .emitted as u32;
                }
                let out = clock(StepOutputInputs {
                    step: true,
                    flush: true,
                    ..settings
                });
                emitted += out.emitted as u32;
                assert!(
                    !out.pending_forward && !out.pending_backward,
                    "{what}: pending after the flush"
                );
                assert!(!out.overrun, "{what}");
                let before_flush = emitted;
                for _ in 0..200 {
                    let out = clock(settings);
                    assert!(!out.emitted, "{what}: a step left after the flush");
                    assert!(!out.pending_forward && !out.pending_backward, "{what}");
                }
                assert!(before_flush <= 1, "{what}: {before_flush} steps left");
                // The next request after the flush is kept.
                clock(StepOutputInputs {
                    step: true,
                    ..settings
                });
                let mut left = 0;
                for _ in 0..200 {
                    let out = clock(settings);
                    if out.emitted {
                        assert_eq!(out.emitted_forward, forward, "{what}");
                        left += 1;
                    }
                }
                assert_eq!(left, 1, "{what}: the request after the flush");
                assert_eq!(model_differs, None, "{what}: RTL and model");
            }
        }
    }
}

/// A flush with a request that meets a saturated count: the request is
/// dropped with the rest and flags `overrun`, as it would without the flush;
/// the count is empty after it.
#[test]
fn a_flush_with_a_request_at_a_saturated_count_flags_overrun() {
    let (min, max) = pending_limits(4);
    for forward in [true, false] {
        let mut harness = Harness::new("step_output", StepOutput::<16, 4>::default()).unwrap();
        let mut model = StepOutputModel::new(16, 4);
        let mut model_differs = None;
        let slow = StepOutputInputs {
            dir: forward,
            step_len: 1000,
            step_space: 1000,
            ..Default::default()
        };
        // The model is compared last, after the checks that do not use it.
        let mut clock = |inputs: StepOutputInputs| {
            let out = rtl_clock(&mut harness, &inputs);
            let expected = model.step(inputs);
            if out != expected && model_differs.is_none() {
                model_differs = Some(format!("{inputs:?}: RTL {out:?}, model {expected:?}"));
            }
            out
        };
        // Fill to the limit without an overrun (the first step leaves).
        // The first step leaves at once; then the count fills to its limit.
        let sign = if forward { 1 } else { -1 };
        let limit = if forward { max } else { min };
        let mut pending = 0;
        while pending != limit {
            let out = clock(StepOutputInputs { step: true, ..slow });
            assert!(
                !out.overrun,
                "forward {forward}: overrun at {pending} pending"
            );
            pending += sign - if out.emitted { sign } else { 0 };
            assert_eq!(
                (out.pending_forward, out.pending_backward),
                (pending > 0, pending < 0)
            );
        }
        let out = clock(StepOutputInputs {
            step: true,
            flush: true,
            ..slow
        });
        assert!(
            out.overrun,
            "forward {forward}: the dropped request at the limit"
        );
        assert!(!out.pending_forward && !out.pending_backward);
        // The pulse in flight completes; nothing follows it.
        let mut rises = 0;
        let mut last_a = out.out_a;
        for _ in 0..5000 {
            let out = clock(StepOutputInputs {
                clear_overrun: true,
                ..slow
            });
            rises += (out.out_a && !last_a) as u32;
            last_a = out.out_a;
            assert!(!out.overrun && !out.emitted);
            assert!(!out.pending_forward && !out.pending_backward);
        }
        assert_eq!(rises, 0, "forward {forward}: a step after the flush");
        assert_eq!(model_differs, None, "forward {forward}: RTL and model");
    }
}
