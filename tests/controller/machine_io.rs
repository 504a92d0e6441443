//! `motion_controller` machine I/O and hardware safety (issue #16): limits,
//! drive alarms, E-stop, home, drive enables and general I/O, checked at
//! the pins.
//!
//! Every test runs the exported controller (compiled by Verilator) in
//! lockstep with the model through the bench, so the model is checked on
//! every clock too; the assertions here are written from the datasheet's
//! latencies ([`latency`]) and counted at the pins, not taken from the model.

use crate::bench::Bench;
use motion_hdl::blocks::motion_controller::latency;
use motion_hdl::blocks::motion_controller::model::ControllerOutputs;
use motion_hdl::blocks::motion_controller::registers::{global, StopCause};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

pub(crate) type Controller3 = Bench<3, 4, 5, true, false, true>;

/// Step output modes.
pub(crate) const STEP_DIR: u8 = 0;
pub(crate) const UP_DOWN: u8 = 1;
pub(crate) const QUADRATURE: u8 = 2;

/// A step seen at the pins of one axis in one clock: +1 forward, -1
/// backward, 0 none. Step/dir: a rise of A, direction B; up/down: a rise of
/// A (forward) or B (backward); quadrature: a Gray state change.
fn pin_step(mode: u8, before: (bool, bool), now: (bool, bool)) -> i64 {
    match mode {
        UP_DOWN => (now.0 && !before.0) as i64 - (now.1 && !before.1) as i64,
        QUADRATURE => {
            if now == before {
                0
            } else if now == (!before.1, before.0) {
                1
            } else if now == (before.1, !before.0) {
                -1
            } else {
                panic!("quadrature pins jumped {before:?} -> {now:?}")
            }
        }
        _ => {
            if now.0 && !before.0 {
                if now.1 {
                    1
                } else {
                    -1
                }
            } else {
                0
            }
        }
    }
}

/// The controller set up as firmware would: a base tick every clock,
/// `period` ticks per period, DDA axes in `modes` with pulses `step_len`
/// long, limits and alarms enabled, every drive enabled, the input filter
/// at `filter` samples, every clock.
pub(crate) fn setup(
    b: &mut Controller3,
    modes: [u8; 3],
    step_len: [u32; 3],
    filter: u64,
    period: u32,
) {
    b.write("TICK_DIVISOR", 0, 1);
    b.write("PERIOD_TICKS", 0, period);
    let f = b.pack("INPUT_FILTER", &[("LENGTH", filter), ("SAMPLE_RATE", 0)]);
    b.write("INPUT_FILTER", 0, f);
    for axis in 0..3u32 {
        let config = b.pack("AXIS_CONFIG", &[("STEP_MODE", modes[axis as usize] as u64)]);
        b.write("AXIS_CONFIG", axis, config);
        b.write("STEP_LEN", axis, step_len[axis as usize]);
        for timer in ["STEP_SPACE", "DIR_SETUP", "DIR_HOLD"] {
            b.write(timer, axis, 2);
        }
        let io = b.pack(
            "IO_CONFIG",
            &[
                ("LIMIT_ENABLE", 1),
                ("ALARM_ENABLE", 1),
                ("DRIVE_ENABLE", 1),
            ],
        );
        b.write("IO_CONFIG", axis, io);
    }
    b.idle(20);
}

/// Queues `periods` periods of `counts` steps and starts.
pub(crate) fn queue_and_run(b: &mut Controller3, counts: [i32; 3], periods: usize) {
    for _ in 0..periods {
        for (axis, n) in counts.iter().enumerate() {
            b.write("FIFO_WRITE", axis as u32, *n as u32);
        }
    }
    b.write("CONTROL", 0, 1);
}

/// Records the step pins of every clock and counts the steps per axis.
pub(crate) struct PinLog {
    modes: [u8; 3],
    last: Vec<(bool, bool)>,
    /// Net steps per axis since the log began.
    net: [i64; 3],
    /// (clock, axis, direction) of every step.
    /// (clock, axis, step) of every step seen at the pins.
    pub(crate) steps: Vec<(u64, usize, i64)>,
}

impl PinLog {
    pub(crate) fn new(b: &Controller3, modes: [u8; 3]) -> Self {
        Self {
            modes,
            last: b.last.steps.clone(),
            net: [0; 3],
            steps: Vec::new(),
        }
    }

