//! Issue 9: the log reader (`read_log_bytes`, then `summary_from_log`) on any bytes: no panic, no
//! unbounded allocation, every problem one line.
//!
//! Goal: replay the regression corpus (`tests/corpus/logs/`, plus the cargo-fuzz findings copied
//! there) and a few thousand seeded mutations of a real log, byte-level and inside the chunks
//! behind correct CRCs (so that the messages themselves are reached), and check the reader's
//! properties. `BEAM_IMPACT_FUZZ_ITERATIONS=200000` runs a longer campaign; `fuzz/` holds the
//! coverage-guided targets.

use crate::fuzz_support;

use std::path::Path;
use std::sync::OnceLock;

use beam_impact::replay::report::{
    envelope_of_log, read_log_bytes, summary_from_log, EnvelopeSource, LogData, RETAINED_RATIO, RETAINED_SLACK,
};
use beam_impact::results::StepResult;
use beam_impact::{Scenario, Simulation};
use fuzz_support::{corpus_files, crafted_logs, edit_chunks, iterations, mutate_log, real_log_bytes, Rng};

fn simulation() -> &'static Simulation {
    static SIMULATION: OnceLock<Simulation> = OnceLock::new();
    SIMULATION.get_or_init(|| Simulation::new(&Scenario::default()).unwrap())
}

/// Reads `bytes` and checks what any log must give: one-line problems, steps in increasing step
/// order (rollbacks applied), memory within the retained bound, and a summary (or a one-line
/// error) from the steps.
fn check(name: &str, bytes: &[u8]) -> Option<LogData> {
    match read_log_bytes(bytes, Path::new(name)) {
        Err(e) => {
            let text = e.to_string();
            assert!(!text.contains('\n'), "{name}: {text}");
            None
        }
        Ok(log) => {
            assert_eq!(log.complete, log.problem.is_none(), "{name}");
            if let Some(problem) = &log.problem {
                assert!(!problem.contains('\n'), "{name}: {problem}");
            }
            assert!(log.steps.windows(2).all(|w| w[0].step < w[1].step), "{name}: steps out of order");
            let kept = log.steps.len() * std::mem::size_of::<StepResult>();
            assert!(kept as u64 <= RETAINED_RATIO * bytes.len() as u64 + RETAINED_SLACK, "{name}: {kept} bytes kept");
            match summary_from_log(&log, simulation()) {
                Ok(_) => assert!(!log.steps.is_empty()),
                Err(e) => assert!(!e.to_string().contains('\n')),
            }
            // The stress envelope (issue 30): stored, rebuilt from the stations' stresses or
            // absent, with one line saying which; a rebuilt one has a value per station.
            let kept = log.stations.values.len() * 4;
            assert!(kept as u64 <= RETAINED_RATIO * bytes.len() as u64 + RETAINED_SLACK, "{name}: {kept} bytes kept");
            assert_eq!(log.stations.values.len(), log.stations.rows() * log.stations.width(), "{name}");
            let (envelope, source) = envelope_of_log(&log);
            assert!(!source.describe().contains('\n'), "{name}: {}", source.describe());
            if let EnvelopeSource::Rebuilt { .. } = source {
                assert_eq!(envelope.lower.bending.max.len(), log.stations.layout.as_ref().unwrap().lower_bending.len());
            }
            Some(log)
        }
    }
}

#[test]
fn the_committed_corpus_and_the_crafted_logs_read_without_panic() {
    for (name, bytes) in corpus_files("logs").into_iter().chain(crafted_logs()) {
        check(&name, &bytes);
    }
}

#[test]
fn seeded_mutations_of_a_real_log_read_without_panic() {
    let real = real_log_bytes();
    let full = check("real", &real).unwrap();
    assert!(full.complete && full.steps.len() > 50);
    // The real log holds the stations' stresses and the envelope (issue 30): mutations reach them.
    assert!(full.envelope_json.is_some() && full.stations.rows() == full.steps.len());
    let mut rng = Rng(9);
    let (mut read, mut damaged, mut stations) = (0, 0, 0);
    for i in 0..iterations(3000) {
        let bytes = mutate_log(&real, &mut rng);
        if let Some(log) = check(&format!("mutation {i}"), &bytes) {
            read += 1;
            damaged += usize::from(log.damaged);
            stations += usize::from(log.problem.as_deref().is_some_and(|p| p.contains("stations message")));
        }
    }
    assert!(read > 0 && damaged > 0, "{read} read, {damaged} of them damaged");
    assert!(stations > 0 || iterations(3000) < 1000, "no mutation stopped at a stations message");
}

/// A killed writer leaves a prefix of the file: whatever the cut, the steps read are a prefix of
/// the full log's steps, and no more of them are lost than the chunk the cut falls in holds.
#[test]
fn every_prefix_of_a_log_reads_a_prefix_of_its_steps() {
    let real = real_log_bytes();
    let full = check("real", &real).unwrap();
    let mut previous = 0;
    for cut in (0..real.len()).step_by(97) {
        let Some(log) = check(&format!("cut at {cut}"), &real[..cut]) else { continue };
        assert!(!log.complete && !log.damaged, "cut at {cut}: {:?}", log.problem);
        assert_eq!(log.steps[..], full.steps[..log.steps.len()], "cut at {cut}");
        assert!(log.steps.len() >= previous, "cut at {cut}: fewer steps than a shorter prefix");
        previous = log.steps.len();
    }
    assert_eq!(previous, full.steps.len());
}

