//! Every ground-motion record bundled in `examples/records/` (issue 27: an 11-record suite)
//! is read and checked against the facts of `examples/records/README.md`, typed in from each
//! file's own header (CSMIP/CDMG V2: "N points … at equally-spaced intervals of DT sec",
//! "Peak acceleration = P cm/sec/sec at T sec") or, for the PEER `.AT2` files, whose header
//! states NPTS and DT but no peak, from the data set's description (PGA to 3 decimals in g).
//! None of these numbers comes from this program.

use std::collections::BTreeSet;
use std::path::Path;

use pounding::model::ground_motion::{Component, Record, RecordOptions, STANDARD_GRAVITY};

const DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/records");

/// The peak as a source states it.
enum Peak {
    /// PGA in g to 3 decimals (the data set's description of a PEER file).
    G3(f64),
    /// Peak acceleration in cm/s² and its time in s, as the V2 header prints them.
    CmS2At(f64, f64),
}

/// One horizontal component of a bundled file: file, channel (None for one-component
/// files), NPTS, DT (s), peak.
struct Row {
    file: &'static str,
    channel: Option<usize>,
    npts: usize,
    dt: f64,
    peak: Peak,
}

const fn row(file: &'static str, channel: Option<usize>, npts: usize, dt: f64, peak: Peak) -> Row {
    Row {
        file,
        channel,
        npts,
        dt,
        peak,
    }
}

/// The table of `examples/records/README.md`.
const TABLE: [Row; 17] = [
    // PEER NGA-West2, Loma Prieta 1989: NPTS and DT from the 4th header line, PGA from the
    // data set's description.
    row(
        "RSN753_LOMAP_CLS000.AT2",
        None,
        7995,
        0.005,
        Peak::G3(0.645),
    ),
    row(
        "RSN753_LOMAP_CLS090.AT2",
        None,
        7999,
        0.005,
        Peak::G3(0.483),
    ),
    row(
        "RSN786_LOMAP_PAE055.AT2",
        None,
        11999,
        0.005,
        Peak::G3(0.215),
    ),
    row(
        "RSN808_LOMAP_TRI000.AT2",
        None,
        7999,
        0.005,
        Peak::G3(0.100),
    ),
    row(
        "RSN813_LOMAP_YBI090.AT2",
        None,
        7999,
        0.005,
        Peak::G3(0.068),
    ),
    // CDMG V2 (1980s layout): channel 1 = 90°, channel 3 = 0°.
    // Coalinga 2 May 1983, station 36456 Parkfield – Fault Zone 14
    row(
        "ce36456p_CE36456.V2",
        Some(1),
        3251,
        0.020,
        Peak::CmS2At(-267.957, 10.940),
    ),
    row(
        "ce36456p_CE36456.V2",
        Some(3),
        3250,
        0.020,
        Peak::CmS2At(-256.231, 7.740),
    ),
    // Whittier Narrows 1 October 1987, station 14196 Inglewood – Union Oil Yard
    row(
        "INGLEWOO.V2",
        Some(1),
        2000,
        0.020,
        Peak::CmS2At(219.267, 5.960),
    ),
    row(
        "INGLEWOO.V2",
        Some(3),
        2000,
        0.020,
        Peak::CmS2At(246.104, 6.340),
    ),
    // Whittier Narrows 1987, station 24399 Mt. Wilson – Caltech Seismic Station
    row(
        "MTWILSON.V2",
        Some(1),
        2000,
        0.020,
        Peak::CmS2At(-171.321, 4.120),
    ),
    row(
        "MTWILSON.V2",
        Some(3),
        2000,
        0.020,
        Peak::CmS2At(-121.339, 4.260),
    ),
    // Whittier Narrows 1987, station 24514 Sylmar – Olive View Medical Center free field
    row(
        "SYLMOVFF.V2",
        Some(1),
        2000,
        0.020,
        Peak::CmS2At(50.298, 6.820),
    ),
    row(
        "SYLMOVFF.V2",
        Some(3),
        2000,
        0.020,
        Peak::CmS2At(-55.792, 7.920),
    ),
    // CGS V2 (today's layout). South Napa 24 August 2014, station 58667 Concord: H1, H2
    row(
        "CE58667.V2",
        Some(1),
        7500,
        0.010,
        Peak::CmS2At(27.114, 32.570),
    ),
    row(
        "CE58667.V2",
        Some(3),
        7500,
        0.010,
        Peak::CmS2At(-26.411, 30.720),
    ),
    // 13 February 2012, station 89146 Willow Creek: 360°, 90°
    row(
        "CE89146.V2",
        Some(1),
        12000,
        0.005,
        Peak::CmS2At(77.280, 30.585),
    ),
    row(
        "CE89146.V2",
        Some(3),
        12000,
        0.005,
        Peak::CmS2At(-44.200, 30.575),
    ),
];

