//! Our SVG reader against an independent one, the resvg project's `usvg`, on every SVG icon of
//! the installed Adwaita theme (`adwaita-icon-theme`; skipped with a message when absent,
//! a failure where `INRS_REQUIRE_SYSTEM_FILES=1`).
//!
//! What both readers must agree on is geometry: the boundary curves of every drawn shape
//! (`usvg` keeps a shape's path whatever its fill or stroke, so every path of its tree counts;
//! clip paths, masks and definitions stay out of its tree as they stay out of ours), in the
//! root's user units. `usvg` maps everything through the root's `viewBox` transform; our reader
//! does not apply it (docs/FORMATS.md), so the `usvg` paths are mapped back by its inverse.
//! `usvg` turns arcs into cubics and we flatten its paths, so the comparison leaves out points
//! within `NEAR` (relative to the diagonal) of the flattened boundary. For every other point of
//! a grid over the icon, the integer winding number of all the flattened subpaths (each closed,
//! as for filling) must equal our winding number, and their crossing parity our even-odd
//! classification.

use std::path::Path;

use rs_contain::{Classifier, ContainOptions, FastWindingField, Location, Method};
use rs_spline::{BoundingBox, Domain, Point};
use rs_testkit::{DensePolygon, NearBoundary};
use usvg::tiny_skia_path::{self, PathSegment};

/// Points per side of the grid classified in each icon.
const GRID: usize = 64;

/// Points closer than this fraction of the diagonal to the flattened `usvg` boundary are not
/// compared (arcs as cubics, flattening).
const NEAR: f64 = 1e-3;

/// The two bounding boxes agree within this fraction of the diagonal.
const BOX_TOLERANCE: f64 = 1e-4;

/// Straight pieces per Bezier segment of a `usvg` path (chord error below 1e-5 of the size of
/// a 16-unit icon).
const PIECES: usize = 64;

/// Icons our reader reads differently from `usvg` on purpose, with the reason (the file
/// name). Each must still disagree or be refused, so that the list stays true.
const EXCLUDED: &[(&str, &str)] = &[];

/// A 2-D affine map in `f64`: `(x, y) -> (a x + c y + e, b x + d y + f)`.
#[derive(Clone, Copy, Debug)]
struct Map {
    a: f64,
    b: f64,
    c: f64,
    d: f64,
    e: f64,
    f: f64,
}

impl Map {
    fn apply(&self, x: f64, y: f64) -> Point {
        Point::new(
            self.a * x + self.c * y + self.e,
            self.b * x + self.d * y + self.f,
        )
    }

    /// `self` after `inner`.
    fn after(&self, inner: &Map) -> Map {
        Map {
            a: self.a * inner.a + self.c * inner.b,
            b: self.b * inner.a + self.d * inner.b,
            c: self.a * inner.c + self.c * inner.d,
            d: self.b * inner.c + self.d * inner.d,
            e: self.a * inner.e + self.c * inner.f + self.e,
            f: self.b * inner.e + self.d * inner.f + self.f,
        }
    }

    fn from_usvg(t: tiny_skia_path::Transform) -> Map {
        Map {
            a: f64::from(t.sx),
            b: f64::from(t.ky),
            c: f64::from(t.kx),
            d: f64::from(t.sy),
            e: f64::from(t.tx),
            f: f64::from(t.ty),
        }
    }
}

/// The inverse of the root's viewBox-to-viewport map (SVG's default `preserveAspectRatio`,
/// `xMidYMid meet`), for a viewport of `size`; the identity without a `viewBox`.
fn user_units_from_viewport(text: &str, size: usvg::Size) -> Map {
    let identity = Map {
        a: 1.0,
        b: 0.0,
        c: 0.0,
        d: 1.0,
        e: 0.0,
        f: 0.0,
    };
    let doc = roxmltree::Document::parse_with_options(
        text,
        roxmltree::ParsingOptions {
            allow_dtd: true,
            ..Default::default()
        },
    )
    .expect("usvg read it, so it is XML");
    let root = doc.root_element();
    assert!(
        root.attribute("preserveAspectRatio").is_none(),
        "the test maps only the default preserveAspectRatio"
    );
    let Some(vb) = root.attribute("viewBox") else {
        return identity;
    };
    let v: Vec<f64> = vb
        .split(|c: char| c == ',' || c.is_whitespace())
        .filter(|s| !s.is_empty())
        .map(|s| s.parse().expect("a viewBox of plain numbers"))
        .collect();
    let [vx, vy, vw, vh] = v[..] else {
        panic!("viewBox {vb:?}")
    };
    let (w, h) = (f64::from(size.width()), f64::from(size.height()));
    let s = (w / vw).min(h / vh);
    let (tx, ty) = ((w - vw * s) / 2.0 - vx * s, (h - vh * s) / 2.0 - vy * s);
    // Inverse of p -> s p + t.
    Map {
        a: 1.0 / s,
        b: 0.0,
        c: 0.0,
        d: 1.0 / s,
        e: -tx / s,
        f: -ty / s,
    }
}

