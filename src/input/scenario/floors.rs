//! `[[structure]]` tables of buildings with floors (issue 11): `kind = "shear-building"` and
//! `kind = "modal"` (the engineer's own modes, inline or from a CSV file), checked into a
//! [`Structure::Floors`]. The cantilever keys stay in the parent module.

use std::path::Path;

use toml::Spanned;

use super::DEFAULT_DAMPING_RATIO;
use super::RawStructure;
use super::diagnostics::{Check, ScenarioError, list_error};
use crate::model::building::{
    EngineerModes, FloorDamping, Floors, MAX_ORTHOGONALITY_ERROR, ShearBuilding,
    WARN_ORTHOGONALITY_ERROR,
};
use crate::model::structure::{FloorKind, FloorStructure, Structure};

/// Most floors a building may have (each is a degree of freedom of the eigenproblem).
pub const MAX_FLOORS: usize = 500;

/// The kinds of `[[structure]]`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Kind {
    Cantilever,
    ShearBuilding,
    Modal,
}

const CANTILEVER_KEYS: &[&str] = &[
    "length",
    "mass",
    "period",
    "bending_stiffness",
    "tip_stiffness",
    "strain_rate_damping",
    "air_damping",
];

/// The keys of `s` that are given, with where (only those that belong to one kind).
fn given(s: &RawStructure) -> Vec<(&'static str, usize)> {
    macro_rules! spans {
        ($($k:ident),*) => {
            [$((stringify!($k), s.$k.as_ref().map(|v| v.span().start))),*]
        };
    }
    spans!(
        length,
        mass,
        period,
        bending_stiffness,
        tip_stiffness,
        strain_rate_damping,
        air_damping,
        floor_heights,
        floor_masses,
        storey_stiffnesses,
        storeys,
        storey_height,
        floor_mass,
        storey_stiffness,
        rayleigh,
        periods,
        mode_shapes,
        modes_file,
        hysteresis
    )
    .into_iter()
    .filter_map(|(k, at)| at.map(|a| (k, a)))
    .collect()
}

/// Refuses the first of `keys` that `s` gives (`value`: how it is given, `reason`: why not).
fn refuse_any(
    c: &Check,
    i: usize,
    s: &RawStructure,
    keys: &[&str],
    value: &str,
    reason: &str,
) -> Result<(), ScenarioError> {
    match given(s).into_iter().find(|(k, _)| keys.contains(k)) {
        Some((k, at)) => Err(ScenarioError::Invalid {
            at: c.ctx.at(Some(at)),
            key: format!("structure[{}].{k}", i + 1),
            value: value.into(),
            reason: reason.into(),
        }),
        None => Ok(()),
    }
}

/// The keys each kind accepts besides `kind`, `name`, `modes`, `damping_ratio`.
fn accepted(kind: Kind) -> &'static [&'static str] {
    match kind {
        Kind::Cantilever => CANTILEVER_KEYS,
        Kind::ShearBuilding => &[
            "floor_heights",
            "floor_masses",
            "storey_stiffnesses",
            "storeys",
            "storey_height",
            "floor_mass",
            "storey_stiffness",
            "rayleigh",
            "hysteresis",
        ],
        Kind::Modal => &[
            "floor_heights",
            "floor_masses",
            "rayleigh",
            "periods",
            "mode_shapes",
            "modes_file",
        ],
    }
}

/// The structure's kind, and no key of another kind.
pub(super) fn kind(c: &Check, i: usize, s: &RawStructure) -> Result<Kind, ScenarioError> {
    let key = |k: &str| format!("structure[{}].{k}", i + 1);
    let kind = match &s.kind {
        None => Kind::Cantilever,
        Some(k) => match k.get_ref().as_str() {
            "cantilever" => Kind::Cantilever,
            "shear-building" => Kind::ShearBuilding,
            "modal" => Kind::Modal,
            _ => {
                return Err(c.invalid(
                    k,
                    &key("kind"),
                    "must be \"cantilever\" (the default), \"shear-building\" or \"modal\"",
                ));
            }
        },
    };
    let ok = accepted(kind);
    if let Some((k, at)) = given(s).into_iter().find(|(k, _)| !ok.contains(k)) {
        let name = match kind {
            Kind::Cantilever => "cantilever",
            Kind::ShearBuilding => "shear-building",
            Kind::Modal => "modal",
        };
        return Err(ScenarioError::Invalid {
            at: c.ctx.at(Some(at)),
            key: key(k),
            value: "given".into(),
            reason: format!(
                "is not a key of kind = \"{name}\" (its keys: {}, and name, modes, damping_ratio{}); \
                 set `kind` to the structure you mean",
                ok.join(", "),
                if kind == Kind::Cantilever {
                    ""
                } else {
                    ", rayleigh"
                }
            ),
        });
    }
    Ok(kind)
}

