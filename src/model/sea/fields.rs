//! The `[sea]` fields as parameters (`--set sea.FIELD=VALUE`, `--vary`, sweep columns), from the
//! table every scenario field has ([`crate::model::parameters::Parameter`]). A field set on a
//! scenario without `[sea]` is an error naming it; `0` is "absent" for the fields that have a
//! rule when absent (`peak_enhancement`: DNV's rule; `frequency_min`, `frequency_max`: the
//! spectrum's range), as "auto" for the time steps.

use super::settings::{SeaSettings, MAX_SEED};
use super::spectrum::SpectrumKind;
use crate::error::{Error, Result};
use crate::model::parameters::{Kind, Parameter};
use crate::model::Scenario;

/// The sea of `scenario`, or the error naming `name`.
fn sea<'a>(scenario: &'a mut Scenario, name: &'static str) -> Result<&'a mut SeaSettings> {
    scenario.sea.as_mut().ok_or_else(|| {
        Error::Other(format!("{name} is a field of [sea], and the scenario has none (add a [sea] section to set it)"))
    })
}

macro_rules! real {
    ($name:literal, $unit:literal, $desc:literal, $field:ident) => {
        Parameter {
            name: $name,
            unit: $unit,
            description: $desc,
            kind: Kind::Real,
            get: |s| s.sea.as_ref().map_or(f64::NAN, |x| x.$field),
            put: |s, v| {
                sea(s, $name)?.$field = v;
                Ok(())
            },
        }
    };
}

macro_rules! optional {
    ($name:literal, $unit:literal, $desc:literal, $field:ident) => {
        Parameter {
            name: $name,
            unit: $unit,
            description: $desc,
            kind: Kind::Real,
            get: |s| s.sea.as_ref().map_or(f64::NAN, |x| x.$field.unwrap_or(0.0)),
            put: |s, v| {
                sea(s, $name)?.$field = if v == 0.0 { None } else { Some(v) };
                Ok(())
            },
        }
    };
}

macro_rules! coordinate {
    ($name:literal, $desc:literal, $point:ident, $k:literal) => {
        Parameter {
            name: $name,
            unit: "m",
            description: $desc,
            kind: Kind::Real,
            get: |s| s.sea.as_ref().and_then(|x| x.$point).map_or(f64::NAN, |p| p[$k]),
            put: |s, v| {
                let point = &mut sea(s, $name)?.$point;
                let p = point.as_mut().ok_or_else(|| {
                    Error::Other(format!(
                        "{} is not given (that support stands on a fixed platform): give the whole point in [sea]",
                        stringify!($point)
                    ))
                })?;
                p[$k] = v;
                Ok(())
            },
        }
    };
}

/// Every `[sea]` field a setting or a sweep can change.
pub static SEA_FIELDS: [Parameter; 18] = [
    real!("sea.significant_wave_height", "m", "Significant wave height Hs", significant_wave_height),
    real!("sea.peak_period", "s", "Peak period Tp", peak_period),
    Parameter {
        name: "sea.spectrum",
        unit: "",
        description: "The wave spectrum: 0 JONSWAP, 1 Pierson-Moskowitz",
        kind: Kind::Integer,
        get: |s| s.sea.as_ref().map_or(f64::NAN, |x| f64::from(x.spectrum.index())),
        put: |s, v| {
            sea(s, "sea.spectrum")?.spectrum = SpectrumKind::from_index(v)
                .ok_or_else(|| Error::invalid("sea.spectrum", "jonswap (0) or pierson-moskowitz (1)", v))?;
            Ok(())
        },
    },
    optional!("sea.peak_enhancement", "1", "JONSWAP gamma; 0: DNV-RP-C205's rule from Tp / sqrt(Hs)", peak_enhancement),
    real!("sea.heading", "deg", "The waves' direction of travel from the bow towards port (180: head seas)", heading),
    Parameter {
        name: "sea.seed",
        unit: "",
        description: "The random components' seed",
        kind: Kind::Real,
        get: |s| s.sea.as_ref().map_or(f64::NAN, |x| x.seed as f64),
        put: |s, v| {
            if !(v.fract() == 0.0 && (0.0..=MAX_SEED as f64).contains(&v)) {
                return Err(Error::invalid("sea.seed", format!("a whole number from 0 to 2^53 = {MAX_SEED}"), v));
            }
            sea(s, "sea.seed")?.seed = v as u64;
            Ok(())
        },
    },
    Parameter {
        name: "sea.components",
        unit: "",
        description: "Number of wave components",
        kind: Kind::Integer,
        get: |s| s.sea.as_ref().map_or(f64::NAN, |x| f64::from(x.components)),
        put: |s, v| {
            sea(s, "sea.components")?.components = v as u32;
            Ok(())
        },
    },
    optional!("sea.frequency_min", "rad/s", "Lowest component frequency; 0: 0.5 w_p within the RAOs", frequency_min),
    optional!("sea.frequency_max", "rad/s", "Highest component frequency; 0: 5 w_p within the RAOs", frequency_max),
    real!("sea.time_shift", "s", "The record's time at the run's t = 0 (the support lost)", time_shift),
    real!(
        "sea.arrestor_direction",
        "deg",
        "The arrestor's axis from the bow towards port (180: aft)",
        arrestor_direction
    ),
    real!("sea.sample_interval", "s", "Interval of the record's samples the supports follow", sample_interval),
    coordinate!("sea.hinge_point.x", "The hinge's deck point, forward of the motion reference point", hinge_point, 0),
    coordinate!("sea.hinge_point.y", "The hinge's deck point, to port", hinge_point, 1),
    coordinate!("sea.hinge_point.z", "The hinge's deck point, up", hinge_point, 2),
    coordinate!("sea.clamp_point.x", "The clamp's deck point, forward of the motion reference point", clamp_point, 0),
    coordinate!("sea.clamp_point.y", "The clamp's deck point, to port", clamp_point, 1),
    coordinate!("sea.clamp_point.z", "The clamp's deck point, up", clamp_point, 2),
];
