//! Many domains at once: a batch of points per domain, the domains spread over the cores.
//!
//! A user with thousands of small domains (the faces of a CAD part, the glyphs of a font)
//! would otherwise build and query them one after the other, each build on one core. Here each
//! domain goes through the one decision of [`Containment::new`] and [`Containment::engine`]
//! (never a method of its own), and rayon hands the domains to the threads of its pool.

use std::borrow::Borrow;

use rs_spline::Domain;

use crate::{ContainError, ContainOptions, Containment, Engine, Location, PointQuery, PointSource};

/// One domain's answers in [`locate_many`] and [`locate_each`]: the locations of its points
/// in input order, or why the domain could not be prepared.
pub type DomainLocations = Result<Vec<Location>, ContainError>;

/// The locations of the same `points` in every domain of `domains`: `result[k][i]` is the
/// location of `points.point(i)` in `domains[k]`, exactly as
/// `Containment::new(&domains[k], options)?.engine(points.len())` gives it.
///
/// The domains are spread over rayon's pool (with the `parallel` feature, on by default;
/// otherwise one after the other): each domain is prepared and answers its batch on one
/// thread, unless its batch is larger than one parallel task of its engine
/// ([`PointQuery::parallel_chunk`]), which is then split over the pool as
/// [`PointQuery::par_values_into`] does. Both give every point the same location.
///
/// # Errors
/// One result per domain, in the order of `domains`: a domain that cannot be prepared (an
/// open boundary with a crossing method, a bad tolerance, too many boxes: the errors of
/// [`Containment::new`]) gets its own `Err`; every other domain still answers.
///
/// ```
/// use rs_contain::{ContainOptions, Location, locate_many};
/// use rs_spline::{circle, Domain, Point};
/// let disc = |r: f64| Domain::new(vec![circle(Point::new(0.0, 0.0), r).unwrap()]).unwrap();
/// let domains = [disc(1.0), disc(3.0)];
/// let points = [Point::new(0.5, 0.0), Point::new(2.0, 0.0)];
/// let found = locate_many(&domains, &points[..], ContainOptions::DEFAULT);
/// assert_eq!(found[0].as_ref().unwrap(), &[Location::Inside, Location::Outside]);
/// assert_eq!(found[1].as_ref().unwrap(), &[Location::Inside, Location::Inside]);
/// ```
pub fn locate_many<D, P>(domains: &[D], points: &P, options: ContainOptions) -> Vec<DomainLocations>
where
    D: Borrow<Domain> + Sync,
    P: PointSource + Sync + ?Sized,
{
    map_in_order(domains, |d| locate_one(d.borrow(), points, options))
}

/// The locations of each domain's own points: for `batches[k] = (domain, points)`,
/// `result[k][i]` is the location of `points.point(i)` in `domain`, as [`locate_many`] gives
/// it (the same decision per domain, the domains spread over the pool in the same way).
///
/// # Errors
/// One result per batch, in the order of `batches`; a domain that cannot be prepared gets its
/// own `Err` ([`Containment::new`]'s errors) and the others still answer.
///
/// ```
/// use rs_contain::{ContainOptions, Location, locate_each};
/// use rs_spline::{circle, Domain, Point};
/// let disc = Domain::new(vec![circle(Point::new(0.0, 0.0), 1.0).unwrap()]).unwrap();
/// let far = Domain::new(vec![circle(Point::new(10.0, 0.0), 1.0).unwrap()]).unwrap();
/// let near = [Point::new(0.0, 0.0)];
/// let both = [Point::new(10.0, 0.5), Point::new(0.0, 0.0)];
/// let found = locate_each(&[(&disc, &near[..]), (&far, &both[..])], ContainOptions::DEFAULT);
/// assert_eq!(found[0].as_ref().unwrap(), &[Location::Inside]);
/// assert_eq!(found[1].as_ref().unwrap(), &[Location::Inside, Location::Outside]);
/// ```
pub fn locate_each<D, P>(batches: &[(D, &P)], options: ContainOptions) -> Vec<DomainLocations>
where
    D: Borrow<Domain> + Sync,
    P: PointSource + Sync + ?Sized,
{
    map_in_order(batches, |(d, points)| {
        locate_one(d.borrow(), *points, options)
    })
}

/// Every domain of `domains` prepared with `options`, in order, the domains spread over the
/// pool as [`locate_many`] spreads them: `result[k]` is `Containment::new(&domains[k], options)`.
/// For a caller that streams points through many domains itself (then [`engines_many`]).
///
/// # Errors
/// One result per domain: a domain that cannot be prepared gets its own `Err`.
pub fn prepare_many<D>(
    domains: &[D],
    options: ContainOptions,
) -> Vec<Result<Containment, ContainError>>
where
    D: Borrow<Domain> + Sync,
{
    map_in_order(domains, |d| Containment::new(d.borrow(), options))
}

