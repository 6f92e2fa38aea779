//! Issue 9: the scenario parser (`Scenario::from_toml`, which validates) on any text: a scenario
//! within the limits or a one-line error naming the field, never a panic; what it accepts
//! round-trips through `to_toml` and builds a model.
//!
//! Goal: replay `tests/corpus/scenarios/` and seeded mutations of real scenario files: values
//! replaced by hostile literals (1e308, nan, inf, subnormals, 2^64, strings, arrays, tables),
//! lines deleted, duplicated and swapped, unknown keys and tables, deep nesting, and byte-level
//! mutations. `BEAM_IMPACT_FUZZ_ITERATIONS` sets the number of mutations.

use crate::fuzz_support;

use beam_impact::record::NullRecorder;
use beam_impact::{Scenario, Simulation};
use fuzz_support::{corpus_files, iterations, mutate, Rng};

const LITERALS: &[&str] = &[
    "1e308",
    "-1e308",
    "1.7976931348623157e308",
    "nan",
    "-nan",
    "inf",
    "-inf",
    "0",
    "-0.0",
    "1e-320",
    "5e-324",
    "1e-9",
    "1e-10",
    "4294967295",
    "4294967296",
    "-1",
    "9223372036854775807",
    "18446744073709551616",
    "1e6",
    "1e9",
    "256",
    "257",
    "\"auto\"",
    "\"mean\"",
    "\"left\"",
    "\"pinned-pinned\"",
    "\"clamped-clamped\"",
    "\"\"",
    "true",
    "[1, 2]",
    "{}",
    "{ a = 1 }",
    "1979-05-27T07:32:00Z",
];

/// The seed scenarios: every field (the default), the paper's, a sparse file, and beams of
/// sections (issue 30: `[[lower.sections]]` and `[[upper.sections]]` tables mutated too).
fn seeds() -> Vec<String> {
    vec![
        Scenario::default().to_toml(),
        Scenario::paper().to_toml(),
        include_str!("../examples/tapered-arrestor.toml").to_string(),
        include_str!("../examples/three-section-gangway.toml").to_string(),
        // Issue 44: `[[load_cases]]` with their factors and `set` tables mutated too.
        include_str!("../examples/load-cases.toml").to_string(),
        // Issue 45: the struck beam on two supports, struck at a given position.
        include_str!("../examples/deck-beam-supports.toml").to_string(),
        "[lower]\nsupports = \"clamped-pinned\"\ncontact_position = 3.5\nelements = 8\ntip_mass = 0\n".to_string(),
        // Issue 45: a rigid impactor, with Hertz's law and with a linear contact.
        include_str!("../examples/lab-sphere.toml").to_string(),
        include_str!("../examples/dropped-container.toml").to_string(),
        "drop_height = 0.8\nstep_free = 5e-5\n[upper]\nelements_to_contact = 14\n[lower]\nelements = 3\n".to_string(),
    ]
}

/// Lines a mutation may insert.
const EXTRAS: &[&str] = &[
    "unknown = 1",
    "[upper]",
    "[[upper]]",
    "[upper.deeper]",
    "[nothing]",
    "upper = 1",
    "upper.length = 3",
    "\"drop_height\" = 1",
    "drop_height.x = 1",
];

/// One structure-aware mutation of the TOML text `text` ([`fuzz_support::mutate_toml`]).
fn mutate_toml(text: &str, rng: &mut Rng) -> String {
    fuzz_support::mutate_toml(text, rng, LITERALS, EXTRAS, &|rng: &mut Rng, lines: &mut Vec<String>, i: usize| {
        let depth = *rng.pick(&[2usize, 64, 1000, 100_000]);
        let nested = format!("drop_height = {}1{}", "[".repeat(depth), "]".repeat(depth));
        lines.insert(i, nested);
    })
}

/// Parses `text`; an accepted scenario must validate, round-trip and (when small, every `every`-th
/// one) build a model whose first millisecond is finite.
fn check(name: &str, text: &str, built: &mut usize, every: usize) {
    match Scenario::from_toml(text, name) {
        Err(e) => assert!(!e.to_string().contains('\n'), "{name}: {e}"),
        Ok(s) => {
            s.validate().unwrap_or_else(|e| panic!("{name}: accepted but does not validate: {e}"));
            let again = Scenario::from_toml(&s.to_toml(), name).unwrap_or_else(|e| panic!("{name}: round trip: {e}"));
            assert_eq!(again, s, "{name}: round trip");
            let largest = s.upper.elements_to_contact.max(s.upper.elements_beyond_contact).max(s.lower.elements);
            // A model costs milliseconds.
            if largest <= 16 && (*built).is_multiple_of(every) {
                match Simulation::new(&s) {
                    Err(e) => assert!(!e.to_string().contains('\n'), "{name}: {e}"),
                    Ok(mut sim) => {
                        if let Err(e) = sim.advance_to(1_000_000, &mut NullRecorder, false) {
                            assert!(!e.to_string().contains('\n'), "{name}: {e}");
                        } else {
                            let r = sim.result();
                            assert!(
                                r.lower_tip_deflection.is_finite() && r.energy.residual.is_finite(),
                                "{name}: accepted, and after 1 ms: {r:?}\n{text}"
                            );
                        }
                    }
                }
            }
            *built += 1;
        }
    }
}

