//! Helpers shared by the coverage tests.

use rs_contain::{FillRule, even_odd_area, filled_area, loop_depths, loop_nesting};
use rs_spline::quadrature::integrate_adaptive;
use rs_spline::{Domain, prelude::*};

/// `(area, first moment x, first moment y)` of the region of `d` under `rule`: each loop
/// with the sign that makes it bound the region on its left (0 for loops that do not bound
/// it), and `int int x dA = oint x^2 / 2 dy`, `int int y dA = -oint y^2 / 2 dx` on its pieces
/// by adaptive quadrature. Under even-odd the signs are also checked against the depths'
/// `(-1)^depth` times the orientation.
pub(crate) fn domain_moments(d: &Domain, rule: FillRule) -> (f64, f64, f64) {
    let depths = loop_depths(d).unwrap();
    let nesting = loop_nesting(d).unwrap();
    let (mut mx, mut my) = (0.0, 0.0);
    let scale = d.bounding_box().diagonal();
    for (i, l) in d.loops().iter().enumerate() {
        let a = d.loop_signed_area(i);
        let even_odd = a.signum()
            * if depths[i].is_multiple_of(2) {
                1.0
            } else {
                -1.0
            };
        let s = nesting[i].boundary_sign(rule) as f64;
        if rule == FillRule::EvenOdd {
            assert_eq!(s, even_odd, "loop {i}");
        }
        for c in l.curves() {
            for b in d.curves()[c].to_bezier() {
                let tol = 1e-16 * scale.powi(3);
                let fx = integrate_adaptive(
                    |t| {
                        let (p, v) = b.point_and_tangent(t);
                        (0.5 * p.x * p.x * v.y, 0.5 * p.x * p.x * v.y.abs())
                    },
                    0.0,
                    1.0,
                    tol,
                );
                let fy = integrate_adaptive(
                    |t| {
                        let (p, v) = b.point_and_tangent(t);
                        (-0.5 * p.y * p.y * v.x, 0.5 * p.y * p.y * v.x.abs())
                    },
                    0.0,
                    1.0,
                    tol,
                );
                mx += s * fx.value;
                my += s * fy.value;
            }
        }
    }
    let area = filled_area(d, rule).unwrap();
    if rule == FillRule::EvenOdd {
        assert_eq!(area.to_bits(), even_odd_area(d).unwrap().to_bits());
    }
    (area, mx, my)
}
