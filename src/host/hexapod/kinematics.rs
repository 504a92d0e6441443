//! Inverse and forward kinematics of a Stewart-Gough platform (6-UPS),
//! LinuxCNC's genhexkins model: leg i runs from base joint `b_i` (base
//! frame) to platform joint `p_i` (platform frame), and its length is
//! |t + R p_i − b_i| for the platform at position `t` and orientation `R`.

use thiserror::Error;

use super::geometry::Geometry;
use super::linear::{self, Matrix6};

/// Where the platform is: its origin in the base frame, mm, and its
/// orientation as LinuxCNC's A, B, C in degrees, roll about X, pitch about
/// Y and yaw about Z: R = Rz(C) · Ry(B) · Rx(A) (posemath's
/// `pmRpyMatConvert`, which genhexkins uses).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Pose {
    /// X, Y, Z, mm.
    pub position: [f64; 3],
    /// A, B, C, degrees.
    pub angles: [f64; 3],
}

impl Pose {
    /// X, Y, Z in mm and A, B, C in radians: the coordinates the
    /// Jacobian of [`pose_jacobian`] differentiates by.
    pub fn coordinates(&self) -> [f64; 6] {
        let [a, b, c] = self.angles.map(f64::to_radians);
        let [x, y, z] = self.position;
        [x, y, z, a, b, c]
    }

    /// X, Y, Z in mm and A, B, C in degrees: the units of a
    /// [`MotionSample`](super::card::MotionSample).
    pub fn coordinates_degrees(&self) -> [f64; 6] {
        let [x, y, z] = self.position;
        let [a, b, c] = self.angles;
        [x, y, z, a, b, c]
    }

    /// The pose of [`Pose::coordinates_degrees`].
    pub fn from_coordinates_degrees(q: [f64; 6]) -> Self {
        Pose {
            position: [q[0], q[1], q[2]],
            angles: [q[3], q[4], q[5]],
        }
    }

    /// The pose of [`Pose::coordinates`].
    pub fn from_coordinates(q: [f64; 6]) -> Self {
        Pose {
            position: [q[0], q[1], q[2]],
            angles: [q[3], q[4], q[5]].map(f64::to_degrees),
        }
    }
}

/// A forward-kinematics solve that did not end at a pose.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum ForwardError {
    /// A leg length of 0 or less (genhexkins's first check).
    #[error("leg {leg} is {length} mm long: a leg is longer than 0")]
    LegNotPositive { leg: usize, length: f64 },
    /// The Jacobian became singular on the way.
    #[error("forward kinematics met a singular pose after {iterations} iterations")]
    Singular { iterations: u32 },
    /// The summed leg error grew beyond [`ForwardLimits::max_error`].
    #[error("forward kinematics diverged: the legs' summed error reached {error:.3e} mm after {iterations} iterations")]
    Diverged { iterations: u32, error: f64 },
    /// [`ForwardLimits::iterations`] ran out.
    #[error("forward kinematics did not converge in {iterations} iterations: the largest leg error is {error:.3e} mm")]
    NoConvergence { iterations: u32, error: f64 },
}

/// When the Newton-Raphson iteration of [`forward`] stops: genhexkins's
/// limits (`limit-iterations` 120, `convergence-criterion` 1e-9,
/// `max-error` 500 in its sample machine's inches: 12700 mm); the
/// criterion is kept at 1e-9 in mm, 25.4 times tighter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ForwardLimits {
    /// Iterations at most.
    pub iterations: u32,
    /// Converged when every leg is within this of its length, mm.
    pub criterion: f64,
    /// Diverged when the legs' errors sum beyond this, mm.
    pub max_error: f64,
}

impl Default for ForwardLimits {
    fn default() -> Self {
        Self {
            iterations: 120,
            criterion: 1e-9,
            max_error: 12_700.0,
        }
    }
}

/// A converged forward solve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Forward {
    pub pose: Pose,
    /// Newton-Raphson iterations it took.
    pub iterations: u32,
}

/// R = Rz(c) · Ry(b) · Rx(a) for A, B, C in degrees (rows of the matrix).
pub fn rotation(angles: [f64; 3]) -> [[f64; 3]; 3] {
    let [r, p, y] = angles.map(f64::to_radians);
    let (sg, cg) = r.sin_cos();
    let (sb, cb) = p.sin_cos();
    let (sa, ca) = y.sin_cos();
    [
        [ca * cb, ca * sb * sg - sa * cg, ca * sb * cg + sa * sg],
        [sa * cb, sa * sb * sg + ca * cg, sa * sb * cg - ca * sg],
        [-sb, cb * sg, cb * cg],
    ]
}

