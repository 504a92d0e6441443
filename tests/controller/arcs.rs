//! Arcs in the planner and the coarse interpolator: closed-form cases (a
//! full circle, a quarter arc's centripetal limit, a tangent line-arc-line
//! chain) and random toolpaths of lines and arcs against every limit: the
//! exact end, the feed, per-axis velocity and acceleration, and the chord
//! error.

use motion_hdl::host::planner::to_steps;
use motion_hdl::host::{
    interpolate, plan_toolpath, Arc, Interpolation, Item, LaserPower, MachineSettings, Move,
    MoveKind, Plane, PlannedSegment, Shape, Toolpath,
};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

fn line(end: [f64; 3], feed: f64) -> Item {
    Item::Move(Move {
        kind: MoveKind::Line,
        end,
        angles: [0.0; 3],
        feed: Some(feed),
        laser: LaserPower::OFF,
        line: 0,
    })
}

fn arc(end: [f64; 3], center: [f64; 2], clockwise: bool, feed: f64) -> Item {
    Item::Move(Move {
        kind: MoveKind::Arc(Arc {
            plane: Plane::Xy,
            center,
            clockwise,
            turns: 0,
        }),
        end,
        angles: [0.0; 3],
        feed: Some(feed),
        laser: LaserPower::OFF,
        line: 0,
    })
}

fn run(toolpath: &Toolpath, machine: &MachineSettings) -> (Vec<PlannedSegment>, Interpolation) {
    let segments = plan_toolpath(toolpath, machine).unwrap();
    let start = to_steps(toolpath.start, machine.steps_per_mm);
    let interpolation = interpolate(start, &segments, machine.period);
    (segments, interpolation)
}

/// The machine's centripetal share of the plane's acceleration.
const CENTRIPETAL: f64 = 0.866_025_403_784_438_6;

#[test]
fn a_full_circle_returns_exactly_to_its_start() {
    let machine = MachineSettings::default();
    for clockwise in [false, true] {
        let toolpath = Toolpath {
            start_angles: [0.0; 3],
            start: [10.0, 0.0, 0.0],
            items: vec![arc([10.0, 0.0, 0.0], [0.0, 0.0], clockwise, 20.0)],
        };
        let (segments, i) = run(&toolpath, &machine);
        assert!((segments[0].length - std::f64::consts::TAU * 10.0).abs() < 1e-9);
        assert_eq!(*i.positions.last().unwrap(), [1000, 0, 0]);
        let sum = i.counts.iter().fold([0i64; 3], |s, c| {
            std::array::from_fn(|k| s[k] + c[k] as i64)
        });
        assert_eq!(sum, [0, 0, 0], "the counts of a circle add up to nothing");
        // It went all the way round: through (-10, 0) and (0, +-10).
        let xs = i.positions.iter().map(|p| p[0]);
        assert_eq!((xs.clone().min(), xs.max()), (Some(-1000), Some(1000)));
        let ys = i.positions.iter().map(|p| p[1]);
        assert_eq!((ys.clone().min(), ys.max()), (Some(-1000), Some(1000)));
        // The first period heads the arc's way.
        let y1 = i.positions.iter().find(|p| p[1] != 0).unwrap()[1];
        assert_eq!(y1 < 0, clockwise, "G2 starts downward from (10, 0)");
    }
}

