//! A hexapod's geometry, from a small file or the defaults, and the check
//! that a pose is one the machine can take.
//!
//! ## Geometry file
//! The settings files' format (one statement a line, `#` a comment); any
//! statement left out keeps its default:
//!
//! ```text
//! base 0 -582.93 336.55 0      # leg 0's base joint, base frame, mm
//! platform 0 -25.4 292.1 0     # leg 0's platform joint, platform frame, mm
//! stroke 600 950               # every leg's length, mm, shortest and longest
//! leg_speed 500                # every leg's speed limit, mm/s
//! limit z 300 700              # the workspace along an axis: x y z mm, a b c degrees
//! home 0 0 508 0 0 0           # the pose at power-up: X Y Z mm, A B C degrees
//! condition_limit 1000         # the largest Jacobian condition number accepted
//! ```
//!
//! | statement | default | meaning |
//! |---|---|---|
//! | `base N X Y Z` | genhexkins's, in mm (below) | leg N's (0 to 5) base joint, base frame |
//! | `platform N X Y Z` | genhexkins's, in mm | leg N's platform joint, platform frame |
//! | `stroke MIN MAX` | 600 950 | every leg's length range, mm |
//! | `leg_speed V` | 500 | every leg's speed limit, mm/s |
//! | `limit AXIS MIN MAX` | x, y ±200; z 300 to 700; a, b, c ±20 | the workspace: a pose outside is refused |
//! | `home X Y Z A B C` | 0 0 508 0 0 0 | the pose at power-up |
//! | `condition_limit K` | 1000 | near-singular above this (see [`check_pose`]) |
//!
//! The defaults are LinuxCNC's genhexkins defaults and its vismach
//! hexapod-sim machine (inch; home Z 20 in, legs 29.7466 in at home) in
//! mm: base joints in pairs on a 26.5 in circle, platform joints on an
//! 11.5 in circle. The stroke, leg speed, workspace and condition limit are
//! ours (genhexkins has none): at home every leg is 755.56 mm.

use thiserror::Error;

use super::kinematics::{inverse, twist_jacobian, Pose};
use super::linear;
use crate::host::path::PathError;
use crate::host::statements::statements;

/// A platform's joints, its legs' limits and its workspace, mm and
/// degrees.
#[derive(Clone, Debug, PartialEq)]
pub struct Geometry {
    /// Each leg's base joint, base frame, mm.
    pub base: [[f64; 3]; 6],
    /// Each leg's platform joint, platform frame, mm.
    pub platform: [[f64; 3]; 6],
    /// Every leg's shortest and longest length, mm.
    pub stroke: [f64; 2],
    /// Every leg's speed limit, mm/s.
    pub leg_speed: f64,
    /// The workspace: X, Y, Z (mm) and A, B, C (degrees), min and max.
    pub limits: [[f64; 2]; 6],
    /// The pose at power-up.
    pub home: Pose,
    /// The largest condition number of the scaled twist Jacobian accepted.
    pub condition_limit: f64,
}

const INCH: f64 = 25.4;

impl Default for Geometry {
    fn default() -> Self {
        let base = [
            [-22.950, 13.250, 0.0],
            [22.950, 13.250, 0.0],
            [22.950, 13.250, 0.0],
            [0.0, -26.500, 0.0],
            [0.0, -26.500, 0.0],
            [-22.950, 13.250, 0.0],
        ];
        let platform = [
            [-1.000, 11.500, 0.0],
            [1.000, 11.500, 0.0],
            [10.459, -4.884, 0.0],
            [9.459, -6.616, 0.0],
            [-9.459, -6.616, 0.0],
            [-10.459, -4.884, 0.0],
        ];
        let mm = |joints: [[f64; 3]; 6]| joints.map(|j| j.map(|v| v * INCH));
        Geometry {
            base: mm(base),
            platform: mm(platform),
            stroke: [600.0, 950.0],
            leg_speed: 500.0,
            limits: [
                [-200.0, 200.0],
                [-200.0, 200.0],
                [300.0, 700.0],
                [-20.0, 20.0],
                [-20.0, 20.0],
                [-20.0, 20.0],
            ],
            home: Pose {
                position: [0.0, 0.0, 20.0 * INCH],
                angles: [0.0; 3],
            },
            condition_limit: 1000.0,
        }
    }
}

