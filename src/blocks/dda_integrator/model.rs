//! Reference model of [`super::DdaIntegrator`]: the DDA arithmetic as the
//! port contract states it (s = acc + J with the carry kept), cycle-exact
//! with the RTL's two-clock pulse latency.

/// Inputs of one clock cycle.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct DdaIntegratorInputs {
    /// Synchronous reset.
    pub reset: bool,
    /// Accumulate enable.
    pub tick: bool,
    /// J.
    pub integrand: u64,
    /// M; 0 means 2^width.
    pub modulus: u64,
    /// Clears `overrange`.
    pub clear_overrange: bool,
}

impl DdaIntegratorInputs {
    /// The RTL's input vector, in its port order.
    pub fn to_vector(&self) -> Vec<u64> {
        vec![
            self.reset as u64,
            self.tick as u64,
            self.integrand,
            self.modulus,
            self.clear_overrange as u64,
        ]
    }
}

/// Outputs after one clock edge.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct DdaIntegratorOutputs {
    /// One pulse per overflow.
    pub pulse: bool,
    /// Sticky: J > M was used.
    pub overrange: bool,
}

impl DdaIntegratorOutputs {
    /// Reads the RTL's output vector, in its port order.
    pub fn from_vector(v: &[u64]) -> Self {
        Self {
            pulse: v[0] != 0,
            overrange: v[1] != 0,
        }
    }
}

/// The accumulator arithmetic alone: one tick of a `width`-bit DDA.
/// Returns `(pulse, J > M)`; `acc` is updated.
pub fn dda_tick(acc: &mut u128, integrand: u64, modulus: u64, width: u32) -> (bool, bool) {
    let mask = (1u128 << width) - 1;
    let m = if modulus as u128 & mask == 0 {
        1u128 << width
    } else {
        modulus as u128 & mask
    };
    let mut j = integrand as u128 & mask;
    let too_large = j > m;
    if too_large {
        j = m;
    }
    let s = *acc + j;
    let pulse = j != 0 && s >= m;
    *acc = if pulse {
        s - m
    } else if j == 0 {
        *acc
    } else {
        s
    };
    (pulse, too_large)
}

/// Plain-Rust, cycle-exact model of a `width`-bit DDA integrator.
#[derive(Clone, Debug)]
pub struct DdaIntegratorModel {
    width: u32,
    acc: u128,
    /// The tick sampled at the last edge, with its J and M.
    staged: Option<(u64, u64)>,
    out: DdaIntegratorOutputs,
}

impl DdaIntegratorModel {
    /// A DDA of `width` bits (1 to 64), in its power-up state.
    pub fn new(width: u32) -> Self {
        assert!((1..=64).contains(&width), "width must be 1..=64");
        Self {
            width,
            acc: 0,
            staged: None,
            out: DdaIntegratorOutputs::default(),
        }
    }

    /// The outputs after the last edge.
    pub fn outputs(&self) -> DdaIntegratorOutputs {
        self.out
    }

    /// The accumulator (for tests).
    pub fn accumulator(&self) -> u128 {
        self.acc
    }

    /// One rising clock edge; returns the outputs after it.
    pub fn step(&mut self, inputs: DdaIntegratorInputs) -> DdaIntegratorOutputs {
        let mut set_overrange = false;
        self.out.pulse = false;
        if let Some((j, m)) = self.staged.take() {
            let (pulse, too_large) = dda_tick(&mut self.acc, j, m, self.width);
            self.out.pulse = pulse;
            set_overrange = too_large;
        }
        if set_overrange {
            self.out.overrange = true;
        }
        if inputs.clear_overrange {
            self.out.overrange = false;
        }
        if inputs.tick {
            self.staged = Some((inputs.integrand, inputs.modulus));
        }
        if inputs.reset {
            *self = Self::new(self.width);
        }
        self.out
    }
}

crate::lockstep_model!(DdaIntegratorModel {
    inputs: DdaIntegratorInputs,
    outputs: DdaIntegratorOutputs,
    step: |model, inputs| model.step(*inputs),
});

/// Inputs of one clock cycle of the DDA mode of a
/// [`UniformPulseCore`](crate::blocks::uniform_pulse_gen::UniformPulseCore)
/// (its `dda_` ports; the generator's inputs idle).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PeriodDdaInputs {
    /// Synchronous reset.
    pub reset: bool,
    /// Accumulate enable.
    pub tick: bool,
    /// The first clock of a new J and -M.
    pub reload: bool,
    /// J.
    pub integrand: u64,
    /// -M, two's complement in `width + 1` bits.
    pub modulus_negated: u64,
    /// Clears `overrange`.
    pub clear_overrange: bool,
}

