//! The sub-impacts of a run as text (issue 45): each contact window's start, duration, peak
//! force and apparent restitution ([`crate::results::SubImpact`]), for `run` and for `report
//! LOG` (read back from the log's `answer.json`, bounded like everything read from a log).

use crate::results::SubImpact;

/// The most windows printed; `run --json` and `answer.json` hold them all.
pub const SHOWN: usize = 20;

/// The most windows read back from a log's `answer.json`.
pub const READ_BACK: usize = 10_000;

/// The table of `impacts` (nothing without any), at most [`SHOWN`] rows.
pub fn lines(impacts: &[SubImpact]) -> String {
    if impacts.is_empty() {
        return String::new();
    }
    let mut text = format!(
        "sub-impacts: {} contact window{} (restitution = separation / approach speed of the striking point \
         relative to the struck point)\n",
        impacts.len(),
        if impacts.len() == 1 { "" } else { "s" }
    );
    text +=
        "   #   start [s]  duration [s]  peak force [kN]  at [s]     approach [m/s]  separation [m/s]  restitution\n";
    for (i, w) in impacts.iter().take(SHOWN).enumerate() {
        let optional = |v: Option<f64>, width: usize| match v {
            Some(v) => format!("{v:>width$.6}"),
            None => format!("{:>width$}", "in contact"),
        };
        text += &format!(
            "{:>4} {:>11.6} {:>13.6} {:>16.3} {:>10.6} {:>15.6} {} {}\n",
            i + 1,
            w.start,
            w.duration,
            w.peak_force / 1e3,
            w.peak_time,
            w.approach_speed,
            optional(w.separation_speed, 17),
            optional(w.restitution, 12),
        );
    }
    if impacts.len() > SHOWN {
        text += &format!("   ... and {} more (run --json lists them all)\n", impacts.len() - SHOWN);
    }
    text
}

/// The sub-impacts table of a log whose stored scenario is a rigid impactor's (`upper.kind =
/// "mass"`), from its `answer.json` (nothing for a bridge, whose contact windows `report` lists
/// already, or without either file).
pub fn stored_lines(scenario_toml: Option<&str>, answer_json: Option<&str>) -> String {
    let mass = scenario_toml
        .and_then(|t| t.parse::<toml::Table>().ok())
        .is_some_and(|t| t.get("upper").and_then(|u| u.get("kind")).and_then(|k| k.as_str()) == Some("mass"));
    match answer_json.and_then(|a| serde_json::from_str::<serde_json::Value>(a).ok()) {
        Some(doc) if mass => lines(&from_json(&doc)),
        _ => String::new(),
    }
}

/// The sub-impacts a log's `answer.json` stores (at most [`READ_BACK`]; entries that are not
/// well-formed, with finite numbers, are skipped: nothing in a log is trusted).
pub fn from_json(doc: &serde_json::Value) -> Vec<SubImpact> {
    let Some(list) = doc["sub_impacts"].as_array() else { return Vec::new() };
    list.iter()
        .take(READ_BACK)
        .filter_map(|v| serde_json::from_value::<SubImpact>(v.clone()).ok())
        .filter(|w| {
            [w.start, w.duration, w.peak_force, w.peak_time, w.approach_speed].iter().all(|x| x.is_finite())
                && w.separation_speed.is_none_or(f64::is_finite)
                && w.restitution.is_none_or(f64::is_finite)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A log's hostile `sub_impacts` (wrong types, non-finite numbers, too many) read back
    /// bounded, well-formed entries only, and their table never exceeds [`SHOWN`] rows.
    #[test]
    fn stored_sub_impacts_are_read_back_bounded_and_well_formed() {
        let good = serde_json::json!({"start": 0.0, "duration": 0.01, "peak_force": 1e3, "peak_time": 0.005,
            "approach_speed": 1.0, "separation_speed": 0.9, "restitution": 0.9});
        let mut list = vec![serde_json::json!("text"), serde_json::json!({"start": "x"}), good.clone()];
        list.extend(std::iter::repeat_n(good, READ_BACK + 5));
        let doc = serde_json::json!({ "sub_impacts": list });
        let impacts = from_json(&doc);
        assert_eq!(impacts.len(), READ_BACK - 2);
        let text = lines(&impacts);
        assert_eq!(text.lines().count(), 2 + SHOWN + 1, "{text}");
        assert!(from_json(&serde_json::json!({ "sub_impacts": 3 })).is_empty());
    }
}
