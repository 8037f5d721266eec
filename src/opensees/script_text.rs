//! The exported script's text: a header saying what it is and how the scenario was mapped,
//! the `MODEL` data, the driver(s). A pair's script ([`script`]) and a row's
//! ([`super::row::row_script`]) are written by the same [`script_text`], from the parts in
//! which they differ ([`ScriptParts`]).

use serde::Serialize;

use super::{
    BOUC_WEN_MAPPING, DRIVER, ExportError, ExportOptions, ExportStructure, TESTED_OPENSEESPY,
    damping_notes, mapping_text, model,
};
use crate::input::scenario::Scenario;

/// What a pair's script says it prints.
const PAIR_PRINTS: &str = "# prints JSON with the headline numbers of pounding's summary.json (peaks at the contact\n\
     # heights and at every floor, every storey's peak drift and storey force, a yielding\n\
     # storey's residual drift and hysteretic energy, peak force, impacts, required separation).\n#\n";

/// The parts in which a pair's script and a row's differ.
pub(super) struct ScriptParts<'a> {
    /// What is modelled, the header's second line: `scenario "title" (file)` or a row's.
    pub what: String,
    /// What the script prints, as comment lines (each ending in a newline).
    pub prints: &'a str,
    /// What wrote the model (`pounding` and its version), the analysis step and the simulated
    /// time, s.
    pub source: &'a str,
    /// See `source`.
    pub dt: f64,
    /// See `source`.
    pub duration: f64,
    /// The exported structures, in order.
    pub structures: &'a [ExportStructure],
    /// The header's line for each pair's contact law (each ending in a newline).
    pub contacts: Vec<String>,
    /// The drivers appended after the `MODEL` data, in order.
    pub drivers: &'a [&'a str],
}

/// A script's text: the header (what it models and how to run it, what it prints, the step, a
/// line per structure and per contact, the damping notes, the yielding storeys' mapping), the
/// `MODEL` literal of `model`, the drivers.
pub(super) fn script_text(
    scenario: &Scenario,
    model: &impl Serialize,
    parts: ScriptParts<'_>,
) -> Result<String, ExportError> {
    let json = serde_json::to_string(model)
        .map_err(|e| ExportError::Option(format!("could not serialise the model: {e}")))?;
    let drivers: usize = parts.drivers.iter().map(|d| d.len()).sum();
    let mut out = String::with_capacity(json.len() + drivers + 8192);
    out.push_str("#!/usr/bin/env python3\n");
    out.push_str(&format!(
        "# OpenSeesPy model of the pounding {},\n",
        parts.what
    ));
    out.push_str(&format!(
        "# written by `pounding export opensees` ({}). Needs openseespy (tested with {}):\n",
        parts.source, TESTED_OPENSEESPY
    ));
    out.push_str(&format!(
        "#   pip install openseespy=={TESTED_OPENSEESPY}\n#   python3 model.py [--json out.json] [--only contact|free] [--dt DT] [--duration T]\n"
    ));
    out.push_str(parts.prints);
    out.push_str(&format!(
        "# OpenSees step dt = {} s over {} s; Newmark average acceleration, Newton.\n",
        parts.dt, parts.duration
    ));
    for (s, st) in parts.structures.iter().enumerate() {
        out.push_str(&structure_line(s, st));
    }
    for c in &parts.contacts {
        out.push_str(c);
    }
    for n in damping_notes(scenario) {
        out.push_str(&format!("# damping: {}\n", one_line(&n)));
    }
    if parts.structures.iter().any(|s| s.bouc_wen.is_some()) {
        out.push_str(&format!("# yielding {BOUC_WEN_MAPPING}\n"));
    }
    out.push_str("import json\n\nMODEL = json.loads(r'''");
    out.push_str(&json);
    out.push_str("''')\n\n");
    for d in parts.drivers {
        out.push_str(d);
    }
    Ok(out)
}

/// The self-contained OpenSeesPy script of `scenario`: a header saying what it is and how the
/// scenario was mapped, the `MODEL` data, the driver. `source` names the scenario file.
pub fn script(
    scenario: &Scenario,
    opts: &ExportOptions,
    source: &str,
) -> Result<String, ExportError> {
    let m = model(scenario, opts)?;
    let law = &scenario.contact.law;
    let parts = ScriptParts {
        what: format!(
            "scenario \"{}\" ({})",
            one_line(&scenario.title),
            one_line(source)
        ),
        prints: PAIR_PRINTS,
        source: &m.source,
        dt: m.dt,
        duration: m.duration,
        structures: &m.structures,
        contacts: vec![format!(
            "# contact `{}`: {}\n",
            law.name(),
            mapping_text(law)
        )],
        drivers: &[DRIVER],
    };
    script_text(scenario, &m, parts)
}

/// The header line of structure `s` (0-based) of the script.
fn structure_line(s: usize, st: &ExportStructure) -> String {
    format!(
        "# structure {} ({}): {}\n",
        s + 1,
        one_line(&st.name),
        match st.kind {
            "cantilever" => format!(
                "{} elasticBeamColumn elements, EI = {:e} N·m², m = {:e} kg/m, consistent mass",
                st.node_heights.len() - 1,
                st.bending_stiffness.unwrap_or(0.0),
                st.mass_per_length.unwrap_or(0.0)
            ),
            _ => format!(
                "shear building, {} floors (nodal masses, twoNodeLink storey springs{})",
                st.node_heights.len() - 1,
                if st.bouc_wen.is_some() {
                    ", BoucWen: yielding"
                } else {
                    ""
                }
            ),
        }
    )
}

/// `text` on one line (for comments).
pub(super) fn one_line(text: &str) -> String {
    text.replace(['\n', '\r'], " ")
}
