//! Issue 9: `beam-impact report` on logs made by somebody else never crashes, hangs or lies.
//!
//! Goal: the binary, given the crafted logs of the issue (a chunk declaring 2^40 or 2^64-1
//! bytes, lengths beyond their records, a zstd bomb, a scenario beyond the limits, a rollback-heavy
//! log), the committed regression corpus (`tests/corpus/logs/`) and a few hundred random
//! mutations of a real log, exits 0 (report written) or 2 (one line on stderr naming what is
//! wrong), never with a panic (101) or an abort (134).
//! Sketch: each file is written to a temporary directory and `report` runs on it as a child
//! process. Times and memory are not asserted here; `tests/corpus/measure-report.sh` measures them.

use crate::fuzz_support;

use std::path::Path;
use std::process::Command;

use fuzz_support::{corpus_files, crafted_logs, mutate_log, real_log_bytes, scenario_log, synthetic_log, Rng};

/// Runs `report` on `bytes`; returns (exit code, stdout, stderr), after checking the contract:
/// exit 0 or 2, and on 2 exactly one line on stderr, `beam-impact: ...`.
fn report(dir: &Path, name: &str, bytes: &[u8]) -> (i32, String, String) {
    let log = dir.join(name);
    std::fs::write(&log, bytes).unwrap();
    let (code, stdout, stderr) = report_file(&log, &dir.join(format!("{name}-figures")));
    std::fs::remove_file(&log).ok();
    (code, stdout, stderr)
}

fn report_file(log: &Path, figures: &Path) -> (i32, String, String) {
    let name = log.display();
    let out = Command::new(env!("CARGO_BIN_EXE_beam-impact"))
        .arg("report")
        .arg(log)
        .arg("--out")
        .arg(figures)
        .output()
        .unwrap();
    std::fs::remove_dir_all(figures).ok();
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    let code = out.status.code().unwrap_or_else(|| panic!("{name}: killed by a signal: {:?}; {stderr}", out.status));
    assert!(code == 0 || code == 2, "{name}: exit code {code}; stderr: {stderr}");
    assert!(!stderr.contains("internal error") && !stderr.contains("panicked"), "{name}: {stderr}");
    if code == 2 {
        assert!(stderr.starts_with("beam-impact: ") && stderr.ends_with('\n'), "{name}: {stderr:?}");
        assert_eq!(stderr.lines().count(), 1, "{name}: more than one line: {stderr:?}");
    }
    (code, stdout, stderr)
}

#[test]
fn crafted_logs_are_refused_in_one_line() {
    let dir = tempfile::tempdir().unwrap();
    for (name, bytes) in crafted_logs() {
        let (code, stdout, stderr) = report(dir.path(), &name, &bytes);
        // None of them holds a step: each is refused, with the record and where it is.
        assert_eq!(code, 2, "{name}: {stdout}");
        assert!(stderr.contains(&name), "{name}: the message names the file: {stderr}");
    }
    let (_, _, stderr) = report(dir.path(), "x.mcap", &fuzz_support::inner_record_log(1 << 40));
    assert!(
        stderr.contains("message record (opcode 0x05) at byte 0 of the records of the chunk at byte")
            && stderr.contains("declares 1099511627785 bytes"),
        "{stderr}"
    );
    let mut chunk = fuzz_support::start();
    chunk.extend(fuzz_support::chunk(&fuzz_support::message(1, 0, b"x"), true, Some(u64::MAX)));
    fuzz_support::end(&mut chunk);
    let (_, _, stderr) = report(dir.path(), "y.mcap", &chunk);
    assert!(stderr.contains("chunk record (opcode 0x06) at byte") && stderr.contains("uncompressed bytes"), "{stderr}");
}

#[test]
fn the_committed_corpus_replays() {
    let dir = tempfile::tempdir().unwrap();
    let files = corpus_files("logs");
    assert!(files.len() >= 20, "the corpus holds {} logs", files.len());
    for (name, bytes) in files {
        report(dir.path(), &name, &bytes);
    }
}

