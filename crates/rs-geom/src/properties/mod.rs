//! Mass properties of faces and solids: area, centroid and second moments of a face; volume,
//! area, centroid and inertia tensor of a solid, with principal moments and axes.
//!
//! Every quantity is an integral over the faces' trimmed `(u, v)` domains. A face's area
//! element is `dA = |S_u x S_v| du dv`, and its outward area vector `n dA = s (S_u x S_v) du dv`
//! with `s = +1` where the face runs with its surface (`same_sense`), `-1` otherwise. A solid's
//! integrals come from the divergence theorem over the faces of its shells (voids included,
//! their faces facing into the void): `V = 1/3 oint p . n dA`, `int x dV = 1/2 oint x^2 n_x dA`,
//! `int x^2 dV = 1/3 oint x^3 n_x dA`, `int x y dV = 1/2 oint x^2 y n_x dA`, and so on. The
//! integrands are polynomials in the surface's point and derivatives (`S_u x S_v`, never its
//! normalised normal), so they stay finite at poles and apexes, where the area element
//! vanishes.
//!
//! The integrals over `(u, v)` are computed by Green's theorem on the loops (`integrate.rs`),
//! in coordinates centred on the model and scaled by its size so that every component is of
//! order one. Where the integrand is a polynomial in a parameter
//! ([`Surface::polynomial_degrees`]: a plane in both, a cylinder, cone or extrusion along its
//! straight lines) a Gauss rule of exactly the needed degree integrates along it, and on a
//! plane the loops' polynomial pieces too: exact to rounding, no adaptivity. Elsewhere
//! (angles, rational surfaces, B-spline area elements) adaptive Gauss-Legendre stops at the
//! rounding noise of the integrand, with an error estimate reported
//! ([`FaceProperties::error`], relative to the model's size).

mod integrate;
mod surface_integral;

pub use surface_integral::SurfaceIntegral;

use nalgebra::{Matrix3, SymmetricEigen};
use thiserror::Error;

use crate::brep::{Face, FaceError, Model, ModelError};
use crate::surface::ParamSurface;
use crate::{Point3, Surface};
use rs_spline::BoundingBox;

use integrate::{DomainIntegral, grid, integrate_over_domain};

/// A face's area, centroid and second moments.
#[derive(Clone, Debug, PartialEq)]
pub struct FaceProperties {
    /// The face's area.
    pub area: f64,
    /// Its centroid `int p dA / area`.
    pub centroid: Point3,
    /// Its second moments of area about its centroid, `int (p - c)(p - c)^T dA` (a symmetric
    /// matrix, rows and columns x, y, z).
    pub second_moments: [[f64; 3]; 3],
    /// An estimate of the integrals' absolute error relative to the model's size (the worst
    /// of every integral, each scaled to the model's size to its power).
    pub error: f64,
    /// Whether every adaptive rule met its tolerance within its bounded work.
    pub converged: bool,
}

/// A solid's volume, boundary area, centroid and inertia (for a uniform unit density).
#[derive(Clone, Debug, PartialEq)]
pub struct SolidProperties {
    /// The volume (outer shell's minus the voids').
    pub volume: f64,
    /// The area of its boundary (every face of every shell).
    pub area: f64,
    /// The centre of its volume.
    pub centroid: Point3,
    /// The inertia tensor about the centroid for unit density: `I_xx = int (y^2 + z^2) dV`,
    /// `I_xy = -int x y dV`, ... (coordinates relative to the centroid).
    pub inertia: [[f64; 3]; 3],
    /// The principal moments (the inertia tensor's eigenvalues), ascending.
    pub principal_moments: [f64; 3],
    /// The principal axes, unit vectors, one per principal moment.
    pub principal_axes: [Point3; 3],
    /// As [`FaceProperties::error`], the worst over its faces.
    pub error: f64,
    /// Whether every integral met its tolerance.
    pub converged: bool,
    /// The length of the net area vector `N = oint n dA` over its shells: zero (to rounding)
    /// for a watertight boundary, else about the area of the gaps between its faces as seen
    /// along `N` (a file whose faces' loops miss their neighbours'). The divergence theorem's
    /// volume then depends on the reference point `p0` by `(p0 . N) / 3`, so `volume` (taken
    /// about the centre of the model's box) is defined only to about `leak_area` times the
    /// distance between two reference points over 3; the moments likewise.
    pub leak_area: f64,
}