#[test]
fn a_quarter_arc_is_driven_at_its_centripetal_limit() {
    // r = 5 mm at a 100 mm/s feed with 500 mm/s^2 per plane axis: the
    // centripetal share sqrt(3)/2 * 500 gives v = sqrt(433 * 5) = 46.5 mm/s,
    // below the axes' 50 mm/s and the chord limit (632 mm/s at 0.01 mm).
    let machine = MachineSettings {
        max_velocity: [1000.0; 3],
        ..MachineSettings::default()
    };
    // Tangent lines before and after it, so that it is driven throughout
    // at its limit.
    let toolpath = Toolpath {
        start_angles: [0.0; 3],
        start: [5.0, -20.0, 0.0],
        items: vec![
            line([5.0, 0.0, 0.0], 100.0),
            arc([0.0, 5.0, 0.0], [0.0, 0.0], false, 100.0),
            line([-20.0, 5.0, 0.0], 100.0),
        ],
    };
    let (segments, i) = run(&toolpath, &machine);
    let a = machine.max_accel[0];
    let expected = (CENTRIPETAL * a * 5.0).sqrt();
    let quarter = &segments[1];
    assert!(
        (quarter.v_limit - expected).abs() < 1e-9,
        "{} vs {expected}",
        quarter.v_limit
    );
    for v in [quarter.v_entry, quarter.v_cruise, quarter.v_exit] {
        assert!(
            (v - expected).abs() < 1e-9,
            "{v}: the whole arc at its limit"
        );
    }
    assert_eq!(
        quarter.accel,
        0.5 * a,
        "half the plane's acceleration along the arc"
    );
    let on_arc: Vec<f64> = (0..i.speeds.len())
        .filter(|&k| i.moves[k] == 1)
        .map(|k| i.speeds[k])
        .collect();
    assert!(on_arc.len() > 100, "{} periods on the arc", on_arc.len());
    for v in on_arc {
        assert!(
            v * v / 5.0 <= CENTRIPETAL * a * (1.0 + 1e-12),
            "v = {v}: v^2/r above the centripetal share"
        );
        assert!(v * v / 5.0 <= a, "v^2/r <= a_max");
    }
    assert_eq!(*i.positions.last().unwrap(), [-2000, 500, 0]);
}

#[test]
fn a_coarse_period_limits_an_arcs_speed_by_its_chord_error() {
    // r = 10 mm, e = 0.001 mm, T = 10 ms: a chord may span
    // 2 acos(1 - e/r) = 0.02828 rad, so v <= 0.02828 * 10 / 0.01 = 28.3 mm/s,
    // below the centripetal 65.8 mm/s.
    let machine = MachineSettings {
        contour_error: 0.001,
        period: 0.01,
        ..MachineSettings::default()
    };
    let toolpath = Toolpath {
        start_angles: [0.0; 3],
        start: [10.0, 0.0, 0.0],
        items: vec![arc([10.0, 0.0, 0.0], [0.0, 0.0], false, 100.0)],
    };
    let (segments, i) = run(&toolpath, &machine);
    let expected = 2.0 * (1.0 - 0.001f64 / 10.0).acos() * 10.0 / 0.01;
    assert!(
        (segments[0].v_limit - expected).abs() < 1e-9,
        "{} vs {expected}",
        segments[0].v_limit
    );
    assert!((segments[0].v_cruise - expected).abs() < 1e-9);
    // The per-period chord at that speed deviates e from the circle.
    let (p, q) = (i.points[100], i.points[101]);
    let mid = [(p[0] + q[0]) / 2.0, (p[1] + q[1]) / 2.0];
    assert!(
        (10.0 - mid[0].hypot(mid[1]) - 0.001).abs() < 1e-9,
        "sagitta {}",
        10.0 - mid[0].hypot(mid[1])
    );
}

