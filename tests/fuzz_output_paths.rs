//! Every output path of the CLI against every kind of target a careless user or a stranger's
//! folder can hand it (issue 16: "every output path joins the property tests"): the whole matrix
//! of 7 file outputs x 12 targets and 2 figure folders x 6 targets, each run as a child process.
//!
//! The contract checked on every cell: the command ends (a 60 s `timeout`; a FIFO never blocks
//! it), exits 0 or 2 (never a panic, 101), and on 2 says why in exactly one line; a file that is
//! not the target (a link's target, the scenario, the log read) is never changed; an output that
//! succeeds is a regular file (or folder) at the target, not written through a link; no
//! `NAME.partial` is left behind except one another run still holds. Where the outcome is
//! determined (a new file succeeds; a link, a FIFO, a folder, an input or a locked partial file
//! is refused), the exit status is asserted too.

use std::os::unix::fs::FileTypeExt;
use std::path::{Path, PathBuf};
use std::process::Command;

const VICTIM: &str = "a file the run must never change\n";

/// Runs the binary under `timeout 60`; returns (exit status, stderr).
fn run(args: &[&str], dir: &Path) -> (i32, String) {
    let out = Command::new("timeout")
        .arg("60")
        .arg(env!("CARGO_BIN_EXE_beam-impact"))
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    let code = out.status.code().unwrap_or_else(|| panic!("{args:?}: killed by a signal: {stderr}"));
    assert_ne!(code, 124, "{args:?} did not end within 60 s (blocked on a FIFO?)");
    assert!(code == 0 || code == 2, "{args:?}: exit {code}: {stderr}");
    if code == 2 {
        assert_eq!(stderr.lines().count(), 1, "{args:?}: one line: {stderr}");
        assert!(stderr.starts_with("beam-impact: "), "{args:?}: {stderr}");
    }
    (code, stderr)
}

/// What a case expects: success, refusal, or either (the program may accept or refuse it, but
/// the contract holds).
#[derive(Clone, Copy, Debug, PartialEq)]
enum Expect {
    Ok,
    Refused,
    Either,
}

/// The kinds of target of a file output, set up at `target` (the victim file is `victim`, the
/// scenario `scenario`); returns what the run must do, and the path to give it.
#[derive(Clone, Copy, Debug)]
enum Target {
    New,
    Existing,
    LinkToVictim,
    DanglingLink,
    Fifo,
    Folder,
    TheInput,
    PartialLeftover,
    PartialLinkToVictim,
    PartialLocked,
    MissingFolder,
    DevNull,
}

const TARGETS: [Target; 12] = [
    Target::New,
    Target::Existing,
    Target::LinkToVictim,
    Target::DanglingLink,
    Target::Fifo,
    Target::Folder,
    Target::TheInput,
    Target::PartialLeftover,
    Target::PartialLinkToVictim,
    Target::PartialLocked,
    Target::MissingFolder,
    Target::DevNull,
];

fn fifo(path: &Path) {
    let c = std::ffi::CString::new(path.as_os_str().as_encoded_bytes()).unwrap();
    assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o644) }, 0);
}

fn partial(path: &Path) -> PathBuf {
    let mut name = path.file_name().unwrap().to_os_string();
    name.push(".partial");
    path.with_file_name(name)
}

/// A case's folder: the scenario (`s.toml`, a 2 ms run), a log to report on, the victim.
struct Case {
    dir: tempfile::TempDir,
}

/// The scenario every subcommand reads: 2 ms on the paper's mesh (the paths are under test, not
/// the physics; `verify` of the converged method took 2.8 s per cell, of this one 0.02 s).
const SCENARIO: &str = "duration = 0.002\nmethod = \"paper\"\n";

impl Case {
    fn new(log: &[u8]) -> Case {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("s.toml"), SCENARIO).unwrap();
        std::fs::write(dir.path().join("victim.txt"), VICTIM).unwrap();
        std::fs::write(dir.path().join("in.mcap"), log).unwrap();
        Case { dir }
    }
    fn path(&self, name: &str) -> PathBuf {
        self.dir.path().join(name)
    }
    /// The inputs and the victim are as they were.
    fn untouched(&self, log: &[u8], context: &str) {
        assert_eq!(std::fs::read_to_string(self.path("victim.txt")).unwrap(), VICTIM, "{context}: victim changed");
        assert_eq!(std::fs::read_to_string(self.path("s.toml")).unwrap(), SCENARIO, "{context}: scenario");
        assert_eq!(std::fs::read(self.path("in.mcap")).unwrap(), log, "{context}: the log read changed");
        assert!(!self.path("ghost.txt").exists(), "{context}: a dangling link's target was created");
    }
}

