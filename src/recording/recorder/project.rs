//! The recorder's sums over the modes: the tracked heights' displacements and velocities
//! (`φ·η`, `φ·η̇`) and the modal energy, in one chain below [`LANES_FROM`] modes and in four
//! lanes from it on ([`project`]); [`Tracks`] forms every tracked height's projections of an
//! observation structure by structure, with each sum's lanes taking the same products in the
//! same order as [`project`]: the same bits.

use crate::model::system::System;
use crate::numerics::lanes::F2;

/// Below this many modes a sum runs in one chain (as it always did); from it on in four
/// lanes, which the compiler turns into vector operations.
pub(super) const LANES_FROM: usize = 8;

/// `(φ·η, φ·η̇)` in one pass (from [`LANES_FROM`] modes on in four lanes: the same products
/// added in another order, so the values move by round-off only): one projection as the
/// recorder formed it before [`Tracks`], kept as the reference its tests compare with.
#[cfg(test)]
#[inline(always)]
pub(super) fn project(phi: &[f64], q: &[f64], v: &[f64]) -> (f64, f64) {
    let n = phi.len().min(q.len()).min(v.len());
    let (phi, q, v) = (&phi[..n], &q[..n], &v[..n]);
    if n < LANES_FROM {
        let (mut w, mut wd) = (0.0, 0.0);
        for j in 0..n {
            w += phi[j] * q[j];
            wd += phi[j] * v[j];
        }
        return (w, wd);
    }
    // four lanes as two pairs, (0, 1) and (2, 3), for w and for ẇ, each pair one vector
    // operation ([`F2`]), where with four-lane arrays the compiler paired w with ẇ and
    // shuffled every product into place (29 instructions per four modes); the same products
    // in the same lanes, added in the same order: the same bits
    let z = F2::zero();
    let mut acc = [z; 4];
    let (cp, _) = phi.as_chunks::<4>();
    let (cq, _) = q.as_chunks::<4>();
    let (cv, _) = v.as_chunks::<4>();
    for ((p, q), v) in cp.iter().zip(cq).zip(cv) {
        lanes4(&mut acc, p, q, v);
    }
    lanes_end(acc, phi, q, v)
}

/// One group of four modes of [`project`]'s lanes: `acc` = (w lanes 0–1, w lanes 2–3, ẇ lanes
/// 0–1, ẇ lanes 2–3).
#[cfg(test)]
#[inline(always)]
fn lanes4(acc: &mut [F2; 4], p: &[f64; 4], q: &[f64; 4], v: &[f64; 4]) {
    let (p01, p23) = (F2::new(p[0], p[1]), F2::new(p[2], p[3]));
    acc[0] = acc[0] + p01 * F2::new(q[0], q[1]);
    acc[1] = acc[1] + p23 * F2::new(q[2], q[3]);
    acc[2] = acc[2] + p01 * F2::new(v[0], v[1]);
    acc[3] = acc[3] + p23 * F2::new(v[2], v[3]);
}

/// [`project`]'s end: the modes after the last group of four, each into its lane, and the
/// lanes added as (0 + 1) + (2 + 3).
#[cfg(test)]
#[inline(always)]
fn lanes_end(acc: [F2; 4], phi: &[f64], q: &[f64], v: &[f64]) -> (f64, f64) {
    let n = phi.len().min(q.len()).min(v.len());
    let ([w0, w1], [w2, w3]) = (acc[0].get(), acc[1].get());
    let ([d0, d1], [d2, d3]) = (acc[2].get(), acc[3].get());
    let (mut w, mut wd) = ([w0, w1, w2, w3], [d0, d1, d2, d3]);
    let r = n / 4 * 4;
    for l in 0..n - r {
        w[l] += phi[r + l] * q[r + l];
        wd[l] += phi[r + l] * v[r + l];
    }
    (
        (w[0] + w[1]) + (w[2] + w[3]),
        (wd[0] + wd[1]) + (wd[2] + wd[3]),
    )
}

