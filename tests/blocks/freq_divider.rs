//! `freq_divider`: RTL against the model, RTL against the port contract, and
//! the exported Verilog against the Rust simulation.

use motion_hdl::blocks::freq_divider::model::{FreqDividerInputs, FreqDividerModel};
use motion_hdl::blocks::freq_divider::FreqDivider;
use motion_hdl::sim::{Harness, Lockstep};
use motion_hdl::tools::cosim::{check_instance, Instance};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// Random stimulus: bursts with one divisor (mostly small, sometimes large,
/// sometimes 0), enable gating of varying density, divisor changes at any
/// phase, and rare resets.
fn random_stimulus(rng: &mut StdRng, cycles: usize, width: u32) -> Vec<FreqDividerInputs> {
    let mask = motion_hdl::blocks::width_mask(width);
    let mut out = Vec::with_capacity(cycles);
    let mut divisor = 3;
    let mut enable_density = 1.0;
    while out.len() < cycles {
        let burst = rng.gen_range(1..400);
        divisor = match rng.gen_range(0..20) {
            0 => 0,
            1 => rng.gen::<u64>() & mask,
            2..=4 => rng.gen_range(1..300),
            5 => divisor, // unchanged: tests long constant runs
            _ => rng.gen_range(1..12),
        } & mask;
        enable_density = match rng.gen_range(0..4) {
            0 => rng.gen_range(0.0..1.0),
            1 => enable_density,
            _ => 1.0,
        };
        for _ in 0..burst {
            out.push(FreqDividerInputs {
                reset: rng.gen_ratio(1, 5000),
                enable: rng.gen_bool(enable_density),
                divisor,
            });
        }
    }
    out.truncate(cycles);
    // No reset at cycle 0: power-up must equal the reset state.
    out
}

/// An independent monitor of the port contract (not derived from the model):
/// it sees only the inputs applied at each rising edge and the strobe after it.
///
/// Between two strobes the divisor may change; the contract says the new D
/// takes effect at the next strobe at the latest and no interval is shorter
/// than the smaller D. So an interval lasts at least the smallest and at
/// most the largest divisor applied during it (exactly D when D was
/// constant), and a strobe must come once the largest is reached.
#[derive(Default)]
struct ContractMonitor {
    /// Enabled edges since the last strobe; None after reset (no strobe yet).
    edges_since_strobe: Option<u64>,
    /// Divisors applied on the enabled edges since the last strobe (inclusive).
    min_divisor: u64,
    max_divisor: u64,
    constant_divisor: Option<u64>,
    /// D = 0 was applied during the interval: the divider was stopped, so
    /// only "no strobe with D = 0" is checked until the next strobe.
    stopped: bool,
    cycle: u64,
}

impl ContractMonitor {
    fn edge(&mut self, inputs: &FreqDividerInputs, strobe: bool) {
        let cycle = self.cycle;
        self.cycle += 1;
        if inputs.reset {
            assert!(!strobe, "cycle {cycle}: strobe during reset");
            *self = Self {
                cycle: self.cycle,
                ..Self::default()
            };
            return;
        }
        if !inputs.enable {
            assert!(
                !strobe,
                "cycle {cycle}: strobe after an edge with enable low"
            );
            return;
        }
        let d = inputs.divisor;
        assert!(
            !strobe || d != 0,
            "cycle {cycle}: strobe on an edge with D=0"
        );
        let Some(edges) = self.edges_since_strobe.as_mut() else {
            // From power-up or reset, the first enabled edge with D != 0 strobes.
            assert_eq!(
                strobe,
                d != 0,
                "cycle {cycle}: first strobe after reset with D={d}"
            );
            if strobe {
                self.restart(d);
            }
            return;
        };
        *edges += 1;
        let edges = *edges;
        self.min_divisor = self.min_divisor.min(d);
        self.max_divisor = self.max_divisor.max(d);
        self.stopped |= d == 0;
        if self.constant_divisor != Some(d) {
            self.constant_divisor = None;
        }
        if strobe {
            if !self.stopped {
                assert!(
                    (self.min_divisor..=self.max_divisor).contains(&edges),
                    "cycle {cycle}: interval {edges} outside the divisors applied during it ({}..={})",
                    self.min_divisor,
                    self.max_divisor
                );
                if let Some(constant) = self.constant_divisor {
                    assert_eq!(edges, constant, "cycle {cycle}: interval with constant D");
                }
            }
            self.restart(d);
        } else if !self.stopped {
            assert!(
                edges < self.max_divisor,
                "cycle {cycle}: no strobe after {edges} enabled edges (divisors {}..={})",
                self.min_divisor,
                self.max_divisor
            );
        }
    }

    fn restart(&mut self, divisor: u64) {
        self.edges_since_strobe = Some(0);
        self.constant_divisor = Some(divisor);
        self.min_divisor = divisor;
        self.max_divisor = divisor;
        self.stopped = false;
    }
}

