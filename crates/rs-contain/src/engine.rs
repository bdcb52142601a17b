//! Which algorithm answers a batch: decided here, once, for the library and every front end.

use rs_spline::{Domain, Point};

use crate::query::PARALLEL_CHUNK;
use crate::{
    Classifier, ContainError, ContainOptions, FastWindingField, Locate, Location, Method,
    PointLocator, PointQuery, PointSource, WindingField, fast_uses_locator,
};

/// A domain prepared for containment queries with given options: what the command line and
/// the Python package build from a domain and its options before they read any point.
///
/// [`Method::Gwn`] builds only the [`WindingField`] with the options' fill rule (so open
/// boundaries are allowed); every other method builds a [`Classifier`] (closed loops only).
/// [`Containment::engine`] then hands back what answers a batch of `n` points.
///
/// ```
/// use rs_contain::{Containment, ContainOptions, Locate, Location, PointQuery};
/// use rs_spline::{circle, Domain, Point};
/// let d = Domain::new(vec![circle(Point::new(0.0, 0.0), 1.0).unwrap()]).unwrap();
/// let c = Containment::new(&d, ContainOptions::DEFAULT).unwrap();
/// let pts = [Point::new(0.5, 0.0), Point::new(2.0, 0.0)];
/// let mut out = [Location::Outside; 2];
/// c.engine(pts.len()).values_into(&pts[..], &mut out);
/// assert_eq!(out, [Location::Inside, Location::Outside]);
/// ```
#[derive(Clone)]
pub struct Containment(Prepared);

#[derive(Clone)]
// One value per domain, held for the whole run: its size does not matter.
#[allow(clippy::large_enum_variant)]
enum Prepared {
    Classifier(Classifier),
    Winding(WindingField),
}

impl Containment {
    /// Prepares `domain` for the method, tolerance, box subdivisions and fill rule of
    /// `options`.
    ///
    /// # Errors
    /// As [`Classifier::new`] (an open boundary, a bad tolerance, too many boxes), or for
    /// [`Method::Gwn`] as [`WindingField::new`].
    pub fn new(domain: &Domain, options: ContainOptions) -> Result<Self, ContainError> {
        let options = options.validated()?;
        Ok(Self(if options.method == Method::Gwn {
            Prepared::Winding(
                WindingField::new(domain, options.relative_tolerance)?
                    .with_fill_rule(options.fill_rule),
            )
        } else {
            Prepared::Classifier(Classifier::new(domain, options)?)
        }))
    }

    /// What answers a batch of `n` points (for a stream, its expected total).
    pub fn engine(&self, n: usize) -> Engine<'_> {
        match &self.0 {
            Prepared::Classifier(c) => c.engine(c.method(), n),
            Prepared::Winding(f) => Engine::Winding(FastWindingField::new(f)),
        }
    }

    /// The classifier, unless the method is [`Method::Gwn`].
    pub fn classifier(&self) -> Option<&Classifier> {
        match &self.0 {
            Prepared::Classifier(c) => Some(c),
            Prepared::Winding(_) => None,
        }
    }
}

