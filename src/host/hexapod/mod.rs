//! # The hexapod: a Stewart-Gough platform (6-UPS) for the parallel-machine card (#36)
//!
//! Six linear legs join a base (fixed, world frame) to a platform (the
//! tool's frame); a pose of the platform, X Y Z in mm and A B C in degrees,
//! fixes the six leg lengths. The model is LinuxCNC's genhexkins (same
//! joints, same angle convention, the same Newton-Raphson limits, read in
//! mm); its defaults are genhexkins's sample machine.
//!
//! | Item | What |
//! |---|---|
//! | [`Geometry`] | joints, stroke, leg speed, workspace, home, condition limit; [`Geometry::parse`] reads a small file |
//! | [`inverse`] | pose → leg lengths, closed form |
//! | [`twist_jacobian`], [`leg_velocities`] | twist (mm/s, rad/s) → leg rates (mm/s) |
//! | [`pose_jacobian`] | d(legs)/d(X Y Z A B C), angles in radians |
//! | [`forward`] | leg lengths → pose, Newton-Raphson from a guess, [`ForwardLimits`] (120 iterations, 1e-9 mm, 12700 mm) |
//! | [`check_pose`] | a pose the machine can take: inside the workspace, legs within stroke, not near a singularity |
//! | [`leg_inertia`], [`joint_inertia`] | the platform's inertia seen by each leg, Λ = J⁻ᵀ M J⁻¹ ([`PlatformInertia`]): the pose-dependent load the gains are scheduled on |
//! | [`PeriodPoint`] | one period's pose, twist and acceleration as the 19 words the control DSP writes to every motor DSP through `parallel_card` |
//! | [`card`] | the card run by its DSPs: control DSP, motor DSPs, leg plants, [`card::run_card`]; the Cartesian planner [`card::PosePlan`] |
//! | [`simulate`] | `simulate PROGRAM --kinematics hexapod`: a G-code program in X Y Z A B C on the card, scheduled and fixed gains |
//!
//! ## Accuracy and bad input
//! - [`forward`] stops when every leg is within 1e-9 mm of its length; on
//!   10^4 random poses of the default workspace it returns the pose within
//!   1e-9 m and 1e-9 rad (tested). It never returns a pose that does not
//!   meet the criterion: no convergence in 120 iterations, divergence
//!   (legs' errors summing above 12700 mm), a singular Jacobian or a leg of
//!   0 or less are each a [`ForwardError`].
//! - [`check_pose`] refuses a pose outside the workspace, a leg beyond its
//!   stroke, or a scaled Jacobian condition number above the limit
//!   ([`PoseError`]); [`Geometry::parse`] refuses a platform that does not
//!   work (joints on one line, a stroke or speed of 0 or less, limits out
//!   of order, a home the machine cannot take), naming the setting.

pub mod card;
mod commands;
mod dynamics;
pub mod geometry;
mod kinematics;
mod linear;
pub mod simulate;

#[doc(hidden)]
pub use commands::FIELDS;
pub use commands::{CommandError, PeriodPoint, HEADER_MARK, POINTS_PER_FIFO, WORDS};
pub use dynamics::{joint_inertia, leg_inertia, PlatformInertia};
pub use geometry::{check_pose, condition, Geometry, PoseError};
pub use kinematics::{
    forward, inverse, leg_vectors, leg_velocities, pose_jacobian, rotation, twist_jacobian,
    Forward, ForwardError, ForwardLimits, Pose,
};
pub use linear::Matrix6;
