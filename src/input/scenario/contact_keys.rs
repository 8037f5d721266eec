//! `[contact]`: the law, its parameters and the contact levels, checked into a
//! [`super::ContactSpec`].

use toml::Spanned;

use crate::model::contact::{ContactLaw, HertzDampModel};
use crate::model::system::ContactLevel;

use super::RawContact;
use super::diagnostics::{Check, ScenarioError, quoted};
use super::{CONTACT_LAWS, ContactSpec, MIN_CONTACT_HEIGHT_FRACTION};

/// One contact table (`[contact]`, or one `[[contact]]` of a row) at byte `start` of the
/// file, its keys named as `{key}.law`, `{key}.level[j].gap`, …; `min_length` is the lower of
/// its two structures' heights, m.
pub(super) fn contact_table(
    c: &Check,
    r: &RawContact,
    start: usize,
    key: &str,
    min_length: f64,
    defaults: &mut Vec<String>,
) -> Result<ContactSpec, ScenarioError> {
    let k_ = |name: &str| format!("{key}.{name}");
    let near = Some(start);
    let law_name = r.law.as_ref().map_or("hertz", |l| l.get_ref().as_str());
    if r.law.is_none() {
        defaults.push(format!("{} = \"hertz\"", k_("law")));
    }
    let stiffness_unit = match law_name {
        "linear" | "kelvin" => "N/m",
        _ => "N/m^1.5",
    };
    let impulsive = law_name == "stereomechanical";
    let stiffness = match (&r.stiffness, impulsive) {
        (Some(k), true) => {
            return Err(c.invalid(
                k,
                &k_("stiffness"),
                "law `stereomechanical` is instantaneous and has no stiffness",
            ));
        }
        (None, true) => 0.0,
        (k, false) => c.positive(
            c.required(
                k,
                &k_("stiffness"),
                &format!("contact stiffness in {stiffness_unit}"),
                near,
            )?,
            &k_("stiffness"),
            stiffness_unit,
        )?,
    };
    let needs_e = matches!(
        law_name,
        "kelvin" | "hertzdamp" | "jankowski" | "stereomechanical"
    );
    let restitution = match (&r.restitution, needs_e) {
        (Some(e), true) if impulsive => {
            let x = *e.get_ref();
            if x.is_finite() && (0.0..=1.0).contains(&x) {
                x
            } else {
                return Err(c.invalid(
                    e,
                    &k_("restitution"),
                    "coefficient of restitution must be in [0, 1]",
                ));
            }
        }
        (Some(e), true) => c.restitution(e, &k_("restitution"))?,
        (None, true) => {
            return Err(c.missing(
                &k_("restitution"),
                &format!("law `{law_name}` needs a coefficient of restitution"),
                near,
            ));
        }
        (Some(e), false) => {
            return Err(c.invalid(
                e,
                &k_("restitution"),
                &format!(
                    "law `{law_name}` has no restitution parameter (it is used by kelvin, hertzdamp, jankowski, stereomechanical)"
                ),
            ));
        }
        (None, false) => 1.0,
    };
    if r.restitution.is_some() {
        c.usual(restitution, &k_("restitution"), "");
    }
    if let (Some(m), false) = (&r.damping_model, law_name == "hertzdamp") {
        return Err(c.invalid(
            m,
            &k_("damping_model"),
            "only law `hertzdamp` takes a damping model",
        ));
    }
    let law = match law_name {
        "hertz" => ContactLaw::Hertz { stiffness },
        "linear" => ContactLaw::Linear { stiffness },
        "kelvin" => ContactLaw::Kelvin {
            stiffness,
            restitution,
        },
        "jankowski" => ContactLaw::Jankowski {
            stiffness,
            restitution,
        },
        "stereomechanical" => ContactLaw::Stereomechanical { restitution },
        "hertzdamp" => {
            let model = match r.damping_model.as_ref().map(|m| m.get_ref().as_str()) {
                None | Some("lankarani-nikravesh") => HertzDampModel::LankaraniNikravesh,
                Some("hunt-crossley") => HertzDampModel::HuntCrossley,
                Some("ye-li-zhu") => HertzDampModel::YeLiZhu,
                Some(_) => {
                    let m = r.damping_model.as_ref().unwrap_or_else(|| unreachable!());
                    return Err(c.invalid(
                        m,
                        &k_("damping_model"),
                        "must be one of \"lankarani-nikravesh\", \"hunt-crossley\", \"ye-li-zhu\"",
                    ));
                }
            };
            ContactLaw::HertzDamp {
                stiffness,
                restitution,
                model,
            }
        }
        _ => {
            let l = r.law.as_ref().unwrap_or_else(|| unreachable!());
            return Err(c.invalid(
                l,
                &k_("law"),
                &format!("must be one of {}", quoted(CONTACT_LAWS)),
            ));
        }
    };
    // (near the base the structures barely move: the effective mass of a contact there grows
    // without bound, 1/φ(h)², and is infinite at h = 0)
    let lowest = min_length * MIN_CONTACT_HEIGHT_FRACTION;
    let height_reason = format!(
        "contact height must be in [{lowest}, {min_length}] m, i.e. [{MIN_CONTACT_HEIGHT_FRACTION} \
         min(L1, L2), min(L1, L2)] (no contact transfers anything at the base)"
    );
    let check_height = |h: &Spanned<f64>, key: &str| -> Result<f64, ScenarioError> {
        let x = *h.get_ref();
        if x.is_finite() && x >= lowest && x <= min_length * (1.0 + 1e-12) {
            Ok(x.min(min_length))
        } else {
            Err(c.invalid(h, key, &height_reason))
        }
    };
    let levels = match &r.level {
        None => {
            let gap = c.non_negative(
                c.required(&r.gap, &k_("gap"), "at-rest gap in m (≥ 0)", near)?,
                &k_("gap"),
                "m",
            )?;
            let height = match &r.height {
                Some(h) => check_height(h, &k_("height"))?,
                None => {
                    defaults.push(format!("{} = {min_length} (min(L1, L2))", k_("height")));
                    min_length
                }
            };
            vec![ContactLevel { height, gap }]
        }
        Some(levels) => {
            for (k, v) in [(&k_("gap"), &r.gap), (&k_("height"), &r.height)] {
                if let Some(v) = v {
                    return Err(c.invalid(
                        v,
                        k,
                        "with [[contact.level]] tables, give `height` and `gap` in each level instead",
                    ));
                }
            }
            if levels.is_empty() {
                return Err(c.missing(&k_("level"), "at least one [[contact.level]]", near));
            }
            let mut out = Vec::with_capacity(levels.len());
            for (i, lv) in levels.iter().enumerate() {
                let key = |k: &str| format!("{key}.level[{}].{k}", i + 1);
                let lnear = Some(lv.span().start);
                let l = lv.get_ref();
                let height = check_height(
                    c.required(&l.height, &key("height"), "contact height in m", lnear)?,
                    &key("height"),
                )?;
                let gap = c.non_negative(
                    c.required(&l.gap, &key("gap"), "at-rest gap in m (≥ 0)", lnear)?,
                    &key("gap"),
                    "m",
                )?;
                if out.iter().any(|o: &ContactLevel| o.height == height) {
                    return Err(c.invalid(
                        l.height.as_ref().unwrap_or_else(|| unreachable!()),
                        &key("height"),
                        "two contact levels at the same height",
                    ));
                }
                out.push(ContactLevel { height, gap });
            }
            out
        }
    };
    Ok(ContactSpec { law, levels })
}
