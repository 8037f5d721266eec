//! A spool of rows of numbers: written in binary (8 bytes a number) to an anonymous temporary
//! file while the run with contact goes on, then read back row by row while the run without
//! contact completes each line — so that a CSV with both runs side by side is streamed with one
//! row in memory (`history.csv`, `floors.csv`).

use std::io::{BufReader, BufWriter, Read as _, Seek as _, Write as _};
use std::path::Path;

enum State {
    Writing(BufWriter<std::fs::File>),
    Reading(BufReader<std::fs::File>),
    Failed,
}

/// Rows of `width` numbers, first all written, then all read (see the module).
pub struct RowSpool {
    state: State,
    width: usize,
    record: Vec<u8>,
    error: Option<std::io::Error>,
}

impl std::fmt::Debug for RowSpool {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("RowSpool")
            .field("width", &self.width)
            .finish_non_exhaustive()
    }
}

impl RowSpool {
    /// A spool of rows of `width` numbers in an anonymous temporary file in `dir`.
    pub fn new(dir: &Path, width: usize) -> std::io::Result<RowSpool> {
        let f = tempfile::tempfile_in(dir)?;
        Ok(RowSpool {
            state: State::Writing(BufWriter::with_capacity(1 << 16, f)),
            width,
            record: Vec::with_capacity(8 * width),
            error: None,
        })
    }

    /// Append a row (its first `width` numbers; missing ones as NaN). Ignored once reading.
    pub fn push(&mut self, row: impl IntoIterator<Item = f64>) {
        let State::Writing(out) = &mut self.state else {
            return;
        };
        self.record.clear();
        let mut it = row.into_iter();
        for _ in 0..self.width {
            let v = it.next().unwrap_or(f64::NAN);
            self.record.extend_from_slice(&v.to_le_bytes());
        }
        if let Err(e) = out.write_all(&self.record) {
            self.state = State::Failed;
            self.fail(e);
        }
    }

    /// Whether rows are still being written.
    pub fn writing(&self) -> bool {
        matches!(self.state, State::Writing(_))
    }

    /// Switch from writing to reading (does nothing when already reading).
    pub fn rewind(&mut self) {
        if !self.writing() {
            return;
        }
        if let State::Writing(w) = std::mem::replace(&mut self.state, State::Failed) {
            match w
                .into_inner()
                .map_err(|e| e.into_error())
                .and_then(|mut f| {
                    f.rewind()?;
                    Ok(f)
                }) {
                Ok(f) => self.state = State::Reading(BufReader::with_capacity(1 << 16, f)),
                Err(e) => self.fail(e),
            }
        }
    }

    /// The next row into `out` (`width` numbers); false at the end (or after an error).
    pub fn next(&mut self, out: &mut [f64]) -> bool {
        let State::Reading(r) = &mut self.state else {
            return false;
        };
        self.record.resize(8 * self.width, 0);
        match r.read_exact(&mut self.record) {
            Ok(()) => {}
            Err(e) if e.kind() == std::io::ErrorKind::UnexpectedEof => return false,
            Err(e) => {
                self.fail(e);
                return false;
            }
        }
        for (o, c) in out.iter_mut().zip(self.record.chunks_exact(8)) {
            *o = f64::from_le_bytes(c.try_into().unwrap_or([0; 8]));
        }
        true
    }

    fn fail(&mut self, e: std::io::Error) {
        if self.error.is_none() {
            self.error = Some(e);
        }
    }

    /// The first I/O error met, if any (taken).
    pub fn take_error(&mut self) -> Option<std::io::Error> {
        self.error.take()
    }
}
