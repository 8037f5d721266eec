//! How the integrators cut time into steps: the one step plan (a span cut into steps no longer
//! than `[solver] dt`) and the one dyadic walk (a base step walked in sub-steps `hh/2^m` whose
//! level an error estimate or a search refines and coarsens).

/// Number of steps no longer than `dt` that cover a span of length `len` (s): `⌈len/dt − 1e-9⌉`,
/// at least 1. The 1e-9 keeps a span that is a whole number of steps up to round-off (a
/// duration of 20 s at dt = 0.01 s: 2000.0000000000002) from gaining a sliver of a last step.
/// As a float, for the plans that divide by it.
#[inline]
pub(crate) fn step_count(len: f64, dt: f64) -> f64 {
    ((len / dt) - 1e-9).ceil().max(1.0)
}

/// `rk4`'s plan ([`super::SolverSettings::fixed_step`]): steps of exactly `dt` from t = 0
/// covering `duration`, the last one shortened to end on it. Returns the number of steps and
/// the length of the last.
pub(crate) fn step_plan(dt: f64, duration: f64) -> (usize, f64) {
    let steps = step_count(duration, dt) as usize;
    let last = duration - (steps - 1) as f64 * dt;
    (steps, last)
}

/// `exact-modal`'s plan ([`super::SolverSettings::base_step`]): the span `[start, end]` (the
/// whole run, or one interval of a recorded motion, whose ground load is one polynomial) cut
/// into [`step_count`] equal steps of length `h`, the last ending exactly on `end`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct EqualSteps {
    /// Start of the span, s.
    pub start: f64,
    /// End of the span, s.
    pub end: f64,
    /// Number of steps (a whole number, as a float).
    pub steps: f64,
    /// Their length, s.
    pub h: f64,
}

impl EqualSteps {
    /// The plan of `[start, end]` with steps no longer than `dt`.
    #[inline]
    pub(crate) fn new(start: f64, end: f64, dt: f64) -> EqualSteps {
        let len = end - start;
        let steps = step_count(len, dt);
        EqualSteps {
            start,
            end,
            steps,
            h: len / steps,
        }
    }

    /// Start and end of step `i` (0-based): `start + i·h` to `start + (i + 1)·h`, the last to
    /// `end` itself (no round-off gap before the next span).
    #[inline]
    pub(crate) fn bounds(&self, i: usize) -> (f64, f64) {
        let ts = self.start + i as f64 * self.h;
        let te = if (i + 1) as f64 == self.steps {
            self.end
        } else {
            self.start + (i + 1) as f64 * self.h
        };
        (ts, te)
    }
}

/// A walk over a base step of length `hh` in dyadic sub-steps `hh/2^level`, `level ≤ max`: the
/// position is kept in units of `hh/2^max` as an integer, so that no sub-step drifts off the
/// dyadic grid and the walk ends exactly at the base step's end. Refining halves the sub-step
/// at the current position; coarsening doubles it only where the position is a multiple of
/// the coarser sub-step (aligned), so the sub-steps always tile the base step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct DyadicWalk {
    /// Position from the base step's start, in units of hh/2^max.
    pos: u64,
    /// Current level m: sub-steps hh/2^m.
    pub level: u32,
    /// Finest level.
    max: u32,
}

impl DyadicWalk {
    /// A walk at the start of the base step, at `level` (≤ `max` ≤ 63).
    #[inline]
    pub(crate) fn new(level: u32, max: u32) -> DyadicWalk {
        debug_assert!(level <= max && max < 64);
        DyadicWalk { pos: 0, level, max }
    }

    /// A walk at position `pos` (in units of hh/2^max from the base step's start, ≤ 2^max), at
    /// `level`: one that starts mid-step (a phase entering the grid at a point of it).
    #[inline]
    pub(crate) fn at(pos: u64, level: u32, max: u32) -> DyadicWalk {
        debug_assert!(level <= max && max < 64 && pos <= 1u64 << max);
        DyadicWalk { pos, level, max }
    }

    /// The position from the base step's start, in units of hh/2^max.
    #[inline]
    pub(crate) fn pos(&self) -> u64 {
        self.pos
    }

    /// Whether the position is a point of the grid of `level` (a multiple of hh/2^level).
    #[inline]
    pub(crate) fn aligned(&self, level: u32) -> bool {
        self.pos
            .is_multiple_of((1u64 << self.max) >> level.min(self.max))
    }

    /// The number of the last grid point of `level` at or before the position: ⌊pos/2^(max −
    /// level)⌋ (the position's offset is that times hh/2^level where the walk is aligned).
    #[inline]
    pub(crate) fn index(&self, level: u32) -> u64 {
        self.pos >> (self.max - level.min(self.max))
    }

    /// The distance to the next grid point of `level` after the position, in units of
    /// hh/2^max: a whole sub-step hh/2^level where the position is on that grid, else the rest
    /// of the one it is inside.
    #[inline]
    pub(crate) fn until_next(&self, level: u32) -> u64 {
        let unit = (1u64 << self.max) >> level.min(self.max);
        unit - self.pos % unit
    }

    /// Whether the whole base step has been walked.
    #[inline]
    pub(crate) fn done(&self) -> bool {
        self.pos >= 1u64 << self.max
    }

    /// The current sub-step's length `hh/2^level`, s.
    #[inline]
    pub(crate) fn length(&self, hh: f64) -> f64 {
        hh / (1u64 << self.level) as f64
    }

