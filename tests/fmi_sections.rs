//! Issue 30 through the FMU: beams of sections packed as the FMU's starting scenario
//! (`beam-impact pack --scenario`, `resources/scenario.toml`), each beam's worst stress along it
//! as outputs, and the bridge's shear area and allowable shear stress as parameters.
//!
//! - Oracle: `answer::run` (the CLI's run) of the packed scenario. With constant inputs the FMU
//!   takes the very same internal steps as the library run (`tests/fmi_grid.rs`), so its running
//!   peaks and its envelope at the stop time are the CLI's to the bit (compared exactly).
//! - A resource scenario that cannot be the FMU's (damaged, oversized, not a regular file, a
//!   `[motion]` table, one that does not belong to the description's token) fails the
//!   instantiation (a null instance, FMI's error for it) with one logged line, never a crash; a
//!   parameter that contradicts the packed sections fails `ExitInitializationMode`, as every
//!   invalid parameter does.

use crate::fmi_common;

use std::io::Read;
use std::path::Path;

use beam_impact::fmi::description;
use beam_impact::fmi::pack::{pack_platforms_with, PackedScenario, Platform};
use beam_impact::fmi::resource::{MAX_SCENARIO_RESOURCE_BYTES, SCENARIO_RESOURCE};
use beam_impact::fmi::variables::{table, Causality, Source, Variability};
use beam_impact::record::NullRecorder;
use beam_impact::results::ENVELOPE_PEAK_NAMES;
use beam_impact::{answer, Scenario};
use fmi_common::importer::{load, Fmu2, Fmu3, Log, ERROR, OK};

/// The tapered arrestor of `examples/`: three sections, the paper's bridge.
fn tapered() -> Scenario {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/tapered-arrestor.toml");
    Scenario::from_toml(&std::fs::read_to_string(path).unwrap(), "tapered-arrestor.toml").unwrap()
}

/// A resource directory holding `text` as `scenario.toml`.
fn resources_with(text: &[u8]) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join(SCENARIO_RESOURCE), text).unwrap();
    dir
}

/// FMI 2's resource location of a directory: a `file:` URI.
fn uri(dir: &Path) -> String {
    format!("file://{}", dir.display())
}

/// FMI 3's resource path of a directory: the path with a trailing `/`.
fn path3(dir: &Path) -> String {
    format!("{}/", dir.display())
}

/// The token an FMU packed with `scenario` carries.
fn token_of(scenario: &Scenario) -> String {
    description::token_for(Some(scenario))
}

/// Unpacks the FMU at `fmu` into a new directory.
fn unzip(fmu: &Path) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let mut archive = zip::ZipArchive::new(std::fs::File::open(fmu).unwrap()).unwrap();
    for k in 0..archive.len() {
        let mut entry = archive.by_index(k).unwrap();
        let path = dir.path().join(entry.enclosed_name().unwrap());
        if entry.is_dir() {
            continue;
        }
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        let mut bytes = Vec::new();
        entry.read_to_end(&mut bytes).unwrap();
        std::fs::write(path, bytes).unwrap();
    }
    dir
}

/// The value of attribute `name` of the root element of a model description.
fn root_attribute(xml: &str, name: &str) -> String {
    let root = &xml[xml.find("<fmiModelDescription").unwrap()..];
    let at = root.find(&format!(" {name}=\"")).unwrap() + name.len() + 3;
    root[at..at + root[at..].find('"').unwrap()].to_string()
}

/// Every FMU output the test compares with the CLI, with the CLI's value: the paper's five
/// running peaks, each beam's worst stress along it, its position and its utilisation (0 where
/// the FMU says there is none).
fn expected_outputs(a: &answer::Answer) -> Vec<(String, f64)> {
    let mut expected: Vec<(String, f64)> = beam_impact::vocabulary::PEAK_QUANTITIES
        .iter()
        .zip(a.summary.peaks.as_array())
        .map(|(name, value)| (format!("peak.{name}"), value))
        .collect();
    let utilisation = a.design.utilisation.envelope();
    for (k, name) in ENVELOPE_PEAK_NAMES.iter().enumerate() {
        let peak = a.envelope_peaks[k];
        expected.push((format!("peak.{name}"), peak.map_or(0.0, |p| p.value)));
        expected.push((format!("peak_position.{name}"), peak.map_or(0.0, |p| p.position)));
        expected.push((format!("utilisation.{name}"), utilisation[k].unwrap_or(0.0)));
    }
    expected
}

