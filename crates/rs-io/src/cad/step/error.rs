//! The STEP reader's errors: one line each, naming the instance at fault (`#12 CIRCLE: ...`).
//!
//! A file-level error (the file does not parse, its shape structure is broken) becomes an
//! [`IoError::Cad`](crate::IoError::Cad) with this message; a face-level one is kept whole in
//! the face (`FaceError::Read`), where `downcast_ref::<StepError>()` recovers it.

use rs_geom::GeomError;
use thiserror::Error;

/// Why a STEP file, or one of its faces, cannot be read.
#[derive(Clone, Debug, Error, PartialEq)]
#[non_exhaustive]
pub enum StepError {
    /// The Part 21 text is malformed (the message names the line).
    #[error("{0}")]
    Syntax(String),
    /// A reference to an instance the file does not define.
    #[error("{from} refers to #{label}, which is not in the file")]
    MissingInstance {
        /// The instance (or context) that refers to it.
        from: String,
        /// The missing label.
        label: u64,
    },
    /// An attribute that is missing or of the wrong kind.
    #[error("{what}: attribute {} ({name}) {problem}", index + 1)]
    Attribute {
        /// The instance (`#12 CIRCLE`).
        what: String,
        /// The attribute's 0-based position in its record.
        index: usize,
        /// The attribute's name in the schema.
        name: &'static str,
        /// What is wrong with it.
        problem: String,
    },
    /// An instance of another type than the one its referrer needs.
    #[error("{what} is not a {expected}")]
    WrongType {
        /// The instance.
        what: String,
        /// The type needed.
        expected: String,
    },
    /// A complex instance where a simple one is needed.
    #[error("{what}: unexpected complex instance")]
    Complex {
        /// The instance.
        what: String,
    },
    /// Products, representations or topology nested beyond the limit.
    #[error("{what}: structure nested deeper than {limit} levels")]
    TooDeep {
        /// The instance reached at the limit.
        what: String,
        /// The limit.
        limit: usize,
    },
    /// An assembly that contains itself.
    #[error("{what}: the assembly contains itself")]
    AssemblyCycle {
        /// The product definition met again.
        what: String,
    },
    /// A representation, shell or item that contains itself.
    #[error("{what}: reference cycle")]
    Cycle {
        /// The instance met again.
        what: String,
    },
    /// More of something than the reader accepts (face uses, control points, edges).
    #[error("{what}: more than {limit}")]
    TooMany {
        /// What is counted (`face uses`, `#12 EDGE_LOOP edges`).
        what: String,
        /// The limit.
        limit: usize,
    },
    /// A number that must be positive, finite, or in a range, is not.
    #[error("{what}: {name} {value:e}")]
    BadNumber {
        /// The instance.
        what: String,
        /// The attribute (`radius`, `magnitude`, `plane angle unit factor`).
        name: &'static str,
        /// Its value.
        value: f64,
    },
    /// A structural defect of one instance, described in words.
    #[error("{what}: {problem}")]
    Invalid {
        /// The instance.
        what: String,
        /// What is wrong (`fewer than two points`, `degree 0`, `empty trim [0, 0]`, ...).
        problem: String,
    },
    /// An entity type the reader does not read where it was found.
    #[error("{what}: {role} type {name} is not supported")]
    Unsupported {
        /// The instance.
        what: String,
        /// What it stands for (`curve`, `surface`, `loop`, `transformation`).
        role: &'static str,
        /// Its type name.
        name: String,
    },
    /// A placement whose axes do not span space.
    #[error("{what}: degenerate axes: {reason}")]
    DegenerateAxes {
        /// The placement.
        what: String,
        /// Why (`the axis is zero`, `the reference direction is along the axis`).
        reason: String,
    },
    /// The geometry layer refused what an instance describes.
    #[error("{what}: {source}")]
    Geometry {
        /// The instance.
        what: String,
        /// Why.
        source: GeomError,
    },
    /// A face with no edge loop on a surface with no finite natural box.
    #[error("{face}: a face with no bounds on an unbounded {surface} #{label}")]
    UnboundedFace {
        /// The face (`#12 ADVANCED_FACE`).
        face: String,
        /// The surface's type name.
        surface: String,
        /// The surface's label.
        label: u64,
    },
    /// A face whose surface could not be read, so nothing more can be done with it.
    #[error("{face}: no surface to bound ({reason})")]
    NoSurface {
        /// The face.
        face: String,
        /// Why the surface could not be read.
        reason: String,
    },
    /// An edge whose vertices come in the wrong order along its curve.
    #[error(
        "{edge}: the vertices are at parameters {start} and {end} of the curve, the wrong way round for same_sense {same_sense}"
    )]
    VertexOrder {
        /// The edge (`#55 EDGE_CURVE`).
        edge: String,
        /// The start vertex's parameter.
        start: f64,
        /// The end vertex's parameter.
        end: f64,
        /// The edge's `same_sense`.
        same_sense: bool,
    },
    /// An edge without a pcurve on a face whose surface could not be read, so that none can
    /// be computed.
    #[error(
        "edge #{edge} has no pcurve on its {surface} #{label}, which could not be read to compute one"
    )]
    NoPcurve {
        /// The edge's label.
        edge: u64,
        /// The surface's type name.
        surface: String,
        /// The surface's label.
        label: u64,
    },
    /// An edge without a pcurve whose computed pcurve is farther from it than the file's
    /// tolerance.
    #[error(
        "edge #{edge} has no pcurve on its {surface} #{label}; the one computed from its 3-D curve is within {bound:.3e} of it, more than the file's tolerance {tolerance:.3e}"
    )]
    PcurveDeviation {
        /// The edge's label.
        edge: u64,
        /// The surface's type name.
        surface: String,
        /// The surface's label.
        label: u64,
        /// The computed pcurve's bound on its 3-D distance from the edge.
        bound: f64,
        /// The file's tolerance.
        tolerance: f64,
    },
    /// An edge mapped into a plane whose 3-D curve leaves the plane.
    #[error(
        "{edge}: its 3-D curve leaves the face's plane by {off:.3e} (more than the tolerance {tolerance:.3e})"
    )]
    OffPlane {
        /// The edge.
        edge: String,
        /// The largest distance found.
        off: f64,
        /// The tolerance.
        tolerance: f64,
    },
    /// Consecutive edges of a loop that do not meet in `(u, v)`.
    #[error(
        "{edge_loop}: edge #{edge} does not meet the previous edge in (u, v): gap {gap:.3e} at ({:.6}, {:.6})",
        at[0],
        at[1]
    )]
    EdgeGap {
        /// The loop (`#107 EDGE_LOOP`).
        edge_loop: String,
        /// The edge that does not continue the loop.
        edge: u64,
        /// The smallest gap found.
        gap: f64,
        /// Where the loop was.
        at: [f64; 2],
    },
    /// A loop whose last edge does not return to its first.
    #[error(
        "{edge_loop}: the loop does not close in (u, v): gap {gap:.3e} from ({:.6}, {:.6}) to ({:.6}, {:.6})",
        from[0],
        from[1],
        to[0],
        to[1]
    )]
    LoopOpen {
        /// The loop.
        edge_loop: String,
        /// The gap.
        gap: f64,
        /// The loop's end.
        from: [f64; 2],
        /// Its start.
        to: [f64; 2],
    },
}

impl StepError {
    /// A [`StepError::Geometry`] naming `what`.
    pub(crate) fn geometry(what: impl Into<String>, source: GeomError) -> StepError {
        StepError::Geometry {
            what: what.into(),
            source,
        }
    }

    /// A [`StepError::Invalid`] naming `what`.
    pub(crate) fn invalid(what: impl Into<String>, problem: impl Into<String>) -> StepError {
        StepError::Invalid {
            what: what.into(),
            problem: problem.into(),
        }
    }
}

/// The results of the reader.
pub(crate) type Result<T, E = StepError> = std::result::Result<T, E>;
