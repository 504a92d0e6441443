//! `Watchdog`: RTL against the model, and from the ports alone: `expired`
//! rises exactly at the `timeout`-th tick after a kick with no kick in
//! between, and never otherwise.

use motion_hdl::blocks::watchdog::model::WatchdogModel;
use motion_hdl::blocks::watchdog::Watchdog;
use motion_hdl::sim::Harness;
use motion_hdl::tools::cosim::cross_simulate_generated;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// [reset, tick, timeout, kick, clear] per clock: a host that kicks on
/// time, late, or stops; timeouts from 0 (disarmed) up; sparse ticks.
fn random_inputs(seed: u64, cycles: usize, timeout_mask: u64) -> Vec<[u64; 5]> {
    let mut rng = StdRng::seed_from_u64(seed);
    let mut timeout = 10;
    let mut kick_every = 8;
    (0..cycles)
        .map(|cycle| {
            if rng.gen_ratio(1, 500) {
                timeout = [0, 1, 2, 3, rng.gen_range(1..40)][rng.gen_range(0..5)] & timeout_mask;
                kick_every = rng.gen_range(1..50);
            }
            let kick = cycle % kick_every == 0 && rng.gen_ratio(9, 10);
            [
                rng.gen_ratio(1, 50_000) as u64,
                rng.gen_ratio(2, 3) as u64,
                timeout,
                kick as u64,
                rng.gen_ratio(1, 60) as u64,
            ]
        })
        .collect()
}

#[test]
fn rtl_matches_model_and_expires_exactly_on_time() {
    let mut h = Harness::new("watchdog", Watchdog::<16>::default()).unwrap();
    let mut model = WatchdogModel::new();
    // The independent view: ticks counted since the last arming kick.
    let mut since_kick: Option<(u64, u64)> = None; // (ticks, timeout)
    let (mut expiries, mut last_expired) = (0, false);
    for (cycle, v) in random_inputs(0x3d, 1_000_000, 0xffff).iter().enumerate() {
        let [reset, tick, timeout, kick, clear] = v.map(|x| x);
        let out = h.step_vector(v).unwrap();
        let (expired, armed) = (out[0] != 0, out[1] != 0);
        assert_eq!(
            (expired, armed),
            model.step(reset != 0, tick != 0, timeout, kick != 0, clear != 0),
            "cycle {cycle}"
        );
        let mut expires_now = false;
        if reset != 0 {
            since_kick = None;
        } else if kick != 0 {
            since_kick = (timeout != 0).then_some((0, timeout));
        } else if let (1, Some((ticks, limit))) = (tick, since_kick) {
            if ticks + 1 == limit {
                expires_now = true;
                since_kick = None;
            } else {
                since_kick = Some((ticks + 1, limit));
            }
        }
        if reset == 0 {
            // An expiry sets the flag; the flag is never set (fresh, or
            // again on a clearing edge) without one.
            let set_now = expired && (!last_expired || clear != 0);
            assert!(!expires_now || expired, "cycle {cycle}: expiry missed");
            assert!(
                !set_now || expires_now,
                "cycle {cycle}: expiry at the wrong tick"
            );
            assert_eq!(armed, since_kick.is_some(), "cycle {cycle}: armed");
        }
        expiries += expires_now as u32;
        last_expired = expired;
    }
    assert!(expiries > 1000, "{expiries} expiries");
}

#[test]
fn generated_verilog_matches_rust_in_icarus_and_verilator() {
    let stimulus: Vec<Vec<u64>> = random_inputs(0x3e, 20_000, 0x3f)
        .iter()
        .map(|v| v.to_vec())
        .collect();
    cross_simulate_generated("watchdog_w6", Watchdog::<6>::default(), &stimulus)
        .unwrap_or_else(|e| panic!("{e}"));
}

/// The widest timeout counts every one of its ticks.
#[test]
fn the_largest_timeout_expires_on_its_last_tick() {
    let mut h = Harness::new("watchdog", Watchdog::<16>::default()).unwrap();
    let kick = [0, 1, 0xffff, 1, 0];
    let wait = [0, 1, 0xffff, 0, 0];
    h.step_vector(&kick).unwrap();
    for tick in 1..0xffff {
        let out = h.step_vector(&wait).unwrap();
        assert_eq!(out, vec![0, 1], "tick {tick}");
    }
    assert_eq!(h.step_vector(&wait).unwrap(), vec![1, 0], "tick 65535");
}
