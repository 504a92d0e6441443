//! Tests of `motion_hdl::host::laser_run` (`src/host/laser_run.rs`).

use motion_hdl::host::interpolator::interpolate;
use motion_hdl::host::laser_run::*;
use motion_hdl::host::machine::MachineSettings;
use motion_hdl::host::planner::plan_toolpath;
use motion_hdl::host::toolpath::{Item, Toolpath};
use motion_hdl::host::toolpath::{LaserPower, Move, MoveKind};

fn feed_move(x: f64, laser: LaserPower) -> Item {
    Item::Move(Move {
        kind: MoveKind::Line,
        end: [x, 0.0, 0.0],
        angles: [0.0; 3],
        feed: Some(10.0),
        laser,
        line: 1,
    })
}

#[test]
fn a_change_between_m3_and_m4_cuts_the_run_and_off_moves_join() {
    let m3 = LaserPower {
        fraction: 0.5,
        dynamic: false,
    };
    let m4 = LaserPower {
        fraction: 0.5,
        dynamic: true,
    };
    let items = [
        feed_move(1.0, LaserPower::OFF),
        feed_move(2.0, m4),
        feed_move(3.0, LaserPower::OFF),
        feed_move(4.0, m4),
        feed_move(5.0, m3),
        feed_move(6.0, LaserPower::OFF),
    ];
    let parts = split_by_mode(&items);
    let shape: Vec<(bool, usize)> = parts.iter().map(|p| (p.dynamic, p.items.len())).collect();
    assert_eq!(shape, [(true, 4), (false, 2)]);
}

#[test]
fn feed_is_the_planes_steps_per_period_and_power_the_clocks() {
    let machine = MachineSettings {
        steps_per_mm: [80.0, 160.0, 400.0],
        laser_s_max: 1000.0,
        ..MachineSettings::default()
    };
    let laser = LaserPower {
        fraction: 0.25,
        dynamic: true,
    };
    // Along Y at 10 mm/s, 1 ms periods: 1.6 steps a period, 25.6/16.
    let toolpath = Toolpath {
        items: vec![Item::Move(Move {
            kind: MoveKind::Line,
            end: [0.0, 20.0, 0.0],
            angles: [0.0; 3],
            feed: Some(10.0),
            laser,
            line: 3,
        })],
        ..Toolpath::default()
    };
    let segments = plan_toolpath(&toolpath, &machine).unwrap();
    let i = interpolate([0; 3], &segments, machine.period);
    let entries = laser_entries(&segments, &i, [0.0; 3], &machine, 1000).unwrap();
    // POWER 250 and FEED 26, both scaled by the headroom, 16.
    assert!(entries.iter().all(|e| e.power == 4000));
    assert!(entries.iter().all(|e| e.feed == 416), "{:?}", &entries[..3]);
    let burns = burns_of(&segments, &i, [0.0; 3], 0, &machine);
    assert_eq!(burns.len(), 1);
    assert_eq!(burns[0].periods.last().unwrap().0, 3200);
    let length: f64 = burns[0].periods.iter().map(|p| p.1).sum();
    assert!((length - 20.0).abs() < 1e-9, "{length}");
    assert!((burns[0].programmed - 0.025).abs() < 1e-12);
    // 1.6 steps a period at the feed, weighted by length (mm).
    assert!((burns[0].feed_steps / length - 1.6).abs() < 1e-9);
}
