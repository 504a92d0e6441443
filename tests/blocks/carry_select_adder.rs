//! Tests of `motion_hdl::blocks::carry_select_adder` (`src/blocks/carry_select_adder/mod.rs`).

use motion_hdl::blocks::carry_select_adder::CarrySelectAdder;
use rust_hdl::prelude::*;

/// Every operand pair of the 6-bit and 5-bit adders (odd split too).
#[test]
fn matches_arithmetic_for_every_operand_pair() {
    fn check<const W: usize>() {
        let mut adder = CarrySelectAdder::<W>::default();
        adder.connect_all();
        for a in 0..1u64 << W {
            for b in 0..1u64 << W {
                adder.a.next = a.into();
                adder.b.next = b.into();
                assert!(simulate(&mut adder, 20), "did not settle");
                let total = a + b + 1;
                assert_eq!(
                    adder.sum.val().to_u64(),
                    total & ((1 << W) - 1),
                    "W={W} {a}+{b}+1"
                );
                assert_eq!(
                    adder.carry_out.val(),
                    total >> W != 0,
                    "W={W} carry of {a}+{b}+1"
                );
            }
        }
    }
    check::<6>();
    check::<5>();
    check::<2>();
}
