//! The supports' motion in a sea: for each support coordinate j (the hinge's heave, the clamp's
//! heave and rotation, [`DeckPoints::supports`] of the six RAOs) the sum over the components
//! x_j(t) = sum a_i |H_j(w_i)| cos(w_i t + phi_i + eps_j(w_i)) = Re(sum c_ij e^(i w_i t)) with
//! c_ij = a_i e^(i phi_i) H_j(w_i), its velocity and acceleration the exact derivatives of the sum
//! (i w_i and -w_i^2 times each term), t the record's time.
//!
//! Sampled every `dt` on the record's own grid (record times k dt, k whole), the samples are the
//! support-motion table the solver takes from a motion file ([`MotionTable`]): between rows each
//! support moves with the row's constant acceleration, so the motion followed departs from the
//! sum by at most sum a|H| w^3 dt^3 / 6 in displacement, w^3 dt^2 / 2 in velocity and w^3 dt in
//! acceleration (the third derivative over the interval): with the default dt = 5 ms, per metre
//! of response at w = 1 rad/s, 2e-8 m, 1.3e-5 m/s and 0.5 % of the acceleration's amplitude (1.5 %
//! at 3 rad/s). The grid being the record's, a `beam-impact sea` file and a `[sea]` run sample the
//! same instants and give the same rows to the bit.

use nalgebra::Complex;

use super::components::WaveComponents;
use super::deck_motion::DeckPoints;
use super::raos::RaoTable;
use crate::model::motion_table::MotionTable;
use crate::model::support_motion::{check_motion_value, SupportMotion, Track, MOTION_NAMES};

/// Adds one component's terms to the sums `v` (displacement, velocity, acceleration of each
/// support coordinate): Re(c e^(i w t)) and its exact derivatives, with cos(w t) = `co`,
/// sin(w t) = `s`.
fn add_terms(v: &mut [f64; 9], c: &[Complex<f64>; 3], w: f64, co: f64, s: f64) {
    for (j, cj) in c.iter().enumerate() {
        let re = cj.re * co - cj.im * s;
        let rate = -(cj.re * s + cj.im * co);
        v[3 * j] += re;
        v[3 * j + 1] += w * rate;
        v[3 * j + 2] -= w * w * re;
    }
}

/// Blocks advanced side by side in [`add_component`] (the CPU's vector across the blocks): eight
/// f64 fill an AVX-512 register, four an AVX2 one ([`lanes`]).
const WIDE: usize = 8;
/// The lanes where AVX-512 is missing.
const NARROW: usize = 4;

/// Whether this CPU advances [`WIDE`] blocks at once (AVX-512), else [`NARROW`]: the rows' bits
/// are the same either way (each lane is one block's own sums).
fn wide() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        std::arch::is_x86_feature_detected!("avx512f")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// The nine sums of [`add_terms`] for each row of `N` blocks: `[row][sum][lane]`.
type Chunk<const N: usize> = [[[f64; N]; 9]; ANCHOR_ROWS];

/// One component's terms added to every row of one chunk of `N` blocks ([`SeaRecord::motions`]):
/// (`re`, `im`) hold each block's e^(i w t) at its anchor and are advanced by `step` = e^(i w dt)
/// row by row (num-complex's product, written out: the same operations in the same order), each
/// term as [`add_terms`] makes it (the same bits). The chunk's sums (9 to 18 KB) stay in the
/// first-level cache while every component passes over them, and each row's phase stays in
/// registers for its nine sums.
#[multiversion::multiversion(targets("x86_64+avx512f", "x86_64+avx2"))]
fn add_component<const N: usize>(
    sums: &mut Chunk<N>,
    (mut re, mut im): ([f64; N], [f64; N]),
    c: &[Complex<f64>; 3],
    w: f64,
    step: Complex<f64>,
) {
    let w2 = w * w;
    for (j, row) in sums.iter_mut().enumerate() {
        if j > 0 {
            for l in 0..N {
                let (a, b) = (re[l], im[l]);
                re[l] = a * step.re - b * step.im;
                im[l] = a * step.im + b * step.re;
            }
        }
        for (k, cj) in c.iter().enumerate() {
            let [value, rate_sum, acceleration] = &mut row[3 * k..3 * k + 3] else { unreachable!() };
            for l in 0..N {
                let (co, s) = (re[l], im[l]);
                let re = cj.re * co - cj.im * s;
                let rate = -(cj.re * s + cj.im * co);
                value[l] += re;
                rate_sum[l] += w * rate;
                acceleration[l] -= w2 * re;
            }
        }
    }
}

/// The sums as the supports' motion.
fn support_motion(v: &[f64; 9]) -> SupportMotion {
    let track = |j: usize| Track { displacement: v[3 * j], velocity: v[3 * j + 1], acceleration: v[3 * j + 2] };
    SupportMotion { hinge_heave: track(0), clamp_heave: track(1), clamp_rotation: track(2) }
}

