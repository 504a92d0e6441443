//! Tests of `motion_hdl::host::geometry` (`src/host/geometry.rs`).

use motion_hdl::host::geometry::*;
use motion_hdl::host::toolpath::{Arc, Plane};

/// The derivatives of a spiral helix (its radius and its normal axis
/// both change) match finite differences of its points.
#[test]
fn the_derivatives_match_finite_differences() {
    for clockwise in [false, true] {
        let arc = Arc {
            plane: Plane::Zx,
            center: [1.0, 2.0],
            clockwise,
            turns: 1,
        };
        let g = ArcGeometry::new(&arc, [2.0 + 5.0, 0.0, 1.0], [2.0, 4.0, 1.0 + 5.5]);
        assert!((g.radius[1] - g.radius[0]).abs() > 0.4, "{g:?}");
        let h = 1e-6;
        for i in 1..50 {
            let f = i as f64 / 50.0;
            let (d1, d2) = g.derivatives(f);
            let (before, after) = (g.point(f - h), g.point(f + h));
            let (t0, t1) = (g.derivatives(f - h).0, g.derivatives(f + h).0);
            for k in 0..3 {
                let v = (after[k] - before[k]) / (2.0 * h);
                let a = (t1[k] - t0[k]) / (2.0 * h);
                assert!((v - d1[k]).abs() < 1e-5, "{f} {k}: {v} {}", d1[k]);
                assert!((a - d2[k]).abs() < 1e-3, "{f} {k}: {a} {}", d2[k]);
            }
        }
    }
}
