//! The wave components of a long-crested, deep-water, first-order irregular sea: N equal bins over
//! [w_min, w_max], dw = (w_max - w_min) / N; in bin i a random frequency w_i = w_min + (i + u_i) dw
//! (so that the record has no period: equally spaced frequencies would repeat it every
//! 2 pi / dw), a random phase phi_i = 2 pi v_i and the amplitude a_i = sqrt(2 S(w_i) dw), the
//! random-phase method of OrcaFlex's and SIMA's random waves. The elevation at the vessel's motion
//! reference point is zeta(t) = sum a_i cos(w_i t + phi_i), t the record's time.
//!
//! The random numbers are splitmix64 (Steele, Lea and Flood 2014, the generator of Java's
//! `SplittableRandom`) seeded with the sea's `seed`, u = (next >> 11) 2^-53, drawn u_i then v_i
//! for i = 0, 1, ...: integer arithmetic, so a seed gives the same components everywhere.

use super::spectrum::Spectrum;

/// splitmix64: a 64-bit state advanced by the golden-ratio increment, then mixed.
#[derive(Clone, Debug)]
pub struct SplitMix64 {
    state: u64,
}

impl SplitMix64 {
    /// The generator seeded with `seed`.
    pub fn new(seed: u64) -> SplitMix64 {
        SplitMix64 { state: seed }
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.state = self.state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// A uniform number in [0, 1) with 53 random bits.
    pub fn next_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
}

/// The components of one realisation.
#[derive(Clone, Debug, PartialEq)]
pub struct WaveComponents {
    /// Angular frequencies w_i, rad/s, one in each bin, ascending.
    pub frequencies: Vec<f64>,
    /// Amplitudes a_i = sqrt(2 S(w_i) dw), m.
    pub amplitudes: Vec<f64>,
    /// Phases phi_i, rad, in [0, 2 pi).
    pub phases: Vec<f64>,
    /// The bin width dw, rad/s.
    pub bin_width: f64,
}

impl WaveComponents {
    /// `count` components of `spectrum` over [`lo`, `hi`] rad/s drawn from `seed`.
    pub fn new(spectrum: &Spectrum, count: usize, lo: f64, hi: f64, seed: u64) -> WaveComponents {
        let dw = (hi - lo) / count as f64;
        let mut rng = SplitMix64::new(seed);
        let mut frequencies = Vec::with_capacity(count);
        let mut amplitudes = Vec::with_capacity(count);
        let mut phases = Vec::with_capacity(count);
        for i in 0..count {
            let u = rng.next_f64();
            let v = rng.next_f64();
            let w = lo + (i as f64 + u) * dw;
            frequencies.push(w);
            amplitudes.push((2.0 * spectrum.density(w) * dw).sqrt());
            phases.push(2.0 * std::f64::consts::PI * v);
        }
        WaveComponents { frequencies, amplitudes, phases, bin_width: dw }
    }

    /// The elevation at the motion reference point at the record's time `t`, m.
    pub fn elevation(&self, t: f64) -> f64 {
        let mut sum = 0.0;
        for i in 0..self.frequencies.len() {
            sum += self.amplitudes[i] * libm::cos(self.frequencies[i] * t + self.phases[i]);
        }
        sum
    }

    /// The variance the components carry, sum a_i^2 / 2, m^2 (the discrete m0).
    pub fn variance(&self) -> f64 {
        self.amplitudes.iter().map(|a| 0.5 * a * a).sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn splitmix64_gives_the_reference_sequence() {
        // The reference implementation's outputs (Vigna's splitmix64.c) for this seed, as the
        // `rand_xoshiro` crate's test `splitmix64::tests::reference` quotes them.
        let mut rng = SplitMix64::new(1_477_776_061_723_855_037);
        let expected: [u64; 5] =
            [1985237415132408290, 2979275885539914483, 13511426838097143398, 8488337342461049707, 15141737807933549159];
        for e in expected {
            assert_eq!(rng.next_u64(), e);
        }
    }

    #[test]
    fn each_frequency_lies_in_its_bin() {
        let c = WaveComponents::new(&Spectrum::pierson_moskowitz(2.0, 8.0), 100, 0.3, 3.3, 7);
        for (i, w) in c.frequencies.iter().enumerate() {
            let lo = 0.3 + i as f64 * c.bin_width;
            assert!(*w >= lo && *w < lo + c.bin_width + 1e-12, "{i}: {w}");
        }
    }
}
