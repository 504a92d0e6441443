//! The probe input at the pins: the trip latches every axis's positions of
//! one documented clock, once per arming, and interrupts.

use crate::machine_io::{queue_and_run, setup, Controller3, PinLog, QUADRATURE, STEP_DIR, UP_DOWN};
use motion_hdl::blocks::motion_controller::latency;

const MODES: [u8; 3] = [STEP_DIR, UP_DOWN, QUADRATURE];

/// Arms the probe on the rising (`falling` false) or falling edge.
fn arm(b: &mut Controller3, falling: bool) {
    let word = b.pack("PROBE_CONTROL", &[("ARM", 1), ("EDGE", falling as u64)]);
    b.write("PROBE_CONTROL", 0, word);
}

/// STATUS.PROBE.
fn status_probe(b: &mut Controller3) -> u64 {
    let status = b.read("STATUS", 0);
    b.field("STATUS", "PROBE", status)
}

/// The steps of `axis` whose first pin edge came before clock `before`.
fn steps_before(log: &PinLog, axis: usize, before: u64) -> i64 {
    log.steps
        .iter()
        .filter(|s| s.1 == axis && s.0 < before)
        .map(|s| s.2)
        .sum()
}

/// A probe edge at every phase of the axes' step pulses, on either edge,
/// with all three axes moving (step/dir, up/down and quadrature): the trip
/// is acted on `latency::switch` clocks after the pin, and every axis's
/// PROBE_CMD_POSITION counts exactly the steps whose first pin edge came
/// before that clock, its PROBE_ACT_POSITION is the encoder count of that
/// clock, STATUS.PROBE interrupts two clocks later, and the move goes on.
#[test]
fn the_probe_latches_every_axis_at_the_clock_it_is_acted_on() {
    let filter = 3;
    let seen = latency::switch(filter, 0);
    for falling in [false, true] {
        for phase in 0..16u64 {
            let mut b = Controller3::new().with_loopback();
            b.pins.probe = falling;
            setup(&mut b, MODES, [4, 3, 2], filter, 160);
            b.write("IRQ_ENABLE", 0, b.pack("IRQ_ENABLE", &[("PROBE", 1)]));
            arm(&mut b, falling);
            queue_and_run(&mut b, [20, -15, 12], 4);
            let mut log = PinLog::new(&b, MODES);
            for _ in 0..200 + phase {
                log.clock(&mut b);
            }
            let c = b.cycles;
            b.pins.probe = !falling;
            let mut act_at_trip = None;
            let mut irq_at = None;
            for _ in 0..40 {
                let out = log.clock(&mut b);
                if b.cycles - 1 == c + seen {
                    let axes = b.model().axes();
                    act_at_trip = Some([0, 1, 2].map(|k| axes[k].actual_position()));
                }
                if out.irq && irq_at.is_none() {
                    irq_at = Some(b.cycles - 1);
                }
            }
            let what = format!("falling {falling}, phase {phase}");
            assert_eq!(irq_at, Some(c + seen + 2), "{what}: the PROBE interrupt");
            for axis in 0..3 {
                assert_eq!(
                    b.read("PROBE_CMD_POSITION", axis as u32) as i32 as i64,
                    steps_before(&log, axis, c + seen),
                    "{what}: axis {axis} commanded"
                );
                assert_eq!(
                    b.read("PROBE_ACT_POSITION", axis as u32) as i32,
                    act_at_trip.unwrap()[axis],
                    "{what}: axis {axis} actual"
                );
            }
            assert!(
                steps_before(&log, 0, u64::MAX) != steps_before(&log, 0, c + seen),
                "{what}: steps after the trip (the latch is not the end position)"
            );
            let control = b.read("PROBE_CONTROL", 0);
            assert_eq!(b.field("PROBE_CONTROL", "TRIPPED", control), 1, "{what}");
            assert_eq!(b.field("PROBE_CONTROL", "ARM", control), 0, "{what}");
            assert_eq!(
                b.field("PROBE_CONTROL", "LEVEL", control),
                !falling as u64,
                "{what}"
            );
            assert!(b.last.running, "{what}: the trip does not stop the move");
        }
    }
}

