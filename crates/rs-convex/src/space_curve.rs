//! Space NURBS curves (3-D), as a pair of planar NURBS sharing knots and weights.

use rs_spline::prelude::*;
use rs_spline::{NurbsCurve, Point, SplineError};

use crate::Point3;

/// A NURBS curve in 3-D: `C(u) = sum_i w_i P_i N_i(u) / sum_i w_i N_i(u)` with `P_i` in
/// `R^3`. Stored as the planar curves `(x, y)` and `(z, 0)`, which share knots and weights, so
/// every planar algorithm (evaluation, knot insertion, Bezier extraction) applies to each.
#[derive(Clone, Debug, PartialEq)]
pub struct SpaceCurve {
    xy: NurbsCurve,
    z: NurbsCurve,
}

impl SpaceCurve {
    /// Validates and builds a curve (as [`NurbsCurve::new`]).
    ///
    /// # Errors
    /// Every [`SplineError`] about degree, knots, control points and weights.
    pub fn new(
        degree: usize,
        knots: Vec<f64>,
        points: &[Point3],
        weights: Option<Vec<f64>>,
    ) -> Result<Self, SplineError> {
        let xy = NurbsCurve::new(
            degree,
            knots.clone(),
            points.iter().map(|p| Point::new(p.x, p.y)).collect(),
            weights.clone(),
        )?;
        let z = NurbsCurve::new(
            degree,
            knots,
            points.iter().map(|p| Point::new(p.z, 0.0)).collect(),
            weights,
        )?;
        Ok(Self { xy, z })
    }

    /// A single Bezier piece of degree `points.len() - 1` on `[0, 1]`.
    ///
    /// # Errors
    /// As [`SpaceCurve::new`].
    pub fn bezier(points: &[Point3], weights: Option<Vec<f64>>) -> Result<Self, SplineError> {
        Ok(Self {
            xy: NurbsCurve::bezier(
                points.iter().map(|p| Point::new(p.x, p.y)).collect(),
                weights.clone(),
            )?,
            z: NurbsCurve::bezier(
                points.iter().map(|p| Point::new(p.z, 0.0)).collect(),
                weights,
            )?,
        })
    }

    /// The `(x, y)` projection (same knots and weights).
    pub fn xy(&self) -> &NurbsCurve {
        &self.xy
    }

    /// The curve `(z, 0)` (same knots and weights).
    pub fn z(&self) -> &NurbsCurve {
        &self.z
    }

    /// Degree `p`.
    pub fn degree(&self) -> usize {
        self.xy.degree()
    }

    /// The control points.
    pub fn control_points(&self) -> Vec<Point3> {
        self.xy
            .control_points()
            .iter()
            .zip(self.z.control_points())
            .map(|(p, q)| Point3::new(p.x, p.y, q.x))
            .collect()
    }

    /// The weights.
    pub fn weights(&self) -> &[f64] {
        self.xy.weights()
    }

    /// The parameter range (the knot domain).
    pub fn param_range(&self) -> (f64, f64) {
        self.xy.param_range()
    }

    /// `C(u)`.
    pub fn point_at(&self, u: f64) -> Point3 {
        let p = self.xy.point_at(u);
        Point3::new(p.x, p.y, self.z.point_at(u).x)
    }

    /// The same curve with control point `i` moved to `p`.
    ///
    /// # Errors
    /// [`SplineError`] for an index out of range or a non-finite point.
    pub fn with_control_point(&self, i: usize, p: Point3) -> Result<Self, SplineError> {
        Ok(Self {
            xy: self.xy.with_control_point(i, Point::new(p.x, p.y))?,
            z: self.z.with_control_point(i, Point::new(p.z, 0.0))?,
        })
    }
}
