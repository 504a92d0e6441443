//! `HoldRamp` (the feed hold's factor and tick gate): RTL against the
//! model, and a monitor of the contract from the ports alone: the gated
//! ticks are exactly floor(sum of the factor at each tick / UNITY) since
//! reset (no fraction lost), the factor moves only on a tick, by at most
//! one step of `rate` toward the requested end, and reaches it.

use motion_hdl::blocks::motion_controller::hold_ramp::{
    HoldRamp, HoldRampInputs, HoldRampModel, HoldRampOutputs, UNITY,
};
use motion_hdl::sim::{Backend, Lockstep};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// Holds and releases at random, rates from the smallest to 0 (no ramp),
/// dense and sparse ticks, rare resets.
fn random_inputs(seed: u64, cycles: usize) -> Vec<HoldRampInputs> {
    let mut rng = StdRng::seed_from_u64(seed);
    let (mut hold, mut rate, mut tick_ratio) = (false, 100u16, 1u32);
    (0..cycles)
        .map(|_| {
            if rng.gen_ratio(1, 3000) {
                hold = !hold;
            }
            if rng.gen_ratio(1, 20_000) {
                rate = [0, 1, 7, 100, 4096, 65535, rng.gen()][rng.gen_range(0..7)];
                tick_ratio = rng.gen_range(1..4);
            }
            HoldRampInputs {
                reset: rng.gen_ratio(1, 200_000),
                tick: rng.gen_ratio(1, tick_ratio),
                hold,
                rate,
            }
        })
        .collect()
}

/// The contract at the ports, checked clock by clock on the outputs after
/// each edge; the first violation.
struct Monitor {
    /// The factor's sum over the ticks since reset, and the gated ticks.
    factor_sum: u64,
    gated: u64,
    /// The outputs after the last edge (the power-up state at first).
    last: HoldRampOutputs,
}

/// The outputs in the power-up and reset state.
const FULL_SPEED: HoldRampOutputs = HoldRampOutputs {
    tick_out: false,
    factor: UNITY,
    phase: 0,
    slowed: false,
    stopped: false,
};

impl Default for Monitor {
    fn default() -> Self {
        Self {
            factor_sum: 0,
            gated: 0,
            last: FULL_SPEED,
        }
    }
}

impl Monitor {
    fn check(&mut self, i: &HoldRampInputs, o: &HoldRampOutputs) -> Result<(), String> {
        let prev = self.last;
        // This clock's gated tick, from the state before its edge.
        let gated_now = i.tick && prev.phase + prev.factor >= UNITY;
        if i.reset {
            *self = Self::default();
            let expected = HoldRampOutputs {
                tick_out: i.tick,
                ..FULL_SPEED
            };
            return match *o == expected {
                true => Ok(()),
                false => Err(format!("after reset: {o:?}")),
            };
        }
        let step = if i.rate == 0 { UNITY } else { i.rate as u32 };
        let expected = match (i.tick, i.hold) {
            (false, _) => prev.factor,
            (true, true) => prev.factor.saturating_sub(step),
            (true, false) => (prev.factor + step).min(UNITY),
        };
        if o.factor != expected {
            return Err(format!(
                "factor {} after {} ({i:?}), expected {expected}",
                o.factor, prev.factor
            ));
        }
        if o.slowed != (o.factor < UNITY) || o.stopped != (o.factor == 0) {
            return Err(format!("flags of factor {}: {o:?}", o.factor));
        }
        if o.tick_out != (i.tick && o.phase + o.factor >= UNITY) {
            return Err(format!("tick_out of {o:?} with tick {}", i.tick));
        }
        if i.tick {
            self.factor_sum += prev.factor as u64;
            self.gated += gated_now as u64;
        }
        if self.gated * UNITY as u64 + o.phase as u64 != self.factor_sum {
            return Err(format!(
                "{} gated ticks and phase {} for a factor sum of {}",
                self.gated, o.phase, self.factor_sum
            ));
        }
        self.last = *o;
        Ok(())
    }

    /// The gated ticks since reset.
    fn gated(&self) -> u64 {
        self.gated
    }
}

/// Runs the monitor over `model`-like outputs from `step`.
fn monitor_run(
    stimulus: &[HoldRampInputs],
    mut step: impl FnMut(&HoldRampInputs) -> HoldRampOutputs,
) -> Result<(), String> {
    let mut monitor = Monitor::default();
    for (cycle, i) in stimulus.iter().enumerate() {
        let o = step(i);
        monitor
            .check(i, &o)
            .map_err(|e| format!("cycle {cycle}: {e}"))?;
    }
    Ok(())
}

