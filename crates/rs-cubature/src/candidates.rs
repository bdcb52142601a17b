//! Candidate points strictly inside the domain, each kept only when the grid locator says
//! [`Location::Inside`] (farther than the boundary tolerance from the boundary): Halton points
//! in the bounding box, and above degree 20 also boundary layers ([`boundary_layers`]).

use std::f64::consts::{FRAC_PI_2, PI};

use rs_contain::baselines::halton_points_from;
use rs_contain::{Classifier, Locate, Location};
use rs_spline::prelude::*;
use rs_spline::{ArcLengthTable, Domain, Point, RationalBezier};

/// Most Halton points generated per candidate wanted: a domain that fills less than
/// `1 / 256` of its bounding box gets fewer candidates than wanted and an error, rather
/// than an unbounded search.
pub(crate) const MAX_GENERATED_PER_CANDIDATE: usize = 256;

/// The Halton points kept so far, and where the sequence continues: a retry adds to them.
#[derive(Debug)]
pub(crate) struct Candidates<'a> {
    classifier: &'a Classifier,
    points: Vec<Point>,
    /// Points of the sequence tried so far (the first, the box's corner, is skipped).
    generated: usize,
}

impl<'a> Candidates<'a> {
    pub(crate) fn new(classifier: &'a Classifier) -> Self {
        Self {
            classifier,
            points: Vec::new(),
            generated: 0,
        }
    }

    /// The points found inside.
    pub(crate) fn points(&self) -> &[Point] {
        &self.points
    }

    /// Points of the sequence tried.
    pub(crate) fn generated(&self) -> usize {
        self.generated
    }

    /// Tries further Halton points until `wanted` are inside or
    /// `MAX_GENERATED_PER_CANDIDATE * wanted` have been tried in all; keeps at most `wanted`.
    pub(crate) fn grow_to(&mut self, wanted: usize) {
        let bbox = self.classifier.boxes().bounding_box();
        let locator = self.classifier.locator();
        let budget = wanted.saturating_mul(MAX_GENERATED_PER_CANDIDATE);
        while self.points.len() < wanted && self.generated < budget {
            let missing = wanted - self.points.len();
            // Ask for the missing ones at the acceptance rate seen so far (at least 1 / 2).
            let rate = if self.generated > 0 {
                (self.points.len() as f64 / self.generated as f64).max(1.0 / 256.0)
            } else {
                0.5
            };
            let batch = ((missing as f64 / rate * 1.1) as usize + 64)
                .min(budget - self.generated)
                .max(1);
            let start = 1 + self.generated as u64;
            let points = halton_points_from(start, batch, bbox);
            let locations = locator.locate_all(&points);
            self.generated += batch;
            for (p, l) in points.into_iter().zip(locations) {
                if l == Location::Inside && self.points.len() < wanted {
                    self.points.push(p);
                }
            }
        }
    }
}

/// How densely [`boundary_layers`] samples: layers of offsets and points along the boundary per
/// unit of what a degree-`n` rule needs (see there); a retry multiplies both by `sqrt 2`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct LayerDensity {
    /// Layers per `(n + 2) / 4`.
    pub(crate) normal: f64,
    /// Points along the boundary per `(n + 1) / diagonal` of arc length.
    pub(crate) along: f64,
}

/// Panels per Bezier piece of its arc-length table (the candidates need spreading, not
/// accurate lengths: between the panels' ends the table is linear).
const ARC_PANELS: usize = 8;

/// A piece's end is a corner when its tangent turns by more than this (radians) into the next
/// piece's: points along the piece then cluster towards that end.
const CORNER_ANGLE: f64 = 0.0175; // 1 degree

