//! Unit tests of the sweep file: the grid, the axes, the case scenarios, the identity.

use super::*;
use crate::model::structure::{Damping, Stiffness};

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

const BASE: &str = include_str!("../../../examples/paper-c.toml");

fn sweep(axes: &str) -> Result<Sweep, SweepError> {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "base.toml", BASE);
    let p = write(
        dir.path(),
        "s.toml",
        &format!("scenario = \"base.toml\"\n{axes}"),
    );
    Sweep::from_file(&p)
}

#[test]
fn grid_order_first_axis_slowest() {
    let s = sweep(
        "[[axis]]\nkey = \"period_ratio\"\nvalues = [0.3, 0.5]\n\
         [[axis]]\nkey = \"ground_motion.pga\"\nfrom = 0.1\nto = 0.3\nsteps = 3\n",
    )
    .unwrap();
    assert_eq!(s.len(), 6);
    assert_eq!(s.label(0), "period_ratio = 0.3, ground_motion.pga = 0.1");
    assert_eq!(s.label(4), "period_ratio = 0.5, ground_motion.pga = 0.2");
    assert_eq!(s.axes[1].values[1], AxisValue::Number(0.2));
}

#[test]
fn derived_axes_set_periods() {
    let s = sweep(
        "[[axis]]\nkey = \"period_ratio\"\nvalues = [0.7]\n\
         [[axis]]\nkey = \"ground_period_ratio\"\nvalues = [2.0]\n",
    )
    .unwrap();
    let sc = s.case_scenario(0).unwrap();
    let t2 = 0.4203 / 0.7;
    assert_eq!(
        sc.structures[1].as_cantilever().unwrap().stiffness,
        Stiffness::Period(t2)
    );
    let h = match &sc.ground_motion {
        crate::model::ground_motion::GroundMotion::Harmonic(h) => *h,
        _ => panic!(),
    };
    assert!((h.period() - t2 / 2.0).abs() < 1e-12);
}

#[test]
fn period_ratio_from_stiffness() {
    // structure 1 given by tip stiffness: T1 from the modal model
    let base = BASE.replacen("period = 0.4203", "tip_stiffness = 5.0e8", 1);
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "base.toml", &base);
    let p = write(
        dir.path(),
        "s.toml",
        "scenario = \"base.toml\"\n[[axis]]\nkey = \"period_ratio\"\nvalues = [0.5]\n",
    );
    let s = Sweep::from_file(&p).unwrap();
    let sc = s.case_scenario(0).unwrap();
    let t1 = sc.structures[0].modal().periods()[0];
    let t2 = sc.structures[1].modal().periods()[0];
    assert!((t1 / t2 - 0.5).abs() < 1e-12, "{t1} {t2}");
}

#[test]
fn errors_name_file_key_and_range() {
    let e = sweep("[[axis]]\nkey = \"ground_motion.pgaa\"\nvalues = [1]\n")
        .unwrap_err()
        .to_string();
    assert!(e.contains("s.toml:3:7"), "{e}");
    assert!(e.contains("did you mean `ground_motion.pga`"), "{e}");
    let e = sweep("[[axis]]\nkey = \"period_ratio\"\nvalues = [0.5, -1]\n")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("s.toml:4:16") && e.contains("must be > 0"),
        "{e}"
    );
    let e = sweep("[[axis]]\nkey = \"structure.3.mass\"\nvalues = [1]\n")
        .unwrap_err()
        .to_string();
    // (a row may have more: the base scenario's count decides)
    assert!(
        e.contains("has 2 structures") && e.contains("axis[1].key"),
        "{e}"
    );
    let e = sweep("[[axis]]\nkey = \"contact.gap\"\nfrom = 0\nto = 1\n")
        .unwrap_err()
        .to_string();
    assert!(e.contains("axis[1].steps") && e.contains("missing"), "{e}");
    let e = sweep("[[axis]]\nkey = \"contact.gap\"\nvalues = [0.1]\nfoo = 1\n")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("s.toml:5:1")
            && e.contains("unknown key `foo` in [[axis]]")
            && e.contains("(valid keys: key, values, from, to, steps, scale)"),
        "{e}"
    );
    let e = sweep(
        "[[axis]]\nkey = \"period_ratio\"\nvalues = [0.5]\n[[axis]]\nkey = \"structure[2].period\"\nvalues = [1.0]\n",
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("cannot be an axis together"), "{e}");
}