/// A pose the machine cannot take.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum PoseError {
    #[error("{axis} {value} is outside the workspace, {min} to {max}")]
    OutsideWorkspace {
        axis: char,
        value: f64,
        min: f64,
        max: f64,
    },
    #[error("leg {leg} would be {length:.3} mm long, beyond its stroke of {min} to {max} mm")]
    LegBeyondStroke {
        leg: usize,
        length: f64,
        min: f64,
        max: f64,
    },
    #[error("the pose is singular or nearly: the Jacobian's condition number is {condition:.3e}, above the limit of {limit}")]
    NearSingular { condition: f64, limit: f64 },
}

const AXES: [char; 6] = ['X', 'Y', 'Z', 'A', 'B', 'C'];

/// The condition number (1-norm) of the twist Jacobian with its angular
/// columns divided by the platform's radius (its farthest joint from its
/// origin), so that every column is dimensionless.
pub fn condition(geometry: &Geometry, pose: &Pose) -> f64 {
    let radius = geometry
        .platform
        .iter()
        .map(|p| p.iter().map(|v| v * v).sum::<f64>().sqrt())
        .fold(0.0, f64::max);
    let mut j = twist_jacobian(geometry, pose);
    for row in &mut j {
        for v in &mut row[3..] {
            *v /= radius;
        }
    }
    linear::condition(&j)
}

/// The legs' lengths at `pose` if the machine can take it: within the
/// workspace, every leg within its stroke, and the scaled Jacobian's
/// condition number ([`condition`]) at most `condition_limit`.
pub fn check_pose(geometry: &Geometry, pose: &Pose) -> Result<[f64; 6], PoseError> {
    let values = [pose.position, pose.angles].concat();
    for (k, &value) in values.iter().enumerate() {
        let [min, max] = geometry.limits[k];
        if !(min..=max).contains(&value) {
            return Err(PoseError::OutsideWorkspace {
                axis: AXES[k],
                value,
                min,
                max,
            });
        }
    }
    let legs = inverse(geometry, pose);
    let [min, max] = geometry.stroke;
    if let Some((leg, &length)) = legs
        .iter()
        .enumerate()
        .find(|(_, l)| !(min..=max).contains(*l))
    {
        return Err(PoseError::LegBeyondStroke {
            leg,
            length,
            min,
            max,
        });
    }
    let condition = condition(geometry, pose);
    if condition.is_nan() || condition > geometry.condition_limit {
        return Err(PoseError::NearSingular {
            condition,
            limit: geometry.condition_limit,
        });
    }
    Ok(legs)
}

