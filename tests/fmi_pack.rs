//! `fmi::pack::pack` writes both FMUs with the layout importers expect: modelDescription.xml at
//! the root (the committed ones), the binary under the platform directory of its standard, and
//! the documentation. `BEAM_IMPACT_PACK_TO=DIR` also packs into DIR (for trying the FMUs out
//! before the CLI's `pack`). The CLI's `pack` packs a glibc 2.17 build when cargo-zigbuild is on
//! PATH (a stand-in here), the host build with `--no-zigbuild`, and the host build with one
//! warning line without cargo-zigbuild.

use crate::fmi_common;

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

/// The CLI's `pack` with the given PATH and CARGO_TARGET_DIR; returns (status, stdout, stderr).
fn cli_pack(args: &[&str], path: &std::path::Path, target_dir: &std::path::Path) -> (bool, String, String) {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_beam-impact"))
        .arg("pack")
        .args(args)
        .env("PATH", path)
        .env_remove("CARGO")
        .env("CARGO_TARGET_DIR", target_dir)
        .output()
        .unwrap();
    (out.status.success(), String::from_utf8_lossy(&out.stdout).into(), String::from_utf8_lossy(&out.stderr).into())
}

/// What the stand-in zigbuild produces: the host library with `marker` appended.
fn zigbuilt(marker: &str) -> Vec<u8> {
    let mut bytes = host_library();
    bytes.extend_from_slice(marker.as_bytes());
    bytes
}

/// The host build the CLI packs by default: libbeam_impact.so next to the executable.
fn host_library() -> Vec<u8> {
    let exe = std::path::Path::new(env!("CARGO_BIN_EXE_beam-impact"));
    // `cargo build` puts it beside the executable; `cargo test` alone only in deps/.
    let beside = exe.with_file_name("libbeam_impact.so");
    std::fs::read(&beside)
        .unwrap_or_else(|_| std::fs::read(exe.with_file_name("deps").join("libbeam_impact.so")).unwrap())
}

