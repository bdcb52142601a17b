//! The sizes meshing refuses beyond: vertices of a curved triangulation, Bezier pieces of a
//! boundary.

use rs_spline::Domain;

use crate::MeshError;

/// The most vertices a curved triangulation is built with (about 1 GB of triangulation data).
pub const MAX_MESH_VERTICES: usize = 2_000_000;

/// The most Bezier pieces a boundary to be meshed or sampled by lines may have: every piece
/// gets an arc-length table and its start is a vertex, so the work grows with the pieces;
/// the limit keeps it to seconds, refusing a boundary written as one huge path (an SVG path
/// of 10^6 commands) before any work.
pub const MAX_MESH_PIECES: usize = 10_000;

/// Refuses, before any work, a boundary of more than [`MAX_MESH_PIECES`] Bezier pieces.
///
/// # Errors
/// [`MeshError::TooManyPieces`].
pub fn check_boundary_pieces(domain: &Domain) -> Result<(), MeshError> {
    let pieces: usize = domain
        .curves()
        .iter()
        .map(|c| c.knots().interior_breaks().len() + 1)
        .sum();
    if pieces > MAX_MESH_PIECES {
        return Err(MeshError::TooManyPieces {
            pieces,
            limit: MAX_MESH_PIECES,
        });
    }
    Ok(())
}
