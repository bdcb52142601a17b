//! Read planar domains for `inrs` from the files users hold their curves in.
//!
//! - [`json`]: the JSON domain file (read and write).
//! - [`svg`]: SVG path data (every command, absolute and relative, shorthand forms, elliptical
//!   arcs converted exactly to rational quadratics) and SVG files (all drawn shapes, transforms
//!   applied).
//! - [`font`]: TrueType/OpenType glyphs (quadratic or cubic contours) as domains with holes.
//! - [`dxf_file`] (feature `dxf`, on by default): DXF drawings: `SPLINE`, `LWPOLYLINE`/`POLYLINE` with bulges (exact arcs),
//!   `LINE`, `ARC`, `CIRCLE`, `ELLIPSE`, chained into loops.
//! - [`cad`]: STEP and IGES parts: the trimming loops of each face in its `(u, v)`
//!   (`part.step#face:3`).
//! - [`load_domain`]: one entry point choosing the reader from the file name, as the `inrs`
//!   command line does.
//! - [`points`]: the points files (CSV `x,y`, `.npy`) the command line streams points from,
//!   read in bounded memory, in order or by position.
//! - [`formula`]: formulas in `x` and `y` (`inrs fit --function`, `inrs integrate
//!   --function`, the Python package), one grammar with standard float literals.
//!
//! Every reader produces exact NURBS (no flattening): lines stay degree 1, Bezier commands
//! keep their degree, arcs are exact conics. Loops are watertight: shared end points are
//! bit-identical. Errors name the element, entity or glyph and what is wrong.
//!
//! # Examples
//!
//! ```
//! use rs_io::svg::domain_from_path_data;
//! // A unit square with a round hole of radius 1/4 drawn as two arcs.
//! let d = domain_from_path_data("M0 0h1v1H0z M0.75 0.5a0.25 0.25 0 0 0 -0.5 0a0.25 0.25 0 0 0 0.5 0z")
//!     .unwrap();
//! assert_eq!(d.loops().len(), 2);
//! let area = 1.0 - std::f64::consts::PI / 16.0;
//! assert!((d.signed_area() - area).abs() < 1e-12); // the hole is drawn clockwise
//! ```

mod builder;
pub mod cad;
#[cfg(feature = "dxf")]
pub mod dxf_file;
mod error;
pub mod font;
pub mod formula;
pub mod json;
pub mod points;
pub mod svg;

use std::path::Path;

pub use error::IoError;
use rs_spline::Domain;

/// How [`load_domain_with`] reads a domain.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LoadOptions {
    /// The closure tolerance, relative to the diagonal of the domain's bounding box: the
    /// largest gap between consecutive curves that still counts as meeting. `None`: the
    /// reader's default ([`rs_spline::DEFAULT_RELATIVE_CLOSURE_TOLERANCE`]; for a CAD face the
    /// larger of it and the file's own tolerance, see [`cad`]).
    pub closure_tolerance: Option<f64>,
}

/// A domain read, with the errors the reader recovered from on the way, as renderers recover
/// from them (an SVG `path` drawn up to an error in its data): each a one-line message of its
/// own, for the caller to show as a warning.
#[derive(Debug)]
#[non_exhaustive]
pub struct Loaded {
    /// The domain.
    pub domain: Domain,
    /// The errors recovered from, in the order met (empty for most files).
    pub warnings: Vec<IoError>,
}

/// Reads a domain from `spec` with the default options ([`load_domain_with`]).
///
/// # Errors
/// As [`load_domain_with`].
pub fn load_domain(spec: &str) -> Result<Domain, IoError> {
    load_domain_with(spec, &LoadOptions::default())
}