/// Edges after the trip change nothing until the probe is armed again;
/// arming clears TRIPPED, and the next edge latches anew. A disarmed probe
/// latches nothing.
#[test]
fn only_the_first_edge_after_arming_latches() {
    let mut b = Controller3::new().with_loopback();
    setup(&mut b, MODES, [2, 2, 2], 2, 100);
    queue_and_run(&mut b, [10, -10, 10], 15);
    let touch = |b: &mut Controller3, level: bool| {
        b.pins.probe = level;
        b.idle(30);
    };
    let latches = |b: &mut Controller3| {
        [0u32, 1, 2].map(|k| {
            (
                b.read("PROBE_CMD_POSITION", k),
                b.read("PROBE_ACT_POSITION", k),
            )
        })
    };
    b.idle(100);
    touch(&mut b, true);
    touch(&mut b, false);
    assert_eq!(latches(&mut b), [(0, 0); 3], "not armed: nothing latched");
    assert_eq!(status_probe(&mut b), 0);

    arm(&mut b, false);
    b.idle(100);
    touch(&mut b, true);
    let first = latches(&mut b);
    assert_ne!(first[0].0, 0, "the armed probe latched");
    assert_eq!(status_probe(&mut b), 1);
    b.write("STATUS", 0, b.pack("STATUS", &[("PROBE", 1)]));
    touch(&mut b, false);
    b.idle(100);
    touch(&mut b, true);
    assert_eq!(latches(&mut b), first, "later edges are ignored");
    assert_eq!(status_probe(&mut b), 0);
    let control = b.read("PROBE_CONTROL", 0);
    assert_eq!(b.field("PROBE_CONTROL", "TRIPPED", control), 1);

    touch(&mut b, false);
    arm(&mut b, false);
    let control = b.read("PROBE_CONTROL", 0);
    assert_eq!(
        b.field("PROBE_CONTROL", "TRIPPED", control),
        0,
        "arming clears it"
    );
    assert_eq!(b.field("PROBE_CONTROL", "ARM", control), 1);
    b.idle(100);
    touch(&mut b, true);
    let second = latches(&mut b);
    assert_ne!(second, first, "the re-armed probe latched again");

    touch(&mut b, false);
    arm(&mut b, false);
    b.write("PROBE_CONTROL", 0, 0);
    b.idle(50);
    touch(&mut b, true);
    assert_eq!(latches(&mut b), second, "disarmed: nothing latched");
}

/// `motion_controller` without the probe latch (`PROBE` = false).
type NoProbe3 = crate::bench::Bench<3, 4, 5, true, false, false>;

/// A build without the probe: `CONFIG.PROBE` reads 0; the probe pin, armed
/// by address as the full build would be, latches nothing, raises no
/// `STATUS.PROBE`, and `PROBE_CONTROL` and `PROBE_*_POSITION` read 0. Then
/// a chaos lockstep run with the probe toggling and armed at random: the
/// RTL equals the model of that build every clock, and STATUS.PROBE is
/// never seen.
#[test]
fn a_build_without_the_probe_ignores_it() {
    use motion_hdl::blocks::motion_controller::registers::{
        axis, fields, global, irq, AXIS_BASE, AXIS_STRIDE,
    };
    let mut b = NoProbe3::new().with_loopback();
    let config = b.read("CONFIG", 0);
    assert_eq!(b.field("CONFIG", "PROBE", config), 0);
    b.write("TICK_DIVISOR", 0, 1);
    b.write("PERIOD_TICKS", 0, 100);
    for axis in 0..3 {
        b.write("STEP_LEN", axis, 2);
    }
    for _ in 0..10 {
        for axis in 0..3 {
            b.write("FIFO_WRITE", axis, 10);
        }
    }
    b.write("CONTROL", 0, 1);
    let read_at = |b: &mut NoProbe3, address: u32| {
        b.clock(false, address, 0, false, true);
        b.clock(false, 0, 0, false, false).read_data
    };
    for falling in [false, true] {
        b.clock(
            false,
            global::PROBE_CONTROL,
            1 << fields::PROBE_ARM | (falling as u32) << fields::PROBE_EDGE,
            true,
            false,
        );
        for level in [!falling, falling, !falling] {
            b.pins.probe = level;
            b.idle(60);
            assert_eq!(read_at(&mut b, global::PROBE_CONTROL), 0);
        }
    }
    assert!(b.pin_steps(0) > 0, "the axes moved while the probe toggled");
    for k in 0..3 {
        for register in [axis::PROBE_CMD_POSITION, axis::PROBE_ACT_POSITION] {
            assert_eq!(read_at(&mut b, AXIS_BASE + k * AXIS_STRIDE + register), 0);
        }
    }
    let status = b.read("STATUS", 0);
    assert_eq!(status >> irq::PROBE & 1, 0, "STATUS {status:#x}");

    let run = crate::motion_controller::chaos_run_on(NoProbe3::new(), 0x0b0e_0001, 200_000);
    assert_eq!(run.status_seen >> irq::PROBE & 1, 0);
    assert_ne!(
        run.status_seen >> irq::PERIOD_DONE & 1,
        0,
        "the run ran periods"
    );
}
