//! M3, M4, M5 and S on a laser machine (`Setup::laser_s_max`): the power
//! each move and dwell carries, and the refusals.

use motion_hdl::host::gcode::{interpret_with, Setup};
use motion_hdl::host::toolpath::{Item, LaserPower};

fn laser(program: &str) -> Result<Vec<(usize, LaserPower)>, String> {
    let setup = Setup {
        laser_s_max: Some(1000.0),
        ..Setup::default()
    };
    let p = interpret_with(program, &setup).map_err(|e| e.to_string())?;
    assert!(
        p.ignored.iter().all(|i| !["S", "M3", "M4", "M5"]
            .iter()
            .any(|w| i.word.starts_with(w))),
        "a laser machine uses S and M3 to M5: {:?}",
        p.ignored
    );
    Ok(p.toolpath
        .items
        .iter()
        .map(|i| match i {
            Item::Move(m) => (m.line, m.laser),
            Item::Dwell { laser, line, .. } => (*line, *laser),
            Item::Synced(m) => (m.line, LaserPower::OFF),
        })
        .collect())
}

fn power(fraction: f64, dynamic: bool) -> LaserPower {
    LaserPower { fraction, dynamic }
}

#[test]
fn m3_and_m4_burn_feed_moves_and_dwells_and_rapids_run_dark() {
    let items = laser(
        "G1 X1 F600\nM3 S500\nG1 X2\nG0 X3\nG4 P0.5\nM4 S250 G1 X4\nG2 X4 Y0 I1 J0\nM5\nG1 X5\nS800\nM4\nG1 X6",
    )
    .unwrap();
    assert_eq!(
        items,
        [
            (1, LaserPower::OFF),
            (3, power(0.5, false)),
            (4, LaserPower::OFF),
            (5, power(0.5, false)),
            (6, power(0.25, true)),
            (7, power(0.25, true)),
            (9, LaserPower::OFF),
            (12, power(0.8, true)),
        ]
    );
}

#[test]
fn an_s_beyond_full_power_is_refused_by_line() {
    assert_eq!(
        laser("M3 S500\nG1 X1 F100\nS1200").unwrap_err(),
        "line 3: S1200 is beyond the laser's full power, S1000 (laser_s_max in the machine settings)"
    );
    assert!(laser("M4 S1000\nG1 X1 F100").is_ok());
}

#[test]
fn without_a_laser_s_is_a_spindle_speed_and_no_move_burns() {
    let p = motion_hdl::host::gcode::interpret("M3 S12000\nG1 X1 F100").unwrap();
    match p.toolpath.items[0] {
        Item::Move(m) => assert_eq!(m.laser, LaserPower::OFF),
        other => panic!("{other:?}"),
    }
}
