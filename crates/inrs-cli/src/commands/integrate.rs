//! `inrs integrate`: the integral of a formula over a domain by a positive interior cubature
//! rule.

use clap::{Args, ValueEnum};
use inrs::io::cad::{CadModel, CadSelection, split_cad_spec};

use crate::args::{DomainArg, FUNCTION_HELP, FillRuleArg};
use crate::cli::error::CliError;
use crate::cli::limits::{self, parse_cubature_degree};
use crate::cli::output::Output;
use crate::commands::cubature::{build_rule, summarize};
use crate::stream::write_f64;
use inrs::io::formula::Formula;

/// The degree of `inrs integrate` when `--degree` is not given.
const DEFAULT_DEGREE: usize = 20;

// The arguments of `inrs integrate`. Not a doc comment: clap would take it for the help, which is
// the doc of `Command::Integrate`.
#[derive(Args, Debug)]
#[command(after_help = limits::AFTER_HELP)]
pub(crate) struct IntegrateArgs {
    #[command(flatten)]
    domain: DomainArg,
    #[arg(long, help = FUNCTION_HELP, allow_hyphen_values = true)]
    function: String,
    /// The degree of exactness of the rule, 0 to 40 [default: 20].
    #[arg(long, value_parser = parse_cubature_degree, allow_negative_numbers = true)]
    degree: Option<usize>,
    /// Which winding numbers are inside (as `inrs cubature --fill-rule`: loops that cross are
    /// refused) [default: even-odd].
    #[arg(long, value_enum)]
    fill_rule: Option<FillRuleArg>,
    /// What to integrate over: the domain's parameters `(x, y)` (a CAD face's `(u, v)`), or,
    /// for a CAD face `part.step#face:K`, the face in space: `int f(x, y, z) dA` with the
    /// surface's area element, by adaptive Gauss-Legendre on the face's trimmed `(u, v)`
    /// domain (`--degree` and `--fill-rule` do not apply; an estimate of the error goes to
    /// standard error).
    #[arg(long, value_enum, default_value_t = Over::Parameters)]
    over: Over,
}

/// What `inrs integrate` integrates over.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum Over {
    /// The plane of the domain's coordinates.
    Parameters,
    /// A CAD face in space.
    Surface,
}

impl IntegrateArgs {
    pub(crate) fn run(self) -> Result<(), CliError> {
        if self.over == Over::Surface {
            return self.over_surface();
        }
        let f = Formula::parse(&self.function).map_err(|e| CliError::Message(e.to_string()))?;
        let degree = self.degree.unwrap_or(DEFAULT_DEGREE);
        let fill_rule = self.fill_rule.unwrap_or(FillRuleArg::EvenOdd);
        let (rule, seconds) = build_rule(&self.domain, degree, fill_rule.into())?;
        let integral = rule
            .integrate(|p| f.at(p))
            .map_err(|e| CliError::Message(format!("--function {:?}: {e}", self.function)))?;
        let mut text = Vec::with_capacity(32);
        write_f64(integral, &mut text);
        text.push(b'\n');
        let mut out = Output::create(None)?;
        out.write_bytes(&text)?;
        out.finish()?;
        summarize(&rule, seconds);
        Ok(())
    }
}

impl IntegrateArgs {
    /// `--over surface`: `int f(x, y, z) dA` over the CAD face `--domain` names, by the
    /// library's one call (`Model::surface_integral`).
    fn over_surface(self) -> Result<(), CliError> {
        if self.degree.is_some() || self.fill_rule.is_some() {
            return Err(CliError::Message(
                "--degree and --fill-rule choose the cubature rule over the parameters; they do \
                 not apply to --over surface"
                    .into(),
            ));
        }
        let spec = self.domain.domain.to_string_lossy().into_owned();
        let face = match split_cad_spec(&spec) {
            Some((file, Some(Ok(CadSelection::Face(k))))) => Some((file, k)),
            Some((_, Some(Err(e)))) => return Err(CliError::Message(format!("{spec}: {e}"))),
            _ => None,
        };
        let Some((file, k)) = face else {
            return Err(CliError::Message(format!(
                "{spec}: --over surface integrates over a face of a STEP or IGES part: give \
                 --domain part.step#face:K"
            )));
        };
        let f = Formula::parse_xyz(&self.function).map_err(|e| CliError::Message(e.to_string()))?;
        let model = CadModel::read(file).map_err(|e| CliError::Message(e.to_string()))?;
        let got = model
            .surface_integral(k, &|p| f.at_xyz(p.x, p.y, p.z))
            .map_err(|e| CliError::Message(format!("{spec}: {e}")))?;
        let mut text = Vec::with_capacity(32);
        write_f64(got.value, &mut text);
        text.push(b'\n');
        let mut out = Output::create(None)?;
        out.write_bytes(&text)?;
        out.finish()?;
        let converged = if got.converged {
            ""
        } else {
            "; NOT converged within the work limit (a singular function?)"
        };
        eprintln!(
            "over the face in space: error estimate {:.1e}{converged}",
            got.error
        );
        Ok(())
    }
}
