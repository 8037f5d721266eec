//! The storeys of shear buildings in a crosscheck (issue 24): OpenSees' storey links against the
//! program's storey peaks, and a yielding building's ductility, residual drift and hysteretic
//! energy.

use super::results::{OpenSeesResults, OsStorey, OsStructure, ProgramNumbers, Row};
use crate::analysis::simulate::StructureReport;

/// The storeys of each shear building: every storey's peak drift and peak storey force
/// (`floors[].peak_shear`, the force the storey carries: OpenSees' link force) with and without
/// contact; for a yielding building also its largest ductility, largest |residual drift|
/// (against its smallest yield drift when smaller) and total hysteretic energy (against 0.1 %
/// of the input energy when smaller), with and without contact.
pub(super) fn storey_rows(p: &ProgramNumbers, o: &OpenSeesResults) -> Vec<Row> {
    let r = &p.report;
    storey_rows_of(&r.structures, r.energy.input, &o.structures, &|s| {
        (s + 1).to_string()
    })
}

/// [`storey_rows`] of any number of structures (a pair's or a row's): the program's
/// `structures` (with `input_energy`, J, the run's input energy with contact) against OpenSees'
/// `os`, structure `s` (0-based) called `label(s)` in the quantities' names.
pub(super) fn storey_rows_of(
    structures: &[StructureReport],
    input_energy: f64,
    os: &[OsStructure],
    label: &dyn Fn(usize) -> String,
) -> Vec<Row> {
    let mut rows = Vec::new();
    let row = |q: String, program: f64, opensees: Option<f64>, scale: f64| Row {
        quantity: q,
        program,
        opensees,
        scale,
    };
    for (s, st) in structures.iter().enumerate() {
        let Some(os) = os.get(s).filter(|x| !x.storeys.is_empty()) else {
            continue;
        };
        let i = label(s);
        for (j, (f, x)) in st.floors.iter().zip(&os.storeys).enumerate() {
            let j = j + 1;
            rows.push(row(
                format!("  storey {j} of {i}: peak drift with contact [m]"),
                f.peak_drift,
                x.peak_drift,
                0.0,
            ));
            rows.push(row(
                format!("  storey {j} of {i}: peak drift without contact [m]"),
                f.peak_drift_no_contact,
                x.peak_drift_no_contact,
                0.0,
            ));
            rows.push(row(
                format!("  storey {j} of {i}: peak storey force with contact [N]"),
                f.peak_shear,
                x.peak_force,
                0.0,
            ));
            rows.push(row(
                format!("  storey {j} of {i}: peak storey force without contact [N]"),
                f.peak_shear_no_contact,
                x.peak_force_no_contact,
                0.0,
            ));
        }
        let (Some(dy), true) = (st.min_yield_drift, st.peak_ductility.is_some()) else {
            continue;
        };
        // OpenSees' side of the structure's summaries, over its storeys
        let ys: Vec<f64> = st.floors.iter().filter_map(|f| f.yield_drift).collect();
        let over = |pick: &dyn Fn(&OsStorey) -> Option<f64>, how: &dyn Fn(&[f64]) -> f64| {
            let v: Option<Vec<f64>> = os.storeys.iter().map(pick).collect();
            v.map(|v| how(&v))
        };
        let largest = |v: &[f64]| v.iter().fold(0.0f64, |a, b| a.max(b.abs()));
        let ductility = |pick: &dyn Fn(&OsStorey) -> Option<f64>| {
            let v: Option<Vec<f64>> = os.storeys.iter().map(pick).collect();
            v.map(|v| v.iter().zip(&ys).map(|(d, y)| d / y).fold(0.0f64, f64::max))
        };
        let energy_scale = 1e-3 * input_energy.abs();
        let total = |v: &[f64]| v.iter().sum::<f64>();
        rows.extend([
            row(
                format!("peak ductility of {i} with contact"),
                st.peak_ductility.unwrap_or(f64::NAN),
                ductility(&|x| x.peak_drift),
                0.0,
            ),
            row(
                format!("peak ductility of {i} without contact"),
                st.peak_ductility_no_contact.unwrap_or(f64::NAN),
                ductility(&|x| x.peak_drift_no_contact),
                0.0,
            ),
            row(
                format!("largest residual drift of {i} with contact [m]"),
                st.max_residual_drift.unwrap_or(f64::NAN),
                over(&|x| x.residual_drift, &largest),
                dy,
            ),
            row(
                format!("largest residual drift of {i} without contact [m]"),
                st.max_residual_drift_no_contact.unwrap_or(f64::NAN),
                over(&|x| x.residual_drift_no_contact, &largest),
                dy,
            ),
            row(
                format!("hysteretic energy of {i} with contact [J]"),
                st.hysteretic_energy.unwrap_or(f64::NAN),
                over(&|x| x.hysteretic_energy, &total),
                energy_scale,
            ),
            row(
                format!("hysteretic energy of {i} without contact [J]"),
                st.hysteretic_energy_no_contact.unwrap_or(f64::NAN),
                over(&|x| x.hysteretic_energy_no_contact, &total),
                energy_scale,
            ),
        ]);
    }
    rows
}
