//! Reference model of [`super::Watchdog`], cycle-exact.

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
