//! `part.step#face:K`: a CAD file and, optionally, which of its faces.

use std::str::FromStr;

use crate::IoError;

/// Which face of a CAD file a domain specification names (`#face:K`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FaceSelection(pub usize);

impl FromStr for FaceSelection {
    type Err = IoError;

    /// Parses `face:K` (K a face index, from 0).
    fn from_str(s: &str) -> Result<Self, IoError> {
        s.strip_prefix("face:")
            .and_then(|k| k.parse().ok())
            .map(Self)
            .ok_or_else(|| IoError::Cad {
                format: "CAD",
                message: format!("bad face selection #{s}: write #face:K with K from 0"),
            })
    }
}

/// For a STEP or IGES domain specification (`part.step`, `part.igs#face:3`, any case of the
/// extensions `.step`, `.stp`, `.igs`, `.iges`): the file's path and the selected face, if a
/// `#face:K` follows. `None` for other files; `Some(Err)` for a bad selection.
pub fn split_face_spec(spec: &str) -> Option<(&str, Option<Result<FaceSelection, IoError>>)> {
    let lower = spec.to_ascii_lowercase();
    for ext in [".step", ".stp", ".igs", ".iges"] {
        let with_hash = format!("{ext}#");
        if let Some(i) = lower.find(&with_hash) {
            let (file, selection) = spec.split_at(i + ext.len());
            return Some((file, Some(selection[1..].parse())));
        }
        if lower.ends_with(ext) {
            return Some((spec, None));
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn specs_split_into_the_file_and_the_face() {
        let (file, face) = split_face_spec("dir/Part.STEP#face:12").unwrap();
        assert_eq!(file, "dir/Part.STEP");
        assert_eq!(face.unwrap().unwrap(), FaceSelection(12));
        assert!(matches!(split_face_spec("a.igs"), Some(("a.igs", None))));
        assert!(matches!(
            split_face_spec("a.iges#face:x"),
            Some((_, Some(Err(_))))
        ));
        assert!(split_face_spec("a.json").is_none());
        assert!(split_face_spec("steps.json").is_none());
    }
}
