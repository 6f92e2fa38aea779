//! The operability table (issue 43): over a grid of sea states, per heading and peak period the
//! largest significant wave height in which losing the support overloads the gangway with a
//! probability below the target, laid out as offshore operability tables are (Hs down the rows,
//! Tp across the columns, the limiting Hs at the foot). A Tp's limit is the largest Hs such that
//! every cell up to it at that Tp is operable ([`super::summary::CellSummary::operable`]); a sea the
//! model refuses (a breaking one) ends the column as a failing cell does.

use std::fmt::Write as _;

use super::summary::{CellSummary, Options};

/// A cell as the table takes it.
#[derive(Clone, Debug, PartialEq)]
pub struct TableCell<'a> {
    /// Significant wave height, m.
    pub significant_wave_height: f64,
    /// Peak period, s.
    pub peak_period: f64,
    /// Heading, deg.
    pub heading: f64,
    /// The summary, or why the sea state is refused.
    pub outcome: std::result::Result<&'a CellSummary, &'a str>,
}

/// One column's limit: the heading and period, and the largest operable Hs (None: not even the
/// smallest).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Limit {
    /// Heading, deg.
    pub heading: f64,
    /// Peak period, s.
    pub peak_period: f64,
    /// The limiting Hs, m.
    pub significant_wave_height: Option<f64>,
}

fn sorted_unique(mut v: Vec<f64>) -> Vec<f64> {
    v.sort_by(f64::total_cmp);
    v.dedup();
    v
}

/// The headings, periods and heights of the grid, each ascending.
pub fn axes(cells: &[TableCell]) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    (
        sorted_unique(cells.iter().map(|c| c.heading).collect()),
        sorted_unique(cells.iter().map(|c| c.peak_period).collect()),
        sorted_unique(cells.iter().map(|c| c.significant_wave_height).collect()),
    )
}

fn find<'a, 'b>(cells: &'b [TableCell<'a>], heading: f64, tp: f64, hs: f64) -> Option<&'b TableCell<'a>> {
    cells.iter().find(|c| c.heading == heading && c.peak_period == tp && c.significant_wave_height == hs)
}

/// Each heading's and period's limiting Hs.
pub fn limits(cells: &[TableCell]) -> Vec<Limit> {
    let (headings, periods, heights) = axes(cells);
    let mut out = Vec::new();
    for &heading in &headings {
        for &tp in &periods {
            let mut limit = None;
            for &hs in &heights {
                match find(cells, heading, tp, hs).map(|c| &c.outcome) {
                    Some(Ok(s)) if s.operable => limit = Some(hs),
                    // A cell not assessed (not run, refused) or failing ends the column: the limit
                    // never passes over a sea state nothing vouches for.
                    _ => break,
                }
            }
            out.push(Limit { heading, peak_period: tp, significant_wave_height: limit });
        }
    }
    out
}

/// The outcome of a cell whose events were not run (the campaign was interrupted first).
pub const NOT_RUN: &str = "not run: the campaign was interrupted before its events";

/// A cell's text: the number its verdict compares with the target, `ok` or `x`, and `!` where
/// failed or untrusted events count as overloads in it: the judged probability's upper bound
/// (`<1.4e-2`, the probability is below it at the stated confidence; `on_upper_bound`) or its
/// estimate; `breaking`, `refused` or `not run` for a sea state not assessed.
pub fn cell_text(outcome: &std::result::Result<&CellSummary, &str>, on_upper_bound: bool) -> String {
    match outcome {
        Ok(s) if s.judged_on.events == 0 => "no events".into(),
        Ok(s) => {
            let i = s.judged_on.interval;
            let p = match (on_upper_bound, i.probability) {
                (true, _) => format!("<{:.1e}", i.high),
                (false, 0.0) => "0".into(),
                (false, p) => format!("{p:.1e}"),
            };
            let doubt = if s.failed > 0 || s.untrusted > 0 { "!" } else { "" };
            format!("{p} {}{doubt}", if s.operable { "ok" } else { "x" })
        }
        Err(why) if why.contains("steeper than a sea can be") => "breaking".into(),
        Err(why) if *why == NOT_RUN => "not run".into(),
        Err(_) => "refused".into(),
    }
}

