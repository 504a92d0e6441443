//! Reference model of [`super::InterruptController`], cycle-exact.

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