#[test]
fn log_axis_and_tidy_values() {
    let s = sweep("[[axis]]\nkey = \"contact.stiffness\"\nfrom = 1e8\nto = 1e11\nsteps = 4\nscale = \"log\"\n").unwrap();
    let v: Vec<String> = s.axes[0].values.iter().map(|v| v.to_csv()).collect();
    assert_eq!(
        v,
        [
            "100000000.0",
            "1000000000.0",
            "10000000000.0",
            "100000000000.0"
        ]
    );
}

#[test]
fn case_toml_round_trips_floats() {
    let s = sweep(
        "[[axis]]\nkey = \"contact.gap\"\nvalues = [0.30000000000000004, 1e-20, 7.123456789012345]\n",
    )
    .unwrap();
    for i in 0..3 {
        let sc = s.case_scenario(i).unwrap();
        assert_eq!(
            sc.contact.levels[0].gap,
            as_f64(&s.axes[0].values[i]),
            "case {i}"
        );
    }
}

#[test]
fn integer_and_replacing_keys() {
    let s = sweep(
        "[[axis]]\nkey = \"structure.2.modes\"\nfrom = 1\nto = 5\nsteps = 3\n\
         [[axis]]\nkey = \"structure[2].tip_stiffness\"\nvalues = [3e8]\n\
         [[axis]]\nkey = \"structure.1.strain_rate_damping\"\nvalues = [0.001]\n",
    )
    .unwrap();
    assert_eq!(s.axes[0].values[1], AxisValue::Integer(3));
    assert_eq!(s.axes[1].key, "structure.2.tip_stiffness");
    let sc = s.case_scenario(2).unwrap();
    assert_eq!(sc.structures[1].modes(), 5);
    assert_eq!(
        sc.structures[1].as_cantilever().unwrap().stiffness,
        Stiffness::Tip(3e8)
    );
    assert!(matches!(
        sc.structures[0].as_cantilever().unwrap().damping,
        Damping::Physical { strain_rate, air } if strain_rate == 0.001 && air == 0.0
    ));
    let e = sweep("[[axis]]\nkey = \"structure.2.modes\"\nvalues = [2.5]\n")
        .unwrap_err()
        .to_string();
    assert!(e.contains("whole numbers"), "{e}");
}

/// The identity hash of a file streamed in blocks (of any size the reader gives) is the
/// hash of its bytes as one part: streaming changes nothing but the memory it takes.
#[test]
fn streamed_identity_equals_the_whole_file_hash() {
    /// A reader giving at most 7 777 bytes a call, as a pipe or a slow disk might.
    struct Trickle<'a>(&'a [u8]);
    impl std::io::Read for Trickle<'_> {
        fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
            let n = self.0.len().min(buf.len()).min(7777);
            buf[..n].copy_from_slice(&self.0[..n]);
            self.0 = &self.0[n..];
            Ok(n)
        }
    }
    let bytes: Vec<u8> = (0..300_000u32)
        .map(|i| (i.wrapping_mul(2_654_435_761) >> 13) as u8)
        .collect();
    let mut streamed = Fnv1a::new();
    streamed.part(b"head");
    streamed.stream(Trickle(&bytes));
    streamed.end_part();
    assert_eq!(streamed.finish(), fnv1a(&[b"head", &bytes]));
    // and a different byte changes it
    let mut other = bytes.clone();
    other[123_456] ^= 1;
    assert_ne!(fnv1a(&[b"head", &bytes]), fnv1a(&[b"head", &other]));
}

#[test]
fn shard_parse() {
    assert_eq!("2/5".parse::<Shard>(), Ok(Shard { k: 2, n: 5 }));
    assert!("0/5".parse::<Shard>().is_err());
    assert!("6/5".parse::<Shard>().is_err());
    assert!("x".parse::<Shard>().is_err());
}
