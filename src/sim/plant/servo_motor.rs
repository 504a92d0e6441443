//! A simulated analog servo axis: a velocity drive and a motor with an
//! encoder, the plant that the host's position loop ([`crate::host::servo`])
//! closes through the DAC and the quadrature decoder.

/// A simulated analog servo: a velocity drive (first-order lag towards its
/// gain times the command voltage, within its velocity and acceleration
/// limits: the motor's torque over its inertia) turning a motor with an
/// encoder.
#[derive(Clone, Debug)]
pub struct ServoMotor {
    /// The drive's gain, counts/s per V.
    pub counts_per_s_per_volt: f64,
    /// The velocity loop's time constant, s.
    pub time_constant_s: f64,
    /// Highest speed, counts/s.
    pub max_velocity: f64,
    /// Highest acceleration (peak torque / inertia), counts/s².
    pub max_acceleration: f64,
    position: f64,
    velocity: f64,
}

impl Default for ServoMotor {
    /// 10 000 counts/s per V, 2 ms, ±100 000 counts/s, 2·10^6 counts/s².
    fn default() -> Self {
        Self::new(10_000.0, 0.002, 100_000.0, 2.0e6)
    }
}

impl ServoMotor {
    /// A motor at rest at count 0.
    pub fn new(
        counts_per_s_per_volt: f64,
        time_constant_s: f64,
        max_velocity: f64,
        max_acceleration: f64,
    ) -> Self {
        Self {
            counts_per_s_per_volt,
            time_constant_s,
            max_velocity,
            max_acceleration,
            position: 0.0,
            velocity: 0.0,
        }
    }

    /// `seconds` under a steady command of `volts`.
    pub fn advance(&mut self, volts: f64, seconds: f64) {
        let target =
            (volts * self.counts_per_s_per_volt).clamp(-self.max_velocity, self.max_velocity);
        // Steps short against the time constant, so the lag is integrated
        // accurately whatever the caller's step.
        let steps = (seconds / (self.time_constant_s / 20.0)).ceil().max(1.0) as u32;
        let dt = seconds / steps as f64;
        for _ in 0..steps {
            let wanted = (target - self.velocity) / self.time_constant_s;
            let acceleration = wanted.clamp(-self.max_acceleration, self.max_acceleration);
            let velocity = self.velocity + acceleration * dt;
            self.position += 0.5 * (self.velocity + velocity) * dt;
            self.velocity = velocity;
        }
    }

    /// The encoder's count (whole counts passed).
    pub fn counts(&self) -> i64 {
        self.position.floor() as i64
    }

    /// The speed, counts/s.
    pub fn velocity(&self) -> f64 {
        self.velocity
    }
}