/// The modal energy `Σ ½(η̇² + ω²η²)` (J; `w2`: ω² of every mode), as
/// [`System::modal_energy`] forms it, in four lanes from [`LANES_FROM`] modes on.
#[inline]
pub(super) fn modal_energy(w2: &[f64], q: &[f64], v: &[f64]) -> f64 {
    let n = w2.len().min(q.len()).min(v.len());
    let (w2, q, v) = (&w2[..n], &q[..n], &v[..n]);
    if n < LANES_FROM {
        let mut e = 0.0;
        for j in 0..n {
            e += 0.5 * (v[j] * v[j] + w2[j] * q[j] * q[j]);
        }
        return e;
    }
    // (as `project`: two pairs of lanes, the same lanes and order as four-lane arrays)
    let (half, z) = (F2::splat(0.5), F2::zero());
    let (mut e01, mut e23) = (z, z);
    let (cw, _) = w2.as_chunks::<4>();
    let (cq, _) = q.as_chunks::<4>();
    let (cv, _) = v.as_chunks::<4>();
    for ((w, q), v) in cw.iter().zip(cq).zip(cv) {
        let (w01, q01, v01) = (
            F2::new(w[0], w[1]),
            F2::new(q[0], q[1]),
            F2::new(v[0], v[1]),
        );
        let (w23, q23, v23) = (
            F2::new(w[2], w[3]),
            F2::new(q[2], q[3]),
            F2::new(v[2], v[3]),
        );
        e01 = e01 + half * (v01 * v01 + w01 * q01 * q01);
        e23 = e23 + half * (v23 * v23 + w23 * q23 * q23);
    }
    let ([a, b], [c, d]) = (e01.get(), e23.get());
    let mut e = [a, b, c, d];
    let r = n / 4 * 4;
    for l in 0..n - r {
        let (w, q, v) = (w2[r + l], q[r + l], v[r + l]);
        e[l] += 0.5 * (v * v + w * q * q);
    }
    (e[0] + e[1]) + (e[2] + e[3])
}

/// Every tracked height's projections of an observation, formed structure by structure: each
/// structure's distinct tracked heights (a row's building is tracked at the same heights
/// with both neighbours: once) in one pass over its modes, each mode's η and η̇ read once for
/// all of them. From [`LANES_FROM`] modes on, each sum keeps [`project`]'s four lanes (mode
/// j in lane j mod 4, the modes after the last group of four into lanes 0, 1, 2, the lanes
/// added as (0 + 1) + (2 + 3)); below it one chain in the modes' order, as [`project`]: the
/// same bits. Where the processor has AVX, a group of four modes is one operation per
/// product and per sum (the same IEEE operations lane by lane), else two SSE2 pairs ([`F2`]).
#[derive(Debug, Clone)]
pub(super) struct Tracks {
    /// One per structure with a tracked height.
    groups: Vec<Group>,
    /// Per tracked height, the entries of its left and its right structure in `values`.
    of: Vec<[usize; 2]>,
    /// `(w, ẇ)` of every entry at the current observation, m and m/s.
    values: Vec<(f64, f64)>,
    /// Whether the processor runs the AVX pass.
    wide: bool,
    /// Whether every structure has fewer than [`LANES_FROM`] modes (one chain per sum).
    chains: bool,
}

/// One structure's tracked heights.
#[derive(Debug, Clone)]
struct Group {
    /// The structure's modes in the state: `start..start + n`.
    start: usize,
    n: usize,
    /// Its entries: `values[first..first + count]`.
    first: usize,
    count: usize,
    /// From [`LANES_FROM`] modes on: φ of every entry four modes at a time, `[chunk·count +
    /// entry]` (the entries of a chunk side by side: one pass reads them in order).
    quads: Vec<[f64; 4]>,
    /// φ of every entry at the modes after the last group of four, `[entry·(n % 4) + l]`;
    /// below [`LANES_FROM`] modes every mode, `[entry·n + j]`.
    rest: Vec<f64>,
}

