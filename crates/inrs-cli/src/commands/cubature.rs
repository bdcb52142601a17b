//! `inrs cubature`: a positive interior cubature rule of a domain, as CSV `x,y,w`.

use std::path::PathBuf;
use std::time::Instant;

use clap::Args;
use inrs::contain::FillRule;
use inrs::cubature::{CubatureOptions, CubatureRule};

use crate::args::{DomainArg, FillRuleArg};
use crate::cli::error::CliError;
use crate::cli::limits::{self, parse_cubature_degree};
use crate::cli::output::Output;
use crate::stream::write_f64;

// The arguments of `inrs cubature`. Not a doc comment: clap would take it for the help, which is
// the doc of `Command::Cubature`.
#[derive(Args, Debug)]
#[command(after_help = limits::AFTER_HELP)]
pub(crate) struct CubatureArgs {
    #[command(flatten)]
    domain: DomainArg,
    /// The degree of exactness n, 0 to 40.
    #[arg(long, value_parser = parse_cubature_degree, allow_negative_numbers = true)]
    degree: usize,
    /// Write the CSV here instead of standard output.
    #[arg(long)]
    output: Option<PathBuf>,
    /// Which winding numbers are inside. Under either rule the loops must not cross each other
    /// or themselves (their fill is then decided by their nesting): a domain whose loops cross
    /// is refused, naming the crossing (`classify` takes any loops).
    #[arg(long, value_enum, default_value_t = FillRuleArg::EvenOdd)]
    fill_rule: FillRuleArg,
}

impl CubatureArgs {
    pub(crate) fn run(self) -> Result<(), CliError> {
        let (rule, seconds) = build_rule(&self.domain, self.degree, self.fill_rule.into())?;
        let mut text = Vec::with_capacity(rule.nodes().len() * 64 + 8);
        text.extend_from_slice(b"x,y,w\n");
        for (p, &w) in rule.nodes().iter().zip(rule.weights()) {
            for (v, end) in [(p.x, b','), (p.y, b','), (w, b'\n')] {
                write_f64(v, &mut text);
                text.push(end);
            }
        }
        let mut out = Output::create(self.output.as_deref())?;
        out.write_bytes(&text)?;
        out.finish()?;
        summarize(&rule, seconds);
        Ok(())
    }
}

/// The rule of degree `degree` on the set the domain of `domain` fills under `fill_rule` (one
/// library call, [`CubatureRule::with_options`]) and the seconds it took; the library's errors
/// prefixed with the domain's file name.
pub(crate) fn build_rule(
    domain: &DomainArg,
    degree: usize,
    fill_rule: FillRule,
) -> Result<(CubatureRule, f64), CliError> {
    let d = domain.load()?;
    let start = Instant::now();
    let options = CubatureOptions::new(degree).with_fill_rule(fill_rule);
    let rule = CubatureRule::with_options(&d, options).map_err(|e| domain.error(e))?;
    Ok((rule, start.elapsed().as_secs_f64()))
}

/// The summary line on standard error, once the command has succeeded (an error stays the
/// only line): nodes, degree, residual, candidates and time.
pub(crate) fn summarize(rule: &CubatureRule, seconds: f64) {
    eprintln!(
        "degree {}, {} nodes (at most {}), residual {:.1e}, {} candidates, {seconds:.3} s",
        rule.degree(),
        rule.nodes().len(),
        inrs::cubature::dim_polynomials(rule.degree()),
        rule.residual(),
        rule.candidates(),
    );
}
