//! Real files that no one on the team drew: `DejaVu` glyphs (TrueType quadratic contours with
//! holes) and Adwaita icons (SVG, cubic paths, arcs, transforms). Grid points are classified by
//! every method; all must agree, and agree with an independent dense polygon wherever the
//! point is clearly away from the boundary. Tests skip with a message when the system files
//! are absent, and fail instead where `INRS_REQUIRE_SYSTEM_FILES=1` (`.ci/run` installs
//! `fonts-dejavu-core`, `fonts-freefont-otf` and `adwaita-icon-theme` and sets it).

use rs_contain::Locate;
use rs_contain::{
    Classifier, ContainOptions, FastWindingField, Location, LocatorOptions, Method, PointLocator,
};
use rs_io::font::{Glyph, glyph_domain};
use rs_spline::{Domain, Point};
use rs_testkit::{DensePolygon, NearBoundary};

const DEJAVU: &str = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
const FREESANS: &str = "/usr/share/fonts/opentype/freefont/FreeSans.otf";

/// Classifies an `n x n` grid over the grown bounding box with every method; asserts they
/// agree with each other and with the dense polygon away from the boundary. Returns the number
/// of points checked against the polygon.
fn check_domain(name: &str, d: &Domain, n: usize) -> usize {
    let s = d.bounding_box().diagonal();
    let mut bb = d.bounding_box();
    let grow = Point::new(0.03 * s, 0.03 * s);
    bb.min = bb.min - grow;
    bb.max = bb.max + grow;
    // An irrational offset keeps grid lines off the (often integer) coordinates of the files;
    // points on vertices are covered by the inRS adversarial suites.
    let pts: Vec<Point> = (0..n * n)
        .map(|k| {
            let (i, j) = (k % n, k / n);
            Point::new(
                bb.min.x
                    + (i as f64 + 0.5 + 0.1 * std::f64::consts::SQRT_2) / n as f64 * bb.width(),
                bb.min.y + (j as f64 + 0.5 + 0.1 * std::f64::consts::E) / n as f64 * bb.height(),
            )
        })
        .collect();
    let classifier =
        Classifier::new(d, ContainOptions::default()).unwrap_or_else(|e| panic!("{name}: {e}"));
    let expected = classifier.locate_all_with(Method::InRS2, &pts);
    for method in Method::ALL {
        assert_eq!(
            classifier.locate_all_with(method, &pts),
            expected,
            "{name}: {method:?}"
        );
    }
    let locator = PointLocator::new(&classifier, LocatorOptions::DEFAULT.with_cells(64));
    assert_eq!(locator.locate_all(&pts), expected, "{name}: locator");
    let fast = FastWindingField::new(classifier.winding_field());
    for (p, e) in pts.iter().zip(&expected) {
        assert_eq!(fast.locate(*p), *e, "{name}: fast GWN at {p:?}");
    }
    let poly = DensePolygon::new(d, 1e-7 * s);
    let near = NearBoundary::new(&poly, 1e-5 * s);
    let mut checked = 0;
    for (p, e) in pts.iter().zip(&expected) {
        if !near.is_near(*p) {
            let want = if poly.contains(*p) {
                Location::Inside
            } else {
                Location::Outside
            };
            assert_eq!(*e, want, "{name}: {p:?}");
            checked += 1;
        }
    }
    checked
}

/// Shoelace area of the dense polygon (independent of the domain's quadrature).
fn polygon_area(poly: &DensePolygon) -> f64 {
    0.5 * poly.edges.iter().map(|(a, b)| a.cross(*b)).sum::<f64>()
}

fn dejavu() -> Option<Vec<u8>> {
    rs_testkit::system_file(DEJAVU, "fonts-dejavu-core")
}

#[test]
fn dejavu_glyphs_with_holes_have_the_right_loops_and_area() {
    let Some(font) = dejavu() else { return };
    // (glyph, contours): the outline plus one loop per counter (and the dot of 'i').
    for (c, loops) in [
        ('B', 3),
        ('8', 3),
        ('@', 2),
        ('g', 2),
        ('Q', 2),
        ('o', 2),
        ('i', 2),
    ] {
        let d = glyph_domain(&font, &Glyph::Char(c)).unwrap();
        assert_eq!(d.loops().len(), loops, "{c:?}");
        assert!(d.require_closed().is_ok(), "{c:?}");
        // TrueType draws outer contours clockwise and counters counter-clockwise.
        let area = d.signed_area();
        let reference = polygon_area(&DensePolygon::new(&d, 1e-9 * d.bounding_box().diagonal()));
        assert!(area < 0.0, "{c:?}: {area}");
        assert!(
            (area - reference).abs() < 1e-6 * area.abs(),
            "{c:?}: {area} vs {reference}"
        );
    }
}

#[test]
fn dejavu_printable_ascii_classifies_like_the_dense_polygon() {
    let Some(font) = dejavu() else { return };
    let mut glyphs = 0;
    let mut checked = 0;
    for code in 0x21u8..=0x7e {
        let c = char::from(code);
        let d = glyph_domain(&font, &Glyph::Char(c)).unwrap_or_else(|e| panic!("{c:?}: {e}"));
        checked += check_domain(&format!("DejaVuSans {c:?}"), &d, 40);
        glyphs += 1;
    }
    assert_eq!(glyphs, 94);
    assert!(
        checked > 94 * 1400,
        "only {checked} points were away from the boundaries"
    );
}

#[test]
fn opentype_cff_glyphs_have_cubic_contours_and_classify_like_the_dense_polygon() {
    let Some(font) = rs_testkit::system_file(FREESANS, "fonts-freefont-otf") else {
        return;
    };
    let mut cubic = 0;
    for c in ['B', '8', '@', 'g', 'Q', 'S', '&', 'e'] {
        let d = glyph_domain(&font, &Glyph::Char(c)).unwrap_or_else(|e| panic!("{c:?}: {e}"));
        cubic += d.curves().iter().filter(|k| k.degree() == 3).count();
        assert!(d.require_closed().is_ok(), "{c:?}");
        let checked = check_domain(&format!("FreeSans {c:?}"), &d, 40);
        assert!(checked > 1200, "{c:?}: {checked}");
    }
    assert!(
        cubic > 50,
        "CFF outlines should be cubic: {cubic} cubic curves"
    );
}

#[test]
fn a_space_has_no_outline() {
    let Some(font) = dejavu() else { return };
    let e = glyph_domain(&font, &Glyph::Char(' ')).unwrap_err();
    assert!(e.to_string().contains("no outline"), "{e}");
    let e = glyph_domain(&font, &Glyph::Char('\u{10FFFD}')).unwrap_err();
    assert!(e.to_string().contains("not in the font"), "{e}");
}

#[test]
fn adwaita_icons_classify_like_the_dense_polygon() {
    let files = rs_testkit::adwaita_icons();
    if files.is_empty() {
        return;
    }
    let (mut icons, mut empty, mut checked) = (0, 0, 0);
    for f in &files {
        match rs_io::svg::domain_from_svg_file(f) {
            Ok(d) => {
                checked += check_domain(&f.display().to_string(), &d, 24);
                icons += 1;
            }
            // Icons drawn only with images or strokes have no filled boundary.
            Err(rs_io::IoError::Empty(_)) => empty += 1,
            Err(e) => panic!("{}: {e}", f.display()),
        }
    }
    eprintln!("{icons} icons classified, {empty} without curves, {checked} points checked");
    assert!(
        icons > 0 && icons >= 10 * empty,
        "{icons} icons, {empty} empty"
    );
    assert!(checked > icons * 300);
}
