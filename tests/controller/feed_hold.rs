//! The feed hold at the pins: a hold and release at any point of a path
//! ends where the unheld run ends, never shortens a step interval, and
//! has a defined outcome with an underrun, an abort and a stop. The RTL
//! (the exported Verilog, compiled) and the model run in lockstep in every
//! clock of these tests.

use crate::machine_io::{setup, Controller3, PinLog, STEP_DIR};
use motion_hdl::blocks::motion_controller::hold_ramp::UNITY;
use motion_hdl::blocks::motion_controller::latency;
use motion_hdl::blocks::motion_controller::registers::StopCause;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

const PERIOD: u32 = 24;
const FILTER: u64 = 2;

/// A random path of `periods` periods on three axes: lines (constant
/// counts) and arcs (the rounded increments of a circle in two axes,
/// fraction carried), at most 5 steps per period of 24 ticks so that the
/// output stages never queue.
fn random_path(rng: &mut StdRng, periods: usize) -> Vec<[i32; 3]> {
    let mut path = Vec::with_capacity(periods);
    while path.len() < periods {
        let length = rng.gen_range(2..6).min(periods - path.len());
        if rng.gen_ratio(1, 2) {
            let line = [0; 3].map(|_| rng.gen_range(-5..=5));
            path.extend(std::iter::repeat_n(line, length));
        } else {
            let radius = rng.gen_range(6.0..20.0);
            let step = rng.gen_range(0.15..0.25) * if rng.gen() { 1.0 } else { -1.0 };
            let start: f64 = rng.gen_range(0.0..std::f64::consts::TAU);
            let z = rng.gen_range(-2..=2);
            let at = |i: usize| {
                let a = start + step * i as f64;
                (radius * a.cos(), radius * a.sin())
            };
            let mut done = (at(0).0.round() as i32, at(0).1.round() as i32);
            for i in 1..=length {
                let (x, y) = at(i);
                let now = (x.round() as i32, y.round() as i32);
                path.push([now.0 - done.0, now.1 - done.1, z]);
                done = now;
            }
        }
    }
    path
}

/// The hold of one run: `HOLD` at clock `at` after the start, `RELEASE`
/// `lasts` clocks later (None: never), with `HOLD_CONTROL.RATE` = `rate`.
#[derive(Clone, Copy, Debug)]
struct Hold {
    at: u64,
    lasts: Option<u64>,
    rate: u32,
}

/// What a run left: every axis's CMD_POSITION and the clocks of its steps
/// at the pins.
struct Run {
    positions: [i64; 3],
    steps: [Vec<u64>; 3],
    held: bool,
}

fn hold_word(b: &Controller3, hold: bool, release: bool, rate: u32) -> u32 {
    b.pack(
        "HOLD_CONTROL",
        &[
            ("HOLD", hold as u64),
            ("RELEASE", release as u64),
            ("RATE", rate as u64),
        ],
    )
}

/// Queues `path`, one entry per period on every axis, then (with
/// `closing`) a last period of no steps.
fn queue(b: &mut Controller3, path: &[[i32; 3]], closing: bool) {
    let close: &[[i32; 3]] = if closing { &[[0; 3]] } else { &[] };
    for entry in path.iter().chain(close) {
        for (axis, n) in entry.iter().enumerate() {
            b.write("FIFO_WRITE", axis as u32, *n as u32);
        }
    }
}

/// Resets `b`, queues `path`, starts, applies `hold`, and runs until the
/// path has ended (an underrun at its end) and the last step left.
fn run_path(b: &mut Controller3, path: &[[i32; 3]], hold: Option<Hold>) -> Run {
    // A last period of no steps, as the driver closes a path (the path
    // without one: `a_path_ending_by_an_underrun_keeps_its_last_step`).
    run_path_closed(b, path, hold, true)
}

