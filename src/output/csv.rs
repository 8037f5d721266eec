//! Numbers in the CSV files, written without `format!` into reused byte buffers.

/// Appends `v` to `out` as the shortest decimal text that reads back as the same `f64`
/// (zmij: plain digits from 1e-5 to 1e16, exponent notation outside; `NaN`, `inf`, `-inf` as
/// Rust writes them). About 10× fewer instructions than `format!("{v}")`, and no allocation:
/// the CSV files of a run hold hundreds of thousands of numbers.
#[inline]
pub(crate) fn push_number(out: &mut Vec<u8>, v: f64) {
    let mut b = zmij::Buffer::new();
    out.extend_from_slice(b.format(v).as_bytes());
}

/// `,v` appended to `out` (see [`push_number`]).
#[inline]
pub(crate) fn push_field(out: &mut Vec<u8>, v: f64) {
    out.push(b',');
    push_number(out, v);
}