fn run_against_model<const W: usize>(stimulus: &[FreqDividerInputs]) {
    let mut pair = Lockstep::harness(
        "freq_divider",
        FreqDivider::<W>::default(),
        FreqDividerModel::new(W as u32),
    );
    let mut monitor = ContractMonitor::default();
    pair.run_all(stimulus, |_, inputs, &strobe| monitor.edge(inputs, strobe))
        .unwrap_or_else(|e| panic!("W={W}: RTL strobe differs from the model: {e}"));
}

#[test]
fn rtl_matches_model_and_contract_on_a_million_random_cycles() {
    let mut rng = StdRng::seed_from_u64(0x5eed_d1de);
    let stimulus = random_stimulus(&mut rng, 1_000_000, 32);
    run_against_model::<32>(&stimulus);
}

#[test]
fn narrow_rtl_matches_model_and_contract() {
    let mut rng = StdRng::seed_from_u64(12);
    run_against_model::<12>(&random_stimulus(&mut rng, 200_000, 12));
    run_against_model::<4>(&random_stimulus(&mut rng, 200_000, 4));
    // The narrowest legal width: D = 3 ends each interval on the edge where
    // the count wraps.
    run_against_model::<2>(&random_stimulus(&mut rng, 100_000, 2));
}

/// Every pair of old and new divisor of a 4-bit divider, with the change
/// landing at every phase of the interval in progress.
#[test]
fn every_divisor_change_at_every_phase_keeps_the_contract() {
    for old in 0..16u64 {
        for new in 0..16u64 {
            for phase in 0..old.max(1) + 1 {
                let mut stimulus = vec![FreqDividerInputs {
                    reset: true,
                    enable: false,
                    divisor: old,
                }];
                // Two full intervals of the old divisor, then `phase` more edges.
                let lead = 1 + 2 * old + phase;
                stimulus.extend((0..lead).map(|_| FreqDividerInputs {
                    reset: false,
                    enable: true,
                    divisor: old,
                }));
                stimulus.extend((0..40).map(|_| FreqDividerInputs {
                    reset: false,
                    enable: true,
                    divisor: new,
                }));
                run_against_model::<4>(&stimulus);
            }
        }
    }
}

/// The monitor must catch a divider that goes quiet after a divisor change
/// (a check that cannot fail is worse than none).
#[test]
#[should_panic(expected = "no strobe after")]
fn monitor_catches_a_missing_strobe_after_a_divisor_change() {
    let mut monitor = ContractMonitor::default();
    let edge = |d| FreqDividerInputs {
        reset: false,
        enable: true,
        divisor: d,
    };
    monitor.edge(&edge(10), true);
    for _ in 0..5 {
        monitor.edge(&edge(10), false);
    }
    for _ in 0..100 {
        monitor.edge(&edge(3), false);
    }
}

#[test]
fn power_up_without_reset_strobes_like_after_reset() {
    let mut from_power_up = Harness::new("freq_divider", FreqDivider::<32>::default()).unwrap();
    let mut from_reset = Harness::new("freq_divider", FreqDivider::<32>::default()).unwrap();
    let run = FreqDividerInputs {
        reset: false,
        enable: true,
        divisor: 3,
    };
    let reset = FreqDividerInputs { reset: true, ..run };
    from_reset.step_vector(&reset.to_vector()).unwrap();
    for cycle in 0..100 {
        let a = from_power_up.step_vector(&run.to_vector()).unwrap();
        let b = from_reset.step_vector(&run.to_vector()).unwrap();
        assert_eq!(a, b, "cycle {cycle}");
    }
}

#[test]
fn strobes_are_exactly_d_clocks_apart() {
    for d in [1u64, 2, 3, 7, 100, 1000] {
        let run = FreqDividerInputs {
            reset: false,
            enable: true,
            divisor: d,
        };
        let reset = FreqDividerInputs {
            reset: true,
            enable: false,
            divisor: d,
        };
        let mut pair = Lockstep::harness(
            "freq_divider",
            FreqDivider::<32>::default(),
            FreqDividerModel::new(32),
        );
        pair.step(&reset).unwrap();
        let times: Vec<u64> = (0..5000u64).filter(|_| pair.step(&run).unwrap()).collect();
        assert_eq!(times.len() as u64, 5000u64.div_ceil(d), "D={d}");
        assert_eq!(
            times[0], 0,
            "D={d}: the first enabled clock after reset strobes"
        );
        assert!(
            times.windows(2).all(|w| w[1] - w[0] == d),
            "D={d}: intervals {times:?}"
        );
    }
}

#[test]
fn exported_verilog_matches_rust_in_icarus_and_verilator() {
    let mut rng = StdRng::seed_from_u64(0xc0515);
    let pass = check_instance::<FreqDivider<32>>(
        Instance::Exported("freq_divider"),
        random_stimulus(&mut rng, 20_000, 32)
            .iter()
            .map(FreqDividerInputs::to_vector),
    );
    assert_eq!(pass.cycles, 20_000);
}

#[test]
fn narrow_12_bit_verilog_matches_rust_in_icarus_and_verilator() {
    let mut rng = StdRng::seed_from_u64(0xc0516);
    check_instance::<FreqDivider<12>>(
        Instance::Generated("freq_divider_w12"),
        random_stimulus(&mut rng, 20_000, 12)
            .iter()
            .map(FreqDividerInputs::to_vector),
    );
}