/// A list of finite numbers > 0 (strictly increasing when `increasing`), 1 … [`MAX_FLOORS`]
/// long.
fn positive_list(
    c: &Check,
    v: &Spanned<Vec<f64>>,
    key: &str,
    unit: &str,
    increasing: bool,
) -> Result<Vec<f64>, ScenarioError> {
    let x = v.get_ref();
    if x.is_empty() || x.len() > MAX_FLOORS {
        return Err(list_error(
            c,
            v,
            key,
            format!("must list 1 to {MAX_FLOORS} values ({unit})"),
        ));
    }
    let range = super::ranges::physical_range(key);
    let mut last = 0.0;
    for (j, &y) in x.iter().enumerate() {
        if let Some((lo, hi, what)) = range.filter(|(lo, hi, _)| !(*lo..=*hi).contains(&y)) {
            return Err(list_error(
                c,
                v,
                key,
                format!(
                    "value {} is {y}: each must be in [{lo:e}, {hi:e}] {unit} ({what})",
                    j + 1
                ),
            ));
        }
        if !(y.is_finite() && y > 0.0) {
            return Err(list_error(
                c,
                v,
                key,
                format!(
                    "value {} is {y}: each must be a finite number > 0 ({unit})",
                    j + 1
                ),
            ));
        }
        c.usual(y, key, unit);
        if increasing && y <= last {
            return Err(list_error(
                c,
                v,
                key,
                format!(
                    "value {} ({y}) is not above the one before ({last}): heights must increase \
                     from the lowest floor up ({unit})",
                    j + 1
                ),
            ));
        }
        last = y;
    }
    Ok(x.clone())
}

/// A whole number in 1..=max from a TOML value.
fn whole(
    c: &Check,
    v: &Spanned<toml::Value>,
    key: &str,
    max: usize,
) -> Result<usize, ScenarioError> {
    match v.get_ref() {
        toml::Value::Integer(n) if *n >= 1 && (*n as u64) <= max as u64 => Ok(*n as usize),
        other => Err(ScenarioError::Invalid {
            at: c.ctx.at(Some(v.span().start)),
            key: key.to_string(),
            value: other.to_string(),
            reason: format!("must be a whole number from 1 to {max}"),
        }),
    }
}

/// The floors of a shear building: explicit lists, or the uniform shorthand.
fn shear_floors(
    c: &Check,
    i: usize,
    s: &RawStructure,
    near: Option<usize>,
) -> Result<(Floors, Vec<f64>), ScenarioError> {
    let key = |k: &str| format!("structure[{}].{k}", i + 1);
    if let Some(n) = &s.storeys {
        refuse_any(
            c,
            i,
            s,
            &["floor_heights", "floor_masses", "storey_stiffnesses"],
            "given with `storeys`",
            "give either the lists (floor_heights, floor_masses, \
                         storey_stiffnesses) or the uniform shorthand (storeys, storey_height, \
                         floor_mass, storey_stiffness), not both",
        )?;
        let n = whole(c, n, &key("storeys"), MAX_FLOORS)?;
        c.usual(n as f64, &key("storeys"), "");
        let h = c.positive(
            c.required(
                &s.storey_height,
                &key("storey_height"),
                "storey height in m",
                near,
            )?,
            &key("storey_height"),
            "m",
        )?;
        let m = c.positive(
            c.required(
                &s.floor_mass,
                &key("floor_mass"),
                "mass of each floor in kg",
                near,
            )?,
            &key("floor_mass"),
            "kg",
        )?;
        let k = c.positive(
            c.required(
                &s.storey_stiffness,
                &key("storey_stiffness"),
                "lateral stiffness of each storey in N/m",
                near,
            )?,
            &key("storey_stiffness"),
            "N/m",
        )?;
        let floors = Floors {
            heights: (1..=n).map(|j| j as f64 * h).collect(),
            masses: vec![m; n],
        };
        return Ok((floors, vec![k; n]));
    }
    refuse_any(
        c,
        i,
        s,
        &["storey_height", "floor_mass", "storey_stiffness"],
        "given without `storeys`",
        "the uniform shorthand needs `storeys` (and storey_height, floor_mass, \
                     storey_stiffness); or give the lists floor_heights, floor_masses, \
                     storey_stiffnesses",
    )?;
    let floors = floors_lists(c, i, s, near)?;
    let k = c.required(
        &s.storey_stiffnesses,
        &key("storey_stiffnesses"),
        "one lateral stiffness per storey in N/m (storey j joins floor j−1, or the base, to floor j)",
        near,
    )?;
    let ks = positive_list(c, k, &key("storey_stiffnesses"), "N/m", false)?;
    if ks.len() != floors.heights.len() {
        return Err(list_error(
            c,
            k,
            &key("storey_stiffnesses"),
            format!(
                "{} values for {} floors: give one stiffness per storey",
                ks.len(),
                floors.heights.len()
            ),
        ));
    }
    Ok((floors, ks))
}

