//! The self-check columns of a suite's row (`check_max_change`, `converged`) from its
//! records' self-checks: shared by a pair suite's rows ([`super::suite_rows`]) and a row
//! suite's ([`super::row_suite_rows`]).

use crate::numerics::format::fmt_f64;

/// The `converged` value of a row not self-checked (`results::UNCHECKED`: `results` reads
/// the suites' rows, so this file does not import it).
const UNCHECKED: &str = "unchecked";

/// The `check_max_change` and `converged` fields of a suite's row from its records'
/// self-checks `(checked, max_change, converged)` (`check`: whether the records were
/// self-checked): the largest change over the records (empty if a check run failed), and
/// `true` only if every record converged; `unchecked` (with an empty change) if any record was
/// not checked. A pair suite's rows and a row suite's ([`super::row_suite_rows::fields`]).
pub(super) fn worst_check(
    mut records: impl Iterator<Item = (bool, Option<f64>, Option<bool>)> + Clone,
    check: bool,
) -> [String; 2] {
    if !check || records.clone().any(|(checked, _, _)| !checked) {
        return [String::new(), UNCHECKED.to_string()];
    }
    let changes: Option<Vec<f64>> = records.clone().map(|(_, c, _)| c).collect();
    [
        changes
            .map(|c| fmt_f64(c.into_iter().fold(0.0, f64::max)))
            .unwrap_or_default(),
        records.all(|(_, _, c)| c == Some(true)).to_string(),
    ]
}

#[cfg(test)]
mod tests {
    #[test]
    fn unchecked_is_the_single_rows_value() {
        assert_eq!(super::UNCHECKED, super::super::results::UNCHECKED);
    }
}