/// Candidates that follow the boundary, as positive rules of high degree need (their nodes
/// cluster towards the boundary, at distances like those of Gauss points, about `1 / n^2` of
/// the domain's width from it), instead of uniform points that under-sample it:
/// - **Width.** `w = 2 A / L` (`A` the area, `L` the boundary's length: a disc's radius, half a
///   strip's width), at most half the bounding box's diagonal `D`.
/// - **Layers.** `K = ceil(normal (n + 2) / 4)` offset distances `d_k = w (1 - cos theta_k)`,
///   `theta_k = (k - 1/2) pi / (2 K)`: from about `w / K^2` to about `w`, spaced as Chebyshev
///   points are towards the ends of an interval of width `2 w` (`normal = 1` is about the
///   density of the `n / 2 + 1` Gauss-Legendre points a product rule of degree `n` has across
///   it).
/// - **Along the boundary.** On every Bezier piece `ceil(along (n + 1) l / D)` points by arc
///   length `l` (an [`ArcLengthTable`] of [`ARC_PANELS`] panels), evenly spaced, or spaced as
///   Chebyshev points towards an end that is a corner (the tangent turns by more than
///   [`CORNER_ANGLE`]), so that corners get the tensor-product clustering of Gauss rules;
///   `along` and `normal` are scaled down together if the points would exceed
///   `max_points`.
/// - **Points.** Each point on the boundary is offset by every `d_k` along both normals, and
///   kept when the grid locator says `Inside` (whichever side the domain is on: holes and loops
///   of either orientation need no care; offsets that cross to another part of the domain are
///   candidates too).
///
/// Points where the tangent vanishes are skipped; a domain without length gets none. The work
/// is bounded: at most `2 max_points` points classified, plus two per piece.
pub(crate) fn boundary_layers(
    domain: &Domain,
    classifier: &Classifier,
    degree: usize,
    area: f64,
    density: LayerDensity,
    max_points: usize,
) -> Vec<Point> {
    let (owners, pieces): (Vec<usize>, Vec<RationalBezier>) =
        domain.bezier_pieces().into_iter().unzip();
    let diagonal = domain.bounding_box().diagonal();
    let tables: Vec<ArcLengthTable> = pieces
        .iter()
        .map(|p| ArcLengthTable::new(p, ARC_PANELS))
        .collect();
    let total: f64 = tables.iter().map(ArcLengthTable::length).sum();
    if !(total > 0.0 && total.is_finite() && diagonal > 0.0 && area > 0.0) {
        return Vec::new();
    }
    let width = (2.0 * area / total).min(0.5 * diagonal);
    let (corner_start, corner_end) = corners(domain, &pieces, &owners);
    let n = degree as f64;
    let mut normal = density.normal;
    let mut along = density.along;
    // Points on the boundary times layers: at most max_points (twice that classified).
    let estimate = |normal: f64, along: f64| {
        let layers = (normal * (n + 2.0) / 4.0).ceil().max(1.0);
        layers * (along * (n + 1.0) * total / diagonal + pieces.len() as f64)
    };
    let e = estimate(normal, along);
    if e > max_points as f64 {
        let shrink = (max_points as f64 / e).sqrt();
        normal *= shrink;
        along *= shrink;
    }
    let layers = ((normal * (n + 2.0) / 4.0).ceil() as usize).max(1);
    let depths: Vec<f64> = (1..=layers)
        .map(|k| {
            let theta = (k as f64 - 0.5) * FRAC_PI_2 / layers as f64;
            width * (1.0 - theta.cos())
        })
        .collect();
    let rate = along * (n + 1.0) / diagonal;
    let mut points = Vec::new();
    for (i, (piece, table)) in pieces.iter().zip(&tables).enumerate() {
        let length = table.length();
        if length.is_nan() || length <= 0.0 {
            continue;
        }
        let count = ((length * rate).ceil() as usize).max(1);
        for j in 0..count {
            let x = (j as f64 + 0.5) / count as f64;
            let fraction = match (corner_start[i], corner_end[i]) {
                (true, true) => 0.5 * (1.0 - (PI * x).cos()),
                (true, false) => 1.0 - (FRAC_PI_2 * x).cos(),
                (false, true) => (FRAC_PI_2 * x).sin(),
                (false, false) => x,
            };
            let (p, tangent) = piece.point_and_tangent(table.u_at(fraction * length));
            let size = tangent.length();
            if !(size > 0.0 && size.is_finite() && p.is_finite()) {
                continue;
            }
            let unit_normal = Point::new(-tangent.y / size, tangent.x / size);
            for &d in &depths {
                points.push(p + unit_normal * d);
                points.push(p - unit_normal * d);
            }
        }
    }
    let locations = classifier.locator().locate_all(&points);
    points
        .into_iter()
        .zip(locations)
        .filter(|(_, l)| *l == Location::Inside)
        .map(|(p, _)| p)
        .collect()
}

