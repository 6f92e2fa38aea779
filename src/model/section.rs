//! Sections along a beam (issue 30): a beam as a list of uniform segments, each with its own
//! second moment, section moduli, shear area, mass per metre and allowables, in order from the
//! support (the arrestor's clamp, the bridge's hinge). A beam without sections is one segment
//! of its uniform fields: the paper's idealisation.

use serde::{Deserialize, Serialize};

use crate::error::{number, Error, Result};

/// Most sections a beam may have: a truss's chords, a telescopic overlap and a bracket fit well
/// within it, and the mesh needs at least one element per section.
pub const MAX_SECTIONS: usize = 32;

/// Shortest section, as a fraction of its beam's length: below it the mesh's shortest element
/// would be too short beside the others for the stepper's steps (the graded meshes' limit).
pub const MIN_SECTION_FRACTION: f64 = 1e-3;

/// Largest ratio of the stiffest section's bending stiffness EI to the softest's in one beam:
/// beyond it the beam's natural modes lose their digits (measured on two-section beams, the soft
/// section at the support: the hinged bridge's rigid-mode check fails from a factor 1e9, the
/// clamped arrestor's from 1e11, with "the lowest elastic eigenvalue is not positive"). A
/// thousandth of that, and far beyond a real beam's (a truss's chords and a telescopic tip: 10 to
/// 100).
pub const MAX_STIFFNESS_RATIO: f64 = 1e6;

/// One segment of a beam as a scenario file states it (`[[lower.sections]]`, `[[upper.sections]]`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SectionSpec {
    /// Length of the segment along the beam, m.
    pub length: f64,
    /// Second moment of area I, m^4.
    pub second_moment: f64,
    /// Section modulus of the top fibre W, m^3 (of both fibres unless `section_modulus_bottom`).
    pub section_modulus: f64,
    /// Section modulus of the bottom fibre, m^3, if it differs from the top's.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub section_modulus_bottom: Option<f64>,
    /// Shear area A_s, m^2, for the shear stress Q / A_s.
    pub shear_area: f64,
    /// Mass per unit length, kg/m.
    pub mass_per_length: f64,
    /// Allowable bending stress, Pa (default: the beam's).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub allowable_bending_stress: Option<f64>,
    /// Allowable shear stress, Pa (default: the beam's).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub allowable_shear_stress: Option<f64>,
}

/// One resolved segment: where it sits and everything the model and the stresses need.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Segment {
    /// Start, m from the support.
    pub start: f64,
    /// End, m from the support.
    pub end: f64,
    /// Bending stiffness E I, N m^2.
    pub bending_stiffness: f64,
    /// Mass per unit length, kg/m.
    pub mass_per_length: f64,
    /// The smaller of the two fibres' section moduli, m^3: |sigma| = |M| / W at the worse fibre.
    pub section_modulus: f64,
    /// Shear area, m^2 (0: not given, no shear stress; the bridge's uniform form).
    pub shear_area: f64,
    /// Allowable bending stress, Pa.
    pub allowable_bending_stress: f64,
    /// Allowable shear stress, Pa (0: none given).
    pub allowable_shear_stress: f64,
}

/// A beam's uniform fields, the form every beam without sections takes.
#[derive(Clone, Copy, Debug)]
pub struct Uniform {
    /// Length, m.
    pub length: f64,
    /// Total distributed mass, kg.
    pub mass: f64,
    /// Young's modulus, Pa.
    pub elastic_modulus: f64,
    /// Second moment, m^4.
    pub second_moment: f64,
    /// Section modulus, m^3.
    pub section_modulus: f64,
    /// Shear area, m^2 (0: none).
    pub shear_area: f64,
    /// Allowable bending stress, Pa.
    pub allowable_bending_stress: f64,
    /// Allowable shear stress, Pa (0: none).
    pub allowable_shear_stress: f64,
}

/// The segments of a beam: its sections when given, else one segment of its uniform fields
/// (whose mass per metre is mass / length, as the uniform assembly has always used).
pub fn segments(uniform: &Uniform, sections: &[SectionSpec]) -> Vec<Segment> {
    if sections.is_empty() {
        return vec![Segment {
            start: 0.0,
            end: uniform.length,
            bending_stiffness: uniform.elastic_modulus * uniform.second_moment,
            mass_per_length: uniform.mass / uniform.length,
            section_modulus: uniform.section_modulus,
            shear_area: uniform.shear_area,
            allowable_bending_stress: uniform.allowable_bending_stress,
            allowable_shear_stress: uniform.allowable_shear_stress,
        }];
    }
    let mut start = 0.0;
    sections
        .iter()
        .map(|s| {
            let end = start + s.length;
            let segment = Segment {
                start,
                end,
                bending_stiffness: uniform.elastic_modulus * s.second_moment,
                mass_per_length: s.mass_per_length,
                section_modulus: s.section_modulus.min(s.section_modulus_bottom.unwrap_or(s.section_modulus)),
                shear_area: s.shear_area,
                allowable_bending_stress: s.allowable_bending_stress.unwrap_or(uniform.allowable_bending_stress),
                allowable_shear_stress: s.allowable_shear_stress.unwrap_or(uniform.allowable_shear_stress),
            };
            start = end;
            segment
        })
        .collect()
}

