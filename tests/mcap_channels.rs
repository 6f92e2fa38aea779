//! Issue 41 item 2, recording at solver speed: the default log's chunks are zstd at a fast level
//! (and that level takes effect), and a log with a reduced set of topics (`log.channels`) holds
//! exactly those topics and still replays with `report`.

use std::path::Path;
use std::process::Command;

use beam_impact::record::mcap::{
    LogChannels, LogCompression, McapRecorder, RecorderOptions, DEFAULT_ZSTD_LEVEL, MODES_TOPIC, SCENE_TOPIC,
    STATIONS_TOPIC, STEP_TOPIC,
};
use beam_impact::replay::report::{read_log, summary_from_log};
use beam_impact::{Scenario, Simulation};

/// 0.3 s of the paper scenario (the impact and bounces) into `path`.
fn record(path: &Path, options: RecorderOptions) -> Simulation {
    let mut simulation = Simulation::new(&Scenario { duration: 0.3, ..Scenario::paper() }).unwrap();
    let mut recorder = McapRecorder::with_options(path, options).unwrap();
    simulation.run(&mut recorder).unwrap();
    simulation
}

/// The compression named by every chunk of the log at `path`.
fn chunk_compressions(path: &Path) -> Vec<String> {
    let bytes = std::fs::read(path).unwrap();
    let summary = ::mcap::Summary::read(&bytes).unwrap().unwrap();
    summary.chunk_indexes.iter().map(|c| c.compression.clone()).collect()
}

#[test]
fn the_default_log_is_zstd_at_a_fast_level_that_takes_effect() {
    assert_eq!(RecorderOptions::default().compression, LogCompression::Zstd);
    assert_eq!(RecorderOptions::default().compression_level, DEFAULT_ZSTD_LEVEL);
    const { assert!(DEFAULT_ZSTD_LEVEL < 0) };
    let dir = tempfile::tempdir().unwrap();
    let mut sizes = Vec::new();
    for level in [DEFAULT_ZSTD_LEVEL, 1, -7] {
        let path = dir.path().join(format!("level{level}.mcap"));
        let simulation = record(&path, RecorderOptions { compression_level: level, ..RecorderOptions::default() });
        let compressions = chunk_compressions(&path);
        assert!(!compressions.is_empty() && compressions.iter().all(|c| c == "zstd"), "{compressions:?}");
        let log = read_log(&path).unwrap();
        assert!(log.complete, "level {level}: {:?}", log.problem);
        assert_eq!(summary_from_log(&log, &simulation).unwrap().peaks, simulation.summary().peaks);
        sizes.push(std::fs::metadata(&path).unwrap().len());
    }
    // A fast level reaches zstd as such (the mcap crate takes the level as u32): the faster the
    // level, the larger the file.
    assert!(sizes[1] < sizes[0] && sizes[0] < sizes[2], "sizes at -1, 1, -7: {sizes:?}");
}

#[test]
fn each_channel_set_writes_exactly_its_topics_and_replays() {
    let dir = tempfile::tempdir().unwrap();
    let optional = [(MODES_TOPIC, "modes"), (SCENE_TOPIC, "scene"), (STATIONS_TOPIC, "stations")];
    for list in ["all", "step", "modes", "scene", "stations", "/beam/modes, stations", "model,step,contact,log"] {
        let channels: LogChannels = list.parse().unwrap();
        let path = dir.path().join("log.mcap");
        let simulation = record(&path, RecorderOptions { channels, ..RecorderOptions::default() });
        let log = read_log(&path).unwrap();
        assert!(log.complete, "{list}: {:?}", log.problem);
        assert_eq!(log.steps.len() as u64, simulation.summary().steps + 1, "{list}");
        assert!(log.messages.get(STEP_TOPIC).copied().unwrap_or(0) > 0, "{list}");
        let written = channels.to_string();
        for (topic, name) in optional {
            let count = log.messages.get(topic).copied().unwrap_or(0);
            assert_eq!(count > 0, written.split(',').any(|n| n == name), "{list}: {topic} has {count} messages");
        }
        let summary = summary_from_log(&log, &simulation).unwrap();
        assert_eq!(summary.peaks, simulation.summary().peaks, "{list}");
        // Without the modal coordinates the bridge's strain energy at the peak is not known.
        assert_eq!(summary.upper_strain_at_peak_deflection.is_nan(), !channels.modes, "{list}");
    }
}

