//! The example scenarios (`examples/*.toml`) and the README's commands that use them (issue 19:
//! the README's sweep example failed verbatim, its scenario file did not exist).

use std::path::Path;
use std::process::Command;

use beam_impact::Scenario;

fn examples() -> Vec<std::path::PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    let mut files: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    files
}

#[test]
fn every_example_scenario_is_valid_and_paper_toml_is_the_papers() {
    let files = examples();
    assert!(files.len() >= 2, "{files:?}");
    for file in &files {
        let text = std::fs::read_to_string(file).unwrap();
        let mut scenario = Scenario::from_toml(&text, &file.display().to_string()).unwrap();
        if !scenario.motion.file.is_empty() {
            // `[motion] file` is relative to the scenario file, read as the CLI reads it.
            let csv = std::fs::read_to_string(file.parent().unwrap().join(&scenario.motion.file)).unwrap();
            let table = beam_impact::model::motion_table::MotionTable::parse(&csv).unwrap();
            assert!(table.mismatches().is_empty(), "{}: its rows describe one motion", scenario.motion.file);
            scenario.motion.table = Some(std::sync::Arc::new(table));
        }
        scenario.validate().unwrap();
        if file.ends_with("paper.toml") {
            assert!(scenario.is_paper(), "examples/paper.toml is the paper's scenario and method");
        }
    }
}

/// The README's commands that name an example file, run as written (with a shorter duration and
/// the outputs in a temporary folder).
#[test]
fn the_readmes_commands_on_the_examples_run() {
    let readme = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("README.md")).unwrap();
    // Shell lines, continuations joined.
    let joined = readme.replace("\\\n", " ");
    let commands: Vec<&str> =
        joined.lines().map(str::trim).filter(|l| l.starts_with("beam-impact ") && l.contains("examples/")).collect();
    assert!(!commands.is_empty(), "the README names an example file in a command");
    let dir = tempfile::tempdir().unwrap();
    for command in commands {
        let words: Vec<&str> = command.split('#').next().unwrap().split_whitespace().collect();
        let out = Command::new(env!("CARGO_BIN_EXE_beam-impact"))
            .args(words[1..].iter().map(|w| {
                if w.starts_with("examples/") {
                    Path::new(env!("CARGO_MANIFEST_DIR")).join(w).display().to_string()
                } else {
                    w.to_string()
                }
            }))
            .args(["--set", "duration=0.005"])
            .current_dir(dir.path())
            .output()
            .unwrap();
        assert!(out.status.success(), "{command}: {}", String::from_utf8_lossy(&out.stderr));
    }
    assert!(dir.path().join("sweep.csv").exists() && dir.path().join("sweep.json").exists());
}
