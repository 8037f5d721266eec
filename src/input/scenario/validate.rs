//! The raw scenario → the checked [`super::Scenario`]: every missing key in one message,
//! each table by its own module (`structure_keys`, `contact_keys`, `ground_keys`, `solver_keys`),
//! contact heights at floors, and the warnings of valid but unusual values.

use std::path::Path;

use crate::model::ground_motion::GroundMotion;
use crate::model::structure::{Damping, Stiffness, Structure};

use super::RawScenario;
use super::diagnostics::{Check, Ctx, Location, ScenarioError, quoted};
use super::floors;
use super::ground_keys::ground;
use super::plausibility::plausibility;
use super::ranges::{USUAL_DAMPING_RATIO, USUAL_STRUCTURE_PERIOD};
use super::row_keys::row_contacts;
use super::solver_keys::solver;
use super::structure_keys::structure;
use super::suite;
use super::{ContactSpec, DEFAULT_MODES, RecordCache, Scenario};

/// Every required key the file lacks (with its place and what is expected), before any value
/// is checked: so that one message lists them all.
pub(super) fn missing_keys(raw: &RawScenario, ctx: &Ctx) -> Vec<(Location, String, String)> {
    let mut out = Vec::new();
    let mut miss = |near: Option<usize>, key: String, expected: &str| {
        out.push((ctx.at(near), key, expected.to_string()));
    };
    match &raw.structure {
        None => miss(
            None,
            "structure".into(),
            "two [[structure]] tables (structure 1 on the left, 2 on the right)",
        ),
        Some(list) => {
            let near = Some(list.span().start);
            for (i, s) in list.get_ref().iter().enumerate().take(super::MAX_ROW) {
                let key = |k: &str| format!("structure[{}].{k}", i + 1);
                if s.kind.as_ref().is_some_and(|k| k.get_ref() != "cantilever") {
                    // a building with floors: its keys are checked by `floors`
                    continue;
                }
                if s.length.is_none() {
                    miss(near, key("length"), "height L in m");
                }
                if s.mass.is_none() {
                    miss(near, key("mass"), "total mass M in kg");
                }
                if s.period.is_none() && s.bending_stiffness.is_none() && s.tip_stiffness.is_none()
                {
                    miss(
                        near,
                        key("period"),
                        "one of `period` (s), `bending_stiffness` (N·m²) or `tip_stiffness` (N/m)",
                    );
                }
            }
        }
    }
    match &raw.contact {
        None => miss(
            None,
            "contact".into(),
            "a [contact] table with at least `stiffness` and `gap`",
        ),
        Some(c) => {
            for (key, r, at) in contact_tables(c) {
                let near = Some(at);
                let law = r.law.as_ref().map_or("hertz", |l| l.get_ref().as_str());
                if r.stiffness.is_none() && law != "stereomechanical" {
                    miss(near, format!("{key}.stiffness"), "contact stiffness");
                }
                if r.restitution.is_none()
                    && matches!(
                        law,
                        "kelvin" | "hertzdamp" | "jankowski" | "stereomechanical"
                    )
                {
                    miss(
                        near,
                        format!("{key}.restitution"),
                        "a coefficient of restitution for this law",
                    );
                }
                match &r.level {
                    None if r.gap.is_none() => {
                        miss(near, format!("{key}.gap"), "at-rest gap in m (≥ 0)")
                    }
                    None => {}
                    Some(levels) => {
                        for (i, l) in levels.iter().enumerate() {
                            let near = Some(l.span().start);
                            if l.get_ref().height.is_none() {
                                miss(
                                    near,
                                    format!("{key}.level[{}].height", i + 1),
                                    "contact height in m",
                                );
                            }
                            if l.get_ref().gap.is_none() {
                                miss(
                                    near,
                                    format!("{key}.level[{}].gap", i + 1),
                                    "at-rest gap in m (≥ 0)",
                                );
                            }
                        }
                    }
                }
            }
        }
    }
    match &raw.ground_motion {
        None => miss(
            None,
            "ground_motion".into(),
            "a [ground_motion] table (kind = \"harmonic\" with `pga` and `period`, or kind = \"record\" with `file`)",
        ),
        Some(g) => {
            let near = Some(g.span().start);
            let r = g.get_ref();
            match r.kind.as_ref().map(|k| k.get_ref().as_str()) {
                None => miss(
                    near,
                    "ground_motion.kind".into(),
                    "\"harmonic\", \"record\" or \"spectrum\"",
                ),
                Some("harmonic") => {
                    if r.pga.is_none() {
                        miss(
                            near,
                            "ground_motion.pga".into(),
                            "peak ground acceleration in g",
                        );
                    }
                    if r.period.is_none() {
                        miss(
                            near,
                            "ground_motion.period".into(),
                            "ground period T_g in s",
                        );
                    }
                }
                Some("record") if r.file.is_none() => {
                    miss(near, "ground_motion.file".into(), "the record file")
                }
                Some(_) => {}
            }
        }
    }
    out
}