    pub(crate) fn clock(&mut self, b: &mut Controller3) -> ControllerOutputs {
        let out = b.clock(false, 0, 0, false, false).clone();
        self.see(b.cycles - 1, &out);
        out
    }

    pub(crate) fn see(&mut self, clock: u64, out: &ControllerOutputs) {
        for axis in 0..3 {
            let step = pin_step(self.modes[axis], self.last[axis], out.steps[axis]);
            if step != 0 {
                self.net[axis] += step;
                self.steps.push((clock, axis, step));
            }
        }
        self.last = out.steps.clone();
    }

    fn last_step(&self, axis: usize, direction: Option<i64>) -> Option<u64> {
        self.steps
            .iter()
            .filter(|s| s.1 == axis && direction.is_none_or(|d| s.2 == d))
            .map(|s| s.0)
            .next_back()
    }
}

fn cmd_position(b: &mut Controller3, axis: u32) -> i64 {
    b.read("CMD_POSITION", axis) as i32 as i64
}

fn stop_cause(b: &mut Controller3) -> (StopCause, u64) {
    let word = b.read("STOP_CAUSE", 0);
    (
        StopCause::from_code(b.field("STOP_CAUSE", "CAUSE", word) as u32),
        b.field("STOP_CAUSE", "AXIS", word),
    )
}

/// A positive limit closing under a moving axis, at every phase of its
/// steps and for several filter lengths: its last forward step rises no
/// later than the datasheet's latency, every other axis stops within its
/// abort latency, both bounds are reached at some phase (they are exact),
/// the trip is flagged with its cause, and every axis's commanded position
/// equals the steps counted at its pins.
#[test]
fn a_limit_cuts_its_axis_and_aborts_all_within_the_stated_latency() {
    for filter in [0u64, 4, 9] {
        let seen = latency::switch(filter, 0);
        let (mut worst_own, mut worst_other) = (0, 0);
        for phase in 0..16u64 {
            let mut b = Controller3::new();
            setup(
                &mut b,
                [STEP_DIR, UP_DOWN, QUADRATURE],
                [2, 3, 2],
                filter,
                200,
            );
            b.write("IRQ_ENABLE", 0, b.pack("IRQ_ENABLE", &[("LIMIT", 1)]));
            queue_and_run(&mut b, [40, -30, 35], 8);
            let mut log = PinLog::new(&b, [STEP_DIR, UP_DOWN, QUADRATURE]);
            for _ in 0..300 + phase {
                log.clock(&mut b);
            }
            let c = b.cycles;
            b.pins.limit_pos = 1;
            let mut irq_at = None;
            for _ in 0..80 {
                let out = log.clock(&mut b);
                if out.irq && irq_at.is_none() {
                    irq_at = Some(b.cycles - 1);
                }
            }
            let own = log.last_step(0, Some(1)).unwrap_or(0).saturating_sub(c);
            assert!(
                own <= seen + latency::LIMIT_OWN_AXIS,
                "filter {filter} phase {phase}: own axis stepped at c + {own}"
            );
            // The other axes abort when a step toward the limit is cut,
            // which may be later than the limit closing: the next forward
            // step. The cut is seen at the pins as the LIMIT interrupt,
            // two clocks after the cut's own clock s (cut at s + 1, status
            // at that edge, irq registered one more).
            let cut = irq_at.expect("the LIMIT interrupt") - 2;
            assert!(cut + 2 > c + seen, "the cut follows the filtered level");
            let other = [1, 2]
                .iter()
                .filter_map(|&a| log.last_step(a, None))
                .max()
                .unwrap_or(0)
                .saturating_sub(cut);
            assert!(
                other <= latency::ABORT_ALL_AXES,
                "filter {filter} phase {phase}: other axis at cut + {other}"
            );
            worst_own = worst_own.max(own);
            worst_other = worst_other.max(other);
            assert!(!b.last.running, "RUN cleared");
            let io = b.read("IO_STATUS", 0);
            assert_eq!(b.field("IO_STATUS", "LIMIT_POS_TRIPPED", io), 1);
            assert_eq!(b.field("IO_STATUS", "LIMIT_NEG_TRIPPED", io), 0);
            let status = b.read("STATUS", 0);
            assert_eq!(b.field("STATUS", "LIMIT", status), 1);
            assert_eq!(stop_cause(&mut b), (StopCause::Limit, 0));
            for axis in 0..3 {
                assert_eq!(
                    cmd_position(&mut b, axis as u32),
                    log.net[axis],
                    "axis {axis} commanded = pins"
                );
            }
        }
        assert_eq!(
            worst_own,
            seen + latency::LIMIT_OWN_AXIS,
            "filter {filter}: own-axis bound is exact"
        );
        assert_eq!(
            worst_other,
            latency::ABORT_ALL_AXES,
            "filter {filter}: abort bound is exact"
        );
    }
}

