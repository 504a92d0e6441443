//! Tests of `motion_hdl::sim::ports` (`src/sim/ports.rs`).

use motion_hdl::sim::*;
use rust_hdl::prelude::Bits;

#[test]
fn a_port_wider_than_64_bits_takes_several_columns() {
    assert_eq!(<Bits<64> as PortValue>::WORDS, 1);
    assert_eq!(<Bits<65> as PortValue>::WORDS, 2);
    assert_eq!(<Bits<96> as PortValue>::WORDS, 2);
    let words = [0x0123_4567_89ab_cdef, 0xdead_beef];
    let x = Bits::<96>::from_words(&words);
    assert!(x.get_bit(0) && !x.get_bit(4) && x.get_bit(64) && x.get_bit(95) && !x.get_bit(93));
    let mut out = vec![];
    x.push_words(&mut out);
    assert_eq!(out, words);
    // Bits above the width are dropped.
    let mut out = vec![];
    Bits::<96>::from_words(&[1, u64::MAX]).push_words(&mut out);
    assert_eq!(out, [1, 0xffff_ffff]);
    assert_eq!(x.to_vector(), words[0]);
}
