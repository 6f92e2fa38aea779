//! Issue 44's leftovers in `beam-impact campaign`: `--fatigue` gives each event's damage (the
//! sweep's `fatigue.damage` column), its mean per cell, and with `--occurrence` the damage per
//! event and per year weighted over the sea states and the life; the occurrence table is bounded
//! and refused in one line (exit code 2), also when mutated at random.

use std::collections::BTreeMap;
use std::path::Path;
use std::process::Command;

use crate::fuzz_support::{self, iterations, Rng};
use crate::sea_scenario::folder;

fn beam_impact() -> Command {
    Command::new(env!("CARGO_BIN_EXE_beam-impact"))
}

/// The fixture's sea (Hs 1 m, Tp 8 s, seed 7) with half-second runs: 10 ms or so an event.
fn scenario() -> String {
    "duration = 0.5\n[sea]\nsignificant_wave_height = 1.0\npeak_period = 8.0\nseed = 7\nraos = \"raos.csv\"\n\
     hinge_point = [-10.0, 0.0, 8.0]\nclamp_point = [15.0, 0.0, 8.0]\n"
        .into()
}

fn campaign(dir: &Path, args: &[&str]) -> std::process::Output {
    beam_impact().arg("campaign").arg("s.toml").args(args).current_dir(dir).output().unwrap()
}

/// The CSV's rows as maps of column to text.
fn rows(path: &Path) -> Vec<BTreeMap<String, String>> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header: Vec<String> = lines.next().unwrap().split(',').map(str::to_string).collect();
    lines.map(|l| header.iter().cloned().zip(l.split(',').map(str::to_string)).collect()).collect()
}

const GRID: [&str; 4] = ["--vary", "sea.significant_wave_height=0.5,1", "--vary", "sea.peak_period=6,8"];

const TABLE: &str = "# an illustrative scatter of the four cells\nsignificant_wave_height,peak_period,probability\n\
                     0.5,6,0.35\n0.5,8,0.25\n1,6,0.2\n1,8,0.1\n";

/// The weighted damage per event is sum_c (p_c / S) mean_c of the rows' `fatigue.damage` read
/// from the CSV (each written as the shortest decimal of its f64, so read back exactly), the
/// year's N times it and the life its inverse, to a relative 1e-12 (sums of a few dozen terms in
/// another order: round-off); each cell's mean and probability too.
#[test]
fn the_weighted_damage_is_the_sum_over_the_cells_rows() {
    let dir = folder(&scenario());
    let d = dir.path();
    std::fs::write(d.join("occurrence.csv"), TABLE).unwrap();
    let mut args = vec!["--events", "6", "--seeds", "2", "--record-length", "600", "--fatigue"];
    args.extend(GRID);
    args.extend([
        "--occurrence",
        "occurrence.csv",
        "--set",
        "fatigue.events_per_year=500",
        "--out",
        "e.csv",
        "--json",
        "s.json",
    ]);
    let o = campaign(d, &args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(text.contains("weighted over the occurrence table"), "{text}");
    let mut by_cell: BTreeMap<(String, String), Vec<f64>> = BTreeMap::new();
    for r in rows(&d.join("e.csv")) {
        let key = (r["sea.significant_wave_height"].clone(), r["sea.peak_period"].clone());
        by_cell.entry(key).or_default().push(r["fatigue.damage"].parse().unwrap());
    }
    assert_eq!(by_cell.len(), 4);
    let p = |hs: &str, tp: &str| match (hs, tp) {
        ("0.5", "6") => 0.35,
        ("0.5", "8") => 0.25,
        ("1", "6") => 0.2,
        ("1", "8") => 0.1,
        other => panic!("{other:?}"),
    };
    let sum = 0.35 + 0.25 + 0.2 + 0.1;
    let mean = |v: &Vec<f64>| v.iter().sum::<f64>() / v.len() as f64;
    let expected: f64 = by_cell.iter().map(|((hs, tp), v)| p(hs, tp) / sum * mean(v)).sum();
    let doc: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(d.join("s.json")).unwrap()).unwrap();
    let f = &doc["fatigue"];
    let close = |a: f64, b: f64| (a / b - 1.0).abs() < 1e-12;
    assert!(close(f["damage_per_event"].as_f64().unwrap(), expected), "{f} vs {expected}");
    assert!(close(f["damage_per_year"].as_f64().unwrap(), 500.0 * expected));
    assert!(close(f["life_years"].as_f64().unwrap(), 1.0 / (500.0 * expected)));
    assert!(close(f["probability_sum"].as_f64().unwrap(), sum));
    for cell in f["cells"].as_array().unwrap() {
        let (hs, tp) = (cell["significant_wave_height"].as_f64().unwrap(), cell["peak_period"].as_f64().unwrap());
        let key = (format!("{hs}"), format!("{tp}"));
        assert!(close(cell["mean_damage"].as_f64().unwrap(), mean(&by_cell[&key])), "{cell}");
        assert_eq!(cell["probability"].as_f64().unwrap(), p(&key.0, &key.1));
        assert_eq!(cell["events"], 6);
    }
}