#[test]
fn mutations_of_a_real_log_exit_0_or_2() {
    let real = real_log_bytes();
    let dir = tempfile::tempdir().unwrap();
    let (code, stdout, _) = report(dir.path(), "real.mcap", &real);
    assert_eq!(code, 0);
    assert!(stdout.contains("status: complete"), "{stdout}");
    let count = fuzz_support::iterations(300);
    let (mut ok, mut refused) = (0, 0);
    // Two workers: each mutation is a process that writes the figures (6-12, SVG and PNG).
    std::thread::scope(|s| {
        let workers: Vec<_> = (0..2u64)
            .map(|w| {
                let (real, dir) = (&real, dir.path());
                s.spawn(move || {
                    let mut rng = Rng(0x5EED_0009 + w);
                    let mut codes = (0, 0);
                    for i in 0..count / 2 {
                        let bytes = mutate_log(real, &mut rng);
                        match report(dir, &format!("m{w}-{i}.mcap"), &bytes).0 {
                            0 => codes.0 += 1,
                            _ => codes.1 += 1,
                        }
                    }
                    codes
                })
            })
            .collect();
        for w in workers {
            let (a, b) = w.join().unwrap();
            ok += a;
            refused += b;
        }
    });
    // Both outcomes occur: the mutations reach the reports, not only the refusals.
    assert!(ok > 0 && refused > 0, "{ok} reported, {refused} refused");
}

/// A byte in the middle of the first chunk record at or after byte `from` of the log `bytes` (its
/// records walked from the magic), so that a change of the log's layout keeps it inside a chunk.
fn inside_chunk(bytes: &[u8], from: usize) -> usize {
    let mut at = 8;
    loop {
        let len = u64::from_le_bytes(bytes[at + 1..at + 9].try_into().unwrap()) as usize;
        if bytes[at] == 0x06 && at >= from {
            return at + 9 + len / 2;
        }
        at += 9 + len;
    }
}

#[test]
fn truncated_real_logs_report_every_complete_chunk() {
    let real = real_log_bytes();
    let dir = tempfile::tempdir().unwrap();
    let full = beam_impact::replay::report::read_log_bytes(&real, Path::new("real")).unwrap();
    assert!(full.complete);
    let mut previous = 0;
    for cut in [real.len() / 4, real.len() / 2, real.len() * 3 / 4, real.len() - 9, real.len() - 1] {
        let log = beam_impact::replay::report::read_log_bytes(&real[..cut], Path::new("cut")).unwrap();
        assert!(!log.complete && !log.damaged, "{cut}: {:?}", log.problem);
        assert!(log.steps.len() >= previous && log.steps.len() <= full.steps.len());
        assert!(log.steps.iter().enumerate().all(|(k, r)| r.step == k as u64));
        previous = log.steps.len();
        let (code, stdout, _) = report(dir.path(), "cut.mcap", &real[..cut]);
        assert_eq!(code, 0);
        assert!(stdout.contains("status: CUT SHORT"), "{stdout}");
    }
    // A bit flipped inside a chunk: the chunk's CRC refuses it; the chunks before it are reported.
    let mut flipped = real.clone();
    flipped[inside_chunk(&real, real.len() / 2)] ^= 0x10;
    let log = beam_impact::replay::report::read_log_bytes(&flipped, Path::new("flipped")).unwrap();
    assert!(log.damaged, "{:?}", log.problem);
    let (code, stdout, _) = report(dir.path(), "flipped.mcap", &flipped);
    assert_eq!(code, 0);
    assert!(stdout.contains("status: DAMAGED: chunk record (opcode 0x06) at byte"), "{stdout}");
}

#[test]
fn a_stored_scenario_beyond_the_limits_is_refused_before_any_model_is_built() {
    let dir = tempfile::tempdir().unwrap();
    let (code, _, stderr) = report(dir.path(), "elements-400.mcap", &scenario_log(400, 400, 400));
    assert_eq!(code, 2);
    assert!(stderr.contains("the scenario stored in the log is refused") && stderr.contains("elements"), "{stderr}");
}