/// The properties of every face and every solid of a model ([`Model::properties`]), in the
/// model's face and solid order, each `Err` for one that cannot be computed.
#[derive(Clone, Debug)]
pub struct ModelProperties {
    /// Per face.
    pub faces: Vec<Result<FaceProperties, PropertiesError>>,
    /// Per solid.
    pub solids: Vec<Result<SolidProperties, PropertiesError>>,
}

/// Why properties could not be computed.
#[derive(Clone, Debug, Error)]
#[non_exhaustive]
pub enum PropertiesError {
    /// A face index or solid index past the last, or a face whose loops cannot be read.
    #[error(transparent)]
    Model(#[from] ModelError),
    /// A face whose surface could not be read.
    #[error("face {index} ({entity}): no surface: {error}")]
    NoSurface {
        /// The face's index.
        index: usize,
        /// Its entity.
        entity: String,
        /// Why the surface could not be read.
        error: String,
    },
    /// A face whose integrand is not finite somewhere in its domain (a surface that cannot be
    /// evaluated there).
    #[error("face {index} ({entity}): the surface's derivatives are not finite inside the face")]
    NotFinite {
        /// The face's index.
        index: usize,
        /// Its entity.
        entity: String,
    },
    /// A function integrated over a face that is not finite at a point of the face.
    #[error("face {index} ({entity}): the function is not finite at ({}, {}, {})", at[0], at[1], at[2])]
    FunctionNotFinite {
        /// The face's index.
        index: usize,
        /// Its entity.
        entity: String,
        /// The first point found where it is not.
        at: [f64; 3],
    },
    /// A solid with an open shell: its volume is not defined.
    #[error(
        "solid {solid}: shell {shell} ({entity}) is open, so its volume is not defined; free edges: {}",
        free_edges_text(free_edges)
    )]
    OpenShell {
        /// The solid's index.
        solid: usize,
        /// The shell's index.
        shell: usize,
        /// The shell's entity.
        entity: String,
        /// The edges only one of its faces uses (their entities).
        free_edges: Vec<String>,
    },
}

fn free_edges_text(edges: &[String]) -> String {
    const SHOWN: usize = 8;
    match edges.len() {
        0 => "none found by entity (the file calls the shell open)".to_string(),
        n if n <= SHOWN => edges.join(", "),
        n => format!("{} and {} more", edges[..SHOWN].join(", "), n - SHOWN),
    }
}

/// The integrals of one face, in the model's normalised coordinates `q = (p - centre) / size`
/// (see [`Frame`]): `[area, int q dA (3), int q q^T dA (6: xx, yy, zz, xy, yz, xz),
/// volume terms: V, int q dV (3), int q_i^2 dV (3), int xy, yz, xz dV (3), the area vector
/// int n dA (3)]`.
#[derive(Clone, Debug, PartialEq)]
struct FaceIntegrals {
    values: [f64; COMPONENTS],
    error: f64,
    converged: bool,
}

const COMPONENTS: usize = 23;

/// The absolute error a face's integrals may have in the model's normalised coordinates
/// (where the model's integrals are of order one): far below the `1e-12` relative the results
/// promise, summed over thousands of faces.
const FACE_FLOOR: f64 = 1e-16;
/// Index of the area.
const AREA: usize = 0;
/// Index of `int q dA`.
const FACE_FIRST: usize = 1;
/// Index of `int q q^T dA` (xx, yy, zz, xy, yz, xz).
const FACE_SECOND: usize = 4;
/// Index of the volume.
const VOLUME: usize = 10;
/// Index of `int q dV`.
const VOLUME_FIRST: usize = 11;
/// Index of `int q_i^2 dV`.
const VOLUME_SQUARES: usize = 14;
/// Index of `int (xy, yz, xz) dV`.
const VOLUME_PRODUCTS: usize = 17;
/// Index of the area vector `int n dA` (zero summed over a closed shell).
const AREA_VECTOR: usize = 20;

/// An integrand over a face's `(u, v)`, given the face and its surface: writes its components
/// at `uv` and returns their magnitude (see `integrate_over_domain`).
type FaceIntegrand<'a> = dyn Fn(&Face, &Surface, [f64; 2], &mut [f64]) -> f64 + 'a;

