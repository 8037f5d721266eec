//! The journal `journal.csv` (`journal-shard-K-of-N.csv` for a part, [`super::results::file_names`])
//! of a sweep, and of any study that resumes the same way ([`JournalKind`], [`Journal::open_kind`]:
//! the fragility study's runs): every finished row is appended as soon as it is known, one
//! `write` per row, in completion order; the first line identifies the study and the format
//! version; a rerun reads it back, drops a torn last line and runs only what is missing. The
//! rows' format is [`super::results`]'s.

use std::collections::BTreeMap;
use std::fs::{File, OpenOptions};
use std::io::{Read, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use super::results::{check_row, header, journal_version, parse_csv_line};
use super::shard::Shard;
use super::{Sweep, SweepError};

/// The first line of the file at `path`, if it can be read (a journal's version line).
fn journal_first_line(path: &Path) -> Option<String> {
    use std::io::BufRead;
    let file = File::open(path).ok()?;
    let mut line = String::new();
    std::io::BufReader::new(file).read_line(&mut line).ok()?;
    Some(line.trim_end().to_string())
}

/// The journal of finished rows, open for appending and locked against a second writer.
#[derive(Debug)]
pub struct Journal {
    path: PathBuf,
    file: File,
    last_sync: Instant,
    /// Rows already in the journal, by case: the line and whether the case failed.
    pub rows: BTreeMap<usize, (String, bool)>,
    /// Lines that were dropped on reading (torn or damaged).
    pub dropped: usize,
}

/// What a journal holds, for [`Journal::open_kind`]: a sweep's ([`Journal::open`]) or another
/// study's rows (a fragility study's runs), with the same resume machinery.
pub struct JournalKind<'a> {
    /// The first line's start up to the version, e.g. `# pounding sweep journal v`.
    pub magic: &'a str,
    /// This version.
    pub version: u32,
    /// The whole first line (magic, version, `;`, the identity …).
    pub ident: String,
    /// The header line.
    pub header: String,
    /// `pounding sweep`: the command, in messages.
    pub command: &'a str,
    /// What changes the identity, in messages: `the sweep file, its base scenario or --shard`.
    pub inputs: &'a str,
    /// Why another version cannot be resumed, in messages.
    pub version_note: &'a str,
    /// A row read back: its key and whether it failed, `None` if damaged or not of this part.
    pub check_row: &'a dyn Fn(&str) -> Option<(usize, bool)>,
}

impl Journal {
    /// Open (or create) the journal of `sweep`'s part `shard` at `path`. Refuses a journal of
    /// another sweep and a journal another process is writing.
    pub fn open(path: &Path, sweep: &Sweep, shard: Shard) -> Result<Journal, SweepError> {
        let this_version = journal_version(sweep);
        let names = sweep.result_columns();
        let columns = 2 + sweep.axes.len() + names.len();
        let check = |body: &str| {
            let whole = parse_csv_line(body).is_some_and(|f| f.len() == columns);
            check_row(body, &names, sweep.row_kind(), sweep.len())
                .filter(|(case, _)| whole && shard.contains(*case))
        };
        // rows of another kind (one run, a suite of records, a row of buildings, a suite on a
        // row per case): never mixed, and said so rather than as "another version"
        let this_kind = sweep.row_kind();
        if let Some(other) = journal_first_line(path)
            .and_then(|first| {
                first
                    .strip_prefix("# pounding sweep journal v")
                    .and_then(|r| r.split(';').next())
                    .and_then(|v| v.parse::<u32>().ok())
            })
            .and_then(super::RowKind::describe_version)
            .filter(|other| *other != this_kind.describe())
        {
            return Err(SweepError::Journal {
                path: path.display().to_string(),
                message: format!(
                    "this journal holds the rows of another sweep ({other}; this sweep has {}): \
                     the two kinds of rows have different columns and are never mixed. Use \
                     another --out, or delete the directory's journal and results to start \
                     afresh",
                    this_kind.describe()
                ),
            });
        }
        let kind = JournalKind {
            magic: "# pounding sweep journal v",
            version: this_version,
            ident: format!(
                "# pounding sweep journal v{this_version}; identity={:016x}; shard={shard}; cases={}",
                sweep.identity(),
                sweep.len()
            ),
            header: header(sweep),
            command: "pounding sweep",
            inputs: "the sweep file, its base scenario or --shard",
            version_note: "its rows lack or differ in the self-check columns check_max_change \
                           and converged, or in the code columns sep_asce7 …",
            check_row: &check,
        };
        Journal::open_kind(path, &kind)
    }