/// `floor_heights` and `floor_masses`, of the same length.
fn floors_lists(
    c: &Check,
    i: usize,
    s: &RawStructure,
    near: Option<usize>,
) -> Result<Floors, ScenarioError> {
    let key = |k: &str| format!("structure[{}].{k}", i + 1);
    let h = c.required(
        &s.floor_heights,
        &key("floor_heights"),
        "the floor heights above the base in m, strictly increasing",
        near,
    )?;
    let heights = positive_list(c, h, &key("floor_heights"), "m", true)?;
    let m = c.required(
        &s.floor_masses,
        &key("floor_masses"),
        "one mass per floor in kg",
        near,
    )?;
    let masses = positive_list(c, m, &key("floor_masses"), "kg", false)?;
    if masses.len() != heights.len() {
        return Err(list_error(
            c,
            m,
            &key("floor_masses"),
            format!(
                "{} masses for {} floor heights: give one mass per floor",
                masses.len(),
                heights.len()
            ),
        ));
    }
    Ok(Floors { heights, masses })
}

/// The engineer's modes from a CSV file: a header row, then one row per floor with
/// `height, mass, mode_1, mode_2, …` (comma, semicolon or whitespace separated).
fn read_modes_file(
    c: &Check,
    v: &Spanned<String>,
    key: &str,
    base_dir: &Path,
) -> Result<(Floors, Vec<Vec<f64>>), ScenarioError> {
    let path = base_dir.join(v.get_ref());
    let bad = |reason: String| c.invalid(v, key, &reason);
    let meta = std::fs::metadata(&path)
        .map_err(|e| bad(format!("cannot read {}: {e}", path.display())))?;
    if !meta.is_file() {
        return Err(bad(format!("{} is not a regular file", path.display())));
    }
    if meta.len() > 64 << 20 {
        return Err(bad(format!(
            "{} is {} bytes: a table of floor modes is at most 64 MiB",
            path.display(),
            meta.len()
        )));
    }
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(true)
        .flexible(false)
        .trim(csv::Trim::All)
        .comment(Some(b'#'))
        .from_path(&path)
        .map_err(|e| bad(format!("cannot read {}: {e}", path.display())))?;
    let headers = reader
        .headers()
        .map_err(|e| bad(format!("{}: {e}", path.display())))?
        .clone();
    let cols: Vec<String> = headers.iter().map(|h| h.to_ascii_lowercase()).collect();
    if cols.len() < 3 || cols[0] != "height" || cols[1] != "mass" {
        return Err(bad(format!(
            "{}: the header must be `height, mass, mode_1, mode_2, …` (found `{}`)",
            path.display(),
            headers.iter().collect::<Vec<_>>().join(", ")
        )));
    }
    let n_modes = cols.len() - 2;
    let (mut heights, mut masses) = (Vec::new(), Vec::new());
    let mut shapes = vec![Vec::new(); n_modes];
    for (r, rec) in reader.records().enumerate() {
        let line = r + 2;
        let rec = rec.map_err(|e| bad(format!("{}, line {line}: {e}", path.display())))?;
        if heights.len() >= MAX_FLOORS {
            return Err(bad(format!(
                "{}: more than {MAX_FLOORS} floors",
                path.display()
            )));
        }
        let nums: Result<Vec<f64>, _> = rec.iter().map(|x| x.parse::<f64>()).collect();
        let nums = nums.map_err(|e| {
            bad(format!(
                "{}, line {line}: not a number ({e})",
                path.display()
            ))
        })?;
        if let Some(x) = nums.iter().find(|x| !x.is_finite()) {
            return Err(bad(format!(
                "{}, line {line}: {x} is not finite",
                path.display()
            )));
        }
        heights.push(nums[0]);
        masses.push(nums[1]);
        for (m, x) in nums[2..].iter().enumerate() {
            shapes[m].push(*x);
        }
    }
    if heights.is_empty() {
        return Err(bad(format!("{}: no floor rows", path.display())));
    }
    Ok((Floors { heights, masses }, shapes))
}

