//! `beam-impact pack --ssp` (issue 31, item 1) writes DIR/GangwayOnVessel.ssp beside the FMUs: a
//! zip with SystemStructure.ssd at its root and the BeamImpact FMU (FMI 2.0) and the vessel-motion
//! FMU (built here from its C source with the host's cc) under resources/; a bad `--out` or a
//! vessel build that cannot run is one line and leaves nothing behind.
//! tests/python/test_ssp.py validates the SSD against the SSP 1.0 schema and runs it in three tools.

use std::io::Read;
use std::path::Path;

/// The host build of the library (beside the executable, or in deps/ under `cargo test`).
fn host_library() -> std::path::PathBuf {
    let exe = Path::new(env!("CARGO_BIN_EXE_beam-impact"));
    let beside = exe.with_file_name("libbeam_impact.so");
    if beside.is_file() {
        beside
    } else {
        exe.with_file_name("deps").join("libbeam_impact.so")
    }
}

/// `pack --ssp` with PATH limited to the system's (the host's cc, no cargo-zigbuild); returns
/// (exit code, stdout, stderr).
fn pack_ssp(args: &[&str]) -> (Option<i32>, String, String) {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_beam-impact"))
        .args(["pack", "--ssp", "--no-zigbuild", "--library"])
        .arg(host_library())
        .args(args)
        .env("PATH", "/usr/local/bin:/usr/bin:/bin")
        .output()
        .unwrap();
    (out.status.code(), String::from_utf8_lossy(&out.stdout).into(), String::from_utf8_lossy(&out.stderr).into())
}

/// The names and contents of a zip's entries.
fn unzip(bytes: &[u8]) -> Vec<(String, Vec<u8>)> {
    let mut archive = zip::ZipArchive::new(std::io::Cursor::new(bytes)).unwrap();
    (0..archive.len())
        .map(|k| {
            let mut entry = archive.by_index(k).unwrap();
            let mut data = Vec::new();
            entry.read_to_end(&mut data).unwrap();
            (entry.name().to_string(), data)
        })
        .collect()
}

#[test]
fn pack_ssp_writes_the_ssd_and_both_fmus_under_resources() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("fmu");
    let (code, stdout, stderr) = pack_ssp(&["--out", out.to_str().unwrap()]);
    assert_eq!(code, Some(0), "{stderr}");
    let ssp = out.join("GangwayOnVessel.ssp");
    assert!(stdout.contains(&format!("wrote {}", ssp.display())), "{stdout}");
    let entries = unzip(&std::fs::read(&ssp).unwrap());
    let names: Vec<&str> = entries.iter().map(|e| e.0.as_str()).collect();
    assert_eq!(names, ["SystemStructure.ssd", "resources/BeamImpact.fmu", "resources/VesselMotion.fmu"]);
    // The BeamImpact FMU is the FMI 2.0 one written beside it, byte for byte.
    assert_eq!(entries[1].1, std::fs::read(out.join("fmi2").join("BeamImpact.fmu")).unwrap());
    let ssd = String::from_utf8(entries[0].1.clone()).unwrap();
    for source in ["resources/BeamImpact.fmu", "resources/VesselMotion.fmu"] {
        assert!(ssd.contains(&format!("source=\"{source}\"")), "{source}");
    }
    // The vessel FMU: its description and the Linux library, exporting the FMI 2 functions.
    let vessel = unzip(&entries[2].1);
    let vessel_names: Vec<&str> = vessel.iter().map(|e| e.0.as_str()).collect();
    assert_eq!(vessel_names, ["modelDescription.xml", "binaries/linux64/VesselMotion.so", "resources/raos.csv"]);
    assert_eq!(vessel[0].1, beam_impact::ssp::vessel::DESCRIPTION.as_bytes());
    // The irregular sea's RAO table: the example vessel's, byte for byte.
    assert_eq!(vessel[2].1, std::fs::read("examples/vessel-sea-raos.csv").unwrap());
    let library = &vessel[1].1;
    assert_eq!(&library[..4], b"\x7fELF");
    assert!(library.windows(10).any(|w| w == b"fmi2DoStep"));
}

#[test]
fn pack_ssp_into_a_file_is_one_line_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("not-a-dir");
    std::fs::write(&file, "x").unwrap();
    let (code, _, stderr) = pack_ssp(&["--out", file.to_str().unwrap()]);
    assert_ne!(code, Some(0));
    assert_eq!(stderr.trim_end().lines().count(), 1, "{stderr}");
    assert!(stderr.contains("not-a-dir"), "{stderr}");
    assert_eq!(std::fs::read(&file).unwrap(), b"x");
}

