//! The OpenSees export of a row of buildings (issue 29): one self-contained OpenSeesPy script
//! with every structure of the row and the contact elements of every adjacent pair.
//!
//! Each structure is exported as the pair export exports it ([`super::model`]: a cantilever's
//! mesh with a node at every contact height of both its neighbours, a shear building's floors,
//! Bouc–Wen storeys), each pair's levels with that pair's law mapped as the pair export maps it
//! ([`super::contact_material`]). The script is the pair's (its header, `MODEL`, the pair's
//! driver) followed by a row driver (`row_driver.py`) whose `RowModel` extends the pair's
//! `Model` to N structures: the same elements, loads, damping, integration and observation, with
//! every level's `zeroLength` element between its pair's two nodes. It prints the headline
//! numbers of a row's summary.json: per structure, and per pair (`pairs`, in row order, with the
//! two names). A pair's script is not touched: [`super::script`].

use serde::Serialize;

use super::{
    DRIVER, ExportError, ExportGround, ExportLevel, ExportOptions, ExportStructure,
    NEWTON_TOLERANCE, Only, ScriptParts, checked_duration, export_ground, export_levels,
    export_structure, exported_by, mapping_text, one_line, script_text,
};
use crate::input::scenario::Scenario;

/// The row driver appended to a row's script after the pair's driver (Python, OpenSeesPy).
pub const ROW_DRIVER: &str = include_str!("row_driver.py");

/// How the pair's driver ends: its `main()` call, which a row's script leaves out (the row
/// driver's `row_main()` runs instead).
pub const PAIR_MAIN_CALL: &str = "\nif __name__ == \"__main__\":\n    main()\n";

/// What a row's script says it prints.
const ROW_PRINTS: &str = "# prints JSON with the headline numbers of a row's summary.json: per structure its peaks\n\
     # (at its highest contact level with either neighbour, at the contact heights and every\n\
     # floor, every storey's peak drift and storey force, a yielding storey's residual drift\n\
     # and hysteretic energy), per adjacent pair (`pairs`, row order) its levels' peak force,\n\
     # penetration, impacts and contact time and its required separation.\n#\n";

/// The pair's driver without its final `main()` call: its functions and `Model` class, which
/// the row driver extends.
pub fn pair_driver_body() -> &'static str {
    DRIVER.strip_suffix(PAIR_MAIN_CALL).unwrap_or(DRIVER)
}

/// A contact level of a row: a pair's level as the pair export has it, and its pair.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RowLevel {
    /// The pair (its left structure's index, 0-based): the level joins structures `pair` and
    /// `pair + 1`.
    pub pair: usize,
    /// Height, gap and OpenSees material.
    #[serde(flatten)]
    pub level: ExportLevel,
}

/// An adjacent pair of the exported row.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ExportPair {
    /// Its left structure's index (0-based).
    pub index: usize,
    /// The two structures' names, left then right.
    pub between: [String; 2],
    /// Its contact law's scenario name.
    pub law: &'static str,
}

/// A row's model data, serialised as the script's `MODEL` literal.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RowExportModel {
    /// Scenario title.
    pub title: String,
    /// What wrote it.
    pub source: String,
    /// Analysis step, s.
    pub dt: f64,
    /// Simulated time, s.
    pub duration: f64,
    /// Newton tolerance.
    pub tolerance: f64,
    /// Runs (`None`: both).
    pub only: Option<Only>,
    /// Every structure, in row order.
    pub structures: Vec<ExportStructure>,
    /// Every pair's contact levels, pair by pair (each in its `[[contact]]` table's order).
    pub levels: Vec<RowLevel>,
    /// Every adjacent pair, in row order.
    pub pairs: Vec<ExportPair>,
    /// Ground motion.
    pub ground: ExportGround,
}

/// `e` as the refusal of pair `p` (0-based) of `scenario`: the key `contact[P]` (1-based, as
/// a sweep names it) and the two names.
fn in_pair(scenario: &Scenario, p: usize, e: ExportError) -> ExportError {
    ExportError::Pair {
        pair: p + 1,
        left: scenario.structures[p].name().to_string(),
        right: scenario.structures[p + 1].name().to_string(),
        source: Box::new(e),
    }
}

