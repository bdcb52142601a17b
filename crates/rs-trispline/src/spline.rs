//! A spline on a curved triangulation: per triangle, the Bernstein–Bézier coefficients of the
//! polynomial on its companion triangle; evaluated anywhere in the domain (Section 5.2).

use rs_contain::PointQuery;
use rs_mesh::{CurvedLocator, CurvedTriangulation};
use rs_spline::Point;

use crate::bb::{Jet, Order, Triangle, coefficient_count, evaluate};
use crate::{SplineSpace, TriSplineError};

/// The space a spline was built in (written to the spline file as `space`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SpaceKind {
    /// `S_d^0`: continuous, on the triangulation as it is (`"s0"`).
    Continuous,
    /// `S_5^{1,2}`: `C^1` quintic super-splines, `C^2` at the vertices (`"s512"`).
    SuperSpline,
    /// `S_3^1` on the Clough–Tocher refinement (`"ct"`).
    CloughTocher,
    /// `S_2^1` on the Powell–Sabin refinement, two-stage (`"ps"`).
    PowellSabin,
    /// `S_2^1` on the Powell–Sabin refinement, minimal energy (`"min-energy"`).
    MinimalEnergy,
}

impl SpaceKind {
    const ALL: [SpaceKind; 5] = [
        SpaceKind::Continuous,
        SpaceKind::SuperSpline,
        SpaceKind::CloughTocher,
        SpaceKind::PowellSabin,
        SpaceKind::MinimalEnergy,
    ];

    /// The name in the spline file.
    pub fn name(self) -> &'static str {
        match self {
            SpaceKind::Continuous => "s0",
            SpaceKind::SuperSpline => "s512",
            SpaceKind::CloughTocher => "ct",
            SpaceKind::PowellSabin => "ps",
            SpaceKind::MinimalEnergy => "min-energy",
        }
    }

    /// What a spline of this kind and degree is, for captions: "quasi-interpolating spline s
    /// of degree 3 (space `S^0_3`)", "C1 interpolating spline s in `S_2^1` on the Powell-Sabin
    /// refinement".
    pub fn description(self, degree: usize) -> String {
        match self {
            SpaceKind::Continuous => {
                format!("quasi-interpolating spline s of degree {degree} (space S^0_{degree})")
            }
            SpaceKind::SuperSpline => "C1 interpolating spline s in S_5^{1,2}".into(),
            SpaceKind::CloughTocher => {
                "C1 interpolating spline s in S_3^1 on the Clough-Tocher refinement".into()
            }
            SpaceKind::PowellSabin => {
                "C1 interpolating spline s in S_2^1 on the Powell-Sabin refinement".into()
            }
            SpaceKind::MinimalEnergy => {
                "minimal-energy C1 interpolating spline s in S_2^1 on the Powell-Sabin refinement"
                    .into()
            }
        }
    }

    /// The kind with that file name.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|k| k.name() == name)
    }
}

/// A polynomial spline of degree `d` on a curved triangulation: on each curved triangle the
/// polynomial whose Bernstein–Bézier coefficients (relative to its companion triangle) are
/// stored, `C(d + 2, 2)` per triangle in coefficient order (see [`crate::bb`]).
#[derive(Clone, Debug)]
pub struct Spline {
    mesh: CurvedTriangulation,
    degree: usize,
    kind: SpaceKind,
    coefficients: Vec<f64>,
}

impl Spline {
    /// The spline with `coefficients` (`C(d + 2, 2)` per triangle, triangle by triangle).
    ///
    /// # Errors
    /// [`TriSplineError::Degree`]; [`TriSplineError::File`] if the number of coefficients is wrong.
    pub fn new(
        mesh: CurvedTriangulation,
        degree: usize,
        kind: SpaceKind,
        coefficients: Vec<f64>,
    ) -> Result<Self, TriSplineError> {
        if !(1..=crate::bb::MAX_DEGREE).contains(&degree) {
            return Err(TriSplineError::Degree(degree));
        }
        let expected = mesh.triangles().len() * coefficient_count(degree);
        if coefficients.len() != expected {
            return Err(TriSplineError::File(format!(
                "{} coefficients for {} triangles of degree {degree} (expected {expected})",
                coefficients.len(),
                mesh.triangles().len()
            )));
        }
        Ok(Self {
            mesh,
            degree,
            kind,
            coefficients,
        })
    }

    /// The curved triangulation.
    pub fn mesh(&self) -> &CurvedTriangulation {
        &self.mesh
    }

    /// The degree.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// The space it was built in.
    pub fn kind(&self) -> SpaceKind {
        self.kind
    }

    /// The coefficients of triangle `t`, in coefficient order.
    pub fn triangle_coefficients(&self, t: usize) -> &[f64] {
        let n = coefficient_count(self.degree);
        &self.coefficients[t * n..(t + 1) * n]
    }