    /// The current position's offset from the base step's start, s.
    #[inline]
    pub(crate) fn offset(&self, hh: f64) -> f64 {
        hh * (self.pos as f64 / (1u64 << self.max) as f64)
    }

    /// Whether the walk is at its finest level.
    #[inline]
    pub(crate) fn finest(&self) -> bool {
        self.level >= self.max
    }

    /// Refine by `levels` (capped at the finest).
    #[inline]
    pub(crate) fn refine(&mut self, levels: u32) {
        self.level = (self.level + levels).min(self.max);
    }

    /// Step past the current sub-step.
    #[inline]
    pub(crate) fn advance(&mut self) {
        self.pos += (1u64 << self.max) >> self.level;
    }

    /// Whether the position is on the grid of the next coarser level (and there is one above
    /// `floor`).
    #[inline]
    pub(crate) fn can_coarsen(&self, floor: u32) -> bool {
        self.level > floor
            && self
                .pos
                .is_multiple_of((1u64 << self.max) >> (self.level - 1))
    }

    /// Go up one level (call where [`DyadicWalk::can_coarsen`]).
    #[inline]
    pub(crate) fn coarsen(&mut self) {
        self.level -= 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The count of steps ≤ dt: whole multiples up to round-off keep their count, anything
    /// longer takes one more, and a span shorter than dt is one step.
    #[test]
    fn step_counts() {
        assert_eq!(step_count(20.0, 0.01), 2000.0);
        assert_eq!(step_count(0.3, 0.1), 3.0); // 0.3/0.1 = 2.9999999999999996
        assert_eq!(step_count(1.0, 0.3), 4.0);
        assert_eq!(step_count(1e-3, 0.01), 1.0);
        let (steps, last) = step_plan(0.3, 1.0);
        assert_eq!(steps, 4);
        assert!((last - 0.1).abs() < 1e-15);
    }

    /// Equal steps tile the span, the last ending on it exactly.
    #[test]
    fn equal_steps_tile_the_span() {
        let p = EqualSteps::new(0.7, 1.05, 0.1);
        assert_eq!(p.steps, 4.0);
        assert!((p.h - 0.0875).abs() < 1e-15);
        let mut t = p.start;
        for i in 0..p.steps as usize {
            let (a, b) = p.bounds(i);
            assert!((a - t).abs() < 1e-15);
            t = b;
        }
        assert_eq!(t, p.end);
    }

    /// A walk refined in the middle and coarsened where aligned covers the base step exactly
    /// once: the sub-steps' lengths sum to hh and each starts where the last ended.
    #[test]
    fn a_dyadic_walk_tiles_the_base_step() {
        let hh = 0.01;
        let mut w = DyadicWalk::new(1, 10);
        let (mut covered, mut n) = (0.0, 0);
        while !w.done() {
            assert!((w.offset(hh) - covered).abs() < 1e-15);
            // refine once at the second sub-step of level 1, and 3 more at offset ½hh
            if n == 1 || (w.level == 2 && (w.offset(hh) - 0.5 * hh).abs() < 1e-15) {
                w.refine(if n == 1 { 1 } else { 3 });
                n += 1;
                continue;
            }
            covered += w.length(hh);
            w.advance();
            while w.can_coarsen(0) {
                w.coarsen();
            }
            n += 1;
        }
        assert!((covered - hh).abs() < 1e-15, "{covered}");
        assert!(w.level == 0 && !w.finest());
    }

    /// A walk placed mid-step answers by its definition in exact integers: aligned at level m
    /// iff pos is a multiple of 2^(max−m), the index ⌊pos/2^(max−m)⌋, the distance to the
    /// next level-m point 2^(max−m) − pos mod 2^(max−m). An entry step to the next level-3
    /// point followed by level-3 sub-steps tiles the rest of the base step exactly.
    #[test]
    fn a_walk_placed_mid_step_tiles_the_rest() {
        let max = 10;
        let w = DyadicWalk::at(0b01_0110_0000, 2, max); // 352 = 11·32 = 5.5·64
        assert_eq!(w.pos(), 352);
        assert!(w.aligned(5) && w.aligned(6) && w.aligned(10));
        assert!(!w.aligned(4) && !w.aligned(3) && !w.aligned(0));
        assert_eq!((w.index(5), w.index(3), w.index(0)), (11, 2, 0));
        assert_eq!(
            (w.until_next(5), w.until_next(3), w.until_next(2)),
            (32, 32, 160)
        );
        assert_eq!(w.until_next(0), 1024 - 352);
        // every position: the next point is on the grid, and no point lies between
        for pos in 0..1u64 << max {
            let w = DyadicWalk::at(pos, 0, max);
            for m in 0..=max {
                let unit = 1u64 << (max - m);
                let d = w.until_next(m);
                assert!(
                    (1..=unit).contains(&d) && (pos + d) / unit * unit == pos + d,
                    "{pos} {m}"
                );
                assert_eq!(w.aligned(m), pos / unit * unit == pos);
                assert_eq!(w.index(m), pos / unit);
            }
        }
        // the entry step, then level-3 sub-steps: positions exact, lengths sum to the rest
        let mut w = DyadicWalk::at(352, 3, max);
        let first = w.until_next(3);
        w = DyadicWalk::at(w.pos() + first, 3, max);
        let mut walked = first;
        while !w.done() {
            assert!(w.aligned(3));
            walked += w.until_next(3);
            w.advance();
        }
        assert_eq!((w.pos(), walked), (1024, 1024 - 352));
    }
}