/// A Windows binary asked for without zig to build the vessel's DLL: one line naming what is
/// missing, before any FMU is written.
#[test]
fn pack_ssp_without_zig_for_windows_is_one_line_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let dll = dir.path().join("BeamImpact.dll");
    std::fs::write(&dll, "stand-in").unwrap();
    let out = dir.path().join("fmu");
    let (code, _, stderr) = pack_ssp(&[
        "--platforms",
        "linux,windows",
        "--windows-library",
        dll.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_ne!(code, Some(0));
    assert_eq!(stderr.trim_end().lines().count(), 1, "{stderr}");
    assert!(stderr.contains("vessel-motion library for windows") && stderr.contains("cargo-zigbuild"), "{stderr}");
    assert!(!out.exists());
}

/// Issue 40 (part 5) item 9: a symbolic link at DIR/GangwayOnVessel.ssp was refused only after
/// both FMUs in DIR had been replaced. Now every output of `pack` goes through the output guard's
/// checks before the first is written (before anything is built): one line naming the archive,
/// the earlier FMUs untouched (content and modification time), the link's target too.
#[test]
fn pack_ssp_onto_a_link_is_refused_before_any_fmu_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("fmu");
    let earlier: Vec<std::path::PathBuf> =
        ["fmi2", "fmi3"].iter().map(|v| out.join(v).join("BeamImpact.fmu")).collect();
    for fmu in &earlier {
        std::fs::create_dir_all(fmu.parent().unwrap()).unwrap();
        std::fs::write(fmu, "an earlier FMU").unwrap();
    }
    let modified = |p: &Path| std::fs::metadata(p).unwrap().modified().unwrap();
    let before: Vec<_> = earlier.iter().map(|p| modified(p)).collect();
    let victim = dir.path().join("victim.txt");
    std::fs::write(&victim, "keep me").unwrap();
    std::os::unix::fs::symlink(&victim, out.join("GangwayOnVessel.ssp")).unwrap();
    let (code, stdout, stderr) = pack_ssp(&["--out", out.to_str().unwrap()]);
    assert_eq!(code, Some(2), "{stderr}");
    assert_eq!(stderr.trim_end().lines().count(), 1, "{stderr}");
    assert!(stderr.contains("GangwayOnVessel.ssp") && stderr.contains("symbolic link"), "{stderr}");
    assert!(stdout.is_empty(), "{stdout}");
    for (fmu, mtime) in earlier.iter().zip(before) {
        assert!(std::fs::read(fmu).unwrap() == b"an earlier FMU", "{} replaced", fmu.display());
        assert_eq!(modified(fmu), mtime, "{}", fmu.display());
    }
    assert_eq!(std::fs::read_to_string(&victim).unwrap(), "keep me");
    // The same for an FMU's folder that is a link: refused before the other FMU is written.
    std::fs::remove_file(out.join("GangwayOnVessel.ssp")).unwrap();
    std::fs::remove_dir_all(out.join("fmi3")).unwrap();
    std::os::unix::fs::symlink(dir.path(), out.join("fmi3")).unwrap();
    let (code, _, stderr) = pack_ssp(&["--out", out.to_str().unwrap()]);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("fmi3") && stderr.contains("symbolic link"), "{stderr}");
    assert!(std::fs::read(&earlier[0]).unwrap() == b"an earlier FMU", "the FMI 2 FMU replaced");
}

/// `pack --ssp --scenario examples/vessel-sea.toml` (issue 42): the [sea] goes to the vessel FMU. The
/// SSD binds the sea state and the deck points (Hs 2.5 m switches the FMU to the irregular sea), the
/// vessel FMU's resources/raos.csv is the scenario's RAO file byte for byte, and the BeamImpact
/// FMU's packed scenario has no [sea] (its supports move as the vessel says).
#[test]
fn pack_ssp_with_a_sea_scenario_binds_the_sea_and_packs_its_raos() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("fmu");
    let (code, _, stderr) = pack_ssp(&["--scenario", "examples/vessel-sea.toml", "--out", out.to_str().unwrap()]);
    assert_eq!(code, Some(0), "{stderr}");
    let entries = unzip(&std::fs::read(out.join("GangwayOnVessel.ssp")).unwrap());
    let ssd = String::from_utf8(entries[0].1.clone()).unwrap();
    for (name, value, unit) in [
        ("sea.significant_wave_height", "2.5", "m"),
        ("sea.peak_period", "8.0", "s"),
        ("sea.heading", "180.0", "deg"),
        ("sea.seed", "1.0", "1"),
        ("hinge.x", "-10.0", "m"),
        ("clamp.x", "15.0", "m"),
        ("sea.arrestor_direction", "180.0", "deg"),
    ] {
        let binding = format!(
            "<ssv:Parameter name=\"{name}\">\n                    <ssv:Real value=\"{value}\" unit=\"{unit}\"/>"
        );
        assert!(ssd.contains(&binding), "{binding}");
    }
    let vessel = unzip(&entries[2].1);
    assert_eq!(vessel[2].0, "resources/raos.csv");
    assert_eq!(vessel[2].1, std::fs::read("examples/vessel-sea-raos.csv").unwrap());
    let beam = unzip(&entries[1].1);
    let scenario = beam.iter().find(|e| e.0 == "resources/scenario.toml").expect("the packed scenario");
    let text = String::from_utf8(scenario.1.clone()).unwrap();
    assert!(!text.contains("[sea]") && text.contains("duration"), "{text}");
}

/// A [sea] with a support on a fixed platform cannot be bound (the SSD binds Real parameters; the
/// supports' on_vessel switches are Boolean): one line, nothing written.
#[test]
fn pack_ssp_with_a_sea_on_one_support_is_one_line_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let scenario = dir.path().join("one.toml");
    std::fs::copy("examples/vessel-sea-raos.csv", dir.path().join("vessel-sea-raos.csv")).unwrap();
    let text = std::fs::read_to_string("examples/vessel-sea.toml").unwrap();
    let one: String = text.lines().filter(|l| !l.starts_with("hinge_point")).map(|l| format!("{l}\n")).collect();
    std::fs::write(&scenario, one).unwrap();
    let out = dir.path().join("fmu");
    let (code, _, stderr) = pack_ssp(&["--scenario", scenario.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    assert_ne!(code, Some(0));
    assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
    assert!(stderr.contains("sea.hinge_point and sea.clamp_point must both be given"), "{stderr}");
    assert!(!out.exists());
}