/// The engine of every prepared domain for a stream of about `n` points
/// ([`Containment::engine`]), in order, built over the pool (a grid locator's build is a
/// domain's largest cost after its preparation).
pub fn engines_many(prepared: &[Containment], n: usize) -> Vec<Engine<'_>> {
    map_in_order(prepared, |c| c.engine(n))
}

/// One domain's batch: prepared, the engine picked for the batch's size, then answered on
/// this thread, or split over the pool when the batch is longer than one parallel task.
fn locate_one<P: PointSource + Sync + ?Sized>(
    domain: &Domain,
    points: &P,
    options: ContainOptions,
) -> DomainLocations {
    let containment = Containment::new(domain, options)?;
    let n = points.len();
    let engine = containment.engine(n);
    let mut out = vec![Location::Outside; n];
    if n > engine.parallel_chunk() {
        engine.par_values_into(points, &mut out);
    } else {
        engine.values_into(points, &mut out);
    }
    Ok(out)
}

/// `f` of every item, in the items' order: on rayon's pool with the `parallel` feature, one
/// item per task (a domain's preparation dwarfs a task's cost), else in a loop.
fn map_in_order<'a, T: Sync, R: Send>(
    items: &'a [T],
    f: impl Fn(&'a T) -> R + Sync + Send,
) -> Vec<R> {
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        items.par_iter().with_max_len(1).map(f).collect()
    }
    #[cfg(not(feature = "parallel"))]
    {
        items.iter().map(f).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{FAST_METHOD_MIN_POINTS, Method};
    use rs_spline::{NurbsCurve, Point, circle};

    /// A disc of radius `r` about `(cx, 0)`.
    fn disc(cx: f64, r: f64) -> Domain {
        Domain::new(vec![circle(Point::new(cx, 0.0), r).unwrap()]).unwrap()
    }

    /// The annulus `r0 < |p - (cx, 0)| < r1`.
    fn annulus(cx: f64, r0: f64, r1: f64) -> Domain {
        Domain::new(vec![
            circle(Point::new(cx, 0.0), r1).unwrap(),
            circle(Point::new(cx, 0.0), r0).unwrap(),
        ])
        .unwrap()
    }

    /// An open boundary: one straight segment.
    fn open_segment() -> Domain {
        let line = NurbsCurve::new(
            1,
            vec![0.0, 0.0, 1.0, 1.0],
            vec![Point::new(0.0, 0.0), Point::new(1.0, 1.0)],
            None,
        )
        .unwrap();
        Domain::new(vec![line]).unwrap()
    }

    /// `n` points on a grid over `[-4, 4]^2`, none within 1e-6 of the circles of radius 1, 2
    /// and 3 about the origin.
    fn grid_points(n: usize) -> Vec<Point> {
        let side = (n as f64).sqrt().ceil() as usize;
        let mut pts = Vec::new();
        for i in 0..side {
            for j in 0..side {
                let p = Point::new(
                    -4.0 + 8.0 * (i as f64 + 0.37) / side as f64,
                    -4.0 + 8.0 * (j as f64 + 0.61) / side as f64,
                );
                let r = p.x.hypot(p.y);
                if [1.0, 2.0, 3.0].iter().all(|c| (r - c).abs() > 1e-6) {
                    pts.push(p);
                }
            }
        }
        pts
    }

    fn analytic(p: Point, r0: f64, r1: f64) -> Location {
        let r = p.x.hypot(p.y);
        if r > r0 && r < r1 {
            Location::Inside
        } else {
            Location::Outside
        }
    }

    /// Discs and annuli answer analytically, in the order given, for every method and for a
    /// batch small enough for one thread and one large enough for the grid and the pool.
    #[test]
    fn discs_and_annuli_answer_analytically_in_order() {
        let domains = [disc(0.0, 1.0), annulus(0.0, 1.0, 3.0), disc(0.0, 2.0)];
        let radii = [(-1.0, 1.0), (1.0, 3.0), (-1.0, 2.0)];
        for n in [200, FAST_METHOD_MIN_POINTS + 10_000] {
            let pts = grid_points(n);
            for method in [Method::Fast, Method::InRS1, Method::InRS2, Method::Gwn] {
                let options = ContainOptions::DEFAULT.with_method(method);
                let found = locate_many(&domains, &pts[..], options);
                assert_eq!(found.len(), domains.len());
                for (k, (r0, r1)) in radii.into_iter().enumerate() {
                    let want: Vec<_> = pts.iter().map(|&p| analytic(p, r0, r1)).collect();
                    let got = found[k].as_ref().unwrap();
                    assert_eq!(got, &want, "domain {k}, {method:?}, {n} points");
                }
            }
        }
    }

    /// Every domain's answers equal one call per domain through `Containment`, points on the
    /// circles (the boundary) included.
    #[test]
    fn answers_equal_one_call_per_domain() {
        let domains: Vec<Domain> = (0..12)
            .map(|k| {
                if k % 2 == 0 {
                    disc(0.1 * k as f64, 1.0 + 0.2 * k as f64)
                } else {
                    annulus(-0.1 * k as f64, 0.5, 1.5 + 0.1 * k as f64)
                }
            })
            .collect();
        let mut pts = grid_points(900);
        // Points on and near the boundaries too.
        for k in 0..64 {
            let t = k as f64 * std::f64::consts::TAU / 64.0;
            for r in [0.5, 1.0, 1.5, 2.0, 2.0 + 1e-13] {
                pts.push(Point::new(r * t.cos(), r * t.sin()));
            }
        }
        for method in [Method::Fast, Method::InRS2, Method::Gwn] {
            let options = ContainOptions::DEFAULT.with_method(method);
            let found = locate_many(&domains, &pts[..], options);
            let each: Vec<(&Domain, &[Point])> = domains.iter().map(|d| (d, &pts[..])).collect();
            let found_each = locate_each(&each, options);
            for (k, d) in domains.iter().enumerate() {
                let c = Containment::new(d, options).unwrap();
                let mut want = vec![Location::Outside; pts.len()];
                c.engine(pts.len()).values_into(&pts[..], &mut want);
                assert_eq!(found[k].as_ref().unwrap(), &want, "domain {k}, {method:?}");
                assert_eq!(found_each[k].as_ref().unwrap(), &want, "domain {k}");
            }
            assert!(
                found
                    .iter()
                    .flatten()
                    .flatten()
                    .any(|&l| l == Location::Boundary),
                "the test has boundary points"
            );
        }
    }

    /// An open domain gets its own error with a crossing method while the others answer; the
    /// winding-number method accepts it.
    #[test]
    fn an_open_domain_fails_alone() {
        let domains = [disc(0.0, 1.0), open_segment(), disc(0.0, 2.0)];
        let pts = [Point::new(1.5, 0.0), Point::new(0.0, 0.0)];
        let found = locate_many(&domains, &pts[..], ContainOptions::DEFAULT);
        assert_eq!(
            found[0].as_ref().unwrap(),
            &[Location::Outside, Location::Inside]
        );
        assert!(matches!(found[1], Err(ContainError::Domain(_))));
        assert_eq!(
            found[2].as_ref().unwrap(),
            &[Location::Inside, Location::Inside]
        );
        let gwn = ContainOptions::DEFAULT.with_method(Method::Gwn);
        assert!(
            locate_many(&domains, &pts[..], gwn)
                .iter()
                .all(Result::is_ok)
        );
        // A bad tolerance fails every domain, each with its own error.
        let bad = ContainOptions::DEFAULT.with_relative_tolerance(-1.0);
        let found = locate_many(&domains, &pts[..], bad);
        assert_eq!(found.len(), 3);
        assert!(found.iter().all(Result::is_err));
    }

    /// Preparing many domains and building their engines for a stream answers each point as
    /// `locate_many` does, with the open domain's error in its place; the grid locators of a
    /// long stream's engines are built (the engine for a long stream is the grid).
    #[test]
    fn prepared_engines_answer_as_locate_many() {
        let domains = [disc(0.0, 1.0), open_segment(), annulus(0.5, 0.5, 2.0)];
        let pts: Vec<Point> = (0..200)
            .map(|i| Point::new(-3.0 + 0.03 * f64::from(i), 0.01 * f64::from(i % 7)))
            .collect();
        let prepared = prepare_many(&domains, ContainOptions::DEFAULT);
        assert!(matches!(prepared[1], Err(ContainError::Domain(_))));
        let found = locate_many(&domains, &pts[..], ContainOptions::DEFAULT);
        let kept: Vec<Containment> = prepared.into_iter().flatten().collect();
        let engines = engines_many(&kept, FAST_METHOD_MIN_POINTS * 10);
        assert!(engines.iter().all(|e| matches!(e, Engine::Grid(_))));
        for (engine, want) in engines.iter().zip([&found[0], &found[2]]) {
            let mut out = vec![Location::Outside; pts.len()];
            engine.values_into(&pts[..], &mut out);
            assert_eq!(&out, want.as_ref().unwrap());
        }
    }

    /// Per-domain batches of different lengths (an empty one too) each get their own answers.
    #[test]
    fn batches_of_their_own() {
        let a = disc(0.0, 1.0);
        let b = disc(5.0, 1.0);
        let batches = [
            (&a, &vec![Point::new(0.0, 0.0), Point::new(5.0, 0.0)]),
            (&b, &vec![]),
            (&b, &vec![Point::new(5.0, 0.0)]),
        ];
        let found = locate_each(&batches, ContainOptions::DEFAULT);
        assert_eq!(
            found[0].as_ref().unwrap(),
            &[Location::Inside, Location::Outside]
        );
        assert!(found[1].as_ref().unwrap().is_empty());
        assert_eq!(found[2].as_ref().unwrap(), &[Location::Inside]);
        assert!(locate_each::<&Domain, [Point]>(&[], ContainOptions::DEFAULT).is_empty());
    }
}
