//! `inrs classify`: inside, outside or boundary for every point of a points file, against one
//! domain or several ([`super::classify_many`] reads and prepares them), streamed alike.

use std::cell::OnceCell;
use std::path::PathBuf;

use clap::Args;
use inrs::boxes::DEFAULT_SUBDIVISIONS;
use inrs::{ContainOptions, Containment, Location, NpyType, engines_many};

use crate::args::{DomainsArg, FillRuleArg, MethodArg};
use crate::cli::error::CliError;
use crate::cli::limits::{self, parse_subdivisions, parse_tolerance};
use crate::stream::{Column, PointsInput, stream_points, stream_prepared};

use super::{classify_many, classify_solid};

// The arguments of `inrs classify`. Not a doc comment: clap would take it for the help, which is
// the doc of `Command::Classify`.
#[derive(Args, Debug)]
#[command(after_help = limits::AFTER_HELP)]
pub(crate) struct ClassifyArgs {
    #[command(flatten)]
    pub(super) domains: DomainsArg,
    /// The points file: CSV `x,y` per line (extra columns ignored; optional header; `#`
    /// comments), or `.npy` (float64 or float32, shape (N, 2)); streamed: any number of points.
    #[arg(long)]
    pub(super) points: PathBuf,
    /// The algorithm; all agree on closed domains.
    #[arg(long, value_enum, default_value_t = MethodArg::Fast)]
    pub(super) method: MethodArg,
    /// Which winding numbers are inside; every method honours it, on any loops (nested,
    /// overlapping, crossing themselves).
    #[arg(long, value_enum, default_value_t = FillRuleArg::EvenOdd)]
    pub(super) fill_rule: FillRuleArg,
    /// Write here instead of standard output: CSV, or `.npy` (int8: 0 outside, 1 inside,
    /// 2 boundary; shape (points, domains) with several domains) when the name ends in `.npy`.
    #[arg(long)]
    pub(super) output: Option<PathBuf>,
    /// Boundary tolerance relative to the bounding-box diagonal (>= 0, see below).
    #[arg(long, default_value = limits::DEFAULT_TOL, value_parser = parse_tolerance, allow_negative_numbers = true)]
    pub(super) tol: f64,
    /// The most sub-boxes per monotone piece (the paper's box refinement), 1 to 4096; a piece
    /// small against the domain gets fewer (about 64 boxes per diagonal of the domain), and a
    /// domain has at most about 131072 boxes.
    #[arg(long, default_value_t = DEFAULT_SUBDIVISIONS, value_parser = parse_subdivisions, allow_negative_numbers = true)]
    pub(super) subdivisions: usize,
    /// With several domains: leave out the columns of the domains (faces) that cannot be read
    /// or prepared (an open boundary, ...), naming each on standard error, instead of failing.
    #[arg(long)]
    pub(super) skip_unreadable: bool,
}

/// The location columns: CSV labels, `.npy` int8 codes (0 outside, 1 inside, 2 boundary, as
/// the Python package returns them). One column `location` (a 1-D `.npy` array), or one per
/// domain, headed by its label (`.npy` of shape (points, domains), row by row).
struct Locations {
    header: String,
    per_domain: bool,
}

impl Locations {
    /// The one column of a single domain.
    fn one() -> Self {
        Self {
            header: "x,y,location".into(),
            per_domain: false,
        }
    }

    /// A column per domain, headed by `labels`.
    fn per_domain<'a>(labels: impl IntoIterator<Item = &'a str>) -> Self {
        let mut header = String::from("x,y");
        for l in labels {
            header.push(',');
            header.push_str(&csv_field(l));
        }
        Self {
            header,
            per_domain: true,
        }
    }
}