/// Every contact table of the file with the name its keys take (`contact`, `contact[2]`) and
/// where it starts.
fn contact_tables(
    c: &toml::Spanned<super::row_keys::RawContacts>,
) -> Vec<(String, &super::RawContact, usize)> {
    match c.get_ref() {
        super::row_keys::RawContacts::One(r) => vec![("contact".into(), &**r, c.span().start)],
        super::row_keys::RawContacts::Many(list) => (list.iter().enumerate())
            .map(|(i, t)| (format!("contact[{}]", i + 1), t.get_ref(), t.span().start))
            .collect(),
    }
}

/// A building with floors touches only at its floors: every contact height must be one of
/// them (a cantilever may touch at any height up to its top). `contacts[p]` is the pair of
/// structures p and p + 1.
pub(super) fn floors_at_contact(
    c: &Check,
    raw: &RawScenario,
    structures: &[Structure],
    contacts: &[ContactSpec],
) -> Result<(), ScenarioError> {
    let Some(rc) = raw.contact.as_ref() else {
        return Ok(());
    };
    let tables = contact_tables(rc);
    for (p, contact) in contacts.iter().enumerate() {
        // the table of this pair: the one whose `between` names it, else the p-th
        let (name, table, start) = tables
            .iter()
            .find(|(_, t, _)| {
                t.between.as_ref().is_some_and(|b| {
                    let names = [p, p + 1].map(|i| structures[i].name());
                    b.get_ref()
                        .iter()
                        .all(|n| names.contains(&n.get_ref().as_str()))
                })
            })
            .or_else(|| tables.get(p))
            .map(|(n, t, s)| (n.as_str(), *t, *s))
            .unwrap_or(("contact", tables[0].1, tables[0].2));
        let levels = table.level.as_ref();
        for (k, lv) in contact.levels.iter().enumerate() {
            for (i, s) in structures.iter().enumerate().skip(p).take(2) {
                let Some(heights) = s.floor_heights() else {
                    continue;
                };
                if heights
                    .iter()
                    .any(|&h| crate::model::building::same_height(h, lv.height))
                {
                    continue;
                }
                let (key, at) = match levels.and_then(|l| l.get(k)) {
                    Some(l) => (
                        format!("{name}.level[{}].height", k + 1),
                        l.get_ref()
                            .height
                            .as_ref()
                            .map_or(l.span().start, |h| h.span().start),
                    ),
                    None => (
                        format!("{name}.height"),
                        table.height.as_ref().map_or(start, |h| h.span().start),
                    ),
                };
                let floors: Vec<String> = heights.iter().map(|h| format!("{h}")).collect();
                return Err(ScenarioError::Invalid {
                    at: c.ctx.at(Some(at)),
                    key,
                    value: format!("{} m", lv.height),
                    reason: format!(
                        "structure {} (\"{}\") has floors at {} m: a building with floors touches \
                         its neighbour only at a floor, so a contact height must be one of them",
                        i + 1,
                        s.name(),
                        floors.join(", ")
                    ),
                });
            }
        }
    }
    Ok(())
}

