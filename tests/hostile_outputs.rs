//! Hostile inputs, round two (issue 16): every file the CLI writes goes through one guard
//! (`src/record/output.rs`), every input is read within a bound, and sweep grids are checked
//! from their counts. Each test is one of the reproductions, which failed before.

use std::path::Path;
use std::process::{Command, Output, Stdio};

fn beam_impact() -> Command {
    Command::new(env!("CARGO_BIN_EXE_beam-impact"))
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// Exit 2 with one line on standard error, naming `needle`.
fn refused(out: &Output, needle: &str) {
    let text = stderr(out);
    assert_eq!(out.status.code(), Some(2), "{text}");
    assert_eq!(text.lines().count(), 1, "one line: {text}");
    assert!(text.contains(needle), "`{needle}` in: {text}");
}

const SHORT: [&str; 2] = ["--set", "duration=0.002"];

/// Item 1: `run --json ./x.mcap --mcap x.mcap` wrote the JSON over the log; the two paths name
/// one file (by folder and name while it does not exist yet): refused before anything is written.
#[test]
fn json_and_log_naming_one_new_file_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let out = beam_impact()
        .current_dir(dir.path())
        .args(["run", "--json", "./x.mcap", "--mcap", "x.mcap"])
        .args(SHORT)
        .output()
        .unwrap();
    refused(&out, "name the same file");
    assert!(!dir.path().join("x.mcap").exists());
    let out = beam_impact().current_dir(dir.path()).args(["run", "--json", "./paper.mcap"]).output().unwrap();
    refused(&out, "name the same file");
}

/// Item 4: `run s.toml --json s.toml` overwrote the scenario; `sweep --out` and `verify --json`
/// followed symbolic links and overwrote the scenario file itself.
#[test]
fn outputs_never_overwrite_the_scenario_or_write_through_a_link() {
    let dir = tempfile::tempdir().unwrap();
    let scenario = dir.path().join("s.toml");
    std::fs::write(&scenario, "duration = 0.002\n").unwrap();
    let victim = dir.path().join("victim.txt");
    std::fs::write(&victim, "keep me").unwrap();
    let link = dir.path().join("link.csv");
    std::os::unix::fs::symlink(&victim, &link).unwrap();

    let out = beam_impact().arg("run").arg(&scenario).arg("--json").arg(&scenario).arg("--no-mcap").output().unwrap();
    refused(&out, "name the same file");
    let out = beam_impact()
        .arg("sweep")
        .arg(&scenario)
        .arg("--out")
        .arg(&scenario)
        .args(["--vary", "drop_height=0.5"])
        .output()
        .unwrap();
    refused(&out, "name the same file");
    let out = beam_impact()
        .arg("sweep")
        .arg(&scenario)
        .arg("--out")
        .arg(&link)
        .args(["--vary", "drop_height=0.5"])
        .output()
        .unwrap();
    refused(&out, "symbolic link");
    let out = beam_impact().arg("verify").arg(&scenario).arg("--json").arg(&link).output().unwrap();
    refused(&out, "symbolic link");
    assert_eq!(std::fs::read_to_string(&scenario).unwrap(), "duration = 0.002\n");
    assert_eq!(std::fs::read_to_string(&victim).unwrap(), "keep me");
}

