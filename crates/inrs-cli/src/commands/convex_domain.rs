//! `inrs convex-domain`: where one control point may move keeping the sign of the curvature
//! (plane) or torsion (space).

use std::fmt::Write as _;
use std::path::PathBuf;

use clap::Args;
use inrs::convex::{
    BoundingBox3, ConvexDomain, ConvexDomainOptions, FreeCurve, Region, Sign, SignNumerator,
};

use crate::args::SignArg;
use crate::cli::error::CliError;
use crate::cli::limits::{self, parse_free_index, parse_level, parse_tolerance};
use crate::cli::output::write_text;

// The arguments of `inrs convex-domain`. Not a doc comment: clap would take it for the help, which is
// the doc of `Command::ConvexDomain`.
#[derive(Args, Debug)]
pub(crate) struct ConvexDomainArgs {
    /// The curve: a JSON domain file (curve --curve-index is used) or one curve object
    /// `{"degree", "control_points", "knots"?, "weights"?}` with [x, y] or [x, y, z] points.
    #[arg(long)]
    curve: PathBuf,
    /// Which curve of a domain file.
    #[arg(long, default_value_t = 0, value_parser = parse_free_index, allow_negative_numbers = true)]
    curve_index: usize,
    /// Index of the free control point (0-based).
    #[arg(long, value_parser = parse_free_index, allow_negative_numbers = true)]
    free_index: usize,
    /// The box: xmin,xmax,ymin,ymax (plane) or xmin,xmax,ymin,ymax,zmin,zmax (space);
    /// |coordinates| <= 1e100. Write it as --box=-1,1,-1,1.
    #[arg(
        long = "box",
        required = true,
        allow_hyphen_values = true,
        value_delimiter = ','
    )]
    bbox: Vec<f64>,
    /// The sign to keep.
    #[arg(long, value_enum, default_value_t = SignArg::Auto)]
    sign: SignArg,
    /// Stop when the relative area (volume) growth is at most this (>= 0).
    #[arg(long, default_value = limits::DEFAULT_CONVEX_TOL, value_parser = parse_tolerance, allow_negative_numbers = true)]
    tol: f64,
    /// The last refinement level tried (0 to 20).
    #[arg(long, default_value_t = 10, value_parser = parse_level, allow_negative_numbers = true)]
    max_level: u32,
    /// Write an SVG of the nested polygons, the outer bound and the curve (plane only).
    #[arg(long)]
    svg: Option<PathBuf>,
}

impl ConvexDomainArgs {
    pub(crate) fn run(self) -> Result<(), CliError> {
        let in_file = |e: inrs::convex::ConvexError| format!("{}: {e}", self.curve.display());
        let curve = inrs::convex::load_curve(&self.curve, self.curve_index).map_err(in_file)?;
        let bbox = BoundingBox3::from_ranges(&self.bbox).map_err(|e| e.to_string())?;
        let h = curve.numerator(self.free_index).map_err(in_file)?;
        let sign = self.sign_to_keep(&curve, &h);
        let options = ConvexDomainOptions::DEFAULT
            .with_sign(sign)
            .with_relative_tolerance(self.tol)
            .with_max_level(self.max_level);
        let k = inrs::convex::approximate(&h, &bbox, &options).map_err(|e| e.to_string())?;
        if let Some(out) = &self.svg {
            write_text(Some(out), &self.figure(&curve, &k)?)?;
        }
        write_text(None, &report(&curve, &h, sign, self.free_index, &k))
    }

    /// The sign asked for, or with `auto` the sign of the given curve's numerator at the middle
    /// of its first piece.
    fn sign_to_keep(&self, curve: &FreeCurve, h: &SignNumerator) -> Sign {
        match self.sign {
            SignArg::Positive => Sign::Positive,
            SignArg::Negative => Sign::Negative,
            SignArg::Auto => curve.own_sign(self.free_index, h),
        }
    }

    /// The SVG figure (planar domains only).
    fn figure(&self, curve: &FreeCurve, k: &ConvexDomain) -> Result<String, CliError> {
        let planar = match curve {
            FreeCurve::Planar(c) => Some(c),
            FreeCurve::Space(_) => None,
        };
        match (&k.outer, planar) {
            (Region::Polygon(_), Some(c)) => inrs::convex::to_svg(k, Some(c), self.free_index),
            _ => None,
        }
        .ok_or_else(|| CliError::Message("--svg draws planar domains only".into()))
    }
}

/// The table printed: one line per level, then the outer bound and the outcome.
fn report(
    curve: &FreeCurve,
    h: &SignNumerator,
    sign: Sign,
    free: usize,
    k: &ConvexDomain,
) -> String {
    let space = curve.dimension() == 3;
    let (what, measure, invariant) = if space {
        ("faces", "volume", "torsion")
    } else {
        ("vertices", "area", "curvature")
    };
    let count = |r: &Region| {
        if space {
            r.face_count()
        } else {
            r.vertex_count()
        }
    };
    let mut text = String::new();
    let _ = writeln!(
        text,
        "{invariant} sign {sign:?}, free control point {free}, numerator degree {} on {} piece(s)",
        h.degree(),
        h.piece_count()
    );
    let _ = writeln!(
        text,
        "level  inequalities  {what:>8}  {measure:>14}  {:>12}  {:>12}",
        "abs.error", "rel.error"
    );
    let opt = |v: Option<f64>| v.map_or("-".to_string(), |x| format!("{x:.5e}"));
    for l in &k.levels {
        let _ = writeln!(
            text,
            "{:>5}  {:>12}  {:>8}  {:>14.8e}  {:>12}  {:>12}",
            l.level,
            l.inequalities,
            count(&l.region),
            l.region.measure(),
            opt(l.abs_error),
            opt(l.rel_error)
        );
    }
    let _ = writeln!(
        text,
        "outer bound ({} sampled parameters per piece): {measure} {:.8e}, {} {what}",
        ConvexDomainOptions::default().outer_samples,
        k.outer.measure(),
        count(&k.outer)
    );
    let _ = writeln!(text, "outcome: {:?}", k.outcome);
    text
}
