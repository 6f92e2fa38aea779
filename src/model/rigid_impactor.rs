//! A rigid impactor (issue 45): `upper.kind = "mass"`, a rigid body of `upper.mass` kg moving
//! vertically (one translational DOF, no rotation) that strikes the struck beam's contact point
//! at `impact_speed`, or after a free fall from `drop_height` (v = sqrt(2 g h)); and the Hertz
//! law's constant of a sphere of `upper.radius` on a flat face (`contact.law = "hertz"`). The
//! scenario's rules for both: which fields apply, their ranges, and the refusals of fields that
//! would be ignored.

use super::contact_law::{LawKind, EXPONENT_RANGE};
use super::scenario::{
    bound, within, ImpactorKind, Scenario, HERTZ_EXPONENT, MAX_POWER_LAW_STIFFNESS, SMALLEST_CONTACT_STIFFNESS,
};
use crate::error::{Error, Result};

/// Largest drop height of a rigid impactor, m (the FMU's declared maximum of `drop_height`): a
/// fall of 500 m reaches 99 m/s in vacuum, far beyond an elastic impact (steel on steel yields
/// from about 0.1-1 m/s at a sphere's contact).
pub const MAX_DROP_HEIGHT: f64 = 500.0;

/// Largest impact speed of a rigid impactor, m/s (see [`MAX_DROP_HEIGHT`]).
pub const MAX_IMPACT_SPEED: f64 = 1e3;

/// Smallest and largest radius of a Hertz contact, m: a 1 um asperity to a 1 km body.
pub const RADIUS_RANGE: (f64, f64) = (1e-6, 1e3);

/// The largest Poisson's ratio accepted: below an isotropic solid's limit 1/2 (incompressible),
/// with rubber's 0.4999 inside.
pub const MAX_POISSON_RATIO: f64 = 0.4999;

/// The `[upper]` fields a rigid impactor takes; the rest are the bridge's.
pub const MASS_FIELDS: [&str; 6] = ["kind", "mass", "radius", "poisson_ratio", "elastic_modulus", "tip_force"];

/// The impactor's speed at first contact, m/s: `impact_speed` when given, else a free fall
/// from `drop_height`, v = sqrt(2 g h) (0 for a mass resting on the contact).
pub fn impact_speed(s: &Scenario) -> f64 {
    if s.impact_speed != 0.0 {
        s.impact_speed
    } else {
        (2.0 * s.gravity * s.drop_height).max(0.0).sqrt()
    }
}

/// Hertz's constant of the scenario's sphere on the struck beam: [`Scenario::hertz_constant`].
pub fn hertz_constant(s: &Scenario) -> f64 {
    s.hertz_constant()
}

/// A scenario file with `upper.kind = "mass"` that states a bridge's field (or where the bridge
/// is struck): refused, the mass has none of them.
pub fn refuse_beam_fields(text: &str) -> Result<()> {
    let Ok(table) = text.parse::<toml::Table>() else { return Ok(()) };
    let mut given: Vec<String> = table
        .get("upper")
        .and_then(|u| u.as_table())
        .map(|u| u.keys().filter(|k| !MASS_FIELDS.iter().any(|f| f == k)).map(|k| format!("upper.{k}")).collect())
        .unwrap_or_default();
    for key in ["contact_position", "impact_angular_velocity", "stress_recovery"] {
        if table.contains_key(key) {
            given.push(key.to_string());
        }
    }
    if given.is_empty() {
        return Ok(());
    }
    Err(Error::Other(format!(
        "upper.kind = \"mass\" is a rigid body, not the bridge, but {} {} given: leave {} out (a mass takes {})",
        given.join(", "),
        if given.len() == 1 { "is" } else { "are" },
        if given.len() == 1 { "it" } else { "them" },
        MASS_FIELDS.iter().map(|k| format!("upper.{k}")).collect::<Vec<_>>().join(", ")
    )))
}

/// Leaves out of a scenario's TOML table what a rigid impactor does not take (so that the
/// text reads back: see [`refuse_beam_fields`]).
pub fn retain_mass_fields(table: &mut toml::Table) {
    if let Some(toml::Value::Table(upper)) = table.get_mut("upper") {
        upper.retain(|k, _| MASS_FIELDS.contains(&k));
    }
    for key in ["contact_position", "impact_angular_velocity", "stress_recovery"] {
        table.remove(key);
    }
}