/// 320 000 step messages of which half follow a rollback (each step recorded, rolled back and
/// recorded again): read in linear time (it took 40-56 s with a `retain` per rollback).
#[test]
fn a_rollback_heavy_log_reads_every_rollback() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("rollbacks.mcap");
    // Every step a row (the synthetic steps are no run's: no dense output).
    let options = beam_impact::record::mcap::RecorderOptions {
        scene_interval_ns: 0,
        sample_interval_ns: 0,
        ..Default::default()
    };
    synthetic_log(&path, &beam_impact::Scenario::default(), 160_000, true, options);
    let log = beam_impact::replay::report::read_log(&path).unwrap();
    assert!(log.complete, "{:?}", log.problem);
    assert_eq!(log.rollbacks, 159_999);
    assert_eq!(log.steps.len(), 160_000);
    assert!(log.steps.iter().enumerate().all(|(k, r)| r.step == k as u64));
    assert_eq!(log.events.len(), 159);
    let (code, stdout, _) = report_file(&path, &dir.path().join("figures"));
    assert_eq!(code, 0);
    assert!(stdout.contains("rollbacks: 159999"), "{stdout}");
}

#[test]
fn odd_values_in_the_steps_are_reported_or_refused() {
    let dir = tempfile::tempdir().unwrap();
    for value in [f64::NAN, f64::INFINITY, 1e308, 1e300, f64::MIN_POSITIVE / 4.0, 0.0] {
        for odd_time in [false, true] {
            let (code, stdout, _) = report(dir.path(), "odd.mcap", &fuzz_support::odd_values_log(value, odd_time));
            assert_eq!(code, 0);
            let drawn = stdout.contains("fig6-deflection.png");
            assert_eq!(drawn, value.abs() <= 1e300, "{value} {odd_time}: {stdout}");
        }
    }
}

/// Writes the regression corpus `tests/corpus/logs/` from the builders above (run it after
/// changing them; fuzz findings are added to the directory by hand):
/// `cargo test --release --test integration -- --ignored hostile_logs::write_corpus`.
#[test]
#[ignore]
fn write_corpus() {
    let dir = fuzz_support::corpus_dir("logs");
    std::fs::create_dir_all(&dir).unwrap();
    let mut files = crafted_logs();
    let real = real_log_bytes();
    files.push(("real-2ms.mcap".into(), real.clone()));
    files.push(("real-cut-half.mcap".into(), real[..real.len() / 2].to_vec()));
    files.push(("real-cut-in-footer.mcap".into(), real[..real.len() - 12].to_vec()));
    let mut flipped = real.clone();
    flipped[real.len() / 3] ^= 0x04;
    files.push(("real-bit-flipped.mcap".into(), flipped));
    // Inside the chunks, behind correct CRCs: a step message cut in half; a channel id changed.
    let cut_message = fuzz_support::edit_chunks(&real, &mut |i, mut records| {
        if i == 1 {
            let n = records.len();
            records.truncate(n - 40);
        }
        records
    });
    files.push(("real-chunk-records-cut.mcap".into(), cut_message));
    for (name, value) in
        [("nan", f64::NAN), ("inf", f64::INFINITY), ("1e308", 1e308), ("1e300", 1e300), ("subnormal", 1e-310)]
    {
        files.push((format!("steps-all-{name}.mcap"), fuzz_support::odd_values_log(value, false)));
        files.push((format!("steps-and-times-all-{name}.mcap"), fuzz_support::odd_values_log(value, true)));
    }
    // Constant values far from 0 (an axis range narrower than its values' spacing), a single
    // infinity among finite values, values spanning the whole plottable range.
    let series: [(&str, &dyn Fn(u64) -> f64); 4] = [
        ("constant-1e20", &|_| 1e20),
        ("constant-minus-1e300", &|_| -1e300),
        ("one-infinity", &|k| if k == 30 { f64::INFINITY } else { k as f64 }),
        ("spanning", &|k| (k as f64 - 25.0) * 4e298),
    ];
    for (name, value) in series {
        files.push((format!("steps-{name}.mcap"), fuzz_support::odd_series_log(value, false)));
    }
    files.push(("scenario-400-400-400-elements.mcap".into(), scenario_log(400, 400, 400)));
    files.push(("scenario-256-256-256-elements.mcap".into(), scenario_log(256, 256, 256)));
    for (name, bytes) in files {
        std::fs::write(dir.join(name), bytes).unwrap();
    }
}

