//! Machine settings: what the planner needs to know about the machine a
//! G-code program runs on, from a small settings file or the defaults.
//!
//! ## Settings file
//! Plain text, one setting per line, `#` starts a comment; any setting left
//! out keeps its default:
//!
//! ```text
//! steps_per_mm 100 100 400     # X Y Z
//! max_velocity 50 50 20        # mm/s per axis (G0 runs at these)
//! max_accel 500 500 200        # mm/s^2 per axis
//! contour_error 0.01           # mm: corner deviation and arc chord error
//! period_us 1000               # interpolation period T
//! parameter 5221 100.0         # G54's X origin, machine mm (LinuxCNC's #5221)
//! spindle_encoder 4096          # spindle encoder counts per revolution (0: none)
//! laser_s_max 1000              # a laser machine: S1000 is full power (0: no laser)
//! laser_pwm_us 200              # the laser's PWM period, microseconds
//! ```
//!
//! | setting | default | meaning |
//! |---|---|---|
//! | `steps_per_mm` | 100 100 400 | steps (encoder counts) per mm, X Y Z |
//! | `max_velocity` | 50 50 20 | per-axis speed limit, mm/s (3000/3000/1200 mm/min) |
//! | `max_accel` | 500 500 200 | per-axis acceleration limit, mm/s^2 |
//! | `contour_error` | 0.01 | mm: how far a corner is rounded, and the chord error of an arc's per-period chords |
//! | `period_us` | 1000 | interpolation period T, microseconds |
//! | `spindle_encoder` | 4096 | the spindle encoder's quadrature counts per revolution (a 1024-line encoder), for G33, G33.1 and G76; 0: the machine has none, and they are refused |
//! | `laser_s_max` | 0 | a laser machine: the S of full laser power. M3 and M4 then burn at S over it on feed moves and dwells (M4 scaled in gateware by the path speed), rapids run with the laser off, and an S above it is an error; it runs on `motion_controller_dda_laser` with the laser's plane X and Y. 0: no laser, S is a spindle speed |
//! | `laser_pwm_us` | 200 | the laser's PWM period, microseconds (5 kHz); at the simulated clock it must be 1 to 65535 clocks |
//! | `parameter N V` | see [`PersistentParameters`] | a G-code parameter LinuxCNC keeps between runs (#5161 to #5390: G28 and G30 positions, G92 offset, active coordinate system, G54 to G59.3 origins), mm; repeatable |
//!
//! The defaults are a small stepper mill: 1.8 degree motors at 1/8
//! microstep on 16 mm-lead (X, Y) and 4 mm-lead (Z) screws.

/// The machine's axis letters: axis k is `AXIS_LETTERS[k]`.
pub const AXIS_LETTERS: [char; 3] = ['X', 'Y', 'Z'];

/// The index of the axis named `name` (`x`, `y` or `z`, either case), as
/// command-line options name them; `None` for any other name.
pub fn axis_index(name: &str) -> Option<usize> {
    let mut chars = name.chars();
    match (chars.next(), chars.next()) {
        (Some(c), None) => AXIS_LETTERS.iter().position(|l| l.eq_ignore_ascii_case(&c)),
        _ => None,
    }
}

use super::gcode::PersistentParameters;
use super::path::PathError;
use super::statements::statements;

/// The finest resolution accepted: a nanometre a step.
pub const MAX_STEPS_PER_MM: f64 = 1e6;

/// The machine's limits and resolution, in mm and seconds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MachineSettings {
    /// Steps per mm, X Y Z.
    pub steps_per_mm: [f64; 3],
    /// Per-axis maximum velocity, mm/s (infinite: no limit).
    pub max_velocity: [f64; 3],
    /// Per-axis maximum acceleration, mm/s^2 (infinite: no limit).
    pub max_accel: [f64; 3],
    /// Maximum path acceleration, mm/s^2, beside the per-axis ones
    /// (infinite for G-code: only the axes limit; a `.path` file's `accel`).
    pub path_accel: f64,
    /// Contour error, mm: corner deviation and arc chord error.
    pub contour_error: f64,
    /// Interpolation period, seconds.
    pub period: f64,
    /// The G-code parameters kept between runs (#5161 to #5390), mm.
    pub parameters: PersistentParameters,
    /// The spindle encoder's counts per revolution (0: no encoder).
    pub spindle_counts_per_rev: u32,
    /// A laser machine's full-power S; 0: no laser.
    pub laser_s_max: f64,
    /// The laser's PWM period, seconds.
    pub laser_pwm_period: f64,
}

impl Default for MachineSettings {
    fn default() -> Self {
        Self {
            steps_per_mm: [100.0, 100.0, 400.0],
            max_velocity: [50.0, 50.0, 20.0],
            max_accel: [500.0, 500.0, 200.0],
            path_accel: f64::INFINITY,
            contour_error: 0.01,
            period: 1e-3,
            parameters: PersistentParameters::default(),
            spindle_counts_per_rev: 4096,
            laser_s_max: 0.0,
            laser_pwm_period: 200e-6,
        }
    }
}

