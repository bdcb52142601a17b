//! What `inrs info part.step` prints: one line per face, shell and solid of a CAD file.

use std::fmt;

use rs_spline::prelude::*;
use rs_spline::{BoundingBox, Domain};

use super::CadModel;
use crate::IoError;

/// Facts about one face of a CAD file: its place, its surface, and either its loops, curves,
/// `(u, v)` area and box, or why it cannot be read.
#[derive(Clone, Debug, PartialEq)]
pub struct CadFaceSummary {
    /// The face's index (`#face:K`).
    pub index: usize,
    /// Its entity in the file (`#123`, `DE 57`).
    pub entity: String,
    /// The surface type as the file names it.
    pub surface: String,
    /// Number of trimming loops (0 when refused).
    pub loops: usize,
    /// Number of trimming curves (0 when refused).
    pub curves: usize,
    /// The area of the face's parameter domain (0 when refused).
    pub area: f64,
    /// Its `(u, v)` bounding box (`None` when refused).
    pub bounding_box: Option<BoundingBox>,
    /// The gap within which its loops were closed (`(u, v)` units; 0 when refused).
    pub closure_tolerance: f64,
    /// A width of the face in `(u, v)`: twice its area over its loops' length, the width of a
    /// strip of the same area and perimeter (0 when refused).
    pub width: f64,
    /// The largest 3-D distance between a computed pcurve and its edge (model units), when
    /// pcurves were fitted.
    pub pcurve_deviation: Option<f64>,
    /// Whether the loops are the surface's natural parameter box.
    pub natural_bounds: bool,
    /// Why the face cannot be read as a domain, if it cannot.
    pub error: Option<String>,
}

impl CadFaceSummary {
    /// Whether the face is narrower than the gap its loops were closed within: its shape in
    /// `(u, v)` is then no more exact than the file's tolerance, whatever the classification
    /// says.
    pub fn is_narrow(&self) -> bool {
        self.error.is_none() && self.width < self.closure_tolerance
    }
}

/// A shell of a CAD file: its entity, whether the file calls it closed, its faces.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CadShellSummary {
    /// The shell's index in the model.
    pub index: usize,
    /// Its entity.
    pub entity: String,
    /// Whether the file says it is closed.
    pub closed: bool,
    /// Its faces (`#face:K` indices).
    pub faces: Vec<usize>,
}

/// A solid of a CAD file: its entity and shells (the outer one first).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CadSolidSummary {
    /// The solid's index (`#solid:K`).
    pub index: usize,
    /// Its entity.
    pub entity: String,
    /// Its shells: the outer one, then the voids.
    pub shells: Vec<CadShellSummary>,
}

impl CadModel {
    /// One summary per face, in file order, with the closure tolerance of
    /// [`CadModel::face_domain`].
    pub fn face_summaries(&self, relative_closure_tolerance: Option<f64>) -> Vec<CadFaceSummary> {
        self.face_domains(relative_closure_tolerance)
            .iter()
            .enumerate()
            .map(|(index, d)| CadFaceSummary::of(self, index, d, relative_closure_tolerance))
            .collect()
    }

    /// The shell `index` of the model as a summary.
    ///
    /// # Panics
    /// If `index` is not a shell of the model.
    pub fn shell_summary(&self, index: usize) -> CadShellSummary {
        let s = &self.shells[index];
        CadShellSummary {
            index,
            entity: s.entity.clone(),
            closed: s.closed,
            faces: s.faces.clone(),
        }
    }

    /// One summary per solid, in solid order.
    pub fn solid_summaries(&self) -> Vec<CadSolidSummary> {
        self.solids
            .iter()
            .enumerate()
            .map(|(index, s)| CadSolidSummary {
                index,
                entity: s.entity.clone(),
                shells: s
                    .shells
                    .iter()
                    .filter(|&&k| k < self.shells.len())
                    .map(|&k| self.shell_summary(k))
                    .collect(),
            })
            .collect()
    }
}

impl CadFaceSummary {
    /// The summary of face `index` of `model` from its domain (or the reason it has none), as
    /// [`CadModel::face_domains`] gives it with `relative_closure_tolerance`.
    ///
    /// # Panics
    /// If `index` is not a face of `model`.
    pub fn of(
        model: &CadModel,
        index: usize,
        domain: &Result<Domain, IoError>,
        relative_closure_tolerance: Option<f64>,
    ) -> Self {
        let face = &model.faces[index];
        let mut s = CadFaceSummary {
            index,
            entity: face.entity.clone(),
            surface: face.surface_name.clone(),
            loops: 0,
            curves: 0,
            area: 0.0,
            bounding_box: None,
            closure_tolerance: 0.0,
            width: 0.0,
            pcurve_deviation: face.pcurve_deviation,
            natural_bounds: face.natural_bounds,
            error: None,
        };
        match domain {
            Ok(d) => {
                s.loops = d.loops().len();
                s.curves = d.curves().len();
                s.area = d.signed_area();
                s.bounding_box = Some(d.bounding_box());
                if let Some(b) = face.loops_box() {
                    s.closure_tolerance =
                        model.tolerance.closure_gap(&b, relative_closure_tolerance);
                }
                let length: f64 = d.curves().iter().map(|c| c.arclen(1e-9)).sum();
                s.width = if length > 0.0 {
                    2.0 * s.area.abs() / length
                } else {
                    0.0
                };
            }
            Err(IoError::CadFace { message, .. }) => s.error = Some(message.clone()),
            Err(other) => s.error = Some(other.to_string()),
        }
        s
    }
}