/// Writes the logs `tests/corpus/measure-report.sh` measures into `$BEAM_IMPACT_HOSTILE_OUT`:
/// `mutations/` (`BEAM_IMPACT_FUZZ_ITERATIONS` mutations of a real log, default 1000) and `big/`
/// (320 000 step messages: linear, linear in a chunk per step, and half after a rollback).
#[test]
#[ignore]
fn write_measurement_logs() {
    let out = std::path::PathBuf::from(std::env::var("BEAM_IMPACT_HOSTILE_OUT").expect("BEAM_IMPACT_HOSTILE_OUT"));
    let (mutations, big) = (out.join("mutations"), out.join("big"));
    std::fs::create_dir_all(&mutations).unwrap();
    std::fs::create_dir_all(&big).unwrap();
    let real = real_log_bytes();
    let mut rng = Rng(0x1000);
    for i in 0..fuzz_support::iterations(1000) {
        std::fs::write(mutations.join(format!("mutation-{i:04}.mcap")), mutate_log(&real, &mut rng)).unwrap();
    }
    std::fs::write(big.join("compressible-events-60mib.mcap"), fuzz_support::compressible_events_log()).unwrap();
    let options = beam_impact::record::mcap::RecorderOptions { scene_interval_ns: 0, ..Default::default() };
    let scenario = beam_impact::Scenario::default();
    synthetic_log(&big.join("linear-320000.mcap"), &scenario, 320_000, false, options);
    synthetic_log(&big.join("rollbacks-160000-of-320000.mcap"), &scenario, 160_000, true, options);
    // The recorder flushes at each rollback, so the rollback log is made of tiny chunks: the same
    // chunking without rollbacks, for a comparison at equal file structure.
    let every_step = beam_impact::record::mcap::RecorderOptions { flush_every: 1, ..options };
    synthetic_log(&big.join("linear-320000-chunk-per-step.mcap"), &scenario, 320_000, false, every_step);
}

/// The worst memory per file byte: a 1 MiB log whose chunk decompresses (within the 64x budget)
/// to 2 million contact events; the reader stops at what it may keep and says so.
#[test]
fn what_the_reader_keeps_is_bounded_by_the_file() {
    use beam_impact::replay::report::{read_log_bytes, RETAINED_RATIO, RETAINED_SLACK};
    let bytes = fuzz_support::compressible_events_log();
    let log = read_log_bytes(&bytes, Path::new("events")).unwrap();
    assert!(log.damaged, "{:?}", log.problem);
    assert!(log.problem.as_deref().unwrap().contains("the log decodes to more than"), "{:?}", log.problem);
    let kept = (log.events.len() * std::mem::size_of::<beam_impact::results::ContactEvent>()) as u64;
    assert!(kept <= RETAINED_RATIO * bytes.len() as u64 + RETAINED_SLACK);
    assert!(log.events.len() > 100_000);
}

/// A byte changed in the top-level metadata record (which has no CRC of its own) went unnoticed
/// (an attack pass: a scenario value silently different). Logs now carry the data section's
/// CRC: such a change is reported as damage, and a changed log format names the damage too.
#[test]
fn a_changed_metadata_byte_fails_the_data_section_crc() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("run.mcap");
    let out = Command::new(env!("CARGO_BIN_EXE_beam-impact"))
        .args(["run", "--set", "duration=0.01", "--mcap"])
        .arg(&path)
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let good = std::fs::read(&path).unwrap();
    let log = beam_impact::replay::report::read_log(&path).unwrap();
    assert!(log.complete && !log.damaged, "{:?}", log.problem);
    let find = |needle: &[u8]| good.windows(needle.len()).rposition(|w| w == needle).unwrap();
    // contact.area = "0.04" in the metadata's string map (key, then the value's u32 length).
    let entry = find(b"contact.area\x04\x00\x00\x000.04");
    let mut bad = good.clone();
    bad[entry + b"contact.area".len() + 4 + 3] = b'5';
    std::fs::write(&path, &bad).unwrap();
    let log = beam_impact::replay::report::read_log(&path).unwrap();
    let problem = log.problem.clone().unwrap_or_default();
    assert!(log.damaged && problem.contains("the data section fails its CRC check"), "{problem}");
    // The log format itself changed: refused, naming the damage.
    let mut bad = good.clone();
    let at = find(b"log_format") + b"log_format".len() + 4;
    assert_eq!(bad[at], b'2');
    bad[at] = b'3';
    std::fs::write(&path, &bad).unwrap();
    let error = beam_impact::replay::report::read_log(&path).unwrap_err().to_string();
    assert!(error.contains("log format \"3\"") && error.contains("the file is damaged"), "{error}");
}