/// After a limit trip the firmware clears the flag and backs off the
/// switch, still active: the steps away leave, exactly; a step toward it
/// trips again and never leaves.
#[test]
fn backing_off_a_limit_after_clearing_its_flag() {
    let mut b = Controller3::new();
    setup(&mut b, [STEP_DIR; 3], [2; 3], 4, 100);
    queue_and_run(&mut b, [20, 0, 0], 4);
    let mut log = PinLog::new(&b, [STEP_DIR; 3]);
    for _ in 0..150 {
        log.clock(&mut b);
    }
    b.pins.limit_pos = 1;
    for _ in 0..100 {
        log.clock(&mut b);
    }
    assert!(!b.last.running);
    let at_switch = log.net[0];
    assert!(at_switch > 0 && at_switch < 80);
    // RUN is refused while the trip is held.
    b.write("CONTROL", 0, b.pack("CONTROL", &[("FLUSH", 1)]));
    queue_and_run(&mut b, [-10, 0, 0], 3);
    b.idle(50);
    assert!(!b.last.running, "RUN refused while LIMIT_POS_TRIPPED");
    let refused = b.read("STATE", 0);
    assert_eq!(b.field("STATE", "ABORTED", refused), 1);
    // Clear, flush the stale periods, back off.
    b.write(
        "IO_COMMAND",
        0,
        b.pack("IO_COMMAND", &[("CLEAR_LIMITS", 1)]),
    );
    b.write("CONTROL", 0, b.pack("CONTROL", &[("FLUSH", 1)]));
    let start = log.net[0];
    queue_and_run(&mut b, [-10, 0, 0], 3);
    for _ in 0..600 {
        log.clock(&mut b);
    }
    assert_eq!(
        log.net[0],
        start - 30,
        "every step away from the active limit left"
    );
    assert_eq!(cmd_position(&mut b, 0), log.net[0]);
    let io = b.read("IO_STATUS", 0);
    assert_eq!(
        b.field("IO_STATUS", "LIMIT_POS", io),
        1,
        "the switch is still active"
    );
    assert_eq!(
        b.field("IO_STATUS", "LIMIT_POS_TRIPPED", io),
        0,
        "backing off is no trip"
    );
    assert_eq!(stop_cause(&mut b).0, StopCause::Underrun);
    // Toward the switch again: cut, no step leaves.
    let before = log.net[0];
    queue_and_run(&mut b, [5, 0, 0], 2);
    for _ in 0..400 {
        log.clock(&mut b);
    }
    assert_eq!(log.net[0], before, "no step toward the active limit");
    assert_eq!(stop_cause(&mut b), (StopCause::Limit, 0));
    assert_eq!(cmd_position(&mut b, 0), log.net[0]);
}

/// The home edge latches CMD_POSITION and ACT_POSITION of the clock it is
/// acted on: the commanded position counts every step whose first pin edge
/// came before that clock, for a home edge at every phase of a step pulse.
#[test]
fn home_latches_the_position_of_its_clock_at_every_phase_of_a_step() {
    let filter = 3;
    let seen = latency::switch(filter, 0);
    for phase in 0..16u64 {
        let mut b = Controller3::new().with_loopback();
        setup(&mut b, [STEP_DIR; 3], [4; 3], filter, 160);
        queue_and_run(&mut b, [20, 0, 0], 4);
        let mut log = PinLog::new(&b, [STEP_DIR; 3]);
        for _ in 0..200 + phase {
            log.clock(&mut b);
        }
        let c = b.cycles;
        b.pins.home = 1;
        let mut act_at_latch = None;
        for _ in 0..40 {
            log.clock(&mut b);
            if b.cycles - 1 == c + seen {
                // CMD_POSITION counts a step one clock after its first pin
                // edge: the register of clock c + seen holds the steps
                // whose edge came at c + seen - 1 or before.
                act_at_latch = Some(b.model().axes()[0].actual_position());
            }
        }
        let expected = log
            .steps
            .iter()
            .filter(|s| s.1 == 0 && s.0 < c + seen)
            .map(|s| s.2)
            .sum::<i64>();
        assert_eq!(
            b.read("HOME_CMD_POSITION", 0) as i32 as i64,
            expected,
            "phase {phase}"
        );
        assert_eq!(
            b.read("HOME_ACT_POSITION", 0) as i32,
            act_at_latch.unwrap(),
            "phase {phase}"
        );
        let io = b.read("IO_STATUS", 0);
        assert_eq!(b.field("IO_STATUS", "HOME_SEEN", io), 1);
        assert!(b.last.running, "without STOP_ON_HOME the move goes on");
    }
}