/// Rows between the exact phases of [`SeaRecord::motions`].
pub const ANCHOR_ROWS: usize = 32;

/// A realisation of the sea with the supports' response to it.
#[derive(Clone, Debug, PartialEq)]
pub struct SeaRecord {
    /// The wave components.
    pub components: WaveComponents,
    /// Per component, c_ij = a_i e^(i phi_i) H_j(w_i) for the hinge's heave (m), the clamp's heave
    /// (m) and rotation (rad).
    coefficients: Vec<[Complex<f64>; 3]>,
}

impl SeaRecord {
    /// The record of `components` for a vessel of `raos` in waves travelling at `heading` deg,
    /// its supports at `deck`. Every component's frequency must lie in the RAO table's range.
    pub fn new(components: WaveComponents, raos: &RaoTable, heading: f64, deck: &DeckPoints) -> Result<Self, String> {
        let column = raos.at_heading(heading)?;
        let mut coefficients = Vec::with_capacity(components.frequencies.len());
        for i in 0..components.frequencies.len() {
            let w = components.frequencies[i];
            let six = raos.at_frequency(&column, w).ok_or_else(|| {
                let (lo, hi) = raos.frequency_range();
                format!("wave component at {w} rad/s is outside the RAO file's frequencies ({lo} to {hi} rad/s)")
            })?;
            let wave = Complex::from_polar(components.amplitudes[i], components.phases[i]);
            let supports = deck.supports(&six);
            coefficients.push(std::array::from_fn(|j| wave * supports[j]));
        }
        Ok(SeaRecord { components, coefficients })
    }

    /// The supports' motion at the record's time `t` (exact sums and derivatives).
    pub fn motion(&self, t: f64) -> SupportMotion {
        let mut v = [0.0; 9];
        for (i, c) in self.coefficients.iter().enumerate() {
            let w = self.components.frequencies[i];
            let (s, co) = libm::sincos(w * t);
            add_terms(&mut v, c, w, co, s);
        }
        support_motion(&v)
    }

    /// The wave elevation at the motion reference point at the record's time `t`, m.
    pub fn elevation(&self, t: f64) -> f64 {
        self.components.elevation(t)
    }

    /// The whole `k` of the record's grid (times k dt) from the last at or before `start` to the
    /// first at or after `end`.
    pub fn grid(start: f64, end: f64, dt: f64) -> (i64, i64) {
        let mut first = (start / dt).floor() as i64;
        while first as f64 * dt > start {
            first -= 1;
        }
        let mut last = (end / dt).ceil() as i64;
        while (last as f64) * dt < end {
            last += 1;
        }
        (first, last)
    }

    /// The supports' motion at the record's times k dt for k = `first` to `last`: the sums of
    /// [`Self::motion`], each component's e^(i w_i t) advanced from row to row by one complex
    /// product with e^(i w_i dt) and taken afresh from `sincos` at every k that is a multiple of
    /// [`ANCHOR_ROWS`] (a row's bits depend on k alone), so that a row departs from [`Self::motion`] by a few units in the last place of each term (the
    /// products' rounding over at most 31 rows) at a fifth of its cost (no sine per term).
    pub fn motions(&self, first: i64, last: i64, dt: f64) -> Vec<SupportMotion> {
        let rows = (last - first + 1).max(0) as usize;
        if rows == 0 {
            return Vec::new();
        }
        if wide() {
            self.motions_by::<WIDE>(first, last, dt)
        } else {
            self.motions_by::<NARROW>(first, last, dt)
        }
    }

    /// [`Self::motions`] with `N` blocks advanced side by side (the same rows to the bit for any
    /// `N`).
    fn motions_by<const N: usize>(&self, first: i64, last: i64, dt: f64) -> Vec<SupportMotion> {
        // The rows by blocks of ANCHOR_ROWS, each from its anchor's exact phase: the blocks are
        // independent, so each component advances N of them side by side (the CPU's vectors
        // across the blocks), every row getting the same terms in the same order as one block
        // after the other would give it (the same bits). A chunk of N blocks takes every
        // component before the next chunk (its sums stay in cache); lanes past the last block
        // are padding (phase 1, never read).
        let block = ANCHOR_ROWS as i64;
        let anchor = first.div_euclid(block) * block;
        let blocks = ((last - anchor) / block + 1) as usize;
        let chunks = blocks.div_ceil(N);
        let steps: Vec<Complex<f64>> = self
            .components
            .frequencies
            .iter()
            .map(|&w| {
                let (s, co) = libm::sincos(w * dt);
                Complex::new(co, s)
            })
            .collect();
        let mut sums: Vec<Chunk<N>> = vec![[[[0.0; N]; 9]; ANCHOR_ROWS]; chunks];
        for (n, chunk) in sums.iter_mut().enumerate() {
            for (i, c) in self.coefficients.iter().enumerate() {
                let w = self.components.frequencies[i];
                let (mut re, mut im) = ([1.0; N], [0.0; N]);
                for l in 0..N.min(blocks - n * N) {
                    let k = anchor + ((n * N + l) as i64) * block;
                    let (s, co) = libm::sincos(w * (k as f64 * dt));
                    (re[l], im[l]) = (co, s);
                }
                add_component::<N>(chunk, (re, im), c, w, steps[i]);
            }
        }
        (first..=last)
            .map(|k| {
                let (b, j) = (((k - anchor) / block) as usize, ((k - anchor) % block) as usize);
                let row = &sums[b / N][j];
                support_motion(&std::array::from_fn(|m| row[m][b % N]))
            })
            .collect()
    }