    /// Open (or create) a journal of `kind` at `path`: refuses a journal of other inputs
    /// (another first line) or of another version, and one another process is writing; drops
    /// a torn last line and damaged rows (their keys are recomputed).
    pub fn open_kind(path: &Path, kind: &JournalKind) -> Result<Journal, SweepError> {
        let io = |e: std::io::Error| SweepError::Write {
            path: path.display().to_string(),
            source: e,
        };
        let mut file = OpenOptions::new()
            .read(true)
            .append(true)
            .create(true)
            .open(path)
            .map_err(io)?;
        match file.try_lock() {
            Ok(()) => {}
            Err(std::fs::TryLockError::WouldBlock) => {
                return Err(SweepError::Journal {
                    path: path.display().to_string(),
                    message: format!(
                        "another `{}` is writing this journal right now; wait for it or use another --out",
                        kind.command
                    ),
                });
            }
            Err(std::fs::TryLockError::Error(e)) => return Err(io(e)),
        }
        let this_version = kind.version;
        let version = format!("{}{this_version};", kind.magic);
        let ident = kind.ident.clone();
        let head = kind.header.clone();
        let preamble = format!("{ident}\n{head}\n");
        let mut text = String::new();
        file.read_to_string(&mut text)
            .map_err(|e| SweepError::Journal {
                path: path.display().to_string(),
                message: format!("cannot be read ({e}); remove it to start the sweep afresh"),
            })?;
        let mut rows = BTreeMap::new();
        let mut dropped = 0;
        if text.len() < preamble.len() && preamble.starts_with(&text) {
            // new, or killed while writing the preamble
            file.set_len(0).map_err(io)?;
            file.write_all(preamble.as_bytes()).map_err(io)?;
        } else {
            let mut lines = text.split_inclusive('\n');
            let first = lines.next().unwrap_or("").trim_end();
            if first.starts_with(kind.magic) && !first.starts_with(&version) {
                let other = first
                    .trim_start_matches(kind.magic.trim_end_matches('v'))
                    .split(';')
                    .next()
                    .unwrap_or("?");
                return Err(SweepError::Journal {
                    path: path.display().to_string(),
                    message: format!(
                        "this journal was written by another version of pounding (journal {other}, \
                         this one v{this_version}: {}). \
                         Finish it with the version that started it, or use another --out, \
                         or delete the directory's journal and results to start afresh",
                        kind.version_note
                    ),
                });
            }
            if first != ident {
                let other = first
                    .split("identity=")
                    .nth(1)
                    .and_then(|s| s.get(..16))
                    .unwrap_or("unknown");
                return Err(SweepError::Journal {
                    path: path.display().to_string(),
                    message: format!(
                        "this directory holds results of a different {} (identity {other}, this one {}; \
                         {} changed). Use another --out, or delete \
                         the directory's journal and results to start afresh",
                        kind.command.trim_start_matches("pounding "),
                        ident
                            .split("identity=")
                            .nth(1)
                            .and_then(|s| s.get(..16))
                            .unwrap_or("?"),
                        kind.inputs
                    ),
                });
            }
            if lines.next().map(str::trim_end) != Some(head.as_str()) {
                return Err(SweepError::Journal {
                    path: path.display().to_string(),
                    message:
                        "the header line is damaged; delete the file to start the sweep afresh"
                            .into(),
                });
            }
            let mut good_end = preamble.len();
            let mut pos = preamble.len();
            for line in lines {
                pos += line.len();
                let Some(body) = line.strip_suffix('\n') else {
                    // torn last line: never completed
                    dropped += 1;
                    break;
                };
                good_end = pos;
                match (kind.check_row)(body) {
                    Some((case, failed)) => {
                        rows.entry(case).or_insert((body.to_string(), failed));
                    }
                    _ => dropped += 1,
                }
            }
            if good_end < text.len() {
                file.set_len(good_end as u64).map_err(io)?;
                file.seek(SeekFrom::End(0)).map_err(io)?;
            }
        }
        Ok(Journal {
            path: path.to_path_buf(),
            file,
            last_sync: Instant::now(),
            rows,
            dropped,
        })
    }

    /// Append a finished row (one write, so that a kill leaves at most a torn last line).
    pub fn append(&mut self, case: usize, line: String, failed: bool) -> Result<(), SweepError> {
        let mut buf = String::with_capacity(line.len() + 1);
        buf.push_str(&line);
        buf.push('\n');
        let io = |e| SweepError::Write {
            path: self.path.display().to_string(),
            source: e,
        };
        self.file.write_all(buf.as_bytes()).map_err(io)?;
        if self.last_sync.elapsed() > Duration::from_secs(5) {
            self.file.sync_data().map_err(io)?;
            self.last_sync = Instant::now();
        }
        self.rows.entry(case).or_insert((line, failed));
        Ok(())
    }

    /// Flush to disk.
    pub fn sync(&mut self) -> Result<(), SweepError> {
        self.file.sync_data().map_err(|e| SweepError::Write {
            path: self.path.display().to_string(),
            source: e,
        })
    }
}