/// Rollbacks in any pattern: the steps kept are those of the last branch, in order.
#[test]
fn rollbacks_keep_the_last_branch() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("rollbacks.mcap");
    fuzz_support::synthetic_log(&path, &Scenario::default(), 2000, true, fuzz_support::small_chunks());
    let log = check("rollbacks", &std::fs::read(&path).unwrap()).unwrap();
    assert_eq!(log.rollbacks, 1999);
    assert!(log.steps.iter().enumerate().all(|(k, r)| r.step == k as u64));
    // Reordered chunks: a step index that jumps back far drops every later step at once.
    let bytes = std::fs::read(&path).unwrap();
    let swapped = edit_chunks(&bytes, &mut |i, records| if i == 3 { Vec::new() } else { records });
    check("a chunk emptied", &swapped);
}

/// Writes the seeds of the cargo-fuzz targets `log_file` (the committed log corpus) and
/// `log_chunk` (the decompressed records of each chunk of a real log, and all of them at once,
/// schema data left out):
/// `cargo test --release --test integration -- --ignored fuzz_log_reader::write_fuzz_seeds`.
#[test]
#[ignore]
fn write_fuzz_seeds() {
    let fuzz = Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz").join("corpus");
    let (files, chunks) = (fuzz.join("log_file"), fuzz.join("log_chunk"));
    std::fs::create_dir_all(&files).unwrap();
    std::fs::create_dir_all(&chunks).unwrap();
    for (name, bytes) in corpus_files("logs") {
        std::fs::write(files.join(name), bytes).unwrap();
    }
    let mut all = Vec::new();
    edit_chunks(&real_log_bytes(), &mut |i, records| {
        let stripped = fuzz_support::strip_schema_data(&records);
        std::fs::write(chunks.join(format!("real-chunk-{i}")), &stripped).unwrap();
        all.extend_from_slice(&stripped);
        records
    });
    std::fs::write(chunks.join("real-all-chunks"), all).unwrap();
}

/// Replays what the cargo-fuzz campaigns kept (`fuzz/corpus/log_file`, and `fuzz/corpus/log_chunk`
/// wrapped as that target wraps it), when present.
#[test]
fn the_fuzz_corpora_replay() {
    let fuzz = Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz").join("corpus");
    for (target, wrap) in [("log_file", false), ("log_chunk", true)] {
        let Ok(entries) = std::fs::read_dir(fuzz.join(target)) else { continue };
        for entry in entries {
            let path = entry.unwrap().path();
            let bytes = std::fs::read(&path).unwrap();
            let bytes = if wrap { fuzz_support::wrap_chunk_records(&bytes) } else { bytes };
            check(&path.display().to_string(), &bytes);
        }
    }
}

/// Prints the time to read the log `$BEAM_IMPACT_BENCH_LOG` with the bounded reader (framing,
/// zstd, CRCs) and with the mcap crate's `ChunkFlattener` (what `report` used before issue 9), best
/// of 5; a measurement, not a test:
/// `BEAM_IMPACT_BENCH_LOG=paper.mcap cargo test --release --test integration -- --ignored --nocapture fuzz_log_reader::bench_readers`.
#[test]
#[ignore]
fn bench_readers() {
    use beam_impact::replay::safe_read::{read_records, Limits};
    use std::time::{Duration, Instant};
    let path = std::env::var("BEAM_IMPACT_BENCH_LOG").expect("BEAM_IMPACT_BENCH_LOG");
    let bytes = std::fs::read(&path).unwrap();
    let best = |f: &dyn Fn() -> usize| {
        let mut best = Duration::MAX;
        let mut n = 0;
        for _ in 0..5 {
            let t = Instant::now();
            n = f();
            best = best.min(t.elapsed());
        }
        (best, n)
    };
    let (ours, n_ours) = best(&|| {
        let mut n = 0;
        read_records::<()>(&bytes, Limits::default(), &mut |_, _| {
            n += 1;
            Ok(())
        })
        .unwrap();
        n
    });
    let (theirs, n_theirs) = best(&|| {
        use mcap::read::{ChunkFlattener, Options};
        let reader = ChunkFlattener::new_with_options(&bytes, Options::ValidateChunkCrcs | Options::IgnoreEndMagic);
        reader.unwrap().inspect(|r| assert!(r.is_ok())).count()
    });
    let (full, _) = best(&|| read_log_bytes(&bytes, Path::new(&path)).unwrap().steps.len());
    println!(
        "{path} ({} bytes): safe_read {:.1} ms ({n_ours} records), mcap ChunkFlattener {:.1} ms ({n_theirs} records), \
         read_log_bytes (decoding every message) {:.1} ms",
        bytes.len(),
        ours.as_secs_f64() * 1e3,
        theirs.as_secs_f64() * 1e3,
        full.as_secs_f64() * 1e3
    );
}
