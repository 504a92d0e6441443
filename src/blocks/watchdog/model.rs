//! Reference model of [`super::Watchdog`], cycle-exact.

/// Inputs of one clock cycle.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct WatchdogInputs {
    /// Synchronous reset.
    pub reset: bool,
    /// Time base tick.
    pub tick: bool,
    /// Ticks from a kick to expiry; 0 disarms.
    pub timeout: u64,
    /// Re-arms with `timeout`.
    pub kick: bool,
    /// Clears `expired`.
    pub clear: bool,
}

impl WatchdogInputs {
    /// The RTL's input vector, in its port order.
    pub fn to_vector(&self) -> Vec<u64> {
        vec![
            self.reset as u64,
            self.tick as u64,
            self.timeout,
            self.kick as u64,
            self.clear as u64,
        ]
    }
}

/// Outputs after one clock edge.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct WatchdogOutputs {
    /// Sticky: the timeout ran out.
    pub expired: bool,
    /// Counting towards an expiry.
    pub armed: bool,
}

impl WatchdogOutputs {
    /// Reads the RTL's output vector, in its port order.
    pub fn from_vector(v: &[u64]) -> Self {
        Self {
            expired: v[0] != 0,
            armed: v[1] != 0,
        }
    }
}

/// Model of the watchdog.
#[derive(Clone, Debug, Default)]
pub struct WatchdogModel {
    /// Ticks left while armed.
    left: Option<u64>,
    expired: bool,
}

impl WatchdogModel {
    /// A watchdog in its power-up state (disarmed).
    pub fn new() -> Self {
        Self::default()
    }

    /// One edge; returns (expired, armed) after it.
    pub fn step(
        &mut self,
        reset: bool,
        tick: bool,
        timeout: u64,
        kick: bool,
        clear: bool,
    ) -> (bool, bool) {
        if clear {
            self.expired = false;
        }
        if kick {
            self.left = (timeout != 0).then_some(timeout);
        } else if let (true, Some(left)) = (tick, self.left) {
            if left == 1 {
                self.expired = true;
                self.left = None;
            } else {
                self.left = Some(left - 1);
            }
        }
        if reset {
            *self = Self::new();
        }
        (self.expired, self.left.is_some())
    }
}

crate::lockstep_model!(WatchdogModel {
    inputs: WatchdogInputs,
    outputs: WatchdogOutputs,
    step: |model, i| {
        let (expired, armed) = model.step(i.reset, i.tick, i.timeout, i.kick, i.clear);
        WatchdogOutputs { expired, armed }
    },
});
