//! The entry converter (the 20-bit FIFO entry the axes store): its RTL
//! against the format's model `entry_of` on every edge of the format and
//! 10^5 random words, and the model against the contract decoded back to
//! the bus word, which a wrong boundary in the model fails.

use motion_hdl::blocks::motion_controller::entry::{
    entry_of, EntryConverter, ENTRY_CODE_WIDE, ENTRY_NONZERO, ENTRY_SIGN, ENTRY_TOO_LARGE,
};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use rust_hdl::prelude::*;

/// The converter's entry for `w`, settled (the block is combinational).
fn convert(uut: &mut EntryConverter, w: i32) -> u32 {
    uut.word.next = (w as u32 as u64).into();
    for _ in 0..16 {
        uut.update_all();
        if !uut.has_changed() {
            return uut.entry.val().to_u64() as u32;
        }
    }
    panic!("the entry converter did not settle for {w}");
}

/// Every word within 2 of each edge of the format (the controller tests'
/// `ENTRY_EDGES`: 0, 16 bits signed, 16 bits unsigned, 32 bits).
fn edge_words() -> Vec<i32> {
    let mut words: Vec<i32> = crate::motion_controller::ENTRY_EDGES
        .iter()
        .flat_map(|&e| (-2..=2).filter_map(move |d| i32::try_from(e as i64 + d).ok()))
        .collect();
    words.sort_unstable();
    words.dedup();
    words
}

/// The contract, decoded back: the magnitude and sign give w whenever it
/// is not too large, and each flag says what the format says it does.
fn check_contract(w: i32, entry: u32) {
    let magnitude = entry & 0xffff;
    let flag = |b: usize| entry >> b & 1 == 1;
    assert_eq!(entry >> 20, 0, "{w}: bits above the entry");
    assert_eq!(
        flag(ENTRY_TOO_LARGE),
        w.unsigned_abs() > 0xffff,
        "{w}: too large"
    );
    if flag(ENTRY_TOO_LARGE) {
        assert_eq!(magnitude, 0xffff, "{w}: saturated magnitude");
    } else {
        let back = if flag(ENTRY_SIGN) {
            -(magnitude as i64)
        } else {
            magnitude as i64
        };
        assert_eq!(back, w as i64, "{w}: magnitude and sign");
    }
    assert_eq!(flag(ENTRY_SIGN), w < 0, "{w}: sign");
    assert_eq!(
        flag(ENTRY_CODE_WIDE),
        !(-32768..=32767).contains(&w),
        "{w}: code wide"
    );
    assert_eq!(flag(ENTRY_NONZERO), w != 0, "{w}: nonzero");
}

#[test]
fn the_format_model_keeps_its_contract_on_every_edge_and_random_words() {
    let mut rng = StdRng::seed_from_u64(0xe7e7);
    for w in edge_words()
        .into_iter()
        .chain((0..100_000).map(|_| rng.gen::<i32>()))
    {
        check_contract(w, entry_of(w));
    }
}

#[test]
fn the_contract_check_fails_a_model_with_a_wrong_boundary() {
    // The mutant saturates from 2^16 on instead of above 2^16 - 1.
    let mutant = |w: i32| {
        let mut e = entry_of(w);
        if w.unsigned_abs() == 0xffff {
            e |= 1 << ENTRY_TOO_LARGE;
        }
        e
    };
    let caught = std::panic::catch_unwind(|| check_contract(0xffff, mutant(0xffff)));
    assert!(
        caught.is_err(),
        "the contract check passed a wrong saturation edge"
    );
}

#[test]
fn rtl_converts_every_edge_and_random_word_as_the_model_does() {
    let mut uut = EntryConverter::default();
    uut.connect_all();
    check_all(&uut).expect("the entry converter passes rust-hdl's checks");
    let mut rng = StdRng::seed_from_u64(0xc0de);
    let words = edge_words()
        .into_iter()
        .chain((0..100_000).map(|_| match rng.gen_range(0..3) {
            // Small words, words near 16 bits and any word.
            0 => rng.gen_range(-70_000..70_000),
            1 => rng.gen_range(-0x2_0000..0x2_0000),
            _ => rng.gen::<i32>(),
        }));
    for w in words {
        assert_eq!(convert(&mut uut, w), entry_of(w), "entry of {w} ({w:#x})");
    }
}
