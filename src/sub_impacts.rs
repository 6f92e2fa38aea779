//! The sub-impacts of a run (issue 45): each contact window's start, duration, peak force and
//! apparent restitution ([`crate::results::SubImpact`]), as text for `run` and for `report LOG`,
//! and as the documents' list (`run --json`, `answer.json`, read back by `report` and Python's
//! `load_log`). A chattering contact opens thousands of windows (6 672 were seen on a stiff
//! power law), so the documents keep the first [`KEPT`] and, when it comes later, the one of the
//! largest force (with its `number`), beside `sub_impacts_total` and `sub_impacts_truncated`.

use crate::results::SubImpact;

/// The most windows printed; the documents keep [`KEPT`].
pub const SHOWN: usize = 20;

/// The most windows a document (`run --json`, `answer.json`) lists, before the largest-force
/// one if it comes later: enough for every rebound of an impact that settles (the lab sphere's
/// 2, the dropped container's 4), a bound on a chattering contact's thousands.
pub const KEPT: usize = 100;

/// The most windows read back from a log's `answer.json`.
pub const READ_BACK: usize = 10_000;

/// A run's sub-impacts as a document or a table holds them: the first windows, the count of all,
/// and the largest-force window with its 1-based number when it is not among the first.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Kept {
    /// The first windows, in order.
    pub first: Vec<SubImpact>,
    /// How many windows the run had.
    pub total: usize,
    /// The window of the largest contact force, with its number (1-based), when it is not among
    /// [`Self::first`].
    pub largest: Option<(usize, SubImpact)>,
}

impl Kept {
    /// The first `count` of `impacts`, their total and the largest-force window if later (the
    /// first of equal largest forces).
    pub fn of(impacts: &[SubImpact], count: usize) -> Kept {
        let largest = impacts
            .iter()
            .enumerate()
            .min_by(|a, b| b.1.peak_force.total_cmp(&a.1.peak_force))
            .filter(|(i, _)| *i >= count)
            .map(|(i, w)| (i + 1, *w));
        Kept { first: impacts.iter().take(count).copied().collect(), total: impacts.len(), largest }
    }

    /// True when windows are left out.
    pub fn truncated(&self) -> bool {
        self.total > self.first.len()
    }
}

/// Sets a document's `sub_impacts` (the first [`KEPT`] windows, then the largest-force one with
/// its `number` if it comes later), `sub_impacts_total` and `sub_impacts_truncated`.
pub fn add_to(doc: &mut serde_json::Value, impacts: &[SubImpact]) {
    let kept = Kept::of(impacts, KEPT);
    let mut list: Vec<serde_json::Value> = kept.first.iter().map(|w| serde_json::json!(w)).collect();
    if let Some((number, w)) = kept.largest {
        let mut entry = serde_json::json!(w);
        entry["number"] = serde_json::json!(number);
        list.push(entry);
    }
    doc["sub_impacts"] = serde_json::Value::Array(list);
    doc["sub_impacts_total"] = serde_json::json!(kept.total);
    doc["sub_impacts_truncated"] = serde_json::json!(kept.truncated());
}

/// The table of `impacts` (nothing without any): the first [`SHOWN`] rows, then the
/// largest-force window if it comes later, and how many more there were.
pub fn lines(impacts: &[SubImpact]) -> String {
    table(&Kept::of(impacts, SHOWN))
}

/// The table of `kept`, at most [`SHOWN`] rows of its first windows and its largest.
pub fn table(kept: &Kept) -> String {
    if kept.total == 0 {
        return String::new();
    }
    let mut text = format!(
        "sub-impacts: {} contact window{} (restitution = separation / approach speed of the striking point \
         relative to the struck point)\n",
        kept.total,
        if kept.total == 1 { "" } else { "s" }
    );
    text +=
        "   #   start [s]  duration [s]  peak force [kN]  at [s]     approach [m/s]  separation [m/s]  restitution\n";
    let row = |number: usize, w: &SubImpact| {
        let optional = |v: Option<f64>, width: usize| match v {
            Some(v) => format!("{v:>width$.6}"),
            None => format!("{:>width$}", "in contact"),
        };
        format!(
            "{:>4} {:>11.6} {:>13.6} {:>16.3} {:>10.6} {:>15.6} {} {}\n",
            number,
            w.start,
            w.duration,
            w.peak_force / 1e3,
            w.peak_time,
            w.approach_speed,
            optional(w.separation_speed, 17),
            optional(w.restitution, 12),
        )
    };
    let shown = kept.first.len().min(SHOWN);
    for (i, w) in kept.first.iter().take(SHOWN).enumerate() {
        text += &row(i + 1, w);
    }
    // The largest of all: the kept one beyond the first, else the largest of the first.
    let largest = kept
        .largest
        .or_else(|| {
            kept.first
                .iter()
                .enumerate()
                .min_by(|a, b| b.1.peak_force.total_cmp(&a.1.peak_force))
                .map(|(i, w)| (i + 1, *w))
        })
        .filter(|(number, _)| *number > shown);
    let more = kept.total - shown - usize::from(largest.is_some());
    if let Some((number, w)) = largest {
        text += &format!("   ... the largest contact force is window {number}:\n");
        text += &row(number, &w);
    }
    if more > 0 {
        text += &format!(
            "   ... {more} more (run --json and answer.json list the first {KEPT} and the largest; \
             sub_impacts_total = {})\n",
            kept.total
        );
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
        Some(doc) if mass => table(&stored(&doc)),
        _ => String::new(),
    }
}