/// Issue 30: a stations message that does not decode or does not hold one stress per station of
/// the model stops the reading there in one line (the steps before it reported); an envelope
/// attachment that does not parse (bytes, a nesting deeper than any parser's stack) is said in
/// one line and nothing is drawn from it. Never a panic.
#[test]
fn a_malformed_stations_message_or_envelope_attachment_is_one_line() {
    use beam_impact::record::mcap::{ENVELOPE_ATTACHMENT, STATIONS_TOPIC};
    use beam_impact::record::schema::StationStressesMessage;
    use prost::Message;
    let dir = tempfile::tempdir().unwrap();
    let real = real_log_bytes();
    let (code, stdout, _) = report(dir.path(), "real.mcap", &real);
    assert_eq!(code, 0);
    assert!(stdout.contains("stress envelope: from the log's envelope.json"), "{stdout}");
    let garbage = fuzz_support::rewrite_messages(&real, STATIONS_TOPIC, &mut |k, data| {
        if k == 20 {
            vec![0xff; 7]
        } else {
            data.to_vec()
        }
    });
    let (code, stdout, _) = report(dir.path(), "garbage.mcap", &garbage);
    assert_eq!(code, 0, "{stdout}");
    assert!(stdout.contains("DAMAGED: stations message at") && stdout.contains("does not decode"), "{stdout}");
    let short = fuzz_support::rewrite_messages(&real, STATIONS_TOPIC, &mut |k, data| {
        if k == 3 {
            StationStressesMessage { step: 3, lower_bending: vec![1.0], ..Default::default() }.encode_to_vec()
        } else {
            data.to_vec()
        }
    });
    let (code, stdout, _) = report(dir.path(), "short.mcap", &short);
    assert_eq!(code, 0, "{stdout}");
    assert!(stdout.contains("holds 1 stresses ([1, 0, 0, 0]) where the model has"), "{stdout}");
    // Attachments a run never writes, on a log without stations.
    let deep = "[".repeat(100_000);
    let texts: [&[u8]; 4] = [b"\xff\xfe not json", deep.as_bytes(), b"{\"lower\": 1e999}", b"null"];
    for (k, text) in texts.into_iter().enumerate() {
        let path = dir.path().join(format!("attached-{k}.mcap"));
        let mut recorder =
            beam_impact::record::mcap::McapRecorder::with_options(&path, fuzz_support::small_chunks()).unwrap();
        let shapes = nalgebra::DMatrix::<f64>::zeros(2, 2);
        let scenario = beam_impact::Scenario::default();
        use beam_impact::record::Recorder;
        let info = beam_impact::record::RunInfo {
            scenario: &scenario,
            lower_nodes: &[0.0, 12.0],
            upper_nodes: &[0.0, 29.0],
            nodal_shapes: &shapes,
            stations: None,
        };
        recorder.start(&info).unwrap();
        recorder.step(&beam_impact::results::StepResult::default(), &[0.0, 0.0]).unwrap();
        recorder.attach(ENVELOPE_ATTACHMENT, "application/json", text).unwrap();
        recorder.finish().unwrap();
        let (code, stdout, _) = report_file(&path, &dir.path().join("figures"));
        assert_eq!(code, 0, "{stdout}");
        let line = stdout.lines().find(|l| l.starts_with("stress envelope:")).unwrap();
        assert!(line.contains("envelope.json does not parse") || line.contains("is refused"), "{line}");
        assert!(line.len() < 400, "{line}");
    }
}
