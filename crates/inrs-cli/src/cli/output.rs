//! Where a command writes: a file replaced atomically, or standard output.

use std::fs::File;
use std::io::{BufWriter, ErrorKind, Write};
use std::path::{Path, PathBuf};

use crate::cli::error::CliError;

/// An output stream. A file is written under a temporary name in the same directory and
/// renamed over the target by [`Output::finish`]; if the command fails (or panics) first, the
/// temporary file is removed, so a failed run never leaves a partial or truncated output.
pub(crate) struct Output {
    sink: Sink,
    /// The temporary file and the target it replaces when finished.
    file: Option<(PathBuf, PathBuf)>,
    /// The output's name in messages (`None`: standard output).
    name: Option<PathBuf>,
}

/// Where the bytes go.
enum Sink {
    Stdout(BufWriter<std::io::StdoutLock<'static>>),
    File(BufWriter<File>),
    /// After `finish` closed the file.
    Closed,
}

impl Write for Sink {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        match self {
            Sink::Stdout(w) => w.write(buf),
            Sink::File(w) => w.write(buf),
            Sink::Closed => Ok(buf.len()),
        }
    }

    fn write_all(&mut self, buf: &[u8]) -> std::io::Result<()> {
        match self {
            Sink::Stdout(w) => w.write_all(buf),
            Sink::File(w) => w.write_all(buf),
            Sink::Closed => Ok(()),
        }
    }

    fn flush(&mut self) -> std::io::Result<()> {
        match self {
            Sink::Stdout(w) => w.flush(),
            Sink::File(w) => w.flush(),
            Sink::Closed => Ok(()),
        }
    }
}

impl Output {
    /// Standard output, or a new temporary file next to `path`.
    pub(crate) fn create(path: Option<&Path>) -> Result<Self, CliError> {
        match path {
            None => Ok(Self {
                sink: Sink::Stdout(BufWriter::with_capacity(1 << 16, std::io::stdout().lock())),
                file: None,
                name: None,
            }),
            Some(target) if is_special(target) => {
                // A device or a pipe (/dev/null, /dev/stdout, a FIFO): write to it as it is;
                // renaming a temporary file over it would replace the device.
                let f = std::fs::OpenOptions::new()
                    .write(true)
                    .open(target)
                    .map_err(|e| format!("{}: {e}", target.display()))?;
                Ok(Self {
                    sink: Sink::File(BufWriter::with_capacity(1 << 16, f)),
                    file: None,
                    name: Some(target.to_path_buf()),
                })
            }
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
                    sink: Sink::File(BufWriter::with_capacity(1 << 16, f)),
                    file: Some((tmp, target.to_path_buf())),
                    name: Some(target.to_path_buf()),
                })
            }
        }
    }

    /// What a write error means here.
    fn failure(&self, e: std::io::Error) -> CliError {
        match &self.name {
            _ if e.kind() == ErrorKind::BrokenPipe => CliError::ClosedPipe,
            None => CliError::Message(format!("standard output: {e}")),
            Some(target) => CliError::Message(format!("{}: {e}", target.display())),
        }
    }

    /// Writes `text`.
    pub(crate) fn write_str(&mut self, text: &str) -> Result<(), CliError> {
        self.sink
            .write_all(text.as_bytes())
            .map_err(|e| self.failure(e))
    }

    /// Writes `bytes`.
    pub(crate) fn write_bytes(&mut self, bytes: &[u8]) -> Result<(), CliError> {
        self.sink.write_all(bytes).map_err(|e| self.failure(e))
    }

    /// Overwrites the first bytes of a file output with `bytes` (a header written before the
    /// count it holds was known); nothing for standard output.
    pub(crate) fn rewrite_start(&mut self, bytes: &[u8]) -> Result<(), CliError> {
        use std::io::{Seek, SeekFrom};
        if let Sink::File(w) = &mut self.sink {
            let result = w.flush().and_then(|()| {
                let f = w.get_mut();
                f.seek(SeekFrom::Start(0))?;
                f.write_all(bytes)?;
                f.seek(SeekFrom::End(0)).map(|_| ())
            });
            result.map_err(|e| self.failure(e))?;
        }
        Ok(())
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
            drop(std::mem::replace(&mut self.sink, Sink::Closed));
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

/// True if `path` exists and is not a regular file (or a link to one).
fn is_special(path: &Path) -> bool {
    std::fs::metadata(path).is_ok_and(|m| !m.is_file())
}

/// Writes `text` to `path` (atomically) or to standard output.
pub(crate) fn write_text(path: Option<&Path>, text: &str) -> Result<(), CliError> {
    let mut out = Output::create(path)?;
    out.write_str(text)?;
    out.finish()
}