impl fmt::Display for CadFaceSummary {
    /// `face 3  #245  PLANE  loops 2  curves 9  area 1.25  u [0, 2]  v [-1, 0.5]`, then
    /// `natural bounds`, `pcurves fitted within 3.2e-8` and `narrow: ...` where they apply, or
    /// the reason the face is refused.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "face {:<4} {:<9} {:<28}",
            self.index, self.entity, self.surface
        )?;
        match (&self.error, self.bounding_box) {
            (Some(e), _) => write!(f, " refused: {e}"),
            (None, Some(b)) => {
                write!(
                    f,
                    " loops {}  curves {}  area {:.6e}  u [{:.6e}, {:.6e}]  v [{:.6e}, {:.6e}]",
                    self.loops, self.curves, self.area, b.min.x, b.max.x, b.min.y, b.max.y
                )?;
                if self.natural_bounds {
                    write!(f, "  natural bounds")?;
                }
                if let Some(d) = self.pcurve_deviation {
                    write!(f, "  pcurves fitted within {d:.1e}")?;
                }
                if self.is_narrow() {
                    write!(
                        f,
                        "  narrow: {:.1e} wide, closed within {:.1e}",
                        self.width, self.closure_tolerance
                    )?;
                }
                Ok(())
            }
            (None, None) => Ok(()),
        }
    }
}

impl fmt::Display for CadShellSummary {
    /// `shell 0  #12  closed  faces 0-5` (ranges of consecutive faces joined).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "shell {:<3} {:<9} {:<6} {} face{} {}",
            self.index,
            self.entity,
            if self.closed { "closed" } else { "open" },
            self.faces.len(),
            if self.faces.len() == 1 { "" } else { "s" },
            ranges(&self.faces)
        )
    }
}

impl fmt::Display for CadSolidSummary {
    /// `solid 0  #10  1 shell`, then one indented line per shell (`void` after the first).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "solid {:<3} {:<9} {} shell{}",
            self.index,
            self.entity,
            self.shells.len(),
            if self.shells.len() == 1 { "" } else { "s" }
        )?;
        for (k, s) in self.shells.iter().enumerate() {
            write!(f, "\n  {} {s}", if k == 0 { "outer" } else { "void " })?;
        }
        Ok(())
    }
}

/// `0-5, 8, 10-11`: sorted indices with runs joined.
fn ranges(indices: &[usize]) -> String {
    let mut sorted = indices.to_vec();
    sorted.sort_unstable();
    sorted.dedup();
    let mut out: Vec<String> = Vec::new();
    let mut i = 0;
    while i < sorted.len() {
        let mut j = i;
        while j + 1 < sorted.len() && sorted[j + 1] == sorted[j] + 1 {
            j += 1;
        }
        out.push(if j > i {
            format!("{}-{}", sorted[i], sorted[j])
        } else {
            sorted[i].to_string()
        });
        i = j + 1;
    }
    out.join(", ")
}

#[cfg(test)]
mod tests {
    use rs_geom::Tolerance;
    use rs_geom::brep::{Face, Model};
    use rs_spline::{Point, segment};

    use super::*;
    use crate::cad::CadFormat;

    /// A one-face model: a `w` by 1 rectangle in `(u, v)`, in a file of tolerance `tol`.
    fn strip(w: f64, tol: f64) -> CadModel {
        let c = [(0.0, 0.0), (w, 0.0), (w, 1.0), (0.0, 1.0)].map(|(x, y)| Point::new(x, y));
        let lines = (0..4)
            .map(|k| segment(c[k], c[(k + 1) % 4]).unwrap())
            .collect();
        CadModel {
            format: CadFormat::Step,
            model: Model {
                faces: vec![Face {
                    entity: "#1".into(),
                    surface_name: "PLANE".into(),
                    surface: None,
                    surface_error: None,
                    same_sense: true,
                    loops: Ok(vec![lines]),
                    edges: Vec::new(),
                    pcurve_deviation: None,
                    natural_bounds: false,
                }],
                tolerance: Tolerance::new(Some(tol)).unwrap(),
                ..Model::default()
            },
        }
    }

    /// A face narrower than the gap its loops close within says so (`SOD_323`'s faces a few
    /// 1e-7 wide in a file of tolerance 2e-4); a wide one does not.
    #[test]
    fn faces_narrower_than_their_closure_tolerance_are_flagged() {
        let thin = &strip(3e-7, 2e-4).face_summaries(None)[0];
        // Width 2 area / perimeter = 2 (3e-7) / (2 + 6e-7).
        assert!((thin.width - 3e-7).abs() < 1e-12, "{}", thin.width);
        assert_eq!(thin.closure_tolerance, 2e-4);
        assert!(thin.is_narrow());
        assert!(
            thin.to_string()
                .contains("narrow: 3.0e-7 wide, closed within 2.0e-4"),
            "{thin}"
        );
        let wide = &strip(0.5, 2e-4).face_summaries(None)[0];
        assert!(
            !wide.is_narrow() && !wide.to_string().contains("narrow"),
            "{wide}"
        );
        // A caller's relative closure tolerance decides too.
        assert!(!strip(3e-7, 2e-4).face_summaries(Some(1e-9))[0].is_narrow());
    }

    #[test]
    fn runs_of_indices_are_joined() {
        assert_eq!(ranges(&[5, 0, 1, 2, 8, 10, 11]), "0-2, 5, 8, 10-11");
        assert_eq!(ranges(&[]), "");
    }
}