/// The rules of the impact's speed and of the Poisson's ratios, for either impactor: a mass's
/// drop height and speed (one of the two), `impact_speed` refused for the bridge (its speed is
/// `impact_angular_velocity`), both ratios 0 <= nu < 0.5.
pub fn validation_errors(s: &Scenario) -> Vec<Error> {
    let mut errors = Vec::new();
    let mut check = |result: Result<()>| {
        if let Err(e) = result {
            errors.push(e);
        }
    };
    for (name, nu) in [("upper.poisson_ratio", s.upper.poisson_ratio), ("lower.poisson_ratio", s.lower.poisson_ratio)] {
        if !(nu.is_finite() && (0.0..=MAX_POISSON_RATIO).contains(&nu)) {
            check(Err(Error::invalid(
                name,
                format!("between 0 and {MAX_POISSON_RATIO} (an isotropic solid's nu < 1/2)"),
                bound(nu),
            )));
        }
    }
    if s.upper.radius != 0.0 {
        check(within("upper.radius", "m (0: not given)", s.upper.radius, RADIUS_RANGE.0, RADIUS_RANGE.1));
    }
    if s.upper.kind == ImpactorKind::Beam {
        if s.impact_speed != 0.0 {
            check(Err(Error::invalid(
                "impact_speed",
                "0 (not given) with upper.kind = \"beam\" (a mass's speed; the bridge's is impact_angular_velocity)",
                bound(s.impact_speed),
            )));
        }
        return errors;
    }
    check(within("drop_height", "m", s.drop_height, 0.0, MAX_DROP_HEIGHT));
    check(within("impact_speed", "m/s (0: not given)", s.impact_speed, 0.0, MAX_IMPACT_SPEED));
    if s.impact_speed != 0.0 && s.drop_height != 0.0 {
        check(Err(Error::Other(format!(
            "drop_height = {} m and impact_speed = {} m/s are both given: give one (the mass's speed at first \
             contact, or the height it falls from; with impact_speed, drop_height is 0)",
            bound(s.drop_height),
            bound(s.impact_speed)
        ))));
    }
    if let Some(omega) = s.impact_angular_velocity {
        check(Err(Error::invalid(
            "impact_angular_velocity",
            "absent with upper.kind = \"mass\" (the bridge's; a mass strikes at impact_speed)",
            bound(omega),
        )));
    }
    if s.gravity == 0.0 && s.impact_speed == 0.0 && s.drop_height != 0.0 {
        check(Err(Error::Other(
            "gravity = 0 needs impact_speed: nothing makes the mass fall, so state the impact by its speed (and \
             drop_height = 0)"
                .into(),
        )));
    }
    if !s.upper.sections.is_empty() {
        check(Err(Error::invalid(
            "upper.sections",
            "absent with upper.kind = \"mass\" (a rigid body has no sections)",
            format!("{} sections", s.upper.sections.len()),
        )));
    }
    errors
}

/// The rules of `contact.law = "hertz"`: a radius, no stiffness of its own, the exponent 3/2 or
/// not given, and a constant within the power law's range.
pub fn hertz_errors(s: &Scenario) -> Vec<Error> {
    let mut errors = Vec::new();
    let c = &s.contact;
    let radius_ok = RADIUS_RANGE.0 <= s.upper.radius && s.upper.radius <= RADIUS_RANGE.1;
    if s.upper.radius == 0.0 {
        errors.push(Error::invalid(
            "upper.radius",
            "given with contact.law = \"hertz\" (the sphere's radius, m: k = 4/3 E* sqrt(R))",
            "0 (not given)",
        ));
    }
    if let Some(k) = c.given_stiffness {
        errors.push(Error::invalid(
            "contact.stiffness",
            "absent with contact.law = \"hertz\" (its constant is 4/3 E* sqrt(R), from upper.radius and both bodies' \
             moduli)",
            bound(k),
        ));
    }
    if c.exponent != 0.0 && c.exponent != HERTZ_EXPONENT && (EXPONENT_RANGE.0..=EXPONENT_RANGE.1).contains(&c.exponent)
    {
        errors.push(Error::invalid(
            "contact.exponent",
            "0 (not given) or 1.5 with contact.law = \"hertz\" (for another exponent set contact.law = \"power\")",
            bound(c.exponent),
        ));
    }
    let moduli_ok = [s.upper.elastic_modulus, s.lower.elastic_modulus].iter().all(|e| e.is_finite() && *e > 0.0);
    let ratios_ok =
        [s.upper.poisson_ratio, s.lower.poisson_ratio].iter().all(|nu| (0.0..=MAX_POISSON_RATIO).contains(nu));
    if radius_ok && moduli_ok && ratios_ok {
        let k = hertz_constant(s);
        if !(SMALLEST_CONTACT_STIFFNESS..=MAX_POWER_LAW_STIFFNESS).contains(&k) {
            errors.push(Error::invalid(
                "contact.law = \"hertz\"'s constant 4/3 E* sqrt(R)",
                format!("between {SMALLEST_CONTACT_STIFFNESS:e} and {MAX_POWER_LAW_STIFFNESS:e} N/m^1.5"),
                bound(k),
            ));
        }
    }
    if c.law != LawKind::Hertz {
        errors.clear();
    }
    errors
}

/// The rigid impactor's rules as the scenario applies them (methods here, so that the scenario's
/// file does not use this one: the rules extend the scenario, not the other way round).
impl Scenario {
    /// [`refuse_beam_fields`].
    pub(super) fn refuse_mass_beam_fields(text: &str) -> Result<()> {
        refuse_beam_fields(text)
    }

    /// [`retain_mass_fields`].
    pub(super) fn retain_mass_fields(table: &mut toml::Table) {
        retain_mass_fields(table)
    }

    /// [`validation_errors`].
    pub(super) fn rigid_impactor_errors(&self) -> Vec<Error> {
        validation_errors(self)
    }

    /// [`hertz_errors`].
    pub(super) fn hertz_errors(&self) -> Vec<Error> {
        hertz_errors(self)
    }

    /// [`impact_speed`].
    pub(super) fn mass_impact_speed(&self) -> f64 {
        impact_speed(self)
    }
}
