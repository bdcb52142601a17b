//! Winding-number queries allocate nothing: the per-curve field on any query with pieces of
//! degree <= 3, the fast field once the hierarchies a query needs exist.

use rs_contain::baselines::halton_points;
use rs_contain::{FastWindingField, WindingField};
use rs_spline::Point;
use rs_spline::prelude::*;

fn queries(field: &WindingField) -> Vec<Point> {
    let b = field.monotone_boxes().unwrap().bounding_box();
    let mut pts = halton_points(2000, b.grown_by(0.05 * b.diagonal()));
    // Near and on the curves, where the adaptive algorithm subdivides.
    for p in field.pieces() {
        let d = p.derivatives(0.3);
        let n = d.first.perp() / d.first.length();
        pts.extend([d.point, d.point + n * 1e-6 * b.diagonal(), p.start_point()]);
    }
    pts
}

#[test]
fn winding_queries_do_not_allocate() {
    for name in ["butterfly", "bubble", "twirl"] {
        let d = rs_testkit::gwn_shape(name);
        let field = WindingField::new(&d, rs_contain::DEFAULT_RELATIVE_TOLERANCE).unwrap();
        let fast = FastWindingField::new(&field);
        let pts = queries(&field);
        let mut sum = 0.0;
        let info = allocation_counter::measure(|| {
            sum += pts.iter().map(|&q| field.winding_number(q)).sum::<f64>();
        });
        assert_eq!(info.count_total, 0, "{name}: per-curve field");
        // The first pass builds the hierarchies it needs; the second allocates nothing.
        sum += pts.iter().map(|&q| fast.winding_number(q)).sum::<f64>();
        let info = allocation_counter::measure(|| {
            sum += pts.iter().map(|&q| fast.winding_number(q)).sum::<f64>();
        });
        assert_eq!(info.count_total, 0, "{name}: fast field");
        assert!(sum.is_finite());
    }
}