/// Item 2: a stranger's log folder with `fig6-deflection.svg -> victim` had the victim
/// overwritten by `report`, and a FIFO there blocked it forever. Now the figure replaces the link
/// and the FIFO (renamed into place), the victim is untouched and the report ends. A figure
/// folder that is itself a link is refused. Item 4: `report --csv DIR/fig6-deflection.svg` was
/// replaced by the figure: a CSV inside the figure folder is refused.
#[test]
fn figures_replace_links_and_fifos_instead_of_writing_through_them() {
    let dir = tempfile::tempdir().unwrap();
    let log = dir.path().join("log.mcap");
    let out = beam_impact().args(["run", "--set", "duration=0.05", "--mcap"]).arg(&log).output().unwrap();
    assert!(out.status.success(), "{}", stderr(&out));
    let figures = dir.path().join("log-figures");
    std::fs::create_dir(&figures).unwrap();
    let victim = dir.path().join("bashrc");
    std::fs::write(&victim, "keep me").unwrap();
    std::os::unix::fs::symlink(&victim, figures.join("fig6-deflection.svg")).unwrap();
    let fifo = figures.join("fig6-deflection.png");
    let c = std::ffi::CString::new(fifo.to_str().unwrap()).unwrap();
    // SAFETY: a valid NUL-terminated path.
    assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0);
    let mut child = beam_impact().arg("report").arg(&log).stdout(Stdio::null()).stderr(Stdio::piped()).spawn().unwrap();
    let started = std::time::Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if started.elapsed().as_secs() > 120 {
            child.kill().unwrap();
            panic!("report hangs on a FIFO in the figure folder");
        }
        std::thread::sleep(std::time::Duration::from_millis(50));
    };
    assert!(status.success());
    assert_eq!(std::fs::read_to_string(&victim).unwrap(), "keep me");
    for name in ["fig6-deflection.svg", "fig6-deflection.png"] {
        let m = std::fs::symlink_metadata(figures.join(name)).unwrap();
        assert!(m.is_file() && m.len() > 0, "{name} is a fresh figure");
    }
    let out =
        beam_impact().arg("report").arg(&log).arg("--csv").arg(figures.join("fig6-deflection.svg")).output().unwrap();
    refused(&out, "inside the figure folder");

    let elsewhere = dir.path().join("elsewhere");
    std::fs::create_dir(&elsewhere).unwrap();
    let linked = dir.path().join("linked-figures");
    std::os::unix::fs::symlink(&elsewhere, &linked).unwrap();
    let out = beam_impact().arg("report").arg(&log).arg("--out").arg(&linked).output().unwrap();
    refused(&out, "symbolic link");
    assert_eq!(std::fs::read_dir(&elsewhere).unwrap().count(), 0);
}

/// Item 5: `run /dev/zero` and `cat /dev/zero | beam-impact run -` grew until the machine ran out
/// of memory; a device is refused as a scenario file, and reads stop at 4 MiB with a one-line
/// error naming the limit.
#[test]
fn endless_scenario_inputs_stop_at_the_limit() {
    // A device as the scenario file is refused before reading; a 5 MiB file stops at the limit.
    let out = beam_impact().args(["run", "/dev/zero"]).output().unwrap();
    refused(&out, "device other than /dev/null");
    let dir = tempfile::tempdir().unwrap();
    let big = dir.path().join("big.toml");
    std::fs::write(&big, vec![b'#'; 5 << 20]).unwrap();
    let out = beam_impact().arg("run").arg(&big).output().unwrap();
    refused(&out, "larger than 4194304 bytes");
    let zero = std::fs::File::open("/dev/zero").unwrap();
    let out = beam_impact().args(["run", "-"]).stdin(zero).output().unwrap();
    refused(&out, "larger than 4194304 bytes");
    let out = beam_impact().args(["sweep", "/dev/zero", "--out", "/dev/null"]).output().unwrap();
    refused(&out, "device other than /dev/null");
    let out = beam_impact().arg("verify").arg(&big).output().unwrap();
    refused(&out, "larger than 4194304 bytes");
}

/// Item 6: a count of u64::MAX panicked (exit 101), 1e9 aborted on an 8 GB allocation, 1e8 built
/// 788 MB of values: counts are checked before any value is built.
#[test]
fn sweep_counts_are_checked_before_any_value_is_built() {
    for spec in [
        "drop_height=0.1:0.5:18446744073709551615",
        "drop_height=0.1:0.5:1000000000",
        "drop_height=0.1:0.5:1e9",
        "drop_height=0.1:0.5:inf",
    ] {
        let out = beam_impact().args(["sweep", "--vary", spec]).arg("--out").arg("/dev/null").output().unwrap();
        refused(&out, "1000000");
    }
    let out = beam_impact()
        .args([
            "sweep",
            "--vary",
            "drop_height=0.1:0.5:1000",
            "--vary",
            "damping_ratio=0:0.05:1001",
            "--out",
            "/dev/null",
        ])
        .output()
        .unwrap();
    refused(&out, "more than 1000000 scenarios");
}