/// Without a table: the cells' means, no year; without `--fatigue`, no fatigue column or block;
/// `--occurrence` alone is a usage error.
#[test]
fn without_a_table_the_cells_means_and_without_fatigue_nothing() {
    let dir = folder(&scenario());
    let d = dir.path();
    let o = campaign(d, &["--events", "2", "--seeds", "1", "--fatigue", "--out", "a.csv", "--json", "a.json"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(text.contains("damage a year: give the sea states' occurrence"), "{text}");
    let doc: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(d.join("a.json")).unwrap()).unwrap();
    assert!(doc["fatigue"]["cells"][0]["mean_damage"].as_f64().unwrap() > 0.0);
    assert!(doc["fatigue"]["damage_per_event"].is_null());
    let o = campaign(d, &["--events", "2", "--seeds", "1", "--out", "b.csv", "--json", "b.json"]);
    assert!(o.status.success());
    assert!(!std::fs::read_to_string(d.join("b.csv")).unwrap().contains("fatigue."));
    let doc: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(d.join("b.json")).unwrap()).unwrap();
    assert!(doc.get("fatigue").is_none());
    std::fs::write(d.join("o.csv"), TABLE).unwrap();
    let o = campaign(d, &["--events", "2", "--seeds", "1", "--occurrence", "o.csv", "--out", "c.csv"]);
    assert_eq!(o.status.code(), Some(2));
}

/// Tables that do not fit the grid or break a bound: exit 2, one line naming the file and the
/// line, before any event runs (no rows written).
#[test]
fn a_bad_occurrence_table_is_refused_in_one_line_before_any_event() {
    let dir = folder(&scenario());
    let d = dir.path();
    for (table, needle) in [
        ("significant_wave_height,peak_period,probability\n0.5,7,0.5\n", "line 2: Hs 0.5 m, Tp 7 s is not a cell"),
        ("significant_wave_height,peak_period,probability\n0.5,6,0.7\n1,8,0.7\n", "sum to 1.4"),
        ("significant_wave_height,peak_period,probability\n0.5,6,inf\n", "must be a finite number"),
        ("significant_wave_height,peak_period,heading,probability\n0.5,6,90,0.5\n", "is not a cell"),
        ("hs,tp,p\n", "unknown column `hs`"),
    ] {
        std::fs::write(d.join("o.csv"), table).unwrap();
        let mut args = vec!["--events", "2", "--seeds", "1", "--fatigue", "--occurrence", "o.csv", "--out", "x.csv"];
        args.extend(GRID);
        let o = campaign(d, &args);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{table}: {stderr}");
        assert!(stderr.contains(needle) && stderr.contains("o.csv"), "{table}: {stderr}");
        assert_eq!(stderr.lines().count(), 1, "{stderr}");
        assert!(!d.join("x.csv").exists());
    }
}

