//! Integrals of a function of the point over a face in space: `int_F f(p) dA`.

use super::integrate::integrate_over_domain;
use super::{FACE_FLOOR, PropertiesError};
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
        f: &(dyn Fn(Point3) -> f64 + Sync),
    ) -> Result<SurfaceIntegral, PropertiesError> {
        let (domain, face, surface) = self.face_parts(index)?;
        let bad = std::sync::Mutex::new(None);
        let g = |uv: [f64; 2], out: &mut [f64]| {
            let d = surface.derivatives(uv);
            let da = d.du.cross(d.dv).length();
            let v = f(d.point);
            if !v.is_finite() {
                let mut b = bad
                    .lock()
                    .unwrap_or_else(std::sync::PoisonError::into_inner);
                b.get_or_insert(d.point);
            }
            out[0] = v * da;
            out[0].abs()
        };
        let [u_lines, v_lines] = surface.knot_lines();
        let lines = [u_lines.as_slice(), v_lines.as_slice()];
        let got = integrate_over_domain(&domain, lines, FACE_FLOOR, 1, &g);
        let bad = bad
            .into_inner()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        if let Some(at) = bad {
            return Err(PropertiesError::FunctionNotFinite {
                index,
                entity: face.entity.clone(),
                at: [at.x, at.y, at.z],
            });
        }
        let got = got.ok_or_else(|| PropertiesError::NotFinite {
            index,
            entity: face.entity.clone(),
        })?;
        Ok(SurfaceIntegral {
            value: got.values[0],
            error: got.error,
            converged: got.converged,
        })
    }
}
