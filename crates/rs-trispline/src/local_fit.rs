//! The first stage of the two-stage methods (Schumaker, *Spline Functions: Computational
//! Methods*, Sect. 6.7): derivatives of the data's underlying function estimated by local
//! least-squares polynomial fits.
//!
//! # Neighbourhoods
//! A fit of degree `q` at a point `x0` has `m = (q + 1)(q + 2) / 2` monomial coefficients
//! (one fewer when `x0` is itself a data site: the fit then passes through its value). It uses
//! the `k = 2m` data sites nearest to `x0` (found on a uniform grid), in the coordinates
//! `(x - x0) / r` with `r` the distance to the farthest of them, so every monomial is at most 1
//! there. The fit is accepted when its scaled design matrix has condition number at most
//! [`MAX_FIT_CONDITION`] (singular values by SVD); otherwise `k` grows by half, at most
//! [`FIT_GROWTH_ROUNDS`] times (about `7.6 m` sites), and if the sites still do not determine
//! a polynomial of degree `q` (too few, or nearly on one line or conic) the fit is an error
//! naming the point.

use nalgebra::{DMatrix, DVector};
use rs_spline::Point;

use crate::TriSplineError;
use crate::bb::Jet;
use crate::nearest::NearestSites;

/// The largest condition number of a local fit's scaled design matrix accepted.
pub const MAX_FIT_CONDITION: f64 = 1e6;

/// How many times a fit's neighbourhood grows (by half) before it is an error.
pub const FIT_GROWTH_ROUNDS: usize = 5;

/// The fitted polynomial of degree at most 3 around a point: `sum a_pq u^p v^q` in the scaled
/// coordinates `(u, v) = (p - centre) / scale`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LocalPolynomial {
    centre: Point,
    scale: f64,
    degree: usize,
    /// Coefficients of `1, u, v, u^2, u v, v^2, u^3, u^2 v, u v^2, v^3` (the first
    /// `(degree + 1)(degree + 2) / 2` used).
    coefficients: [f64; 10],
}

/// The exponents `(p, q)` of the monomials `u^p v^q` of degree at most 3, in the order of
/// [`LocalPolynomial`]'s coefficients.
const MONOMIALS: [(i32, i32); 10] = [
    (0, 0),
    (1, 0),
    (0, 1),
    (2, 0),
    (1, 1),
    (0, 2),
    (3, 0),
    (2, 1),
    (1, 2),
    (0, 3),
];

/// `x^n` for a small non-negative `n`, and 0 for negative `n` (a differentiated-away term).
fn pow(x: f64, n: i32) -> f64 {
    if n < 0 { 0.0 } else { x.powi(n) }
}

impl LocalPolynomial {
    /// The degree of the fit.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// The point the fit is centred at.
    pub fn centre(&self) -> Point {
        self.centre
    }

    /// Value, gradient and Hessian of the polynomial at `p`.
    pub fn jet_at(&self, p: Point) -> Jet {
        let (u, v) = (
            (p.x - self.centre.x) / self.scale,
            (p.y - self.centre.y) / self.scale,
        );
        let mut jet = Jet::default();
        let m = crate::bb::coefficient_count(self.degree);
        for (&a, &(i, j)) in self.coefficients[..m].iter().zip(&MONOMIALS) {
            let (fi, fj) = (f64::from(i), f64::from(j));
            jet.value += a * pow(u, i) * pow(v, j);
            jet.gradient[0] += a * fi * pow(u, i - 1) * pow(v, j);
            jet.gradient[1] += a * fj * pow(u, i) * pow(v, j - 1);
            jet.hessian[0] += a * fi * (fi - 1.0) * pow(u, i - 2) * pow(v, j);
            jet.hessian[1] += a * fi * fj * pow(u, i - 1) * pow(v, j - 1);
            jet.hessian[2] += a * fj * (fj - 1.0) * pow(u, i) * pow(v, j - 2);
        }
        let s = self.scale;
        jet.gradient = jet.gradient.map(|g| g / s);
        jet.hessian = jet.hessian.map(|h| h / (s * s));
        jet
    }
}

/// Local least-squares fits of one degree to scattered data `(sites[i], values[i])`.
#[derive(Clone, Debug)]
pub struct LocalFits<'a> {
    values: &'a [f64],
    nearest: NearestSites<'a>,
    degree: usize,
}

impl<'a> LocalFits<'a> {
    /// Fits of degree `degree` (1 to 3) to the data.
    ///
    /// # Errors
    /// [`TriSplineError::Degree`] for a degree outside 1 to 3; [`TriSplineError::Data`] if the
    /// lengths differ or a site or value is not finite.
    pub fn new(
        sites: &'a [Point],
        values: &'a [f64],
        degree: usize,
    ) -> Result<Self, TriSplineError> {
        if !(1..=3).contains(&degree) {
            return Err(TriSplineError::Degree(degree));
        }
        if sites.len() != values.len() {
            return Err(TriSplineError::Data(format!(
                "{} sites and {} values",
                sites.len(),
                values.len()
            )));
        }
        if let Some(i) = (0..sites.len()).find(|&i| !sites[i].is_finite() || !values[i].is_finite())
        {
            return Err(TriSplineError::Data(format!(
                "data point {} is not finite: ({}, {}) -> {}",
                i + 1,
                sites[i].x,
                sites[i].y,
                values[i]
            )));
        }
        Ok(Self {
            values,
            nearest: NearestSites::new(sites),
            degree,
        })
    }