/// The new outputs are continuous, calculated outputs with the units of their kind, declared in
/// both descriptions; the bridge's shear area and allowable shear stress are fixed, exact
/// parameters starting at 0 (none given); all of them follow every older variable.
#[test]
fn the_envelope_outputs_and_the_bridge_shear_parameters_are_in_both_descriptions() {
    let variables = table();
    let last_older = variables.iter().find(|v| v.name == "impact.closing_speed").unwrap().vr;
    let (fmi2, fmi3) = (description::fmi2(), description::fmi3());
    for name in ENVELOPE_PEAK_NAMES {
        for (prefix, declared) in [("peak", "Stress"), ("peak_position", "Length"), ("utilisation", "Ratio")] {
            let full = format!("{prefix}.{name}");
            let v = variables.iter().find(|v| v.name == full).unwrap_or_else(|| panic!("no {full}"));
            assert_eq!(
                (v.causality, v.variability, v.exact),
                (Causality::Output, Variability::Continuous, Some(false))
            );
            assert!(v.vr > last_older, "{full}: value reference {} among the older ones", v.vr);
            let attributes = format!(
                "name=\"{full}\" valueReference=\"{}\" description=\"{}\" causality=\"output\" \
                 variability=\"continuous\" initial=\"calculated\"",
                v.vr,
                v.description.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
            );
            assert!(fmi2.contains(&format!("<ScalarVariable {attributes}>\n      <Real declaredType=\"{declared}\"/>")));
            assert!(fmi3.contains(&format!("<Float64 {attributes} declaredType=\"{declared}\"/>")), "{full}");
            assert!(fmi2.contains(&format!("<Unknown index=\"{}\" dependencies=\"\"/>", v.vr + 1)), "{full}");
            assert!(fmi3.contains(&format!("<Output valueReference=\"{}\" dependencies=\"\"/>", v.vr)), "{full}");
        }
    }
    for (name, declared) in [("upper.shear_area", "Area"), ("upper.allowable_shear_stress", "Stress")] {
        let v = variables.iter().find(|v| v.name == name).unwrap();
        assert!(matches!(v.source, Source::Parameter(_)));
        assert_eq!((v.causality, v.variability, v.exact), (Causality::Parameter, Variability::Fixed, Some(true)));
        assert!(v.vr > last_older, "{name}");
        assert_eq!((v.min, v.start.as_deref()), (Some(0.0), Some("0.0")), "{name}");
        assert!(fmi3.contains(&format!("name=\"{name}\" valueReference=\"{}\"", v.vr)), "{name}");
        assert!(fmi3.contains(&format!("declaredType=\"{declared}\" min=\"0.0\"")), "{name}");
    }
    // The bridge's shear outputs say what 0 means.
    let shear = variables.iter().find(|v| v.name == "peak.upper.shear_stress").unwrap();
    assert!(shear.description.contains("0 when the bridge has no shear area"), "{}", shear.description);
}

