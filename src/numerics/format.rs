//! Numbers as text: tick labels ([`fmt_num`]) and the shortest decimal that reads back to the
//! same `f64` ([`fmt_f64`], as summary.json and the results tables write them).

/// A number as a tick label: at most 4 significant digits, no trailing zeros, `e` notation
/// outside `[1e-3, 1e5)`, a true minus sign.
pub fn fmt_num(v: f64) -> String {
    if !v.is_finite() {
        return String::new();
    }
    let a = v.abs();
    let s = if a < 1e-300 {
        "0".to_string()
    } else if (1e-3..1e5).contains(&a) {
        let decimals = (3 - a.log10().floor() as i32).clamp(0, 7) as usize;
        trim_zeros(&format!("{v:.decimals$}")).to_string()
    } else {
        let s = format!("{v:.3e}");
        let (m, e) = s.split_once('e').unwrap_or((&s, "0"));
        format!("{}e{e}", trim_zeros(m))
    };
    match s.strip_prefix('-') {
        Some(rest) => format!("−{rest}"),
        None => s,
    }
}

fn trim_zeros(s: &str) -> &str {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.')
    } else {
        s
    }
}

/// An `f64` as `summary.json` writes it: the shortest decimal that reads back to the same
/// value (`NaN`/`inf` for non-finite values, which JSON cannot hold).
pub fn fmt_f64(x: f64) -> String {
    if x.is_finite() {
        serde_json::to_string(&x).unwrap_or_else(|_| x.to_string())
    } else {
        x.to_string()
    }
}
