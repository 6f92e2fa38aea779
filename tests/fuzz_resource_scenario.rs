//! Issue 30: the FMU's starting scenario, `resources/scenario.toml`, read at instantiation
//! (`fmi::resource::read_scenario`, `scenario_from_bytes`) from a file somebody else made: on
//! any bytes a scenario the FMU can run or one bounded line of error, never a panic.
//!
//! Goal: replay `tests/corpus/resource_scenarios/` and seeded mutations of what `pack --scenario`
//! writes for the two examples of sections: section tables deleted, duplicated, swapped and
//! emptied, hostile values in their fields (1e308, nan, subnormals, negative lengths, strings),
//! stray `[motion]` and unknown tables, byte-level damage. What is accepted validates, has a
//! token, reads back through `to_toml` and (every few) builds a model that steps 1 ms.
//! `BEAM_IMPACT_FUZZ_ITERATIONS` sets the number of mutations.

use crate::fuzz_support;

use std::path::Path;

use beam_impact::fmi::description::token_for;
use beam_impact::fmi::pack::PackedScenario;
use beam_impact::fmi::resource::{read_scenario, scenario_from_bytes, MAX_SCENARIO_RESOURCE_BYTES, SCENARIO_RESOURCE};
use beam_impact::record::NullRecorder;
use beam_impact::{Scenario, Simulation};
use fuzz_support::{corpus_files, iterations, mutate, Rng};

/// Longest error line: `bounded_line`'s 550 characters of a long message, its cut note and the
/// caller's prefix.
const LONGEST_LINE: usize = 700;

const LITERALS: &[&str] = &[
    "1e308",
    "-1e308",
    "nan",
    "inf",
    "-inf",
    "0",
    "-0.0",
    "5e-324",
    "1e-12",
    "1e-4",
    "-1",
    "1e3",
    "1000.0001",
    "4294967296",
    "\"auto\"",
    "\"\"",
    "true",
    "[1, 2]",
    "{}",
];

/// What `pack --scenario` writes for the examples of sections, and the paper scenario.
fn seeds() -> Vec<String> {
    let example = |name: &str| {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples").join(name);
        let scenario = Scenario::from_toml(&std::fs::read_to_string(path).unwrap(), name).unwrap();
        PackedScenario::new(&scenario, name).unwrap().text
    };
    vec![
        example("tapered-arrestor.toml"),
        example("three-section-gangway.toml"),
        PackedScenario::new(&Scenario::default(), "paper.toml").unwrap().text,
    ]
}

/// Lines a mutation may insert.
const EXTRAS: &[&str] = &[
    "[[lower.sections]]",
    "[[upper.sections]]",
    "[lower.sections]",
    "[[lower.sections.x]]",
    "section_modulus_bottom = 1e-13",
    "allowable_shear_stress = 0",
    "[motion]",
    "time_shift = 1.0",
    "file = \"motion.csv\"",
    "unknown = 1",
    "sections = []",
];

/// One structure-aware mutation of the TOML text `text` ([`fuzz_support::mutate_toml`]).
fn mutate_toml(text: &str, rng: &mut Rng) -> String {
    fuzz_support::mutate_toml(text, rng, LITERALS, EXTRAS, &|rng: &mut Rng, lines: &mut Vec<String>, _: usize| {
        // Many sections (appended): beyond the 32 a beam may have.
        let table = "[[lower.sections]]\nlength = 0.1\nsecond_moment = 0.002\nsection_modulus = 0.01\n\
                     shear_area = 0.01\nmass_per_length = 800.0";
        let count = *rng.pick(&[2usize, 31, 33, 500]);
        lines.push(vec![table; count].join("\n"));
    })
}

/// Reads `bytes`: an error is one bounded line naming the resource; an accepted scenario
/// validates, has a token, round-trips and (when small, every `every`-th one) builds a model
/// whose first millisecond is finite.
fn check(name: &str, bytes: &[u8], built: &mut usize, every: usize) -> bool {
    match scenario_from_bytes(bytes) {
        Err(e) => {
            assert!(!e.contains('\n') && e.chars().count() <= LONGEST_LINE, "{name}: {e}");
            assert!(e.contains(&format!("resources/{SCENARIO_RESOURCE}")), "{name}: {e}");
            false
        }
        Ok(s) => {
            s.validate().unwrap_or_else(|e| panic!("{name}: accepted but does not validate: {e}"));
            assert!(s.motion.is_unset(), "{name}: a motion accepted");
            assert_eq!(token_for(Some(&s)).len(), 38, "{name}");
            let again = Scenario::from_toml(&s.to_toml(), name).unwrap_or_else(|e| panic!("{name}: round trip: {e}"));
            assert_eq!(again, s, "{name}: round trip");
            let largest = s.upper.elements_to_contact.max(s.upper.elements_beyond_contact).max(s.lower.elements);
            let sections = s.upper.sections.len() + s.lower.sections.len();
            // A model costs milliseconds ("auto" meshes of sections tens of them).
            if largest <= 16 && sections <= 4 && (*built).is_multiple_of(every) {
                match Simulation::new(&s) {
                    Err(e) => assert!(!e.to_string().contains('\n'), "{name}: {e}"),
                    Ok(mut sim) => {
                        if let Err(e) = sim.advance_to(1_000_000, &mut NullRecorder, false) {
                            assert!(!e.to_string().contains('\n'), "{name}: {e}");
                        } else {
                            let r = sim.result();
                            assert!(r.lower_tip_deflection.is_finite(), "{name}: after 1 ms: {r:?}");
                        }
                    }
                }
            }
            *built += 1;
            true
        }
    }
}

