//! Integrals of a function of the point over a face in space: `int_F f(p) dA`.

use std::cell::Cell;

use super::PropertiesError;
use crate::Point3;
use crate::brep::Model;
use crate::surface::ParamSurface;

/// `int_F f(p) dA` over a face, with how far it can be trusted.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceIntegral {
    /// The integral.
    pub value: f64,
    /// An estimate of its absolute error (the adaptive rules' estimates; see
    /// [`FaceProperties::error`](super::FaceProperties::error)).
    pub error: f64,
    /// Whether every adaptive rule met its tolerance within its bounded work.
    pub converged: bool,
}

impl Model {
    /// `int_F f(p) dA` over face `index` in space (`dA = |S_u x S_v| du dv` over the face's
    /// trimmed `(u, v)` domain), by the rules of [`Model::face_properties`]: exact to rounding
    /// where `f(S(u, v)) |S_u x S_v|` is a polynomial of degree up to 31 along each parameter
    /// within a knot span, adaptive to the rounding noise of the integrand elsewhere.
    ///
    /// # Errors
    /// As [`Model::face_properties`]; [`PropertiesError::FunctionNotFinite`] where `f` is not
    /// finite at a point of the face the rules sample.
    pub fn surface_integral(
        &self,
        index: usize,
        f: &dyn Fn(Point3) -> f64,
    ) -> Result<SurfaceIntegral, PropertiesError> {
        // The first point where `f` is not finite (the rules run on this thread).
        let bad = Cell::new(None);
        // `f` is any function: no degree is known, every rule is adaptive.
        let got = self.integrate_face(index, 1, |_| [None, None], &|_, surface, uv, out| {
            let [point, du, dv] = surface.first_derivatives(uv);
            let v = f(point);
            if !v.is_finite() && bad.get().is_none() {
                bad.set(Some(point));
            }
            out[0] = v * du.cross(dv).length();
            out[0].abs()
        });
        if let Some(at) = bad.get() {
            return Err(PropertiesError::FunctionNotFinite {
                index,
                entity: self.faces[index].entity.clone(),
                at: [at.x, at.y, at.z],
            });
        }
        let got = got?;
        Ok(SurfaceIntegral {
            value: got.values[0],
            error: got.error,
            converged: got.converged,
        })
    }
}