#[test]
fn a_tangent_line_arc_line_chain_keeps_the_feed_through_its_junctions() {
    // Along X, a G3 quarter of radius 10 turning to +Y, then along Y, at
    // 20 mm/s: every junction is tangent and the arc's limits (65.8 mm/s
    // centripetal) are above the feed, so the junctions pass at the feed.
    let machine = MachineSettings::default();
    let feed = 20.0;
    let toolpath = Toolpath {
        start_angles: [0.0; 3],
        start: [0.0, 0.0, 0.0],
        items: vec![
            line([20.0, 0.0, 0.0], feed),
            arc([30.0, 10.0, 0.0], [20.0, 10.0], false, feed),
            line([30.0, 30.0, 0.0], feed),
        ],
    };
    let (segments, i) = run(&toolpath, &machine);
    assert_eq!(segments.len(), 3);
    for junction in 0..2 {
        assert!(
            (segments[junction].v_exit - feed).abs() < 1e-9,
            "junction {junction}: {}",
            segments[junction].v_exit
        );
        assert_eq!(segments[junction].v_exit, segments[junction + 1].v_entry);
    }
    // Every period from the end of the first acceleration to the start of
    // the last deceleration is at the feed: no dip at the junctions.
    let at_feed: Vec<usize> = (0..i.speeds.len())
        .filter(|&k| (i.speeds[k] - feed).abs() < 1e-9)
        .collect();
    let (first, last) = (at_feed[0], *at_feed.last().unwrap());
    assert!(
        at_feed.len() == last - first + 1,
        "the speed left the feed between periods {first} and {last}"
    );
    assert!(
        i.moves[first] == 0 && i.moves[last] == 2,
        "the feed spans all three moves"
    );
    assert_eq!(*i.positions.last().unwrap(), [3000, 3000, 0]);
}

#[test]
fn a_helix_and_a_dwell_end_exactly_and_the_dwell_holds_still() {
    let machine = MachineSettings::default();
    let helix = Item::Move(Move {
        kind: MoveKind::Arc(Arc {
            plane: Plane::Xy,
            center: [0.0, 0.0],
            clockwise: true,
            turns: 1,
        }),
        end: [2.0, 0.0, -1.5],
        angles: [0.0; 3],
        feed: Some(5.0),
        laser: LaserPower::OFF,
        line: 0,
    });
    let toolpath = Toolpath {
        start_angles: [0.0; 3],
        start: [2.0, 0.0, 0.0],
        items: vec![
            helix,
            Item::Dwell {
                seconds: 0.25,
                laser: LaserPower::OFF,
                line: 0,
            },
            line([0.0, 0.0, -1.5], 10.0),
        ],
    };
    let (segments, i) = run(&toolpath, &machine);
    assert!(
        (segments[0].length - (2.0 * std::f64::consts::TAU * 2.0).hypot(1.5)).abs() < 1e-9,
        "two turns"
    );
    assert_eq!(segments[0].v_exit, 0.0);
    assert_eq!(segments[2].v_entry, 0.0);
    let still = i.counts.iter().filter(|c| **c == [0, 0, 0]).count();
    assert!(
        still >= 249,
        "a 0.25 s dwell is at least 249 still periods: {still}"
    );
    assert_eq!(*i.positions.last().unwrap(), [0, 0, -600]);
}

#[test]
fn an_arc_without_contour_error_is_refused_by_its_line() {
    let machine = MachineSettings {
        contour_error: 0.0,
        ..MachineSettings::default()
    };
    let mut item = arc([0.0, 5.0, 0.0], [0.0, 0.0], false, 10.0);
    if let Item::Move(m) = &mut item {
        m.line = 7;
    }
    let toolpath = Toolpath {
        start_angles: [0.0; 3],
        start: [5.0, 0.0, 0.0],
        items: vec![item],
    };
    assert_eq!(
        plan_toolpath(&toolpath, &machine).unwrap_err().to_string(),
        "line 7: an arc needs a contour error above 0 (its chords would have to be points)"
    );
}