/// [`run_path`], with or without the closing period of no steps.
fn run_path_closed(
    b: &mut Controller3,
    path: &[[i32; 3]],
    hold: Option<Hold>,
    closing: bool,
) -> Run {
    b.reset();
    setup(b, [STEP_DIR; 3], [2, 2, 2], FILTER, PERIOD);
    queue(b, path, closing);
    let mut log = PinLog::new(b, [STEP_DIR; 3]);
    b.write("CONTROL", 0, 1);
    let start = b.cycles;
    let mut held = false;
    let limit = 40 * PERIOD as u64 * path.len() as u64 + 20_000;
    loop {
        let t = b.cycles - start;
        let out = match hold {
            Some(h) if t == h.at => {
                let word = hold_word(b, true, false, h.rate);
                let address = b.address("HOLD_CONTROL", 0);
                b.clock(false, address, word, true, false).clone()
            }
            Some(Hold {
                at,
                lasts: Some(lasts),
                rate,
            }) if t == at + lasts => {
                let word = hold_word(b, false, true, rate);
                let address = b.address("HOLD_CONTROL", 0);
                b.clock(false, address, word, true, false).clone()
            }
            _ => b.clock(false, 0, 0, false, false).clone(),
        };
        log.see(b.cycles - 1, &out);
        held |= b.model().feed_hold().held();
        if !out.active && t > 4 {
            break;
        }
        assert!(t < limit, "the run did not end: {hold:?}");
    }
    // Once `active` has fallen, no step of the run is left to come.
    for _ in 0..64 {
        let out = b.clock(false, 0, 0, false, false).clone();
        assert!(!out.active, "active rose again after the run ended");
    }
    let mut steps: [Vec<u64>; 3] = Default::default();
    for &(clock, axis, _) in &log.steps {
        steps[axis].push(clock - start);
    }
    let positions = [0, 1, 2].map(|k| b.read("CMD_POSITION", k) as i32 as i64);
    Run {
        positions,
        steps,
        held,
    }
}

/// 1000 holds and releases at random clocks of 100 random paths of lines
/// and arcs, at random ramp rates (and the immediate stop, RATE 0), some
/// long enough to stop, some released while still slowing: every axis
/// ends where the unheld run of the same path ends, with the same number
/// of steps, and no interval between two steps of an axis is shorter than
/// the same interval without the hold (no axis steps faster than it did
/// unheld). The RTL and the model agree in every clock.
#[test]
fn a_hold_and_release_at_1000_random_points_end_where_the_unheld_run_ends() {
    let mut rng = StdRng::seed_from_u64(0x4f1d);
    let mut b = Controller3::new();
    let mut stopped = 0;
    for _ in 0..100 {
        let path = random_path(&mut rng, 10);
        let free = run_path(&mut b, &path, None);
        let expected: [i64; 3] = [0, 1, 2].map(|k| path.iter().map(|e| e[k] as i64).sum());
        assert_eq!(free.positions, expected, "the unheld run of {path:?}");
        let span = PERIOD as u64 * path.len() as u64;
        for _ in 0..10 {
            let rate = match rng.gen_range(0..10) {
                0 => 0,
                1 => rng.gen_range(1..65536),
                _ => rng.gen_range(300..8000),
            };
            let hold = Hold {
                at: rng.gen_range(0..span),
                lasts: Some(rng.gen_range(1..150)),
                rate,
            };
            let run = run_path(&mut b, &path, Some(hold));
            stopped += run.held as u32;
            let what = format!("{hold:?} on {path:?}");
            assert_eq!(run.positions, free.positions, "{what}: end positions");
            for axis in 0..3 {
                let (held, unheld) = (&run.steps[axis], &free.steps[axis]);
                assert_eq!(held.len(), unheld.len(), "{what}: axis {axis} steps");
                for (i, (h, u)) in held.windows(2).zip(unheld.windows(2)).enumerate() {
                    assert!(
                        h[1] - h[0] >= u[1] - u[0],
                        "{what}: axis {axis} step {i} came {} clocks after the last, {} unheld",
                        h[1] - h[0],
                        u[1] - u[0]
                    );
                }
            }
        }
    }
    // Both kinds happened: holds that reached a stop, and holds released
    // while still slowing.
    assert!(
        stopped > 50 && stopped < 950,
        "{stopped} of 1000 holds stopped"
    );
}

