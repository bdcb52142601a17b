//! Errors of the readers: every message names the element, entity or glyph and what is wrong.

use std::path::PathBuf;

use rs_spline::{DomainError, SplineError};
use thiserror::Error;

/// Why a file or string could not be read into a domain.
#[derive(Debug, Error)]
pub enum IoError {
    /// The file could not be read.
    #[error("{}: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// The underlying error.
        source: std::io::Error,
    },
    /// The file could not be written.
    #[error("{}: {source}", path.display())]
    Write {
        /// The file.
        path: PathBuf,
        /// The underlying error.
        source: std::io::Error,
    },
    /// A domain file is not valid JSON.
    #[error("invalid JSON at line {line}, column {column}: {message}")]
    Json {
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// What the JSON parser said.
        message: String,
    },
    /// The JSON is valid but not a domain file (its top level).
    #[error("not a domain file: {0}")]
    NotADomainFile(String),
    /// A curve entry of a domain file has the wrong shape (missing key, wrong type, ...).
    #[error("curve {curve}: {message}")]
    CurveEntry {
        /// Index of the curve in the file.
        curve: usize,
        /// What is wrong.
        message: String,
    },
    /// The format's reader was left out of this build.
    #[error("{format} files are not supported by this build (Cargo feature \"{feature}\")")]
    FormatDisabled {
        /// The format.
        format: &'static str,
        /// The Cargo feature of `rs-io` that adds it.
        feature: &'static str,
    },
    /// The file name does not say which format it is in.
    #[error(
        "{}: unknown domain file type (expected .json, .svg, .ttf/.otf/.ttc with #glyph, .dxf, or .step/.stp/.igs/.iges)",
        path.display()
    )]
    UnknownFormat {
        /// The file.
        path: PathBuf,
    },
    /// SVG path data (`d` attribute or a path string) is malformed.
    #[error("SVG path data, at byte {position}: {message}")]
    PathData {
        /// Byte offset into the path string.
        position: usize,
        /// What is wrong.
        message: String,
    },
    /// The SVG document is not well-formed XML.
    #[error("SVG: not well-formed XML: {0}")]
    Xml(String),
    /// An SVG element has a bad attribute or bad path data.
    #[error("SVG <{element}> at line {line}: {message}")]
    SvgElement {
        /// The element name (with its `id` if it has one).
        element: String,
        /// 1-based line of the element in the file.
        line: u32,
        /// What is wrong.
        message: String,
    },
    /// The font file could not be parsed.
    #[error("font: {0}")]
    Font(String),
    /// The glyph selection is invalid or the glyph is not in the font.
    #[error("font glyph {glyph}: {message}")]
    Glyph {
        /// The requested glyph as written (`'B'`, `U+0042`, `gid 37`).
        glyph: String,
        /// What is wrong.
        message: String,
    },
    /// The DXF file could not be parsed.
    #[error("DXF: {0}")]
    Dxf(String),
    /// A DXF entity is unusable.
    #[error("DXF {kind} entity (handle {handle}): {message}")]
    DxfEntity {
        /// Entity type (`SPLINE`, `LWPOLYLINE`, ...).
        kind: &'static str,
        /// The entity's handle (hexadecimal, as in the file).
        handle: String,
        /// What is wrong.
        message: String,
    },
    /// A CAD file (STEP, IGES) could not be read: its syntax or its entity graph is broken.
    #[error("{format}: {message}")]
    Cad {
        /// `"STEP"` or `"IGES"`.
        format: &'static str,
        /// What is wrong, and where (line, entity).
        message: String,
    },
    /// A face of a CAD file could not be turned into a domain.
    #[error("{format} face {index} ({entity}): {message}")]
    CadFace {
        /// `"STEP"` or `"IGES"`.
        format: &'static str,
        /// The face's index in the file (`#face:K`).
        index: usize,
        /// The face's entity (`#123`, `DE 57`).
        entity: String,
        /// What is wrong.
        message: String,
    },
    /// The input holds no boundary with area (no paths, only open lines, empty glyph, ...).
    #[error("no boundary curves found in the {0}")]
    Empty(String),
    /// A curve built from the input is invalid (reported with its origin).
    #[error("{origin}: {source}")]
    Curve {
        /// Where the curve came from.
        origin: String,
        /// What is wrong.
        source: SplineError,
    },
    /// The curves do not form a domain.
    #[error(transparent)]
    Domain(#[from] DomainError),
}