/// With STOP_ON_HOME the home edge aborts like a limit trip, and a second
/// edge does not overwrite the latch until CLEAR_HOME.
#[test]
fn stop_on_home_aborts_and_the_latch_holds_the_first_edge() {
    let mut b = Controller3::new();
    setup(&mut b, [STEP_DIR; 3], [2; 3], 2, 100);
    b.write(
        "IO_CONFIG",
        1,
        b.pack("IO_CONFIG", &[("LIMIT_ENABLE", 1), ("STOP_ON_HOME", 1)]),
    );
    queue_and_run(&mut b, [10, 10, 10], 10);
    b.idle(300);
    b.pins.home = 0b010;
    b.idle(60);
    assert!(!b.last.running);
    assert_eq!(stop_cause(&mut b), (StopCause::Home, 1));
    let latched = b.read("HOME_CMD_POSITION", 1);
    b.pins.home = 0;
    b.idle(20);
    b.pins.home = 0b010;
    b.idle(20);
    assert_eq!(
        b.read("HOME_CMD_POSITION", 1),
        latched,
        "the first edge stays latched"
    );
    b.write("IO_COMMAND", 1, b.pack("IO_COMMAND", &[("CLEAR_HOME", 1)]));
    // ABORTED is the registered hold: one clock after the flag.
    b.idle(1);
    let state = b.read("STATE", 0);
    assert_eq!(
        b.field("STATE", "ABORTED", state),
        0,
        "CLEAR_HOME releases the stop"
    );
}

/// E-stop in the middle of a long step pulse: the pulse keeps its full
/// length, no step rises after the abort latency, every drive enable drops
/// at its latency, RUN is refused until the E-stop is released and
/// acknowledged, and the safe general outputs drop with it.
#[test]
fn estop_during_a_step_pulse_finishes_the_pulse_and_stops_everything() {
    let filter = 2;
    let seen = latency::switch(filter, 0);
    for phase in 0..12u64 {
        let mut b = Controller3::new();
        setup(&mut b, [STEP_DIR; 3], [30, 30, 30], filter, 400);
        b.write("GPIO_OUT", 0, 0b1111_0000);
        b.write("GPIO_SAFE", 0, 0b0011_0000);
        queue_and_run(&mut b, [8, -8, 5], 10);
        let mut log = PinLog::new(&b, [STEP_DIR; 3]);
        // Into a pulse of axis 0.
        while !b.last.steps[0].0 {
            log.clock(&mut b);
        }
        for _ in 0..phase {
            log.clock(&mut b);
        }
        let c = b.cycles;
        b.pins.estop = true;
        // Pulses already high at c count from their rise.
        let mut high_run: [u64; 3] = std::array::from_fn(|axis| {
            if b.last.steps[axis].0 {
                log.steps
                    .iter()
                    .filter(|s| s.1 == axis)
                    .map(|s| c - s.0)
                    .next_back()
                    .unwrap_or(0)
            } else {
                0
            }
        });
        for _ in 0..150 {
            let out = log.clock(&mut b);
            let n = b.cycles - 1;
            for axis in 0..3 {
                if out.steps[axis].0 {
                    high_run[axis] += 1;
                } else if high_run[axis] > 0 {
                    assert_eq!(
                        high_run[axis], 30,
                        "phase {phase} axis {axis}: pulse cut short"
                    );
                    high_run[axis] = 0;
                }
            }
            if n >= c + seen + latency::DRIVE_ENABLE {
                assert_eq!(
                    out.drive_enable,
                    0,
                    "phase {phase}: drive enables at c + {}",
                    n - c
                );
                assert_eq!(out.gpio_out, 0b1100_0000, "safe outputs dropped");
            } else {
                assert_eq!(
                    out.drive_enable, 0b111,
                    "drive enables held until the latency"
                );
            }
        }
        let last = (0..3).filter_map(|a| log.last_step(a, None)).max().unwrap();
        assert!(
            last <= c + seen + latency::ABORT_ALL_AXES,
            "phase {phase}: step at c + {}",
            last - c
        );
        assert_eq!(stop_cause(&mut b), (StopCause::Estop, 0));
        b.write("CONTROL", 0, 1);
        b.idle(5);
        assert!(!b.last.running, "RUN refused during E-stop");
        // Released but not acknowledged: still refused.
        b.pins.estop = false;
        b.idle(20);
        b.write("CONTROL", 0, 1);
        b.idle(5);
        assert!(!b.last.running, "RUN refused until STATUS.ESTOP is cleared");
        b.write("STATUS", 0, b.pack("STATUS", &[("ESTOP", 1)]));
        let state = b.read("STATE", 0);
        assert_eq!(b.field("STATE", "ESTOP_LATCHED", state), 0);
        b.write("CONTROL", 0, 1);
        b.idle(5);
        assert!(b.last.running, "restart after the acknowledge");
        assert_eq!(
            b.last.drive_enable, 0b111,
            "drive enables back with their register bits"
        );
        for axis in 0..3u32 {
            assert_eq!(cmd_position(&mut b, axis), log.net[axis as usize]);
        }
    }
}