/// The exported model of a row `scenario` (any number of structures ≥ 2; see the module
/// documentation). Whatever the pair export refuses is refused, a pair's contact or contact
/// height named by its key `contact[P]`.
pub fn row_model(scenario: &Scenario, opts: &ExportOptions) -> Result<RowExportModel, ExportError> {
    let duration = checked_duration(scenario, opts)?;
    let contacts: Vec<_> = scenario.contacts().collect();
    let n = scenario.structures.len();
    let mut structures = Vec::with_capacity(n);
    for (i, s) in scenario.structures.iter().enumerate() {
        // the structure's own refusal (its kind) first, then each neighbour's contact heights
        export_structure(s, &[], opts.elements)?;
        let mut heights: Vec<f64> = Vec::new();
        for p in [i.checked_sub(1), (i + 1 < n).then_some(i)]
            .into_iter()
            .flatten()
        {
            let hp: Vec<f64> = contacts[p].levels.iter().map(|l| l.height).collect();
            export_structure(s, &hp, opts.elements).map_err(|e| in_pair(scenario, p, e))?;
            for h in hp {
                if !heights.contains(&h) {
                    heights.push(h);
                }
            }
        }
        structures.push(export_structure(s, &heights, opts.elements)?);
    }
    let levels = export_levels(scenario)
        .map_err(|(p, e)| in_pair(scenario, p, e))?
        .into_iter()
        .map(|(pair, level)| RowLevel { pair, level })
        .collect();
    let pairs = (0..n - 1)
        .map(|p| ExportPair {
            index: p,
            between: [p, p + 1].map(|i| scenario.structures[i].name().to_string()),
            law: contacts[p].law.name(),
        })
        .collect();
    let ground = export_ground(scenario, &structures);
    Ok(RowExportModel {
        title: scenario.title.clone(),
        source: exported_by(),
        dt: opts.dt,
        duration,
        tolerance: NEWTON_TOLERANCE,
        only: opts.only,
        structures,
        levels,
        pairs,
        ground,
    })
}

/// The self-contained OpenSeesPy script of a row `scenario`: a header saying what it is and how
/// each structure and each pair's contact was mapped, the `MODEL` data, the pair's driver and
/// the row driver. `source` names the scenario file.
pub fn row_script(
    scenario: &Scenario,
    opts: &ExportOptions,
    source: &str,
) -> Result<String, ExportError> {
    let m = row_model(scenario, opts)?;
    let contacts = scenario
        .contacts()
        .zip(&m.pairs)
        .enumerate()
        .map(|(p, (c, pair))| {
            format!(
                "# contact[{}] \"{}\"–\"{}\" `{}`: {}\n",
                p + 1,
                one_line(&pair.between[0]),
                one_line(&pair.between[1]),
                c.law.name(),
                mapping_text(&c.law)
            )
        })
        .collect();
    let parts = ScriptParts {
        what: format!(
            "row \"{}\" ({}): {} structures, {} adjacent pairs",
            one_line(&scenario.title),
            one_line(source),
            m.structures.len(),
            m.pairs.len()
        ),
        prints: ROW_PRINTS,
        source: &m.source,
        dt: m.dt,
        duration: m.duration,
        structures: &m.structures,
        contacts,
        drivers: &[pair_driver_body(), ROW_DRIVER],
    };
    script_text(scenario, &m, parts)
}

/// The script of `scenario`, a pair's ([`super::script`], unchanged) or a row's
/// ([`row_script`]): what `pounding export opensees` writes.
pub fn any_script(
    scenario: &Scenario,
    opts: &ExportOptions,
    source: &str,
) -> Result<String, ExportError> {
    if scenario.is_row() {
        row_script(scenario, opts, source)
    } else {
        super::script(scenario, opts, source)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The pair's driver ends with its `main()` call, which a row's script leaves out; the
    /// row driver ends with its own.
    #[test]
    fn the_pair_driver_loses_only_its_main_call() {
        assert!(DRIVER.ends_with(PAIR_MAIN_CALL));
        assert_eq!(
            pair_driver_body().len() + PAIR_MAIN_CALL.len(),
            DRIVER.len()
        );
        assert!(pair_driver_body().contains("class Model:"));
        assert!(ROW_DRIVER.ends_with("if __name__ == \"__main__\":\n    row_main()\n"));
    }
}
