//! The DSP's half of an analog servo axis (#18): a velocity-mode position
//! loop that turns the commanded position and the encoder count into a DAC
//! code each period. The simulated servo it closes the loop through (an
//! analog velocity drive and a motor, turning the DAC voltage back into
//! encoder counts) is a plant model: [`crate::sim::plant::ServoMotor`].
//!
//! Units are the drive's: positions in encoder counts, velocities in
//! counts/s, the drive's gain in counts/s per volt. The loop's output is a
//! velocity command; the drive scale turns it into volts and the DAC scale
//! into a signed code (two's complement, as `dac_interface`'s `CODE`
//! registers take it; 0 is 0 V).
//!
//! ```text
//! commanded ──┬─ kff · velocity ────────────────┐
//!             └─(+)─ error ─ kp, ki, kd ─(+)────┴─> counts/s ─ /drive gain ─> volts ─ DAC code (clamped)
//! encoder ───────(−)
//! ```

/// What is wrong with a servo setting: each names the setting.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ServoError {
    /// A setting is not a finite number in its range.
    #[error("servo setting `{name}` = {value}: {rule}")]
    Setting {
        /// The setting.
        name: &'static str,
        /// Its value.
        value: f64,
        /// The range it must be in.
        rule: &'static str,
    },
}

fn check(name: &'static str, value: f64, rule: &'static str, ok: bool) -> Result<(), ServoError> {
    if value.is_finite() && ok {
        Ok(())
    } else {
        Err(ServoError::Setting { name, value, rule })
    }
}

/// The position loop's gains.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ServoGains {
    /// Proportional: counts/s of velocity command per count of error (1/s).
    pub kp: f64,
    /// Integral: counts/s per count-second of error (1/s²).
    pub ki: f64,
    /// Derivative: counts/s per count/s of error change (s).
    pub kd: f64,
    /// Velocity feed-forward: the share of the commanded velocity sent
    /// straight to the drive (1 = all of it).
    pub kff: f64,
}

impl Default for ServoGains {
    /// A stiff loop for the default [`crate::sim::ServoMotor`] at a 1 ms period.
    fn default() -> Self {
        Self {
            kp: 150.0,
            ki: 3000.0,
            kd: 0.0,
            kff: 1.0,
        }
    }
}

/// From velocity command to DAC code.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DriveScale {
    /// The drive's velocity per volt of command, counts/s per V.
    pub counts_per_s_per_volt: f64,
    /// The DAC's full scale, V (the code -2^(W-1) gives -full scale).
    pub full_scale_volts: f64,
    /// The DAC's code width W.
    pub code_bits: u32,
}

impl Default for DriveScale {
    /// An AD669 (±10 V, 16 bits) into a drive of 10 000 counts/s per volt.
    fn default() -> Self {
        Self {
            counts_per_s_per_volt: 10_000.0,
            full_scale_volts: 10.0,
            code_bits: 16,
        }
    }
}

impl DriveScale {
    /// The signed code for `volts`, clamped to the DAC's range; and whether
    /// it was clamped.
    pub fn code(&self, volts: f64) -> (i64, bool) {
        let half = 1i64 << (self.code_bits - 1);
        let ideal = (volts / self.full_scale_volts * half as f64).round();
        let code = ideal.clamp(-(half as f64), (half - 1) as f64) as i64;
        (code, code as f64 != ideal)
    }

    /// The voltage of signed `code`.
    pub fn volts(&self, code: i64) -> f64 {
        code as f64 / (1i64 << (self.code_bits - 1)) as f64 * self.full_scale_volts
    }

    /// `code` as the W-bit pattern a `CODE` register takes.
    pub fn register_value(&self, code: i64) -> u32 {
        (code as u64 & ((1u64 << self.code_bits) - 1)) as u32
    }
}

/// One period's result of the loop.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LoopOutput {
    /// Commanded minus measured position, counts.
    pub following_error: f64,
    /// The DAC code (signed).
    pub code: i64,
    /// The code was clamped at the DAC's range.
    pub saturated: bool,
}

/// The velocity-mode position loop, run once per period.
#[derive(Clone, Debug)]
pub struct PositionLoop {
    gains: ServoGains,
    scale: DriveScale,
    period_s: f64,
    integral: f64,
    last_error: Option<f64>,
}

impl PositionLoop {
    /// A loop at rest, run every `period_s` seconds.
    pub fn new(gains: ServoGains, scale: DriveScale, period_s: f64) -> Result<Self, ServoError> {
        check("kp", gains.kp, "0 or more (1/s)", gains.kp >= 0.0)?;
        check("ki", gains.ki, "0 or more (1/s²)", gains.ki >= 0.0)?;
        check("kd", gains.kd, "0 or more (s)", gains.kd >= 0.0)?;
        check("kff", gains.kff, "0 to 2", (0.0..=2.0).contains(&gains.kff))?;
        check(
            "counts_per_s_per_volt",
            scale.counts_per_s_per_volt,
            "not 0 (counts/s per V; negative for a reversed drive)",
            scale.counts_per_s_per_volt != 0.0,
        )?;
        check(
            "full_scale_volts",
            scale.full_scale_volts,
            "above 0 (V)",
            scale.full_scale_volts > 0.0,
        )?;
        check(
            "code_bits",
            scale.code_bits as f64,
            "2 to 32",
            (2..=32).contains(&scale.code_bits),
        )?;
        check("period_s", period_s, "above 0 (s)", period_s > 0.0)?;
        Ok(Self {
            gains,
            scale,
            period_s,
            integral: 0.0,
            last_error: None,
        })
    }

    /// New gains from the next period on (a schedule); the integral is
    /// kept.
    pub fn set_gains(&mut self, gains: ServoGains) {
        self.gains = gains;
    }

    /// One period: the commanded position and velocity (counts, counts/s)
    /// and the encoder count give the DAC code. The integral is held while
    /// the output is clamped (no wind-up).
    pub fn step(&mut self, commanded: f64, commanded_velocity: f64, measured: i64) -> LoopOutput {
        let g = self.gains;
        let error = commanded - measured as f64;
        let rate = self
            .last_error
            .map_or(0.0, |last| (error - last) / self.period_s);
        self.last_error = Some(error);
        let integral = self.integral + error * self.period_s;
        let velocity = g.kff * commanded_velocity + g.kp * error + g.ki * integral + g.kd * rate;
        let (code, saturated) = self.scale.code(velocity / self.scale.counts_per_s_per_volt);
        if !saturated {
            self.integral = integral;
        }
        LoopOutput {
            following_error: error,
            code,
            saturated,
        }
    }
}

/// Following-error figures of a run, in counts.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FollowingError {
    /// Largest magnitude.
    pub max: f64,
    /// Root mean square over the periods.
    pub rms: f64,
    /// Periods counted.
    pub periods: u64,
    sum_squares: f64,
}

impl FollowingError {
    /// Adds one period's error.
    pub fn add(&mut self, error: f64) {
        self.max = self.max.max(error.abs());
        self.sum_squares += error * error;
        self.periods += 1;
        self.rms = (self.sum_squares / self.periods as f64).sqrt();
    }
}
