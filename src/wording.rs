//! The words a run's text, its report and its page give the struck beam's measured point, its
//! first support and the striking body (issue 45). The paper's pair is a bridge falling onto the
//! free end of a clamped cantilever: "end deflection", "clamp", "bridge". A beam on two supports,
//! or one struck elsewhere than its free end, is measured at the contact point; a pinned first
//! support is a pin (its bending stress is zero by construction); a rigid impactor
//! (`upper.kind = "mass"`) is no bridge and has no bending stress, hinge or modes of its own.
//! JSON field names never change with the wording: only the words a reader sees.

use crate::model::scenario::ImpactorKind;
use crate::model::Scenario;

/// The words of one scenario.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Wording {
    /// The struck beam's first support (x = 0): `"clamp"` or `"pin"`.
    pub first_support: &'static str,
    /// True when w_din,a is measured at the contact point rather than at a free end.
    pub at_contact: bool,
    /// True for a rigid impactor (`upper.kind = "mass"`).
    pub rigid_impactor: bool,
    /// True when the energy method's spring is the paper's k_f = 3 E I / l^3 (a uniform
    /// cantilever struck at its free end).
    pub uniform_cantilever_tip: bool,
}

impl Default for Wording {
    /// The paper's pair's words.
    fn default() -> Self {
        Wording { first_support: "clamp", at_contact: false, rigid_impactor: false, uniform_cantilever_tip: true }
    }
}

impl Wording {
    /// The words for `s`.
    pub fn of(s: &Scenario) -> Wording {
        let l = &s.lower;
        let at_contact = l.supports.has_far_support() || s.lower_contact_position() != l.length;
        Wording {
            first_support: if l.supports.first_is_clamped() { "clamp" } else { "pin" },
            at_contact,
            rigid_impactor: s.upper.kind == ImpactorKind::Mass,
            uniform_cantilever_tip: !at_contact && l.sections.is_empty(),
        }
    }

    /// The striking body: `"bridge"` or `"impactor"`.
    pub fn striker(&self) -> &'static str {
        if self.rigid_impactor {
            "impactor"
        } else {
            "bridge"
        }
    }

    /// Where w_din,a is measured, as a phrase: `"end deflection"` or `"deflection at the contact"`.
    pub fn deflection(&self) -> &'static str {
        if self.at_contact {
            "deflection at the contact"
        } else {
            "end deflection"
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The paper's scenario keeps the paper's words; a pinned-pinned beam struck by a mass gets
    /// a pin, the contact point and an impactor.
    #[test]
    fn the_words_follow_the_supports_and_the_impactor() {
        let paper = Scenario::paper();
        assert_eq!(Wording::of(&paper), Wording::default());
        let mut s = Scenario::paper();
        s.lower.supports = crate::model::supports::Supports::PinnedPinned;
        s.upper.kind = ImpactorKind::Mass;
        let w = Wording::of(&s);
        assert_eq!((w.first_support, w.at_contact, w.rigid_impactor), ("pin", true, true));
        assert_eq!((w.striker(), w.deflection()), ("impactor", "deflection at the contact"));
        s.lower.supports = crate::model::supports::Supports::ClampedFree;
        s.lower.contact_position = 0.5 * s.lower.length;
        assert!(Wording::of(&s).at_contact, "a cantilever struck inside its span is measured at the contact");
        assert_eq!(Wording::of(&s).first_support, "clamp");
    }
}