impl MachineSettings {
    /// Checks every setting: resolutions, velocities and accelerations
    /// positive (infinite allowed for the limits, but some acceleration
    /// limit must be finite), the contour error 0 or positive, the period
    /// positive.
    pub fn validate(&self) -> Result<(), PathError> {
        let invalid = |message: String| Err(PathError::Invalid(message));
        if let Some(k) = (0..3).find(|&k| self.steps_per_mm[k] > MAX_STEPS_PER_MM) {
            return invalid(format!(
                "steps_per_mm for {} is {}, beyond {MAX_STEPS_PER_MM} (a nanometre a step)",
                ["X", "Y", "Z"][k],
                self.steps_per_mm[k]
            ));
        }
        for (name, values, infinite_ok) in [
            ("steps_per_mm", self.steps_per_mm, false),
            ("max_velocity", self.max_velocity, true),
            ("max_accel", self.max_accel, true),
        ] {
            for (axis, v) in ["X", "Y", "Z"].iter().zip(values) {
                if !(v > 0.0 && (v.is_finite() || (infinite_ok && v == f64::INFINITY))) {
                    return invalid(format!(
                        "{name} for {axis} must be a positive number, not {v}"
                    ));
                }
            }
        }
        if self.path_accel.is_nan() || self.path_accel <= 0.0 {
            return invalid(format!(
                "the path acceleration must be positive, not {}",
                self.path_accel
            ));
        }
        if self.max_accel.iter().all(|a| a.is_infinite()) && self.path_accel.is_infinite() {
            return invalid("no acceleration limit: set max_accel".into());
        }
        if !(self.contour_error.is_finite() && self.contour_error >= 0.0) {
            return invalid(format!(
                "contour_error must be 0 or positive, not {}",
                self.contour_error
            ));
        }
        if !(self.period.is_finite() && self.period > 0.0) {
            return invalid(format!("period must be positive, not {} s", self.period));
        }
        if !(self.laser_s_max.is_finite() && self.laser_s_max >= 0.0) {
            return invalid(format!(
                "laser_s_max must be 0 (no laser) or positive, not {}",
                self.laser_s_max
            ));
        }
        if !(self.laser_pwm_period.is_finite() && self.laser_pwm_period > 0.0) {
            return invalid(format!(
                "laser_pwm_us must be positive, not {}",
                self.laser_pwm_period * 1e6
            ));
        }
        Ok(())
    }

    /// The full-power S of a laser machine; `None` without a laser.
    pub fn laser(&self) -> Option<f64> {
        (self.laser_s_max > 0.0).then_some(self.laser_s_max)
    }

    /// Reads a settings file (see the [module documentation](self)) over
    /// the defaults; every error names the line.
    pub fn parse(text: &str) -> Result<Self, PathError> {
        let mut settings = Self::default();
        for statement in statements(text) {
            let numbers = statement.numbers()?;
            match statement.keyword {
                "steps_per_mm" => settings.steps_per_mm = numbers.exactly()?,
                "max_velocity" => settings.max_velocity = numbers.exactly()?,
                "max_accel" => settings.max_accel = numbers.exactly()?,
                "contour_error" => [settings.contour_error] = numbers.exactly()?,
                "period_us" => settings.period = numbers.exactly::<1>()?[0] * 1e-6,
                "laser_s_max" => [settings.laser_s_max] = numbers.exactly()?,
                "laser_pwm_us" => {
                    settings.laser_pwm_period = numbers.exactly::<1>()?[0] * 1e-6
                }
                "spindle_encoder" => {
                    let [n] = numbers.exactly()?;
                    settings.spindle_counts_per_rev = u32::try_from(n as i64)
                        .ok()
                        .filter(|&whole| f64::from(whole) == n && whole <= 1 << 24)
                        .ok_or_else(|| {
                            statement.error(format!(
                                "spindle_encoder `{n}` is not a count per revolution: a whole number from 0 to 16777216"
                            ))
                        })?;
                }
                "parameter" => {
                    let [n, value] = numbers.exactly()?;
                    let n = u32::try_from(n as i64)
                        .ok()
                        .filter(|&whole| f64::from(whole) == n)
                        .ok_or_else(|| statement.error(format!("parameter `{n}` is not a parameter number")))?;
                    settings
                        .parameters
                        .set(n, value)
                        .map_err(|e| statement.error(e))?;
                }
                other => {
                    return Err(statement.error(format!(
                        "unknown setting `{other}` (steps_per_mm, max_velocity, max_accel, contour_error, period_us, parameter, spindle_encoder, laser_s_max, laser_pwm_us)"
                    )))
                }
            }
            settings
                .validate()
                .map_err(|e| statement.error(e.to_string()))?;
        }
        Ok(settings)
    }
}