/// Item 7: an existing `--json` was emptied before a bad `--mcap` path was even tried. Now the
/// JSON is written beside and renamed into place when the run ends: a failed run leaves it.
#[test]
fn a_failed_run_leaves_the_earlier_results_as_they_were() {
    let dir = tempfile::tempdir().unwrap();
    let json = dir.path().join("results.json");
    std::fs::write(&json, "{\"earlier\": true}\n").unwrap();
    for mcap in [dir.path().join("missing/x.mcap"), Path::new("/dev/full").to_path_buf()] {
        let out =
            beam_impact().args(["run", "--json"]).arg(&json).arg("--mcap").arg(&mcap).args(SHORT).output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
        assert_eq!(std::fs::read_to_string(&json).unwrap(), "{\"earlier\": true}\n", "--mcap {}", mcap.display());
    }
    let names: Vec<_> = std::fs::read_dir(dir.path()).unwrap().map(|e| e.unwrap().file_name()).collect();
    assert_eq!(names, vec![std::ffi::OsString::from("results.json")], "no partial file left");
    let out = beam_impact().args(["run", "--no-mcap", "--json"]).arg(&json).args(SHORT).output().unwrap();
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(std::fs::read_to_string(&json).unwrap().contains("\"summary\""));
}

/// `--mcap x.mcap/` ran the whole run into `x.mcap.partial` and then failed to rename it over
/// `x.mcap/` ("Not a directory"), leaving the partial file: a name ending with `/` can only be a
/// folder's, refused before the run, as `--json x.json/` is.
#[test]
fn a_name_ending_with_a_slash_is_refused_before_the_run() {
    let dir = tempfile::tempdir().unwrap();
    let slash = |name: &str| format!("{}/", dir.path().join(name).display());
    for args in
        [vec!["--mcap".to_string(), slash("x.mcap")], vec!["--no-mcap".into(), "--json".into(), slash("x.json")]]
    {
        let out = beam_impact().arg("run").args(&args).args(SHORT).output().unwrap();
        refused(&out, "ends with `/`");
    }
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0, "nothing written");
}

/// Item 10: a 100 MB string in a scenario gave a 300 MB error line. Within the 4 MiB read limit a
/// 3 MB string still makes a bounded line.
#[test]
fn error_lines_stay_short_whatever_the_input_holds() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("big.toml");
    std::fs::write(&file, format!("drop_height = \"{}\"\n", "x".repeat(3_000_000))).unwrap();
    let out = beam_impact().arg("run").arg(&file).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(out.stderr.len() < 1000, "{} bytes of error", out.stderr.len());
    assert!(stderr(&out).contains("characters cut"), "{}", stderr(&out));
}

