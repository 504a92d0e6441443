//! Tests of `motion_hdl::host::soft_window` (`src/host/soft_window.rs`).

use motion_hdl::host::soft_window::*;

#[test]
fn reads_a_window_and_names_bad_ones() {
    assert_eq!(
        SoftWindow::parse("y=-1.5:20").unwrap(),
        SoftWindow {
            axis: 1,
            min_mm: -1.5,
            max_mm: 20.0
        }
    );
    for (text, message) in [
        ("y", "not AXIS=MIN:MAX"),
        ("y=3", "not AXIS=MIN:MAX"),
        ("w=0:1", "unknown axis `w`"),
        ("x=a:1", "`a` is not a number"),
        ("x=0:inf", "`inf` is not a number"),
        ("x=2:1", "the window is empty"),
    ] {
        let e = SoftWindow::parse(text).unwrap_err();
        assert!(e.contains(message), "{text}: {e}");
    }
    let x = SoftWindow::parse("x=0:1").unwrap();
    assert!(by_axis(&[x, x]).unwrap_err().contains("x given twice"));
}

#[test]
fn rounds_the_bounds_inward_from_the_start() {
    let w = SoftWindow::parse("x=-1.01:2.01").unwrap();
    assert_eq!(w.steps(100.0, 0), Ok((-101, 201)));
    assert_eq!(w.steps(100.0, 50), Ok((-151, 151)));
    assert_eq!(w.steps(10.0, 0), Ok((-10, 20)));
    let narrow = SoftWindow::parse("x=0.01:0.02").unwrap();
    assert!(narrow.steps(10.0, 0).unwrap_err().contains("holds no step"));
    let far = SoftWindow::parse("x=0:1000").unwrap();
    assert!(far.steps(10_000.0, 0).unwrap_err().contains("24-bit"));
    // Far enough to saturate an i64: still named, never wrapped.
    let huge = SoftWindow::parse("x=-1e18:5").unwrap();
    assert!(huge.steps(80.0, 0).unwrap_err().contains("24-bit"));
    let widest = SoftWindow::parse("x=-8388608:8388607").unwrap();
    assert_eq!(widest.steps(1.0, 0), Ok((-8_388_608, 8_388_607)));
}

#[test]
fn names_a_stop_past_the_bound() {
    let w = SoftWindow::parse("x=-1:4").unwrap();
    let inside = tripped_line(&w, false, [3.5, 0.0, 0.0], 5, 9);
    assert!(inside.contains("3.5000 mm, 0.5000 mm inside"), "{inside}");
    let past = tripped_line(&w, false, [4.25, 0.0, 0.0], 5, 9);
    assert!(past.contains("0.2500 mm PAST it"), "{past}");
}
