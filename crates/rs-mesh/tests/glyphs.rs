//! Curved triangulations of real outlines no one on the team drew: every printable ASCII glyph
//! of `DejaVu` Sans (quadratic contours, holes, tiny curves far from the origin), coarse and
//! fine. Skips with a message when the font is absent (`.ci/run` installs it).

use rs_contain::Locate;
use rs_contain::baselines::halton_points;
use rs_contain::{Classifier, ContainOptions, Location};
use rs_io::font::{Glyph, glyph_domain};
use rs_mesh::{CurvedLocator, CurvedTriangulation, well_spaced_points};

const DEJAVU: &str = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

#[test]
fn every_ascii_glyph_gets_a_curved_triangulation_covering_it_exactly() {
    let Some(font) = rs_testkit::system_file(DEJAVU, "fonts-dejavu-core") else {
        return;
    };
    for code in 0x21u8..=0x7e {
        let c = char::from(code);
        let d = glyph_domain(&font, &Glyph::Char(c)).unwrap();
        let exact = d.signed_area().abs(); // contours do not nest more than one level
        for ny in [6, 20] {
            let pts = well_spaced_points(&d, ny).unwrap();
            let m = CurvedTriangulation::new(&d, &pts).unwrap_or_else(|e| panic!("{c:?}: {e}"));
            let areas: Vec<f64> = (0..m.triangles().len())
                .map(|t| m.triangle_area(t))
                .collect();
            assert!(areas.iter().all(|&a| a > 0.0), "{c:?} ny={ny}");
            let total: f64 = areas.iter().sum();
            assert!(
                (total - exact).abs() <= 1e-9 * exact,
                "{c:?} ny={ny}: {total} vs {exact}"
            );
        }
        // Location agrees with containment.
        let m = CurvedTriangulation::new(&d, &well_spaced_points(&d, 10).unwrap()).unwrap();
        let loc = CurvedLocator::new(&m).unwrap();
        let cl = Classifier::new(&d, ContainOptions::default()).unwrap();
        for p in halton_points(300, d.bounding_box()) {
            let inside = cl.locate(p) != Location::Outside;
            assert_eq!(loc.triangle_at(p).is_some(), inside, "{c:?}: {p:?}");
        }
    }
}