/// A grid value as the table's rows and columns name it: at most four decimals, trailing zeros
/// dropped (`1.6667` for a range's 5/3, which would not fit its column in full; `2.5`, `8`).
fn label(v: f64) -> String {
    let text = format!("{v:.4}");
    let text = text.trim_end_matches('0').trim_end_matches('.');
    if text == "-0" {
        "0".into()
    } else {
        text.into()
    }
}

/// The table as text: one block per heading.
pub fn table(cells: &[TableCell], options: &Options) -> String {
    let (headings, periods, heights) = axes(cells);
    let limits = limits(cells);
    let width = 12;
    let mut s = String::new();
    let criterion = if options.on_upper_bound {
        format!("its {} % upper bound", 100.0 * options.confidence)
    } else {
        "its estimate".into()
    };
    let _ = writeln!(
        s,
        "operability: the probability that losing the support overloads the gangway (any utilisation > 1), per loss; \
         a cell is ok when {criterion} is below the target {}",
        super::summary::significant(options.target)
    );
    for &heading in &headings {
        let _ = writeln!(s, "heading {} deg", label(heading));
        let _ = write!(s, "{:<14}", "Hs [m] \\ Tp [s]");
        for tp in &periods {
            let _ = write!(s, "{:>width$}", label(*tp));
        }
        s.push('\n');
        for &hs in heights.iter().rev() {
            let _ = write!(s, "{:<14}", label(hs));
            for &tp in &periods {
                let text = find(cells, heading, tp, hs)
                    .map_or("-".to_string(), |c| cell_text(&c.outcome, options.on_upper_bound));
                let _ = write!(s, "{text:>width$}");
            }
            s.push('\n');
        }
        let _ = write!(s, "{:<14}", "limit Hs [m]");
        for l in limits.iter().filter(|l| l.heading == heading) {
            let text = l.significant_wave_height.map_or("none".to_string(), label);
            let _ = write!(s, "{text:>width$}");
        }
        s.push('\n');
    }
    if cells.iter().any(|c| matches!(c.outcome, Ok(s) if s.failed > 0 || s.untrusted > 0)) {
        s.push_str(
            "!: some of the cell's events failed (the sea beyond the model's range) or are not trusted: the verdict \
             counts them as overloads\n",
        );
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::studies::campaign::summary::{summarise, EventOutcome, EventResults};

    fn summary(overloads: usize, events: usize) -> CellSummary {
        let outcome = |k: usize| EventOutcome {
            seed: 1 + k as u64 % 10,
            results: Some(EventResults {
                peaks: [Some(1.0 + k as f64 * 1e-3); 9],
                utilisation: [Some(if k < overloads { 1.5 } else { 0.5 }); 9],
                design_pass: k >= overloads,
                trusted: true,
            }),
        };
        let outcomes: Vec<EventOutcome> = (0..events).map(outcome).collect();
        summarise(&outcomes, &Options { target: 0.05, on_upper_bound: false, ..Options::default() })
    }

    /// An event the model cannot vouch for counts as an overload in the verdict: a failed one
    /// (issue 43's grid lost events where the vessel's pitch left the model's 0.1 rad) and an
    /// untrusted one that passed; the statistics of the events that ran stay as they are.
    #[test]
    fn failed_and_untrusted_events_count_as_overloads_in_the_verdict() {
        let options = Options { target: 0.05, on_upper_bound: false, ..Options::default() };
        let mut outcomes: Vec<EventOutcome> = (0..100)
            .map(|k| EventOutcome {
                seed: 1 + k % 10,
                results: Some(EventResults {
                    peaks: [Some(1.0 + k as f64 * 1e-3); 9],
                    utilisation: [Some(0.5); 9],
                    design_pass: true,
                    trusted: true,
                }),
            })
            .collect();
        // None of 100 overloads: operable on the estimate 0 < 0.05.
        assert!(summarise(&outcomes, &options).operable);
        // Five failed: 5 of 100 judged, 0.05, not below the target; the statistics of the 95 that
        // ran show no overload.
        for o in &mut outcomes[..5] {
            o.results = None;
        }
        let failed = summarise(&outcomes, &options);
        assert!(!failed.operable && failed.failed == 5);
        assert_eq!((failed.overload.exceeding, failed.overload.events), (0, 95));
        assert_eq!((failed.judged_on.exceeding, failed.judged_on.events), (5, 100));
        assert!(failed.warnings.iter().any(|w| w.contains("5 of 100 events failed")), "{:?}", failed.warnings);
        // The cell prints the number its verdict compares: the judged 5 of 100 (0.05, not below
        // 0.05), not the 95 that ran (none overloading, below 3.8e-2); on the upper bound, the
        // judged one's (Clopper-Pearson 95 % of 5 / 100: 0.1128).
        assert_eq!(cell_text(&Ok(&failed), false), "5.0e-2 x!");
        assert_eq!(cell_text(&Ok(&failed), true), "<1.1e-1 x!");
        // Four failed and one untrusted: judged the same.
        outcomes[0].results = outcomes[9].results.map(|r| EventResults { trusted: false, ..r });
        let doubtful = summarise(&outcomes, &options);
        assert_eq!((doubtful.judged_on.exceeding, doubtful.judged_on.events), (5, 100));
        assert!(!doubtful.operable);
        // One failed only: 1 of 100 judged, operable on the estimate.
        let fine = outcomes[9].results;
        for o in &mut outcomes[..4] {
            o.results = fine;
        }
        assert!(summarise(&outcomes, &options).operable);
    }

    /// A grid value takes at most four decimals in the table, so that a range's thirds keep their
    /// column.
    #[test]
    fn grid_values_are_labelled_in_at_most_four_decimals() {
        assert_eq!(
            [label(5.0 / 3.0), label(2.5), label(8.0), label(0.0), label(180.0)],
            ["1.6667", "2.5", "8", "0", "180"]
        );
    }

    /// A cell not run (an interrupted campaign's) ends its column as a failing one does: the
    /// limit never passes over a sea state no event vouches for; the table says `not run`.
    #[test]
    fn a_cell_not_run_ends_the_column_and_is_printed_so() {
        let ok = summary(0, 100);
        let options = Options { target: 0.05, on_upper_bound: true, ..Options::default() };
        let cell =
            |hs: f64, outcome| TableCell { significant_wave_height: hs, peak_period: 8.0, heading: 180.0, outcome };
        let cells = vec![cell(1.0, Ok(&ok)), cell(2.0, Err(NOT_RUN)), cell(3.0, Ok(&ok))];
        assert_eq!(limits(&cells)[0].significant_wave_height, Some(1.0));
        let text = table(&cells, &options);
        assert!(text.contains("not run"), "{text}");
        // No overload in 100 on the upper bound: below 1 - 0.025^(1/100) = 3.6e-2, ok.
        assert_eq!(cell_text(&Ok(&ok), true), "<3.6e-2 ok");
        assert_eq!(cell_text(&Ok(&ok), false), "0 ok");
    }

    /// The limit is the largest Hs up to which every cell is operable: a failing cell (or a
    /// breaking sea) ends the column even if a higher one passes by chance.
    #[test]
    fn the_limit_is_the_last_operable_height_before_the_first_failure() {
        let (ok, bad) = (summary(0, 100), summary(20, 100));
        let options = Options { target: 0.05, on_upper_bound: false, ..Options::default() };
        let cell = |hs: f64, tp: f64, outcome| TableCell {
            significant_wave_height: hs,
            peak_period: tp,
            heading: 180.0,
            outcome,
        };
        let cells = vec![
            cell(1.0, 6.0, Ok(&ok)),
            cell(2.0, 6.0, Ok(&bad)),
            cell(3.0, 6.0, Ok(&ok)),
            cell(1.0, 8.0, Ok(&ok)),
            cell(2.0, 8.0, Ok(&ok)),
            cell(3.0, 8.0, Err("sea: ... is steeper than a sea can be ...")),
            cell(1.0, 10.0, Ok(&bad)),
            cell(2.0, 10.0, Ok(&ok)),
            cell(3.0, 10.0, Ok(&ok)),
        ];
        let l: Vec<Option<f64>> = limits(&cells).iter().map(|l| l.significant_wave_height).collect();
        assert_eq!(l, vec![Some(1.0), Some(2.0), None]);
        let text = table(&cells, &options);
        assert!(text.contains("breaking"), "{text}");
        assert!(text.contains("2.0e-1 x"), "20 of 100 overload: {text}");
        assert!(
            text.lines().last().unwrap().split_whitespace().collect::<Vec<_>>().ends_with(&["1", "2", "none"]),
            "{text}"
        );
    }
}