/// Every subpath of every path of `usvg`'s tree, flattened and mapped by `to_user` after the
/// path's own absolute transform; subpaths are closed (first point repeated at the end), and
/// those without area (all points on one line) are dropped, as our reader drops them.
fn usvg_polygons(group: &usvg::Group, to_user: &Map, out: &mut Vec<Vec<Point>>) {
    for node in group.children() {
        match node {
            usvg::Node::Group(g) => usvg_polygons(g, to_user, out),
            usvg::Node::Path(p) => {
                let map = to_user.after(&Map::from_usvg(p.abs_transform()));
                let at = |q: tiny_skia_path::Point| map.apply(f64::from(q.x), f64::from(q.y));
                let mut current: Vec<Point> = Vec::new();
                let mut finish = |current: &mut Vec<Point>| {
                    if current.len() > 2 && has_area(current) {
                        let first = current[0];
                        current.push(first);
                        out.push(std::mem::take(current));
                    } else {
                        current.clear();
                    }
                };
                for seg in p.data().segments() {
                    let last = current.last().copied();
                    let bezier = |controls: &[Point], current: &mut Vec<Point>| {
                        let Some(p0) = last else { return };
                        for k in 1..=PIECES {
                            current.push(de_casteljau(p0, controls, k as f64 / PIECES as f64));
                        }
                    };
                    match seg {
                        PathSegment::MoveTo(q) => {
                            finish(&mut current);
                            current.push(at(q));
                        }
                        PathSegment::LineTo(q) => current.push(at(q)),
                        PathSegment::QuadTo(c, q) => bezier(&[at(c), at(q)], &mut current),
                        PathSegment::CubicTo(c1, c2, q) => {
                            bezier(&[at(c1), at(c2), at(q)], &mut current);
                        }
                        PathSegment::Close => finish(&mut current),
                    }
                }
                finish(&mut current);
            }
            // Images and text (not built here: no `text` feature) have no outline.
            _ => {}
        }
    }
}

fn de_casteljau(p0: Point, controls: &[Point], t: f64) -> Point {
    let mut pts: Vec<Point> = std::iter::once(p0)
        .chain(controls.iter().copied())
        .collect();
    while pts.len() > 1 {
        for i in 0..pts.len() - 1 {
            pts[i] = pts[i] + (pts[i + 1] - pts[i]) * t;
        }
        pts.pop();
    }
    pts[0]
}

fn has_area(pts: &[Point]) -> bool {
    let p0 = pts[0];
    let far = pts
        .iter()
        .copied()
        .max_by(|a, b| a.distance(p0).total_cmp(&b.distance(p0)))
        .unwrap_or(p0);
    let d = far - p0;
    let len = d.length();
    len > 0.0
        && pts
            .iter()
            .any(|&q| (q - p0).cross(d).abs() > 1e-9 * len * len)
}

fn bounding_box(polygons: &[Vec<Point>]) -> Option<BoundingBox> {
    polygons
        .iter()
        .flatten()
        .map(|&p| BoundingBox::from_point(p))
        .reduce(BoundingBox::union)
}

/// The integer winding number of the closed `polygons` at every point of `rows` (points of
/// one row share their `y`), by crossings of the horizontal line through the row.
fn winding_numbers(polygons: &[Vec<Point>], rows: &[Vec<Point>]) -> Vec<Vec<i64>> {
    rows.iter()
        .map(|row| {
            let y = row[0].y;
            // (x of the crossing, +1 upwards / -1 downwards), a half-open rule at vertices.
            let mut crossings: Vec<(f64, i64)> = polygons
                .iter()
                .flat_map(|poly| poly.windows(2))
                .filter(|w| (w[0].y <= y) != (w[1].y <= y))
                .map(|w| {
                    let (a, b) = (w[0], w[1]);
                    let x = a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y);
                    (x, if b.y > a.y { 1 } else { -1 })
                })
                .collect();
            crossings.sort_by(|p, q| p.0.total_cmp(&q.0));
            // Counter-clockwise (in x-right, y-up terms) counts +1: the crossings to the
            // right of the point, upward ones positive.
            row.iter()
                .map(|p| {
                    crossings
                        .iter()
                        .filter(|(x, _)| *x > p.x)
                        .map(|(_, dir)| dir)
                        .sum()
                })
                .collect()
        })
        .collect()
}