#[test]
fn a_spiral_whose_radius_change_is_most_of_its_motion_keeps_every_axis_limit() {
    // A G3 from (100, 0) about (0, 0) to a point 0.0999 mm further out:
    // within the interpreter's 0.1 % radius tolerance, and mostly radial.
    // Planned with the mean radius's length it ran X at 2.7 times its
    // limit; the planner's length is the fastest rate of the point.
    let machine = MachineSettings::default();
    let toolpath = Toolpath {
        start_angles: [0.0; 3],
        start: [0.0, 0.0, 0.0],
        items: vec![
            line([100.0, 0.0, 0.0], 50.0),
            arc([100.0999, 0.01001, 0.0], [0.0, 0.0], false, 50.0),
            line([200.0, 0.0, 0.0], 50.0),
        ],
    };
    let (segments, i) = run(&toolpath, &machine);
    let true_length = 0.0999f64.hypot(0.01001);
    assert!(
        segments[1].length >= true_length,
        "{} < {true_length}",
        segments[1].length
    );
    let mut previous = toolpath.start;
    for (k, p) in i.points.iter().enumerate() {
        for axis in 0..3 {
            let v = (p[axis] - previous[axis]).abs() / machine.period;
            assert!(
                v <= machine.max_velocity[axis] * (1.0 + 1e-9),
                "period {k}: axis {axis} at {v} mm/s"
            );
        }
        previous = *p;
    }
    assert_eq!(*i.positions.last().unwrap(), [20_000, 0, 0]);
}

#[test]
fn a_toolpath_that_is_not_a_set_of_positions_is_refused_by_its_line() {
    let machine = MachineSettings::default();
    let plan = |items: Vec<Item>| {
        let items = items
            .into_iter()
            .map(|item| match item {
                Item::Move(m) => Item::Move(Move { line: 4, ..m }),
                other => other,
            })
            .collect();
        plan_toolpath(
            &Toolpath {
                start_angles: [0.0; 3],
                start: [0.0; 3],
                items,
            },
            &machine,
        )
        .unwrap_err()
        .to_string()
    };
    assert_eq!(
        plan(vec![
            line([f64::NAN, 0.0, 0.0], 10.0),
            line([1.0, 0.0, 0.0], 10.0)
        ]),
        "line 4: the end [NaN, 0.0, 0.0] is NaN steps on axis 0, beyond +-2^40"
    );
    assert_eq!(
        plan(vec![line([f64::INFINITY, 0.0, 0.0], 10.0)]),
        "line 4: the end [inf, 0.0, 0.0] is inf steps on axis 0, beyond +-2^40"
    );
    assert_eq!(
        plan(vec![line([1.0, 0.0, 0.0], f64::NAN)]),
        "line 4: feed NaN is not a speed"
    );
    assert_eq!(
        plan(vec![arc([1.0, 0.0, 0.0], [f64::NAN, 0.0], false, 10.0)]),
        "line 4: the arc's center [NaN, 0.0] is not a position"
    );
    let fast = MachineSettings {
        steps_per_mm: [1e6; 3],
        max_velocity: [1e9; 3],
        ..MachineSettings::default()
    };
    let toolpath = Toolpath {
        start_angles: [0.0; 3],
        start: [0.0; 3],
        items: vec![line([1.0, 0.0, 0.0], 1e7)],
    };
    assert_eq!(
        plan_toolpath(&toolpath, &fast).unwrap_err().to_string(),
        "line 0: the move may take 10000000000 steps a period, beyond the 1073741824 an axis's count holds"
    );
}

/// The angle between two unit tangents, radians.
fn tangent_angle(u1: [f64; 3], u2: [f64; 3]) -> f64 {
    let dot: f64 = (0..3).map(|k| u1[k] * u2[k]).sum();
    dot.clamp(-1.0, 1.0).acos()
}

