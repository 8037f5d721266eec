//! One line of the audit's table (`tests/audit_round.rs`, `tests/audit_cantilever_laws.rs`):
//! a run's largest error against the independent reference, its self-check's estimate and
//! verdict, and whether that verdict is honest.

use pounding::analysis::simulate::StructureReport;

use super::FloorPeaks;
use super::physical_laws::Peaks;

/// The largest error of a structure's floors against the reference `want`, each quantity
/// relative to its own reference peak or to 10 % of that quantity's largest over the floors
/// when below it (how the self-check measures a floor quantity), with the quantity's name.
pub fn floor_error(s: &StructureReport, want: &FloorPeaks) -> (f64, String) {
    let mut worst = (0.0f64, String::new());
    let got: [(&str, Vec<f64>, &Vec<f64>); 5] = [
        (
            "displacement",
            s.floors.iter().map(|f| f.peak_displacement).collect(),
            &want.disp,
        ),
        (
            "acceleration",
            s.floors.iter().map(|f| f.peak_acceleration).collect(),
            &want.acc,
        ),
        (
            "drift",
            s.floors.iter().map(|f| f.peak_drift).collect(),
            &want.drift,
        ),
        (
            "storey force",
            s.floors.iter().map(|f| f.peak_shear).collect(),
            &want.force,
        ),
        (
            "equilibrium shear",
            s.floors.iter().map(|f| f.peak_shear_with_damping).collect(),
            &want.shear,
        ),
    ];
    for (name, x, w) in got {
        assert_eq!(x.len(), w.len(), "{name}: one peak per floor");
        let big = w.iter().fold(0.0f64, |m, v| m.max(*v));
        for (f, (a, b)) in x.iter().zip(w.iter()).enumerate() {
            let e = (a - b).abs() / b.max(0.1 * big);
            if e > worst.0 {
                worst = (e, format!("{name} floor {}", f + 1));
            }
        }
    }
    worst
}

/// One line of the audit's table: the largest error over `structures`' floors and the peak
/// forces, the check's estimate and verdict.
pub struct Line {
    /// The largest relative error.
    pub error: f64,
    /// Where it is.
    pub what: String,
    /// The check's largest change.
    pub estimate: Option<f64>,
    /// The check's verdict.
    pub converged: Option<bool>,
    /// The run's impacts.
    pub impacts: usize,
    /// The reference's impacts.
    pub impacts_ref: usize,
}

impl Line {
    pub fn of(
        structures: &[StructureReport],
        forces: &[f64],
        impacts: usize,
        want: &Peaks,
        estimate: Option<f64>,
        converged: Option<bool>,
    ) -> Line {
        let mut worst = (0.0f64, String::new());
        for (i, (s, w)) in structures.iter().zip(&want.floors).enumerate() {
            let (e, what) = floor_error(s, w);
            if e > worst.0 {
                worst = (e, format!("structure {} {what}", i + 1));
            }
        }
        let fmax = want.force.iter().fold(0.0f64, |m, v| m.max(*v));
        for (k, (a, b)) in forces.iter().zip(&want.force).enumerate() {
            let e = (a - b).abs() / b.max(0.1 * fmax);
            if e > worst.0 {
                worst = (e, format!("peak force {}", k + 1));
            }
        }
        Line {
            error: worst.0,
            what: worst.1,
            estimate,
            converged,
            impacts,
            impacts_ref: want.impacts.iter().sum(),
        }
    }

    /// The line printed as a row of the README's table.
    pub fn print(&self, case: &str, method: &str) {
        eprintln!(
            "| {case} | {method} | {:.2e} ({}) | {} | {} | {} / {} |",
            self.error,
            self.what,
            self.estimate.map_or("-".into(), |e| format!("{e:.2e}")),
            match self.converged {
                Some(true) => "converged",
                Some(false) => "NOT CONVERGED",
                None => "-",
            },
            self.impacts,
            self.impacts_ref,
        );
    }

    /// Honest: a true error above the check's 1 % threshold is flagged.
    pub fn honest(&self) -> bool {
        self.error <= 0.01 || self.converged == Some(false)
    }

    /// The error within `tol` and the verdict honest.
    pub fn assert_within(&self, tol: f64, case: &str, method: &str) {
        assert!(
            self.honest(),
            "{case} {method}: a dishonest check ({:.2e} {})",
            self.error,
            self.what
        );
        assert!(
            self.error < tol,
            "{case} {method}: {:.2e} ({})",
            self.error,
            self.what
        );
    }
}
