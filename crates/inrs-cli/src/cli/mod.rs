//! The command-line tool's plumbing: outputs and option limits.

pub(crate) mod limits;
pub(crate) mod output;