/// The `feed_hold` pin: its filtered level is set `latency::switch`
/// clocks after it changes, the request follows in the next clock, and the
/// ramp lowers the factor at the first base tick `HOLD_REQUEST_TO_RAMP`
/// clocks after that (`TICK_DIVISOR` 1: that clock); the request is sticky after the
/// pin is released, `RELEASE` is refused while the pin is active, and a
/// release brings the factor back to 1, raising `STATE.HELD` and
/// `STATUS.HELD` on the way down.
#[test]
fn the_feed_hold_pin_holds_after_its_latency_and_release_waits_for_it() {
    let mut b = Controller3::new();
    setup(&mut b, [STEP_DIR; 3], [2, 2, 2], FILTER, PERIOD);
    b.write("IRQ_ENABLE", 0, b.pack("IRQ_ENABLE", &[("HELD", 1)]));
    let rate = 4096;
    b.write("HOLD_CONTROL", 0, hold_word(&b, false, false, rate));
    b.pins.feed_hold = true;
    let c = b.cycles;
    let seen = latency::switch(FILTER, 0);
    let mut lowered_at = None;
    let mut irq_at = None;
    for _ in 0..60 {
        let out = b.clock(false, 0, 0, false, false).clone();
        let factor = b.model().feed_hold().ramp().factor();
        if factor < UNITY && lowered_at.is_none() {
            lowered_at = Some(b.cycles - 1);
        }
        if out.irq && irq_at.is_none() {
            irq_at = Some(b.cycles - 1);
        }
    }
    // The filtered level is set at c + seen; the request follows it in
    // the next clock, and the factor falls at the tick of the clock the
    // ramp sees it.
    let decided = c + seen + 1;
    let lowered = decided + latency::HOLD_REQUEST_TO_RAMP;
    assert_eq!(lowered_at, Some(lowered), "the first reduced factor");
    // 16 ticks from 1 to 0 at 4096 per tick, the last at lowered + 15;
    // irq two clocks after the clock that brings the factor to 0.
    assert_eq!(irq_at, Some(lowered + 15 + 2), "the HELD interrupt");
    let state = b.read("STATE", 0);
    assert_eq!(b.field("STATE", "HELD", state), 1);
    assert_eq!(b.field("STATE", "HOLDING", state), 1);
    // RELEASE while the pin is active: refused.
    b.write("HOLD_CONTROL", 0, hold_word(&b, false, true, rate));
    let control = b.read("HOLD_CONTROL", 0);
    assert_eq!(b.field("HOLD_CONTROL", "REQUESTED", control), 1);
    assert_eq!(b.field("HOLD_CONTROL", "INPUT", control), 1);
    assert_eq!(b.field("HOLD_CONTROL", "RATE", control), rate as u64);
    // The pin released: still requested (sticky) until RELEASE.
    b.pins.feed_hold = false;
    b.idle(seen + 5);
    let control = b.read("HOLD_CONTROL", 0);
    assert_eq!(b.field("HOLD_CONTROL", "REQUESTED", control), 1);
    assert_eq!(b.field("HOLD_CONTROL", "INPUT", control), 0);
    assert!(b.model().feed_hold().held());
    b.write("HOLD_CONTROL", 0, hold_word(&b, false, true, rate));
    b.idle(16);
    let state = b.read("STATE", 0);
    assert_eq!(b.field("STATE", "HOLDING", state), 0, "back to full speed");
    assert_eq!(b.model().feed_hold().ramp().factor(), UNITY);
}

