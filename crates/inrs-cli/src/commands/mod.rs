//! One module per subcommand: its arguments (`#[derive(Args)]`) and its `run`.

pub(crate) mod classify;
pub(crate) mod classify_many;
pub(crate) mod classify_solid;
pub(crate) mod convert;
pub(crate) mod convex_domain;
pub(crate) mod cubature;
pub(crate) mod eval;
pub(crate) mod fit;
pub(crate) mod fractions;
pub(crate) mod info;
pub(crate) mod integrate;
pub(crate) mod mesh;
pub(crate) mod properties;
pub(crate) mod sample;
pub(crate) mod winding;
