//! The `hysteresis` table of a shear building (issue 16): the Bouc–Wen keys, checked with
//! file:line:col, key and range into a [`BoucWen`].

use toml::Spanned;

use super::diagnostics::{Check, ScenarioError, list_error};
use crate::model::bouc_wen::{BoucWen, DEFAULT_BETA, DEFAULT_EXPONENT, DEFAULT_GAMMA};

/// `hysteresis = { model = "bouc-wen", … }` of a shear building (issue 16), checked against its
/// storeys (`k`: the initial storey stiffnesses, N/m).
pub(super) fn bouc_wen(
    c: &Check,
    i: usize,
    h: &Spanned<super::RawHysteresis>,
    k: &[f64],
    heights: &[f64],
    defaults: &mut Vec<String>,
) -> Result<BoucWen, ScenarioError> {
    let key = |k: &str| format!("structure[{}].hysteresis.{k}", i + 1);
    let near = Some(h.span().start);
    let r = h.get_ref();
    match &r.model {
        None => defaults.push(format!("{} = \"bouc-wen\"", key("model"))),
        Some(m) if m.get_ref() == "bouc-wen" => {}
        Some(m) => {
            return Err(c.invalid(
                m,
                &key("model"),
                "must be \"bouc-wen\" (the smooth Bouc–Wen storey, the one hysteretic model)",
            ));
        }
    }
    let storeys = k.len();
    // one value for every storey, or a list of one per storey
    let per_storey = |v: &Spanned<super::RawZeta>, name: &str, unit: &str| {
        let values = match v.get_ref() {
            super::RawZeta::One(x) => vec![*x; storeys],
            super::RawZeta::Many(x) => x.clone(),
        };
        if values.len() != storeys {
            return Err(list_error(
                c,
                v,
                &key(name),
                format!(
                    "{} values for {storeys} storeys: give one value for every storey, or a list \
                     of one per storey (lowest first)",
                    values.len()
                ),
            ));
        }
        let (lo, hi, what) =
            super::ranges::physical_range(name).unwrap_or((0.0, f64::MAX, "a value"));
        for (j, &y) in values.iter().enumerate() {
            if !(y.is_finite() && y > 0.0 && (lo..=hi).contains(&y)) {
                return Err(list_error(
                    c,
                    v,
                    &key(name),
                    format!(
                        "storey {} has {y}: each must be in [{lo:e}, {hi:e}] {unit} ({what})",
                        j + 1
                    ),
                ));
            }
        }
        Ok(values)
    };
    let yield_drifts = match (&r.yield_drifts, &r.yield_forces) {
        (Some(_), Some(f)) => {
            return Err(ScenarioError::Invalid {
                at: c.ctx.at(Some(f.span().start)),
                key: key("yield_forces"),
                value: "given with yield_drifts".into(),
                reason: "give either `yield_drifts` (m) or `yield_forces` (N, = k·d_y), not both"
                    .into(),
            });
        }
        (Some(d), None) => per_storey(d, "yield_drifts", "m")?,
        (None, Some(f)) => {
            let forces = per_storey(f, "yield_forces", "N")?;
            let drifts: Vec<f64> = forces.iter().zip(k).map(|(f, k)| f / k).collect();
            // the drift F_y/k must itself be a storey's yield drift: F_y = 1e-3 N on 1e8 N/m
            // storeys would yield at 1e-11 m, F_y = 1e14 N on 1e5 N/m at 1e9 m
            let (lo, hi, what) = super::ranges::physical_range("yield_drifts")
                .unwrap_or_else(|| unreachable!("yield_drifts has a range"));
            if let Some(j) = drifts.iter().position(|d| !(lo..=hi).contains(d)) {
                return Err(list_error(
                    c,
                    f,
                    &key("yield_forces"),
                    format!(
                        "storey {} yields at F_y/k = {:e} N / {:e} N/m = {:e} m: the yield \
                         drift F_y/k must be in [{lo:e}, {hi:e}] m ({what}); check the force and \
                         its unit (N)",
                        j + 1,
                        forces[j],
                        k[j],
                        drifts[j]
                    ),
                ));
            }
            drifts
        }
        (None, None) => {
            return Err(c.missing(
                &key("yield_drifts"),
                "the yield drift of every storey in m (one value, or a list per storey), or \
                 `yield_forces` in N",
                near,
            ));
        }
    };
    let alpha = c.required(
        &r.post_yield_ratio,
        &key("post_yield_ratio"),
        "the post-yield stiffness ratio α in [0, 1)",
        near,
    )?;
    let post_yield_ratio = *alpha.get_ref();
    if !(post_yield_ratio.is_finite() && (0.0..1.0).contains(&post_yield_ratio)) {
        return Err(c.invalid(
            alpha,
            &key("post_yield_ratio"),
            "must be in [0, 1) (the post-yield stiffness over the initial one)",
        ));
    }
    c.usual(post_yield_ratio, &key("post_yield_ratio"), "");
    fn real<'v>(
        c: &Check,
        key: &dyn Fn(&str) -> String,
        v: &'v Option<Spanned<f64>>,
        name: &str,
        default: f64,
        defaults: &mut Vec<String>,
    ) -> Result<(f64, Option<&'v Spanned<f64>>), ScenarioError> {
        match v {
            None => {
                defaults.push(format!("{} = {default}", key(name)));
                Ok((default, None))
            }
            Some(x) if x.get_ref().is_finite() => Ok((*x.get_ref(), Some(x))),
            Some(x) => Err(c.invalid(x, &key(name), "must be a finite number")),
        }
    }
    let (exponent, at) = real(c, &key, &r.exponent, "exponent", DEFAULT_EXPONENT, defaults)?;
    if let Some(x) = at
        && !(1.0..=100.0).contains(&exponent)
    {
        return Err(c.invalid(
            x,
            &key("exponent"),
            "must be a real number in [1, 100] (the sharpness of yielding; 1 smooth, ≥ 10 \
             nearly bilinear)",
        ));
    }
    c.usual(exponent, &key("exponent"), "");
    let (beta, beta_at) = real(c, &key, &r.beta, "beta", DEFAULT_BETA, defaults)?;
    let (gamma, gamma_at) = real(c, &key, &r.gamma, "gamma", DEFAULT_GAMMA, defaults)?;
    // the law is bounded (z → (β + γ)^(−1/n) on loading) and dissipates energy in every cycle
    // (dE_h/dt ≥ 0) only with β + γ > 0 and β ≥ γ, i.e. β ≥ |γ|
    if !(beta >= gamma.abs() && beta + gamma > 0.0 && beta <= 100.0) {
        let (v, name) = match (beta_at, gamma_at) {
            (Some(b), _) if !(beta > 0.0 && beta <= 100.0) => (b, "beta"),
            (_, Some(g)) => (g, "gamma"),
            (Some(b), None) => (b, "beta"),
            (None, None) => unreachable!("the defaults satisfy β ≥ |γ|"),
        };
        return Err(c.invalid(
            v,
            &key(name),
            &format!(
                "β = {beta}, γ = {gamma}: need 0 < β ≤ 100 and |γ| ≤ β (a bounded Bouc–Wen \
                 storey that dissipates energy in every cycle; β + γ = 1 puts the yield force at \
                 k·d_y)"
            ),
        ));
    }
    unusual_bouc_wen(
        c,
        &key,
        &r.yield_forces,
        &yield_drifts,
        heights,
        beta,
        gamma,
    );
    Ok(BoucWen {
        yield_drifts,
        post_yield_ratio,
        exponent,
        beta,
        gamma,
    })
}

