use motion_hdl::host::gcode::{interpret_with, Setup};
use motion_hdl::host::hexapod::card::*;
use motion_hdl::host::hexapod::condition;
use motion_hdl::host::hexapod::Geometry;
use motion_hdl::host::toolpath::Toolpath;

fn toolpath(program: &str, geometry: &Geometry) -> Toolpath {
    let setup = Setup {
        start: geometry.home.position,
        start_angles: geometry.home.angles,
        rotary_axes: true,
        ..Setup::default()
    };
    interpret_with(program, &setup)
        .unwrap_or_else(|e| panic!("{e}"))
        .toolpath
}

fn plan(program: &str) -> PosePlan {
    let g = Geometry::default();
    PosePlan::plan(&toolpath(program, &g), &g, &PoseLimits::default())
        .unwrap_or_else(|e| panic!("{e}"))
}

// The G3 is a spiral: 20 mm from its center at the start, 20.01 at the end.
const MIXED: &str = "G0 X20 Z520\nG1 X20 Y20 A3 F1200\nG3 X-20.01 Y20 I-20 J0 B-4\n\
                     G1 A0 B0 C5 F600\nG4 P0.1\nG2 X20 Y20 Z530 I20 J0 C0 F900\nG0 X0 Y0 Z508";

fn coords(s: &MotionSample) -> [f64; 6] {
    s.pose.coordinates_degrees()
}

/// The velocity is the pose's derivative everywhere, and the acceleration
/// the velocity's (it is continuous: the ramps are sines).
#[test]
fn velocity_and_acceleration_are_the_derivatives_of_the_pose() {
    let p = plan(MIXED);
    let h = 1e-6;
    let mut checked = 0;
    let steps = 4000;
    for i in 1..steps {
        let t = p.duration() * i as f64 / steps as f64;
        let (before, now, after) = (p.at(t - h), p.at(t), p.at(t + h));
        for k in 0..6 {
            let v = (coords(&after)[k] - coords(&before)[k]) / (2.0 * h);
            assert!(
                (v - now.velocity[k]).abs() < 1e-4 * (1.0 + v.abs()),
                "t {t} axis {k}: {v} against {}",
                now.velocity[k]
            );
            let a = (after.velocity[k] - before.velocity[k]) / (2.0 * h);
            assert!(
                (a - now.acceleration[k]).abs() < 1e-2 * (1.0 + a.abs()),
                "t {t} axis {k}: {a} against {}",
                now.acceleration[k]
            );
            if now.acceleration[k].abs() > 1.0 {
                checked += 1;
            }
        }
    }
    // The accelerating samples (ramps, arcs) are most of the checks.
    assert!(checked > 5_000, "{checked}");
}

/// It starts at home at rest, stops at every move's end, and ends at the
/// program's end.
#[test]
fn it_stops_at_every_move_and_ends_at_the_program_end() {
    let g = Geometry::default();
    let path = toolpath(MIXED, &g);
    let p = PosePlan::plan(&path, &g, &PoseLimits::default()).unwrap();
    assert_eq!(p.items(), 7);
    assert_eq!(p.at(0.0).pose, g.home);
    let mut t = 0.0;
    for (start_time, duration, s) in p.item_ends() {
        assert!((start_time - t).abs() < 1e-12);
        t += duration;
        // Each item's own end, not the next one's start.
        assert!(s.velocity.iter().all(|v| v.abs() < 1e-9), "{t}: {s:?}");
        assert!(s.acceleration.iter().all(|v| v.abs() < 1e-6), "{t}: {s:?}");
    }
    assert!((t - p.duration()).abs() < 1e-9);
    assert_eq!(p.end_pose().position, path.end());
    assert_eq!(p.end_pose().angles, path.end_angles());
}

/// A long line cruises at its F; its time is its length over F plus one
/// sine ramp, and the ramp's peak acceleration is the limit.
#[test]
fn a_long_line_cruises_at_its_feed() {
    let p = plan("G1 X100 F1200");
    let (v, a) = (20.0, 1000.0);
    let ramp = std::f64::consts::PI * v / (2.0 * a);
    assert!((p.duration() - (100.0 / v + ramp)).abs() < 1e-12);
    let mid = p.at(p.duration() / 2.0);
    assert!((mid.velocity[0] - v).abs() < 1e-12);
    assert_eq!(mid.acceleration[0], 0.0);
    assert!((p.at(ramp / 2.0).acceleration[0] - a).abs() < 1e-9);
    assert!((p.at(p.duration() - ramp / 2.0).acceleration[0] + a).abs() < 1e-9);
    assert!((p.at(ramp / 2.0).velocity[0] - v / 2.0).abs() < 1e-9);
    // A short one never reaches it: two ramps, no cruise.
    let p = plan("G1 X0.1 F1200");
    let v = (2.0 * 0.1 * a / std::f64::consts::PI).sqrt();
    assert!((p.duration() - 2.0 * std::f64::consts::PI * v / (2.0 * a)).abs() < 1e-12);
    assert!((p.end_pose().position[0] - 0.1).abs() < 1e-12);
    // The angles alone at F degrees a minute.
    let p = plan("G1 A6 B8 F600");
    let mid = p.at(p.duration() / 2.0);
    assert!((mid.velocity[3].hypot(mid.velocity[4]) - 10.0).abs() < 1e-9);
}