pub(super) fn validate(
    raw: RawScenario,
    ctx: &Ctx,
    base_dir: &Path,
    records: Option<&RecordCache>,
) -> Result<Scenario, ScenarioError> {
    let c = Check { ctx };
    let mut defaults = Vec::new();
    let mut structure_warnings = Vec::new();
    let structures = {
        let list = c.required(
            &raw.structure,
            "structure",
            "two [[structure]] tables (structure 1 on the left, 2 on the right)",
            None,
        )?;
        super::row_keys::check_count(&c, list.get_ref().len(), list.span().start)?;
        let start = list.span().start;
        list.get_ref()
            .iter()
            .enumerate()
            .map(|(i, s)| match floors::kind(&c, i, s)? {
                floors::Kind::Cantilever => structure(&c, i, s, start, &mut defaults),
                kind => floors::floor_structure(
                    &c,
                    i,
                    s,
                    kind,
                    start,
                    base_dir,
                    &mut defaults,
                    &mut structure_warnings,
                ),
            })
            .collect::<Result<Vec<Structure>, ScenarioError>>()?
    };
    let mut contacts = row_contacts(&c, raw.contact.as_ref(), &structures, &mut defaults)?;
    let suite = suite::suite(&c, &raw, base_dir, records)?;
    let ground_motion = match suite {
        Some(_) => GroundMotion::None,
        None => ground(&c, raw.ground_motion.as_ref(), base_dir, records)?,
    };
    let from = suite::defaults_ground(suite.as_ref(), &ground_motion);
    let yielding = structures.iter().any(|s| s.hysteresis().is_some());
    let (solver, output_interval) = solver(&c, raw.solver.as_ref(), from, yielding, &mut defaults)?;
    suite::note_defaults(suite.as_ref(), &mut defaults);
    floors_at_contact(&c, &raw, &structures, &contacts)?;
    // each key within its range can still combine into a structure no run can mean (a huge
    // mass on a thread-like EI): its first period must be within [1e-3, 1e4] s
    for (i, st) in structures.iter().enumerate() {
        let t1 = st.modal().periods().first().copied().unwrap_or(f64::NAN);
        if !(1e-3..=1e4).contains(&t1) {
            return Err(ScenarioError::Invalid {
                at: c.ctx.at(raw.structure.as_ref().map(|l| l.span().start)),
                key: format!("structure[{}]", i + 1),
                value: format!("first-mode period {t1:e} s"),
                reason: "the mass, height and stiffness give a first-mode period outside \
                         [1e-3, 1e4] s: check their units"
                    .into(),
            });
        }
    }
    let mut warnings = structure_warnings;
    for contact in &contacts {
        warnings.extend(plausibility(contact, &ground_motion));
    }
    warnings.extend(derived_warnings(&structures));
    let design = crate::input::scenario::design::validate(
        &c,
        raw.ground_motion.as_ref(),
        raw.separation.as_ref(),
        base_dir,
        &mut defaults,
    )?;
    let floor_stations = match raw
        .output
        .as_ref()
        .and_then(|o| o.get_ref().floor_stations.as_ref())
    {
        None => crate::recording::stations::FloorStations::default(),
        Some(v) => {
            crate::recording::stations::FloorStations::from_name(v.get_ref()).ok_or_else(|| {
                c.invalid(
                    v,
                    "output.floor_stations",
                    &format!(
                        "must be one of {}",
                        quoted(&crate::recording::stations::FloorStations::NAMES)
                    ),
                )
            })?
        }
    };
    // (after `design`, which may warn too: a_g probably in g)
    warnings.extend(ctx.warnings.take());
    let scenario = Scenario {
        floor_stations,
        title: raw.title.unwrap_or_else(|| ctx.file.to_string()),
        structures,
        contact: contacts.remove(0),
        row_contacts: contacts,
        ground_motion,
        solver,
        output_interval,
        defaults_applied: defaults,
        warnings,
        design,
        suite,
    };
    // stability: needs the modal model (docs/model.md §2.9)
    if let Err(e) = solver.check_stability(&scenario.system().without_contact()) {
        let dt = raw
            .solver
            .as_ref()
            .and_then(|s| s.get_ref().dt.as_ref())
            .map(|d| d.span().start);
        return Err(ScenarioError::Invalid {
            at: ctx.at(dt),
            key: "solver.dt".into(),
            value: solver.dt.to_string(),
            reason: if scenario
                .defaults_applied
                .iter()
                .any(|d| d.contains(".modes = "))
            {
                format!(
                    "{e}. `modes` was not given for every structure: the default of {DEFAULT_MODES} \
                     modes was used; give `modes` to keep fewer, or omit `method` for the \
                     adaptive default, stable with any number of modes"
                )
            } else {
                e.to_string()
            },
        });
    }
    Ok(scenario)
}

/// Warnings about what several keys give together: the first-mode period of a structure given
/// by its stiffness (not by `period`), the first-mode damping ratio of physical damping
/// (`strain_rate_damping`, `air_damping`), each outside its usual band ([`usual_range`]).
pub(super) fn derived_warnings(structures: &[Structure]) -> Vec<String> {
    let mut out = Vec::new();
    for (i, st) in structures.iter().enumerate() {
        let (by_period, physical) = match st {
            Structure::Cantilever(c) => (
                matches!(c.stiffness, Stiffness::Period(_)),
                matches!(c.damping, Damping::Physical { .. }),
            ),
            Structure::Floors(f) => (
                matches!(f.kind, crate::model::structure::FloorKind::Modal(_)),
                false,
            ),
        };
        let modal = st.modal();
        let (lo, hi) = USUAL_STRUCTURE_PERIOD;
        if let Some(&t1) = modal.periods().first()
            && !by_period
            && !(lo..=hi).contains(&t1)
        {
            out.push(format!(
                "structure {} (\"{}\"): its stiffness, mass and height give a first-mode period of \
                 {t1:.4e} s, outside the usual [{lo}, {hi}] s of buildings; check their units",
                i + 1,
                st.name()
            ));
        }
        let (lo, hi) = USUAL_DAMPING_RATIO;
        if let Some(&z1) = modal.zeta.first()
            && physical
            && !(lo..=hi).contains(&z1)
        {
            out.push(format!(
                "structure {} (\"{}\"): strain_rate_damping and air_damping give a first-mode \
                 damping ratio of {z1:.4}, outside the usual [{lo}, {hi}] of buildings; check \
                 their units (c_s/E in s, c_a in N·s/m²)",
                i + 1,
                st.name()
            ));
        }
    }
    out
}