impl Tracks {
    /// The tracked heights `heights` (m) of a row `system`, height k between structures
    /// `pairs[k]` and `pairs[k] + 1`.
    pub(super) fn new(system: &System, heights: &[f64], pairs: &[usize]) -> Tracks {
        let st = &system.structures;
        // every structure's distinct heights, in the order of their first track
        let mut per: Vec<Vec<f64>> = vec![Vec::new(); st.len()];
        for (&h, &p) in heights.iter().zip(pairs) {
            for s in [p, p + 1] {
                if !per[s].iter().any(|x| x.to_bits() == h.to_bits()) {
                    per[s].push(h);
                }
            }
        }
        let spans: Vec<(usize, usize, Vec<Vec<f64>>)> = (per.iter().enumerate())
            .filter(|(_, hs)| !hs.is_empty())
            .map(|(s, hs)| {
                let modes = system.modes_of(s);
                let rows = hs.iter().map(|&h| st[s].shapes_at(h)).collect();
                (modes.start, modes.len(), rows)
            })
            .collect();
        // the entries: each structure's distinct heights in turn
        let entry = |s: usize, h: f64| -> usize {
            let before: usize = per[..s].iter().map(Vec::len).sum();
            before
                + per[s]
                    .iter()
                    .position(|x| x.to_bits() == h.to_bits())
                    .expect("a tracked height has its entry")
        };
        let of = heights
            .iter()
            .zip(pairs)
            .map(|(&h, &p)| [entry(p, h), entry(p + 1, h)])
            .collect();
        Tracks::from_groups(spans, of, crate::numerics::vex::available())
    }

    /// The projections of every structure `(start, n, rows)` (its modes `start..start + n` in
    /// the state, φ of each of its entries at its n modes), the entries numbered structure
    /// after structure; `of`: per tracked height, its two entries; `wide`: the AVX pass (only
    /// where the processor has AVX).
    pub(super) fn from_groups(
        spans: Vec<(usize, usize, Vec<Vec<f64>>)>,
        of: Vec<[usize; 2]>,
        wide: bool,
    ) -> Tracks {
        let mut groups = Vec::new();
        let mut first = 0;
        for (start, n, rows) in spans {
            let (quads, rest) = if n < LANES_FROM {
                (Vec::new(), rows.concat())
            } else {
                let r = n / 4 * 4;
                let quads = (0..r / 4)
                    .flat_map(|c| {
                        rows.iter()
                            .map(move |row| std::array::from_fn(|l| row[4 * c + l]))
                    })
                    .collect();
                let rest = rows
                    .iter()
                    .flat_map(|row| row[r..].iter().copied())
                    .collect();
                (quads, rest)
            };
            groups.push(Group {
                start,
                n,
                first,
                count: rows.len(),
                quads,
                rest,
            });
            first += rows.len();
        }
        Tracks {
            chains: groups.iter().all(|g| g.n < LANES_FROM),
            groups,
            of,
            values: vec![(0.0, 0.0); first],
            wide: wide && crate::numerics::vex::available(),
        }
    }

    /// Form every entry's `(w, ẇ)` from the modal state (`q`, `v`: every mode of the system).
    #[inline(always)]
    pub(super) fn project(&mut self, q: &[f64], v: &[f64]) {
        if self.chains {
            // (a few modes a structure: the chains here, without a call)
            for g in &self.groups {
                let (q, v) = (&q[g.start..g.start + g.n], &v[g.start..g.start + g.n]);
                g.chain(q, v, &mut self.values[g.first..g.first + g.count]);
            }
            return;
        }
        #[cfg(target_arch = "x86_64")]
        if self.wide {
            // SAFETY: `wide` only where the processor has AVX ([`crate::numerics::vex::available`])
            unsafe { self.project_avx(q, v) };
            return;
        }
        for g in &self.groups {
            let (q, v) = (&q[g.start..g.start + g.n], &v[g.start..g.start + g.n]);
            let out = &mut self.values[g.first..g.first + g.count];
            if g.n < LANES_FROM {
                g.chain(q, v, out);
                continue;
            }
            // (blocks of up to four entries: their sums stay in registers over the modes)
            let mut e0 = 0;
            while e0 < g.count {
                let m = (g.count - e0).min(4);
                let out = &mut out[e0..e0 + m];
                match m {
                    1 => g.pairs::<1>(e0, q, v, out),
                    2 => g.pairs::<2>(e0, q, v, out),
                    3 => g.pairs::<3>(e0, q, v, out),
                    _ => g.pairs::<4>(e0, q, v, out),
                }
                e0 += m;
            }
        }
    }

