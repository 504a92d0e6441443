//! A simulated quadrature encoder on a step/dir output, for loopback
//! benches: the motor turns one encoder count per step.

/// The quadrature (A, B) levels after `phase` forward steps from 00:
/// 00 -> 10 -> 11 -> 01 -> 00 (A leads B going forward).
pub fn quadrature_state(phase: i64) -> (bool, bool) {
    [(false, false), (true, false), (true, true), (false, true)][phase.rem_euclid(4) as usize]
}

/// Follows step/dir pins: each rising edge of the step pin moves the
/// encoder one Gray state (one count of a 4x decoder) in the direction of
/// the dir pin. Its A/B outputs change in the clock after the step edge is
/// seen. It also counts the net steps it saw, an independent count of what
/// left the pins.
#[derive(Clone, Copy, Debug, Default)]
pub struct SimulatedEncoder {
    state: u8,
    last_step: bool,
    /// Net steps seen on the pins.
    pub net: i64,
    /// Steps seen in either direction.
    pub total: u64,
}

impl SimulatedEncoder {
    /// The encoder's pins now: (a, b, index).
    pub fn outputs(&self) -> (bool, bool, bool) {
        let (a, b) = quadrature_state(self.state as i64);
        (a, b, false)
    }

    /// Watches the step/dir pins after an edge; returns (a, b, index).
    pub fn follow(&mut self, (step, dir): (bool, bool)) -> (bool, bool, bool) {
        if step && !self.last_step {
            self.state = if dir {
                (self.state + 1) % 4
            } else {
                (self.state + 3) % 4
            };
            self.net += if dir { 1 } else { -1 };
            self.total += 1;
        }
        self.last_step = step;
        self.outputs()
    }
}