/// The section modulus, m^3, and the allowable bending stress, Pa, that the bending stress at
/// `position` m is checked with: on one segment its own; at a change between two, the smaller
/// modulus (the stress is |M| / W there) with the allowable that makes |M| / W / allowable the
/// worse side's utilisation, min_i(W_i allowable_i) / W.
pub fn bending_check_at(segments: &[Segment], position: f64) -> (f64, f64) {
    let touching = || segments.iter().filter(|g| g.start <= position && position <= g.end);
    if let [one] = touching().collect::<Vec<_>>()[..] {
        return (one.section_modulus, one.allowable_bending_stress);
    }
    let modulus = touching().map(|g| g.section_modulus).fold(f64::INFINITY, f64::min);
    let capacity = touching().map(|g| g.section_modulus * g.allowable_bending_stress).fold(f64::INFINITY, f64::min);
    (modulus, capacity / modulus)
}

/// The segments' mass, kg, first moment S = int mu x dx, kg m, and second moment
/// J = int mu x^2 dx, kg m^2, about the support (the rigid pitching's, Eqs. 17-22).
pub fn mass_moments(segments: &[Segment]) -> (f64, f64, f64) {
    segments.iter().fold((0.0, 0.0, 0.0), |(m, first, second), g| {
        let (a, b, mu) = (g.start, g.end, g.mass_per_length);
        (m + mu * (b - a), first + mu * (b * b - a * a) / 2.0, second + mu * (b * b * b - a * a * a) / 3.0)
    })
}

/// A cantilever's tip deflection per unit tip load, m/N: the unit-load integral
/// sum over segments of int (l - x)^2 / EI dx = ((l - a)^3 - (l - b)^3) / (3 EI) (Eq. 29's
/// l^3 / 3EI for one segment).
pub fn tip_flexibility(segments: &[Segment]) -> f64 {
    let l = segments.last().map_or(0.0, |g| g.end);
    segments
        .iter()
        .map(|g| {
            let (p, q) = (l - g.start, l - g.end);
            (p * p * p - q * q * q) / (3.0 * g.bending_stiffness)
        })
        .sum()
}

/// The sections' total length, m, and mass, kg.
pub fn totals(sections: &[SectionSpec]) -> (f64, f64) {
    sections.iter().fold((0.0, 0.0), |(l, m), s| (l + s.length, m + s.length * s.mass_per_length))
}

/// Every rule a beam's sections break, each naming the section (1-based, from the support) and
/// its field: `lower.sections[2].second_moment must be > 0 m^4, got -1`. Sections whose bending
/// stiffnesses (`elastic_modulus` times their second moments) differ by more than
/// [`MAX_STIFFNESS_RATIO`] are refused naming the softest and the stiffest with their EI.
pub fn validation_errors(beam: &str, elastic_modulus: f64, sections: &[SectionSpec]) -> Vec<Error> {
    let mut errors = Vec::new();
    if sections.len() > MAX_SECTIONS {
        errors.push(Error::invalid(
            format!("{beam}.sections"),
            format!("at most {MAX_SECTIONS} sections"),
            sections.len(),
        ));
        return errors;
    }
    let (total, _) = totals(sections);
    for (i, s) in sections.iter().enumerate() {
        let name = |field: &str| format!("{beam}.sections[{}].{field}", i + 1);
        let mut check = |field: &str, unit: &str, value: f64, lo: f64, hi: f64| {
            if !(value.is_finite() && value >= lo && value <= hi) {
                errors.push(Error::invalid(name(field), format!("between {lo:e} and {hi:e} {unit}"), number(value)));
            }
        };
        check("length", "m", s.length, 1e-4, 1e3);
        check("second_moment", "m^4", s.second_moment, 1e-12, 1e3);
        check("section_modulus", "m^3", s.section_modulus, 1e-12, 1e3);
        if let Some(w) = s.section_modulus_bottom {
            check("section_modulus_bottom", "m^3", w, 1e-12, 1e3);
        }
        check("shear_area", "m^2", s.shear_area, 1e-12, 1e3);
        check("mass_per_length", "kg/m", s.mass_per_length, 1e-6, 1e9);
        if let Some(a) = s.allowable_bending_stress {
            check("allowable_bending_stress", "Pa", a, 1e-3, 1e12);
        }
        if let Some(a) = s.allowable_shear_stress {
            check("allowable_shear_stress", "Pa", a, 1e-3, 1e12);
        }
        if total.is_finite() && total > 0.0 && s.length.is_finite() && s.length < MIN_SECTION_FRACTION * total {
            errors.push(Error::invalid(
                name("length"),
                format!(
                    "at least {MIN_SECTION_FRACTION} of the beam's {} m (shorter than the mesh can resolve beside \
                     the other sections)",
                    number(total)
                ),
                number(s.length),
            ));
        }
    }
    if errors.is_empty() {
        errors.extend(stiffness_ratio_error(beam, elastic_modulus, sections));
    }
    errors
}