    /// [`Tracks::project`] with AVX. Safety: the processor has AVX.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx")]
    #[inline]
    unsafe fn project_avx(&mut self, q: &[f64], v: &[f64]) {
        for g in &self.groups {
            let (q, v) = (&q[g.start..g.start + g.n], &v[g.start..g.start + g.n]);
            let out = &mut self.values[g.first..g.first + g.count];
            if g.n < LANES_FROM {
                g.chain(q, v, out);
                continue;
            }
            let mut e0 = 0;
            while e0 < g.count {
                let m = (g.count - e0).min(4);
                let out = &mut out[e0..e0 + m];
                // SAFETY: AVX (the caller)
                unsafe {
                    match m {
                        1 => g.quad::<1>(e0, q, v, out),
                        2 => g.quad::<2>(e0, q, v, out),
                        3 => g.quad::<3>(e0, q, v, out),
                        _ => g.quad::<4>(e0, q, v, out),
                    }
                }
                e0 += m;
            }
        }
    }

    /// The SSE2 pass even where the processor has AVX (tests: both passes agree).
    #[cfg(test)]
    pub(super) fn narrow(&mut self) {
        self.wide = false;
    }

    /// Whether the projections run in AVX (the processor has it).
    #[inline(always)]
    pub(super) fn wide(&self) -> bool {
        self.wide
    }

    /// `(w₁, ẇ₁)` and `(w₂, ẇ₂)` of tracked height k at the current observation.
    #[inline(always)]
    pub(super) fn at(&self, k: usize) -> ((f64, f64), (f64, f64)) {
        let [a, b] = self.of[k];
        (self.values[a], self.values[b])
    }
}

impl Group {
    /// Below [`LANES_FROM`] modes: every entry's sums in one chain in the modes' order.
    #[inline(always)]
    fn chain(&self, q: &[f64], v: &[f64], out: &mut [(f64, f64)]) {
        // (the mode counts of most structures, unrolled)
        match self.n {
            1 => self.chain_of::<1>(q, v, out),
            2 => self.chain_of::<2>(q, v, out),
            3 => self.chain_of::<3>(q, v, out),
            4 => self.chain_of::<4>(q, v, out),
            _ => self.chain_any(q, v, out),
        }
    }

    /// [`Group::chain`] of `N` modes.
    #[inline(always)]
    fn chain_of<const N: usize>(&self, q: &[f64], v: &[f64], out: &mut [(f64, f64)]) {
        let (q, v) = (&q[..N], &v[..N]);
        let (rows, _) = self.rest.as_chunks::<N>();
        for (o, phi) in out.iter_mut().zip(rows) {
            let (mut w, mut wd) = (0.0, 0.0);
            for j in 0..N {
                w += phi[j] * q[j];
                wd += phi[j] * v[j];
            }
            *o = (w, wd);
        }
    }

    /// [`Group::chain`] of any number of modes.
    #[inline(always)]
    fn chain_any(&self, q: &[f64], v: &[f64], out: &mut [(f64, f64)]) {
        let n = self.n;
        let (q, v) = (&q[..n], &v[..n]);
        for (e, o) in out.iter_mut().enumerate() {
            let phi = &self.rest[e * n..(e + 1) * n];
            let (mut w, mut wd) = (0.0, 0.0);
            for j in 0..n {
                w += phi[j] * q[j];
                wd += phi[j] * v[j];
            }
            *o = (w, wd);
        }
    }

    /// The modes after the last group of four into the lanes `w`, `ẇ` of entry `e` (mode
    /// r + l into lane l), and the lanes added as (0 + 1) + (2 + 3).
    #[inline(always)]
    fn end(&self, e: usize, q: &[f64], v: &[f64], mut w: [f64; 4], mut wd: [f64; 4]) -> (f64, f64) {
        let r = self.n / 4 * 4;
        let tail = self.n - r;
        let phi = &self.rest[e * tail..(e + 1) * tail];
        for l in 0..tail {
            w[l] += phi[l] * q[r + l];
            wd[l] += phi[l] * v[r + l];
        }
        (
            (w[0] + w[1]) + (w[2] + w[3]),
            (wd[0] + wd[1]) + (wd[2] + wd[3]),
        )
    }

