//! How a scenario is discretised: the method (the paper's own mesh and full modal basis, or a
//! converged answer), element counts and the modal cut-off, each of which may be `"auto"`.

use serde::de::{self, Visitor};
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// The solution method of a run.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Method {
    /// A converged answer (the default): a fine mesh with a truncated modal basis and its static
    /// correction (see [`crate::solver::truncation`]), chosen from the [`LADDER`] when the element
    /// counts and the cut-off are `"auto"`, judged against the next coarser rung.
    #[default]
    Converged,
    /// The paper's method: its mesh (7 + 7/7 elements when `"auto"`) and the full modal basis.
    Paper,
}

impl Method {
    /// The FMU's Integer parameter: 0 converged, 1 paper.
    pub fn index(self) -> u32 {
        match self {
            Method::Converged => 0,
            Method::Paper => 1,
        }
    }

    /// The method of an FMU Integer parameter value.
    pub fn from_index(value: f64) -> Option<Method> {
        if value == 0.0 {
            Some(Method::Converged)
        } else if value == 1.0 {
            Some(Method::Paper)
        } else {
            None
        }
    }
}

/// Below this damping ratio a run is lightly damped: the converged method doubles its automatic
/// cut-offs and halves its automatic steps, and its late-impact peaks are not vouched for. From
/// 0.02 on the high modes are damped between impacts (the paper's Appendix A: the stresses level
/// off from 0.02; measured: every whole-run peak at 0.03 within 0.2 % of the full basis).
pub const LIGHT_DAMPING: f64 = 0.02;

/// omega_max dt of the converged method's automatic steps in a lightly damped run, as a fraction of
/// the energy-safe limit. With little damping the first sustained contact is hundreds of short
/// bounces, and its clamp bending peak depends on the phase of the modes near the cut-off: measured
/// at drop 2 m, contact 16 m, damping 0.01 (first-contact sigma_a, 56 elements, printed cut-off):
/// 709.0 / 702.4 / 702.2 MPa at omega_max dt = 1 / 0.5 / 0.25, against 699.4 MPa for the full
/// basis at 112 elements; the ladder's rungs, whose steps scale with their cut-offs, agreed
/// with the first figure to 5e-4 % and so could not flag it. The exact modal advance (issue 29;
/// every converged run with the linear bar) has no phase error and so no need of it
/// (699.5 MPa there at omega_max dt = 1).
pub const LIGHT_DAMPING_STEP_FACTOR: f64 = 0.5;

/// The automatic steps' omega_max dt, as a fraction of the energy-safe limit:
/// [`LIGHT_DAMPING_STEP_FACTOR`] for a lightly damped converged run stepped by Eqs. (7)-(11) (a
/// nonlinear contact law: `linear_acceleration`), else 1.
pub fn auto_step_factor(method: Method, damping_ratio: f64, linear_acceleration: bool) -> f64 {
    if method == Method::Converged && damping_ratio < LIGHT_DAMPING && linear_acceleration {
        LIGHT_DAMPING_STEP_FACTOR
    } else {
        1.0
    }
}

/// The paper's elements per segment (Fig. 5): what `"auto"` means for `method = "paper"`.
pub const PAPER_ELEMENTS: u32 = 7;

/// One rung of the automatic discretisation: elements per segment (the arrestor, the bridge up to
/// the contact node, the bridge beyond it) and the modal cut-off as a multiple of the scenario's
/// reference frequency (the highest natural frequency of either beam on the paper's 7-element
/// mesh, out of contact: 43 710 rad/s for the paper scenario; doubled for light damping; or, where
/// larger, 6 times the contact's own frequency sqrt(k_c / m_struck), which a stiff contact at a
/// light point such as the bridge's free end puts above the mesh's: see
/// `crate::discretise::ReferenceFrequencies`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Rung {
    /// Elements per segment.
    pub elements: u32,
    /// Cut-off frequency / reference frequency.
    pub cutoff_factor: f64,
}

/// The ladder of automatic rungs, coarse to fine: each halves the element length and doubles the
/// cut-off, so that the mesh and the modal basis converge together. A converged run prints the
/// rung [`DEFAULT_RUNG`] and judges each peak against the two rungs before it.
pub const LADDER: [Rung; 3] = [
    Rung { elements: 14, cutoff_factor: 0.25 },
    Rung { elements: 28, cutoff_factor: 0.5 },
    Rung { elements: 56, cutoff_factor: 1.0 },
];

/// The rung a converged run with `"auto"` counts prints.
pub const DEFAULT_RUNG: usize = 2;

