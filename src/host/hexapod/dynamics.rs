//! The load each leg carries: the platform's inertia seen in joint space.
//!
//! With the twist Jacobian J (leg rates = J · twist), the platform's kinetic
//! energy ½ twistᵀ M twist is ½ q̇ᵀ Λ q̇ with Λ = J⁻ᵀ M J⁻¹: the joint-space
//! inertia. Its diagonal Λ_ii is the mass leg i drives along its own axis
//! when the others hold still; it changes with the pose, which is why the
//! motor DSPs' position loops schedule their gains on the configuration.
//! M is the platform's rigid body with its centre of mass at the platform's
//! origin: its mass on the linear block, its inertia tensor turned into the
//! base frame (R I Rᵀ) on the angular block. Units: kg and mm (the tensor
//! in kg·mm², Λ in kg).

use super::linear::{inverse as invert, Matrix6};
use super::{rotation, twist_jacobian, Geometry, Pose};

/// The platform's rigid body, its centre of mass at the platform's origin.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlatformInertia {
    /// Mass, kg.
    pub mass_kg: f64,
    /// Inertia tensor about the origin, in the platform's frame, kg·mm².
    pub tensor_kg_mm2: [[f64; 3]; 3],
}

impl Default for PlatformInertia {
    /// A 50 kg disc of 300 mm radius (a platform with its spindle):
    /// ¼ m r² about X and Y, ½ m r² about Z.
    fn default() -> Self {
        let (m, r) = (50.0, 300.0);
        let (side, axial) = (m * r * r / 4.0, m * r * r / 2.0);
        Self {
            mass_kg: m,
            tensor_kg_mm2: [[side, 0.0, 0.0], [0.0, side, 0.0], [0.0, 0.0, axial]],
        }
    }
}

impl PlatformInertia {
    /// M at `pose`: mass on the linear block, R I Rᵀ on the angular block.
    pub fn matrix(&self, pose: &Pose) -> Matrix6 {
        let r = rotation(pose.angles);
        let mut m = [[0.0; 6]; 6];
        for i in 0..3 {
            m[i][i] = self.mass_kg;
            for j in 0..3 {
                m[3 + i][3 + j] = (0..3)
                    .map(|k| {
                        (0..3)
                            .map(|l| r[i][k] * self.tensor_kg_mm2[k][l] * r[j][l])
                            .sum::<f64>()
                    })
                    .sum();
            }
        }
        m
    }
}

/// Λ = J⁻ᵀ M J⁻¹ at `pose`, kg; `None` where the Jacobian is singular.
pub fn joint_inertia(geometry: &Geometry, pose: &Pose, body: &PlatformInertia) -> Option<Matrix6> {
    let j_inv = invert(&twist_jacobian(geometry, pose))?;
    let m = body.matrix(pose);
    Some(std::array::from_fn(|a| {
        std::array::from_fn(|b| {
            (0..6)
                .map(|k| {
                    (0..6)
                        .map(|l| j_inv[k][a] * m[k][l] * j_inv[l][b])
                        .sum::<f64>()
                })
                .sum()
        })
    }))
}

/// Each leg's load along its axis, Λ_ii, kg; `None` where the Jacobian is
/// singular.
pub fn leg_inertia(geometry: &Geometry, pose: &Pose, body: &PlatformInertia) -> Option<[f64; 6]> {
    let lambda = joint_inertia(geometry, pose, body)?;
    Some(std::array::from_fn(|i| lambda[i][i]))
}