fn apply(m: &[[f64; 3]; 3], v: [f64; 3]) -> [f64; 3] {
    m.map(|row| row[0] * v[0] + row[1] * v[1] + row[2] * v[2])
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn norm(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

/// Each leg's vector from its base joint to its platform joint, mm.
pub fn leg_vectors(geometry: &Geometry, pose: &Pose) -> [[f64; 3]; 6] {
    let r = rotation(pose.angles);
    std::array::from_fn(|i| {
        let p = apply(&r, geometry.platform[i]);
        [0, 1, 2].map(|k| pose.position[k] + p[k] - geometry.base[i][k])
    })
}

/// The inverse kinematics: each leg's length at `pose`, mm (closed form,
/// always one answer).
pub fn inverse(geometry: &Geometry, pose: &Pose) -> [f64; 6] {
    leg_vectors(geometry, pose).map(norm)
}

/// The twist Jacobian (genhexkins's "inverse Jacobian"): row i is
/// [u_i, (R p_i) × u_i], u_i the leg's unit vector, so that the legs'
/// rates, mm/s, are this times the platform's twist (its origin's
/// velocity, mm/s, and its angular velocity in the base frame, rad/s).
pub fn twist_jacobian(geometry: &Geometry, pose: &Pose) -> Matrix6 {
    let r = rotation(pose.angles);
    let legs = leg_vectors(geometry, pose);
    std::array::from_fn(|i| {
        let length = norm(legs[i]);
        let u = legs[i].map(|v| v / length);
        let arm = cross(apply(&r, geometry.platform[i]), u);
        [u[0], u[1], u[2], arm[0], arm[1], arm[2]]
    })
}

/// The legs' rates, mm/s, for the platform's twist at `pose`: linear
/// velocity, mm/s, then angular velocity in the base frame, rad/s.
pub fn leg_velocities(geometry: &Geometry, pose: &Pose, twist: &[f64; 6]) -> [f64; 6] {
    linear::mul(&twist_jacobian(geometry, pose), twist)
}

/// d(leg lengths) / d(X, Y, Z, A, B, C) with A, B, C in radians: the twist
/// Jacobian times the map from A, B, C rates to angular velocity.
pub fn pose_jacobian(geometry: &Geometry, pose: &Pose) -> Matrix6 {
    let [_, p, y] = pose.angles.map(f64::to_radians);
    let (sp, cp) = p.sin_cos();
    let (sy, cy) = y.sin_cos();
    // ω = Ȧ Rz(C)Ry(B) x̂ + Ḃ Rz(C) ŷ + Ċ ẑ.
    let columns = [[cy * cp, sy * cp, -sp], [-sy, cy, 0.0], [0.0, 0.0, 1.0]];
    let j = twist_jacobian(geometry, pose);
    std::array::from_fn(|i| {
        let mut row = [j[i][0], j[i][1], j[i][2], 0.0, 0.0, 0.0];
        for (k, column) in columns.iter().enumerate() {
            row[3 + k] = (0..3).map(|m| j[i][3 + m] * column[m]).sum();
        }
        row
    })
}

/// The forward kinematics: the pose at which the legs have `lengths`,
/// by Newton-Raphson from `guess` (the nearest solution; a far guess may
/// find another assembly or none). Unlike genhexkins, which steps A, B, C
/// by the angular-velocity solution, each step here solves with
/// [`pose_jacobian`], a true Newton step: it converges in 3 to 5
/// iterations near the pose.
pub fn forward(
    geometry: &Geometry,
    lengths: &[f64; 6],
    guess: &Pose,
    limits: &ForwardLimits,
) -> Result<Forward, ForwardError> {
    if let Some((leg, &length)) = lengths
        .iter()
        .enumerate()
        .find(|(_, l)| l.is_nan() || **l <= 0.0)
    {
        return Err(ForwardError::LegNotPositive { leg, length });
    }
    let mut q = guess.coordinates();
    for iteration in 1..=limits.iterations {
        let pose = Pose::from_coordinates(q);
        let at = inverse(geometry, &pose);
        let diff: [f64; 6] = std::array::from_fn(|i| at[i] - lengths[i]);
        let largest = diff.iter().fold(0.0_f64, |m, d| m.max(d.abs()));
        if largest <= limits.criterion {
            return Ok(Forward {
                pose,
                iterations: iteration - 1,
            });
        }
        let summed: f64 = diff.iter().map(|d| d.abs()).sum();
        if summed.is_nan() || summed > limits.max_error {
            return Err(ForwardError::Diverged {
                iterations: iteration - 1,
                error: summed,
            });
        }
        let step = linear::solve(&pose_jacobian(geometry, &pose), &diff).ok_or(
            ForwardError::Singular {
                iterations: iteration - 1,
            },
        )?;
        for k in 0..6 {
            q[k] -= step[k];
        }
    }
    let pose = Pose::from_coordinates(q);
    let at = inverse(geometry, &pose);
    let error = (0..6).fold(0.0_f64, |m, i| m.max((at[i] - lengths[i]).abs()));
    if error <= limits.criterion {
        return Ok(Forward {
            pose,
            iterations: limits.iterations,
        });
    }
    Err(ForwardError::NoConvergence {
        iterations: limits.iterations,
        error,
    })
}
