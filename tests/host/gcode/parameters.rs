//! Tests of `motion_hdl::host::gcode::parameters` (`src/host/gcode/parameters.rs`).

use motion_hdl::host::gcode::parameters::*;

#[test]
fn the_groups_are_where_linuxcnc_keeps_them() {
    let mut p = PersistentParameters::default();
    assert_eq!(p.active_system(), 0);
    for (n, v) in [
        (5161, 1.0),
        (5183, 3.0),
        (5211, -4.0),
        (5220, 9.0),
        (5381, 7.0),
    ] {
        p.set(n, v).unwrap();
    }
    p.set(5383, 8.0).unwrap();
    p.set(5210, 1.0).unwrap();
    assert_eq!(p.home(false), [1.0, 0.0, 0.0]);
    assert_eq!(p.home(true), [0.0, 0.0, 3.0]);
    assert_eq!(p.g92(), [-4.0, 0.0, 0.0]);
    assert_eq!(p.active_system(), 8);
    assert_eq!(p.origin(8), [7.0, 0.0, 8.0]);
    assert_eq!(p.origin(0), [0.0; 3]);
    p.set_g92([1.0, 2.0, 3.0], false);
    assert_eq!((p.g92(), p.g92_stored()), ([0.0; 3], [1.0, 2.0, 3.0]));
    assert_eq!(p.get(5212), Some(2.0));
    assert_eq!(p.get(5160), None);
}

#[test]
fn values_that_mean_nothing_here_are_refused_by_name() {
    let mut p = PersistentParameters::default();
    let error = |p: &mut PersistentParameters, n, v| p.set(n, v).unwrap_err();
    assert_eq!(
        error(&mut p, 5100, 1.0),
        "#5100 is not a parameter LinuxCNC keeps between runs (#5161 to #5390)"
    );
    assert_eq!(
        error(&mut p, 5164, 1.0),
        "#5164 = 1 is an offset along an A, B, C, U, V or W axis; this machine has X, Y and Z only"
    );
    assert_eq!(
        error(&mut p, 5230, 30.0),
        "#5230 = 30 rotates a coordinate system, which is not supported"
    );
    assert_eq!(
        error(&mut p, 5220, 10.0),
        "#5220 = 10 is not a coordinate system: 1 (G54) to 9 (G59.3)"
    );
    assert_eq!(
        error(&mut p, 5210, 0.5),
        "#5210 = 0.5: it is 1 when the G92 offset applies and 0 when not"
    );
    assert_eq!(
        error(&mut p, 5175, 0.0),
        "#5175 is a parameter LinuxCNC does not use"
    );
    assert_eq!(
        error(&mut p, 5231, 0.0),
        "#5231 is a parameter LinuxCNC does not use"
    );
    p.set(5164, 0.0).unwrap();
    p.set(5390, 0.0).unwrap();
    assert_eq!(p, PersistentParameters::default());
}