/// The damping of a building: one ratio (or one per mode kept), or Rayleigh.
fn floor_damping(
    c: &Check,
    i: usize,
    s: &RawStructure,
    modes: usize,
    defaults: &mut Vec<String>,
) -> Result<FloorDamping, ScenarioError> {
    let key = |k: &str| format!("structure[{}].{k}", i + 1);
    match (&s.damping_ratio, &s.rayleigh) {
        (Some(_), Some(r)) => Err(ScenarioError::Invalid {
            at: c.ctx.at(Some(r.span().start)),
            key: key("rayleigh"),
            value: "given with damping_ratio".into(),
            reason: "give either `damping_ratio` (modal) or `rayleigh`, not both".into(),
        }),
        (None, None) => {
            defaults.push(format!(
                "{} = {DEFAULT_DAMPING_RATIO}",
                key("damping_ratio")
            ));
            Ok(FloorDamping::Modal(vec![DEFAULT_DAMPING_RATIO]))
        }
        (Some(z), None) => {
            let values = match z.get_ref() {
                super::RawZeta::One(v) => vec![*v],
                super::RawZeta::Many(v) => v.clone(),
            };
            if values.len() != 1 && values.len() != modes {
                return Err(ScenarioError::Invalid {
                    at: c.ctx.at(Some(z.span().start)),
                    key: key("damping_ratio"),
                    value: format!("a list of {}", values.len()),
                    reason: format!(
                        "give one ratio, or a list of exactly {modes} (one per mode kept)"
                    ),
                });
            }
            if let Some(bad) = values
                .iter()
                .find(|v| !(v.is_finite() && (0.0..1.0).contains(*v)))
            {
                return Err(ScenarioError::Invalid {
                    at: c.ctx.at(Some(z.span().start)),
                    key: key("damping_ratio"),
                    value: bad.to_string(),
                    reason: "damping ratios must be in [0, 1)".into(),
                });
            }
            for v in &values {
                c.usual(*v, &key("damping_ratio"), "");
            }
            Ok(FloorDamping::Modal(values))
        }
        (None, Some(r)) => {
            let near = Some(r.span().start);
            let rr = r.get_ref();
            let z = c.required(
                &rr.damping_ratio,
                &key("rayleigh.damping_ratio"),
                "the damping ratio at the two modes",
                near,
            )?;
            let ratio = *z.get_ref();
            if !(ratio.is_finite() && ratio > 0.0 && ratio < 1.0) {
                return Err(c.invalid(z, &key("rayleigh.damping_ratio"), "must be in (0, 1)"));
            }
            c.usual(ratio, &key("rayleigh.damping_ratio"), "");
            let m = c.required(
                &rr.modes,
                &key("rayleigh.modes"),
                "the two modes (1-based) where the ratio holds, e.g. [1, 3]",
                near,
            )?;
            match m.get_ref().as_slice() {
                [a, b] if *a >= 1 && *b >= 1 && a != b && *a <= 1000 && *b <= 1000 => {
                    Ok(FloorDamping::Rayleigh {
                        ratio,
                        modes: [*a as usize, *b as usize],
                    })
                }
                _ => Err(list_error(
                    c,
                    m,
                    &key("rayleigh.modes"),
                    "must be two different mode numbers (1-based), e.g. [1, 3]".into(),
                )),
            }
        }
    }
}