/// Points per side of the [`grid`] over each face's `(u, v)` box that give the model's frame:
/// quarter periods of a full angle (a torus's natural box reaches its extremes in both
/// directions), and few, since every `face_properties` call computes the frame anew. The
/// frame only conditions the sums; any box of the model's size would do.
const FRAME_GRID: usize = 5;

/// The model's normalised coordinates: `q = (p - centre) / size`.
#[derive(Clone, Copy, Debug)]
struct Frame {
    centre: Point3,
    size: f64,
}

impl Frame {
    /// The box of the faces' points on the [`grid`] over the box of each face's loops'
    /// control points (which contains the loops, and costs no more than reading them; the
    /// control points alone can all map to one point: a torus's natural box).
    fn of(model: &Model) -> Frame {
        let points = model.faces.iter().filter_map(|f| {
            let s = f.surface.as_ref()?;
            let loops = f.loops.as_ref().ok()?;
            let control = loops
                .iter()
                .flatten()
                .flat_map(|c| c.control_points().iter().copied());
            let b = BoundingBox::from_points(control)?;
            Some(
                grid(&b, FRAME_GRID)
                    .map(|uv| s.point(uv))
                    .collect::<Vec<_>>(),
            )
        });
        match Point3::bounds(points.flatten().filter(|p| p.is_finite())) {
            Some((lo, hi)) => {
                let size = (hi - lo).length();
                Frame {
                    centre: (lo + hi) * 0.5,
                    size: if size > 0.0 && size.is_finite() {
                        size
                    } else {
                        1.0
                    },
                }
            }
            None => Frame {
                centre: Point3::new(0.0, 0.0, 0.0),
                size: 1.0,
            },
        }
    }
}

impl Model {
    /// Face `index`'s area, centroid and second moments of area.
    ///
    /// # Errors
    /// [`PropertiesError::Model`] for a face that does not exist or whose loops cannot be
    /// read; [`PropertiesError::NoSurface`]; [`PropertiesError::NotFinite`].
    pub fn face_properties(&self, index: usize) -> Result<FaceProperties, PropertiesError> {
        let frame = Frame::of(self);
        let f = self.face_integrals(index, frame)?;
        Ok(face_properties(&f, frame))
    }

    /// Solid `index`'s volume, area, centroid and inertia.
    ///
    /// # Errors
    /// [`PropertiesError::OpenShell`] for a solid with a shell that is not closed; the errors
    /// of [`Model::face_properties`] for any of its faces; [`ModelError::NoSolid`].
    pub fn solid_properties(&self, index: usize) -> Result<SolidProperties, PropertiesError> {
        let frame = Frame::of(self);
        self.solid_from_faces(index, frame, &mut |face| self.face_integrals(face, frame))
    }

    /// Every face's and every solid's properties, each face integrated once.
    pub fn properties(&self) -> ModelProperties {
        let frame = Frame::of(self);
        let integrals = self.all_face_integrals(frame);
        let solids = (0..self.solids.len())
            .map(|k| self.solid_from_faces(k, frame, &mut |face| integrals[face].clone()))
            .collect();
        ModelProperties {
            faces: integrals
                .into_iter()
                .map(|f| f.map(|f| face_properties(&f, frame)))
                .collect(),
            solids,
        }
    }

    /// Every face's integrals: on rayon's pool with the `parallel` feature (the default),
    /// faces handed out by work stealing; in order on this thread without it.
    fn all_face_integrals(&self, frame: Frame) -> Vec<Result<FaceIntegrals, PropertiesError>> {
        #[cfg(feature = "parallel")]
        {
            use rayon::prelude::*;
            (0..self.faces.len())
                .into_par_iter()
                .map(|k| self.face_integrals(k, frame))
                .collect()
        }
        #[cfg(not(feature = "parallel"))]
        {
            (0..self.faces.len())
                .map(|k| self.face_integrals(k, frame))
                .collect()
        }
    }