/// Warnings for the Bouc–Wen values known only together ([`super::ranges::usual_range`]): a storey's
/// yield drift over its height (`yield_drift_ratio`, once per building, the first unusual
/// storey), and β + γ (`beta_plus_gamma`).
fn unusual_bouc_wen(
    c: &Check,
    key: &dyn Fn(&str) -> String,
    forces: &Option<Spanned<super::RawZeta>>,
    drifts: &[f64],
    heights: &[f64],
    beta: f64,
    gamma: f64,
) {
    let mut warnings = c.ctx.warnings.borrow_mut();
    let given = key(if forces.is_some() {
        "yield_forces"
    } else {
        "yield_drifts"
    });
    if let Some((lo, hi, why)) = super::ranges::usual_range("yield_drift_ratio") {
        let mut below = 0.0;
        for (j, (&d, &top)) in drifts.iter().zip(heights).enumerate() {
            let h = top - below;
            below = top;
            let ratio = d / h;
            if !(lo..=hi).contains(&ratio) {
                warnings.push(format!(
                    "`{given}`: storey {} yields at a drift of {d:.4e} m, {ratio:.3e} of its \
                     {h} m height, outside the usual [{lo:e}, {hi:e}] of the storey height: \
                     {why}; check the value and its unit (m for yield_drifts, N for \
                     yield_forces)",
                    j + 1
                ));
                break;
            }
        }
    }
    if let Some((lo, hi, why)) = super::ranges::usual_range("beta_plus_gamma")
        && !(lo..=hi).contains(&(beta + gamma))
    {
        warnings.push(format!(
            "`{}` + `{}`: β + γ = {beta} + {gamma} = {:.4} is outside the usual [{lo:e}, {hi:e}]: \
             {why}",
            key("beta"),
            key("gamma"),
            beta + gamma
        ));
    }
}