/// Sampled every 0.1 ms: X Y Z, the angles and every leg within the
/// limits; with fast X Y Z limits the legs' speed is what binds.
#[test]
fn every_sample_keeps_within_the_limits() {
    let g = Geometry::default();
    let fast = "G0 X150 Y-100 Z560 A10\nG0 X-120 Y80 Z520 B-12 C8\nG2 X-120 Y80 I50 J0 F100000\n\
                G0 A-8 B8 C-10\nG1 X0 Y0 Z508 A0 B0 C0 F100000";
    let quick = PoseLimits {
        max_velocity: 2000.0,
        max_acceleration: 20_000.0,
        max_angular_velocity: 600.0,
        max_angular_acceleration: 6000.0,
        leg_speed_share: 0.9,
    };
    for (program, limits) in [
        (MIXED, PoseLimits::default()),
        (fast, PoseLimits::default()),
        (fast, quick),
    ] {
        let p = PosePlan::plan(&toolpath(program, &g), &g, &limits).unwrap();
        let steps = (p.duration() / 1e-4) as usize;
        let mut fastest_leg: f64 = 0.0;
        for i in 0..=steps {
            let s = p.at(i as f64 * 1e-4);
            let v = &s.velocity;
            assert!(v[0].hypot(v[1]).hypot(v[2]) <= limits.max_velocity * (1.0 + 1e-9));
            assert!(v[3].hypot(v[4]).hypot(v[5]) <= limits.max_angular_velocity * (1.0 + 1e-9));
            let a = &s.acceleration;
            assert!(a[0].hypot(a[1]).hypot(a[2]) <= limits.max_acceleration * (1.0 + 1e-9));
            assert!(a[3].hypot(a[4]).hypot(a[5]) <= limits.max_angular_acceleration * (1.0 + 1e-9));
            let rad: [f64; 6] =
                std::array::from_fn(|k| if k < 3 { v[k] } else { v[k].to_radians() });
            let j = motion_hdl::host::hexapod::pose_jacobian(&g, &s.pose);
            let legs: [f64; 6] = std::array::from_fn(|i| (0..6).map(|k| j[i][k] * rad[k]).sum());
            fastest_leg = legs.iter().fold(fastest_leg, |m, l| m.max(l.abs()));
        }
        assert!(fastest_leg <= g.leg_speed, "{fastest_leg}");
        if limits == quick {
            assert!(fastest_leg > 0.85 * g.leg_speed, "{fastest_leg}");
        }
        p.check(&g, 1e-3).unwrap();
    }
}

/// Each pose the machine cannot take is an error naming its line.
#[test]
fn a_pose_the_machine_cannot_take_names_its_line() {
    let g = Geometry::default();
    let refused = |program: &str, geometry: &Geometry| {
        PosePlan::plan(
            &toolpath(program, geometry),
            geometry,
            &PoseLimits::default(),
        )
        .unwrap_err()
        .to_string()
    };
    assert_eq!(
        refused("G0 X10\nG1 X250 F600", &g),
        "line 2: X 250 is outside the workspace, -200 to 200"
    );
    assert_eq!(
        refused("G0 X10\n\nG0 A25", &g),
        "line 3: A 25 is outside the workspace, -20 to 20"
    );
    // In the workspace, but leg 1 would be 996 mm long.
    let stroke = refused("G0 X-150 Z700", &g);
    assert!(
        stroke.starts_with("line 1: leg ") && stroke.contains("beyond its stroke of 600 to 950 mm"),
        "{stroke}"
    );
    // A condition limit just above home's: a tilt goes beyond it.
    let tight = Geometry {
        condition_limit: condition(&g, &g.home) * 1.01,
        ..g.clone()
    };
    let singular = refused("G0 X1\nG0 A15 B15", &tight);
    assert!(
        singular.starts_with("line 2: the pose is singular or nearly"),
        "{singular}"
    );
    // An arc that swings outside though both its ends are inside.
    let arc = refused("G0 X150\nG2 X150 Y0 I-180 J0 F600", &g);
    assert!(
        arc.starts_with("line 2: X -2") && arc.ends_with("is outside the workspace, -200 to 200"),
        "{arc}"
    );
}

/// A program that would run longer than the limit is refused naming the
/// line, and so is a feed so low its move never ends; a crawl still ends at
/// rest exactly.
#[test]
fn a_program_too_long_is_refused_naming_its_line() {
    let g = Geometry::default();
    let refused = |program: &str| {
        PosePlan::plan(&toolpath(program, &g), &g, &PoseLimits::default())
            .unwrap_err()
            .to_string()
    };
    assert!(refused("G0 X1\nG4 P20000").starts_with("line 2: the program would run 2.000e4 s"));
    assert!(refused("G1 X1 F0.000001").starts_with("line 1: the program would run"));
    let p = plan("G1 X1 F0.01");
    let end = p.at(p.duration());
    assert!(end.velocity.iter().all(|v| *v == 0.0), "{end:?}");
    assert_eq!(end.pose.position[0], 1.0);
}

/// The period check holds every leg to the geometry's speed, naming the
/// line; bad limits name the setting.
#[test]
fn a_leg_too_fast_and_bad_limits_are_named() {
    let g = Geometry::default();
    let p = PosePlan::plan(
        &toolpath("G0 X5\nG1 X50 F6000", &g),
        &g,
        &PoseLimits::default(),
    )
    .unwrap();
    let slow = Geometry {
        leg_speed: 10.0,
        ..g.clone()
    };
    let e = p.check(&slow, 1e-3).unwrap_err().to_string();
    assert!(
        e.starts_with("line 1: leg ") && e.ends_with("above its limit of 10 mm/s"),
        "{e}"
    );
    let bad = PoseLimits {
        max_velocity: 0.0,
        ..PoseLimits::default()
    };
    assert_eq!(
        PosePlan::plan(&toolpath("G0 X5", &g), &g, &bad)
            .unwrap_err()
            .to_string(),
        "planner limits: max_velocity 0: above 0"
    );
}
