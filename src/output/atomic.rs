//! Files appear complete or not at all: every output is written to a temporary file in its
//! target directory and renamed into place, so a reader never sees a half-written file; the
//! temporary file gets the permissions an ordinary new file would.
//!
//! The files are not synced to disk (`fsync`) before the rename, and a file of an earlier run
//! is removed just before the new one is renamed to its name ([`persist`]) rather than
//! replaced by the rename. Both are wall time a user's run waited for and nothing a reader
//! sees: the rename is what makes a file appear whole, and a process that dies (Ctrl-C, a
//! kill, a panic) leaves its writes in the page cache, so the files stay whole and
//! `summary.json` (removed when a run starts, written last) still means "every file of the run
//! is complete". Measured on this project's ext4 machine (`strace -f -c -w`, five runs of the
//! paper case's `pounding run` with pictures into a directory holding the previous run's
//! files, load ~7; README "Speed"): blocked in fsync + rename + unlink 30–50 ms a run with the
//! eight `fsync`s (a journal commit each), 24–31 ms without them (ext4 flushes a new file
//! whose rename replaces a file, `auto_da_alloc`), 6–9 ms removing the old file first. What
//! this gives up is only a power loss's or a kernel crash's: files of the interrupted run may
//! then be empty, beside no `summary.json` or an empty one. The sweep journal, which a resumed
//! sweep reads back, still syncs its rows.

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

/// Write `bytes` to `path` atomically (temporary file in the same directory, then [`persist`]).
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
    persist(tmp, path).map_err(io)
}

/// Rename the complete temporary file `tmp` to `path`, removing a file already there first
/// (see the module: a rename that replaces a file waits for the new file's data on ext4).
/// In between, a reader finds no file at `path`, never a partial one.
pub fn persist(tmp: tempfile::NamedTempFile, path: &Path) -> std::io::Result<()> {
    // (an error other than "not there", e.g. a directory at `path`, is the rename's to report)
    let _ = std::fs::remove_file(path);
    tmp.persist(path).map(drop).map_err(|e| e.error)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A file already at the path is replaced by the new content and no temporary file is
    /// left; a directory at the path is an error that leaves the directory (and its content)
    /// as it was, with no temporary file beside it.
    #[test]
    fn persist_replaces_a_file_and_refuses_a_directory() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.csv");
        std::fs::write(&path, "old run, longer than the new one\n").unwrap();
        write_atomic(&path, b"new\n").unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"new\n");
        let names = |d: &Path| {
            let mut v: Vec<_> = std::fs::read_dir(d)
                .unwrap()
                .map(|e| e.unwrap().file_name().into_string().unwrap())
                .collect();
            v.sort();
            v
        };
        assert_eq!(names(dir.path()), ["out.csv"]);

        let sub = dir.path().join("taken");
        std::fs::create_dir(&sub).unwrap();
        std::fs::write(sub.join("inside"), "kept").unwrap();
        assert!(write_atomic(&sub, b"x").is_err());
        assert_eq!(std::fs::read(sub.join("inside")).unwrap(), b"kept");
        assert_eq!(names(dir.path()), ["out.csv", "taken"]);
    }
}