    /// Solid `index`'s properties from its faces' integrals (`face(k)` for face `k`).
    fn solid_from_faces(
        &self,
        index: usize,
        frame: Frame,
        face: &mut dyn FnMut(usize) -> Result<FaceIntegrals, PropertiesError>,
    ) -> Result<SolidProperties, PropertiesError> {
        let solid = self.solids.get(index).ok_or(ModelError::NoSolid {
            index,
            count: self.solids.len(),
        })?;
        for &k in &solid.shells {
            let shell = &self.shells[k];
            if !shell.closed {
                return Err(PropertiesError::OpenShell {
                    solid: index,
                    shell: k,
                    entity: shell.entity.clone(),
                    free_edges: self.free_edges(&shell.faces),
                });
            }
        }
        let mut sum = FaceIntegrals {
            values: [0.0; COMPONENTS],
            error: 0.0,
            converged: true,
        };
        for &k in &solid.shells {
            for &f in &self.shells[k].faces {
                let f = face(f)?;
                for (s, v) in sum.values.iter_mut().zip(f.values) {
                    *s += v;
                }
                sum.error = sum.error.max(f.error);
                sum.converged &= f.converged;
            }
        }
        Ok(solid_properties(&sum, frame))
    }

    /// `int int g` over face `index`'s trimmed `(u, v)` domain, `g` given the face and its
    /// surface, split at the surface's knot lines ([`integrate_over_domain`]); `degrees(s)` is
    /// `g`'s degree in each parameter on the surface `s` where it is a polynomial in it.
    fn integrate_face(
        &self,
        index: usize,
        dim: usize,
        degrees: impl Fn(&Surface) -> [Option<usize>; 2],
        g: &FaceIntegrand<'_>,
    ) -> Result<DomainIntegral, PropertiesError> {
        let domain = self.face_domain(index, None)?;
        let face = &self.faces[index];
        let surface = face
            .surface
            .as_ref()
            .ok_or_else(|| PropertiesError::NoSurface {
                index,
                entity: face.entity.clone(),
                error: face
                    .surface_error
                    .as_ref()
                    .map_or_else(|| "not read".to_string(), FaceError::to_string),
            })?;
        let [u_lines, v_lines] = surface.knot_lines();
        let at = |uv: [f64; 2], out: &mut [f64]| g(face, surface, uv, out);
        let degrees = degrees(surface);
        integrate_over_domain(&domain, [&u_lines, &v_lines], degrees, FACE_FLOOR, dim, &at)
            .ok_or_else(|| PropertiesError::NotFinite {
                index,
                entity: face.entity.clone(),
            })
    }

    /// The integrals of face `index` in `frame`'s coordinates.
    fn face_integrals(&self, index: usize, frame: Frame) -> Result<FaceIntegrals, PropertiesError> {
        let got = self.integrate_face(
            index,
            COMPONENTS,
            integrand_degrees,
            &|face, surface, uv, out| {
                let sense = if face.same_sense { 1.0 } else { -1.0 };
                integrand(surface, frame, sense, uv, out)
            },
        )?;
        let mut values = [0.0; COMPONENTS];
        values.copy_from_slice(&got.values);
        Ok(FaceIntegrals {
            values,
            error: got.error,
            converged: got.converged,
        })
    }
}

/// The degree of the [`integrand`] in each parameter where the surface is a polynomial in it:
/// `q^3` times the area vector (the volume terms) is the highest.
fn integrand_degrees(surface: &Surface) -> [Option<usize>; 2] {
    surface
        .polynomial_degrees()
        .map(|d| d.map(|d| 3 * d.point + d.area))
}

/// The integrands at `uv` in `frame`'s coordinates (see [`FaceIntegrals`]); returns their
/// magnitude (the largest).
fn integrand(surface: &Surface, frame: Frame, sense: f64, uv: [f64; 2], out: &mut [f64]) -> f64 {
    let [point, du, dv] = surface.first_derivatives(uv);
    let inv = 1.0 / frame.size;
    let q = (point - frame.centre) * inv;
    // The area vector in normalised coordinates: S_u x S_v scaled by 1 / size^2.
    let n = du.cross(dv) * (inv * inv);
    let da = n.length();
    let n = n * sense;
    let (x, y, z) = (q.x, q.y, q.z);
    out[AREA] = da;
    out[FACE_FIRST] = x * da;
    out[FACE_FIRST + 1] = y * da;
    out[FACE_FIRST + 2] = z * da;
    out[FACE_SECOND] = x * x * da;
    out[FACE_SECOND + 1] = y * y * da;
    out[FACE_SECOND + 2] = z * z * da;
    out[FACE_SECOND + 3] = x * y * da;
    out[FACE_SECOND + 4] = y * z * da;
    out[FACE_SECOND + 5] = x * z * da;
    out[VOLUME] = (x * n.x + y * n.y + z * n.z) / 3.0;
    out[VOLUME_FIRST] = 0.5 * x * x * n.x;
    out[VOLUME_FIRST + 1] = 0.5 * y * y * n.y;
    out[VOLUME_FIRST + 2] = 0.5 * z * z * n.z;
    out[VOLUME_SQUARES] = x * x * x * n.x / 3.0;
    out[VOLUME_SQUARES + 1] = y * y * y * n.y / 3.0;
    out[VOLUME_SQUARES + 2] = z * z * z * n.z / 3.0;
    out[VOLUME_PRODUCTS] = 0.5 * x * x * y * n.x;
    out[VOLUME_PRODUCTS + 1] = 0.5 * y * y * z * n.y;
    out[VOLUME_PRODUCTS + 2] = 0.5 * z * z * x * n.z;
    out[AREA_VECTOR] = n.x;
    out[AREA_VECTOR + 1] = n.y;
    out[AREA_VECTOR + 2] = n.z;
    out.iter().fold(0.0f64, |m, v| m.max(v.abs())).max(da)
}