/// The packed FMUs (`pack_platforms_with`, what `beam-impact pack --scenario` calls) of the
/// tapered arrestor, instantiated as an importer does from their unpacked archives: FMI 2 at
/// 10 ms and FMI 3 at 1 ms to the scenario's 3 s give the CLI's running peaks, each beam's worst
/// stress along it with its position and utilisation, and its design verdict, to the bit.
#[test]
fn an_fmu_packed_with_the_tapered_arrestor_gives_the_clis_peaks_and_envelope_peaks() {
    let scenario = tapered();
    let expected = answer::run(&scenario, &mut NullRecorder, Default::default()).unwrap();
    let peaks = expected.envelope_peaks;
    assert!(peaks[2].is_some_and(|p| p.value > 0.0) && peaks[3].is_some() && peaks[1].is_none(), "{peaks:?}");

    let out = tempfile::tempdir().unwrap();
    let packed = PackedScenario::new(&scenario, "tapered-arrestor.toml").unwrap();
    let written =
        pack_platforms_with(&[(Platform::Linux, fmi_common::library())], out.path(), "beam-impact test", Some(&packed))
            .unwrap();
    let (two, three) = (unzip(&written[0]), unzip(&written[1]));
    let resources = |dir: &tempfile::TempDir| dir.path().join("resources");
    assert_eq!(
        Scenario::from_toml(&std::fs::read_to_string(resources(&two).join(SCENARIO_RESOURCE)).unwrap(), "r").unwrap(),
        scenario
    );
    let token = |dir: &tempfile::TempDir, name: &str| {
        root_attribute(&std::fs::read_to_string(dir.path().join("modelDescription.xml")).unwrap(), name)
    };
    let (guid, instantiation_token) = (token(&two, "guid"), token(&three, "instantiationToken"));
    assert_eq!(guid, token_of(&scenario));
    assert_eq!(instantiation_token, guid);
    assert_ne!(guid, description::token(), "the packed FMU's token is its own");
    // Its start values are the scenario's (an importer that sets every start value sets these).
    let xml = std::fs::read_to_string(two.path().join("modelDescription.xml")).unwrap();
    assert!(xml.contains("<Real declaredType=\"Mass\" min=\"0.001\" max=\"1000000000.0\" start=\"10094.8\"/>"));

    let lib = load();
    let fmu2 = Fmu2::try_new_in(&lib, Some(&guid), true, "packed", &uri(&resources(&two))).0.expect("instantiated");
    assert!(
        fmu2.log.text().contains(
            "starts from its packed scenario resources/scenario.toml (bridge: uniform, arrestor: 3 sections)"
        ),
        "{}",
        fmu2.log.text()
    );
    assert_eq!(fmu2.set_string("log.path", ""), OK);
    assert_eq!(fmu2.initialize(), OK, "{}", fmu2.log.text());
    fmu2.run(0.0, 3.0, 0.01);
    let fmu3 = Fmu3::try_new_in(&lib, Some(&instantiation_token), false, &path3(&resources(&three))).0.unwrap();
    assert_eq!(fmu3.get("lower.length"), 12.0, "the packed scenario's, from Instantiated on");
    assert_eq!(fmu3.set_string("log.path", ""), OK);
    assert_eq!(fmu3.initialize_until(Some(3.0)), OK, "{}", fmu3.log.text());
    fmu3.run(0.0, 3.0, 1e-3);
    for (name, value) in expected_outputs(&expected) {
        assert_eq!(fmu2.get(&name), value, "FMI 2 {name}");
        assert_eq!(fmu3.get(&name), value, "FMI 3 {name}");
    }
    assert_eq!(fmu2.get_boolean("design.pass"), expected.design.pass);
    assert_eq!(fmu3.get_boolean("design.pass"), expected.design.pass);
    // Reset goes back to the packed scenario, not the paper's.
    assert_eq!(fmu3.set("lower.tip_mass", 1000.0), ERROR, "a parameter after initialization");
    assert_eq!(fmu3.call0("fmi3Reset"), OK);
    assert_eq!((fmu3.get("lower.length"), fmu3.get("drop_height")), (12.0, 0.8));
}

