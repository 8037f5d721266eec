//! `K/N`: one of N disjoint parts of a sweep's grid (`--shard`).

use std::fmt;

/// `K/N`: the K-th (1-based) of N disjoint parts of the grid. Case `i` belongs to part
/// `i mod N + 1` (interleaved, so that every part gets a similar mix of cheap and costly cases).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// 1-based part number.
    pub k: usize,
    /// Number of parts.
    pub n: usize,
}

impl Shard {
    /// The whole grid.
    pub const ALL: Shard = Shard { k: 1, n: 1 };

    /// Does case `case` belong to this part?
    pub fn contains(&self, case: usize) -> bool {
        case % self.n + 1 == self.k
    }

    /// Is this the whole grid?
    pub fn is_all(&self) -> bool {
        self.n == 1
    }
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.k, self.n)
    }
}

impl std::str::FromStr for Shard {
    type Err = String;
    fn from_str(s: &str) -> Result<Shard, String> {
        let bad =
            || format!("--shard `{s}`: expected K/N with 1 ≤ K ≤ N, e.g. 3/8 (the 3rd of 8 parts)");
        let (k, n) = s.split_once('/').ok_or_else(bad)?;
        let k: usize = k.trim().parse().map_err(|_| bad())?;
        let n: usize = n.trim().parse().map_err(|_| bad())?;
        if k == 0 || n == 0 || k > n {
            return Err(bad());
        }
        Ok(Shard { k, n })
    }
}
