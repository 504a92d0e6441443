//! A simulated spindle for threading runs: its speed follows the speed
//! commanded (S, with M3 or M4) with a first-order lag, carries a
//! sinusoidal speed ripple and dips under load, and its encoder drives the
//! controller's `spindle_a`, `spindle_b` and `spindle_index` pins.
//!
//! The encoder has `counts_per_rev` quadrature counts per revolution (a
//! 1024-line encoder is 4096 counts); its index pin is high for the one
//! count where the position is a whole number of revolutions. M3
//! (clockwise) counts up.

use super::encoder::quadrature_state;

/// A spindle motor and its encoder.
#[derive(Clone, Debug, PartialEq)]
pub struct SpindleMotor {
    /// Quadrature counts per revolution.
    pub counts_per_rev: u32,
    /// The speed ripple's amplitude, a fraction of the speed (0.1: ±10 %).
    pub ripple: f64,
    /// The ripple's frequency, Hz.
    pub ripple_hz: f64,
    /// How far the speed falls under load, a fraction (0.05: 5 %).
    pub load_dip: f64,
    /// The speed's time constant, seconds (also the load dip's).
    pub time_constant_s: f64,
    /// Speed commanded, rpm, signed (+: M3, counting up).
    command_rpm: f64,
    /// Speed without the ripple, rpm, signed.
    speed_rpm: f64,
    loaded: bool,
    /// Position, counts, from power-up.
    position: f64,
    time_s: f64,
}

impl Default for SpindleMotor {
    /// A 1024-line encoder (4096 counts), ±10 % ripple at 7 Hz, a 5 % dip
    /// under load, a 50 ms time constant, stopped.
    fn default() -> Self {
        Self::new(4096)
    }
}

impl SpindleMotor {
    /// A stopped spindle with the default ripple, dip and time constant
    /// and an encoder of `counts_per_rev` counts.
    pub fn new(counts_per_rev: u32) -> Self {
        Self {
            counts_per_rev,
            ripple: 0.1,
            ripple_hz: 7.0,
            load_dip: 0.05,
            time_constant_s: 0.05,
            command_rpm: 0.0,
            speed_rpm: 0.0,
            loaded: false,
            position: 0.5,
            time_s: 0.0,
        }
    }

    /// Commands `rpm` (signed: + for M3).
    pub fn command(&mut self, rpm: f64) {
        self.command_rpm = rpm;
    }

    /// The speed commanded, rpm, signed.
    pub fn commanded_rpm(&self) -> f64 {
        self.command_rpm
    }

    /// Puts the cutting load on (true) or takes it off.
    pub fn set_load(&mut self, loaded: bool) {
        self.loaded = loaded;
    }

    /// The speed now, rpm, signed, ripple included.
    pub fn speed_rpm(&self) -> f64 {
        let ripple = (std::f64::consts::TAU * self.ripple_hz * self.time_s).sin();
        self.speed_rpm * (1.0 + self.ripple * ripple)
    }

    /// Advances `dt` seconds.
    pub fn advance(&mut self, dt: f64) {
        let target = match self.loaded {
            true => self.command_rpm * (1.0 - self.load_dip),
            false => self.command_rpm,
        };
        let k = (dt / self.time_constant_s).min(1.0);
        self.speed_rpm += (target - self.speed_rpm) * k;
        self.position += self.speed_rpm() / 60.0 * self.counts_per_rev as f64 * dt;
        self.time_s += dt;
    }

    /// The encoder's count: whole counts from power-up.
    pub fn count(&self) -> i64 {
        self.position.floor() as i64
    }

    /// The encoder's pins: (a, b, index).
    pub fn pins(&self) -> (bool, bool, bool) {
        let count = self.count();
        let (a, b) = quadrature_state(count);
        (a, b, count.rem_euclid(self.counts_per_rev as i64) == 0)
    }
}