/// Every way a resource scenario cannot be the FMU's: the instantiation fails (a null instance)
/// with one error line in the logger naming `resources/scenario.toml` and the reason, through FMI
/// 2 and FMI 3; nothing crashes or hangs (a FIFO is refused, not waited on).
#[test]
fn a_corrupt_or_oversized_resource_scenario_fails_instantiation_with_the_loggers_message() {
    let good = PackedScenario::new(&tapered(), "tapered-arrestor.toml").unwrap().text;
    let broken_section = good.replacen("length = 4.0", "length = -1.0", 2);
    let mut oversized = good.clone().into_bytes();
    oversized.extend(std::iter::repeat_n(b'#', MAX_SCENARIO_RESOURCE_BYTES as usize));
    let cases: Vec<(&str, Vec<u8>, &str)> = vec![
        ("not TOML", b"[[lower.sections]\nlength = ".to_vec(), "resources/scenario.toml: "),
        (
            "a section out of range",
            broken_section.into_bytes(),
            "resources/scenario.toml: lower.sections[1].length must be between",
        ),
        ("oversized", oversized, "bytes, larger than 1048576 bytes (the limit"),
        ("not UTF-8", vec![b'#', 0xff, 0xfe, b'\n'], "not UTF-8 text"),
        (
            "a motion table",
            format!("{good}\n[motion]\nfile = \"vessel-motion.csv\"\n").into_bytes(),
            "[motion] is not for an FMU",
        ),
        (
            "a length that contradicts the sections",
            good.replace("length = 12.0", "length = 11.0").into_bytes(),
            "lower.length must be equal to what the beam's sections give, 12 m",
        ),
    ];
    let lib = load();
    let check = |what: &str, log: &Log, reason: &str| {
        let errors: Vec<_> = log.all().into_iter().filter(|m| m.status == ERROR).collect();
        assert_eq!(errors.len(), 1, "{what}: {}", log.text());
        let text = &errors[0].text;
        assert_eq!(errors[0].category, "logStatusError", "{what}");
        assert!(text.contains(reason), "{what}: {text}");
        assert!(!text.contains('\n') && text.len() < 1000, "{what}: {} characters", text.len());
    };
    for (what, bytes, reason) in &cases {
        let dir = resources_with(bytes);
        let (fmu, log) = Fmu2::try_new_in(&lib, Some(&token_of(&tapered())), true, "bad", &uri(dir.path()));
        assert!(fmu.is_none(), "FMI 2, {what}: instantiated");
        check(what, &log, reason);
        assert!(log.text().contains("fmi2Instantiate: "), "{what}: {}", log.text());
        let (fmu, log) = Fmu3::try_new_in(&lib, Some(&token_of(&tapered())), false, &path3(dir.path()));
        assert!(fmu.is_none(), "FMI 3, {what}: instantiated");
        check(what, &log, reason);
    }
    // Not a regular file: a folder, a FIFO.
    let folder = tempfile::tempdir().unwrap();
    std::fs::create_dir(folder.path().join(SCENARIO_RESOURCE)).unwrap();
    let fifo = tempfile::tempdir().unwrap();
    let made = std::process::Command::new("mkfifo").arg(fifo.path().join(SCENARIO_RESOURCE)).status().unwrap();
    assert!(made.success());
    for (what, dir, reason) in [("a folder", &folder, "it is a directory"), ("a FIFO", &fifo, "FIFO")] {
        let (fmu, log) = Fmu2::try_new_in(&lib, Some(&token_of(&tapered())), true, "bad", &uri(dir.path()));
        assert!(fmu.is_none(), "{what}: instantiated");
        check(what, &log, reason);
    }
    // A good scenario added to an FMU whose description is the paper's (by hand, not by pack).
    let dir = resources_with(good.as_bytes());
    let (fmu, log) = Fmu3::try_new_in(&lib, None, false, &path3(dir.path()));
    assert!(fmu.is_none());
    check("a scenario added by hand", &log, "a scenario.toml changed or added by hand?");
}

