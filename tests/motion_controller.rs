//! `motion_controller`: the RTL against the whole-controller model through
//! the register bus, firmware-style runs with the steps looped back into
//! the encoders, every fault, and cross-simulation.

#[path = "motion_controller/bench.rs"]
mod bench;

use bench::Bench;

type Controller3 = Bench<3, 4, 5>;

#[test]
fn smoke_dda_periods_reach_their_positions() {
    let mut b = Controller3::new().with_loopback();
    b.write("TICK_DIVISOR", 0, 1);
    b.write("PERIOD_TICKS", 0, 100);
    let counts = [[10i32, -5, 30], [0, 7, -20], [50, 50, 1]];
    for period in counts {
        for (axis, n) in period.iter().enumerate() {
            b.write("FIFO_WRITE", axis as u32, *n as u32);
        }
    }
    b.write("CONTROL", 0, 1);
    b.idle(500);
    for axis in 0..3u32 {
        let expected: i32 = counts.iter().map(|p| p[axis as usize]).sum();
        let cmd = b.read("CMD_POSITION", axis) as i32;
        let act = b.read("ACT_POSITION", axis) as i32;
        assert_eq!(cmd, expected, "axis {axis} commanded");
        assert_eq!(act, expected, "axis {axis} actual");
    }
    let status = b.read("STATUS", 0);
    assert_eq!(b.field("STATUS", "UNDERRUN", status), 1);
}