/// How one icon compares.
enum Outcome {
    /// Geometry agrees; the number of grid points compared.
    Agreed(usize),
    /// Neither reader finds a shape with area.
    BothEmpty,
    /// What differs.
    Differs(String),
}

fn compare(file: &Path) -> Outcome {
    let text = std::fs::read_to_string(file).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
    let tree = match usvg::Tree::from_str(&text, &usvg::Options::default()) {
        Ok(t) => t,
        Err(e) => return Outcome::Differs(format!("usvg refuses it: {e}")),
    };
    let to_user = user_units_from_viewport(&text, tree.size());
    let mut polygons = Vec::new();
    usvg_polygons(tree.root(), &to_user, &mut polygons);
    let ours = rs_io::svg::domain_from_svg_str(&text);
    let d: Domain = match (ours, polygons.is_empty()) {
        (Ok(d), false) => d,
        (Err(rs_io::IoError::Empty(_)), true) => return Outcome::BothEmpty,
        (Ok(_), true) => return Outcome::Differs("usvg finds no shape with area".into()),
        (Err(e), _) => return Outcome::Differs(format!("our reader refuses it: {e}")),
    };
    let ours_box = d.bounding_box();
    let Some(theirs) = bounding_box(&polygons) else {
        return Outcome::Differs("usvg has no points".into());
    };
    let diagonal = theirs.diagonal();
    let tol = BOX_TOLERANCE * diagonal;
    if ours_box.min.distance(theirs.min) > tol || ours_box.max.distance(theirs.max) > tol {
        return Outcome::Differs(format!(
            "bounding boxes: ours [{}, {}] x [{}, {}], usvg's [{}, {}] x [{}, {}]",
            ours_box.min.x,
            ours_box.max.x,
            ours_box.min.y,
            ours_box.max.y,
            theirs.min.x,
            theirs.max.x,
            theirs.min.y,
            theirs.max.y
        ));
    }
    // The grid over the box grown by 3%, off the (often integer) coordinates of the files.
    let grow = Point::new(0.03 * diagonal, 0.03 * diagonal);
    let (lo, hi) = (theirs.min - grow, theirs.max + grow);
    let rows: Vec<Vec<Point>> = (0..GRID)
        .map(|j| {
            let y =
                lo.y + (j as f64 + 0.5 + 0.1 * std::f64::consts::E) / GRID as f64 * (hi.y - lo.y);
            (0..GRID)
                .map(|i| {
                    let x = lo.x
                        + (i as f64 + 0.5 + 0.1 * std::f64::consts::SQRT_2) / GRID as f64
                            * (hi.x - lo.x);
                    Point::new(x, y)
                })
                .collect()
        })
        .collect();
    let expected = winding_numbers(&polygons, &rows);
    let near = NearBoundary::new(
        &DensePolygon {
            edges: polygons
                .iter()
                .flat_map(|p| p.windows(2).map(|w| (w[0], w[1])))
                .collect(),
        },
        NEAR * diagonal,
    );
    let classifier = Classifier::new(&d, ContainOptions::default())
        .unwrap_or_else(|e| panic!("{}: {e}", file.display()));
    let field = FastWindingField::new(classifier.winding_field());
    let points: Vec<Point> = rows.iter().flatten().copied().collect();
    let even_odd = classifier.locate_all_with(Method::InRS2, &points);
    let mut compared = 0;
    let mut wrong = Vec::new();
    for ((p, w_usvg), loc) in points.iter().zip(expected.iter().flatten()).zip(&even_odd) {
        if near.is_near(*p) {
            continue;
        }
        compared += 1;
        let w = field.winding_number(*p);
        let parity = if w_usvg.rem_euclid(2) == 1 {
            Location::Inside
        } else {
            Location::Outside
        };
        if (w - *w_usvg as f64).abs() > 1e-6 || *loc != parity {
            wrong.push(format!(
                "({}, {}): winding {w} vs usvg's {w_usvg}, {loc:?}",
                p.x, p.y
            ));
        }
    }
    if wrong.is_empty() {
        Outcome::Agreed(compared)
    } else {
        Outcome::Differs(format!(
            "{} of {compared} points differ, first {}",
            wrong.len(),
            wrong[0]
        ))
    }
}

