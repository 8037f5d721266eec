//! `floors.csv`: the time histories of every floor (a cantilever's stations) — displacement
//! and absolute acceleration, with and without pounding — streamed as `history.csv` is: the
//! rows of the run with contact are spooled in binary to an anonymous temporary file, and each
//! row of the run without contact completes one line. Memory holds one row; the file appears
//! under its name only when complete (temporary file, renamed by [`FloorsCsv::finish`]).

use std::fmt::Write as _;
use std::io::{BufWriter, Write as _};

use crate::output::csv::{push_field, push_number};
use std::path::{Path, PathBuf};

use crate::output::row_spool::RowSpool;

/// The file's name in a run's directory.
pub const FILE_NAME: &str = "floors.csv";

/// A `floors.csv` being written (see the module).
pub struct FloorsCsv {
    path: PathBuf,
    csv: Option<BufWriter<tempfile::NamedTempFile>>,
    /// The rows with contact: t and the values.
    spool: RowSpool,
    /// Values per row of one run.
    n: usize,
    /// t and the values of the spooled row being completed.
    contact: Vec<f64>,
    /// Reused text of one CSV line.
    line: Vec<u8>,
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
        // (the permissions of every other output: an ordinary new file's under the umask)
        let tmp = crate::output::atomic::temp_file(dir, ".pounding-floors-", ".tmp")?;
        let mut csv = BufWriter::with_capacity(1 << 16, tmp);
        let mut head = String::from("t");
        for c in columns {
            let _ = write!(head, ",{c}");
        }
        for c in columns {
            let _ = write!(head, ",{c}_free");
        }
        writeln!(csv, "{head}")?;
        Ok(FloorsCsv {
            path: dir.join(FILE_NAME),
            csv: Some(csv),
            spool: RowSpool::new(dir, 1 + columns.len())?,
            n: columns.len(),
            contact: vec![0.0; 1 + columns.len()],
            line: Vec::with_capacity(24 * (1 + 2 * columns.len())),
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
        self.spool
            .push(std::iter::once(t).chain(values.iter().copied()));
    }

    /// A row of the run without contact: completes the next spooled row.
    pub fn free_row(&mut self, _t: f64, values: &[f64]) {
        self.spool.rewind();
        if self.spool.next(&mut self.contact) {
            self.contact_part();
            for &v in values.iter().take(self.n) {
                push_field(&mut self.line, v);
            }
            self.line.push(b'\n');
            self.write_line();
        }
    }

    /// Start the line with the spooled row (t and the values with contact).
    fn contact_part(&mut self) {
        self.line.clear();
        push_number(&mut self.line, self.contact[0]);
        for &v in &self.contact[1..] {
            push_field(&mut self.line, v);
        }
    }

    fn write_line(&mut self) {
        if let Some(csv) = self.csv.as_mut()
            && let Err(e) = csv.write_all(&self.line)
        {
            self.fail(e);
        }
    }

    /// Write what is left and rename the file into place; returns its path.
    pub fn finish(mut self) -> std::io::Result<PathBuf> {
        // rows with contact that the run without contact did not match (none, normally)
        self.spool.rewind();
        while self.spool.next(&mut self.contact) {
            self.contact_part();
            for _ in 0..self.n {
                self.line.extend_from_slice(b",NaN");
            }
            self.line.push(b'\n');
            self.write_line();
        }
        if let Some(e) = self.error.take().or_else(|| self.spool.take_error()) {
            return Err(e);
        }
        if let Some(csv) = self.csv.take() {
            let tmp = csv.into_inner().map_err(|e| e.into_error())?;
            crate::output::atomic::persist(tmp, &self.path)?;
        }
        Ok(self.path.clone())
    }
}
