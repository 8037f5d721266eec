//! Compare two run directories (`pounding run … --out A` and `--out B`, say an old and a new
//! binary): every `.png` by its decoded pixels (the `image` crate, 8-bit RGB), every other
//! file byte for byte, and the two directories must hold the same file names. A PNG's bytes
//! may differ between encoder settings while its pixels do not; this says whether they do.
//!
//! ```text
//! cargo build --release --example same-pixels
//! target/release/examples/same-pixels DIR_A DIR_B
//! ```
//!
//! Prints one line per file (`same`, `same pixels (N → M bytes)` or what differs) and exits
//! with 1 when anything differs, 2 on a usage or read error.

use std::collections::BTreeSet;
use std::path::Path;
use std::process::ExitCode;

fn names(dir: &Path) -> std::io::Result<BTreeSet<String>> {
    let mut out = BTreeSet::new();
    for e in std::fs::read_dir(dir)? {
        let e = e?;
        if e.file_type()?.is_file() {
            out.insert(e.file_name().to_string_lossy().into_owned());
        }
    }
    Ok(out)
}

/// `None` when the two files hold the same content (pixels for a PNG), else what differs.
fn compare(a: &Path, b: &Path) -> Result<Option<String>, String> {
    let read = |p: &Path| std::fs::read(p).map_err(|e| format!("{}: {e}", p.display()));
    let (ba, bb) = (read(a)?, read(b)?);
    if ba == bb {
        return Ok(None);
    }
    if a.extension().is_some_and(|e| e == "png") {
        let decode = |bytes: &[u8], p: &Path| {
            image::load_from_memory(bytes)
                .map(|i| i.to_rgb8())
                .map_err(|e| format!("{}: {e}", p.display()))
        };
        let (ia, ib) = (decode(&ba, a)?, decode(&bb, b)?);
        if ia.dimensions() != ib.dimensions() {
            return Ok(Some(format!(
                "sizes differ: {:?} against {:?}",
                ia.dimensions(),
                ib.dimensions()
            )));
        }
        let differ = ia.pixels().zip(ib.pixels()).filter(|(p, q)| p != q).count();
        return Ok(if differ == 0 {
            println!(
                "{}: same pixels ({} → {} bytes)",
                a.file_name().unwrap_or_default().to_string_lossy(),
                ba.len(),
                bb.len()
            );
            None
        } else {
            Some(format!("{differ} pixels differ"))
        });
    }
    let first = ba.iter().zip(&bb).take_while(|(x, y)| x == y).count();
    Ok(Some(format!(
        "bytes differ from byte {first} ({} against {} bytes)",
        ba.len(),
        bb.len()
    )))
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [a, b] = args.as_slice() else {
        eprintln!("usage: same-pixels DIR_A DIR_B");
        return ExitCode::from(2);
    };
    let (a, b) = (Path::new(a), Path::new(b));
    let (na, nb) = match (names(a), names(b)) {
        (Ok(na), Ok(nb)) => (na, nb),
        (Err(e), _) | (_, Err(e)) => {
            eprintln!("same-pixels: {e}");
            return ExitCode::from(2);
        }
    };
    let mut same = true;
    for n in na.symmetric_difference(&nb) {
        println!("{n}: only in {}", if na.contains(n) { "A" } else { "B" });
        same = false;
    }
    for n in na.intersection(&nb) {
        match compare(&a.join(n), &b.join(n)) {
            Ok(None) => {}
            Ok(Some(why)) => {
                println!("{n}: {why}");
                same = false;
            }
            Err(e) => {
                eprintln!("same-pixels: {e}");
                return ExitCode::from(2);
            }
        }
    }
    if same {
        println!("same: {} files", na.len());
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}
