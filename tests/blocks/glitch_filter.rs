//! `GlitchFilter`: RTL against the model on random input, and the filter
//! contract (a level held for fewer than k samples is never accepted, one
//! held for k samples is) checked exhaustively for every k and width.

use motion_hdl::blocks::glitch_filter::model::{
    GlitchFilterInputs, GlitchFilterModel, GlitchFilterOutputs,
};
use motion_hdl::blocks::glitch_filter::GlitchFilter;
use motion_hdl::sim::{Harness, Lockstep};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

fn harness() -> Harness<GlitchFilter> {
    Harness::new("glitch_filter", GlitchFilter::default()).unwrap()
}

/// One edge; returns (filtered, changed) after it.
fn edge(
    h: &mut Harness<GlitchFilter>,
    reset: bool,
    raw: bool,
    sample: bool,
    length: u8,
    prime: bool,
) -> (bool, bool) {
    let inputs = GlitchFilterInputs {
        reset,
        raw,
        sample,
        length,
        prime,
    };
    let out = GlitchFilterOutputs::from_vector(&h.step_vector(&inputs.to_vector()).unwrap());
    (out.filtered, out.changed)
}

#[test]
fn rtl_matches_model_on_random_input() {
    let mut rng = StdRng::seed_from_u64(0x91f);
    let mut pair = Lockstep::harness(
        "glitch_filter",
        GlitchFilter::default(),
        GlitchFilterModel::new(),
    );
    let (mut raw, mut length, mut accepts) = (false, 0u8, 0);
    let stimulus = |cycle: u64, model: &GlitchFilterModel| {
        if cycle == 1_000_000 {
            return None;
        }
        if rng.gen_ratio(1, 2000) {
            length = rng.gen_range(0..16);
        }
        // Runs of random length, so every run length meets every k.
        if rng.gen_ratio(1, [2, 5, 20][cycle as usize / 1000 % 3]) {
            raw = !raw;
        }
        let sample = rng.gen_ratio(3, 4);
        let prime = rng.gen_ratio(1, 5000);
        let reset = rng.gen_ratio(1, 50_000);
        accepts += model.accepts(raw, sample, prime) as u32;
        Some(GlitchFilterInputs {
            reset,
            raw,
            sample,
            length,
            prime,
        })
    };
    pair.run(stimulus, |_, _, _| {})
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(accepts > 10_000, "only {accepts} acceptances");
}

/// For every k and every pulse width w (in samples, with idle clocks
/// between samples): the pulse is accepted exactly when w >= max(k, 1), at
/// its max(k, 1)-th sample, and the return to the old level likewise.
#[test]
fn a_level_is_accepted_exactly_after_k_samples() {
    for k in 0..16u8 {
        for w in 1..20u32 {
            for gap in 0..3u32 {
                let mut h = harness();
                edge(&mut h, false, false, false, k, true);
                let mut accepted_at = None;
                let mut returned_at = None;
                let mut sample_index = 0;
                for clock in 0..(w + 20) * (gap + 1) {
                    let sample = clock % (gap + 1) == 0;
                    let raw = sample_index < w;
                    let (filtered, _) = edge(&mut h, false, raw, sample, k, false);
                    if sample {
                        sample_index += 1;
                    }
                    if filtered && accepted_at.is_none() {
                        accepted_at = Some(sample_index);
                    }
                    if !filtered && accepted_at.is_some() && returned_at.is_none() {
                        returned_at = Some(sample_index);
                    }
                }
                let need = k.max(1) as u32;
                if w >= need {
                    assert_eq!(accepted_at, Some(need), "k {k} w {w} gap {gap}");
                    assert_eq!(returned_at, Some(w + need), "k {k} w {w} gap {gap}: return");
                } else {
                    assert_eq!(accepted_at, None, "k {k} w {w} gap {gap}: glitch passed");
                }
            }
        }
    }
}

#[test]
fn prime_loads_the_level_without_a_change() {
    let mut h = harness();
    let (filtered, changed) = edge(&mut h, false, true, true, 15, true);
    assert!(filtered && !changed);
}

#[test]
fn changed_is_high_for_the_one_clock_after_each_accepted_change() {
    let mut h = harness();
    edge(&mut h, false, false, true, 0, true);
    let mut last = false;
    for clock in 0..200u32 {
        let raw = clock / 7 % 2 == 1;
        let (filtered, changed) = edge(&mut h, false, raw, true, 3, false);
        assert_eq!(changed, filtered != last, "clock {clock}");
        last = filtered;
    }
}
