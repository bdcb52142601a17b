//! The boundary representation of a CAD part as one read of its file gives it: faces (a
//! surface, its trimming loops in the surface's `(u, v)`, its sense, its 3-D edges), shells
//! (faces) and solids (an outer shell and voids), in `OpenCASCADE`'s explorer order of the same
//! file, so that an index means the same face or solid here and in `OpenCASCADE`-based tools.

mod domain;

use std::error::Error;
use std::fmt;
use std::sync::Arc;

use rs_spline::{DomainError, NurbsCurve, Point3};
use thiserror::Error;

use crate::{Curve, Tolerance};

/// A boundary representation: faces, shells of faces, solids of shells.
#[derive(Clone, Debug, Default)]
pub struct Model {
    /// The faces, in `OpenCASCADE`'s face-explorer order (`#face:K`).
    pub faces: Vec<Face>,
    /// The shells, in `OpenCASCADE`'s shell-explorer order.
    pub shells: Vec<Shell>,
    /// The solids, in `OpenCASCADE`'s solid-explorer order (`#solid:K`).
    pub solids: Vec<Solid>,
    /// The file's tolerance policy.
    pub tolerance: Tolerance,
    /// The length unit of the file's coordinates, when the file states one (lengths stay in
    /// it: the model is not converted).
    pub length_unit: Option<LengthUnit>,
}

impl Model {
    /// The entities of the edges that only one of `faces` (indices into [`Model::faces`])
    /// uses, sorted: the free edges of a shell of those faces (none for a closed shell). Edges
    /// are told apart by their entity (`#123`, `DE 57`); faces without 3-D edges add none.
    pub fn free_edges(&self, faces: &[usize]) -> Vec<String> {
        let mut uses = std::collections::BTreeMap::<&str, usize>::new();
        for &f in faces {
            for e in self.faces[f].edges.iter().flatten() {
                *uses.entry(e.entity.as_str()).or_default() += 1;
            }
        }
        uses.into_iter()
            .filter(|&(_, n)| n == 1)
            .map(|(e, _)| e.to_string())
            .collect()
    }
}

/// The length unit of a model's coordinates.
#[derive(Clone, Debug, PartialEq)]
pub struct LengthUnit {
    /// The unit's name as the file gives it (`MM`, `INCH`, ...).
    pub name: String,
    /// Millimetres per unit (`25.4` for inches): a length `l` of the model is `l * millimetres`
    /// millimetres.
    pub millimetres: f64,
}

impl LengthUnit {
    /// The unit's usual symbol (`mm`, `cm`, `m`, `km`, `um`, `nm`, `in`, `ft`, `yd`, `mi`,
    /// `mil`, `uin`), from its length in millimetres; `None` for another length.
    ///
    /// ```
    /// use rs_geom::brep::LengthUnit;
    /// let unit = |name: &str, millimetres| LengthUnit { name: name.into(), millimetres };
    /// assert_eq!(unit("MILLIMETRE", 1.0).symbol(), Some("mm"));
    /// assert_eq!(unit("INCH", 25.4).symbol(), Some("in"));
    /// assert_eq!(unit("FURLONG", 201_168.0).symbol(), None);
    /// ```
    pub fn symbol(&self) -> Option<&'static str> {
        const SYMBOLS: [(f64, &str); 12] = [
            (1.0, "mm"),
            (10.0, "cm"),
            (1000.0, "m"),
            (1e6, "km"),
            (1e-3, "um"),
            (1e-6, "nm"),
            (25.4, "in"),
            (304.8, "ft"),
            (914.4, "yd"),
            (1_609_344.0, "mi"),
            (0.0254, "mil"),
            (2.54e-5, "uin"),
        ];
        SYMBOLS
            .iter()
            .find(|(mm, _)| (self.millimetres - mm).abs() <= 1e-12 * mm)
            .map(|&(_, s)| s)
    }
}

/// One face: a patch of a surface bounded by trimming loops in the surface's `(u, v)`.
#[derive(Clone, Debug)]
pub struct Face {
    /// The face's entity in the file: `#123` (STEP instance) or `DE 57` (IGES directory entry).
    pub entity: String,
    /// The surface type as the file names it (`PLANE`, `B_SPLINE_SURFACE_WITH_KNOTS`,
    /// IGES `128 (rational B-spline surface)`, ...).
    pub surface_name: String,
    /// The surface, in the parameters of the file's standard; `None` when it could not be
    /// read (its type is not supported, or its data is broken: `surface_error` says why).
    pub surface: Option<crate::surface::Surface>,
    /// Why the surface could not be read, when it could not.
    pub surface_error: Option<FaceError>,
    /// Whether the face's outward normal is the surface's `S_u x S_v` (`true`) or its
    /// opposite (STEP's `same_sense`, IGES's face orientation in its shell).
    pub same_sense: bool,
    /// The loops, the outer one first, each its curves in loop order in `(u, v)`; each curve
    /// ends where the next one starts within the file's tolerance and the last returns to the
    /// first. `Err` says why the face's loops could not be read (the other faces of the file
    /// are unaffected).
    pub loops: Result<Vec<Vec<NurbsCurve>>, FaceError>,
    /// The face's 3-D edges, loop by loop in loop order (empty where the file gives none, or
    /// the face is bounded by its surface's natural limits).
    pub edges: Vec<Vec<Edge>>,
    /// The largest 3-D distance between a computed pcurve and its edge, a bound computed when
    /// the pcurve was fitted (model units); `None` when every pcurve came from the file or is
    /// exact.
    pub pcurve_deviation: Option<f64>,
    /// Whether the loops are the surface's natural parameter box (a face written without
    /// bounds: a full sphere or torus).
    pub natural_bounds: bool,
}