/// The importer's parameters override the packed scenario's uniform fields; one that contradicts
/// its sections (the arrestor's length, its first section's second moment) fails
/// `ExitInitializationMode` with the scenario's message, as any invalid parameter does.
#[test]
fn a_parameter_contradicting_the_packed_sections_is_refused_at_initialisation() {
    let scenario = tapered();
    let dir = resources_with(PackedScenario::new(&scenario, "t.toml").unwrap().text.as_bytes());
    let lib = load();
    let packed = || {
        let fmu = Fmu2::try_new_in(&lib, Some(&token_of(&scenario)), true, "packed", &uri(dir.path())).0.unwrap();
        assert_eq!(fmu.set_string("log.path", ""), OK);
        fmu
    };
    for (name, value, message) in [
        ("lower.length", 11.0, "lower.length must be equal to what the beam's sections give, 12 m"),
        ("lower.second_moment", 0.002075, "lower.second_moment must be equal to what the beam's sections give, 0.003"),
    ] {
        let fmu = packed();
        assert_eq!(fmu.set(name, value), OK, "checked at initialization");
        assert_eq!(fmu.setup(0.0, Some(0.5)), OK);
        assert_eq!(fmu.call0("fmi2EnterInitializationMode"), OK);
        assert_eq!(fmu.call0("fmi2ExitInitializationMode"), ERROR, "{name}");
        assert!(fmu.log.text().contains(message), "{name}: {}", fmu.log.text());
    }
    // A uniform field the sections leave free (the drop, the arrestor's modulus) overrides the
    // packed one: the run is the CLI's of the scenario with those values.
    let fmu = packed();
    assert_eq!(fmu.set("drop_height", 0.5), OK);
    assert_eq!(fmu.set("lower.elastic_modulus", 2.0e11), OK);
    assert_eq!(fmu.setup(0.0, Some(0.5)), OK);
    assert_eq!(fmu.call0("fmi2EnterInitializationMode"), OK);
    assert_eq!(fmu.call0("fmi2ExitInitializationMode"), OK, "{}", fmu.log.text());
    fmu.run(0.0, 0.5, 0.01);
    let mut changed = scenario.clone();
    (changed.drop_height, changed.lower.elastic_modulus, changed.duration) = (0.5, 2.0e11, 0.5);
    let expected = answer::run(&changed, &mut NullRecorder, Default::default()).unwrap();
    for (name, value) in expected_outputs(&expected) {
        assert_eq!(fmu.get(&name), value, "{name}");
    }
}

/// The FMU without `resources/scenario.toml` is the paper FMU: a resource folder without it takes
/// the committed token and starts from the paper scenario.
#[test]
fn without_the_resource_the_fmu_starts_from_the_paper_scenario() {
    let empty = tempfile::tempdir().unwrap();
    let lib = load();
    let fmu = Fmu2::try_new_in(&lib, None, true, "plain", &uri(empty.path())).0.expect("the committed token");
    assert!(
        fmu.log.text().contains("no scenario.toml there: the FMU starts from the paper scenario"),
        "{}",
        fmu.log.text()
    );
    assert_eq!(fmu.call0("fmi2EnterInitializationMode"), OK);
    assert_eq!(fmu.get("lower.length"), Scenario::default().lower.length);
    // A resource location that is a file, not a folder: no resources either.
    let file = empty.path().join("not-a-folder");
    std::fs::write(&file, "x").unwrap();
    assert!(Fmu3::try_new_in(&lib, None, false, &path3(&file)).0.is_some());
    let (refused, log) = Fmu2::try_new_in(&lib, Some(&token_of(&tapered())), true, "plain", &uri(empty.path()));
    assert!(refused.is_none());
    assert!(log.text().contains("whose resources/scenario.toml is missing?"), "{}", log.text());
}

