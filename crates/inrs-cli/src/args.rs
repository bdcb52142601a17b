//! Arguments shared by several subcommands, and the option enums (each a clap `ValueEnum`
//! mapped onto the library's type).

use std::path::PathBuf;

use clap::{Args, ValueEnum};
use inrs::Domain;
use inrs::contain::FillRule;
use inrs::contain::baselines::WindingAlgorithm;

use crate::cli::error::CliError;

// `--domain`: the domain every subcommand but `convex-domain` reads. (Not a doc comment: clap
// would take it for the help of the subcommands that flatten it in.)
#[derive(Args, Debug)]
pub(crate) struct DomainArg {
    /// The domain: a JSON domain file (docs/FORMATS.md), an .svg or .dxf file, a font
    /// glyph (`font.ttf#B`, `#U+0040`, `#gid:37`), or a face of a STEP/IGES part in its (u, v)
    /// (`part.step#face:3`; `inrs info part.step` lists the faces).
    #[arg(long)]
    pub(crate) domain: PathBuf,
    /// Closure tolerance, relative to the diagonal of the domain's bounding box: consecutive
    /// curves whose end and start are at most this far apart meet [default: 1e-9; for a CAD
    /// face the larger of it and the file's own tolerance].
    #[arg(long, value_name = "REL")]
    pub(crate) closure_tol: Option<f64>,
}

impl DomainArg {
    /// Reads the domain, choosing the reader by the file name; what the reader recovered from
    /// (an SVG path drawn up to an error in its data) is a warning on standard error, one line
    /// each.
    pub(crate) fn load(&self) -> Result<Domain, CliError> {
        let spec = self.domain.to_string_lossy();
        let options = inrs::io::LoadOptions {
            closure_tolerance: self.closure_tol,
        };
        let loaded = inrs::io::load_domain_with_warnings(&spec, &options).map_err(|e| match e {
            inrs::io::IoError::Read { .. }
            | inrs::io::IoError::UnknownFormat { .. }
            | inrs::io::IoError::FormatDisabled { .. } => CliError::Message(e.to_string()),
            other => CliError::Message(format!("{spec}: {other}")),
        })?;
        for w in &loaded.warnings {
            eprintln!("inrs: warning: {spec}: {w}");
        }
        Ok(loaded.domain)
    }

    /// An error about the domain, prefixed with its file name.
    pub(crate) fn error(&self, e: impl std::fmt::Display) -> CliError {
        CliError::Message(format!("{}: {e}", self.domain.display()))
    }
}

// `classify --domain`, which may be given several times: the domains every point is
// classified against. (Not a doc comment: clap would take it for the help of `classify`.)
#[derive(Args, Debug)]
pub(crate) struct DomainsArg {
    /// The domain: a JSON domain file (docs/FORMATS.md), an .svg or .dxf file, a font
    /// glyph (`font.ttf#B`, `#U+0040`, `#gid:37`), or a face of a STEP/IGES part in its (u, v)
    /// (`part.step#face:3`; `inrs info part.step` lists the faces). Repeat it, or name every
    /// face of a part with `part.step#face:*`, to classify against several domains: one
    /// output column per domain.
    #[arg(long, required = true)]
    pub(crate) domain: Vec<PathBuf>,
    /// Closure tolerance, relative to the diagonal of the domain's bounding box: consecutive
    /// curves whose end and start are at most this far apart meet [default: 1e-9; for a CAD
    /// face the larger of it and the file's own tolerance].
    #[arg(long, value_name = "REL")]
    pub(crate) closure_tol: Option<f64>,
}

impl DomainsArg {
    /// The one domain as a [`DomainArg`], when exactly one is given and it names no set of
    /// faces (`#face:*`): the single-domain path, unchanged.
    pub(crate) fn single(&self) -> Option<DomainArg> {
        match self.domain.as_slice() {
            [d] if all_faces(&d.to_string_lossy()).is_none() => Some(DomainArg {
                domain: d.clone(),
                closure_tol: self.closure_tol,
            }),
            _ => None,
        }
    }
}