/// A `[[structure]]` of kind `shear-building` or `modal`, checked; the defaults it used go to
/// `defaults`, doubts about the engineer's modes to `warnings`.
#[allow(clippy::too_many_arguments)]
pub(super) fn floor_structure(
    c: &Check,
    i: usize,
    s: &RawStructure,
    kind: Kind,
    table_start: usize,
    base_dir: &Path,
    defaults: &mut Vec<String>,
    warnings: &mut Vec<String>,
) -> Result<Structure, ScenarioError> {
    let key = |k: &str| format!("structure[{}].{k}", i + 1);
    let near = Some(table_start);
    let name = s
        .name
        .clone()
        .unwrap_or_else(|| format!("structure {}", i + 1));
    // the number of modes the building has, before `modes` is checked against it
    let (input, available) = match kind {
        Kind::ShearBuilding => {
            let (floors, k) = shear_floors(c, i, s, near)?;
            let n = floors.heights.len();
            (Ok((floors, k)), n)
        }
        _ => {
            let (floors, periods, shapes) = match &s.modes_file {
                Some(f) => {
                    refuse_any(
                        c,
                        i,
                        s,
                        &["floor_heights", "floor_masses", "mode_shapes"],
                        "given with modes_file",
                        "`modes_file` holds the heights, masses and shapes: give \
                                     either it or the inline lists",
                    )?;
                    let (floors, shapes) = read_modes_file(c, f, &key("modes_file"), base_dir)?;
                    let p = c.required(
                        &s.periods,
                        &key("periods"),
                        "one period per mode in s",
                        near,
                    )?;
                    (floors, p, shapes)
                }
                None => {
                    let floors = floors_lists(c, i, s, near)?;
                    let p = c.required(
                        &s.periods,
                        &key("periods"),
                        "one period per mode in s",
                        near,
                    )?;
                    let sh = c.required(
                        &s.mode_shapes,
                        &key("mode_shapes"),
                        "one list per mode with a value per floor (any normalisation)",
                        near,
                    )?;
                    (floors, p, sh.get_ref().clone())
                }
            };
            let periods = positive_list(c, periods, &key("periods"), "s", false)?;
            if shapes.len() != periods.len() {
                return Err(ScenarioError::Invalid {
                    at: c.ctx.at(Some(
                        s.periods.as_ref().map_or(table_start, |p| p.span().start),
                    )),
                    key: key("periods"),
                    value: format!("{} periods", periods.len()),
                    reason: format!(
                        "{} mode shapes are given: one period per mode",
                        shapes.len()
                    ),
                });
            }
            let n = periods.len();
            (Err((floors, periods, shapes)), n)
        }
    };
    let modes = match &s.modes {
        None => {
            defaults.push(format!("{} = {available} (every mode)", key("modes")));
            available
        }
        Some(v) => whole(c, v, &key("modes"), available)?,
    };
    let damping = floor_damping(c, i, s, modes, defaults)?;
    let floor_kind = match input {
        Ok((floors, storey_stiffnesses)) => FloorKind::ShearBuilding(ShearBuilding {
            floors,
            storey_stiffnesses,
            modes,
            damping,
        }),
        Err((floors, periods, shapes)) => FloorKind::Modal(EngineerModes {
            floors,
            periods,
            shapes,
            modes,
            damping,
        }),
    };
    if let FloorKind::Modal(e) = &floor_kind {
        // say clearly how far from mass-orthogonal the engineer's shapes are
        let n = e.normalised().map_err(|err| ScenarioError::Invalid {
            at: c.ctx.at(near),
            key: key("mode_shapes"),
            value: "the modes given".into(),
            reason: err.to_string(),
        })?;
        if n.orthogonality_error > WARN_ORTHOGONALITY_ERROR
            && n.orthogonality_error <= MAX_ORTHOGONALITY_ERROR
        {
            warnings.push(format!(
                "{}: modes {} and {} are orthogonal with the floor masses only to {:.3} \
                 (φᵀMφ of the mass-normalised shapes; accepted up to {MAX_ORTHOGONALITY_ERROR}): \
                 check that the shapes and the masses come from the same model and direction",
                key("mode_shapes"),
                n.worst_pair.0,
                n.worst_pair.1,
                n.orthogonality_error
            ));
        }
    }
    let mut fs = FloorStructure::new(name, floor_kind).map_err(|err| ScenarioError::Invalid {
        at: c.ctx.at(near),
        key: format!("structure[{}]", i + 1),
        value: "the building given".into(),
        reason: err.to_string(),
    })?;
    if let (Some(h), FloorKind::ShearBuilding(b)) = (&s.hysteresis, &fs.kind) {
        fs.hysteresis = Some(super::hysteresis::bouc_wen(
            c,
            i,
            h,
            &b.storey_stiffnesses,
            &b.floors.heights,
            defaults,
        )?);
    }
    Ok(Structure::Floors(Box::new(fs)))
}
