//! `inrs integrate`: the integral of a formula over a domain by a positive interior cubature
//! rule.

use clap::Args;

use crate::args::{DomainArg, FUNCTION_HELP, FillRuleArg};
use crate::cli::error::CliError;
use crate::cli::limits::{self, parse_cubature_degree};
use crate::cli::output::Output;
use crate::commands::cubature::{build_rule, summarize};
use crate::stream::write_f64;
use inrs::io::formula::Formula;

/// The degree of `inrs integrate` when `--degree` is not given.
const DEFAULT_DEGREE: usize = 20;

/// The integral of a formula over a domain; prints it on standard output (shortest round-trip
/// form).
///
/// The sum `sum_i w_i f(x_i)` over the rule `inrs cubature --degree n` writes: exact (up to
/// the residual printed on standard error) when f is a polynomial of degree <= n, and as close
/// as f is to such a polynomial otherwise (for a smooth f the error falls fast with n). f is
/// evaluated only at the nodes, all strictly inside the domain; a value there that is not
/// finite (a division by zero, the square root of a negative number) is an error naming the
/// node.
#[derive(Args, Debug)]
#[command(after_help = limits::AFTER_HELP)]
pub(crate) struct IntegrateArgs {
    #[command(flatten)]
    domain: DomainArg,
    #[arg(long, help = FUNCTION_HELP, allow_hyphen_values = true)]
    function: String,
    /// The degree of exactness of the rule, 0 to 40.
    #[arg(long, default_value_t = DEFAULT_DEGREE, value_parser = parse_cubature_degree, allow_negative_numbers = true)]
    degree: usize,
    /// Which winding numbers are inside (as `inrs cubature --fill-rule`: loops that cross are
    /// refused).
    #[arg(long, value_enum, default_value_t = FillRuleArg::EvenOdd)]
    fill_rule: FillRuleArg,
}

impl IntegrateArgs {
    pub(crate) fn run(self) -> Result<(), CliError> {
        let f = Formula::parse(&self.function).map_err(|e| CliError::Message(e.to_string()))?;
        let (rule, seconds) = build_rule(&self.domain, self.degree, self.fill_rule.into())?;
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
