//! The position counters' range (`POSITION_BITS`, `CONFIG.POSITION_BITS`):
//! they count modulo 2^POSITION_BITS, no count is lost at the wrap, and
//! every register word that holds a position (the live one, its snapshot
//! and its index latch) carries the sign up to bit 31.

use crate::bench::Bench;
use motion_hdl::blocks::motion_controller::model::position_word;
use motion_hdl::blocks::motion_controller::POSITION_BITS;

type Controller3 = Bench<3, 4, 5, true, false, true>;

/// Quadrature states in forward order: (a, b) = 00 -> 10 -> 11 -> 01.
const FORWARD: [(bool, bool); 4] = [(false, false), (true, false), (true, true), (false, true)];

/// The encoder pins of axis 0 stepping forward and axis 1 backward, `n`
/// counts after the start.
fn encoder_pins(n: u64) -> Vec<(bool, bool, bool)> {
    let (a0, b0) = FORWARD[(n % 4) as usize];
    let (a1, b1) = FORWARD[((4 - n % 4) % 4) as usize];
    vec![(a0, b0, false), (a1, b1, false), (false, false, false)]
}

/// Drives axis 0's encoder forward and axis 1's backward at one count a
/// clock (the decoder's highest rate with its filter off) through
/// 2^(POSITION_BITS - 1) and on past the wrap, in lockstep with the model.
/// At each checkpoint the encoders stop, and ACT_POSITION, ACT_SNAPSHOT and
/// INDEX_POSITION are read and checked against the counts driven at the
/// pins (the sign-extended POSITION_BITS value: an independent monitor
/// beside the model). Ignored: about 8.4 million lockstep clocks.
#[test]
#[ignore]
fn encoder_positions_wrap_at_position_bits_and_read_sign_extended() {
    let mut b = Controller3::new();
    b.reset();
    b.idle(8);
    let config = b.read("CONFIG", 0);
    assert_eq!(
        b.field("CONFIG", "POSITION_BITS", config),
        POSITION_BITS as u64
    );
    let latch = b.pack("AXIS_CONFIG", &[("INDEX_LATCH", 1)]);
    b.write("AXIS_CONFIG", 0, latch);
    b.write("AXIS_CONFIG", 1, latch);

    let half = 1u64 << (POSITION_BITS - 1);
    let checkpoints = [
        1000,
        half - 2,
        half - 1,
        half,
        half + 1,
        half + 3000,
        2 * half - 1,
        2 * half,
        2 * half + 2,
    ];
    let mut driven = 0u64;
    for &target in &checkpoints {
        while driven < target {
            driven += 1;
            b.encoders = encoder_pins(driven);
            b.idle(1);
        }
        // Let the last change through the decoder's pipeline.
        b.idle(8);
        b.write("SNAPSHOT", 0, 1);
        // An index pulse on both axes latches ACT_POSITION.
        for axis in 0..2 {
            b.encoders[axis].2 = true;
        }
        b.idle(8);
        for axis in 0..2 {
            b.encoders[axis].2 = false;
        }
        b.idle(8);
        for (axis, count) in [(0u32, driven as i64), (1, -(driven as i64))] {
            let expected = position_word(count as u64);
            for register in ["ACT_POSITION", "ACT_SNAPSHOT", "INDEX_POSITION"] {
                let word = b.read(register, axis);
                assert_eq!(
                    word, expected,
                    "{register}[{axis}] after {driven} counts: {word:#010x}, expected {expected:#010x}"
                );
            }
        }
    }
    // One count past +2^(bits-1) - 1 reads as the most negative value.
    assert_eq!(position_word(half), (-(half as i64)) as u32);
}