    /// All coefficients, triangle by triangle.
    pub fn coefficients(&self) -> &[f64] {
        &self.coefficients
    }

    /// The number of distinct coefficients of the space (`S_d^0`'s dimension).
    pub fn dimension(&self) -> usize {
        SplineSpace::new(&self.mesh, self.degree).dimension()
    }

    /// The companion triangle of curved triangle `t`.
    pub fn companion(&self, t: usize) -> Triangle {
        let v = self.mesh.triangles()[t].map(|i| self.mesh.vertices()[i]);
        Triangle::new(v[0], v[1], v[2])
    }

    /// The polynomial of triangle `t` at `p` (any point of the plane), up to `order`.
    pub fn evaluate_on(&self, t: usize, p: Point, order: Order) -> Jet {
        evaluate(
            &self.companion(t),
            self.degree,
            self.triangle_coefficients(t),
            p,
            order,
        )
    }

    /// An evaluator of the spline's values anywhere in the domain (of more of its jet with
    /// [`SplineEvaluator::with_order`]): a [`PointQuery`] of `Option<Jet>`, `None` outside
    /// the domain.
    ///
    /// # Errors
    /// Containment errors (never for a triangulation built by rs-mesh).
    pub fn evaluator(&self) -> Result<SplineEvaluator<'_>, TriSplineError> {
        Ok(SplineEvaluator {
            spline: self,
            locator: CurvedLocator::new(&self.mesh)?,
            order: Order::Value,
        })
    }
}

/// Evaluates a [`Spline`] at points of its domain: the curved triangle holding the point
/// (exactly, slivers between a boundary arc and its chord included), then its polynomial.
///
/// A [`PointQuery`] of `Option<Jet>` (up to its [`SplineEvaluator::order`]; `None` outside
/// the domain): batches of points from any [`rs_contain::PointSource`] go through
/// [`PointQuery::values_into`] and, on all threads, [`PointQuery::par_values_into`], as
/// every query of the workspace does.
///
/// # Examples
///
/// ```
/// use rs_contain::PointQuery;
/// use rs_mesh::{CurvedTriangulation, well_spaced_points};
/// use rs_spline::{circle, Domain, Point};
/// use rs_trispline::{bb::Order, quasi_interpolate};
///
/// let d = Domain::new(vec![circle(Point::new(0.0, 0.0), 1.0).unwrap()]).unwrap();
/// let mesh = CurvedTriangulation::new(&d, &well_spaced_points(&d, 4).unwrap()).unwrap();
/// let s = quasi_interpolate(mesh, 2, &|p: Point| p.x * p.y).unwrap();
/// let eval = s.evaluator().unwrap().with_order(Order::Gradient);
/// let points = [Point::new(0.5, 0.25), Point::new(2.0, 0.0)];
/// let mut jets = [None; 2];
/// eval.par_values_into(&points[..], &mut jets);
/// let j = jets[0].unwrap();
/// assert!((j.value - 0.125).abs() < 1e-12 && (j.gradient[0] - 0.25).abs() < 1e-12);
/// assert!(jets[1].is_none()); // outside the domain
/// ```
#[derive(Debug)]
pub struct SplineEvaluator<'a> {
    spline: &'a Spline,
    locator: CurvedLocator<'a>,
    order: Order,
}

impl SplineEvaluator<'_> {
    /// The evaluator of the jet up to `order` (the value only by default).
    #[must_use]
    pub fn with_order(mut self, order: Order) -> Self {
        self.order = order;
        self
    }

    /// How much of the jet [`PointQuery::value`] computes.
    pub fn order(&self) -> Order {
        self.order
    }

    /// The spline's value and derivatives up to `order` at `p`, `None` outside the domain.
    pub fn evaluate(&self, p: Point, order: Order) -> Option<Jet> {
        self.locator
            .triangle_at(p)
            .map(|t| self.spline.evaluate_on(t, p, order))
    }

    /// The query's values (the jet up to [`SplineEvaluator::order`]) at every point, in
    /// order, on all threads: [`PointQuery::par_values_into`] into a new vector.
    pub fn evaluate_all(&self, points: &[Point]) -> Vec<Option<Jet>> {
        let mut out = vec![None; points.len()];
        self.par_values_into(points, &mut out);
        out
    }

    /// The curved triangle holding `p`.
    pub fn triangle_at(&self, p: Point) -> Option<usize> {
        self.locator.triangle_at(p)
    }
}

impl PointQuery<Option<Jet>> for SplineEvaluator<'_> {
    /// The jet up to [`SplineEvaluator::order`] at `p`, `None` outside the domain.
    #[inline]
    fn value(&self, p: Point) -> Option<Jet> {
        self.evaluate(p, self.order)
    }
}