/// An attack pass on the guard (this session): devices other than /dev/null, a figure folder
/// named `link/`, a hard link left at the log's `NAME.partial`, an output named like another's
/// partial file, an input inside the figure folder under a figure's name, `report /dev/zero`, a
/// million-value integer axis, and terminal escapes in an error line.
#[test]
fn second_attack_pass_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let run = |args: &[&str]| beam_impact().current_dir(d).args(args).args(SHORT).output().unwrap();
    refused(&run(&["run", "--no-mcap", "--json", "/dev/zero"]), "device other than /dev/null");
    refused(&run(&["run", "--mcap", "/dev/zero"]), "device other than /dev/null");
    refused(&run(&["run", "--json", "out.json", "--mcap", "out.json.partial"]), "is written through");
    std::fs::write(d.join("x.partial"), "duration = 0.002\n").unwrap();
    refused(&run(&["run", "x.partial", "--mcap", "x"]), "is written through");
    assert_eq!(std::fs::read_to_string(d.join("x.partial")).unwrap(), "duration = 0.002\n");

    // A hard link at the log's partial file is removed, not written through.
    std::fs::write(d.join("victim.txt"), "keep me").unwrap();
    std::fs::hard_link(d.join("victim.txt"), d.join("h.mcap.partial")).unwrap();
    let out = run(&["run", "--mcap", "h.mcap"]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(std::fs::read_to_string(d.join("victim.txt")).unwrap(), "keep me");
    assert!(d.join("h.mcap").is_file() && !d.join("h.mcap.partial").exists());

    // `link/` names the link's target: still refused.
    std::fs::create_dir(d.join("elsewhere")).unwrap();
    std::os::unix::fs::symlink(d.join("elsewhere"), d.join("linkdir")).unwrap();
    for out_dir in ["linkdir/", "linkdir/."] {
        let out = beam_impact().current_dir(d).args(["report", "h.mcap", "--out", out_dir]).output().unwrap();
        refused(&out, "symbolic link");
    }
    assert_eq!(std::fs::read_dir(d.join("elsewhere")).unwrap().count(), 0);

    // An input inside the figure folder under a figure's name would be replaced by a figure.
    std::fs::create_dir(d.join("out")).unwrap();
    std::fs::copy(d.join("h.mcap"), d.join("out/fig6-deflection.svg")).unwrap();
    let out =
        beam_impact().current_dir(d).args(["report", "out/fig6-deflection.svg", "--out", "out"]).output().unwrap();
    refused(&out, "lies in the figure folder");

    let out = beam_impact().args(["report", "/dev/zero"]).output().unwrap();
    refused(&out, "not a regular file");
    let out = beam_impact()
        .args([
            "sweep",
            "--out",
            "/dev/null",
            "--vary",
            "lower.elements=1:1000000:1000000",
            "--vary",
            "drop_height=1,2",
        ])
        .output()
        .unwrap();
    refused(&out, "more than 1000000 scenarios");
    let out = beam_impact().args(["run", "--no-mcap", "--set", "method=a\u{1b}[2Kb"]).output().unwrap();
    refused(&out, "method");
    assert!(!out.stderr.contains(&0x1b), "no escape byte reaches the terminal");
}

/// `modes` reads a scenario as `run` does: "auto" element counts (the file `beam-impact
/// scenario` prints) are resolved, not refused.
#[test]
fn modes_takes_the_printed_scenario_file() {
    let dir = tempfile::tempdir().unwrap();
    let printed = beam_impact().arg("scenario").output().unwrap();
    assert!(printed.status.success());
    let file = dir.path().join("s.toml");
    std::fs::write(&file, &printed.stdout).unwrap();
    let out = beam_impact().arg("modes").arg(&file).arg("--out").arg(dir.path().join("modes")).output().unwrap();
    assert!(out.status.success(), "{}", stderr(&out));
}

/// `run --mcap -` wrote a log to a file named `-` in the working folder (an attack pass): the
/// log cannot go to standard output, and nothing is written.
#[test]
fn a_log_to_standard_output_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let out = beam_impact().current_dir(dir.path()).args(["run", "--mcap", "-"]).args(SHORT).output().unwrap();
    refused(&out, "cannot go to standard output");
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0, "nothing written");
}

/// Two runs given the same `--json` (an attack pass): the second removed the first's
/// `NAME.partial` as a killed run's leftover and the first then renamed the second's file. A
/// partial file is locked while its run writes it: the second run is refused, the first's
/// results land; a killed run's leftover (no lock) is still taken over.
#[test]
fn a_partial_output_another_run_writes_is_not_taken_over() {
    let dir = tempfile::tempdir().unwrap();
    let json = dir.path().join("r.json");
    let partial = dir.path().join("r.json.partial");
    // Another run holds the partial file (its lock, as OutputFile takes it).
    let held = std::fs::File::create(&partial).unwrap();
    held.lock().unwrap();
    let out = beam_impact().arg("run").arg("--no-mcap").arg("--json").arg(&json).args(SHORT).output().unwrap();
    refused(&out, "being written by another run");
    assert!(partial.exists() && !json.exists(), "the other run's file is left alone");
    // Its run killed: the lock is free, the leftover is taken over and the results land.
    drop(held);
    let out = beam_impact().arg("run").arg("--no-mcap").arg("--json").arg(&json).args(SHORT).output().unwrap();
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(json.exists() && !partial.exists());
}

