//! The hexapod's kinematics: inverse then forward on random poses,
//! Jacobians against finite differences, and every bad input.

use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

use motion_hdl::host::hexapod::*;

fn random_pose(rng: &mut StdRng, geometry: &Geometry) -> Pose {
    let v: [f64; 6] = std::array::from_fn(|k| {
        let [min, max] = geometry.limits[k];
        rng.gen_range(min..=max)
    });
    Pose {
        position: [v[0], v[1], v[2]],
        angles: [v[3], v[4], v[5]],
    }
}

#[test]
fn inverse_then_forward_returns_10k_random_poses_within_a_nanometre() {
    let geometry = Geometry::default();
    let mut rng = StdRng::seed_from_u64(36);
    let (mut checked, mut most_iterations) = (0, 0);
    while checked < 10_000 {
        let pose = random_pose(&mut rng, &geometry);
        let Ok(legs) = check_pose(&geometry, &pose) else {
            continue;
        };
        let found = forward(&geometry, &legs, &geometry.home, &ForwardLimits::default())
            .unwrap_or_else(|e| panic!("{pose:?}: {e}"));
        let (a, b) = (pose.coordinates(), found.pose.coordinates());
        for k in 0..3 {
            // 1e-9 m.
            assert!(
                (a[k] - b[k]).abs() <= 1e-6,
                "{pose:?} came back as {:?}",
                found.pose
            );
            // 1e-9 rad.
            assert!(
                (a[k + 3] - b[k + 3]).abs() <= 1e-9,
                "{pose:?} came back as {:?}",
                found.pose
            );
        }
        most_iterations = most_iterations.max(found.iterations);
        checked += 1;
    }
    // From home to anywhere in the workspace: Newton converges fast
    // (genhexkins's step, by the twist Jacobian, needs more).
    println!("10000 poses: at most {most_iterations} iterations from home");
    assert!(most_iterations <= 10, "{most_iterations} iterations");
}