#[test]
fn the_older_switches_leave_their_topics_out_whatever_the_channels() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("log.mcap");
    record(&path, RecorderOptions { modal_coordinates: false, station_stresses: false, ..RecorderOptions::default() });
    let log = read_log(&path).unwrap();
    assert_eq!(log.messages.get(MODES_TOPIC).copied().unwrap_or(0), 0);
    assert_eq!(log.messages.get(STATIONS_TOPIC).copied().unwrap_or(0), 0);
    assert!(log.messages.get(SCENE_TOPIC).copied().unwrap_or(0) > 0);
}

#[test]
fn a_cli_log_with_only_the_required_topics_replays_with_report() {
    let dir = tempfile::tempdir().unwrap();
    let log = dir.path().join("small.mcap");
    let bin = env!("CARGO_BIN_EXE_beam-impact");
    let run = Command::new(bin)
        .args(["run", "--set", "duration=0.2", "--log-channels", "step", "--mcap"])
        .arg(&log)
        .output()
        .unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let data = read_log(&log).unwrap();
    for topic in [MODES_TOPIC, SCENE_TOPIC, STATIONS_TOPIC] {
        assert_eq!(data.messages.get(topic).copied().unwrap_or(0), 0, "{topic}");
    }
    assert_eq!(chunk_compressions(&log).first().map(String::as_str), Some("zstd"));
    let report =
        Command::new(bin).arg("report").arg(&log).arg("--out").arg(dir.path().join("figures")).output().unwrap();
    let stdout = String::from_utf8_lossy(&report.stdout);
    assert!(report.status.success(), "{}", String::from_utf8_lossy(&report.stderr));
    assert!(stdout.contains("steps"), "{stdout}");
    assert!(std::fs::read_dir(dir.path().join("figures")).unwrap().count() > 0, "no figures written");
    // A bad list is one line naming it, exit 2, and no log.
    let bad = dir.path().join("bad.mcap");
    let out = Command::new(bin).args(["run", "--log-channels", "step,foo", "--mcap"]).arg(&bad).output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("log.channels: unknown topic \"foo\"; known: model, step"), "{stderr}");
    assert!(!bad.exists());
}

#[test]
fn the_fmus_log_channels_parameter_chooses_the_topics_and_refuses_an_unknown_one() {
    use crate::fmi_common::importer::{load, Fmu2, Fmu3, ERROR, OK};
    let dir = tempfile::tempdir().unwrap();
    let lib = load();
    let path = dir.path().join("fmu.mcap");
    let fmu = Fmu2::new(&lib);
    assert_eq!(fmu.set_string("log.path", path.to_str().unwrap()), OK);
    assert_eq!(fmu.set_string("log.channels", "step,/beam/stations"), OK, "{}", fmu.log.text());
    assert_eq!(fmu.initialize(), OK, "{}", fmu.log.text());
    fmu.run(0.0, 0.05, 1e-2);
    assert_eq!(fmu.call0("fmi2Terminate"), OK);
    // The FMU's log names the full path and the topics.
    let text = fmu.log.text();
    assert!(
        text.contains(&format!("MCAP log of the run: {}, topics model,step,contact,log,stations", path.display())),
        "{text}"
    );
    let data = read_log(&path).unwrap();
    assert!(data.complete, "{:?}", data.problem);
    assert_eq!(data.messages.get(MODES_TOPIC).copied().unwrap_or(0), 0);
    assert_eq!(data.messages.get(SCENE_TOPIC).copied().unwrap_or(0), 0);
    assert!(data.messages.get(STATIONS_TOPIC).copied().unwrap_or(0) > 0);
    // A bad list is the setter's error, naming the value; the parameter keeps its value.
    let fmu3 = Fmu3::try_new(&lib, None, false).0.unwrap();
    assert_eq!(fmu3.set_string("log.channels", "step,foo"), ERROR);
    let text = fmu3.log.text();
    assert!(text.contains("log.channels: unknown topic \"foo\"; known: model, step"), "{text}");
}
