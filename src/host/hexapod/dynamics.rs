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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::host::hexapod::{check_pose, leg_velocities};
    use rand::{Rng, SeedableRng};

    fn random_pose(rng: &mut rand::rngs::StdRng, geometry: &Geometry) -> Pose {
        loop {
            let pose = Pose {
                position: [
                    rng.gen_range(-150.0..150.0),
                    rng.gen_range(-150.0..150.0),
                    rng.gen_range(350.0..650.0),
                ],
                angles: [
                    rng.gen_range(-15.0..15.0),
                    rng.gen_range(-15.0..15.0),
                    rng.gen_range(-15.0..15.0),
                ],
            };
            if check_pose(geometry, &pose).is_ok() {
                return pose;
            }
        }
    }

    /// The platform's kinetic energy is the same counted in the twist or
    /// in the legs' rates: Λ is M seen through the Jacobian.
    #[test]
    fn the_energy_is_the_same_in_joint_space() {
        let geometry = Geometry::default();
        let body = PlatformInertia::default();
        let mut rng = rand::rngs::StdRng::seed_from_u64(361);
        for _ in 0..1000 {
            let pose = random_pose(&mut rng, &geometry);
            let twist: [f64; 6] = std::array::from_fn(|i| {
                if i < 3 {
                    rng.gen_range(-300.0..300.0)
                } else {
                    rng.gen_range(-1.0..1.0)
                }
            });
            let m = body.matrix(&pose);
            let energy = |a: &Matrix6, v: &[f64; 6]| {
                (0..6)
                    .map(|i| (0..6).map(|j| v[i] * a[i][j] * v[j]).sum::<f64>())
                    .sum::<f64>()
                    / 2.0
            };
            let rates = leg_velocities(&geometry, &pose, &twist);
            let lambda = joint_inertia(&geometry, &pose, &body).unwrap();
            let (cartesian, joint) = (energy(&m, &twist), energy(&lambda, &rates));
            assert!(
                (cartesian - joint).abs() <= 1e-9 * cartesian.abs().max(1.0),
                "{pose:?}: {cartesian} against {joint}"
            );
            for i in 0..6 {
                assert!(lambda[i][i] > 0.0);
                for j in 0..6 {
                    assert!((lambda[i][j] - lambda[j][i]).abs() <= 1e-9 * lambda[i][i].abs());
                }
            }
        }
    }

    /// The load changes with the pose: the reason to schedule the gains.
    /// With the default platform every leg drives 18.2 kg at home; over
    /// these 2000 poses (±150 mm, Z 350 to 650 mm, ±15°) the legs' loads
    /// range from 14.0 to 39.8 kg, each leg's over more than 2:1 (the
    /// narrowest, leg 1, 14.4 to 29.4 kg).
    #[test]
    fn a_leg_load_depends_on_the_pose() {
        let geometry = Geometry::default();
        let body = PlatformInertia::default();
        let mut rng = rand::rngs::StdRng::seed_from_u64(362);
        let home = leg_inertia(&geometry, &geometry.home, &body).unwrap();
        let (mut low, mut high) = (home, home);
        for _ in 0..2000 {
            let pose = random_pose(&mut rng, &geometry);
            let legs = leg_inertia(&geometry, &pose, &body).unwrap();
            for i in 0..6 {
                low[i] = low[i].min(legs[i]);
                high[i] = high[i].max(legs[i]);
            }
        }
        for i in 0..6 {
            assert!(
                high[i] > 2.0 * low[i],
                "leg {i}: {} to {} kg",
                low[i],
                high[i]
            );
        }
    }
}