/// For `part.step#face:*` (any case of the CAD extensions and of `face`): the file
/// `part.step`. `None` for any other specification.
pub(crate) fn all_faces(spec: &str) -> Option<&str> {
    let cut = spec.len().checked_sub("#face:*".len())?;
    let (file, tail) = (spec.get(..cut)?, spec.get(cut..)?);
    let is_cad = matches!(inrs::io::cad::split_cad_spec(file), Some((f, None)) if f == file);
    (tail.eq_ignore_ascii_case("#face:*") && is_cad).then_some(file)
}

/// The help of `--function` (`fit`, `integrate`): the grammar of `inrs::io::formula`.
pub(crate) const FUNCTION_HELP: &str = "A formula in x and y: numbers (1e-3 and 2.5E+4 too), \
+ - * / and ^ (or **; -x^2 is -(x^2), 2^3^2 is 2^9), parentheses, the constants pi, e, tau, \
the functions abs signum sqrt cbrt exp ln log (natural) log2 log10 sin cos tan asin acos atan \
sinh cosh tanh asinh acosh atanh floor ceil round trunc fract, and atan2(y, x), min(a, b), \
max(a, b), hypot(a, b). A leading minus is read as the formula: --function -x^2.";

/// `classify --method`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum MethodArg {
    /// inRS2 for small batches, the parallel grid point locator for large ones (the default).
    Fast,
    /// Each point against each box (the paper's inRS1).
    Inrs1,
    /// Points sorted by abscissa, a binary search per box (the paper's inRS2).
    Inrs2,
    /// Rounded generalized winding number: the only method that accepts open or overlapping
    /// boundaries.
    Gwn,
}

impl From<MethodArg> for inrs::Method {
    fn from(m: MethodArg) -> Self {
        match m {
            MethodArg::Fast => inrs::Method::Fast,
            MethodArg::Inrs1 => inrs::Method::InRS1,
            MethodArg::Inrs2 => inrs::Method::InRS2,
            MethodArg::Gwn => inrs::Method::Gwn,
        }
    }
}

/// `--fill-rule` of `classify`, `fractions`, `cubature`, `integrate` and `info`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum FillRuleArg {
    /// Inside where the winding number is odd: holes are holes whatever the loops'
    /// orientation.
    #[value(alias = "evenodd")]
    EvenOdd,
    /// Inside where the winding number is not zero: two nested counter-clockwise circles fill
    /// the outer disc.
    #[value(alias = "non-zero")]
    Nonzero,
}

impl From<FillRuleArg> for FillRule {
    fn from(r: FillRuleArg) -> Self {
        match r {
            FillRuleArg::EvenOdd => FillRule::EvenOdd,
            FillRuleArg::Nonzero => FillRule::NonZero,
        }
    }
}

/// `winding --algorithm`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum AlgorithmArg {
    /// Exact at any distance and at points on the curves (the default).
    Adaptive,
    /// Ray casting by geometric binary search (the GWN paper's baseline).
    BinarySearch,
    /// Ray casting by Bezier clipping (the GWN paper's baseline).
    BezierClipping,
}

impl From<AlgorithmArg> for WindingAlgorithm {
    fn from(a: AlgorithmArg) -> Self {
        match a {
            AlgorithmArg::Adaptive => WindingAlgorithm::Adaptive,
            AlgorithmArg::BinarySearch => WindingAlgorithm::BinarySearch,
            AlgorithmArg::BezierClipping => WindingAlgorithm::BezierClipping,
        }
    }
}

/// `sample --method`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum SampleMethod {
    /// Schumaker-Yu Algorithm 11.1: horizontal lines cut exactly with the boundary.
    Lines,
    /// The first Halton points inside the domain.
    Halton,
}

/// `convex-domain --sign`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum SignArg {
    /// Keep the curvature (torsion) positive.
    Positive,
    /// Keep it negative.
    Negative,
    /// The sign of the given curve at the middle of its first piece.
    Auto,
}