#[test]
fn the_jacobians_match_finite_differences() {
    let geometry = Geometry::default();
    let mut rng = StdRng::seed_from_u64(7);
    for _ in 0..200 {
        let pose = random_pose(&mut rng, &geometry);
        let q = pose.coordinates();
        let j = pose_jacobian(&geometry, &pose);
        let h = 1e-6;
        for k in 0..6 {
            let (mut up, mut down) = (q, q);
            up[k] += h;
            down[k] -= h;
            let (lu, ld) = (
                inverse(&geometry, &Pose::from_coordinates(up)),
                inverse(&geometry, &Pose::from_coordinates(down)),
            );
            for i in 0..6 {
                let numeric = (lu[i] - ld[i]) / (2.0 * h);
                assert!(
                    (numeric - j[i][k]).abs() <= 1e-5 * (1.0 + numeric.abs()),
                    "leg {i}, coordinate {k} at {pose:?}: {numeric} by differences, {} by the Jacobian",
                    j[i][k]
                );
            }
        }
        // The twist Jacobian: a small motion by the twist (a rotation
        // about the base frame's axes through the platform's origin).
        let twist: [f64; 6] = std::array::from_fn(|_| rng.gen_range(-1.0..1.0));
        let rates = leg_velocities(&geometry, &pose, &twist);
        let dt = 1e-7;
        let moved = |sign: f64| {
            let w = [twist[3], twist[4], twist[5]].map(|v| v * sign * dt);
            let angle = (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt();
            let axis = w.map(|v| v / angle);
            // Rodrigues: the small rotation, composed in the base frame.
            let (s, c) = angle.sin_cos();
            let k = axis;
            let rot = [
                [
                    c + k[0] * k[0] * (1.0 - c),
                    k[0] * k[1] * (1.0 - c) - k[2] * s,
                    k[0] * k[2] * (1.0 - c) + k[1] * s,
                ],
                [
                    k[1] * k[0] * (1.0 - c) + k[2] * s,
                    c + k[1] * k[1] * (1.0 - c),
                    k[1] * k[2] * (1.0 - c) - k[0] * s,
                ],
                [
                    k[2] * k[0] * (1.0 - c) - k[1] * s,
                    k[2] * k[1] * (1.0 - c) + k[0] * s,
                    c + k[2] * k[2] * (1.0 - c),
                ],
            ];
            let r = rotation(pose.angles);
            let r2: [[f64; 3]; 3] = std::array::from_fn(|i| {
                std::array::from_fn(|j| (0..3).map(|m| rot[i][m] * r[m][j]).sum())
            });
            let t = [0, 1, 2].map(|m| pose.position[m] + sign * dt * twist[m]);
            std::array::from_fn::<f64, 6, _>(|i| {
                let p = geometry.platform[i];
                let v: [f64; 3] = std::array::from_fn(|m| {
                    t[m] + (0..3).map(|n| r2[m][n] * p[n]).sum::<f64>() - geometry.base[i][m]
                });
                (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
            })
        };
        let (ahead, behind) = (moved(1.0), moved(-1.0));
        for i in 0..6 {
            let numeric = (ahead[i] - behind[i]) / (2.0 * dt);
            assert!(
                (numeric - rates[i]).abs() <= 1e-4 * (1.0 + numeric.abs()),
                "leg {i}: {numeric} by differences, {} by the twist Jacobian",
                rates[i]
            );
        }
    }
}

#[test]
fn the_default_machine_is_genhexkins_sample_in_mm() {
    let geometry = Geometry::default();
    geometry.validate().unwrap();
    // vismach hexapod-sim: every joint's HOME is 29.7466 in at Z 20 in.
    for leg in inverse(&geometry, &geometry.home) {
        // The joints have 3 decimals: the six legs differ by up to 4e-4 in.
        assert!((leg / 25.4 - 29.7466).abs() < 5e-4, "{leg}");
    }
}

#[test]
fn poses_the_machine_cannot_take_are_refused_by_name() {
    let geometry = Geometry::default();
    let at = |position: [f64; 3], angles: [f64; 3]| Pose { position, angles };
    assert_eq!(
        check_pose(&geometry, &at([0.0, 250.0, 508.0], [0.0; 3])).unwrap_err(),
        PoseError::OutsideWorkspace {
            axis: 'Y',
            value: 250.0,
            min: -200.0,
            max: 200.0
        }
    );
    assert_eq!(
        check_pose(&geometry, &at([0.0, 0.0, 508.0], [0.0, 25.0, 0.0]))
            .unwrap_err()
            .to_string(),
        "B 25 is outside the workspace, -20 to 20"
    );
    // A wider workspace lets a pose ask for a leg the stroke has not got.
    let mut wide = geometry.clone();
    wide.limits[2] = [0.0, 2000.0];
    match check_pose(&wide, &at([0.0, 0.0, 900.0], [0.0; 3])) {
        Err(PoseError::LegBeyondStroke { length, max, .. }) => {
            assert!(length > max, "{length}")
        }
        other => panic!("{other:?}"),
    }
    // The platform in the base's plane: every leg horizontal, no leg can
    // push it up or down. Near there the condition number soars.
    let mut flat = geometry.clone();
    flat.limits[2] = [-10.0, 700.0];
    flat.stroke = [100.0, 950.0];
    match check_pose(&flat, &at([0.0, 0.0, 0.01], [0.0; 3])) {
        Err(PoseError::NearSingular { condition, limit }) => {
            assert!(condition > limit, "{condition}")
        }
        other => panic!("{other:?}"),
    }
    assert!(condition(&geometry, &geometry.home) < 100.0);
}

#[test]
fn forward_kinematics_that_does_not_converge_is_an_error() {
    let geometry = Geometry::default();
    let legs = inverse(
        &geometry,
        &Pose {
            position: [50.0, -30.0, 450.0],
            angles: [5.0, -3.0, 10.0],
        },
    );
    let one = ForwardLimits {
        iterations: 1,
        ..ForwardLimits::default()
    };
    match forward(&geometry, &legs, &geometry.home, &one) {
        Err(ForwardError::NoConvergence {
            iterations: 1,
            error,
        }) => assert!(error > 1e-9),
        other => panic!("{other:?}"),
    }
    let mut bad = legs;
    bad[3] = 0.0;
    assert_eq!(
        forward(&geometry, &bad, &geometry.home, &ForwardLimits::default()),
        Err(ForwardError::LegNotPositive {
            leg: 3,
            length: 0.0
        })
    );
    // Legs no pose has (one leg twice the others): no silent answer.
    let mut impossible = inverse(&geometry, &geometry.home);
    impossible[0] *= 3.0;
    assert!(forward(
        &geometry,
        &impossible,
        &geometry.home,
        &ForwardLimits::default()
    )
    .is_err());
}

#[test]
fn a_geometry_file_is_read_and_a_platform_that_cannot_work_is_refused() {
    let g = Geometry::parse(
        "stroke 500 1000 # mm\nleg_speed 250\nlimit z 350 650\nhome 0 0 500 0 0 0\n",
    )
    .unwrap();
    assert_eq!(
        (g.stroke, g.leg_speed, g.limits[2]),
        ([500.0, 1000.0], 250.0, [350.0, 650.0])
    );
    let error = |text: &str| Geometry::parse(text).unwrap_err().to_string();
    assert_eq!(
        error("stroke 800 600"),
        "stroke 800 600: the shortest leg must be above 0 and below the longest"
    );
    assert!(error("home 0 0 900 0 0 0").starts_with("home: Z 900 is outside the workspace"));
    assert!(error("limit z 0 2000\nhome 0 0 900 0 0 0").starts_with("home: leg 0 would be"));
    let line = "platform 0 0 0 0\nplatform 1 1 0 0\nplatform 2 2 0 0\nplatform 3 3 0 0\nplatform 4 4 0 0\nplatform 5 5 0 0\n";
    assert!(error(line).starts_with("the platform joints are on one line"));
    assert!(error("base 6 0 0 0").contains("legs are 0 to 5"));
    assert!(error("limit w 0 1").contains("an axis x, y, z, a, b or c"));
    assert!(error("limit b -100 100").contains("within ±90 degrees"));
    assert!(error("spindle 3").contains("unknown setting `spindle`"));
}

/// A, B, C as genhexkins reads them: R = Rz(C) · Ry(B) · Rx(A), each a
/// right-handed turn about the base frame's axis.
#[test]
fn the_angles_are_roll_pitch_yaw_as_in_posemath() {
    let turn = |axis: usize, degrees: f64| -> [[f64; 3]; 3] {
        let (s, c) = degrees.to_radians().sin_cos();
        let (i, j) = ((axis + 1) % 3, (axis + 2) % 3);
        let mut m = [[0.0; 3]; 3];
        m[axis][axis] = 1.0;
        m[i][i] = c;
        m[j][j] = c;
        m[i][j] = -s;
        m[j][i] = s;
        m
    };
    let mul = |a: [[f64; 3]; 3], b: [[f64; 3]; 3]| -> [[f64; 3]; 3] {
        std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum()))
    };
    let expected = mul(turn(2, 30.0), mul(turn(1, 20.0), turn(0, 10.0)));
    let r = rotation([10.0, 20.0, 30.0]);
    for i in 0..3 {
        for j in 0..3 {
            assert!((r[i][j] - expected[i][j]).abs() < 1e-15, "{r:?}");
        }
    }
    // Pitch then roll, not the other way: Y goes to X at A = B = 90.
    let r = rotation([90.0, 90.0, 0.0]);
    assert!((r[0][1] - 1.0).abs() < 1e-12, "{r:?}");
}
