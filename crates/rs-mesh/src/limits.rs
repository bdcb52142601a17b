//! The sizes sampling and meshing refuse beyond: lines and points of a sampling, vertices of a
//! curved triangulation, Bezier pieces of a boundary. Constants only, so that every module
//! can name them without depending on another.

/// The largest `ny` accepted by [`well_spaced_points`](crate::well_spaced_points).
pub const MAX_LINES: usize = 100_000;

/// The most points [`well_spaced_points`](crate::well_spaced_points) and
/// [`halton_points_in`](crate::halton_points_in) produce: `10^7` (160 MB of coordinates).
/// `well_spaced_points` refuses an `ny` whose grid over the bounding box,
/// `ny^2 * width / height` positions, exceeds four times this.
pub const MAX_SAMPLE_POINTS: usize = 10_000_000;

/// The most Halton candidates [`halton_points_in`](crate::halton_points_in) draws per point
/// asked for (the domain must fill at least `1 / 1000` of its bounding box).
pub const MAX_HALTON_TRIES_PER_POINT: usize = 1000;

/// The most vertices a curved triangulation is built with (about 1 GB of triangulation data).
pub const MAX_MESH_VERTICES: usize = 2_000_000;

/// The most Bezier pieces a boundary to be meshed or sampled by lines may have: every piece
/// gets an arc-length table and its start is a vertex, so the work grows with the pieces;
/// the limit keeps it to seconds, refusing a boundary written as one huge path (an SVG path
/// of 10^6 commands) before any work.
pub const MAX_MESH_PIECES: usize = 10_000;