impl Column<Location> for Locations {
    fn header(&self) -> &str {
        &self.header
    }
    fn initial(&self) -> Location {
        Location::Outside
    }
    #[inline]
    fn csv(&self, value: Location, out: &mut Vec<u8>) {
        out.extend_from_slice(value.as_str().as_bytes());
    }
    fn npy_type(&self) -> NpyType {
        NpyType::I8
    }
    fn npy(&self, values: &[Location], out: &mut Vec<u8>) {
        // Into bytes already there: the loop is a copy (the codes are the discriminants).
        let start = out.len();
        out.resize(start + values.len(), 0);
        for (b, l) in out[start..].iter_mut().zip(values) {
            *b = l.code() as u8;
        }
    }
    fn npy_shape(&self, points: usize, queries: usize) -> Vec<usize> {
        if self.per_domain {
            vec![points, queries]
        } else {
            vec![points]
        }
    }
}

/// `s` as a CSV field: quoted (quotes doubled) when it holds a comma, a quote or a line break.
fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

impl ClassifyArgs {
    /// Classifies the points against the domain, or against each domain (a column each): the
    /// domains are prepared first, then the points streamed through them.
    pub(crate) fn run(self) -> Result<(), CliError> {
        let options = self.options();
        let output = self.output.as_deref();
        if let [spec] = self.domains.domain.as_slice()
            && let Some((file, solid)) = classify_solid::solid_spec(&spec.to_string_lossy())
        {
            return classify_solid::run(file, solid, &self.points, output);
        }
        self.refuse_points_of_space()?;
        if let Some(domain) = self.domains.single() {
            // A domain that cannot be read is named first.
            let input =
                PointsInput::open_after_errors_of(&self.points, 1, || domain.load().map(drop))?;
            // Prepared while the workers start reading the points. (The points file is opened
            // first: a named pipe with no writer yet is waited for before a bad domain is named.)
            let (containment, engine) = (OnceCell::new(), OnceCell::new());
            let column = Locations::one();
            return stream_prepared(input, output, |points| {
                let d = domain.load()?;
                let c = Containment::new(&d, options).map_err(|e| domain.error(e))?;
                let c: &Containment = containment.get_or_init(|| c);
                // The library picks the algorithm for the whole stream's size.
                let engine = engine.get_or_init(|| [c.engine(points)]);
                Ok((&column, &engine[..]))
            });
        }
        let skip = self.skip_unreadable;
        let domains = classify_many::read(&self.domains, skip)?;
        let input = PointsInput::open(&self.points, domains.len())?;
        let (labels, prepared) = classify_many::prepare(domains, options, skip)?;
        let engines = engines_many(&prepared, input.estimated_points());
        let columns = Locations::per_domain(labels.iter().map(String::as_str));
        stream_points(input, output, &columns, &engines)
    }

    /// An error for a CSV points file whose header names a third coordinate `z`: points of
    /// space are classified against a solid (a planar domain would take their `x, y`).
    fn refuse_points_of_space(&self) -> Result<(), CliError> {
        let npy = self
            .points
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("npy"));
        if npy || !self.points.is_file() {
            return Ok(());
        }
        let header = inrs::io::points::csv_header(&self.points)
            .map_err(|e| CliError::Message(e.to_string()))?;
        if header.is_some_and(|h| h.len() >= 3 && h[2].eq_ignore_ascii_case("z")) {
            return Err(CliError::Message(format!(
                "{}: the header names x, y and z: points of space go with a solid (--domain \
                 part.step#solid:K); a planar domain takes x,y",
                self.points.display()
            )));
        }
        Ok(())
    }

    /// The options of every domain.
    fn options(&self) -> ContainOptions {
        ContainOptions::DEFAULT
            .with_relative_tolerance(self.tol)
            .with_subdivisions(self.subdivisions)
            .with_method(self.method.into())
            .with_fill_rule(self.fill_rule.into())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn labels_with_commas_or_quotes_are_quoted() {
        assert_eq!(csv_field("face:3"), "face:3");
        assert_eq!(csv_field("a,b.json"), "\"a,b.json\"");
        assert_eq!(csv_field("say \"x\".json"), "\"say \"\"x\"\".json\"");
        let columns = Locations::per_domain(["a.json", "b,c.json"]);
        assert_eq!(columns.header(), "x,y,a.json,\"b,c.json\"");
        assert_eq!(columns.npy_shape(7, 2), [7, 2]);
        assert_eq!(Locations::one().npy_shape(7, 1), [7]);
    }
}
