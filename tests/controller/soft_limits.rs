//! The soft limits at the pins: on every axis and in both directions, a
//! path that would leave its window starts the hold early enough to stop
//! inside it, `STATUS.SOFT_LIMIT` and `SOFT_LIMIT.AXIS` / `NEGATIVE` name
//! the axis, a release is refused while the verdict stands, and a stop
//! clears it. A path that stays inside, or crosses a disabled window,
//! runs to its end untouched. The RTL (the exported Verilog, compiled)
//! and the model run in lockstep in every clock.

use crate::motion_controller::{configure, Controller3};
use motion_hdl::blocks::motion_controller::registers::irq;
use motion_hdl::blocks::motion_controller::soft_limits::{reach_ticks, MARGIN};

const PERIOD: u32 = 40;
const WINDOW: i64 = 100;

/// The window's reach at `steps` per period: what the check keeps free.
fn reach_steps(rate: u32, steps: i64) -> i64 {
    let ticks = reach_ticks(rate as u16, 3) as i64;
    steps * ticks / PERIOD as i64 + MARGIN as i64
}

struct Outcome {
    tripped: bool,
    axis: u64,
    negative: bool,
    positions: [i64; 3],
    held: bool,
}

/// A fresh controller with every axis's window at +-`WINDOW`, `enable` its
/// enables, `HOLD_CONTROL.RATE` = `rate`; runs `periods` periods of
/// `entry` and returns where it stood.
fn run(b: &mut Controller3, rate: u32, enable: u64, entry: [i32; 3], periods: usize) -> Outcome {
    b.reset();
    configure(b, PERIOD, [false; 3]);
    for axis in 0..3 {
        b.write("SOFT_MIN", axis, (-WINDOW) as u32);
        b.write("SOFT_MAX", axis, WINDOW as u32);
    }
    let enable_word = b.pack("SOFT_LIMIT", &[("ENABLE", enable)]);
    b.write("SOFT_LIMIT", 0, enable_word);
    let hold = b.pack("HOLD_CONTROL", &[("RATE", rate as u64)]);
    b.write("HOLD_CONTROL", 0, hold);
    for _ in 0..periods {
        for (axis, n) in entry.iter().enumerate() {
            b.write("FIFO_WRITE", axis as u32, *n as u32);
        }
    }
    // The reach of the new RATE is measured before the start, or the first
    // verdicts judge with the longest reach.
    for _ in 0..70_000 {
        let soft = b.read("SOFT_LIMIT", 0);
        if b.field("SOFT_LIMIT", "MEASURED", soft) == 1 {
            break;
        }
    }
    b.write("CONTROL", 0, 1);
    for _ in 0..periods as u64 * PERIOD as u64 * 40 + 20_000 {
        b.idle(1);
        let state = b.read("STATE", 0);
        if b.field("STATE", "HELD", state) == 1 || b.field("STATE", "RUNNING", state) == 0 {
            break;
        }
    }
    b.idle(100);
    let status = b.read("STATUS", 0);
    let soft = b.read("SOFT_LIMIT", 0);
    let state = b.read("STATE", 0);
    let positions = [0, 1, 2].map(|axis| b.read("CMD_POSITION", axis) as i32 as i64);
    Outcome {
        tripped: status >> irq::SOFT_LIMIT & 1 == 1,
        axis: b.field("SOFT_LIMIT", "AXIS", soft),
        negative: b.field("SOFT_LIMIT", "NEGATIVE", soft) == 1,
        positions,
        held: b.field("STATE", "HELD", state) == 1,
    }
}

#[test]
fn every_axis_and_direction_stops_inside_its_window() {
    let mut b = Controller3::new();
    for rate in [0u32, 512, 2048] {
        for axis in 0..3 {
            for direction in [1i32, -1] {
                let steps = 10;
                let mut entry = [0; 3];
                entry[axis] = direction * steps;
                // The others move too, inside their windows.
                entry[(axis + 1) % 3] = 2;
                let o = run(&mut b, rate, 0b111, entry, 15);
                let what = format!("rate {rate}, axis {axis}, direction {direction}");
                assert!(
                    o.tripped && o.held,
                    "{what}: tripped {} held {}",
                    o.tripped,
                    o.held
                );
                assert_eq!((o.axis, o.negative), (axis as u64, direction < 0), "{what}");
                let p = o.positions[axis] * direction as i64;
                assert!(p <= WINDOW, "{what}: stopped at {p}, past {WINDOW}");
                // Not absurdly early: the trip comes when the reach meets
                // the bound, within a turn's steps.
                let reach = reach_steps(rate, steps as i64);
                assert!(
                    p >= WINDOW - 2 * reach - steps as i64,
                    "{what}: stopped at {p}, reach {reach}"
                );
                // A release is refused while the verdict stands.
                let release = b.pack("HOLD_CONTROL", &[("RELEASE", 1), ("RATE", rate as u64)]);
                b.write("HOLD_CONTROL", 0, release);
                b.idle(2_000);
                let held = b.read("HOLD_CONTROL", 0);
                assert_eq!(b.field("HOLD_CONTROL", "REQUESTED", held), 1, "{what}");
                assert_eq!(
                    b.read("CMD_POSITION", axis as u32) as i32 as i64,
                    o.positions[axis]
                );
                // A stop clears the verdict: the release then holds.
                b.write("CONTROL", 0, 0);
                b.idle(2);
                let soft = b.read("SOFT_LIMIT", 0);
                assert_eq!(b.field("SOFT_LIMIT", "BEYOND", soft), 0, "{what}");
                b.write("HOLD_CONTROL", 0, release);
                b.idle(2);
                let held = b.read("HOLD_CONTROL", 0);
                assert_eq!(b.field("HOLD_CONTROL", "REQUESTED", held), 0, "{what}");
            }
        }
    }
}

#[test]
fn a_path_inside_its_windows_or_past_a_disabled_one_runs_to_its_end() {
    let mut b = Controller3::new();
    // Inside: 75 steps of a window of 100 at a reach of about 10.
    let o = run(&mut b, 2048, 0b111, [5, -5, 3], 15);
    assert!(!o.tripped && !o.held, "inside: tripped {}", o.tripped);
    assert_eq!(o.positions, [75, -75, 45]);
    // Past a disabled window: axis 1's is off.
    let o = run(&mut b, 2048, 0b101, [5, -10, 3], 15);
    assert!(!o.tripped && !o.held, "disabled: tripped {}", o.tripped);
    assert_eq!(o.positions, [75, -150, 45]);
}
