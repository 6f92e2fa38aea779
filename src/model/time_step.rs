//! A time step as the user gives it: a fixed length, or automatic. An automatic step is resolved
//! once the natural frequencies are known (see [`crate::solver::StepPlan`]): the largest
//! whole-nanosecond step that is stable and energy-safe, never above the paper's.

use serde::de::{self, Visitor};
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// A stage's time step: `"auto"` in TOML and JSON, 0 in the FMU's Float64 parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TimeStep {
    /// The largest stable and energy-safe step for the model (the safe default).
    Auto,
    /// A fixed step, s.
    Fixed(f64),
}

impl TimeStep {
    /// From an FMU parameter value: 0 means automatic.
    pub fn from_parameter(value: f64) -> TimeStep {
        if value == 0.0 {
            TimeStep::Auto
        } else {
            TimeStep::Fixed(value)
        }
    }

    /// As an FMU parameter value: automatic is 0.
    pub fn as_parameter(self) -> f64 {
        match self {
            TimeStep::Auto => 0.0,
            TimeStep::Fixed(step) => step,
        }
    }
}

impl std::fmt::Display for TimeStep {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            TimeStep::Auto => write!(f, "auto"),
            TimeStep::Fixed(step) => write!(f, "{step:e} s"),
        }
    }
}

impl Serialize for TimeStep {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match self {
            TimeStep::Auto => serializer.serialize_str("auto"),
            TimeStep::Fixed(step) => serializer.serialize_f64(*step),
        }
    }
}

struct TimeStepVisitor;

impl Visitor<'_> for TimeStepVisitor {
    type Value = TimeStep;

    fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "a time step in s or \"auto\"")
    }

    fn visit_str<E: de::Error>(self, value: &str) -> Result<TimeStep, E> {
        if value == "auto" {
            Ok(TimeStep::Auto)
        } else {
            Err(E::invalid_value(de::Unexpected::Str(value), &self))
        }
    }

    fn visit_f64<E: de::Error>(self, value: f64) -> Result<TimeStep, E> {
        Ok(TimeStep::Fixed(value))
    }

    fn visit_i64<E: de::Error>(self, value: i64) -> Result<TimeStep, E> {
        Ok(TimeStep::Fixed(value as f64))
    }

    fn visit_u64<E: de::Error>(self, value: u64) -> Result<TimeStep, E> {
        Ok(TimeStep::Fixed(value as f64))
    }
}

impl<'de> Deserialize<'de> for TimeStep {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<TimeStep, D::Error> {
        deserializer.deserialize_any(TimeStepVisitor)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug, PartialEq, Serialize, Deserialize)]
    struct Holder {
        step: TimeStep,
    }

    #[test]
    fn auto_and_seconds_round_trip_through_toml_and_json() {
        for step in [TimeStep::Auto, TimeStep::Fixed(2.5e-5)] {
            let toml_text = toml::to_string(&Holder { step }).unwrap();
            assert_eq!(toml::from_str::<Holder>(&toml_text).unwrap().step, step, "{toml_text}");
            let json = serde_json::to_string(&Holder { step }).unwrap();
            assert_eq!(serde_json::from_str::<Holder>(&json).unwrap().step, step, "{json}");
        }
        assert!(toml::from_str::<Holder>("step = \"fast\"").is_err());
        assert_eq!(toml::from_str::<Holder>("step = 1").unwrap().step, TimeStep::Fixed(1.0));
    }

    #[test]
    fn zero_is_automatic_in_the_fmu_parameter_form() {
        assert_eq!(TimeStep::from_parameter(0.0), TimeStep::Auto);
        assert_eq!(TimeStep::Auto.as_parameter(), 0.0);
        assert_eq!(TimeStep::from_parameter(5e-5), TimeStep::Fixed(5e-5));
    }
}