/// The symmetric matrix of `[xx, yy, zz, xy, yz, xz]`.
fn symmetric(m: &[f64]) -> Matrix3<f64> {
    Matrix3::new(m[0], m[3], m[5], m[3], m[1], m[4], m[5], m[4], m[2])
}

fn rows(m: &Matrix3<f64>) -> [[f64; 3]; 3] {
    std::array::from_fn(|i| std::array::from_fn(|j| m[(i, j)]))
}

/// A face's properties in model coordinates from its normalised integrals.
fn face_properties(f: &FaceIntegrals, frame: Frame) -> FaceProperties {
    let s = frame.size;
    let area_n = f.values[AREA];
    let c_n = Point3::new(
        f.values[FACE_FIRST],
        f.values[FACE_FIRST + 1],
        f.values[FACE_FIRST + 2],
    ) * (1.0 / area_n);
    // About the centroid: int q q^T dA - area c c^T, then scaled by size^4.
    let c = nalgebra::Vector3::new(c_n.x, c_n.y, c_n.z);
    let second = (symmetric(&f.values[FACE_SECOND..FACE_SECOND + 6]) - c * c.transpose() * area_n)
        * s.powi(4);
    FaceProperties {
        area: area_n * s * s,
        centroid: frame.centre + c_n * s,
        second_moments: rows(&second),
        error: f.error,
        converged: f.converged,
    }
}

/// A solid's properties in model coordinates from the sum of its faces' normalised integrals.
fn solid_properties(f: &FaceIntegrals, frame: Frame) -> SolidProperties {
    let s = frame.size;
    let v = &f.values;
    let volume_n = v[VOLUME];
    let c_n =
        Point3::new(v[VOLUME_FIRST], v[VOLUME_FIRST + 1], v[VOLUME_FIRST + 2]) * (1.0 / volume_n);
    // int q q^T dV about the origin of the frame, then about the centroid.
    let moments = symmetric(&[
        v[VOLUME_SQUARES],
        v[VOLUME_SQUARES + 1],
        v[VOLUME_SQUARES + 2],
        v[VOLUME_PRODUCTS],
        v[VOLUME_PRODUCTS + 1],
        v[VOLUME_PRODUCTS + 2],
    ]);
    let c = nalgebra::Vector3::new(c_n.x, c_n.y, c_n.z);
    let about_centroid = (moments - c * c.transpose() * volume_n) * s.powi(5);
    let inertia = Matrix3::identity() * about_centroid.trace() - about_centroid;
    let eigen = SymmetricEigen::new(inertia);
    let mut order = [0, 1, 2];
    order.sort_by(|&a, &b| eigen.eigenvalues[a].total_cmp(&eigen.eigenvalues[b]));
    SolidProperties {
        volume: volume_n * s.powi(3),
        area: v[AREA] * s * s,
        centroid: frame.centre + c_n * s,
        inertia: rows(&inertia),
        principal_moments: order.map(|i| eigen.eigenvalues[i]),
        principal_axes: order.map(|i| {
            let a = eigen.eigenvectors.column(i);
            Point3::new(a[0], a[1], a[2])
        }),
        error: f.error,
        converged: f.converged,
        leak_area: Point3::new(v[AREA_VECTOR], v[AREA_VECTOR + 1], v[AREA_VECTOR + 2]).length()
            * s
            * s,
    }
}

#[cfg(test)]
mod tests;