/// The sub-impacts a log's `answer.json` stores (at most [`READ_BACK`]; entries that are not
/// well-formed, with finite numbers, are skipped: nothing in a log is trusted).
pub fn from_json(doc: &serde_json::Value) -> Vec<SubImpact> {
    let Some(list) = doc["sub_impacts"].as_array() else { return Vec::new() };
    list.iter().take(READ_BACK).filter_map(well_formed).collect()
}

/// One stored entry, if well-formed with finite numbers.
fn well_formed(v: &serde_json::Value) -> Option<SubImpact> {
    let w = serde_json::from_value::<SubImpact>(v.clone()).ok()?;
    let finite = [w.start, w.duration, w.peak_force, w.peak_time, w.approach_speed].iter().all(|x| x.is_finite())
        && w.separation_speed.is_none_or(f64::is_finite)
        && w.restitution.is_none_or(f64::is_finite);
    finite.then_some(w)
}

/// A stored document's sub-impacts as [`add_to`] wrote them: the entries before any with a
/// `number` are the first windows; an entry with a `number` beyond them is the largest; the total
/// is `sub_impacts_total` when it is a count at least as large as what is listed (else the count
/// listed: nothing in a log is trusted).
pub fn stored(doc: &serde_json::Value) -> Kept {
    let list = doc["sub_impacts"].as_array().map_or(&[][..], |l| &l[..]);
    let listed = list.iter().take(READ_BACK);
    let mut first = Vec::new();
    let mut largest = None;
    for v in listed {
        let Some(w) = well_formed(v) else { continue };
        match v.get("number").and_then(serde_json::Value::as_u64).and_then(|n| usize::try_from(n).ok()) {
            Some(n) if largest.is_none() && n > first.len() => largest = Some((n, w)),
            Some(_) => {}
            None if largest.is_none() => first.push(w),
            None => {}
        }
    }
    let least = first.len().max(largest.map_or(0, |(n, _)| n));
    let total = doc["sub_impacts_total"]
        .as_u64()
        .and_then(|t| usize::try_from(t).ok())
        .filter(|t| *t >= least)
        .unwrap_or(least);
    Kept { first, total, largest }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn good_entry() -> serde_json::Value {
        serde_json::json!({"start": 0.0, "duration": 0.01, "peak_force": 1e3, "peak_time": 0.005,
            "approach_speed": 1.0, "separation_speed": 0.9, "restitution": 0.9})
    }

    /// A window of `force` N starting at `start` s.
    fn window(start: f64, force: f64) -> SubImpact {
        SubImpact {
            start,
            duration: 1e-4,
            peak_force: force,
            peak_time: start + 5e-5,
            approach_speed: 0.1,
            separation_speed: Some(0.1),
            restitution: Some(1.0),
        }
    }

    /// 250 windows whose largest force is the 180th: the document keeps the first 100 and the
    /// 180th with its number, says 250 and truncated; read back it is the same, and the table
    /// shows 20 rows, the 180th, and "... 229 more".
    #[test]
    fn a_long_list_keeps_the_first_hundred_and_the_largest_with_the_count() {
        let impacts: Vec<SubImpact> =
            (0..250).map(|i| window(i as f64 * 1e-3, if i == 179 { 9e3 } else { 1e3 + i as f64 })).collect();
        let mut doc = serde_json::json!({});
        add_to(&mut doc, &impacts);
        let list = doc["sub_impacts"].as_array().unwrap();
        assert_eq!(list.len(), KEPT + 1);
        assert_eq!(list[KEPT]["number"], 180);
        assert_eq!((doc["sub_impacts_total"].clone(), doc["sub_impacts_truncated"].clone()), (250.into(), true.into()));
        let kept = stored(&doc);
        assert_eq!(kept, Kept::of(&impacts, KEPT));
        let text = table(&kept);
        assert_eq!(text, lines(&impacts), "report's table is run's");
        assert!(text.contains("window 180:") && text.contains(" 180 ") && text.contains("... 229 more"), "{text}");
        assert_eq!(text.lines().count(), 2 + SHOWN + 2 + 1, "{text}");
        // A short list is kept whole, not truncated, without a number.
        let mut doc = serde_json::json!({});
        add_to(&mut doc, &impacts[..3]);
        assert_eq!(doc["sub_impacts"].as_array().unwrap().len(), 3);
        assert_eq!(doc["sub_impacts_truncated"], false);
        assert!(doc["sub_impacts"][0].get("number").is_none());
        assert!(!lines(&impacts[..3]).contains("more"));
    }

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
        // A hostile total (beyond usize, negative, smaller than the list) falls back to the count.
        for total in [serde_json::json!(u64::MAX), serde_json::json!(-3), serde_json::json!(1), serde_json::json!("x")]
        {
            let doc = serde_json::json!({ "sub_impacts": [good_entry(), good_entry()], "sub_impacts_total": total });
            let kept = stored(&doc);
            assert!(kept.total == 2 || kept.total as u64 == u64::MAX, "{kept:?}");
        }
        assert!(from_json(&serde_json::json!({ "sub_impacts": 3 })).is_empty());
    }
}
