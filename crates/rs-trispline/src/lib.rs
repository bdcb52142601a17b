//! Polynomial splines on curved triangulations (Schumaker and Yu 2021, Sections 5-8): a spline
//! of degree `d` is, on each curved triangle, a bivariate polynomial written in the
//! Bernstein–Bézier basis of its companion (straight) triangle; sharing the coefficients at
//! the domain points of shared edges and vertices makes it continuous (`S_d^0`).
//!
//! - [`bb`]: Bernstein–Bézier polynomials on a triangle: domain points, de Casteljau
//!   evaluation with gradients and Hessians anywhere in the plane, degree raising, interpolation
//!   at the domain points.
//! - [`SplineSpace`]: the global numbering of `S_d^0`, of dimension
//!   `n_v + (d - 1) n_e + C(d - 1, 2) n_t` (formula 5.2).
//! - [`Spline`], [`SplineEvaluator`]: a spline and its evaluation anywhere in the domain,
//!   slivers between a boundary arc and its chord included (Section 5.2).
//! - [`quasi_interpolate`]: the quasi-interpolation operator `Q` of Algorithm 6.1.
//! - [`interpolate_scattered`]: scattered-data interpolation with `C^1` splines (Problem 9.1):
//!   the two-stage methods in `S_5^{1,2}`, `S_3^1` (Clough–Tocher) and `S_2^1` (Powell–Sabin)
//!   ([`hermite`], first stage in [`LocalFits`]) and minimal-energy interpolation in `S_2^1`
//!   ([`minimal_energy`], Section 10).
//! - [`spline_to_json`], [`spline_from_json`]: the spline file; [`spline_svg`],
//!   [`error_svg`]: colour-map figures.
//!
//! # Examples
//!
//! ```
//! use rs_mesh::{CurvedTriangulation, well_spaced_points};
//! use rs_spline::{circle, Domain, Point};
//! use rs_trispline::{bb::Order, quasi_interpolate};
//!
//! let d = Domain::new(vec![circle(Point::new(0.0, 0.0), 1.0).unwrap()]).unwrap();
//! let mesh = CurvedTriangulation::new(&d, &well_spaced_points(&d, 6).unwrap()).unwrap();
//! // Q reproduces polynomials of its degree: here a cubic, with degree 3.
//! let f = |p: Point| p.x * p.x * p.y - 2.0 * p.y + 1.0;
//! let s = quasi_interpolate(mesh, 3, &f).unwrap();
//! let eval = s.evaluator().unwrap();
//! let q = Point::new(0.999, 0.01); // between a boundary arc and its chord
//! let jet = eval.evaluate(q, Order::Gradient).unwrap();
//! assert!((jet.value - f(q)).abs() < 1e-12);
//! assert!((jet.gradient[1] - (q.x * q.x - 2.0)).abs() < 1e-10);
//! ```

pub mod bb;
mod energy;
mod error;
mod figure;
mod file;
pub mod hermite;
mod local_fit;
mod nearest;
mod quasi;
mod scattered;
mod space;
mod spline;

pub use energy::{ENERGY_TOLERANCE, energy, max_energy_iterations, minimal_energy};
pub use error::TriSplineError;
pub use figure::{error_svg, spline_svg};
pub use file::{MAX_SPLINE_FILE_BYTES, load_spline, save_spline, spline_from_json, spline_to_json};
pub use hermite::{C1Space, ExactJets, HermiteData, hermite_interpolate};
pub use local_fit::{FIT_GROWTH_ROUNDS, LocalFits, LocalPolynomial, MAX_FIT_CONDITION};
pub use quasi::{QuasiInterpolation, inner_triangle, quasi_interpolate};
pub use scattered::{
    BOUNDARY_TOLERANCE, MAX_DATA_POINTS, ScatteredData, ScatteredFit, interpolate_on,
    interpolate_scattered,
};
pub use space::SplineSpace;
pub use spline::{SpaceKind, Spline, SplineEvaluator};
