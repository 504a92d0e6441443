//! Reference model of [`super::GlitchFilter`], cycle-exact.

/// Plain-Rust model of one glitch filter.
#[derive(Clone, Debug, Default)]
pub struct GlitchFilterModel {
    filtered: bool,
    /// Consecutive samples of a level different from `filtered` so far.
    run: u8,
    /// The threshold taken when the current run began.
    length: u8,
    changed: bool,
}

impl GlitchFilterModel {
    /// A filter in its power-up state.
    pub fn new() -> Self {
        Self::default()
    }

    /// The accepted level.
    pub fn filtered(&self) -> bool {
        self.filtered
    }

    /// `filtered` changed at the last edge.
    pub fn changed(&self) -> bool {
        self.changed
    }

    /// Whether the edge with these inputs will accept a change.
    pub fn accepts(&self, raw: bool, sample: bool, prime: bool) -> bool {
        !prime && sample && raw != self.filtered && self.run + 1 >= self.length
    }

    /// One rising edge. Returns whether it accepted a change.
    pub fn step(&mut self, reset: bool, raw: bool, sample: bool, length: u8, prime: bool) -> bool {
        let accept = self.accepts(raw, sample, prime);
        if reset {
            *self = Self::new();
        } else if prime || (sample && (raw == self.filtered || accept)) {
            self.filtered = raw;
            self.run = 0;
            self.length = length & 15;
        } else if sample {
            self.run += 1;
        }
        self.changed = accept && !reset;
        accept
    }
}