    /// The support-motion table of the record from `start` to `end` (record times, s) sampled
    /// every `dt` s on the record's grid ([`Self::motions`]), every value checked against the
    /// model's range. The table has all nine columns (a support on a fixed platform: zeros).
    pub fn table(&self, start: f64, end: f64, dt: f64) -> Result<MotionTable, String> {
        let (first, last) = Self::grid(start, end, dt);
        let motions = self.motions(first, last, dt);
        let times: Vec<f64> = (first..=last).map(|k| k as f64 * dt).collect();
        for (t, motion) in times.iter().zip(&motions) {
            for (n, value) in motion.values().iter().enumerate() {
                check_motion_value(n, *value).map_err(|e| {
                    format!("at the record's time {t} s {e}: the sea drives the supports beyond the model's range")
                })?;
            }
        }
        Ok(MotionTable { columns: MOTION_NAMES.to_vec(), times, motions })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// [`SeaRecord::motions`] one component after the other, row by row (the recurrence the
    /// blocked sums must reproduce to the bit).
    fn motions_row_by_row(record: &SeaRecord, first: i64, last: i64, dt: f64) -> Vec<SupportMotion> {
        let rows = (last - first + 1).max(0) as usize;
        let mut sums = vec![[0.0; 9]; rows];
        for (i, c) in record.coefficients.iter().enumerate() {
            let w = record.components.frequencies[i];
            let (s, co) = libm::sincos(w * dt);
            let step = Complex::new(co, s);
            let phase = |k: i64| {
                let (s, co) = libm::sincos(w * (k as f64 * dt));
                Complex::new(co, s)
            };
            let anchor = first.div_euclid(ANCHOR_ROWS as i64) * ANCHOR_ROWS as i64;
            let mut z = phase(anchor);
            for _ in anchor..first {
                z *= step;
            }
            for (k, row) in (first..).zip(sums.iter_mut()) {
                if k != first {
                    z = if k.rem_euclid(ANCHOR_ROWS as i64) == 0 { phase(k) } else { z * step };
                }
                add_terms(row, c, w, z.re, z.im);
            }
        }
        sums.iter().map(support_motion).collect()
    }

    fn record() -> SeaRecord {
        // Three components of made-up amplitudes, phases and support responses: the sums'
        // bookkeeping, not the sea, is under test.
        let components = WaveComponents {
            frequencies: vec![0.41, 0.93, 2.7],
            amplitudes: vec![0.8, 0.3, 0.05],
            phases: vec![0.3, 2.1, -1.2],
            bin_width: 0.1,
        };
        let coefficients = vec![
            [Complex::new(0.5, -0.2), Complex::new(-0.1, 0.4), Complex::new(0.01, 0.003)],
            [Complex::new(0.2, 0.1), Complex::new(0.3, -0.3), Complex::new(-0.02, 0.01)],
            [Complex::new(-0.05, 0.02), Complex::new(0.01, 0.07), Complex::new(0.004, -0.001)],
        ];
        SeaRecord { components, coefficients }
    }

    #[test]
    fn blocked_rows_are_the_row_by_row_recurrence_to_the_bit_at_either_width() {
        let record = record();
        // Tables starting on an anchor, inside a block, before the record's zero, one row long,
        // and ending inside a block.
        for (first, last) in [(0, 600), (17, 618), (-45, 3), (31, 31), (64, 95), (-1, 0), (1000, 1632)] {
            let reference = motions_row_by_row(&record, first, last, 0.005);
            let narrow = record.motions_by::<NARROW>(first, last, 0.005);
            let wide = record.motions_by::<WIDE>(first, last, 0.005);
            assert_eq!(narrow.len(), reference.len());
            assert_eq!(wide.len(), reference.len());
            let both = narrow.iter().zip(&wide).flat_map(|(n, w)| [n, w]);
            for (k, (a, b)) in both.zip(reference.iter().flat_map(|r| [r, r])).enumerate() {
                let (a, b) = (a.values(), b.values());
                assert!(
                    a.iter().zip(&b).all(|(x, y)| x.to_bits() == y.to_bits()),
                    "rows {first}..={last}, row {}, {} lanes: {a:?} against {b:?}",
                    k / 2,
                    [NARROW, WIDE][k % 2]
                );
            }
        }
        assert!(record.motions(5, 4, 0.005).is_empty());
    }
}