#[test]
fn the_committed_corpus_replays() {
    let files = corpus_files("scenarios");
    assert!(!files.is_empty());
    let mut built = 0;
    for (name, bytes) in files {
        check(&name, &String::from_utf8_lossy(&bytes), &mut built, 1);
    }
}

#[test]
fn seeded_mutations_of_scenario_files_never_panic() {
    let seeds = seeds();
    let mut rng = Rng(0x5CE7A);
    let (mut built, mut accepted) = (0, 0);
    for i in 0..iterations(3000) {
        let seed = rng.pick(&seeds).clone();
        let text = if i % 4 == 3 {
            String::from_utf8_lossy(&mutate(seed.as_bytes(), &mut rng)).into_owned()
        } else {
            mutate_toml(&seed, &mut rng)
        };
        let before = built;
        check(&format!("mutation {i}"), &text, &mut built, 8);
        accepted += usize::from(built > before);
    }
    assert!(accepted > 0, "no mutation was accepted: the mutator only reaches the parser's errors");
}

/// Writes `tests/corpus/scenarios/` (the seeds and hostile files):
/// `cargo test --release --test integration -- --ignored fuzz_scenario::write_corpus`.
#[test]
#[ignore]
fn write_corpus() {
    let dir = fuzz_support::corpus_dir("scenarios");
    std::fs::create_dir_all(&dir).unwrap();
    for (i, seed) in seeds().iter().enumerate() {
        std::fs::write(dir.join(format!("seed-{i}.toml")), seed).unwrap();
    }
    let hostile = [
        ("duration-1e6-step-1e-9", "duration = 1e6\nstep_free = 1e-9\nstep_contact = 1e-9\n".to_string()),
        ("drop-height-1e308", "drop_height = 1e308\n".to_string()),
        ("subnormal-section-modulus", "[upper]\nsection_modulus = 5e-324\n".to_string()),
        (
            "elements-400-400-400",
            "[upper]\nelements_to_contact = 400\nelements_beyond_contact = 400\n[lower]\nelements = 400\n".to_string(),
        ),
        ("elements-2p32", "[lower]\nelements = 4294967296\n".to_string()),
        ("nested-5000", format!("drop_height = {}1{}\n", "[".repeat(5000), "]".repeat(5000))),
        ("nan-everywhere", Scenario::default().to_toml().replace("= 0.", "= nan #").replace("= 1", "= nan #")),
        ("empty", String::new()),
        // Issue 45: the contact on a far support, and a hair from a pin (a refused grading).
        ("supports-contact-on-far-pin", "[lower]\nsupports = \"pinned-pinned\"\ncontact_position = 12\n".to_string()),
        (
            "supports-contact-near-pin",
            "[lower]\nsupports = \"pinned-pinned\"\ncontact_position = 1e-9\nelements = 8\n".to_string(),
        ),
    ];
    for (name, text) in hostile {
        std::fs::write(dir.join(format!("{name}.toml")), text).unwrap();
    }
}

/// Writes the seeds of the cargo-fuzz target `scenario` (the committed scenario corpus):
/// `cargo test --release --test integration -- --ignored fuzz_scenario::write_fuzz_seeds`.
#[test]
#[ignore]
fn write_fuzz_seeds() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz").join("corpus").join("scenario");
    std::fs::create_dir_all(&dir).unwrap();
    for (name, bytes) in corpus_files("scenarios") {
        std::fs::write(dir.join(name), bytes).unwrap();
    }
}

/// Replays what the cargo-fuzz campaign kept (`fuzz/corpus/scenario`), when present.
#[test]
fn the_fuzz_corpus_replays() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz").join("corpus").join("scenario");
    let Ok(entries) = std::fs::read_dir(dir) else { return };
    let mut built = 0;
    for entry in entries {
        let path = entry.unwrap().path();
        let text = String::from_utf8_lossy(&std::fs::read(&path).unwrap()).into_owned();
        check(&path.display().to_string(), &text, &mut built, 8);
    }
}