/// The file outputs: a name and the arguments for target `t` (the input is `input`).
type FileOutput = (&'static str, &'static str, fn(&str) -> Vec<String>);

const FILE_OUTPUTS: [FileOutput; 7] = [
    ("run --json", "s.toml", |t| strings(&["run", "s.toml", "--no-mcap", "--json", t])),
    ("run --mcap", "s.toml", |t| strings(&["run", "s.toml", "--mcap", t])),
    ("sweep --out", "s.toml", |t| strings(&["sweep", "s.toml", "--vary", "drop_height=0.3,0.4", "--out", t])),
    ("sweep --json", "s.toml", |t| {
        strings(&["sweep", "s.toml", "--vary", "drop_height=0.3,0.4", "--out", "rows/sweep.csv", "--json", t])
    }),
    ("verify --json", "s.toml", |t| strings(&["verify", "s.toml", "--json", t])),
    ("report --csv", "in.mcap", |t| strings(&["report", "in.mcap", "--out", "figures", "--csv", t])),
    ("modes --out (a file)", "s.toml", |t| strings(&["modes", "s.toml", "--out", t])),
];

fn strings(args: &[&str]) -> Vec<String> {
    args.iter().map(|s| s.to_string()).collect()
}

fn small_log() -> Vec<u8> {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("log.mcap");
    let out = Command::new(env!("CARGO_BIN_EXE_beam-impact"))
        .args(["run", "--set", "duration=0.002", "--mcap"])
        .arg(&path)
        .output()
        .unwrap();
    assert!(out.status.success());
    std::fs::read(path).unwrap()
}

#[test]
fn every_file_output_against_every_kind_of_target_keeps_the_contract() {
    let log = small_log();
    let mut cells = 0;
    for (name, input, args) in FILE_OUTPUTS {
        for target in TARGETS {
            let case = Case::new(&log);
            std::fs::create_dir(case.path("rows")).unwrap();
            let t = case.path("out.file");
            let mut held = None;
            let folder_output = name.starts_with("modes");
            let (given, expect) = match target {
                Target::New => (t.clone(), Expect::Ok),
                Target::Existing => {
                    std::fs::write(&t, "OLD\n").unwrap();
                    (t.clone(), if folder_output { Expect::Refused } else { Expect::Ok })
                }
                Target::LinkToVictim => {
                    std::os::unix::fs::symlink(case.path("victim.txt"), &t).unwrap();
                    (t.clone(), Expect::Refused)
                }
                Target::DanglingLink => {
                    std::os::unix::fs::symlink(case.path("ghost.txt"), &t).unwrap();
                    (t.clone(), Expect::Refused)
                }
                Target::Fifo => {
                    fifo(&t);
                    (t.clone(), Expect::Refused)
                }
                Target::Folder => {
                    std::fs::create_dir(&t).unwrap();
                    (t.clone(), if folder_output { Expect::Ok } else { Expect::Refused })
                }
                Target::TheInput => (case.path(input), Expect::Refused),
                Target::PartialLeftover => {
                    std::fs::write(partial(&t), "a killed run's leftover").unwrap();
                    (t.clone(), if folder_output { Expect::Either } else { Expect::Ok })
                }
                Target::PartialLinkToVictim => {
                    std::os::unix::fs::symlink(case.path("victim.txt"), partial(&t)).unwrap();
                    (t.clone(), Expect::Either)
                }
                Target::PartialLocked => {
                    let file = std::fs::File::create(partial(&t)).unwrap();
                    file.lock().unwrap();
                    held = Some(file);
                    (t.clone(), if folder_output { Expect::Either } else { Expect::Refused })
                }
                Target::MissingFolder => (case.path("missing/out.file"), Expect::Either),
                Target::DevNull => (PathBuf::from("/dev/null"), Expect::Either),
            };
            let given_text = given.to_str().unwrap().to_string();
            let argv = args(&given_text);
            let argv: Vec<&str> = argv.iter().map(String::as_str).collect();
            let context = format!("{name} -> {target:?}");
            let (code, stderr) = run(&argv, case.dir.path());
            match expect {
                Expect::Ok => assert_eq!(code, 0, "{context}: {stderr}"),
                Expect::Refused => assert_eq!(code, 2, "{context}: accepted"),
                Expect::Either => {}
            }
            case.untouched(&log, &context);
            let meta = std::fs::symlink_metadata(&given);
            if code == 0 && given_text != "/dev/null" {
                let m = meta.as_ref().unwrap_or_else(|e| panic!("{context}: no output: {e}"));
                assert!(m.is_file() || (folder_output && m.is_dir()), "{context}: output is {:?}", m.file_type());
            }
            if given_text == "/dev/null" {
                assert!(meta.as_ref().unwrap().file_type().is_char_device(), "{context}: /dev/null replaced");
            }
            if let Target::LinkToVictim | Target::DanglingLink = target {
                assert!(std::fs::symlink_metadata(&t).unwrap().file_type().is_symlink(), "{context}: link replaced");
            }
            if let Target::Fifo = target {
                assert!(std::fs::symlink_metadata(&t).unwrap().file_type().is_fifo(), "{context}: FIFO replaced");
            }
            // No partial file is left behind, except the one another run holds.
            for entry in std::fs::read_dir(case.dir.path()).unwrap() {
                let file_name = entry.unwrap().file_name().into_string().unwrap();
                let held_here = held.is_some() && file_name == "out.file.partial";
                let refused_link = matches!(target, Target::PartialLinkToVictim) && code == 2;
                // A folder output has no partial file: `out.file.partial` there is the user's.
                let not_ours = folder_output && file_name == "out.file.partial";
                assert!(
                    !file_name.contains(".partial") || held_here || refused_link || not_ours,
                    "{context}: {file_name} left"
                );
            }
            drop(held);
            cells += 1;
        }
    }
    assert_eq!(cells, 7 * 12);
}

