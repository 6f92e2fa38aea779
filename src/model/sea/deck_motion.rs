//! The supports on the deck: the six motions of the vessel projected onto the hinge's heave and
//! the clamp's heave and rotation, small angles (docs/moving-supports.md): a deck point at (x, y)
//! from the motion reference point rises by w = heave - x theta + y phi (pitch theta bow down,
//! roll phi starboard down), and the clamp turns with the deck's slope along the arrestor's axis,
//! dw/ds = -theta cos psi + phi sin psi, psi the axis (clamp to free end) from the bow towards port.
//! The points' z and the horizontal motions (surge, sway, yaw) do not enter: the gangway's model
//! is vertical (the page's "what the model leaves out").
//!
//! Linear in the motions, so it applies to each component's complex RAOs as well as to motions.

use nalgebra::Complex;

/// Where the supports stand on the vessel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DeckPoints {
    /// The hinge's deck point (x, y, z), m, or `None`: the hinge stands on a fixed platform.
    pub hinge: Option<[f64; 3]>,
    /// The clamp's deck point, m, or `None`: the clamp stands on a fixed platform.
    pub clamp: Option<[f64; 3]>,
    /// The arrestor's axis psi (clamp to free end), deg from the bow towards port (180: aft).
    pub arrestor_direction: f64,
}

impl DeckPoints {
    /// The deck's vertical motion at `point` from the six motions (surge to yaw; translations m,
    /// rotations rad): heave - x pitch + y roll.
    fn rise(point: [f64; 3], six: &[Complex<f64>; 6]) -> Complex<f64> {
        six[2] - six[4] * point[0] + six[3] * point[1]
    }

    /// The hinge's heave (m), the clamp's heave (m) and rotation (rad) from the six motions
    /// (complex RAOs per metre of wave, or amplitudes): zero for a support on a fixed platform.
    pub fn supports(&self, six: &[Complex<f64>; 6]) -> [Complex<f64>; 3] {
        let zero = Complex::new(0.0, 0.0);
        let psi = self.arrestor_direction.to_radians();
        [
            self.hinge.map_or(zero, |p| Self::rise(p, six)),
            self.clamp.map_or(zero, |p| Self::rise(p, six)),
            self.clamp.map_or(zero, |_| -six[4] * libm::cos(psi) + six[3] * libm::sin(psi)),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pitch_lowers_the_bow_and_roll_the_starboard_side() {
        let c = |x: f64| Complex::new(x, 0.0);
        // Pitch 0.01 rad bow down: a point 10 m forward drops 0.1 m, 10 m aft rises 0.1 m.
        let pitch = [c(0.0), c(0.0), c(0.0), c(0.0), c(0.01), c(0.0)];
        let deck =
            DeckPoints { hinge: Some([10.0, 0.0, 5.0]), clamp: Some([-10.0, 0.0, 5.0]), arrestor_direction: 180.0 };
        let s = deck.supports(&pitch);
        assert!((s[0].re + 0.1).abs() < 1e-15 && (s[1].re - 0.1).abs() < 1e-15);
        // The arrestor points aft: with the bow down, its end (further aft) rises: +0.01 rad.
        assert!((s[2].re - 0.01).abs() < 1e-15);
        // Roll 0.01 rad starboard down: a point 5 m to port rises 0.05 m; an arrestor pointing to
        // port (psi = 90) turns up by 0.01 rad.
        let roll = [c(0.0), c(0.0), c(0.0), c(0.01), c(0.0), c(0.0)];
        let deck = DeckPoints { hinge: None, clamp: Some([0.0, 5.0, 0.0]), arrestor_direction: 90.0 };
        let s = deck.supports(&roll);
        assert_eq!(s[0], c(0.0));
        assert!((s[1].re - 0.05).abs() < 1e-15 && (s[2].re - 0.01).abs() < 1e-15);
    }
}
