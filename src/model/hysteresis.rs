//! Yielding storeys (issue 16): the smooth Bouc–Wen law per storey of a shear building, and its
//! assembly into the modal system as a pseudo-force (docs/model.md §2.6b).
//!
//! Storey j of a shear building carries `V_j = α k_j d_j + (1 − α) k_j d_y,j z_j`, with d_j the
//! inter-storey drift, d_y,j the yield drift and the hysteretic variable z_j obeying
//!
//! ```text
//! ż_j = (ḋ_j / d_y,j) [A − |z_j|ⁿ (β sign(ḋ_j z_j) + γ)],   A = 1.
//! ```
//!
//! The linear part of the model stays the modal model of the *initial* stiffness K₀ (k_j per
//! storey). The difference between the Bouc–Wen storey force and the linear one,
//! `ΔV_j = V_j − k_j d_j = (1 − α) k_j (d_y,j z_j − d_j)`, acts on floor j as −ΔV_j and on floor
//! j − 1 as +ΔV_j, so in mass-normalised modal coordinates it is the load `−e_j ΔV_j` with the
//! storey's *drift row* `e_j = φ(j) − φ(j − 1)` (φ(0) = 0 at the base): exactly like a contact
//! level's coupling row. The drift is `d_j = e_j · η`, its rate `ḋ_j = e_j · η̇`, and z_j is extra
//! state integrated with the modes.
//!
//! Energy (Baber & Wen 1981, *J. Eng. Mech. Div. ASCE* 107(6); the split used by Ismail, Ikhouane
//! & Rodellar 2009, *Arch. Comput. Methods Eng.* 16, §6): the storey's work
//! `∫ V ḋ dt = ½ α k d² + (1 − α) k d_y ∫ z ḋ dt`; of the hysteretic part, `½ (1 − α) k d_y² z²`
//! is held (recoverable) and the rest is dissipated:
//!
//! ```text
//! E_h = (1 − α) k d_y ∫ z ḋ dt − ½ (1 − α) k d_y² z²,
//! dE_h/dt = (1 − α) k d_y |z|ⁿ (β |ḋ z| + γ ḋ z) ≥ 0   when β ≥ |γ|.
//! ```
//!
//! Over a closed cycle z returns to its start and E_h is the area of the loop V(d). In terms of
//! the pseudo-force's work `W_j = ∫ ΔV_j ḋ_j dt` (what the integrators tally, and what enters the
//! modal energy balance): `E_h = W + ½ (1 − α) k (d² − d_y² z²)` (from rest).

use crate::model::bouc_wen::Storey;
use crate::model::modal::{ModalModel, Shapes};
use crate::model::structure::Structure;
use crate::numerics::linalg::dot;

/// Every yielding storey of a system, with its drift row over the system's modal coordinates.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Hysteresis {
    storeys: Vec<Storey>,
    /// Drift rows, `[s·n + j]`.
    rows: Vec<f64>,
    n: usize,
}

impl Hysteresis {
    /// No yielding storey.
    pub fn none() -> Hysteresis {
        Hysteresis::default()
    }

    /// The yielding storeys of every structure (a pair or a row, in row order), for their
    /// modal models `models` (the modes kept: the drift rows are those of the kept modes, so a
    /// truncated model sees only the drift its modes carry).
    pub fn new(structures: &[Structure], models: &[ModalModel]) -> Hysteresis {
        let n: usize = models.iter().map(ModalModel::len).sum();
        let mut h = Hysteresis {
            n,
            ..Hysteresis::default()
        };
        let mut offset = 0;
        for (i, (s, m)) in structures.iter().zip(models).enumerate() {
            // (structure i's coordinates start after those of every structure before it)
            let start = offset;
            offset += m.len();
            let (Some(bw), Some(ks)) = (s.hysteresis(), s.storey_stiffnesses()) else {
                continue;
            };
            let Shapes::Floors { values, .. } = &m.shapes else {
                continue;
            };
            for (j, &k) in ks.iter().enumerate() {
                h.storeys.push(Storey {
                    structure: i,
                    storey: j,
                    k,
                    alpha: bw.post_yield_ratio,
                    dy: bw.yield_drifts[j],
                    n: bw.exponent,
                    beta: bw.beta,
                    gamma: bw.gamma,
                });
                let mut row = vec![0.0; n];
                for (mode, v) in values.iter().enumerate() {
                    let below = if j == 0 { 0.0 } else { v[j - 1] };
                    row[start + mode] = v[j] - below;
                }
                h.rows.extend(row);
            }
        }
        h
    }

    /// Number of yielding storeys (both structures).
    #[inline(always)]
    pub fn len(&self) -> usize {
        self.storeys.len()
    }

    /// True without yielding storeys.
    #[inline(always)]
    pub fn is_empty(&self) -> bool {
        self.storeys.is_empty()
    }

    /// The storeys.
    pub fn storeys(&self) -> &[Storey] {
        &self.storeys
    }

    /// Drift row of storey `s` (kg^(−1/2)).
    #[inline(always)]
    pub fn row(&self, s: usize) -> &[f64] {
        &self.rows[s * self.n..(s + 1) * self.n]
    }

    /// Drift (m) and drift rate (m/s) of storey `s`.
    #[inline(always)]
    pub fn drift(&self, s: usize, q: &[f64], v: &[f64]) -> (f64, f64) {
        let r = self.row(s);
        (dot(r, q), dot(r, v))
    }

    /// The pseudo-forces at state (q, v, z): adds `−Σ_s e_s ΔV_s` to the modal accelerations
    /// `a`, writes ż into `zdot` and the power `ΔV_s ḋ_s` of each storey into `power`; returns
    /// their sum (W), the power the structures give to the pseudo-forces.
    #[inline]
    pub fn apply(
        &self,
        q: &[f64],
        v: &[f64],
        z: &[f64],
        a: &mut [f64],
        zdot: &mut [f64],
        power: &mut [f64],
    ) -> f64 {
        let n = self.n;
        let a = &mut a[..n];
        let mut total = 0.0;
        for (s, st) in self.storeys.iter().enumerate() {
            let r = &self.rows[s * n..(s + 1) * n];
            let (d, dd) = (dot(r, q), dot(r, v));
            let f = st.pseudo_force(d, z[s]);
            zdot[s] = st.z_rate(dd, z[s]);
            power[s] = f * dd;
            total += f * dd;
            if f != 0.0 {
                for j in 0..n {
                    a[j] -= r[j] * f;
                }
            }
        }
        total
    }
}
