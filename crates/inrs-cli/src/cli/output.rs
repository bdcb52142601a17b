//! Where a command writes: a file replaced atomically, or standard output.

use std::fs::File;
use std::io::{BufWriter, ErrorKind, Write};
use std::path::{Path, PathBuf};

use crate::cli::error::CliError;

/// An output stream. A file is written under a temporary name in the same directory and
/// renamed over the target by [`Output::finish`]; if the command fails (or panics) first, the
/// temporary file is removed, so a failed run never leaves a partial or truncated output.
pub(crate) struct Output {
    sink: BufWriter<Box<dyn Write>>,
    file: Option<(PathBuf, PathBuf)>,
}

impl Output {
    /// Standard output, or a new temporary file next to `path`.
    pub(crate) fn create(path: Option<&Path>) -> Result<Self, CliError> {
        match path {
            None => Ok(Self {
                sink: BufWriter::with_capacity(1 << 16, Box::new(std::io::stdout().lock())),
                file: None,
            }),
            Some(target) => {
                let name = target
                    .file_name()
                    .ok_or_else(|| format!("{}: not a file name", target.display()))?;
                let mut tmp_name = std::ffi::OsString::from(".");
                tmp_name.push(name);
                tmp_name.push(format!(".inrs-{}.tmp", std::process::id()));
                let tmp = target.with_file_name(tmp_name);
                let f = File::create(&tmp).map_err(|e| format!("{}: {e}", target.display()))?;
                Ok(Self {
                    sink: BufWriter::with_capacity(1 << 16, Box::new(f)),
                    file: Some((tmp, target.to_path_buf())),
                })
            }
        }
    }

    /// What a write error means here.
    fn failure(&self, e: std::io::Error) -> CliError {
        match &self.file {
            None if e.kind() == ErrorKind::BrokenPipe => CliError::ClosedPipe,
            None => CliError::Message(format!("standard output: {e}")),
            Some((_, target)) => CliError::Message(format!("{}: {e}", target.display())),
        }
    }

    /// Writes `text`.
    pub(crate) fn write_str(&mut self, text: &str) -> Result<(), CliError> {
        self.sink
            .write_all(text.as_bytes())
            .map_err(|e| self.failure(e))
    }

    /// Writes formatted text.
    pub(crate) fn write_fmt(&mut self, args: std::fmt::Arguments<'_>) -> Result<(), CliError> {
        self.sink.write_fmt(args).map_err(|e| self.failure(e))
    }

    /// Flushes and, for a file, moves it into place.
    pub(crate) fn finish(mut self) -> Result<(), CliError> {
        self.sink.flush().map_err(|e| self.failure(e))?;
        if let Some((tmp, target)) = self.file.take() {
            // Close the file before renaming it.
            drop(std::mem::replace(
                &mut self.sink,
                BufWriter::new(Box::new(std::io::sink())),
            ));
            if let Err(e) = std::fs::rename(&tmp, &target) {
                let _ = std::fs::remove_file(&tmp);
                return Err(CliError::Message(format!("{}: {e}", target.display())));
            }
        }
        Ok(())
    }
}

impl Drop for Output {
    fn drop(&mut self) {
        if let Some((tmp, _)) = self.file.take() {
            let _ = std::fs::remove_file(tmp);
        }
    }
}

/// Writes `text` to `path` (atomically) or to standard output.
pub(crate) fn write_text(path: Option<&Path>, text: &str) -> Result<(), CliError> {
    let mut out = Output::create(path)?;
    out.write_str(text)?;
    out.finish()
}