/// The table's parser on mutated and random text: a table or a one-line error, never a panic;
/// an accepted table's probabilities are in [0, 1] and sum to at most 1 + 1e-9, finite.
#[test]
fn mutated_occurrence_tables_never_panic() {
    use beam_impact::studies::campaign::fatigue::Occurrence;
    const LITERALS: &[&str] = &[
        "",
        "NaN",
        "inf",
        "-inf",
        "-0",
        "1e308",
        "5e-324",
        "1.0000000001",
        "8766",
        "8767",
        "0",
        "\"",
        "probability",
        "hours",
        "heading",
        "#",
        "1,2",
    ];
    let seeds = [
        TABLE.to_string(),
        "significant_wave_height,peak_period,heading,hours\n1,6,0,100\n1,6,30,200\n2,8,0,8000\n".to_string(),
    ];
    let cells = [[0.5, 6.0, 180.0], [0.5, 8.0, 180.0], [1.0, 6.0, 180.0], [1.0, 8.0, 180.0], [1.0, 6.0, 0.0]];
    let mut rng = Rng(0x0CC0_0CC0);
    let (mut accepted, mut refused) = (0, 0);
    for _ in 0..iterations(3000) {
        let text = match rng.below(4) {
            0 => {
                let bytes: Vec<u8> = (0..rng.below(200)).map(|_| rng.next_u64() as u8).collect();
                String::from_utf8_lossy(&bytes).into_owned()
            }
            _ => {
                let seed = rng.pick(&seeds).clone();
                fuzz_support::mutate_csv(&seed, LITERALS, &mut rng)
            }
        };
        match Occurrence::parse(&text) {
            Ok(table) => {
                accepted += 1;
                let p: Vec<f64> = table.rows.iter().map(|r| r.probability).collect();
                assert!(p.iter().all(|p| (0.0..=1.0).contains(p)), "{text:?}");
                assert!(p.iter().sum::<f64>() <= 1.0 + 1e-9, "{text:?}");
                if let Err(e) = table.weights(&cells, rng.below(2) == 0) {
                    assert_eq!(e.to_string().lines().count(), 1);
                }
            }
            Err(e) => {
                refused += 1;
                assert_eq!(e.to_string().lines().count(), 1, "{text:?}: {e}");
            }
        }
    }
    assert!(accepted > 0 && refused > 0, "accepted {accepted}, refused {refused}");
}

/// Through the command: random bytes and mutated tables given as `--occurrence` exit 0 or 2,
/// with at most one line on standard error (a table that parses and fits the grid runs its one
/// event per cell).
#[test]
fn the_command_on_hostile_tables_exits_0_or_2_with_one_line() {
    let dir = folder(&scenario());
    let d = dir.path();
    const LITERALS: &[&str] = &["", "NaN", "inf", "-1", "1e308", "0.5", "6", "hours", "heading", "\u{0}"];
    let mut rng = Rng(0x007A_B1E5);
    for i in 0..iterations(12) {
        let bytes: Vec<u8> = if i % 3 == 0 {
            (0..rng.below(300)).map(|_| rng.next_u64() as u8).collect()
        } else {
            fuzz_support::mutate_csv(TABLE, LITERALS, &mut rng).into_bytes()
        };
        std::fs::write(d.join("o.csv"), &bytes).unwrap();
        let mut args = vec!["--events", "1", "--seeds", "1", "--fatigue", "--occurrence", "o.csv", "--out", "h.csv"];
        args.extend(GRID);
        let o = campaign(d, &args);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert!(matches!(o.status.code(), Some(0 | 2)), "{i}: {:?} {stderr}", o.status);
        assert!(stderr.lines().count() <= 1, "{i}: {stderr}");
    }
}

/// A table beyond its size limit is refused from its size, in one line, before it is read.
#[test]
fn a_table_over_its_size_limit_is_refused_in_one_line() {
    use beam_impact::studies::campaign::fatigue::MAX_TABLE_BYTES;
    let dir = folder(&scenario());
    let d = dir.path();
    let file = std::fs::File::create(d.join("big.csv")).unwrap();
    file.set_len(MAX_TABLE_BYTES + 1).unwrap();
    let o = campaign(d, &["--events", "1", "--seeds", "1", "--fatigue", "--occurrence", "big.csv", "--out", "x.csv"]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("occurrence table") && stderr.contains("big.csv"), "{stderr}");
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
}