/// The defined outcomes of a hold meeting the other ways motion ends:
/// - an underrun while slowing: the path ends at its last boundary, as
///   unheld, with STOP_CAUSE underrun and every step made;
/// - an E-stop while held: the abort stops and flushes as without the
///   hold (STOP_CAUSE E-stop); the hold stays requested;
/// - RUN = 1 while held: it starts, but no period begins and no step
///   leaves until the release; then the path runs to its end.
#[test]
fn a_hold_meets_an_underrun_an_abort_and_a_start() {
    let path = [[3, -2, 1]; 4];
    let mut b = Controller3::new();
    let free = run_path(&mut b, &path, None);
    // Underrun while slowing: a slow ramp starting in the last period.
    let slow = Hold {
        at: 3 * PERIOD as u64 + 5,
        lasts: None,
        rate: 300,
    };
    let run = run_path(&mut b, &path, Some(slow));
    assert_eq!(run.positions, free.positions);
    let cause = b.read("STOP_CAUSE", 0);
    assert_eq!(
        StopCause::from_code(b.field("STOP_CAUSE", "CAUSE", cause) as u32),
        StopCause::Underrun
    );

    // An E-stop while held.
    b.reset();
    setup(&mut b, [STEP_DIR; 3], [2, 2, 2], FILTER, PERIOD);
    queue(&mut b, &path, false);
    b.write("CONTROL", 0, 1);
    b.idle(30);
    b.write("HOLD_CONTROL", 0, hold_word(&b, true, false, 0));
    b.idle(5);
    assert!(b.model().feed_hold().held());
    b.pins.estop = true;
    b.idle(latency::switch(FILTER, 0) + latency::ABORT_ALL_AXES + 5);
    let state = b.read("STATE", 0);
    assert_eq!(b.field("STATE", "RUNNING", state), 0);
    assert_eq!(b.field("STATE", "ABORTED", state), 1);
    assert_eq!(b.field("STATE", "HELD", state), 1);
    let cause = b.read("STOP_CAUSE", 0);
    assert_eq!(
        StopCause::from_code(b.field("STOP_CAUSE", "CAUSE", cause) as u32),
        StopCause::Estop
    );
    let control = b.read("HOLD_CONTROL", 0);
    assert_eq!(b.field("HOLD_CONTROL", "REQUESTED", control), 1);

    // RUN while held: nothing moves until the release.
    b.pins.estop = false;
    b.reset();
    setup(&mut b, [STEP_DIR; 3], [2, 2, 2], FILTER, PERIOD);
    b.write("HOLD_CONTROL", 0, hold_word(&b, true, false, 0));
    queue(&mut b, &path, true);
    b.idle(3);
    b.write("CONTROL", 0, 1);
    let mut log = PinLog::new(&b, [STEP_DIR; 3]);
    for _ in 0..500 {
        log.clock(&mut b);
    }
    assert!(log.steps.is_empty(), "a step while held");
    assert!(b.model().running());
    assert_eq!(b.model().axes()[0].fifo_level(), path.len() as u64 + 1);
    b.write("HOLD_CONTROL", 0, hold_word(&b, false, true, 0));
    while b.clock(false, 0, 0, false, false).active {}
    let positions = [0, 1, 2].map(|k| b.read("CMD_POSITION", k) as i32 as i64);
    assert_eq!(positions, free.positions);
}

/// A path whose last period has steps, ended by the underrun at the
/// boundary after it, keeps the step its DDA makes on that boundary tick
/// (PERIOD 24: axis 1 ends at 8). Until VERSION 0.6.1 `active` fell with
/// RUN for the 4 clocks that step took to reach its output stage, and then
/// rose again: a host waiting for `active` to fall read the position a
/// step short (axis 1 at 9). `run_path_closed` checks that `active` stays
/// low once it has fallen.
#[test]
fn a_path_ending_by_an_underrun_keeps_its_last_step() {
    let mut path = vec![[1, 3, -5]; 5];
    path.extend([
        [-2, -1, 0],
        [-2, -1, 0],
        [-1, -1, 0],
        [-1, -2, 0],
        [0, -2, 0],
    ]);
    let expected: [i64; 3] = [0, 1, 2].map(|k| path.iter().map(|e| e[k] as i64).sum());
    let mut b = Controller3::new();
    let run = run_path_closed(&mut b, &path, None, false);
    assert_eq!(run.positions, expected);
}
