//! Files appear complete or not at all: every output is written to a temporary file in its
//! target directory and renamed into place, so a reader never sees a half-written file; the
//! temporary file gets the permissions an ordinary new file would.
//!
//! The files are not synced to disk (`fsync`) before the rename: the rename is what makes a
//! file appear whole to a reader, and a process that dies (Ctrl-C, a kill, a panic) leaves
//! its writes in the page cache, so the files stay whole and `summary.json` (written last)
//! still means "every file of the run is complete". What an `fsync` adds is only survival of
//! a power loss or a kernel crash, at the cost of a journal commit per file: 1–4 ms each on
//! this project's ext4 machine (`strace -T`), eight per `pounding run` with pictures, 10–25 ms
//! of wall time in a run whose instructions take ~40 ms — the largest serial wait of a user's
//! run (issue 25). The sweep journal, which a resumed sweep reads back, still syncs its rows.

use std::io::Write as _;
use std::path::{Path, PathBuf};

/// Why an output could not be written.
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    /// File-system error, with the path concerned.
    #[error("cannot write {path}: {source}")]
    Io {
        /// Path.
        path: PathBuf,
        /// Cause.
        source: std::io::Error,
    },
    /// Serialisation failure.
    #[error("cannot encode {path}: {message}")]
    Encode {
        /// Path.
        path: PathBuf,
        /// Cause.
        message: String,
    },
}

/// A temporary file in `dir` named `<prefix>XXXXXX<suffix>`, for writing and then renaming into
/// place, with the permissions an ordinary new file would get (tempfile's default is
/// owner-only, which the rename would carry over).
pub fn temp_file(
    dir: &Path,
    prefix: impl AsRef<std::ffi::OsStr>,
    suffix: &str,
) -> std::io::Result<tempfile::NamedTempFile> {
    let mut b = tempfile::Builder::new();
    b.prefix(prefix.as_ref()).suffix(suffix);
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        b.permissions(std::fs::Permissions::from_mode(0o666));
    }
    b.tempfile_in(dir)
}

/// Write `bytes` to `path` atomically (temporary file in the same directory, then rename).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), OutputError> {
    let io = |source| OutputError::Io {
        path: path.to_path_buf(),
        source,
    };
    let dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let mut tmp = temp_file(dir, ".pounding-", ".tmp").map_err(io)?;
    tmp.write_all(bytes).map_err(io)?;
    tmp.persist(path).map_err(|e| io(e.error))?;
    Ok(())
}
