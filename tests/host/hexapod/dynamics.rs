//! Tests of `motion_hdl::host::hexapod::dynamics` (`src/host/hexapod/dynamics.rs`).

use motion_hdl::host::hexapod::*;
use motion_hdl::host::hexapod::{check_pose, leg_velocities};
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