/// Issue 11: an installed `beam-impact` (no library beside it) says how to pack: one line naming
/// `--library`, exit 2.
#[test]
fn pack_without_a_library_beside_the_executable_says_how() {
    let dir = tempfile::tempdir().unwrap();
    let installed = dir.path().join("beam-impact");
    std::fs::copy(env!("CARGO_BIN_EXE_beam-impact"), &installed).unwrap();
    let out = std::process::Command::new(&installed)
        .args(["pack", "--no-zigbuild", "--out"])
        .arg(dir.path().join("fmu"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("--library") && stderr.lines().count() == 1, "{stderr}");
}

/// Stand-ins on PATH: a `cargo-zigbuild` (only looked for: the linker wrapper calls it), and a
/// `cargo` that records its arguments and writes the host library with `marker` appended (still
/// a valid FMU library, and told apart from the host build) where the real one puts its build
/// (`<--target-dir>/release/`), or fails.
fn fake_zigbuild(dir: &std::path::Path, marker: &str, fail: bool) {
    use std::os::unix::fs::PermissionsExt;
    let built = dir.join("built.so");
    std::fs::write(&built, zigbuilt(marker)).unwrap();
    let script = format!(
        "#!/bin/sh\nPATH=/usr/bin:/bin\nprintf '%s\\n' \"$@\" > '{log}'\n{fail}\nwhile [ $# -gt 0 ]; do [ \"$1\" = --target-dir ] && dir=\"$2\"; \
         shift; done\nmkdir -p \"$dir/release\"\ncp '{built}' \"$dir/release/libbeam_impact.so\"\n",
        log = dir.join("args").display(),
        built = built.display(),
        fail = if fail { "exit 1" } else { "" },
    );
    for (name, text) in [("cargo", script.as_str()), ("cargo-zigbuild", "#!/bin/sh\nexit 0\n")] {
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        std::fs::set_permissions(&path, std::fs::Permissions::from_mode(0o755)).unwrap();
    }
}

/// Issue 8 item 7 (issue 19: without rebuilding the dependencies): with cargo-zigbuild on PATH,
/// `pack` builds the library for glibc 2.17 itself (`cargo rustc --release --lib --crate-type
/// cdylib` on this crate, in its target directory, linked by a wrapper that runs `cargo-zigbuild
/// zig cc -target x86_64-linux-gnu.2.17`) and packs that build. A stand-in cargo checks the
/// invocation without the build; `tests/python/test_glibc.py` checks the real one's symbols.
#[test]
fn pack_builds_and_packs_the_glibc_2_17_library_when_cargo_zigbuild_is_on_path() {
    let bin = tempfile::tempdir().unwrap();
    let target = tempfile::tempdir().unwrap();
    let out = tempfile::tempdir().unwrap();
    fake_zigbuild(bin.path(), "built for glibc 2.17", false);
    let (ok, stdout, stderr) = cli_pack(&["--out", out.path().to_str().unwrap()], bin.path(), target.path());
    assert!(ok, "{stderr}");
    assert!(!stderr.contains("warning"), "{stderr}");
    assert!(stdout.contains("wrote"), "{stdout}");
    let args: Vec<String> =
        std::fs::read_to_string(bin.path().join("args")).unwrap().lines().map(String::from).collect();
    let manifest = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("Cargo.toml");
    let linker = target.path().join("zigbuild").join("zigcc-x86_64-unknown-linux-gnu.2.17.sh");
    let expected = [
        "rustc".to_string(),
        "--release".into(),
        "--lib".into(),
        "--crate-type".into(),
        "cdylib".into(),
        "--manifest-path".into(),
        manifest.to_str().unwrap().into(),
        "--target-dir".into(),
        target.path().to_str().unwrap().into(),
        "--".into(),
        "-C".into(),
        format!("linker={}", linker.display()),
    ];
    assert_eq!(args, expected);
    let wrapper = std::fs::read_to_string(&linker).unwrap();
    let zig = bin.path().join("cargo-zigbuild");
    assert!(wrapper.contains(&format!("exec '{}' zig cc -- ", zig.display())), "{wrapper}");
    assert!(wrapper.contains("-target x86_64-linux-gnu.2.17 \"$@\""), "{wrapper}");
    for (fmu, platform) in [("fmi2", "linux64"), ("fmi3", "x86_64-linux")] {
        let so = read(&out.path().join(fmu).join("BeamImpact.fmu"), &format!("binaries/{platform}/BeamImpact.so"));
        assert!(so == zigbuilt("built for glibc 2.17"), "{fmu} holds another library than the zigbuilt one");
    }

    // A failed build is an error (exit 2) naming it, not a silent host build.
    fake_zigbuild(bin.path(), "", true);
    let (ok, _, stderr) = cli_pack(&["--out", out.path().to_str().unwrap()], bin.path(), target.path());
    assert!(!ok);
    assert!(
        stderr.contains("cargo rustc") && stderr.contains("failed") && stderr.contains("--no-zigbuild"),
        "{stderr}"
    );
}

/// `--no-zigbuild` packs the host build even with cargo-zigbuild on PATH, and runs no build.
#[test]
fn no_zigbuild_packs_the_host_build() {
    let bin = tempfile::tempdir().unwrap();
    let target = tempfile::tempdir().unwrap();
    let out = tempfile::tempdir().unwrap();
    fake_zigbuild(bin.path(), "not this one", false);
    let (ok, _, stderr) =
        cli_pack(&["--no-zigbuild", "--out", out.path().to_str().unwrap()], bin.path(), target.path());
    assert!(ok, "{stderr}");
    assert_eq!(stderr, "", "no warning: the host build was asked for");
    assert!(!bin.path().join("args").exists(), "cargo-zigbuild ran");
    let so = read(&out.path().join("fmi3/BeamImpact.fmu"), "binaries/x86_64-linux/BeamImpact.so");
    assert!(so == host_library(), "the FMU holds another library than the host build");
}

/// Without cargo-zigbuild on PATH, `pack` packs the host build and says so in one warning line.
#[test]
fn without_cargo_zigbuild_pack_warns_once_and_packs_the_host_build() {
    let empty = tempfile::tempdir().unwrap();
    let out = tempfile::tempdir().unwrap();
    let (ok, _, stderr) = cli_pack(&["--out", out.path().to_str().unwrap()], empty.path(), empty.path());
    assert!(ok, "{stderr}");
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.starts_with("beam-impact: warning: cargo-zigbuild is not on PATH"), "{stderr}");
    let so = read(&out.path().join("fmi2/BeamImpact.fmu"), "binaries/linux64/BeamImpact.so");
    assert!(so == host_library(), "the FMU holds another library than the host build");
}

/// Issue 9: `pack --library` refuses a file that is not the FMU library (random bytes, an ELF
/// executable without the FMI entry points) with a one-line reason, exit 2, writing no FMU.
#[test]
fn pack_refuses_a_library_that_is_not_an_fmu_binary() {
    let dir = tempfile::tempdir().unwrap();
    let random = dir.path().join("random.bin");
    std::fs::write(&random, (0..4096u32).map(|i| (i.wrapping_mul(2654435761) >> 13) as u8).collect::<Vec<u8>>())
        .unwrap();
    for (library, why) in [(random.as_path(), "not an ELF file"), (std::path::Path::new("/bin/true"), "")] {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_beam-impact"))
            .args(["pack", "--no-zigbuild", "--out"])
            .arg(dir.path().join("fmu"))
            .arg("--library")
            .arg(library)
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "{}", String::from_utf8_lossy(&out.stdout));
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(stderr.contains("cannot be packed") && stderr.contains(why), "{stderr}");
        assert_eq!(stderr.lines().count(), 1, "{stderr}");
    }
    assert!(!dir.path().join("fmu").exists());
}
