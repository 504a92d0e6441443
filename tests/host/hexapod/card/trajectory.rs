//! Tests of `motion_hdl::host::hexapod::card::trajectory` (`src/host/hexapod/card/trajectory.rs`).

use motion_hdl::host::hexapod::card::*;
use motion_hdl::host::hexapod::Pose;

/// The velocity and acceleration are the derivatives of the pose.
#[test]
fn the_helix_derivatives_match_finite_differences() {
    let helix = Helix {
        start: Pose {
            position: [1.0, 2.0, 508.0],
            angles: [0.5, -0.5, 1.0],
        },
        radius: 10.0,
        turns: 1.0,
        rise: 20.0,
        a_amplitude: 5.0,
        b_amplitude: 4.0,
        seconds: 2.0,
    };
    let coords = |s: &MotionSample| {
        let mut q = [0.0; 6];
        q[..3].copy_from_slice(&s.pose.position);
        q[3..].copy_from_slice(&s.pose.angles);
        q
    };
    let h = 1e-5;
    for i in 1..40 {
        let t = i as f64 * 0.05;
        let (before, now, after) = (helix.at(t - h), helix.at(t), helix.at(t + h));
        for axis in 0..6 {
            let v = (coords(&after)[axis] - coords(&before)[axis]) / (2.0 * h);
            let a = (after.velocity[axis] - before.velocity[axis]) / (2.0 * h);
            assert!(
                (v - now.velocity[axis]).abs() < 1e-5,
                "t {t} axis {axis}: {v}"
            );
            assert!(
                (a - now.acceleration[axis]).abs() < 1e-4,
                "t {t} axis {axis}: {a}"
            );
        }
    }
    let end = helix.at(2.0);
    assert!((end.pose.position[0] - 1.0).abs() < 1e-9);
    assert!((end.pose.position[2] - 528.0).abs() < 1e-9);
    assert!(end.velocity.iter().all(|v| v.abs() < 1e-9));
}
