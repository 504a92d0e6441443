//! Reference model of [`super::InterruptController`], cycle-exact.

/// Inputs of one clock cycle.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct InterruptControllerInputs {
    /// Synchronous reset.
    pub reset: bool,
    /// Event pulses, one bit per source.
    pub events: u64,
    /// Clear the bits of `clear_bits` on this edge.
    pub clear: bool,
    /// Status bits to clear.
    pub clear_bits: u64,
    /// Sources that raise `irq`.
    pub enable: u64,
}

impl InterruptControllerInputs {
    /// The RTL's input vector, in its port order.
    pub fn to_vector(&self) -> Vec<u64> {
        vec![
            self.reset as u64,
            self.events,
            self.clear as u64,
            self.clear_bits,
            self.enable,
        ]
    }
}

/// Outputs after one clock edge.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct InterruptControllerOutputs {
    /// Sticky event bits.
    pub status: u64,
    /// Registered OR of the enabled status bits.
    pub irq: bool,
}

impl InterruptControllerOutputs {
    /// Reads the RTL's output vector, in its port order.
    pub fn from_vector(v: &[u64]) -> Self {
        Self {
            status: v[0],
            irq: v[1] != 0,
        }
    }
}

/// Model of an N-bit interrupt controller (N <= 64).
#[derive(Clone, Debug, Default)]
pub struct InterruptControllerModel {
    status: u64,
    irq: bool,
}

impl InterruptControllerModel {
    /// A controller in its power-up state.
    pub fn new() -> Self {
        Self::default()
    }

    /// One edge with these inputs; returns (status, irq) after it.
    pub fn step(
        &mut self,
        reset: bool,
        events: u64,
        clear: Option<u64>,
        enable: u64,
    ) -> (u64, bool) {
        let irq = self.status & enable != 0;
        let kept = match clear {
            Some(bits) => self.status & !bits,
            None => self.status,
        };
        self.status = kept | events;
        self.irq = irq;
        if reset {
            *self = Self::new();
        }
        (self.status, self.irq)
    }
}

crate::lockstep_model!(InterruptControllerModel {
    inputs: InterruptControllerInputs,
    outputs: InterruptControllerOutputs,
    step: |model, i| {
        let clear = i.clear.then_some(i.clear_bits);
        let (status, irq) = model.step(i.reset, i.events, clear, i.enable);
        InterruptControllerOutputs { status, irq }
    },
});