/// A random toolpath of lines, arcs (either way, helical sometimes,
/// tangent to the line before them sometimes) and short dwells, within
/// +-40 mm.
fn random_toolpath(rng: &mut StdRng) -> Toolpath {
    let mut at = [rng.gen_range(-5.0..5.0), rng.gen_range(-5.0..5.0), 0.0];
    let start = at;
    let mut items = Vec::new();
    let mut heading = [1.0f64, 0.0];
    for _ in 0..rng.gen_range(1..10) {
        let feed = rng.gen_range(2.0..80.0);
        match rng.gen_range(0..10) {
            0..=3 => {
                let end: [f64; 3] = [
                    rng.gen_range(-40.0..40.0),
                    rng.gen_range(-40.0..40.0),
                    rng.gen_range(-5.0..5.0),
                ];
                let d = [end[0] - at[0], end[1] - at[1]];
                let n = d[0].hypot(d[1]);
                if n > 0.0 {
                    heading = [d[0] / n, d[1] / n];
                }
                items.push(line(end, feed));
                at = end;
            }
            4..=8 => {
                let clockwise = rng.gen_bool(0.5);
                let r: f64 = rng.gen_range(0.2..15.0);
                // Tangent to the heading half of the time: the center a
                // radius to the left (G3) or right (G2) of it.
                let (cx, cy) = if rng.gen_bool(0.5) {
                    let side = if clockwise { -1.0 } else { 1.0 };
                    (at[0] - side * heading[1] * r, at[1] + side * heading[0] * r)
                } else {
                    let a: f64 = rng.gen_range(0.0..std::f64::consts::TAU);
                    (at[0] - r * a.cos(), at[1] - r * a.sin())
                };
                let sweep = rng.gen_range(0.1..std::f64::consts::TAU);
                let a0 = (at[1] - cy).atan2(at[0] - cx);
                let a1 = if clockwise { a0 - sweep } else { a0 + sweep };
                let z = if rng.gen_bool(0.3) {
                    at[2] + rng.gen_range(-2.0..2.0)
                } else {
                    at[2]
                };
                let end = [cx + r * a1.cos(), cy + r * a1.sin(), z];
                let s = if clockwise { -1.0 } else { 1.0 };
                heading = [-s * a1.sin(), s * a1.cos()];
                items.push(arc(end, [cx, cy], clockwise, feed));
                at = end;
            }
            _ => items.push(Item::Dwell {
                seconds: rng.gen_range(0.0..0.01),
                laser: LaserPower::OFF,
                line: 0,
            }),
        }
    }
    Toolpath {
        start,
        start_angles: [0.0; 3],
        items,
    }
}