#[test]
fn rtl_matches_model_and_keeps_every_fraction_for_a_million_clocks() {
    let stimulus = random_inputs(0x401d, 1_000_000);
    let mut pair = Lockstep::on(
        Backend::Verilator,
        "hold_ramp",
        HoldRamp::default(),
        HoldRampModel::default(),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let mut monitor = Monitor::default();
    let (mut gated, mut stops, mut ramps) = (0u64, 0u64, 0u64);
    let mut was_stopped = false;
    pair.run_all(&stimulus, |cycle, i, o| {
        let before = monitor.gated();
        monitor
            .check(i, o)
            .unwrap_or_else(|e| panic!("cycle {cycle}: {e}"));
        gated += monitor.gated().saturating_sub(before);
        stops += (o.stopped && !was_stopped) as u64;
        was_stopped = o.stopped;
        ramps += (o.factor != 0 && o.factor != UNITY) as u64;
    })
    .unwrap_or_else(|e| panic!("{e}"));
    assert!(
        gated > 100_000 && stops > 20 && ramps > 100_000,
        "{gated} {stops} {ramps}"
    );
}

#[test]
fn the_rust_hdl_rtl_matches_the_model() {
    let stimulus = random_inputs(0x401e, 20_000);
    let mut pair = Lockstep::harness("hold_ramp", HoldRamp::default(), HoldRampModel::default());
    pair.run_all(&stimulus, |_, _, _| {})
        .unwrap_or_else(|e| panic!("{e}"));
}

/// Every rate, 0 to 65535: from full speed a hold stops in exactly
/// ceil(UNITY / rate) ticks (one for 0), the release returns to full speed
/// in as many, and the gated ticks of the whole ramp pair are exact.
#[test]
fn every_rate_stops_and_resumes_in_its_tick_count() {
    let mut pair = Lockstep::on(
        Backend::Verilator,
        "hold_ramp",
        HoldRamp::default(),
        HoldRampModel::default(),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let mut monitor = Monitor::default();
    for rate in 0..=u16::MAX {
        let step = if rate == 0 { UNITY } else { rate as u32 };
        let expected = UNITY.div_ceil(step) as u64;
        for hold in [true, false] {
            let i = HoldRampInputs {
                reset: false,
                tick: true,
                hold,
                rate,
            };
            let mut ticks = 0;
            loop {
                let o = pair.step(&i).unwrap_or_else(|e| panic!("rate {rate}: {e}"));
                monitor
                    .check(&i, &o)
                    .unwrap_or_else(|e| panic!("rate {rate}: {e}"));
                ticks += 1;
                let end = if hold { o.stopped } else { o.factor == UNITY };
                if end {
                    break;
                }
                assert!(ticks < expected, "rate {rate}, hold {hold}: {ticks} ticks");
            }
            assert_eq!(ticks, expected, "rate {rate}, hold {hold}");
        }
    }
}

/// The monitor fails a gate that drops the carried fraction, a ramp one
/// step too steep, and a factor that moves between ticks.
#[test]
fn the_monitor_catches_a_lost_fraction_and_a_steep_ramp() {
    let stimulus = random_inputs(0x401f, 200_000);
    let mut model = HoldRampModel::default();
    assert_eq!(monitor_run(&stimulus, |i| model.step(*i)), Ok(()));

    // Lost fraction: the phase is cleared after every gated tick.
    let mut model = HoldRampModel::default();
    let lost = monitor_run(&stimulus, |i| {
        let o = model.step(*i);
        if o.tick_out {
            model = HoldRampModel::with_factor(model.factor());
        }
        o
    });
    assert!(
        lost.as_ref().is_err_and(|e| e.contains("gated ticks")),
        "{lost:?}"
    );

    // Too steep: twice the rate on the way down.
    let mut model = HoldRampModel::default();
    let steep = monitor_run(&stimulus, |i| {
        let doubled = HoldRampInputs {
            rate: i.rate.saturating_mul(2),
            ..*i
        };
        model.step(if i.hold { doubled } else { *i })
    });
    assert!(
        steep.as_ref().is_err_and(|e| e.contains("factor")),
        "{steep:?}"
    );

    // Between ticks: the ramp runs on every clock.
    let mut model = HoldRampModel::default();
    let untimed = monitor_run(&stimulus, |i| {
        model.step(HoldRampInputs { tick: true, ..*i })
    });
    assert!(untimed.is_err(), "{untimed:?}");
}
