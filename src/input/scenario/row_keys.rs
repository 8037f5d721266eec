//! A row of buildings (issue 29): `[[contact]]` tables, one per adjacent pair of the
//! `[[structure]]` tables (in row order), each naming its pair with `between = ["a", "b"]`; or
//! the single `[contact]` of a pair. Checked into one [`super::ContactSpec`] per adjacent pair,
//! in row order.
//!
//! A row needs a contact description for every adjacent pair: two neighbours that cannot touch
//! are given a gap larger than any motion (the physical range of a gap goes to 10 m), so that
//! a missing table is always a mistake and never a silent "no contact".

use serde::Deserialize;
use toml::Spanned;

use crate::model::structure::Structure;

use super::RawContact;
use super::contact_keys::contact_table;
use super::diagnostics::{Check, Ctx, ScenarioError};
use super::{ContactSpec, MAX_ROW};

/// `contact` as the file gives it: one `[contact]` table or an array of `[[contact]]` tables.
#[derive(Debug)]
pub(super) enum RawContacts {
    /// `[contact]` (a pair).
    One(Box<RawContact>),
    /// `[[contact]]` (a row, or a pair written as a row).
    Many(Vec<Spanned<RawContact>>),
}

impl<'de> Deserialize<'de> for RawContacts {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> serde::de::Visitor<'de> for V {
            type Value = RawContacts;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a [contact] table or [[contact]] tables")
            }
            fn visit_map<A: serde::de::MapAccess<'de>>(
                self,
                map: A,
            ) -> Result<RawContacts, A::Error> {
                // (the values are read by the TOML deserializer itself: spans and unknown-key
                // errors stay those of a plain table)
                RawContact::deserialize(serde::de::value::MapAccessDeserializer::new(map))
                    .map(|r| RawContacts::One(Box::new(r)))
            }
            fn visit_seq<A: serde::de::SeqAccess<'de>>(
                self,
                seq: A,
            ) -> Result<RawContacts, A::Error> {
                Vec::<Spanned<RawContact>>::deserialize(
                    serde::de::value::SeqAccessDeserializer::new(seq),
                )
                .map(RawContacts::Many)
            }
        }
        d.deserialize_any(V)
    }
}

/// The contact of every adjacent pair of `structures` (row order), from `raw` at `span_start`
/// in the file (the first `[contact]`/`[[contact]]` table).
pub(super) fn row_contacts(
    c: &Check,
    raw: Option<&Spanned<RawContacts>>,
    structures: &[Structure],
    defaults: &mut Vec<String>,
) -> Result<Vec<ContactSpec>, ScenarioError> {
    let pair_min = |p: usize| structures[p].length().min(structures[p + 1].length());
    let n = structures.len();
    let raw = match raw {
        None => {
            return Err(c.missing(
                "contact",
                &if n == 2 {
                    "a [contact] table with at least `stiffness` and `gap`".to_string()
                } else {
                    format!("{} [[contact]] tables, one per adjacent pair", n - 1)
                },
                None,
            ));
        }
        Some(r) => r,
    };
    let near = Some(raw.span().start);
    match raw.get_ref() {
        RawContacts::One(one) => {
            if n > 2 {
                return Err(ScenarioError::Invalid {
                    at: c.ctx.at(near),
                    key: "contact".into(),
                    value: "one [contact] table".into(),
                    reason: format!(
                        "a row of {n} structures needs one [[contact]] table per adjacent pair \
                         ({} of them), each with `between = [\"left\", \"right\"]` naming its \
                         two structures",
                        n - 1
                    ),
                });
            }
            if let Some(b) = &one.between {
                pair_index(c, b, "contact.between", structures)?;
            }
            Ok(vec![contact_table(
                c,
                one,
                raw.span().start,
                "contact",
                pair_min(0),
                defaults,
            )?])
        }
        RawContacts::Many(list) => {
            let mut slots: Vec<Option<ContactSpec>> = vec![None; n - 1];
            let mut given_at: Vec<Option<usize>> = vec![None; n - 1];
            for (i, t) in list.iter().enumerate() {
                let key = format!("contact[{}]", i + 1);
                let between = match &t.get_ref().between {
                    Some(b) => b,
                    None if n == 2 && list.len() == 1 => {
                        // a pair written as [[contact]]: its one pair
                        slots[0] = Some(contact_table(
                            c,
                            t.get_ref(),
                            t.span().start,
                            &key,
                            pair_min(0),
                            defaults,
                        )?);
                        continue;
                    }
                    None => {
                        return Err(c.missing(
                            &format!("{key}.between"),
                            "the pair's two structures by name, `between = [\"left\", \"right\"]`",
                            Some(t.span().start),
                        ));
                    }
                };
                let bkey = format!("{key}.between");
                let p = pair_index(c, between, &bkey, structures)?;
                if let Some(first) = given_at[p] {
                    return Err(invalid_list(
                        c,
                        between,
                        &bkey,
                        &format!(
                            "the pair \"{}\"–\"{}\" is given twice (also by contact[{}])",
                            structures[p].name(),
                            structures[p + 1].name(),
                            first + 1
                        ),
                    ));
                }
                given_at[p] = Some(i);
                slots[p] = Some(contact_table(
                    c,
                    t.get_ref(),
                    t.span().start,
                    &key,
                    pair_min(p),
                    defaults,
                )?);
            }
            let missing: Vec<String> = (0..n - 1)
                .filter(|&p| slots[p].is_none())
                .map(|p| {
                    format!(
                        "\"{}\"–\"{}\"",
                        structures[p].name(),
                        structures[p + 1].name()
                    )
                })
                .collect();
            if !missing.is_empty() {
                return Err(c.missing(
                    "contact",
                    &format!(
                        "a [[contact]] table for every adjacent pair; none for {} (neighbours \
                         that cannot touch: give them a gap larger than any motion, e.g. \
                         `gap = 10`)",
                        missing.join(", ")
                    ),
                    near,
                ));
            }
            Ok(slots.into_iter().flatten().collect())
        }
    }
}

