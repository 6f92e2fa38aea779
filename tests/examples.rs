//! The example scenarios (`examples/*.toml`) and the commands the README and the docs show (issue 19:
//! the README's sweep example failed verbatim, its scenario file did not exist; issue 31: every
//! command a page shows is run by a test or marked as not run).

use std::path::Path;
use std::process::Command;

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
        // `[motion] file` and `[sea] raos` are relative to the scenario file, read as the CLI
        // reads them; a motion file's rows describe one motion (no warning).
        let mut warnings = Vec::new();
        let scenario = beam_impact::scenario_file::read_file(file, &mut warnings)
            .unwrap_or_else(|e| panic!("{}: {e}", file.display()));
        assert!(warnings.is_empty(), "{}: {warnings:?}", file.display());
        scenario.validate().unwrap();
        if file.ends_with("paper.toml") {
            assert!(scenario.is_paper(), "examples/paper.toml is the paper's scenario and method");
        }
    }
}

/// The subcommands whose run the duration bounds: given `--set duration=0.005` so the pages'
/// commands stay cheap (the whole set runs in a few seconds).
const TIMED: &[&str] = &["run", "sweep", "verify", "damping"];

/// Every command block of the README and the docs marked `<!-- run by tests/examples.rs -->`,
/// run as written, line after line in one temporary folder (so a `report` reads the log a `run`
/// above it wrote), `run`, `sweep`, `verify` and `damping` with `--set duration=0.005`. Each
/// line must be a `beam-impact` command (continuations joined, comments after `#` dropped).
#[test]
fn the_pages_commands_marked_for_this_file_run() {
    let marked = crate::docs::blocks_run_by("tests/examples.rs");
    assert!(marked.len() >= 4, "the README and docs mark their example commands: {marked:?}");
    let dir = tempfile::tempdir().unwrap();
    let mut ran = 0;
    for (page, block) in &marked {
        assert!(block.language == "sh", "{page}:{}: a ```{} block is not a shell block", block.line, block.language);
        let joined = block.body.replace("\\\n", " ");
        for line in joined.lines().map(|l| l.split('#').next().unwrap().trim()).filter(|l| !l.is_empty()) {
            let words: Vec<&str> = line.split_whitespace().collect();
            assert!(
                words[0] == "beam-impact" && !line.contains(['|', '>', '<', ';', '&', '$']),
                "{page}:{}: `{line}` is not a plain beam-impact command: this file runs only those",
                block.line
            );
            let mut command = Command::new(env!("CARGO_BIN_EXE_beam-impact"));
            command.args(words[1..].iter().map(|w| {
                if w.starts_with("examples/") {
                    Path::new(env!("CARGO_MANIFEST_DIR")).join(w).display().to_string()
                } else {
                    w.to_string()
                }
            }));
            if words.get(1).is_some_and(|s| TIMED.contains(s)) {
                command.args(["--set", "duration=0.005"]);
            }
            let out = command.current_dir(dir.path()).output().unwrap();
            assert!(out.status.success(), "{page}:{}: {line}: {}", block.line, String::from_utf8_lossy(&out.stderr));
            ran += 1;
        }
    }
    assert!(ran >= 8, "{ran} commands");
    // What the commands say they write.
    for file in ["sweep.csv", "sweep.json", "arrestor.mcap", "arrestor-figures/fig6-deflection.svg"] {
        assert!(dir.path().join(file).exists(), "{file} not written");
    }
}
