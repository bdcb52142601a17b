//! `part.step#face:K`, `part.step#solid:K`: a CAD file and, optionally, which of its faces or
//! solids.

use std::str::FromStr;

use crate::IoError;

/// What a CAD domain specification selects after `#`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CadSelection {
    /// `#face:K`: face `K` (from 0, `OpenCASCADE`'s face order).
    Face(usize),
    /// `#solid:K`: solid `K` (from 0, `OpenCASCADE`'s solid order).
    Solid(usize),
}

impl FromStr for CadSelection {
    type Err = IoError;

    /// Parses `face:K` or `solid:K` (K from 0).
    fn from_str(s: &str) -> Result<Self, IoError> {
        let number = |rest: &str| rest.parse::<usize>().ok();
        if let Some(k) = s.strip_prefix("face:").and_then(number) {
            return Ok(Self::Face(k));
        }
        if let Some(k) = s.strip_prefix("solid:").and_then(number) {
            return Ok(Self::Solid(k));
        }
        Err(IoError::Cad {
            format: "CAD",
            message: format!("bad selection #{s}: write #face:K or #solid:K with K from 0"),
        })
    }
}

/// For a STEP or IGES domain specification (`part.step`, `part.igs#face:3`,
/// `part.stp#solid:0`, any case of the extensions `.step`, `.stp`, `.igs`, `.iges`): the file's
/// path and the selection, if a `#...` follows. `None` for other files; `Some(Err)` for a bad
/// selection.
pub fn split_cad_spec(spec: &str) -> Option<(&str, Option<Result<CadSelection, IoError>>)> {
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
    fn specs_split_into_the_file_and_the_selection() {
        let (file, face) = split_cad_spec("dir/Part.STEP#face:12").unwrap();
        assert_eq!(file, "dir/Part.STEP");
        assert_eq!(face.unwrap().unwrap(), CadSelection::Face(12));
        let (_, solid) = split_cad_spec("p.stp#solid:0").unwrap();
        assert_eq!(solid.unwrap().unwrap(), CadSelection::Solid(0));
        assert!(matches!(split_cad_spec("a.igs"), Some(("a.igs", None))));
        assert!(matches!(
            split_cad_spec("a.iges#face:x"),
            Some((_, Some(Err(_))))
        ));
        let e = split_cad_spec("a.step#shell:1")
            .unwrap()
            .1
            .unwrap()
            .unwrap_err();
        assert_eq!(
            e.to_string(),
            "CAD: bad selection #shell:1: write #face:K or #solid:K with K from 0"
        );
        assert!(split_cad_spec("a.json").is_none());
        assert!(split_cad_spec("steps.json").is_none());
    }
}