/// A drive alarm on axis 1 stops every axis within the abort latency,
/// drops only that drive's enable, and holds until the alarm is gone and
/// cleared.
#[test]
fn an_alarm_on_one_axis_stops_all_and_disables_only_its_drive() {
    let filter = 4;
    let seen = latency::switch(filter, 0);
    let mut b = Controller3::new();
    setup(&mut b, [STEP_DIR; 3], [2; 3], filter, 100);
    queue_and_run(&mut b, [25, 25, -25], 10);
    let mut log = PinLog::new(&b, [STEP_DIR; 3]);
    for _ in 0..250 {
        log.clock(&mut b);
    }
    let c = b.cycles;
    b.pins.drive_alarm = 0b010;
    for _ in 0..100 {
        let out = log.clock(&mut b);
        let n = b.cycles - 1;
        let expected = if n >= c + seen + latency::DRIVE_ENABLE {
            0b101
        } else {
            0b111
        };
        assert_eq!(out.drive_enable, expected, "at c + {}", n - c);
    }
    let last = (0..3).filter_map(|a| log.last_step(a, None)).max().unwrap();
    assert!(last <= c + seen + latency::ABORT_ALL_AXES);
    assert_eq!(stop_cause(&mut b), (StopCause::DriveAlarm, 1));
    // Clearing while the alarm is active does not clear it.
    b.write("IO_COMMAND", 1, b.pack("IO_COMMAND", &[("CLEAR_ALARM", 1)]));
    let io = b.read("IO_STATUS", 1);
    assert_eq!(b.field("IO_STATUS", "ALARM_TRIPPED", io), 1);
    b.pins.drive_alarm = 0;
    b.idle(20);
    b.write("IO_COMMAND", 1, b.pack("IO_COMMAND", &[("CLEAR_ALARM", 1)]));
    b.idle(3);
    assert_eq!(b.last.drive_enable, 0b111, "the drive is enabled again");
    for axis in 0..3u32 {
        assert_eq!(cmd_position(&mut b, axis), log.net[axis as usize]);
    }
}

/// An independent monitor of the safety contract at the pins. It knows the
/// firmware's configuration (modes, pulse lengths, filter) and sees only
/// the pins and the bus: it is not derived from the model.
struct SafetyMonitor {
    modes: [u8; 3],
    step_len: [u64; 3],
    /// `latency::switch` of the configured filter.
    seen: u64,
    /// Clock since which each pin has been continuously active.
    limit_pos_since: [Option<u64>; 3],
    limit_neg_since: [Option<u64>; 3],
    alarm_since: [Option<u64>; 3],
    estop_since: Option<u64>,
    /// The watchdog: ticks allowed, and the clock of the last kick.
    watchdog_timeout: u64,
    last_kick: Option<u64>,
    /// A lapse the firmware has not acknowledged (STATUS.WATCHDOG) yet.
    lapsed: Option<u64>,
    last: Vec<(bool, bool)>,
    high_for: [u64; 3],
    /// Net steps counted at the pins.
    net: [i64; 3],
    violations: Vec<String>,
    checks: u64,
}