    /// The fit centred at `centre`; when `site` names the data site at `centre`, the fit passes
    /// through its value.
    ///
    /// # Errors
    /// [`TriSplineError::IllPosedFit`] if no neighbourhood (see the module docs) determines the
    /// polynomial.
    pub fn fit_at(
        &self,
        centre: Point,
        site: Option<usize>,
    ) -> Result<LocalPolynomial, TriSplineError> {
        let all = crate::bb::coefficient_count(self.degree);
        let anchored = site.map(|i| self.values[i]);
        let first = usize::from(anchored.is_some());
        let unknowns = all - first;
        let mut k = 2 * all;
        let sites = self.nearest_sites();
        for _ in 0..=FIT_GROWTH_ROUNDS {
            let near: Vec<usize> = self
                .nearest
                .nearest(centre, k)
                .into_iter()
                .filter(|&j| Some(j) != site)
                .collect();
            if near.len() >= unknowns {
                let scale = near
                    .iter()
                    .map(|&j| centre.distance(sites[j]))
                    .fold(0.0f64, f64::max);
                if scale > 0.0 {
                    let a = DMatrix::from_fn(near.len(), unknowns, |r, c| {
                        let s = sites[near[r]];
                        let (u, v) = ((s.x - centre.x) / scale, (s.y - centre.y) / scale);
                        let (i, j) = MONOMIALS[c + first];
                        pow(u, i) * pow(v, j)
                    });
                    let b = DVector::from_fn(near.len(), |r, _| {
                        self.values[near[r]] - anchored.unwrap_or(0.0)
                    });
                    let svd = a.svd(true, true);
                    let (lo, hi) = svd
                        .singular_values
                        .iter()
                        .fold((f64::INFINITY, 0.0f64), |(lo, hi), &s| {
                            (lo.min(s), hi.max(s))
                        });
                    if lo > 0.0
                        && hi / lo <= MAX_FIT_CONDITION
                        && let Ok(x) = svd.solve(&b, 0.0)
                    {
                        let mut coefficients = [0.0; 10];
                        coefficients[0] = anchored.unwrap_or(0.0);
                        for (c, &xc) in x.iter().enumerate() {
                            coefficients[c + first] = xc;
                        }
                        return Ok(LocalPolynomial {
                            centre,
                            scale,
                            degree: self.degree,
                            coefficients,
                        });
                    }
                }
            }
            if k >= self.values.len() {
                break;
            }
            k += k / 2;
        }
        Err(TriSplineError::IllPosedFit {
            x: centre.x,
            y: centre.y,
            degree: self.degree,
        })
    }

    fn nearest_sites(&self) -> &'a [Point] {
        self.nearest.sites()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scattered(n: usize) -> Vec<Point> {
        (0..n)
            .map(|i| {
                let t = i as f64 + 0.5;
                Point::new((t * 0.618_034).fract(), (t * 0.414_214).fract())
            })
            .collect()
    }

    #[test]
    fn fits_reproduce_polynomials_of_their_degree_with_derivatives() {
        let sites = scattered(300);
        let cubic = |p: Point| {
            let (x, y) = (p.x, p.y);
            Jet {
                value: 1.0 + x - 2.0 * y + x * y + 3.0 * x * x * y - y * y * y,
                gradient: [1.0 + y + 6.0 * x * y, -2.0 + x + 3.0 * x * x - 3.0 * y * y],
                hessian: [6.0 * y, 1.0 + 6.0 * x, -6.0 * y],
            }
        };
        let values: Vec<f64> = sites.iter().map(|&p| cubic(p).value).collect();
        let fits = LocalFits::new(&sites, &values, 3).unwrap();
        for (centre, site) in [(sites[17], Some(17)), (Point::new(0.5, 0.5), None)] {
            let fit = fits.fit_at(centre, site).unwrap();
            for p in [centre, Point::new(0.45, 0.52)] {
                let (got, want) = (fit.jet_at(p), cubic(p));
                assert!((got.value - want.value).abs() < 1e-10, "{got:?} {want:?}");
                for i in 0..2 {
                    assert!((got.gradient[i] - want.gradient[i]).abs() < 1e-8);
                }
                for i in 0..3 {
                    assert!((got.hessian[i] - want.hessian[i]).abs() < 1e-6);
                }
            }
        }
    }

    #[test]
    fn an_anchored_fit_passes_through_its_site() {
        let sites = scattered(100);
        let values: Vec<f64> = sites.iter().map(|p| (7.0 * p.x).sin() + p.y).collect();
        let fits = LocalFits::new(&sites, &values, 2).unwrap();
        let fit = fits.fit_at(sites[5], Some(5)).unwrap();
        assert_eq!(fit.jet_at(sites[5]).value, values[5]);
    }

    #[test]
    fn collinear_sites_are_an_error_not_a_wild_fit() {
        let sites: Vec<Point> = (0..50)
            .map(|i| Point::new(i as f64, 2.0 * i as f64))
            .collect();
        let values = vec![1.0; 50];
        let fits = LocalFits::new(&sites, &values, 2).unwrap();
        let e = fits.fit_at(sites[3], Some(3)).unwrap_err();
        assert!(
            matches!(e, TriSplineError::IllPosedFit { degree: 2, .. }),
            "{e}"
        );
        assert!(LocalFits::new(&sites, &values[1..], 2).is_err());
        assert!(LocalFits::new(&sites, &values, 4).is_err());
    }
}