/// For every piece, whether its start and its end are corners: the tangent directions (from
/// the first and last control points distinct from the ends) of consecutive pieces of a loop
/// differ by more than [`CORNER_ANGLE`]. An end whose direction is unknown counts as a corner.
fn corners(domain: &Domain, pieces: &[RationalBezier], owners: &[usize]) -> (Vec<bool>, Vec<bool>) {
    let start_direction = |b: &RationalBezier| {
        let c = b.control_points();
        c.iter()
            .skip(1)
            .map(|&q| q - c[0])
            .find(|d| d.length() > 0.0)
    };
    let end_direction = |b: &RationalBezier| {
        let c = b.control_points();
        let last = c[c.len() - 1];
        c.iter()
            .rev()
            .skip(1)
            .map(|&q| last - q)
            .find(|d| d.length() > 0.0)
    };
    let mut corner_start = vec![true; pieces.len()];
    let mut corner_end = vec![true; pieces.len()];
    let smooth = CORNER_ANGLE.cos();
    for l in domain.loops() {
        let curves = l.curves();
        let members: Vec<usize> = (0..pieces.len())
            .filter(|&i| curves.contains(&owners[i]))
            .collect();
        for (k, &i) in members.iter().enumerate() {
            let j = members[(k + 1) % members.len()];
            if let (Some(a), Some(b)) = (end_direction(&pieces[i]), start_direction(&pieces[j]))
                && a.dot(b) > smooth * a.length() * b.length()
            {
                corner_end[i] = false;
                corner_start[j] = false;
            }
        }
    }
    (corner_start, corner_end)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rs_contain::{ContainOptions, Method};
    use rs_spline::circle;

    /// A disc with two round holes (rational pieces, loops of both orientations).
    fn holed_disc() -> Domain {
        Domain::new(vec![
            circle(Point::new(0.0, 0.0), 2.0).unwrap(),
            circle(Point::new(-0.8, 0.3), 0.5).unwrap(),
            circle(Point::new(0.9, -0.2), 0.4).unwrap().reversed(),
        ])
        .unwrap()
    }

    #[test]
    fn boundary_layers_are_strictly_inside_a_domain_with_holes() {
        let d = holed_disc();
        let area = PI * (4.0 - 0.25 - 0.16);
        let classifier = Classifier::new(&d, ContainOptions::DEFAULT).unwrap();
        let density = LayerDensity {
            normal: 1.5,
            along: 2.5,
        };
        let points = boundary_layers(&d, &classifier, 30, area, density, 100_000);
        assert!(points.len() > 1000, "{} points", points.len());
        // Another method than the grid locator that chose them.
        let locations = classifier.locate_all_with(Method::InRS2, &points);
        for (p, l) in points.iter().zip(&locations) {
            assert_eq!(*l, Location::Inside, "{p:?}");
        }
        // Near every loop: the first layer is about w / K^2 from it (w = 2 area / length = 1.25,
        // K = 12 layers), far closer than uniform points of this number would come.
        for (c, r) in [((0.0, 0.0), 2.0), ((-0.8, 0.3), 0.5), ((0.9, -0.2), 0.4)] {
            let c = Point::new(c.0, c.1);
            let nearest = points
                .iter()
                .map(|p| (p.distance(c) - r).abs())
                .fold(f64::INFINITY, f64::min);
            assert!(nearest < 3e-3, "{nearest} from the circle of radius {r}");
        }
        // The cap holds.
        let few = boundary_layers(&d, &classifier, 30, area, density, 500);
        assert!(few.len() <= 1000, "{}", few.len());
    }

    #[test]
    fn corners_cluster_the_points_along_a_square() {
        let p = |x: f64, y: f64| Point::new(x, y);
        let ring = [
            p(0.0, 0.0),
            p(1.0, 0.0),
            p(1.0, 1.0),
            p(0.0, 1.0),
            p(0.0, 0.0),
        ];
        let d = Domain::new(vec![rs_spline::polyline(&ring).unwrap()]).unwrap();
        let classifier = Classifier::new(&d, ContainOptions::DEFAULT).unwrap();
        let density = LayerDensity {
            normal: 1.0,
            along: 1.0,
        };
        let points = boundary_layers(&d, &classifier, 30, 1.0, density, 100_000);
        assert!(!points.is_empty());
        assert!(
            points
                .iter()
                .all(|q| q.x > 0.0 && q.x < 1.0 && q.y > 0.0 && q.y < 1.0)
        );
        // Chebyshev spacing along each side: a point within 3e-3 of a corner in both directions
        // (evenly spaced, the nearest would be 2e-2 from it along the side).
        assert!(points.iter().any(|q| q.x < 3e-3 && q.y < 3e-3));
    }

    #[test]
    fn a_domain_without_length_gets_no_layers() {
        let d = holed_disc();
        let classifier = Classifier::new(&d, ContainOptions::DEFAULT).unwrap();
        let density = LayerDensity {
            normal: 1.0,
            along: 1.0,
        };
        assert!(boundary_layers(&d, &classifier, 30, 0.0, density, 1000).is_empty());
    }
}
