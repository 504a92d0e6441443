//! `Watchdog`: RTL against the model, and from the ports alone: `expired`
//! rises exactly at the `timeout`-th tick after a kick with no kick in
//! between, and never otherwise.

use motion_hdl::blocks::watchdog::model::{WatchdogInputs, WatchdogModel, WatchdogOutputs};
use motion_hdl::blocks::watchdog::Watchdog;
use motion_hdl::sim::{Harness, Lockstep};
use motion_hdl::tools::cosim::{check_instance, Instance};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// A host that kicks on time, late, or stops; timeouts from 0 (disarmed)
/// up; sparse ticks.
fn random_inputs(seed: u64, cycles: usize, timeout_mask: u64) -> Vec<WatchdogInputs> {
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
            WatchdogInputs {
                reset: rng.gen_ratio(1, 50_000),
                tick: rng.gen_ratio(2, 3),
                timeout,
                kick,
                clear: rng.gen_ratio(1, 60),
            }
        })
        .collect()
}

#[test]
fn rtl_matches_model_and_expires_exactly_on_time() {
    let mut pair = Lockstep::harness("watchdog", Watchdog::<16>::default(), WatchdogModel::new());
    // The independent view: ticks counted since the last arming kick.
    let mut since_kick: Option<(u64, u64)> = None; // (ticks, timeout)
    let (mut expiries, mut last_expired) = (0, false);
    let stimulus = random_inputs(0x3d, 1_000_000, 0xffff);
    pair.run_all(&stimulus, |cycle, v, out| {
        let WatchdogInputs {
            reset,
            tick,
            timeout,
            kick,
            clear,
        } = *v;
        let WatchdogOutputs { expired, armed } = *out;
        let mut expires_now = false;
        if reset {
            since_kick = None;
        } else if kick {
            since_kick = (timeout != 0).then_some((0, timeout));
        } else if let (true, Some((ticks, limit))) = (tick, since_kick) {
            if ticks + 1 == limit {
                expires_now = true;
                since_kick = None;
            } else {
                since_kick = Some((ticks + 1, limit));
            }
        }
        if !reset {
            // An expiry sets the flag; the flag is never set (fresh, or
            // again on a clearing edge) without one.
            let set_now = expired && (!last_expired || clear);
            assert!(!expires_now || expired, "cycle {cycle}: expiry missed");
            assert!(
                !set_now || expires_now,
                "cycle {cycle}: expiry at the wrong tick"
            );
            assert_eq!(armed, since_kick.is_some(), "cycle {cycle}: armed");
        }
        expiries += expires_now as u32;
        last_expired = expired;
    })
    .unwrap_or_else(|e| panic!("{e}"));
    assert!(expiries > 1000, "{expiries} expiries");
}

#[test]
fn generated_verilog_matches_rust_in_icarus_and_verilator() {
    check_instance::<Watchdog<6>>(
        Instance::Generated("watchdog_w6"),
        random_inputs(0x3e, 20_000, 0x3f)
            .iter()
            .map(WatchdogInputs::to_vector),
    );
}

/// The widest timeout counts every one of its ticks.
#[test]
fn the_largest_timeout_expires_on_its_last_tick() {
    let mut h = Harness::new("watchdog", Watchdog::<16>::default()).unwrap();
    let wait = WatchdogInputs {
        tick: true,
        timeout: 0xffff,
        ..Default::default()
    };
    let kick = WatchdogInputs { kick: true, ..wait };
    let mut clock =
        |i: WatchdogInputs| WatchdogOutputs::from_vector(&h.step_vector(&i.to_vector()).unwrap());
    clock(kick);
    let armed = WatchdogOutputs {
        expired: false,
        armed: true,
    };
    for tick in 1..0xffff {
        assert_eq!(clock(wait), armed, "tick {tick}");
    }
    let expired = WatchdogOutputs {
        expired: true,
        armed: false,
    };
    assert_eq!(clock(wait), expired, "tick 65535");
}