/// Where the `dda_` ports sit in `UniformPulseCore`'s port vectors: the
/// number of inputs, the first `dda_` input and the first `dda_` output,
/// read from the core's own port lists (its `vector_ports!`).
fn core_layout() -> (usize, usize, usize) {
    use crate::sim::VectorPorts;
    type Core = crate::blocks::uniform_pulse_gen::UniformPulseCore<4, 5>;
    static LAYOUT: std::sync::OnceLock<(usize, usize, usize)> = std::sync::OnceLock::new();
    *LAYOUT.get_or_init(|| {
        let inputs = Core::input_names();
        let first = |names: &[String], port: &str| {
            names
                .iter()
                .position(|name| name == port)
                .expect("UniformPulseCore has its dda_ ports")
        };
        (
            inputs.len(),
            first(&inputs, "dda_tick"),
            first(&Core::output_names(), "dda_pulse"),
        )
    })
}

impl PeriodDdaInputs {
    /// The core's input vector, in its port order: `reset`, the
    /// generator's inputs at 0 (no tick, no load, no plan), then the
    /// `dda_` ports.
    pub fn to_vector(&self) -> Vec<u64> {
        let (inputs, dda_inputs, _) = core_layout();
        let mut v = vec![0; inputs];
        v[0] = self.reset as u64;
        v[dda_inputs..].copy_from_slice(&[
            self.tick as u64,
            self.reload as u64,
            self.integrand,
            (self.integrand != 0) as u64,
            self.modulus_negated,
            self.clear_overrange as u64,
        ]);
        v
    }
}

impl DdaIntegratorOutputs {
    /// Reads `dda_pulse` and `dda_overrange` from a `UniformPulseCore`'s
    /// output vector.
    pub fn from_core_vector(v: &[u64]) -> Self {
        Self::from_vector(&v[core_layout().2..])
    }
}

/// Plain-Rust, cycle-exact model of the DDA mode of a
/// [`UniformPulseCore`](crate::blocks::uniform_pulse_gen::UniformPulseCore):
/// the [`DdaIntegratorModel`] it stands in for, fed J and M = -(-M), and a
/// check of the contract that lets the core keep no accumulator: the
/// phase is 0 at every `reload` with J != 0.
#[derive(Clone, Debug)]
pub struct PeriodDdaModel {
    dda: DdaIntegratorModel,
    width: u32,
    /// The accumulator at the first `reload` that found it not 0.
    broken_contract: Option<u128>,
}

impl PeriodDdaModel {
    /// The model of the DDA mode of a `UniformPulseCore<width, width + 1>`.
    pub fn new(width: u32) -> Self {
        Self {
            dda: DdaIntegratorModel::new(width),
            width,
            broken_contract: None,
        }
    }

    /// The accumulator a `reload` found not at 0, if one did: the
    /// stimulus broke the contract, and the core need not match.
    pub fn broken_contract(&self) -> Option<u128> {
        self.broken_contract
    }

    /// One rising clock edge; returns the outputs after it.
    pub fn step(&mut self, inputs: PeriodDdaInputs) -> DdaIntegratorOutputs {
        let error_mask = (1u64 << (self.width + 1)) - 1;
        let modulus = inputs.modulus_negated.wrapping_neg() & error_mask;
        let out = self.dda.step(DdaIntegratorInputs {
            reset: inputs.reset,
            tick: inputs.tick,
            integrand: inputs.integrand,
            modulus,
            clear_overrange: inputs.clear_overrange,
        });
        // The tick taken at this edge was the old period's last: the phase
        // must be back at 0 for the reloaded error to be the DDA's.
        if inputs.reload
            && inputs.integrand != 0
            && self.dda.accumulator() != 0
            && self.broken_contract.is_none()
        {
            self.broken_contract = Some(self.dda.accumulator());
        }
        out
    }
}

impl crate::sim::LockstepModel for PeriodDdaModel {
    type Inputs = PeriodDdaInputs;
    type Outputs = DdaIntegratorOutputs;
    fn input_vector(inputs: &PeriodDdaInputs, vector: &mut Vec<u64>) {
        *vector = inputs.to_vector();
    }
    fn read_outputs(&self, vector: &[u64]) -> DdaIntegratorOutputs {
        DdaIntegratorOutputs::from_core_vector(vector)
    }
    fn expected(&mut self, inputs: &PeriodDdaInputs) -> DdaIntegratorOutputs {
        self.step(*inputs)
    }
}