#[test]
fn adwaita_icons_read_like_usvg_reads_them() {
    let files = rs_testkit::adwaita_icons();
    if files.is_empty() {
        return;
    }
    let (mut agreed, mut empty, mut points) = (0, 0, 0);
    let mut failures = Vec::new();
    let mut excluded = Vec::new();
    for f in &files {
        let name = f.file_name().and_then(|n| n.to_str()).unwrap_or("");
        let exclusion = EXCLUDED.iter().find(|(n, _)| *n == name);
        match (compare(f), exclusion) {
            (Outcome::Agreed(n), None) => {
                agreed += 1;
                points += n;
            }
            (Outcome::BothEmpty, None) => empty += 1,
            (Outcome::Differs(why), None) => failures.push(format!("{}: {why}", f.display())),
            (Outcome::Differs(why), Some((_, reason))) => {
                excluded.push(format!("{name} ({reason}): {why}"));
            }
            (_, Some((_, reason))) => failures.push(format!(
                "{}: listed as excluded ({reason}) but agrees: take it off the list",
                f.display()
            )),
        }
    }
    eprintln!(
        "{} icons: {agreed} agree ({points} points compared), {empty} without shapes in both \
         readers, {} excluded, {} differ",
        files.len(),
        excluded.len(),
        failures.len()
    );
    for e in &excluded {
        eprintln!("excluded: {e}");
    }
    assert!(
        failures.is_empty(),
        "{} icons differ:\n{}",
        failures.len(),
        failures.join("\n")
    );
    assert_eq!(excluded.len(), EXCLUDED.len());
    assert!(
        agreed > 0 && agreed >= 10 * (empty + excluded.len()),
        "{agreed} agree, {empty} empty, {} excluded",
        excluded.len()
    );
    assert!(
        points > agreed * GRID * GRID / 4,
        "{points} points compared"
    );
}

/// Path data with an error, as icon themes have it: drawn up to its last complete segment,
/// as the SVG specification says, by our reader as by `usvg` (the winding numbers of every
/// grid point agree, the elements after the path read as usual), with one warning naming the
/// path.
#[test]
fn path_data_with_errors_is_drawn_up_to_the_error_as_usvg_draws_it() {
    let dir = std::env::temp_dir().join(format!("inrs-usvg-path-errors-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let cases = [
        // A command without its arguments at the end (the Adwaita-style case).
        "M 13,9 3,19 h 11 v -3 l",
        // An implicit repetition cut short.
        "M 0 0 L 10 0 10 10 5",
        // A letter that is no command.
        "M 0 0 L 10 0 L 10 10 x 5 5",
        // An error in a second subpath: the first one whole, the second up to it.
        "M 0 0 L 10 0 L 10 10 Z M 20 20 L 30 20 L 30 30 L 25",
        // A curve whose arguments run out.
        "M 0 0 C 5 0 10 5 10 10 C 10",
        // An arc flag that is not 0 or 1.
        "M 0 0 h 10 v 10 A 5 5 0 2 0 0 0",
        // A trailing moveto without its point after a closed subpath.
        "M 0 0 h 10 v 10 h -10 z m",
    ];
    for (k, d) in cases.iter().enumerate() {
        let text = format!(
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="40" height="40"><path id="p{k}" d="{d}"/><circle cx="35" cy="35" r="3"/></svg>"#
        );
        let file = dir.join(format!("case{k}.svg"));
        std::fs::write(&file, &text).unwrap();
        match compare(&file) {
            Outcome::Agreed(n) => assert!(n > GRID * GRID / 2, "{d}: {n} points compared"),
            Outcome::BothEmpty => panic!("{d}: nothing drawn"),
            Outcome::Differs(why) => panic!("{d}: {why}"),
        }
        let read = rs_io::svg::load_svg_str(&text, rs_io::svg::OpenSubpaths::Close).unwrap();
        assert_eq!(read.warnings.len(), 1, "{d}");
        let w = read.warnings[0].to_string();
        assert!(
            w.contains(&format!("path id=\"p{k}\""))
                && w.contains("drawn up to")
                && !w.contains('\n'),
            "{d}: {w}"
        );
        // Path data read on its own is strict.
        assert!(rs_io::svg::curves_from_path_data(d).is_err(), "{d}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