/// The figure folders (`report --out`, `modes --out`): a stranger's folder may hold links and
/// FIFOs under the figures' names; the folder itself may be a link or a file.
#[test]
fn every_figure_folder_against_every_kind_of_target_keeps_the_contract() {
    let log = small_log();
    type FolderOutput = (&'static str, &'static str, fn(&str) -> Vec<String>);
    let outputs: [FolderOutput; 2] = [
        ("report --out", "fig6-deflection.svg", |t| strings(&["report", "in.mcap", "--out", t])),
        ("modes --out", "fig10-arrestor-modes.svg", |t| strings(&["modes", "s.toml", "--out", t])),
    ];
    for (name, figure, args) in outputs {
        for kind in ["new", "link in it", "FIFO in it", "folder is a link", "folder is a file", "link/."] {
            let case = Case::new(&log);
            let folder = case.path("figs");
            let mut given = folder.to_str().unwrap().to_string();
            let expect = match kind {
                "new" => Expect::Ok,
                "link in it" => {
                    std::fs::create_dir(&folder).unwrap();
                    std::os::unix::fs::symlink(case.path("victim.txt"), folder.join(figure)).unwrap();
                    Expect::Ok
                }
                "FIFO in it" => {
                    std::fs::create_dir(&folder).unwrap();
                    fifo(&folder.join(figure));
                    Expect::Ok
                }
                "folder is a link" | "link/." => {
                    std::fs::create_dir(case.path("elsewhere")).unwrap();
                    std::os::unix::fs::symlink(case.path("elsewhere"), &folder).unwrap();
                    if kind == "link/." {
                        given.push_str("/.");
                    }
                    Expect::Refused
                }
                _ => {
                    std::fs::write(&folder, "OLD\n").unwrap();
                    Expect::Refused
                }
            };
            let context = format!("{name} -> {kind}");
            let argv = args(&given);
            let argv: Vec<&str> = argv.iter().map(String::as_str).collect();
            let (code, stderr) = run(&argv, case.dir.path());
            match expect {
                Expect::Ok => assert_eq!(code, 0, "{context}: {stderr}"),
                Expect::Refused => assert_eq!(code, 2, "{context}: accepted"),
                Expect::Either => {}
            }
            case.untouched(&log, &context);
            if code == 0 {
                let m = std::fs::symlink_metadata(folder.join(figure)).unwrap();
                assert!(m.is_file(), "{context}: {figure} is {:?}", m.file_type());
                for entry in std::fs::read_dir(&folder).unwrap() {
                    let file_name = entry.unwrap().file_name().into_string().unwrap();
                    assert!(!file_name.contains(".partial"), "{context}: {file_name} left");
                }
            }
            if kind == "folder is a link" || kind == "link/." {
                assert_eq!(std::fs::read_dir(case.path("elsewhere")).unwrap().count(), 0, "{context}: wrote via link");
            }
        }
    }
}