/// The adjacent pair `between` names: the left structure's index.
fn pair_index(
    c: &Check,
    between: &Spanned<Vec<Spanned<String>>>,
    key: &str,
    structures: &[Structure],
) -> Result<usize, ScenarioError> {
    let names: Vec<&str> = structures.iter().map(Structure::name).collect();
    let list = between.get_ref();
    if list.len() != 2 {
        return Err(invalid_list(
            c,
            between,
            key,
            "must name exactly two structures, `between = [\"left\", \"right\"]`",
        ));
    }
    let mut idx = [0; 2];
    for (slot, name) in idx.iter_mut().zip(list) {
        let found: Vec<usize> = (0..names.len())
            .filter(|&i| names[i] == name.get_ref())
            .collect();
        *slot = match found.as_slice() {
            [i] => *i,
            [] => {
                return Err(c.invalid(
                    name,
                    key,
                    &format!(
                        "\"{}\" is not the name of a structure (they are {})",
                        name.get_ref(),
                        names
                            .iter()
                            .map(|n| format!("\"{n}\""))
                            .collect::<Vec<_>>()
                            .join(", ")
                    ),
                ));
            }
            _ => {
                return Err(c.invalid(
                    name,
                    key,
                    &format!(
                        "{} structures are named \"{}\": give every structure of a row its own \
                         `name`",
                        found.len(),
                        name.get_ref()
                    ),
                ));
            }
        };
    }
    let (a, b) = (idx[0].min(idx[1]), idx[0].max(idx[1]));
    if b != a + 1 {
        return Err(invalid_list(
            c,
            between,
            key,
            &format!(
                "\"{}\" and \"{}\" are structures {} and {} of the row: only adjacent structures \
                 (next to each other in the order of the [[structure]] tables) can touch",
                list[0].get_ref(),
                list[1].get_ref(),
                idx[0] + 1,
                idx[1] + 1
            ),
        ));
    }
    Ok(a)
}

/// The row's size within [2, MAX_ROW].
pub(super) fn check_count(c: &Check, count: usize, near: usize) -> Result<(), ScenarioError> {
    if (2..=MAX_ROW).contains(&count) {
        return Ok(());
    }
    Err(ScenarioError::Invalid {
        at: c.ctx.at(Some(near)),
        key: "structure".into(),
        value: format!("{count} table(s)"),
        reason: format!(
            "two [[structure]] tables (a pair) or a row of up to {MAX_ROW}, in order along the row, \
             are needed{}",
            if count == 1 {
                ": one structure alone has nothing to pound against"
            } else {
                ""
            }
        ),
    })
}

/// `key` = the list `between`: refused for `reason`.
fn invalid_list(
    c: &Check,
    between: &Spanned<Vec<Spanned<String>>>,
    key: &str,
    reason: &str,
) -> ScenarioError {
    let names: Vec<String> = (between.get_ref().iter())
        .map(|n| format!("\"{}\"", n.get_ref()))
        .collect();
    ScenarioError::Invalid {
        at: c.ctx.at(Some(between.span().start)),
        key: key.to_string(),
        value: format!("[{}]", names.join(", ")),
        reason: reason.to_string(),
    }
}

/// A file with both a `[contact]` and `[[contact]]` tables (which TOML itself refuses, as a
/// duplicate key): the error naming both, at the second.
pub(super) fn both_contact_forms(ctx: &Ctx) -> Option<ScenarioError> {
    let mut offset = 0;
    let (mut one, mut many) = (None, None);
    for line in ctx.text.split_inclusive('\n') {
        let t = line.trim_start();
        let header = |h: &str| {
            t.strip_prefix(h).is_some_and(|rest| {
                rest.trim_start().is_empty() || rest.trim_start().starts_with('#')
            })
        };
        let at = offset + (line.len() - t.len());
        if header("[contact]") && one.is_none() {
            one = Some(at);
        } else if header("[[contact]]") && many.is_none() {
            many = Some(at);
        }
        offset += line.len();
    }
    let (one, many) = (one?, many?);
    Some(ScenarioError::Invalid {
        at: ctx.at(Some(one.max(many))),
        key: "contact".into(),
        value: "[contact] and [[contact]]".into(),
        reason: "give either one [contact] table (a pair) or one [[contact]] table per adjacent \
                 pair (a row, each with `between`), not both"
            .into(),
    })
}