fn read(row: &Row) -> Record {
    let opts = RecordOptions {
        component: row.channel.map(Component::Index),
        ..RecordOptions::default()
    };
    Record::read(&Path::new(DIR).join(row.file), &opts)
        .unwrap_or_else(|e| panic!("{} channel {:?}: {e}", row.file, row.channel))
}

/// Count, time step and peak of every bundled component, against the table.
#[test]
fn bundled_records_match_their_headers() {
    for row in &TABLE {
        let r = read(row);
        let what = format!("{} channel {:?}", row.file, row.channel);
        assert_eq!(r.num_samples(), row.npts, "{what}: NPTS");
        // DT is printed exactly (0.005, .010, .020 s); the reader parses it to the nearest f64.
        assert!((r.dt - row.dt).abs() < 1e-12, "{what}: DT {}", r.dt);
        match row.peak {
            Peak::G3(g) => {
                // the description rounds to 3 decimals: half a unit of the last digit
                let pga_g = r.pga() / STANDARD_GRAVITY;
                assert!((pga_g - g).abs() <= 5e-4, "{what}: PGA {pga_g} g vs {g} g");
            }
            Peak::CmS2At(peak, time) => {
                // The V2 data are printed to 0.001 cm/s² like the header's peak, so the
                // largest |sample| and the stated peak agree to the rounding of both, half a
                // unit of the last digit each (1e-3 cm/s² in all).
                let pga = r.pga() / 0.01;
                assert!(
                    (pga - peak.abs()).abs() <= 1e-3,
                    "{what}: PGA {pga} cm/s² vs |{peak}| cm/s²"
                );
                // The header's time is a sample time printed to 0.001 s (1e-9 for the
                // rounding of k·dt in floating point).
                assert!(
                    (r.pga_time() - time).abs() <= 1e-9 + 5e-4,
                    "{what}: time of the peak {} s vs {time} s",
                    r.pga_time()
                );
                // the reader also kept the header's own statement, sign and all
                let stated = r.stated_peak.as_ref().expect("a V2 header states its peak");
                assert!(
                    (stated.accel / 0.01 - peak).abs() <= 1e-6,
                    "{what}: stated peak {} m/s²",
                    stated.accel
                );
            }
        }
    }
}

/// Every file in `examples/records/` has a row, and the suite of one horizontal component per
/// file has the 11 records of the README (no file left undocumented, none missing).
#[test]
fn every_bundled_file_has_a_row() {
    let on_disk: BTreeSet<String> = std::fs::read_dir(DIR)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n != "README.md" && !n.starts_with('.'))
        .collect();
    let in_table: BTreeSet<String> = TABLE.iter().map(|r| r.file.to_string()).collect();
    assert_eq!(on_disk, in_table);
    assert_eq!(in_table.len(), 11);
    // Byte for byte as found: each file's size as its source lists it (the shared data set's
    // directory listing for the `.AT2` files; `git ls-tree -l` of the source repository, or
    // `unzip -l` of its archive for the three Whittier Narrows files). The V2 files end
    // their lines with CRLF, which `.gitattributes` keeps.
    let sizes = [
        ("RSN753_LOMAP_CLS000.AT2", 121_762),
        ("RSN753_LOMAP_CLS090.AT2", 121_794),
        ("RSN786_LOMAP_PAE055.AT2", 182_608),
        ("RSN808_LOMAP_TRI000.AT2", 121_798),
        ("RSN813_LOMAP_YBI090.AT2", 121_802),
        ("ce36456p_CE36456.V2", 309_632),
        ("INGLEWOO.V2", 194_304),
        ("MTWILSON.V2", 194_304),
        ("SYLMOVFF.V2", 194_432),
        ("CE58667.V2", 703_569),
        ("CE89146.V2", 1_118_685),
    ];
    assert_eq!(sizes.len(), on_disk.len());
    for (name, size) in sizes {
        let on_disk = std::fs::metadata(Path::new(DIR).join(name)).unwrap().len();
        assert_eq!(on_disk, size, "{name}: size");
    }
}