/// Reads a domain from `spec`, choosing the reader by extension:
///
/// - `*.json`: the domain file ([`json::domain_from_json_file`]);
/// - `*.svg`: an SVG document ([`svg::domain_from_svg_file`]);
/// - `*.dxf`: a DXF drawing ([`dxf_file::domain_from_dxf_file`]);
/// - `*.ttf`, `*.otf`, `*.ttc`, `*.otc` followed by `#glyph`: one glyph of a font
///   ([`font::Glyph`] syntax: `font.ttf#B`, `font.ttf#U+0040`, `font.ttf#gid:37`);
/// - `*.step`, `*.stp`, `*.igs`, `*.iges`, followed by `#face:K` unless the file has one
///   face: face `K` of a CAD part in its `(u, v)` ([`cad::CadModel::face_domain`]); a solid
///   (`#solid:K`) is not a planar domain and is refused here.
///
/// `options.closure_tolerance`, when given, groups the curves into loops with that relative
/// tolerance whatever the reader. What a reader recovers from (an SVG path drawn up to an
/// error in its data) is dropped here: [`load_domain_with_warnings`] gives it.
///
/// # Errors
/// [`IoError::UnknownFormat`] for another extension; [`IoError::Glyph`] for a font without
/// `#glyph`; [`IoError::Cad`] for a CAD file with several faces and no `#face:K`, or a bad
/// selection; the reader's errors otherwise.
pub fn load_domain_with(spec: &str, options: &LoadOptions) -> Result<Domain, IoError> {
    load_domain_with_warnings(spec, options).map(|l| l.domain)
}

/// [`load_domain_with`], with the errors the reader recovered from ([`Loaded`]), which the
/// command line prints as warnings.
///
/// # Errors
/// As [`load_domain_with`].
pub fn load_domain_with_warnings(spec: &str, options: &LoadOptions) -> Result<Loaded, IoError> {
    let closure = options.closure_tolerance;
    if let Some((file, selection)) = cad::split_cad_spec(spec) {
        let model = cad::CadModel::read(file)?;
        let index = match selection.transpose()? {
            Some(cad::CadSelection::Face(k)) => k,
            Some(cad::CadSelection::Solid(k)) => {
                return Err(IoError::Cad {
                    format: model.format.name(),
                    message: format!(
                        "{file}#solid:{k} is a solid, not a planar domain: name a face as \
                         {file}#face:K (`inrs info {file}#solid:{k}` lists the solid's faces)"
                    ),
                });
            }
            None if model.faces.len() == 1 => 0,
            None => {
                return Err(IoError::Cad {
                    format: model.format.name(),
                    message: format!(
                        "{file} has {} faces: name one as {file}#face:K (`inrs info {file}` lists them)",
                        model.faces.len()
                    ),
                });
            }
        };
        return model.face_domain(index, closure).map(plain);
    }
    let Loaded { domain, warnings } = read_domain(spec, closure)?;
    let domain = match closure {
        Some(t) => domain.with_closure_tolerance(t)?,
        None => domain,
    };
    Ok(Loaded { domain, warnings })
}

/// The domain of a non-CAD `spec` with the reader's own closure (DXF chains its entities with
/// `closure`), and what the reader recovered from.
fn read_domain(spec: &str, closure: Option<f64>) -> Result<Loaded, IoError> {
    #[cfg(not(feature = "dxf"))]
    let _ = closure;
    let lower = spec.to_ascii_lowercase();
    for ext in [".ttf#", ".otf#", ".ttc#", ".otc#"] {
        if let Some(i) = lower.find(ext) {
            let (file, glyph) = spec.split_at(i + ext.len() - 1);
            let glyph: font::Glyph = glyph[1..].parse()?;
            return font::glyph_domain_from_file(file, &glyph).map(plain);
        }
    }
    let path = Path::new(spec);
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    let domain = match ext.as_deref() {
        Some("svg") => return svg::load_svg_file(path, svg::OpenSubpaths::Close),
        Some("ttf" | "otf" | "ttc" | "otc") => Err(IoError::Glyph {
            glyph: String::new(),
            message: format!(
                "name the glyph after the font file: {spec}#B, {spec}#U+0042 or {spec}#gid:37"
            ),
        }),
        Some("json") => json::domain_from_json_file(path),
        #[cfg(feature = "dxf")]
        Some("dxf") => {
            let mut dxf = dxf_file::DxfOptions::default();
            if let Some(t) = closure {
                dxf = dxf.with_relative_closure_tolerance(t);
            }
            dxf_file::domain_from_dxf_file(path, &dxf)
        }
        #[cfg(not(feature = "dxf"))]
        Some("dxf") => Err(IoError::FormatDisabled {
            format: "DXF",
            feature: "dxf",
        }),
        _ => Err(IoError::UnknownFormat {
            path: path.to_path_buf(),
        }),
    };
    domain.map(plain)
}

/// A domain read without anything recovered from.
fn plain(domain: Domain) -> Loaded {
    Loaded {
        domain,
        warnings: Vec::new(),
    }
}
