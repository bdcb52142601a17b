//! IGES files: the parameter-space trimming loops of trimmed (144) and bounded (143) surfaces.

use super::CadModel;
use crate::IoError;

/// Reads the faces of an IGES file's bytes.
///
/// # Errors
/// [`IoError::Cad`] for a file that is not IGES or whose sections are broken.
pub fn read_iges(_bytes: &[u8]) -> Result<CadModel, IoError> {
    Err(IoError::Cad {
        format: "IGES",
        message: "not implemented yet".into(),
    })
}