impl SafetyMonitor {
    fn new(modes: [u8; 3], step_len: [u64; 3], filter: u64, watchdog_timeout: u64) -> Self {
        Self {
            modes,
            step_len,
            seen: latency::switch(filter, 0),
            limit_pos_since: [None; 3],
            limit_neg_since: [None; 3],
            alarm_since: [None; 3],
            estop_since: None,
            watchdog_timeout,
            last_kick: None,
            lapsed: None,
            last: vec![(false, false); 3],
            high_for: [0; 3],
            net: [0; 3],
            violations: Vec::new(),
            checks: 0,
        }
    }

    fn track(since: &mut Option<u64>, active: bool, clock: u64) {
        match (active, *since) {
            (true, None) => *since = Some(clock),
            (false, _) => *since = None,
            _ => {}
        }
    }

    fn violation(&mut self, text: String) {
        if self.violations.len() < 20 {
            self.violations.push(text);
        }
    }

    /// One clock: the pins applied in `clock`, the bus write of that clock,
    /// and the outputs after its edge.
    fn clock(
        &mut self,
        clock: u64,
        b: &Controller3,
        write: Option<(u32, u32)>,
        out: &ControllerOutputs,
    ) {
        let p = b.pins;
        for k in 0..3 {
            Self::track(
                &mut self.limit_pos_since[k],
                p.limit_pos >> k & 1 != 0,
                clock,
            );
            Self::track(
                &mut self.limit_neg_since[k],
                p.limit_neg >> k & 1 != 0,
                clock,
            );
            Self::track(&mut self.alarm_since[k], p.drive_alarm >> k & 1 != 0, clock);
        }
        Self::track(&mut self.estop_since, p.estop, clock);
        if let Some((address, data)) = write {
            if address == global::WATCHDOG_KICK {
                self.last_kick = Some(clock);
            }
            if address == global::STATUS
                && data >> motion_hdl::blocks::motion_controller::registers::irq::WATCHDOG & 1 != 0
            {
                self.lapsed = None;
            }
        }
        // The watchdog expires `timeout` ticks after a kick, one tick per
        // clock: taken 4 clocks later still, a conservative bound.
        if let Some(kick) = self.last_kick {
            if clock == kick + self.watchdog_timeout + 4 {
                self.lapsed = Some(clock);
                self.last_kick = None;
            }
        }
        // A stop is due strictly after its latency (the last step may rise
        // at it); a drive enable is low from its latency on.
        let due = |since: Option<u64>, latency: u64| since.is_some_and(|s| clock > s + latency);
        let from = |since: Option<u64>, latency: u64| since.is_some_and(|s| clock >= s + latency);
        let stopped_by = if due(self.estop_since, self.seen + latency::ABORT_ALL_AXES) {
            Some(format!("E-stop since {:?}", self.estop_since))
        } else if let Some(k) =
            (0..3).find(|&k| due(self.alarm_since[k], self.seen + latency::ABORT_ALL_AXES))
        {
            Some(format!("alarm {k} since {:?}", self.alarm_since[k]))
        } else if due(self.lapsed, latency::WATCHDOG_ALL_AXES) {
            Some(format!("watchdog lapse at {:?}", self.lapsed))
        } else {
            None
        };
        for k in 0..3 {
            let step = pin_step(self.modes[k], self.last[k], out.steps[k]);
            self.net[k] += step;
            if step != 0 {
                self.checks += 1;
                if let Some(cause) = &stopped_by {
                    let text = format!("clock {clock}: axis {k} stepped after {cause}");
                    self.violation(text);
                }
                let limit = if step > 0 {
                    self.limit_pos_since[k]
                } else {
                    self.limit_neg_since[k]
                };
                if due(limit, self.seen + latency::LIMIT_OWN_AXIS) {
                    self.violation(format!(
                        "clock {clock}: axis {k} stepped {step:+} toward its active limit"
                    ));
                }
            }
            // Pulse lengths: exact in step/dir and up/down, at least the
            // setting per quadrature state.
            let high = match self.modes[k] {
                UP_DOWN => out.steps[k].0 || out.steps[k].1,
                QUADRATURE => false,
                _ => out.steps[k].0,
            };
            if high {
                self.high_for[k] += 1;
            } else if self.high_for[k] > 0 {
                if self.high_for[k] != self.step_len[k].max(1) {
                    self.violation(format!(
                        "clock {clock}: axis {k} pulse {} clocks high",
                        self.high_for[k]
                    ));
                }
                self.high_for[k] = 0;
            }
            let disabled = from(self.estop_since, self.seen + latency::DRIVE_ENABLE)
                || from(self.alarm_since[k], self.seen + latency::DRIVE_ENABLE)
                || due(self.lapsed, latency::DRIVE_ENABLE);
            if disabled && out.drive_enable >> k & 1 != 0 {
                self.violation(format!("clock {clock}: drive_enable[{k}] high"));
            }
        }
        self.last = out.steps.clone();
    }
}