/// Random toolpaths on random machines: the last sample is the end in
/// steps, the counts add up to it, and the path speed, each axis's
/// velocity and acceleration, the speed's change per period and each arc
/// chord's deviation stay within the machine's limits; every step position
/// is within a step of the exact point.
#[test]
fn random_lines_and_arcs_end_exactly_within_every_limit() {
    let mut rng = StdRng::seed_from_u64(0xa4c5);
    let mut arcs_checked = 0usize;
    for case in 0..150 {
        let machine = MachineSettings {
            steps_per_mm: [
                rng.gen_range(20.0..400.0),
                rng.gen_range(20.0..400.0),
                rng.gen_range(100.0..1000.0),
            ],
            max_velocity: [
                rng.gen_range(10.0..100.0),
                rng.gen_range(10.0..100.0),
                rng.gen_range(5.0..30.0),
            ],
            max_accel: [
                rng.gen_range(100.0..2000.0),
                rng.gen_range(100.0..2000.0),
                rng.gen_range(50.0..500.0),
            ],
            path_accel: f64::INFINITY,
            // Coarse periods and fine errors too, where the chord limit
            // binds before the centripetal one.
            contour_error: rng.gen_range(1e-4..0.05),
            period: [2.5e-4, 1e-3, 4e-3, 1e-2][rng.gen_range(0..4)],
            parameters: Default::default(),
            spindle_counts_per_rev: 0,
            ..MachineSettings::default()
        };
        let toolpath = random_toolpath(&mut rng);
        let (segments, i) = run(&toolpath, &machine);
        let t = machine.period;
        let end = to_steps(toolpath.end(), machine.steps_per_mm);
        assert_eq!(*i.positions.last().unwrap(), end, "case {case}: the end");
        let start = to_steps(toolpath.start, machine.steps_per_mm);
        let sum = i
            .counts
            .iter()
            .fold(start, |s, c| std::array::from_fn(|k| s[k] + c[k] as i64));
        assert_eq!(sum, end, "case {case}: the counts add up to the move");
        let max_accel = segments.iter().map(|s| s.accel).fold(0.0, f64::max);
        let mut points = vec![toolpath.start];
        points.extend(&i.points);
        for k in 0..i.speeds.len() {
            let s = &segments[i.moves[k]];
            assert!(
                i.speeds[k] <= s.v_limit * (1.0 + 1e-9),
                "case {case}: period {k} above its move's limit"
            );
            let previous = if k == 0 { 0.0 } else { i.speeds[k - 1] };
            assert!(
                (i.speeds[k] - previous).abs() <= max_accel * t * (1.0 + 1e-9) + 1e-9,
                "case {case}: speed step"
            );
            for axis in 0..3 {
                let velocity = (points[k + 1][axis] - points[k][axis]).abs() / t;
                assert!(
                    velocity <= machine.max_velocity[axis] * (1.0 + 1e-6),
                    "case {case}: axis {axis} at {velocity} mm/s"
                );
                // An arc's steps are its points rounded; a line's are the
                // line between its rounded ends, truncated.
                let exact = i.points[k][axis] * machine.steps_per_mm[axis];
                let bound = if matches!(s.shape, Shape::Arc(_)) {
                    0.5
                } else {
                    1.5
                };
                let off = (i.positions[k][axis] as f64 - exact).abs();
                assert!(
                    off <= bound + 1e-6,
                    "case {case}: steps {off} off the point"
                );
            }
        }
        // Per-axis acceleration from second differences, over any three
        // samples whose moves meet only at tangent junctions (a corner
        // changes direction within a period by the contour-error rule).
        let tangent_between = |from: usize, to: usize| {
            (from..to).all(|m| {
                let (a, b) = (&segments[m], &segments[m + 1]);
                matches!(a.shape, Shape::Dwell { .. })
                    || matches!(b.shape, Shape::Dwell { .. })
                    || tangent_angle(a.tangents().1, b.tangents().0) < 1e-7
            })
        };
        // points[j] is the position at j periods; i.moves[j - 1] its move.
        for k in 1..i.points.len() {
            let before = if k >= 2 { i.moves[k - 2] } else { 0 };
            if !tangent_between(before, i.moves[k]) {
                continue;
            }
            for axis in 0..3 {
                let a = (points[k + 1][axis] - 2.0 * points[k][axis] + points[k - 1][axis]).abs()
                    / (t * t);
                assert!(
                    a <= machine.max_accel[axis] * 1.01 + 1e-6,
                    "case {case}: axis {axis} accelerates at {a} mm/s^2 at period {k} (limit {})",
                    machine.max_accel[axis]
                );
            }
        }
        // Chord error: two samples on one arc, the arc between them
        // deviates from their chord by r (1 - cos(dtheta / 2)).
        for k in 1..i.points.len() {
            let (m0, m1) = (i.moves[k - 1], i.moves[k]);
            let Shape::Arc(geometry) = segments[m1].shape else {
                continue;
            };
            if m0 != m1 || k == i.points.len() - 1 {
                continue;
            }
            let angle = |p: [f64; 3]| (p[1] - geometry.center[1]).atan2(p[0] - geometry.center[0]);
            let d = (angle(i.points[k]) - angle(i.points[k - 1])).rem_euclid(std::f64::consts::TAU);
            let d = d.min(std::f64::consts::TAU - d);
            let r = geometry.radius[0].max(geometry.radius[1]);
            let sagitta = r * (1.0 - (d / 2.0).cos());
            assert!(
                sagitta <= machine.contour_error * (1.0 + 1e-6),
                "case {case}: chord error {sagitta} mm"
            );
            arcs_checked += 1;
        }
    }
    assert!(
        arcs_checked > 10_000,
        "the chord check saw {arcs_checked} arc periods"
    );
}