/// The error of sections too unlike in bending stiffness ([`MAX_STIFFNESS_RATIO`]), naming the
/// later of the softest and the stiffest section's second moment, and both sections with their EI.
fn stiffness_ratio_error(beam: &str, elastic_modulus: f64, sections: &[SectionSpec]) -> Option<Error> {
    let by_moment =
        |a: &(usize, &SectionSpec), b: &(usize, &SectionSpec)| a.1.second_moment.total_cmp(&b.1.second_moment);
    let (soft, softest) = sections.iter().enumerate().min_by(by_moment)?;
    let (stiff, stiffest) = sections.iter().enumerate().max_by(by_moment)?;
    let ratio = stiffest.second_moment / softest.second_moment;
    if !(elastic_modulus.is_finite() && elastic_modulus > 0.0) || ratio <= MAX_STIFFNESS_RATIO {
        return None;
    }
    let (named, other) = if stiff > soft { (stiff, soft) } else { (soft, stiff) };
    Some(Error::invalid(
        format!("{beam}.sections[{}].second_moment", named + 1),
        format!(
            "within a factor {MAX_STIFFNESS_RATIO:e} of {beam}.sections[{}].second_moment = {} m^4 (EI {} N m^2 in \
             {beam}.sections[{}] against {} N m^2 in {beam}.sections[{}], a factor {}: beyond {MAX_STIFFNESS_RATIO:e} \
             the beam's natural modes lose their digits)",
            other + 1,
            short(sections[other].second_moment),
            short(elastic_modulus * softest.second_moment),
            soft + 1,
            short(elastic_modulus * stiffest.second_moment),
            stiff + 1,
            short(ratio)
        ),
        sections[named].second_moment,
    ))
}

/// `x` in exponent form to at most 5 significant digits, trailing zeros cut (`2.1e-1`, `1e12`).
fn short(x: f64) -> String {
    let text = format!("{x:.4e}");
    match text.split_once('e') {
        Some((mantissa, exponent)) if mantissa.contains('.') => {
            format!("{}e{exponent}", mantissa.trim_end_matches('0').trim_end_matches('.'))
        }
        _ => text,
    }
}

/// Checks a beam's uniform field against what its sections imply (`upper.length` given and
/// different from the sections' sum): an error naming both.
pub fn agrees(name: String, unit: &str, given: f64, implied: f64) -> Result<()> {
    if (given - implied).abs() <= 1e-9 * implied.abs().max(f64::MIN_POSITIVE) {
        Ok(())
    } else {
        Err(Error::invalid(
            name,
            format!("equal to what the beam's sections give, {implied} {unit} (or left out: it follows from them)"),
            given,
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Issue 40's re-test: a section length of 1e-300 was quoted as 302 characters, filling the
    /// error line's 600; every quoted value is now bounded in length (`1e-300`).
    #[test]
    fn a_tiny_or_huge_section_value_is_quoted_in_a_few_characters() {
        let section = |length: f64| SectionSpec {
            length,
            second_moment: 0.002075,
            section_modulus: 0.0125,
            section_modulus_bottom: None,
            shear_area: 0.0109,
            mass_per_length: 843.7,
            allowable_bending_stress: None,
            allowable_shear_stress: None,
        };
        for (length, shown) in [(1e-300, "got 1e-300"), (1e300, "got 1e300")] {
            let errors = validation_errors("lower", 2.1e11, &[section(length), section(12.0)]);
            let text = errors.iter().map(|e| e.to_string()).collect::<Vec<_>>().join("; ");
            assert!(text.contains("lower.sections[1].length") && text.contains(shown), "{text}");
            assert!(text.len() < 400, "{} characters: {text}", text.len());
        }
    }
}