    /// The sums of the `M` entries from `e0` on into `out`, the four lanes as two SSE2 pairs
    /// ([`F2`]).
    #[inline(always)]
    fn pairs<const M: usize>(&self, e0: usize, q: &[f64], v: &[f64], out: &mut [(f64, f64)]) {
        let z = F2::zero();
        let (mut w, mut d) = ([[z; 2]; M], [[z; 2]; M]);
        let (qc, _) = q.as_chunks::<4>();
        let (vc, _) = v.as_chunks::<4>();
        for (row, (q, v)) in self.quads.chunks_exact(self.count).zip(qc.iter().zip(vc)) {
            let (q01, q23) = (F2::new(q[0], q[1]), F2::new(q[2], q[3]));
            let (v01, v23) = (F2::new(v[0], v[1]), F2::new(v[2], v[3]));
            let row = &row[e0..e0 + M];
            for i in 0..M {
                let p = &row[i];
                let (p01, p23) = (F2::new(p[0], p[1]), F2::new(p[2], p[3]));
                w[i][0] = w[i][0] + p01 * q01;
                w[i][1] = w[i][1] + p23 * q23;
                d[i][0] = d[i][0] + p01 * v01;
                d[i][1] = d[i][1] + p23 * v23;
            }
        }
        for (i, o) in out.iter_mut().enumerate().take(M) {
            let ([a, b], [c, e]) = (w[i][0].get(), w[i][1].get());
            let ([x, y], [z, u]) = (d[i][0].get(), d[i][1].get());
            *o = self.end(e0 + i, q, v, [a, b, c, e], [x, y, z, u]);
        }
    }

    /// [`Group::pairs`] in AVX: each group of four modes one product and one sum per entry
    /// and quantity (the same IEEE operations, lane by lane); without modes after the last
    /// group of four, the lanes added by `vhaddpd` (w₀ + w₁, ẇ₀ + ẇ₁, w₂ + w₃, ẇ₂ + ẇ₃) and
    /// its two halves (the same additions in the same order). Safety: the processor has AVX.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx")]
    #[inline]
    unsafe fn quad<const M: usize>(&self, e0: usize, q: &[f64], v: &[f64], out: &mut [(f64, f64)]) {
        use std::arch::x86_64::{
            _mm_add_pd, _mm_cvtsd_f64, _mm_unpackhi_pd, _mm256_add_pd, _mm256_castpd256_pd128,
            _mm256_extractf128_pd, _mm256_hadd_pd, _mm256_loadu_pd, _mm256_mul_pd,
            _mm256_setzero_pd, _mm256_storeu_pd,
        };
        let z = _mm256_setzero_pd();
        let (mut w, mut d) = ([z; M], [z; M]);
        let (qc, _) = q.as_chunks::<4>();
        let (vc, _) = v.as_chunks::<4>();
        for (row, (q, v)) in self.quads.chunks_exact(self.count).zip(qc.iter().zip(vc)) {
            // SAFETY: AVX (the caller); every chunk holds four values
            let (q, v) = unsafe { (_mm256_loadu_pd(q.as_ptr()), _mm256_loadu_pd(v.as_ptr())) };
            let row = &row[e0..e0 + M];
            for i in 0..M {
                // SAFETY: as above
                let p = unsafe { _mm256_loadu_pd(row[i].as_ptr()) };
                w[i] = _mm256_add_pd(w[i], _mm256_mul_pd(p, q));
                d[i] = _mm256_add_pd(d[i], _mm256_mul_pd(p, v));
            }
        }
        if self.n.is_multiple_of(4) {
            for (i, o) in out.iter_mut().enumerate().take(M) {
                let s = _mm256_hadd_pd(w[i], d[i]);
                let t = _mm_add_pd(_mm256_castpd256_pd128(s), _mm256_extractf128_pd::<1>(s));
                *o = (_mm_cvtsd_f64(t), _mm_cvtsd_f64(_mm_unpackhi_pd(t, t)));
            }
            return;
        }
        for (i, o) in out.iter_mut().enumerate().take(M) {
            let (mut lw, mut ld) = ([0.0; 4], [0.0; 4]);
            // SAFETY: AVX (the caller); four values each
            unsafe {
                _mm256_storeu_pd(lw.as_mut_ptr(), w[i]);
                _mm256_storeu_pd(ld.as_mut_ptr(), d[i]);
            }
            *o = self.end(e0 + i, q, v, lw, ld);
        }
    }
}