/// The algorithm that answers a batch of points, as [`Classifier::engine`] and
/// [`Containment::engine`] choose it. Every engine gives every point the same location; they
/// differ in speed.
pub enum Engine<'a> {
    /// inRS1: each point against each candidate box.
    OneByOne(&'a Classifier),
    /// inRS2: the points sorted by abscissa, each monotone piece finding its points by binary
    /// search, and each refined box of a piece they come near finding its own among them.
    Sorted(&'a Classifier),
    /// The grid locator ([`Method::Fast`] on a batch large enough to pay for its grid).
    Grid(PointLocator<'a>),
    /// The classifier's winding-number field (its fill rule), after its bounding-box test.
    ClassifierWinding(&'a Classifier),
    /// The accelerated winding-number field with its own fill rule.
    Winding(FastWindingField<'a>),
}

/// The largest batch [`Method::Fast`] answers one point at a time (inRS1) while the refined
/// boxes are not built: inRS1 looks at the refined boxes of only the monotone pieces near each
/// point, so a handful of points costs far less than building every refined box, which inRS2
/// needs.
pub const FAST_ONE_BY_ONE_MAX_POINTS: usize = 16;

impl Classifier {
    /// What answers a batch of `n` points with `method`: [`Method::Fast`] takes the grid
    /// locator (built on first use, kept) when [`fast_uses_locator`]`(n)`, inRS1 for at most
    /// [`FAST_ONE_BY_ONE_MAX_POINTS`] points while the refined boxes are not built, inRS2
    /// otherwise. inRS1 for more than [`FAST_ONE_BY_ONE_MAX_POINTS`] points builds the refined
    /// boxes first.
    pub fn engine(&self, method: Method, n: usize) -> Engine<'_> {
        let tiny = n <= FAST_ONE_BY_ONE_MAX_POINTS;
        match method {
            Method::InRS1 => {
                if !tiny {
                    self.boxes().boxes();
                }
                Engine::OneByOne(self)
            }
            Method::Fast if fast_uses_locator(n) => Engine::Grid(self.locator()),
            Method::Fast if tiny && !self.boxes().is_refined() => Engine::OneByOne(self),
            Method::InRS2 | Method::Fast => Engine::Sorted(self),
            Method::Gwn => Engine::ClassifierWinding(self),
        }
    }

    /// The locations of `points` with `method` (rather than the one in the options), in input
    /// order; the same for every method.
    pub fn locate_all_with(&self, method: Method, points: &[Point]) -> Vec<Location> {
        let mut out = vec![Location::Outside; points.len()];
        match self.engine(method, points.len()) {
            // A batch large enough for the grid is large enough to split over the threads.
            Engine::Grid(l) => l.par_values_into(points, &mut out),
            e => e.values_into(points, &mut out),
        }
        out
    }
}

impl PointQuery<Location> for Classifier {
    /// The inRS1 path for one point.
    fn value(&self, p: Point) -> Location {
        self.classify_point_with_decision(p).0
    }

    /// With the method of the options ([`Classifier::engine`]), on the current thread.
    fn values_into<P: PointSource + ?Sized>(&self, points: &P, out: &mut [Location]) {
        self.engine(self.method(), points.len())
            .values_into(points, out);
    }

    fn par_values_into<P: PointSource + Sync + ?Sized>(&self, points: &P, out: &mut [Location]) {
        self.engine(self.method(), points.len())
            .par_values_into(points, out);
    }
}

impl PointQuery<Location> for Engine<'_> {
    fn value(&self, p: Point) -> Location {
        match self {
            Engine::OneByOne(c) | Engine::Sorted(c) => c.classify_point_with_decision(p).0,
            Engine::Grid(l) => l.locate(p),
            Engine::ClassifierWinding(c) => c.winding_location(p),
            Engine::Winding(f) => f.locate(p),
        }
    }

    fn values_into<P: PointSource + ?Sized>(&self, points: &P, out: &mut [Location]) {
        match self {
            Engine::OneByOne(c) => {
                assert_eq!(points.len(), out.len(), "one value per point");
                for (i, o) in out.iter_mut().enumerate() {
                    *o = c.classify_point_with_decision(points.point(i)).0;
                }
            }
            Engine::Sorted(c) => c.sorted_into(points, out),
            Engine::Grid(l) => l.values_into(points, out),
            Engine::ClassifierWinding(c) => {
                assert_eq!(points.len(), out.len(), "one value per point");
                for (i, o) in out.iter_mut().enumerate() {
                    *o = c.winding_location(points.point(i));
                }
            }
            Engine::Winding(f) => f.values_into(points, out),
        }
    }

    fn parallel_chunk(&self) -> usize {
        match self {
            Engine::Grid(l) => PointQuery::<Location>::parallel_chunk(l),
            Engine::Winding(f) => PointQuery::<Location>::parallel_chunk(f),
            _ => PARALLEL_CHUNK,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{FAST_METHOD_MIN_POINTS, FillRule, points_from_fn};
    use rs_spline::circle;
    use rs_spline::prelude::ParamCurve;

    /// An annulus 1 < r < 2 (two circles of one orientation), and a grid of points over it
    /// with their analytic locations (points within 1e-6 of a circle left out).
    fn annulus_and_points(n: usize) -> (Domain, Vec<Point>, Vec<Location>) {
        let d = Domain::new(vec![
            circle(Point::new(0.0, 0.0), 2.0).unwrap(),
            circle(Point::new(0.0, 0.0), 1.0).unwrap(),
        ])
        .unwrap();
        let mut pts = Vec::new();
        let mut expected = Vec::new();
        let side = (n as f64).sqrt().ceil() as usize;
        for i in 0..side {
            for j in 0..side {
                let p = Point::new(
                    -2.5 + 5.0 * i as f64 / side as f64,
                    -2.5 + 5.0 * j as f64 / side as f64,
                );
                let r = p.x.hypot(p.y);
                if (r - 1.0).abs() < 1e-6 || (r - 2.0).abs() < 1e-6 {
                    continue;
                }
                pts.push(p);
                expected.push(if r > 1.0 && r < 2.0 {
                    Location::Inside
                } else {
                    Location::Outside
                });
            }
        }
        (d, pts, expected)
    }

    /// The engine follows the batch size and the method; every engine, through every batch
    /// form and point layout, gives the analytic locations.
    #[test]
    fn every_engine_gives_the_analytic_locations() {
        let (d, pts, expected) = annulus_and_points(FAST_METHOD_MIN_POINTS + 5000);
        let n = pts.len();
        assert!(n >= FAST_METHOD_MIN_POINTS);
        let c = Classifier::new(&d, ContainOptions::DEFAULT).unwrap();
        assert!(matches!(c.engine(Method::Fast, n), Engine::Grid(_)));
        assert!(matches!(
            c.engine(Method::Fast, FAST_METHOD_MIN_POINTS - 1),
            Engine::Sorted(_)
        ));
        assert!(matches!(c.engine(Method::InRS1, n), Engine::OneByOne(_)));
        assert!(matches!(
            c.engine(Method::Gwn, n),
            Engine::ClassifierWinding(_)
        ));
        let (xs, ys): (Vec<f64>, Vec<f64>) = pts.iter().map(|p| (p.x, p.y)).unzip();
        let columns = points_from_fn(n, |i| Point::new(xs[i], ys[i]));
        for method in [Method::InRS1, Method::InRS2, Method::Fast, Method::Gwn] {
            let options = ContainOptions::DEFAULT.with_method(method);
            let containment = Containment::new(&d, options).unwrap();
            for batch in [n, 100] {
                let engine = containment.engine(batch);
                let mut out = vec![Location::Boundary; n];
                engine.values_into(&pts[..], &mut out);
                assert_eq!(out, expected, "{method:?} for {batch}, slice");
                out.fill(Location::Boundary);
                engine.par_values_into(&columns, &mut out);
                assert_eq!(out, expected, "{method:?} for {batch}, columns in parallel");
            }
            assert_eq!(c.locate_all_with(method, &pts), expected, "{method:?}");
        }
    }

    /// A tiny batch with `Method::Fast` is answered one by one without building the refined
    /// boxes (unless a point needs the fallback's rows), and every answer, on, near and away
    /// from the boundary, is the one the refined boxes give (inRS1 and inRS2 after the build).
    /// Seven points on each piece (`t = i / 6`), each also moved by `s x tol` for every `s`
    /// of `scales` in the four axis directions.
    fn near_pieces(d: &Domain, tol: f64, scales: &[f64]) -> Vec<Point> {
        let mut pts = Vec::new();
        for (_, b) in d.bezier_pieces() {
            for i in 0..=6 {
                let p = b.point_at(i as f64 / 6.0);
                pts.push(p);
                for s in scales {
                    for (dx, dy) in [(1.0, 0.0), (-1.0, 0.0), (0.0, 1.0), (0.0, -1.0)] {
                        pts.push(Point::new(p.x + dx * s * tol, p.y + dy * s * tol));
                    }
                }
            }
        }
        pts
    }

    #[test]
    fn a_tiny_batch_builds_no_refined_boxes_and_answers_alike() {
        let mut cases: Vec<(String, Domain)> = rs_testkit::fixtures()
            .into_iter()
            .map(|c| (c.name, c.domain))
            .collect();
        let (annulus, _, _) = annulus_and_points(4);
        cases.push(("annulus".into(), annulus));
        for (name, d) in cases {
            let eager = Classifier::new(&d, ContainOptions::DEFAULT).unwrap();
            assert!(!eager.boxes().is_refined(), "{name}");
            let tol = eager.abs_tol();
            // Points on the curves, moved by fractions and multiples of the tolerance, and a
            // grid over the bounding box.
            let mut pts = near_pieces(&d, tol, &[0.5, 0.7, 1.0, 1.4, 3.0]);
            let bb = d.bounding_box();
            for i in 0..=20 {
                for j in 0..=20 {
                    pts.push(Point::new(
                        bb.min.x - 0.1 * bb.width() + 1.2 * bb.width() * i as f64 / 20.0,
                        bb.min.y - 0.1 * bb.height() + 1.2 * bb.height() * j as f64 / 20.0,
                    ));
                }
            }
            let want = eager.locate_all_with(Method::InRS2, &pts);
            assert!(eager.boxes().is_refined(), "{name}");
            assert_eq!(eager.locate_all_with(Method::InRS1, &pts), want, "{name}");
            for (p, w) in pts.iter().zip(&want) {
                // A fresh classifier for every point, so that the refined boxes are computed
                // on the fly (the amortised build would otherwise take over).
                let lazy = Classifier::new(&d, ContainOptions::DEFAULT).unwrap();
                let engine = lazy.engine(Method::Fast, 1);
                assert!(matches!(engine, Engine::OneByOne(_)), "{name}");
                let mut out = [Location::Outside];
                engine.values_into(&[*p][..], &mut out);
                assert_eq!(out[0], *w, "{name} at {p:?}");
                if !lazy.boxes().is_critical_x(p.x, tol) {
                    assert!(!lazy.boxes().is_refined(), "{name} at {p:?}");
                }
            }
        }
        // Once built, a tiny batch takes inRS2 again; inRS1 on a large batch builds first.
        let (d, _, _) = annulus_and_points(4);
        let c = Classifier::new(&d, ContainOptions::DEFAULT).unwrap();
        assert!(matches!(c.engine(Method::InRS1, 2), Engine::OneByOne(_)));
        assert!(!c.boxes().is_refined());
        assert!(matches!(c.engine(Method::InRS1, 1000), Engine::OneByOne(_)));
        assert!(c.boxes().is_refined());
        assert!(matches!(c.engine(Method::Fast, 1), Engine::Sorted(_)));
    }

    /// inRS2 on a classifier whose refined boxes are not built (each piece's boxes computed on
    /// the fly, only for the pieces the points come near) gives every point, on, near and away
    /// from the boundary, the answer it gives once they are built, and inRS1's; a batch in a
    /// corner of the domain leaves most pieces unrefined.
    #[test]
    fn a_first_sorted_batch_refines_only_what_its_points_touch_and_answers_alike() {
        for case in rs_testkit::fixtures() {
            let (name, d) = (case.name, case.domain);
            let built = Classifier::new(&d, ContainOptions::DEFAULT).unwrap();
            built.boxes().boxes();
            let tol = built.abs_tol();
            let mut pts = near_pieces(&d, tol, &[0.5, 1.0, 2.0, 3.0, 1e6]);
            let bb = d.bounding_box();
            pts.extend(crate::baselines::halton_points(
                2000,
                bb.grown_by(0.05 * bb.diagonal()),
            ));
            let want = built.locate_all_with(Method::InRS2, &pts);
            assert_eq!(built.locate_all_with(Method::InRS1, &pts), want, "{name}");
            let lazy = Classifier::new(&d, ContainOptions::DEFAULT).unwrap();
            assert_eq!(lazy.locate_all_with(Method::InRS2, &pts), want, "{name}");
            // In batches of 100 (the pieces refined on the fly, then built once that adds up).
            let lazy = Classifier::new(&d, ContainOptions::DEFAULT).unwrap();
            for (chunk, w) in pts.chunks(100).zip(want.chunks(100)) {
                assert!(matches!(
                    lazy.engine(Method::Fast, chunk.len()),
                    Engine::Sorted(_)
                ));
                assert_eq!(lazy.locate_all_with(Method::InRS2, chunk), w, "{name}");
            }
            // Points in a corner of the box (clear of its sides, whose abscissas may be
            // critical: those points take the fallback, which builds every refined box).
            let corner = crate::baselines::halton_points(
                400,
                rs_spline::BoundingBox {
                    min: Point::new(bb.min.x + bb.width() / 32.0, bb.min.y + bb.height() / 32.0),
                    max: Point::new(bb.min.x + bb.width() / 16.0, bb.min.y + bb.height() / 16.0),
                },
            );
            let lazy = Classifier::new(&d, ContainOptions::DEFAULT).unwrap();
            let got = lazy.locate_all_with(Method::InRS2, &corner);
            assert_eq!(got, built.locate_all_with(Method::InRS2, &corner), "{name}");
            if lazy.boxes().box_count() > 4 * lazy.boxes().pieces().len() {
                assert!(
                    !lazy.boxes().is_refined(),
                    "{name}: a corner refines everything"
                );
            }
        }
    }

    /// `Method::Gwn` takes the fill rule of the options: the annulus's two circles have one
    /// orientation, so the hole has winding number 2, inside by the nonzero rule.
    #[test]
    fn the_winding_method_takes_the_fill_rule() {
        let (d, _, _) = annulus_and_points(4);
        let hole = [Point::new(0.5, 0.0)];
        for (rule, want) in [
            (FillRule::EvenOdd, Location::Outside),
            (FillRule::NonZero, Location::Inside),
        ] {
            let options = ContainOptions::DEFAULT
                .with_method(Method::Gwn)
                .with_fill_rule(rule);
            let c = Containment::new(&d, options).unwrap();
            assert!(c.classifier().is_none());
            let mut out = [Location::Boundary];
            c.engine(1).values_into(&hole[..], &mut out);
            assert_eq!(out, [want], "{rule:?}");
        }
    }
}