/// Statistics of a monitored run, to show that it exercised the contract.
#[derive(Debug, Default)]
struct MonitoredRun {
    steps: u64,
    running: u64,
    restarts: u64,
    causes: std::collections::BTreeSet<String>,
}

/// `cycles` clocks of random firmware and random switch, alarm, E-stop and
/// watchdog activity on the exported controller, in lockstep with the
/// model, watched by the [`SafetyMonitor`]. With `limits_disabled` the
/// firmware turns the limits off behind the monitor's back: a controller
/// that ignores its limits, which the monitor must catch.
fn monitored_run(
    seed: u64,
    cycles: u64,
    limits_disabled: bool,
) -> Result<MonitoredRun, Vec<String>> {
    let mut rng = StdRng::seed_from_u64(seed);
    let modes = [STEP_DIR, UP_DOWN, QUADRATURE];
    let step_len = [
        rng.gen_range(1..5),
        rng.gen_range(1..5),
        rng.gen_range(1..5),
    ];
    let filter = [0, 1, 3, 6][rng.gen_range(0..4)];
    let timeout = 4000;
    let mut b = Controller3::new();
    setup(&mut b, modes, step_len.map(|l| l as u32), filter, 120);
    if limits_disabled {
        for axis in 0..3 {
            b.write(
                "IO_CONFIG",
                axis,
                b.pack("IO_CONFIG", &[("ALARM_ENABLE", 1), ("DRIVE_ENABLE", 1)]),
            );
        }
    }
    b.write("WATCHDOG_TIMEOUT", 0, timeout);
    let mut monitor = SafetyMonitor::new(modes, step_len, filter, timeout as u64);
    let mut run = MonitoredRun::default();
    let mut stopped_for = 0u64;
    let mut kicking = true;
    let clear_all = b.pack(
        "IO_COMMAND",
        &[("CLEAR_LIMITS", 1), ("CLEAR_ALARM", 1), ("CLEAR_HOME", 1)],
    );
    let ack = b.pack(
        "STATUS",
        &[
            ("ESTOP", 1),
            ("WATCHDOG", 1),
            ("LIMIT", 1),
            ("ALARM", 1),
            ("UNDERRUN", 1),
        ],
    );
    let cause_address = b.address("STOP_CAUSE", 0);
    let mut firmware: std::collections::VecDeque<(u32, u32, bool)> = Default::default();
    for _ in 0..cycles {
        // Switches: rare trips of random length, with bounce.
        let toggle = |rng: &mut StdRng, word: &mut u32, active, inactive| {
            crate::bench::toggle_pins(rng, word, 3, active, inactive)
        };
        toggle(&mut rng, &mut b.pins.limit_pos, 400, 15_000);
        toggle(&mut rng, &mut b.pins.limit_neg, 400, 15_000);
        toggle(&mut rng, &mut b.pins.drive_alarm, 300, 60_000);
        if rng.gen_ratio(1, if b.pins.estop { 300 } else { 50_000 }) {
            b.pins.estop = !b.pins.estop;
        }
        // Firmware: keep the FIFOs fed while running, kick the watchdog
        // (with lapses), and after a stop acknowledge everything and start
        // again.
        if firmware.is_empty() {
            // Now and then the firmware goes silent for longer than the
            // watchdog allows.
            if rng.gen_ratio(1, 6000) {
                kicking = !rng.gen_ratio(1, 3);
            }
            if kicking && rng.gen_ratio(1, 400) {
                firmware.push_back((global::WATCHDOG_KICK, 0, true));
            }
            if b.last.running {
                stopped_for = 0;
                run.running += 1;
                if rng.gen_ratio(1, 60) {
                    for axis in 0..3u32 {
                        let n = rng.gen_range(-50..=50);
                        firmware.push_back((b.address("FIFO_WRITE", axis), n as u32, true));
                    }
                }
            } else {
                stopped_for += 1;
                if stopped_for == 200 {
                    firmware.push_back((cause_address, 0, false));
                }
                if stopped_for > 400 && rng.gen_ratio(1, 50) {
                    for axis in 0..3 {
                        firmware.push_back((b.address("IO_COMMAND", axis), clear_all, true));
                    }
                    firmware.push_back((global::STATUS, ack, true));
                    firmware.push_back((global::WATCHDOG_KICK, 0, true));
                    firmware.push_back((global::CONTROL, b.pack("CONTROL", &[("FLUSH", 1)]), true));
                    for _ in 0..4 {
                        for axis in 0..3u32 {
                            let n = rng.gen_range(-50..=50);
                            firmware.push_back((b.address("FIFO_WRITE", axis), n as u32, true));
                        }
                    }
                    firmware.push_back((global::CONTROL, 1, true));
                    run.restarts += 1;
                    stopped_for = 0;
                }
            }
        }
        let (address, data, write) = firmware.pop_front().unwrap_or((0, 0, false));
        let read = !write && address == cause_address;
        let clock = b.cycles;
        let out = b.clock(false, address, data, write, read).clone();
        if read {
            let cause = StopCause::from_code(b.field("STOP_CAUSE", "CAUSE", out.read_data) as u32);
            run.causes.insert(format!("{cause:?}"));
        }
        monitor.clock(clock, &b, write.then_some((address, data)), &out);
    }
    run.steps = monitor.checks;
    // Quiet the pins and let everything stop, then compare the commanded
    // positions with the pins' count.
    b.pins = Default::default();
    b.pins.estop = true;
    for _ in 0..2000 {
        let clock = b.cycles;
        let out = b.clock(false, 0, 0, false, false).clone();
        monitor.clock(clock, &b, None, &out);
    }
    for axis in 0..3u32 {
        let cmd = b.read("CMD_POSITION", axis) as i32 as i64;
        if cmd != monitor.net[axis as usize] {
            monitor.violation(format!(
                "axis {axis}: CMD_POSITION {cmd}, pins {}",
                monitor.net[axis as usize]
            ));
        }
    }
    if monitor.violations.is_empty() {
        Ok(run)
    } else {
        Err(monitor.violations)
    }
}

