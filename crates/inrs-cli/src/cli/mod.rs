//! The command-line tool's plumbing: its error, outputs and option limits.

pub(crate) mod error;
pub(crate) mod limits;
pub(crate) mod output;