/// Serde for a count where 0 is `"auto"` (TOML: `elements = "auto"` or `elements = 28`).
pub mod auto_count {
    use super::*;

    /// 0 as `"auto"`, anything else as the number.
    pub fn serialize<S: Serializer>(value: &u32, serializer: S) -> Result<S::Ok, S::Error> {
        if *value == 0 {
            serializer.serialize_str("auto")
        } else {
            serializer.serialize_u32(*value)
        }
    }

    struct CountVisitor;

    impl Visitor<'_> for CountVisitor {
        type Value = u32;

        fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
            write!(f, "a whole number or \"auto\"")
        }

        fn visit_str<E: de::Error>(self, value: &str) -> Result<u32, E> {
            if value == "auto" {
                Ok(0)
            } else {
                Err(E::invalid_value(de::Unexpected::Str(value), &self))
            }
        }

        fn visit_i64<E: de::Error>(self, value: i64) -> Result<u32, E> {
            u32::try_from(value).map_err(|_| E::invalid_value(de::Unexpected::Signed(value), &self))
        }

        fn visit_u64<E: de::Error>(self, value: u64) -> Result<u32, E> {
            u32::try_from(value).map_err(|_| E::invalid_value(de::Unexpected::Unsigned(value), &self))
        }
    }

    /// `"auto"` as 0, or a whole number.
    pub fn deserialize<'de, D: Deserializer<'de>>(deserializer: D) -> Result<u32, D::Error> {
        deserializer.deserialize_any(CountVisitor)
    }
}

/// Serde for a real value where 0 is `"auto"` (the modal cut-off).
pub mod auto_real {
    use super::*;

    /// 0 as `"auto"`, anything else as the number.
    pub fn serialize<S: Serializer>(value: &f64, serializer: S) -> Result<S::Ok, S::Error> {
        if *value == 0.0 {
            serializer.serialize_str("auto")
        } else {
            serializer.serialize_f64(*value)
        }
    }

    struct RealVisitor;

    impl Visitor<'_> for RealVisitor {
        type Value = f64;

        fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
            write!(f, "a number or \"auto\"")
        }

        fn visit_str<E: de::Error>(self, value: &str) -> Result<f64, E> {
            if value == "auto" {
                Ok(0.0)
            } else {
                Err(E::invalid_value(de::Unexpected::Str(value), &self))
            }
        }

        fn visit_f64<E: de::Error>(self, value: f64) -> Result<f64, E> {
            Ok(value)
        }

        fn visit_i64<E: de::Error>(self, value: i64) -> Result<f64, E> {
            Ok(value as f64)
        }

        fn visit_u64<E: de::Error>(self, value: u64) -> Result<f64, E> {
            Ok(value as f64)
        }
    }

    /// `"auto"` as 0, or a number.
    pub fn deserialize<'de, D: Deserializer<'de>>(deserializer: D) -> Result<f64, D::Error> {
        deserializer.deserialize_any(RealVisitor)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug, PartialEq, Serialize, Deserialize)]
    struct Holder {
        #[serde(with = "auto_count")]
        elements: u32,
        #[serde(with = "auto_real")]
        cutoff: f64,
        method: Method,
    }

    #[test]
    fn auto_round_trips_as_the_word_and_numbers_as_numbers() {
        let auto = Holder { elements: 0, cutoff: 0.0, method: Method::Converged };
        let text = toml::to_string(&auto).unwrap();
        assert_eq!(text, "elements = \"auto\"\ncutoff = \"auto\"\nmethod = \"converged\"\n");
        assert_eq!(toml::from_str::<Holder>(&text).unwrap(), auto);
        let fixed: Holder = toml::from_str("elements = 28\ncutoff = 5e4\nmethod = \"paper\"").unwrap();
        assert_eq!(fixed, Holder { elements: 28, cutoff: 5e4, method: Method::Paper });
        assert!(toml::from_str::<Holder>("elements = -1\ncutoff = 1\nmethod = \"paper\"").is_err());
        assert!(toml::from_str::<Holder>("elements = \"many\"\ncutoff = 1\nmethod = \"paper\"").is_err());
    }

    #[test]
    fn ladder_refines_monotonically() {
        for pair in LADDER.windows(2) {
            assert!(pair[1].elements >= pair[0].elements && pair[1].cutoff_factor >= pair[0].cutoff_factor);
            assert!(pair[1] != pair[0]);
        }
        assert!(DEFAULT_RUNG >= 2 && DEFAULT_RUNG < LADDER.len());
    }
}
