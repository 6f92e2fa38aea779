//! `fmi::pack::pack` writes both FMUs with the layout importers expect: modelDescription.xml at
//! the root (the committed ones), the binary under the platform directory of its standard, and
//! the documentation. `BEAM_IMPACT_PACK_TO=DIR` also packs into DIR (for trying the FMUs out
//! before the CLI's `pack`).

mod fmi_common;

use std::io::Read;

use beam_impact::fmi::description;

fn entries(fmu: &std::path::Path) -> Vec<String> {
    let archive = zip::ZipArchive::new(std::fs::File::open(fmu).unwrap()).unwrap();
    let mut names: Vec<String> = archive.file_names().map(String::from).collect();
    names.sort();
    names
}

fn read(fmu: &std::path::Path, name: &str) -> Vec<u8> {
    let mut archive = zip::ZipArchive::new(std::fs::File::open(fmu).unwrap()).unwrap();
    let mut data = Vec::new();
    archive.by_name(name).unwrap().read_to_end(&mut data).unwrap();
    data
}

#[test]
fn pack_writes_both_fmus_with_the_standard_layout() {
    let library = fmi_common::library();
    let dir = tempfile::tempdir().unwrap();
    let written = beam_impact::fmi::pack::pack(&library, dir.path()).unwrap();
    assert_eq!(written, vec![dir.path().join("fmi2/BeamImpact.fmu"), dir.path().join("fmi3/BeamImpact.fmu")]);

    let fmi2 = entries(&written[0]);
    assert!(fmi2.contains(&"modelDescription.xml".to_string()), "{fmi2:?}");
    assert!(fmi2.contains(&"binaries/linux64/BeamImpact.so".to_string()), "{fmi2:?}");
    assert!(fmi2.contains(&"documentation/index.html".to_string()), "{fmi2:?}");
    let fmi3 = entries(&written[1]);
    assert!(fmi3.contains(&"binaries/x86_64-linux/BeamImpact.so".to_string()), "{fmi3:?}");
    assert!(fmi3.contains(&"documentation/index.html".to_string()), "{fmi3:?}");
    assert!(fmi2.iter().chain(&fmi3).all(|n| !n.contains('\\')));

    assert_eq!(read(&written[0], "modelDescription.xml"), description::fmi2().into_bytes());
    assert_eq!(read(&written[1], "modelDescription.xml"), description::fmi3().into_bytes());
    assert_eq!(read(&written[1], "binaries/x86_64-linux/BeamImpact.so"), std::fs::read(&library).unwrap());

    if let Some(out) = std::env::var_os("BEAM_IMPACT_PACK_TO") {
        beam_impact::fmi::pack::pack(&library, std::path::Path::new(&out)).unwrap();
    }
}

#[test]
fn a_missing_library_is_an_error_naming_it() {
    let dir = tempfile::tempdir().unwrap();
    let err = beam_impact::fmi::pack::pack(&dir.path().join("nope.so"), dir.path()).unwrap_err().to_string();
    assert!(err.contains("nope.so"), "{err}");
}