/// A 3-D edge of a face: the window of a curve between its vertices, in the direction it runs
/// in its loop.
#[derive(Clone, Debug)]
pub struct Edge {
    /// The edge's entity in the file.
    pub entity: String,
    /// The edge's 3-D curve in its own parameter.
    pub curve: Curve<Point3>,
    /// The parameter window `t0 < t1` between the edge's vertices.
    pub range: (f64, f64),
    /// Whether the loop runs the window from `t1` to `t0`.
    pub reversed: bool,
}

impl Edge {
    /// The edge's start and end in loop order.
    pub fn ends(&self) -> (Point3, Point3) {
        let (a, b) = (
            self.curve.point(self.range.0),
            self.curve.point(self.range.1),
        );
        if self.reversed { (b, a) } else { (a, b) }
    }

    /// `n >= 2` points along the edge in loop order, at equal steps of its parameter.
    pub fn sample(&self, n: usize) -> Vec<Point3> {
        let n = n.max(2);
        let (t0, t1) = self.range;
        (0..n)
            .map(|i| {
                let s = i as f64 / (n - 1) as f64;
                let s = if self.reversed { 1.0 - s } else { s };
                self.curve.point(t0 + s * (t1 - t0))
            })
            .collect()
    }
}

/// A shell: a connected set of faces.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Shell {
    /// The shell's entity in the file.
    pub entity: String,
    /// Its faces, as indices into [`Model::faces`].
    pub faces: Vec<usize>,
    /// Whether the file says the shell is closed (STEP `CLOSED_SHELL`, an IGES 514 of a 186).
    /// The STEP reader also checks its edges, as `OpenCASCADE` does: a `CLOSED_SHELL` with an
    /// edge used by only one of its faces is not closed (and is no solid's shell).
    pub closed: bool,
}

/// A solid: the region inside an outer shell and outside its voids.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Solid {
    /// The solid's entity in the file.
    pub entity: String,
    /// Its shells as indices into [`Model::shells`], the outer one first, then the voids.
    pub shells: Vec<usize>,
}

/// Why a face (its loops or its surface) cannot be used.
#[derive(Clone, Debug, Error)]
#[non_exhaustive]
pub enum FaceError {
    /// The reader could not read it (the reader's own error, which names the entity).
    #[error("{0}")]
    Read(ReadError),
    /// The face has loops but no curves in them.
    #[error("the face has no trimming curves")]
    NoCurves,
    /// Consecutive curves of a loop do not meet.
    #[error(
        "loop {loop_index}: curve {curve} ends {gap:.2e} away from the start of curve {next} \
         (closure tolerance {tolerance:.2e}; a larger relative closure tolerance joins them)"
    )]
    Gap {
        /// The loop.
        loop_index: usize,
        /// The curve whose end misses.
        curve: usize,
        /// The curve whose start it misses.
        next: usize,
        /// The gap.
        gap: f64,
        /// The closure tolerance it exceeds.
        tolerance: f64,
    },
    /// The closed loops do not make a domain.
    #[error(transparent)]
    Domain(#[from] DomainError),
}

/// A reader's error kept whole (its type, for `downcast_ref`), shared by the faces it refuses.
#[derive(Clone)]
pub struct ReadError(pub Arc<dyn Error + Send + Sync>);

impl ReadError {
    /// Wraps a reader's error.
    pub fn new(e: impl Error + Send + Sync + 'static) -> ReadError {
        ReadError(Arc::new(e))
    }
}

impl fmt::Display for ReadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.0.fmt(f)
    }
}

impl fmt::Debug for ReadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.0.fmt(f)
    }
}

/// Why a model cannot give what was asked of it.
#[derive(Clone, Debug, Error)]
#[non_exhaustive]
pub enum ModelError {
    /// A face index past the last face.
    #[error("{}", no_such("face", *index, *count))]
    NoFace {
        /// The index asked for.
        index: usize,
        /// How many faces the model has.
        count: usize,
    },
    /// A solid index past the last solid.
    #[error("{}", no_such("solid", *index, *count))]
    NoSolid {
        /// The index asked for.
        index: usize,
        /// How many solids the model has.
        count: usize,
    },
    /// A face that cannot be made a domain.
    #[error("face {index} ({entity}): {error}")]
    Face {
        /// The face's index.
        index: usize,
        /// Its entity.
        entity: String,
        /// Why.
        error: FaceError,
    },
    /// An invalid relative closure tolerance.
    #[error(transparent)]
    Domain(#[from] DomainError),
}

/// `face 3 does not exist: the file has 2 faces (#face:0 to #face:1)`.
fn no_such(what: &str, index: usize, count: usize) -> String {
    match count {
        0 => format!("{what} {index} does not exist: the file has no {what}s"),
        n => format!(
            "{what} {index} does not exist: the file has {n} {what}{} (#{what}:0 to #{what}:{})",
            if n == 1 { "" } else { "s" },
            n - 1
        ),
    }
}