/// A state saved by a packed FMU carries its sections: restored into a fresh instance of the
/// packed FMU, and into one of the paper FMU (the state's scenario wins, sections included), the
/// run goes on bit for bit as the one that saved it.
#[test]
fn a_packed_fmus_state_carries_its_sections() {
    let scenario = tapered();
    let dir = resources_with(PackedScenario::new(&scenario, "t.toml").unwrap().text.as_bytes());
    let empty = tempfile::tempdir().unwrap();
    let lib = load();
    let packed = || Fmu2::try_new_in(&lib, Some(&token_of(&scenario)), true, "packed", &uri(dir.path())).0.unwrap();
    let first = packed();
    assert_eq!(first.set_string("log.path", ""), OK);
    assert_eq!(first.setup(0.0, Some(1.0)), OK);
    assert_eq!(first.call0("fmi2EnterInitializationMode"), OK);
    assert_eq!(first.call0("fmi2ExitInitializationMode"), OK);
    first.run(0.0, 0.3, 1e-3);
    let state = first.get_state();
    let bytes = first.serialize(state);
    first.free_state(state);
    first.run(0.3, 0.6, 1e-3);
    let names = ["peak.lower.bending_stress", "peak_position.lower.shear_stress", "lower.tip_deflection"];
    let expected: Vec<f64> = names.iter().map(|n| first.get(n)).collect();
    let paper = Fmu2::try_new_in(&lib, None, true, "paper", &uri(empty.path())).0.unwrap();
    for (what, second) in [("packed", packed()), ("paper", paper)] {
        assert_eq!(second.set_string("log.path", ""), OK);
        assert_eq!(second.setup(0.0, Some(1.0)), OK);
        let (status, restored) = second.deserialize(&bytes);
        assert_eq!(status, OK, "{what}: {}", second.log.text());
        assert_eq!(second.set_state(restored), OK, "{what}: {}", second.log.text());
        second.free_state(restored);
        assert_eq!(second.get("lower.length"), 12.0, "{what}");
        second.run(0.3, 0.6, 1e-3);
        let after: Vec<f64> = names.iter().map(|n| second.get(n)).collect();
        assert_eq!(after, expected, "{what}");
    }
}

/// Each beam's worst stress, its position and its utilisation have one name in the sweep's
/// columns and the FMU's outputs (`peak.upper.bending_stress`, ...), in the same unit; so do the
/// paper's peaks and utilisations (the vocabulary of `src/vocabulary.rs`).
#[test]
fn every_sweep_peak_and_utilisation_column_is_an_fmu_output_of_its_unit() {
    let variables = table();
    let former: Vec<String> =
        beam_impact::vocabulary::sweep_former_names().into_iter().map(|(former, _)| former).collect();
    let mut checked = 0;
    for (name, unit) in beam_impact::studies::sweep::column_units(&[]) {
        let named = ["peak.", "peak_position.", "utilisation."].iter().any(|p| name.starts_with(p));
        if !named || former.contains(&name) {
            continue;
        }
        let v = variables.iter().find(|v| v.name == name).unwrap_or_else(|| panic!("{name} is not an FMU variable"));
        assert_eq!((v.unit, v.causality), (Some(unit), Causality::Output), "{name}");
        checked += 1;
    }
    assert_eq!(checked, 5 + 3 * ENVELOPE_PEAK_NAMES.len() + 3);
}

/// Issue 44: a packed scenario's `[[load_cases]]` are not judged by the FMU (each needs a
/// converged answer of its own); the FMU says so to the logger at initialization, and its
/// `design.pass` stays the plain check's.
#[test]
fn a_packed_scenarios_load_cases_are_said_not_judged_by_the_fmu() {
    let lib = fmi_common::importer::load();
    let text = format!(
        "{}\n{}",
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/tapered-arrestor.toml")).unwrap(),
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/load-cases.toml")).unwrap()
    );
    let scenario = Scenario::from_toml(&text, "cases.toml").unwrap();
    let dir = resources_with(text.as_bytes());
    let (fmu, log) = Fmu2::try_new_in(&lib, Some(&token_of(&scenario)), true, "cases", &uri(dir.path()));
    let fmu = fmu.unwrap_or_else(|| panic!("{}", log.text()));
    assert_eq!(fmu.setup(0.0, Some(0.01)), OK);
    assert_eq!(fmu.set_string("log.path", ""), OK);
    assert_eq!(fmu.initialize(), OK, "{}", fmu.log.text());
    let text = fmu.log.text();
    assert!(text.contains("3 load case(s) are not judged by the FMU"), "{text}");
}