/// Issue 40 (part 5) item 1: every path the CLI prints is escaped, as docs/security.md promises.
/// A folder named with an escape sequence and a line break reached the terminal raw through
/// `run`'s "supports moving:", "recorded to" and "results written to", `sweep`'s "rows written
/// to" (its JSON and units sidecar too), `report`'s log and figures, `modes`' figures and `pack`'s
/// "wrote" lines. Now no control byte reaches standard output or standard error, and each path is
/// shown with its escapes (`\u{1b}`, `\n`).
#[test]
fn printed_paths_carry_no_control_character() {
    let dir = tempfile::tempdir().unwrap();
    let hostile = dir.path().join("a\u{1b}[31mb\nc");
    std::fs::create_dir(&hostile).unwrap();
    let escaped = "a\\u{1b}[31mb\\nc";
    let clean = |what: &str, out: &Output| {
        assert!(out.status.success(), "{what}: {}", stderr(out));
        let stdout = String::from_utf8_lossy(&out.stdout);
        for (stream, bytes) in [("stdout", &out.stdout), ("stderr", &out.stderr)] {
            let raw = bytes.iter().any(|&b| (b < 0x20 && b != b'\n') || b == 0x7f);
            assert!(!raw, "{what}: a raw control byte on {stream}: {:?}", String::from_utf8_lossy(bytes));
            assert!(!String::from_utf8_lossy(bytes).contains("b\nc"), "{what}: a raw line break in a path on {stream}");
        }
        assert!(stdout.contains(escaped), "{what}: the path is shown escaped: {stdout}");
        stdout.into_owned()
    };
    let motion = hostile.join("m.csv");
    std::fs::write(
        &motion,
        "time,upper.hinge_heave,upper.hinge_heave_velocity,upper.hinge_heave_acceleration\n0,0,0,0\n1,0,0,0\n",
    )
    .unwrap();
    let log = hostile.join("r.mcap");
    let out = beam_impact()
        .args(["run", "--set", "duration=0.002", "--motion"])
        .arg(&motion)
        .arg("--json")
        .arg(hostile.join("r.json"))
        .arg("--mcap")
        .arg(&log)
        .output()
        .unwrap();
    let stdout = clean("run", &out);
    for line in ["supports moving: ", "recorded to ", "results written to "] {
        let at = stdout.find(line).unwrap_or_else(|| panic!("{line:?} in {stdout}"));
        assert!(stdout[at..].lines().next().unwrap().contains(escaped), "{line:?} in {stdout}");
    }
    let out = beam_impact().arg("report").arg(&log).arg("--out").arg(hostile.join("figures")).output().unwrap();
    let stdout = clean("report", &out);
    assert!(stdout.lines().filter(|l| l.contains(escaped)).count() > 2, "the log and the figures: {stdout}");
    let out = beam_impact()
        .args(["sweep", "--set", "duration=0.002", "--vary", "drop_height=0.5", "--out"])
        .arg(hostile.join("rows.csv"))
        .arg("--json")
        .arg(hostile.join("rows.json"))
        .output()
        .unwrap();
    let stdout = clean("sweep", &out);
    assert_eq!(stdout.matches(escaped).count(), 3, "the CSV, the JSON and the units sidecar: {stdout}");
    let out = beam_impact().arg("modes").arg("--out").arg(hostile.join("modes")).output().unwrap();
    clean("modes", &out);
    let exe = Path::new(env!("CARGO_BIN_EXE_beam-impact"));
    let library = [exe.with_file_name("libbeam_impact.so"), exe.with_file_name("deps").join("libbeam_impact.so")]
        .into_iter()
        .find(|p| p.is_file())
        .unwrap();
    let out = beam_impact()
        .args(["pack", "--no-zigbuild", "--library"])
        .arg(&library)
        .arg("--out")
        .arg(hostile.join("fmu"))
        .output()
        .unwrap();
    let stdout = clean("pack", &out);
    assert_eq!(stdout.lines().filter(|l| l.starts_with("wrote ") && l.contains(escaped)).count(), 2, "{stdout}");
}