/// 10^6 clocks in all of random firmware and random switch activity under
/// the independent pin monitor (and the model, every clock).
#[test]
fn the_pin_monitor_holds_over_a_million_clocks_of_random_switches() {
    let runs: Vec<_> = [0x5afe_0001u64, 0x5afe_0002]
        .into_iter()
        .map(|seed| std::thread::spawn(move || (seed, monitored_run(seed, 500_000, false))))
        .collect();
    for run in runs {
        let (seed, result) = run.join().expect("lockstep failed");
        let run = result.unwrap_or_else(|v| panic!("seed {seed:#x}: {v:#?}"));
        println!("seed {seed:#x}: {run:?}");
        assert!(
            run.steps > 20_000 && run.running > 100_000 && run.restarts > 20,
            "seed {seed:#x} idle: {run:?}"
        );
        for cause in ["Limit", "DriveAlarm", "Estop", "Watchdog"] {
            assert!(
                run.causes.contains(cause),
                "seed {seed:#x}: no stop by {cause}: {run:?}"
            );
        }
    }
}

/// Mutation: with the limits disabled behind its back (a controller that
/// ignores its limit switches), the monitor reports steps toward an active
/// limit.
#[test]
fn the_pin_monitor_catches_a_controller_that_ignores_its_limits() {
    let violations = monitored_run(0x5afe_0001, 200_000, true).expect_err("the monitor must fail");
    assert!(
        violations
            .iter()
            .any(|v| v.contains("toward its active limit")),
        "{violations:#?}"
    );
}