/// Whether `points` span a plane (are not all on one line), within
/// 1e-6 of their extent squared.
fn span_a_plane(points: &[[f64; 3]; 6]) -> bool {
    let extent = points
        .iter()
        .flat_map(|p| {
            points
                .iter()
                .map(move |q| (0..3).map(|k| (p[k] - q[k]).powi(2)).sum::<f64>())
        })
        .fold(0.0, f64::max);
    let o = points[0];
    points.iter().any(|p| {
        points.iter().any(|q| {
            let (u, v) = (
                [0, 1, 2].map(|k| p[k] - o[k]),
                [0, 1, 2].map(|k| q[k] - o[k]),
            );
            let c = [
                u[1] * v[2] - u[2] * v[1],
                u[2] * v[0] - u[0] * v[2],
                u[0] * v[1] - u[1] * v[0],
            ];
            (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt() > 1e-6 * extent
        })
    })
}

impl Geometry {
    /// Whether the geometry describes a platform that works: joints that
    /// span a plane on the base and on the platform, a stroke and a speed
    /// above 0, limits in order (A, B, C within ±90°), and a home pose the
    /// machine can take.
    pub fn validate(&self) -> Result<(), String> {
        if !span_a_plane(&self.base) {
            return Err(
                "the base joints are on one line: the platform would turn freely about it".into(),
            );
        }
        if !span_a_plane(&self.platform) {
            return Err(
                "the platform joints are on one line: the platform would turn freely about it"
                    .into(),
            );
        }
        let [min, max] = self.stroke;
        if !(min > 0.0 && max > min) {
            return Err(format!(
                "stroke {min} {max}: the shortest leg must be above 0 and below the longest"
            ));
        }
        if self.leg_speed <= 0.0 {
            return Err(format!("leg_speed {}: a speed above 0", self.leg_speed));
        }
        for (k, [min, max]) in self.limits.iter().enumerate() {
            if min >= max {
                return Err(format!(
                    "limit {} {min} {max}: the minimum must be below the maximum",
                    AXES[k].to_ascii_lowercase()
                ));
            }
            if k >= 3 && (*min < -90.0 || *max > 90.0) {
                return Err(format!("limit {} {min} {max}: angles within ±90 degrees (B = ±90 is the angles' own singularity)", AXES[k].to_ascii_lowercase()));
            }
        }
        if self.condition_limit <= 1.0 {
            return Err(format!("condition_limit {}: above 1", self.condition_limit));
        }
        check_pose(self, &self.home)
            .map(|_| ())
            .map_err(|e| format!("home: {e}"))
    }

    /// Reads a geometry file (see the [module documentation](self)) over
    /// the defaults; every error names the line, or the setting for a
    /// platform that does not work.
    pub fn parse(text: &str) -> Result<Self, PathError> {
        let mut geometry = Self::default();
        for statement in statements(text) {
            let numbers = || statement.numbers();
            let leg = |n: f64| -> Result<usize, PathError> {
                (0..6)
                    .find(|&i| i as f64 == n)
                    .ok_or_else(|| statement.error(format!("leg `{n}`: legs are 0 to 5")))
            };
            match statement.keyword {
                "base" => {
                    let [n, x, y, z] = numbers()?.exactly()?;
                    geometry.base[leg(n)?] = [x, y, z];
                }
                "platform" => {
                    let [n, x, y, z] = numbers()?.exactly()?;
                    geometry.platform[leg(n)?] = [x, y, z];
                }
                "stroke" => geometry.stroke = numbers()?.exactly()?,
                "leg_speed" => [geometry.leg_speed] = numbers()?.exactly()?,
                "condition_limit" => [geometry.condition_limit] = numbers()?.exactly()?,
                "home" => {
                    let [x, y, z, a, b, c] = numbers()?.exactly()?;
                    geometry.home = Pose {
                        position: [x, y, z],
                        angles: [a, b, c],
                    };
                }
                "limit" => {
                    let axis = statement.words.first().copied().unwrap_or("");
                    let k = AXES
                        .iter()
                        .position(|a| a.to_ascii_lowercase().to_string() == axis)
                        .ok_or_else(|| statement.error(format!("limit `{axis}`: an axis x, y, z, a, b or c")))?;
                    let rest: Vec<f64> = statement.words[1..]
                        .iter()
                        .map(|w| w.parse::<f64>().ok().filter(|v| v.is_finite()))
                        .collect::<Option<_>>()
                        .ok_or_else(|| statement.error("limit AXIS MIN MAX: two numbers after the axis".into()))?;
                    let [min, max] = <[f64; 2]>::try_from(rest)
                        .map_err(|_| statement.error("limit AXIS MIN MAX: two numbers after the axis".into()))?;
                    geometry.limits[k] = [min, max];
                }
                other => {
                    return Err(statement.error(format!(
                        "unknown setting `{other}` (base, platform, stroke, leg_speed, limit, home, condition_limit)"
                    )))
                }
            }
        }
        geometry.validate().map_err(PathError::Invalid)?;
        Ok(geometry)
    }
}
