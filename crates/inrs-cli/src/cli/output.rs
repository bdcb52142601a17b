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
    Stdout(BufWriter<std::io::Stdout>),
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
                sink: Sink::Stdout(BufWriter::with_capacity(1 << 16, std::io::stdout())),
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

    /// Writes `values` as little-endian float64 (`.npy` data): on a little-endian machine their
    /// own bytes, without a copy; elsewhere through `scratch`.
    pub(crate) fn write_f64s(
        &mut self,
        values: &[f64],
        scratch: &mut Vec<u8>,
    ) -> Result<(), CliError> {
        if cfg!(target_endian = "little") {
            return self.write_bytes(bytemuck::cast_slice(values));
        }
        scratch.clear();
        scratch.extend(values.iter().flat_map(|v| v.to_le_bytes()));
        self.write_bytes(scratch)
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

    /// Flushes and, for a file, moves it into place (see [`commit`]).
    pub(crate) fn finish(mut self) -> Result<(), CliError> {
        self.sink.flush().map_err(|e| self.failure(e))?;
        if let Some((tmp, target)) = self.file.take() {
            // Close the file before renaming it.
            drop(std::mem::replace(&mut self.sink, Sink::Closed));
            commit(&tmp, &target)
                .map_err(|e| CliError::Message(format!("{}: {e}", target.display())))?;
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

/// Moves the finished temporary file `tmp` to `target`. An existing `target` is first moved
/// aside under a temporary name and removed once the new file is in place (or moved back if
/// that fails, and `tmp` removed): renaming over it would make ext4 write the new file out to
/// disk at once (its `auto_da_alloc` safeguard for replace-by-rename), a synchronous write the
/// caller would wait for. Like a shell redirection, the output is left to the page cache, not
/// synced.
fn commit(tmp: &Path, target: &Path) -> std::io::Result<()> {
    let mut aside = tmp.as_os_str().to_owned();
    aside.push(".old");
    let aside = PathBuf::from(aside);
    let moved =
        std::fs::symlink_metadata(target).is_ok() && std::fs::rename(target, &aside).is_ok();
    match std::fs::rename(tmp, target) {
        Ok(()) => {
            if moved {
                let _ = std::fs::remove_file(&aside);
            }
            Ok(())
        }
        Err(e) => {
            if moved {
                let _ = std::fs::rename(&aside, target);
            }
            let _ = std::fs::remove_file(tmp);
            Err(e)
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

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch_dir(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("inrs-output-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    /// The directory's entries, sorted.
    fn entries(dir: &Path) -> Vec<String> {
        let mut v: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }

    #[test]
    fn a_finished_output_replaces_the_old_file_and_leaves_nothing_else() {
        let dir = scratch_dir("replace");
        let target = dir.join("out.csv");
        std::fs::write(&target, "old\n").unwrap();
        let mut out = Output::create(Some(&target)).unwrap();
        out.write_str("new\n").unwrap();
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "old\n");
        out.finish().unwrap();
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "new\n");
        assert_eq!(entries(&dir), ["out.csv"]);
        // And when there was no old file.
        let fresh = dir.join("fresh.csv");
        write_text(Some(&fresh), "x\n").unwrap();
        assert_eq!(std::fs::read_to_string(&fresh).unwrap(), "x\n");
        assert_eq!(entries(&dir), ["fresh.csv", "out.csv"]);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_failed_commit_keeps_the_old_file() {
        let dir = scratch_dir("failed");
        let target = dir.join("out.csv");
        std::fs::write(&target, "old\n").unwrap();
        // The new file has vanished before the commit: the rename fails.
        let tmp = dir.join(".out.csv.tmp");
        let err = commit(&tmp, &target).unwrap_err();
        assert_eq!(err.kind(), std::io::ErrorKind::NotFound);
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "old\n");
        assert_eq!(entries(&dir), ["out.csv"]);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_dropped_output_leaves_the_old_file() {
        let dir = scratch_dir("dropped");
        let target = dir.join("out.npy");
        std::fs::write(&target, "old").unwrap();
        let mut out = Output::create(Some(&target)).unwrap();
        out.write_bytes(b"partial").unwrap();
        drop(out);
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "old");
        assert_eq!(entries(&dir), ["out.npy"]);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
