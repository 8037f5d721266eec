//! `floors.csv`: the time histories of every floor (a cantilever's stations) — displacement
//! and absolute acceleration, with and without pounding — streamed as `history.csv` is: the
//! rows of the run with contact are spooled in binary to an anonymous temporary file, and each
//! row of the run without contact completes one line. Memory holds one row; the file appears
//! under its name only when complete (temporary file, renamed by [`FloorsCsv::finish`]).

use std::fmt::Write as _;
use std::io::{BufReader, BufWriter, Read as _, Seek as _, Write as _};
use std::path::{Path, PathBuf};

/// The file's name in a run's directory.
pub const FILE_NAME: &str = "floors.csv";

enum Spool {
    Writing(BufWriter<std::fs::File>),
    Reading(BufReader<std::fs::File>),
    Failed,
}

/// A `floors.csv` being written (see the module).
pub struct FloorsCsv {
    path: PathBuf,
    csv: Option<BufWriter<tempfile::NamedTempFile>>,
    spool: Spool,
    /// Values per row of one run.
    n: usize,
    record: Vec<u8>,
    contact: Vec<f64>,
    line: String,
    error: Option<std::io::Error>,
}

impl std::fmt::Debug for FloorsCsv {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("FloorsCsv")
            .field("path", &self.path)
            .field("n", &self.n)
            .finish_non_exhaustive()
    }
}

impl FloorsCsv {
    /// Start `dir/floors.csv` with the header `t`, the `columns` (with pounding), then the same
    /// with `_free` (without).
    pub fn create(dir: &Path, columns: &[String]) -> std::io::Result<FloorsCsv> {
        let tmp = tempfile::Builder::new()
            .prefix(".pounding-floors-")
            .suffix(".tmp")
            .tempfile_in(dir)?;
        let mut csv = BufWriter::with_capacity(1 << 16, tmp);
        let mut head = String::from("t");
        for c in columns {
            let _ = write!(head, ",{c}");
        }
        for c in columns {
            let _ = write!(head, ",{c}_free");
        }
        writeln!(csv, "{head}")?;
        let spool = tempfile::tempfile_in(dir)?;
        Ok(FloorsCsv {
            path: dir.join(FILE_NAME),
            csv: Some(csv),
            spool: Spool::Writing(BufWriter::with_capacity(1 << 16, spool)),
            n: columns.len(),
            record: Vec::with_capacity(8 * (1 + columns.len())),
            contact: vec![0.0; columns.len()],
            line: String::new(),
            error: None,
        })
    }

    fn fail(&mut self, e: std::io::Error) {
        if self.error.is_none() {
            self.error = Some(e);
        }
    }

    /// A row of the run with contact.
    pub fn contact_row(&mut self, t: f64, values: &[f64]) {
        let Spool::Writing(out) = &mut self.spool else {
            return;
        };
        self.record.clear();
        for v in std::iter::once(&t).chain(values.iter().take(self.n)) {
            self.record.extend_from_slice(&v.to_le_bytes());
        }
        if let Err(e) = out.write_all(&self.record) {
            self.spool = Spool::Failed;
            self.fail(e);
        }
    }

    /// A row of the run without contact: completes the next spooled row.
    pub fn free_row(&mut self, _t: f64, values: &[f64]) {
        self.rewind();
        if let Some(t) = self.next_contact() {
            self.line.clear();
            let _ = write!(self.line, "{t}");
            for v in &self.contact {
                let _ = write!(self.line, ",{v}");
            }
            for v in values.iter().take(self.n) {
                let _ = write!(self.line, ",{v}");
            }
            self.line.push('\n');
            self.write_line();
        }
    }

    fn rewind(&mut self) {
        if !matches!(self.spool, Spool::Writing(_)) {
            return;
        }
        let spool = std::mem::replace(&mut self.spool, Spool::Failed);
        if let Spool::Writing(w) = spool {
            match w
                .into_inner()
                .map_err(|e| e.into_error())
                .and_then(|mut f| {
                    f.rewind()?;
                    Ok(f)
                }) {
                Ok(f) => self.spool = Spool::Reading(BufReader::with_capacity(1 << 16, f)),
                Err(e) => self.fail(e),
            }
        }
    }

    /// The next spooled row with contact (its time; the values in `contact`).
    fn next_contact(&mut self) -> Option<f64> {
        let Spool::Reading(r) = &mut self.spool else {
            return None;
        };
        self.record.resize(8 * (1 + self.n), 0);
        match r.read_exact(&mut self.record) {
            Ok(()) => {}
            Err(e) if e.kind() == std::io::ErrorKind::UnexpectedEof => return None,
            Err(e) => {
                self.fail(e);
                return None;
            }
        }
        let mut it = self
            .record
            .chunks_exact(8)
            .map(|c| f64::from_le_bytes(c.try_into().unwrap_or([0; 8])));
        let t = it.next().unwrap_or(f64::NAN);
        for (c, v) in self.contact.iter_mut().zip(it) {
            *c = v;
        }
        Some(t)
    }

    fn write_line(&mut self) {
        if let Some(csv) = self.csv.as_mut()
            && let Err(e) = csv.write_all(self.line.as_bytes())
        {
            self.fail(e);
        }
    }

    /// Write what is left and rename the file into place; returns its path.
    pub fn finish(mut self) -> std::io::Result<PathBuf> {
        // rows with contact that the run without contact did not match (none, normally)
        self.rewind();
        while let Some(t) = self.next_contact() {
            self.line.clear();
            let _ = write!(self.line, "{t}");
            for v in &self.contact {
                let _ = write!(self.line, ",{v}");
            }
            for _ in 0..self.n {
                self.line.push_str(",NaN");
            }
            self.line.push('\n');
            self.write_line();
        }
        if let Some(e) = self.error.take() {
            return Err(e);
        }
        if let Some(csv) = self.csv.take() {
            let tmp = csv.into_inner().map_err(|e| e.into_error())?;
            tmp.as_file().sync_all()?;
            tmp.persist(&self.path).map_err(|e| e.error)?;
        }
        Ok(self.path.clone())
    }
}
