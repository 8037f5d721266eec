//! Reading the text files a user names (scenarios, sweeps, spectrum tables) without being
//! stalled or flooded by a wrong path: only regular files are opened (opening a FIFO blocks
//! until a writer comes; a device may never end), and only up to a size limit.

use std::io::{Error, ErrorKind, Read};
use std::path::Path;

/// Largest scenario, sweep or spectrum-table file read, bytes.
pub const MAX_TEXT_BYTES: u64 = 64 << 20;

/// The text of `path` if it is a regular file of at most `limit` bytes; otherwise an error
/// that says what the path is instead, or how large it is.
pub fn read_text(path: &Path, limit: u64) -> std::io::Result<String> {
    let meta = std::fs::metadata(path)?;
    if !meta.is_file() {
        let what = if meta.is_dir() {
            "a directory"
        } else {
            "not a regular file (a FIFO, a device or a socket)"
        };
        return Err(Error::new(ErrorKind::InvalidInput, format!("it is {what}")));
    }
    if meta.len() > limit {
        return Err(Error::new(
            ErrorKind::InvalidInput,
            format!("it is {} bytes, more than the {limit} allowed", meta.len()),
        ));
    }
    let mut text = String::new();
    std::fs::File::open(path)?
        .take(limit + 1)
        .read_to_string(&mut text)?;
    if text.len() as u64 > limit {
        return Err(Error::new(
            ErrorKind::InvalidInput,
            format!("it grew past {limit} bytes while it was read"),
        ));
    }
    Ok(text)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A directory, a FIFO and a file over the limit are refused with what they are; a FIFO
    /// without a writer is refused at once instead of blocking.
    #[test]
    fn only_regular_files_within_the_limit() {
        let dir = std::env::temp_dir().join(format!("pounding-input-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let e = read_text(&dir, 10).unwrap_err().to_string();
        assert!(e.contains("directory"), "{e}");
        let big = dir.join("big.txt");
        std::fs::write(&big, "0123456789abc").unwrap();
        let e = read_text(&big, 10).unwrap_err().to_string();
        assert!(e.contains("13 bytes"), "{e}");
        assert_eq!(read_text(&big, 13).unwrap(), "0123456789abc");
        #[cfg(unix)]
        {
            let fifo = dir.join("fifo");
            let c = std::ffi::CString::new(fifo.to_str().unwrap()).unwrap();
            // SAFETY: a valid NUL-terminated path; mkfifo only creates a file system entry.
            let made = unsafe { libc::mkfifo(c.as_ptr(), 0o600) } == 0;
            if made {
                let e = read_text(&fifo, 10).unwrap_err().to_string();
                assert!(e.contains("FIFO"), "{e}");
                let r = crate::model::ground_motion::record::Record::read(
                    &fifo,
                    &crate::model::ground_motion::RecordOptions::default(),
                );
                let e = r.unwrap_err().to_string();
                assert!(e.contains("FIFO"), "{e}");
            }
        }
        std::fs::remove_dir_all(&dir).ok();
    }
}