#[test]
fn the_committed_corpus_replays() {
    let files = corpus_files("resource_scenarios");
    assert!(!files.is_empty());
    let mut built = 0;
    for (name, bytes) in files {
        check(&name, &bytes, &mut built, 1);
    }
}

#[test]
fn seeded_mutations_of_packed_scenarios_never_panic() {
    let seeds = seeds();
    let mut built = 0;
    for (k, seed) in seeds.iter().enumerate() {
        assert!(check(&format!("seed {k}"), seed.as_bytes(), &mut built, 1), "an unmodified seed is accepted");
    }
    let mut rng = Rng(0x5EC7_1025);
    let mut accepted = 0;
    for i in 0..iterations(2000) {
        let seed = rng.pick(&seeds).clone();
        let bytes =
            if i % 4 == 3 { mutate(seed.as_bytes(), &mut rng) } else { mutate_toml(&seed, &mut rng).into_bytes() };
        accepted += usize::from(check(&format!("mutation {i}"), &bytes, &mut built, 8));
    }
    assert!(accepted > 0, "no mutation was accepted: the mutator only reaches the parser's errors");
}

/// The file around the bytes: absent is `None` (the paper scenario); an empty file, a file at
/// the size limit and one byte beyond it, a folder in its place.
#[test]
fn the_resource_file_is_bounded_before_and_while_it_is_read() {
    let dir = tempfile::tempdir().unwrap();
    assert!(read_scenario(dir.path()).unwrap().is_none());
    let file = dir.path().join(SCENARIO_RESOURCE);
    std::fs::write(&file, "").unwrap();
    assert_eq!(read_scenario(dir.path()).unwrap(), Some(Scenario::default()), "an empty file: every default");
    let padded = |len: u64| {
        let mut text = seeds()[0].clone().into_bytes();
        text.resize(len as usize, b'#');
        text
    };
    std::fs::write(&file, padded(MAX_SCENARIO_RESOURCE_BYTES)).unwrap();
    assert!(read_scenario(dir.path()).unwrap().is_some_and(|s| s.lower.sections.len() == 3));
    std::fs::write(&file, padded(MAX_SCENARIO_RESOURCE_BYTES + 1)).unwrap();
    let e = read_scenario(dir.path()).unwrap_err();
    assert!(e.contains("1048577 bytes, larger than 1048576 bytes"), "{e}");
    // A sparse file of 1 GB: refused from its size, nothing of it read.
    std::fs::File::create(&file).unwrap().set_len(1 << 30).unwrap();
    let e = read_scenario(dir.path()).unwrap_err();
    assert!(e.contains("1073741824 bytes, larger than"), "{e}");
    std::fs::remove_file(&file).unwrap();
    std::fs::create_dir(&file).unwrap();
    assert!(read_scenario(dir.path()).unwrap_err().contains("it is a directory"));
}

/// Writes `tests/corpus/resource_scenarios/` (the seeds and hostile files):
/// `cargo test --release --test integration -- --ignored fuzz_resource_scenario::write_corpus`.
#[test]
#[ignore]
fn write_corpus() {
    let dir = fuzz_support::corpus_dir("resource_scenarios");
    std::fs::create_dir_all(&dir).unwrap();
    let seeds = seeds();
    for (i, seed) in seeds.iter().enumerate() {
        std::fs::write(dir.join(format!("seed-{i}.toml")), seed).unwrap();
    }
    let section = "[[lower.sections]]\nlength = 0.1\nsecond_moment = 0.002\nsection_modulus = 0.01\nshear_area = \
                   0.01\nmass_per_length = 800.0\n";
    let hostile = [
        ("sections-33", section.repeat(33)),
        ("sections-200", section.repeat(200)),
        ("section-length-nan", seeds[0].replacen("length = 4.0", "length = nan", 1)),
        ("section-subnormal-modulus", seeds[0].replacen("section_modulus = 0.018", "section_modulus = 5e-324", 1)),
        (
            "section-bottom-1e308",
            seeds[1].replacen("section_modulus_bottom = 0.0062", "section_modulus_bottom = 1e308", 1),
        ),
        ("length-contradicts-sections", seeds[0].replacen("length = 12.0", "length = 12.5", 1)),
        ("motion-table", format!("{}\n[motion]\nfile = \"motion.csv\"\ntime_shift = 2.0\n", seeds[0])),
        ("sections-as-table", "[lower.sections]\nlength = 4.0\n".to_string()),
        ("nested-5000", format!("drop_height = {}1{}\n", "[".repeat(5000), "]".repeat(5000))),
        ("empty", String::new()),
    ];
    for (name, text) in hostile {
        std::fs::write(dir.join(format!("{name}.toml")), text).unwrap();
    }
    std::fs::write(dir.join("not-utf8.toml"), [b'#', 0xff, 0xfe, b'\n']).unwrap();
}

/// Writes the seeds of the cargo-fuzz target `resource_scenario` (the committed corpus):
/// `cargo test --release --test integration -- --ignored fuzz_resource_scenario::write_fuzz_seeds`.
#[test]
#[ignore]
fn write_fuzz_seeds() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz").join("corpus").join("resource_scenario");
    std::fs::create_dir_all(&dir).unwrap();
    for (name, bytes) in corpus_files("resource_scenarios") {
        std::fs::write(dir.join(name), bytes).unwrap();
    }
}

/// Replays what the cargo-fuzz campaign kept (`fuzz/corpus/resource_scenario`), when present.
#[test]
fn the_fuzz_corpus_replays() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz").join("corpus").join("resource_scenario");
    let Ok(entries) = std::fs::read_dir(dir) else { return };
    let mut built = 0;
    for entry in entries {
        let path = entry.unwrap().path();
        check(&path.display().to_string(), &std::fs::read(&path).unwrap(), &mut built, 8);
    }
}
