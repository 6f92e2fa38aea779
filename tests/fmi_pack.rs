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

/// A stand-in Windows DLL: a PE32+ image (machine AMD64, IMAGE_FILE_DLL) with one section holding
/// an export directory of `names`; `marker` (after the section) tells copies apart. Offsets: PE
/// signature 0x80, COFF header 0x84 (sections at 0x86, characteristics at 0x96), optional header
/// 0x98 (240 bytes, the export directory's entry at 0x108), section table 0x188, the section's
/// data at file offset 0x200 = RVA 0x1000.
fn fake_dll_exporting(names: &[&str], marker: &str) -> Vec<u8> {
    let put16 = |b: &mut Vec<u8>, at: usize, v: u16| b[at..at + 2].copy_from_slice(&v.to_le_bytes());
    let put32 = |b: &mut Vec<u8>, at: usize, v: u32| b[at..at + 4].copy_from_slice(&v.to_le_bytes());
    let (rva, raw) = (0x1000u32, 0x200usize);
    // The section: the export directory (40 bytes), the name pointers, the names.
    let mut data = vec![0u8; 40 + 4 * names.len()];
    put32(&mut data, 24, names.len() as u32);
    put32(&mut data, 32, rva + 40);
    for (k, name) in names.iter().enumerate() {
        let at = rva + data.len() as u32;
        put32(&mut data, 40 + 4 * k, at);
        data.extend_from_slice(name.as_bytes());
        data.push(0);
    }
    let mut b = vec![0u8; raw];
    b[..2].copy_from_slice(b"MZ");
    put32(&mut b, 0x3c, 0x80);
    b[0x80..0x84].copy_from_slice(b"PE\0\0");
    put16(&mut b, 0x84, 0x8664);
    put16(&mut b, 0x86, 1);
    put16(&mut b, 0x94, 240);
    put16(&mut b, 0x96, 0x2022);
    put16(&mut b, 0x98, 0x20b);
    put32(&mut b, 0x98 + 108, 16);
    put32(&mut b, 0x108, rva);
    put32(&mut b, 0x10c, data.len() as u32);
    b[0x188..0x18e].copy_from_slice(b".edata");
    put32(&mut b, 0x188 + 8, data.len() as u32);
    put32(&mut b, 0x188 + 12, rva);
    put32(&mut b, 0x188 + 16, data.len() as u32);
    put32(&mut b, 0x188 + 20, raw as u32);
    b.extend_from_slice(&data);
    b.extend_from_slice(marker.as_bytes());
    b
}

/// A stand-in of the beam-impact DLL: every FMI function exported.
fn fake_dll(marker: &str) -> Vec<u8> {
    fake_dll_exporting(&beam_impact::fmi::pack::FMI_FUNCTIONS, marker)
}

/// [`fake_dll`] with `bytes` written at `at` (a header field made hostile).
fn patched_dll(at: usize, bytes: &[u8]) -> Vec<u8> {
    let mut b = fake_dll("");
    b[at..at + bytes.len()].copy_from_slice(bytes);
    b
}

/// A stand-in 64-bit Mach-O dylib slice of CPU type `cpu`, 4096 bytes.
fn fake_slice(cpu: u32, marker: &str) -> Vec<u8> {
    let mut b = vec![0u8; 4096];
    b[..4].copy_from_slice(&0xfeed_facfu32.to_le_bytes());
    b[4..8].copy_from_slice(&cpu.to_le_bytes());
    b[12..16].copy_from_slice(&6u32.to_le_bytes());
    let names = format!("\0_fmi2Instantiate\0_fmi3InstantiateCoSimulation\0{marker}");
    b[64..64 + names.len()].copy_from_slice(names.as_bytes());
    b
}

/// A stand-in universal (fat) Mach-O of `slices` (CPU type, bytes), each at a 4096-byte offset.
fn fake_fat(slices: &[(u32, Vec<u8>)]) -> Vec<u8> {
    let mut b = Vec::new();
    b.extend_from_slice(&0xcafe_babeu32.to_be_bytes());
    b.extend_from_slice(&(slices.len() as u32).to_be_bytes());
    for (k, (cpu, slice)) in slices.iter().enumerate() {
        for field in [*cpu, 3, 4096 * (k as u32 + 1), slice.len() as u32, 12] {
            b.extend_from_slice(&field.to_be_bytes());
        }
    }
    for (_, slice) in slices {
        b.resize(b.len().div_ceil(4096) * 4096, 0);
        b.extend_from_slice(slice);
    }
    b
}

const X86_64: u32 = 0x0100_0007;
const ARM64: u32 = 0x0100_000c;

/// Issue 18: one FMU per FMI version carries every platform's binary under the directory its
/// standard names. FMI 2: linux64, win64 and darwin64 (the universal2 file as it is); FMI 3:
/// x86_64-linux, x86_64-windows, and each macOS slice in its own x86_64-darwin / aarch64-darwin
/// (thin dylibs cut from the fat file). Stand-in DLL and Mach-O files (the real ones are built and
/// checked by scripts/cross-build.sh, run by scripts/cross-check.sh) exercise the layout.
#[test]
fn pack_platforms_puts_each_binary_where_its_standard_looks() {
    use beam_impact::fmi::pack::{pack_platforms, Platform};
    let dir = tempfile::tempdir().unwrap();
    let dll = dir.path().join("beam_impact.dll");
    std::fs::write(&dll, fake_dll("windows")).unwrap();
    let (x86, arm) = (fake_slice(X86_64, "x86"), fake_slice(ARM64, "arm"));
    let fat = fake_fat(&[(X86_64, x86.clone()), (ARM64, arm.clone())]);
    let dylib = dir.path().join("beam_impact.dylib");
    std::fs::write(&dylib, &fat).unwrap();
    let library = fmi_common::library();
    let binaries = [(Platform::Darwin, dylib), (Platform::Linux, library.clone()), (Platform::Windows, dll)];
    let written = pack_platforms(&binaries, &dir.path().join("fmu"), "beam-impact test").unwrap();

    let so = std::fs::read(&library).unwrap();
    let fmi2: [(&str, &[u8]); 3] = [
        ("binaries/linux64/BeamImpact.so", &so),
        ("binaries/win64/BeamImpact.dll", &fake_dll("windows")),
        ("binaries/darwin64/BeamImpact.dylib", &fat),
    ];
    for (name, bytes) in fmi2 {
        assert!(read(&written[0], name) == bytes, "fmi2 {name} differs");
    }
    let fmi3: [(&str, &[u8]); 4] = [
        ("binaries/x86_64-linux/BeamImpact.so", &so),
        ("binaries/x86_64-windows/BeamImpact.dll", &fake_dll("windows")),
        ("binaries/x86_64-darwin/BeamImpact.dylib", &x86),
        ("binaries/aarch64-darwin/BeamImpact.dylib", &arm),
    ];
    for (name, bytes) in fmi3 {
        assert!(read(&written[1], name) == bytes, "fmi3 {name} differs");
    }
    for (fmu, count) in [(&written[0], 3), (&written[1], 4)] {
        assert_eq!(entries(fmu).iter().filter(|n| n.starts_with("binaries/")).count(), count, "{:?}", entries(fmu));
    }
    // The documentation page lists them, and the tool string is the one given.
    let page = String::from_utf8(read(&written[1], "documentation/index.html")).unwrap();
    for dir in ["x86_64-linux", "x86_64-windows", "x86_64-darwin, aarch64-darwin"] {
        assert!(page.contains(&format!("<code>{dir}</code>")), "{dir} not listed");
    }
    let xml = String::from_utf8(read(&written[1], "modelDescription.xml")).unwrap();
    assert!(xml.contains("generationTool=\"beam-impact test\""));
}

/// Each binary is checked for the platform it is packed as: a Linux library is not a DLL, a
/// DLL not a dylib, a thin or one-architecture Mach-O not universal2; the reason in one line
/// naming the file and platform, and no FMU written.
#[test]
fn pack_refuses_a_binary_of_another_platform() {
    use beam_impact::fmi::pack::{pack_platforms, Platform};
    let dir = tempfile::tempdir().unwrap();
    let write = |name: &str, bytes: Vec<u8>| {
        let path = dir.path().join(name);
        std::fs::write(&path, bytes).unwrap();
        path
    };
    let cases = [
        (Platform::Windows, fmi_common::library(), "not a Windows DLL"),
        (Platform::Darwin, write("a.dll", fake_dll("")), "not a universal (fat) Mach-O"),
        (Platform::Darwin, write("thin.dylib", fake_slice(ARM64, "")), "not a universal (fat) Mach-O"),
        (Platform::Darwin, write("arm.dylib", fake_fat(&[(ARM64, fake_slice(ARM64, ""))])), "no x86_64-darwin slice"),
        (Platform::Darwin, write("lie.dylib", fake_fat(&[(X86_64, fake_slice(ARM64, ""))])), "not a 64-bit Mach-O"),
        (Platform::Linux, write("b.dll", fake_dll("")), "not an ELF file"),
        // Hostile headers: read with bounds, refused with a reason, never a panic.
        (
            Platform::Darwin,
            write("dup.dylib", fake_fat(&[(X86_64, fake_slice(X86_64, "")), (X86_64, fake_slice(X86_64, ""))])),
            "two x86_64-darwin slices",
        ),
        (Platform::Darwin, write("none.dylib", fake_fat(&[])), "with 0 architectures"),
        (
            Platform::Darwin,
            write("beyond.dylib", {
                let mut b = fake_fat(&[(X86_64, fake_slice(X86_64, "")), (ARM64, fake_slice(ARM64, ""))]);
                b[16..20].copy_from_slice(&0xffff_f000u32.to_be_bytes());
                b[20..24].copy_from_slice(&0xffff_ffffu32.to_be_bytes());
                b
            }),
            "lies beyond the file",
        ),
        (Platform::Windows, write("far.dll", patched_dll(0x3c, &0xffff_fff0u32.to_le_bytes())), "no PE signature"),
        (Platform::Windows, write("exe.dll", patched_dll(0x96, &0x0022u16.to_le_bytes())), "not a DLL"),
        (Platform::Windows, write("arm.dll", patched_dll(0x84, &0xaa64u16.to_le_bytes())), "not an x86-64 PE file"),
        // Issue 27: the export directory is read, every offset and count bounded by the file.
        (Platform::Windows, write("sections.dll", patched_dll(0x86, &0xffffu16.to_le_bytes())), "65535 sections"),
        (Platform::Windows, write("pe32.dll", patched_dll(0x98, &0x10bu16.to_le_bytes())), "not a PE32+ image"),
        (
            Platform::Windows,
            write("table.dll", patched_dll(0x94, &0xfff0u16.to_le_bytes())),
            "the PE section table (bytes 65672..65712) lies beyond the file",
        ),
        (Platform::Windows, write("noexports.dll", patched_dll(0x108, &0u32.to_le_bytes())), "no export directory"),
        (
            Platform::Windows,
            write("raw.dll", patched_dll(0x188 + 20, &0xffff_ff00u32.to_le_bytes())),
            "PE section 0's data",
        ),
        (
            Platform::Windows,
            write("names.dll", patched_dll(0x200 + 24, &0x00ff_ffffu32.to_le_bytes())),
            "export directory lists 16777215 names",
        ),
        (
            Platform::Windows,
            write("names-beyond.dll", patched_dll(0x200 + 24, &0x000f_ffffu32.to_le_bytes())),
            "export name table (1048575 names at RVA 0x1028) lies outside",
        ),
        (
            Platform::Windows,
            write("entry.dll", patched_dll(0x200 + 40, &0x7fff_0000u32.to_le_bytes())),
            "export name 0 (RVA 0x7fff0000) lies outside",
        ),
        (
            Platform::Windows,
            write("two.dll", fake_dll_exporting(&["fmi2Instantiate", "fmi3InstantiateCoSimulation"], "")),
            "exports 2 of the 109 FMI functions (2 names in all), not fmi2CancelStep",
        ),
    ];
    for (platform, path, why) in cases {
        let out = dir.path().join("fmu");
        let err = pack_platforms(&[(platform, path.clone())], &out, "t").unwrap_err().to_string();
        assert!(err.contains(why) && err.contains(&path.display().to_string()), "{platform:?}: {err}");
        assert!(err.contains(&format!("as the {} binary", platform.name())), "{err}");
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(!out.exists());
    }
}

/// `--platforms` takes `all` or a list of linux, windows, darwin; anything else, or a binary
/// given for a platform not asked for, is one line, exit 2.
#[test]
fn pack_refuses_unknown_platforms_in_one_line() {
    let dir = tempfile::tempdir().unwrap();
    for (args, says) in [
        (vec!["--platforms", "linux,beos"], "unknown platform `beos`"),
        (vec!["--platforms", ""], "unknown platform ``"),
        (vec!["--windows-library", "x.dll"], "--windows-library is given but --platforms `linux` has no windows"),
        (
            vec!["--platforms", "windows", "--library", "x.so"],
            "--library is given but --platforms `windows` has no linux",
        ),
    ] {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_beam-impact"))
            .args(["pack", "--no-zigbuild", "--out"])
            .arg(dir.path().join("fmu"))
            .args(&args)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(stderr.contains(says) && stderr.lines().count() == 1, "{args:?}: {stderr}");
    }
    assert!(!dir.path().join("fmu").exists());
}

/// Without the cross toolchain, `pack --platforms windows` (or darwin, or all) says in one line
/// what is missing, where it looked and how to install it, before building anything.
#[test]
fn pack_without_the_cross_toolchain_says_what_is_missing() {
    let dir = tempfile::tempdir().unwrap();
    let empty = dir.path().join("no-toolchain");
    for platforms in ["windows", "all", "darwin"] {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_beam-impact"))
            .args(["pack", "--no-zigbuild", "--platforms", platforms, "--out"])
            .arg(dir.path().join("fmu"))
            .env("BEAM_IMPACT_CROSS_DIR", &empty)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{stderr}");
        assert_eq!(stderr.lines().count(), 1, "{stderr}");
        assert!(!stderr.contains("  "), "a run of spaces: {stderr}");
        assert!(
            stderr.contains("no cross toolchain")
                && stderr.contains("scripts/cross-toolchain.sh")
                && stderr.contains(&empty.display().to_string()),
            "{stderr}"
        );
        assert!(!dir.path().join("fmu").exists());
    }
}

/// Issue 18: the packed descriptions name the crate version and the source's git commit in
/// `generationTool`; everything else is the committed description (which has no commit, so it
/// stays free of drift).
#[test]
fn packed_description_names_the_git_commit() {
    let dir = tempfile::tempdir().unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_beam-impact"))
        .args(["pack", "--no-zigbuild", "--out"])
        .arg(dir.path())
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let commit = std::process::Command::new("git")
        .args(["-C", env!("CARGO_MANIFEST_DIR"), "rev-parse", "--short=12", "HEAD"])
        .output()
        .ok()
        .filter(|o| o.status.success())
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string());
    for (fmu, committed) in [("fmi2", description::fmi2()), ("fmi3", description::fmi3())] {
        let xml =
            String::from_utf8(read(&dir.path().join(fmu).join("BeamImpact.fmu"), "modelDescription.xml")).unwrap();
        let plain = format!("generationTool=\"{}\"", description::generation_tool(None));
        match &commit {
            Some(commit) => {
                let start =
                    xml.find(&format!("generationTool=\"beam-impact {} (git {commit}", env!("CARGO_PKG_VERSION")));
                let start = start.unwrap_or_else(|| panic!("{fmu}: no commit {commit} in generationTool"));
                let end = start + xml[start..].find(")\"").unwrap() + 2;
                assert_eq!(format!("{}{plain}{}", &xml[..start], &xml[end..]), committed, "{fmu}");
            }
            // No git here (a source tarball): the committed description as it is.
            None => assert_eq!(xml, committed),
        }
    }
}

/// Issue 18: the FMU carries the reference results of the paper scenario (every output at every
/// millisecond from 0 to 3 s, computed by an instance of this build) and a documentation page
/// completed from them: no marker left, every variable listed, Table 1 beside the paper's values
/// and the figures it links to present. `tests/python/test_reference_results.py` runs the
/// packed FMUs in fmpy against the CSV.
#[test]
fn packed_fmu_carries_reference_results_and_its_documentation() {
    use beam_impact::fmi::documentation::{FIGURES, MARKERS};
    use beam_impact::fmi::reference::REFERENCE_CSV;
    use beam_impact::fmi::variables::{table, Causality};
    let dir = tempfile::tempdir().unwrap();
    let written = beam_impact::fmi::pack::pack(&fmi_common::library(), dir.path()).unwrap();
    let outputs: Vec<String> =
        table().into_iter().filter(|v| v.causality == Causality::Output).map(|v| v.name).collect();
    for fmu in &written {
        let csv = String::from_utf8(read(fmu, REFERENCE_CSV)).unwrap();
        let mut lines = csv.lines();
        let header: Vec<String> = lines.next().unwrap().split(',').map(|h| h.trim_matches('"').to_string()).collect();
        assert_eq!(header[0], "time");
        assert_eq!(header[1..], outputs[..]);
        let rows: Vec<Vec<f64>> = lines.map(|l| l.split(',').map(|x| x.parse().unwrap()).collect()).collect();
        assert_eq!(rows.len(), 3001, "0 to 3 s every millisecond");
        for (k, row) in rows.iter().enumerate() {
            assert_eq!(row.len(), header.len());
            assert_eq!(row[0], k as f64 * 1e-3, "row {k}");
        }
        // The defaults' run (the converged method) against Table 1 (FEM): the running peaks at 3 s
        // within 15 % (the converged method moves the shear stress by 13 %: docs/trust.md, "Answers
        // an engineer can sign").
        let last = rows.last().unwrap();
        let peak = |name: &str| last[header.iter().position(|h| h == name).unwrap()];
        for (name, paper) in [
            ("peak.lower.tip_deflection", 0.691),
            ("peak.lower.clamp_bending_stress", 492e6),
            ("peak.lower.clamp_shear_stress", 59e6),
            ("peak.upper.contact_bending_stress", 295e6),
        ] {
            assert!((peak(name) / paper - 1.0).abs() < 0.15, "{name} = {} against {paper}", peak(name));
        }

        let page = String::from_utf8(read(fmu, "documentation/index.html")).unwrap();
        for marker in MARKERS {
            assert!(!page.contains(marker), "{marker} left in the page");
        }
        for v in table() {
            assert!(page.contains(&format!("<code>{}</code>", v.name.replace('&', "&amp;"))), "{} not listed", v.name);
        }
        // Table 1: the paper's values beside this FMU's own peaks at 3 s (the CSV's last row).
        assert!(page.contains("492 MPa") && page.contains("0.691 m"), "Table 1's values");
        for (name, shown) in [
            ("peak.lower.tip_deflection", format!("{:.4} m", peak("peak.lower.tip_deflection"))),
            ("peak.lower.clamp_bending_stress", format!("{:.1} MPa", peak("peak.lower.clamp_bending_stress") * 1e-6)),
        ] {
            assert!(page.contains(&format!("<td>{shown}</td>")), "{name}: {shown} not on the page");
        }
        for (file, _) in FIGURES {
            assert!(page.contains(&format!("src=\"{file}\"")));
            let svg = String::from_utf8(read(fmu, &format!("documentation/{file}"))).unwrap();
            assert!(
                svg.starts_with("<svg")
                    && svg.contains(if file == "result.svg" {
                        "lower.tip_deflection"
                    } else {
                        "lower.clamp_bending_stress"
                    })
            );
        }
    }
}

/// The wine check's importer (`tests/wine/importer.c`, built for Windows and Linux) reads outputs
/// by value reference and instantiates with the token: both must be this build's, or the two
/// platforms would compare the same wrong variables under the right labels.
#[test]
fn wine_importer_names_this_builds_value_references_and_token() {
    let source =
        std::fs::read_to_string(std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/wine/importer.c"))
            .unwrap();
    assert!(source.contains(&format!("#define TOKEN \"{}\"", description::token())), "TOKEN in importer.c is stale");
    let table = beam_impact::fmi::variables::table();
    let mut checked = 0;
    for piece in source.split("{\"").skip(1) {
        let Some((name, rest)) = piece.split_once("\",") else { continue };
        let Some(vr) = rest.trim_start().split('}').next().and_then(|v| v.trim().parse::<u32>().ok()) else { continue };
        let v = table
            .iter()
            .find(|v| v.name == name)
            .unwrap_or_else(|| panic!("importer.c names `{name}`, not a variable"));
        assert_eq!(v.vr, vr, "importer.c reads `{name}` as value reference {vr}");
        checked += 1;
    }
    assert!(checked >= 8, "only {checked} (name, value reference) pairs found in importer.c");
}

/// The 438-byte fake DLL of issue 27 (a PE header with 65535 sections and no export directory,
/// only the two entry point names as text): accepted before, refused now with the reason, by
/// `pack_platforms` and by the CLI (one line, exit 2, no FMU).
#[test]
fn pack_refuses_the_438_byte_fake_dll() {
    let mut b = vec![0u8; 0x188];
    b[..2].copy_from_slice(b"MZ");
    b[0x3c..0x40].copy_from_slice(&0x80u32.to_le_bytes());
    b[0x80..0x84].copy_from_slice(b"PE\0\0");
    b[0x84..0x86].copy_from_slice(&0x8664u16.to_le_bytes());
    b[0x86..0x88].copy_from_slice(&0xffffu16.to_le_bytes());
    b[0x96..0x98].copy_from_slice(&0x2022u16.to_le_bytes());
    b.extend_from_slice(b"\0fmi2Instantiate\0fmi3InstantiateCoSimulation\0");
    b.resize(438, 0);
    let dir = tempfile::tempdir().unwrap();
    let dll = dir.path().join("fake.dll");
    std::fs::write(&dll, &b).unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_beam-impact"))
        .args(["pack", "--no-zigbuild", "--platforms", "linux,windows", "--out"])
        .arg(dir.path().join("fmu"))
        .arg("--windows-library")
        .arg(&dll)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("fake.dll cannot be packed as the windows binary: a PE header with 65535 sections"),
        "{stderr}"
    );
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(!dir.path().join("fmu").exists());
}

/// Issue 27 item 5: a binary given to `pack` is checked from its metadata before any of it is
/// read: a 3 GiB sparse file as `--windows-library`, `--darwin-library` or `--library` is refused
/// at once, naming its size and the limit (before, 1 GiB was read first). The proof is not a
/// clock: the CLI runs under a 512 MiB address-space limit (`ulimit -v`), within which reading
/// 1 GiB cannot be done (before: "cannot read the shared library to pack ...: out of memory").
#[test]
fn pack_refuses_a_huge_binary_from_its_size_before_reading_it() {
    use beam_impact::fmi::pack::{pack_platforms, Platform, MAX_BINARY};
    let dir = tempfile::tempdir().unwrap();
    let huge = dir.path().join("huge.bin");
    std::fs::File::create(&huge).unwrap().set_len(3 << 30).unwrap();
    let size = 3u64 << 30;
    for (option, platforms) in
        [("--windows-library", "windows"), ("--darwin-library", "darwin"), ("--library", "linux")]
    {
        let out = std::process::Command::new("sh")
            .arg("-c")
            .arg("ulimit -v 524288 && exec \"$@\"")
            .arg("sh")
            .arg(env!("CARGO_BIN_EXE_beam-impact"))
            .args(["pack", "--no-zigbuild", "--platforms", platforms, "--out"])
            .arg(dir.path().join("fmu"))
            .arg(option)
            .arg(&huge)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{option}: {stderr}");
        assert!(
            stderr.contains(&format!("huge.bin cannot be packed: {size} bytes, larger than {MAX_BINARY}")),
            "{stderr}"
        );
        assert_eq!(stderr.lines().count(), 1, "{stderr}");
    }
    for platform in Platform::ALL {
        let err = pack_platforms(&[(platform, huge.clone())], &dir.path().join("fmu"), "t").unwrap_err().to_string();
        assert!(err.contains(&format!("{size} bytes, larger than {MAX_BINARY}")), "{platform:?}: {err}");
    }
    assert!(!dir.path().join("fmu").exists());
}

/// The FMI functions `pack` requires of a DLL are the source's: every `extern "C" fn fmi2*` /
/// `fmi3*` in `src/fmi`, as `scripts/cross-build.sh` derives them.
#[test]
fn the_required_exports_are_the_sources_fmi_functions() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("src/fmi");
    let mut source = Vec::new();
    for entry in std::fs::read_dir(dir).unwrap() {
        let text = std::fs::read_to_string(entry.unwrap().path()).unwrap();
        for piece in text.split("extern \"C\" fn ").skip(1) {
            let name: String = piece.chars().take_while(|c| c.is_ascii_alphanumeric() || *c == '_').collect();
            // As cross-build.sh's `fmi[23][A-Za-z0-9_]+`: a name, not the text `fmi2` in a comment.
            if (name.starts_with("fmi2") || name.starts_with("fmi3")) && name.len() > 4 {
                source.push(name);
            }
        }
    }
    source.sort();
    source.dedup();
    let mut listed: Vec<String> = beam_impact::fmi::pack::FMI_FUNCTIONS.iter().map(|s| s.to_string()).collect();
    listed.sort();
    assert_eq!(listed, source);
}

/// Issue 30: `pack --scenario` packs the scenario file (sections included) as both FMUs'
/// `resources/scenario.toml`, which reads back to the file's scenario, with a description whose
/// start values and token are its; a scenario the FMU cannot take as it is (a `[motion]` file: an
/// FMU's supports move by its inputs) or one that does not validate is refused in one line, exit
/// 2, no FMU written.
#[test]
fn cli_pack_with_a_scenario_packs_it_as_the_fmus_starting_scenario() {
    let examples = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    let gangway = examples.join("three-section-gangway.toml");
    let scenario =
        beam_impact::Scenario::from_toml(&std::fs::read_to_string(&gangway).unwrap(), "three-section-gangway.toml")
            .unwrap();
    let bin = tempfile::tempdir().unwrap();
    let target = tempfile::tempdir().unwrap();
    let out = tempfile::tempdir().unwrap();
    let args = ["--no-zigbuild", "--scenario", gangway.to_str().unwrap(), "--out", out.path().to_str().unwrap()];
    let (ok, _, stderr) = cli_pack(&args, bin.path(), target.path());
    assert!(ok, "{stderr}");
    for (fmu, xml) in [
        ("fmi2/BeamImpact.fmu", description::fmi2_for(Some(&scenario), "")),
        ("fmi3/BeamImpact.fmu", description::fmi3_for(Some(&scenario), "")),
    ] {
        let fmu = out.path().join(fmu);
        let text = String::from_utf8(read(&fmu, "resources/scenario.toml")).unwrap();
        assert!(text.starts_with("# The starting scenario of this FMU (issue 30), packed by beam-impact "), "{text}");
        assert!(text.contains(" from three-section-gangway.toml.\n"), "{text}");
        assert_eq!(beam_impact::fmi::resource::scenario_from_bytes(text.as_bytes()).unwrap(), scenario);
        let packed = String::from_utf8(read(&fmu, "modelDescription.xml")).unwrap();
        let token = description::token_for(Some(&scenario));
        assert!(packed.contains(&token) && token != description::token(), "{fmu:?}");
        // The same description but for its generation tool (the CLI names its git commit).
        let tool = |x: &str| x.lines().filter(|l| !l.contains("generationTool=")).collect::<Vec<_>>().join("\n");
        assert_eq!(tool(&packed), tool(&xml), "{fmu:?}");
        let page = String::from_utf8(read(&fmu, "documentation/index.html")).unwrap();
        assert!(page.contains("packed from <code>three-section-gangway.toml</code>"), "the page names the scenario");
        assert!(page.contains("The bridge's sections from its hinge:") && page.contains("The arrestor: uniform."));
        assert!(page.contains("<h2>This FMU's reference run</h2>") && !page.contains("Table 1 (FEM)</th>"));
    }

    for (file, text, reason) in [
        ("vessel.toml", None, "cannot be packed: its [motion] is for the CLI"),
        (
            "bad.toml",
            Some(
                "[[lower.sections]]\nlength = -4.0\nsecond_moment = 0.002\nsection_modulus = 0.01\nshear_area = 0.01\n\
                 mass_per_length = 800.0\n",
            ),
            "lower.sections[1].length must be between",
        ),
    ] {
        let dir = tempfile::tempdir().unwrap();
        let path = match text {
            None => examples.join(file),
            Some(text) => {
                std::fs::write(dir.path().join(file), text).unwrap();
                dir.path().join(file)
            }
        };
        let refused = dir.path().join("fmu");
        let args = ["--no-zigbuild", "--scenario", path.to_str().unwrap(), "--out", refused.to_str().unwrap()];
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_beam-impact"))
            .arg("pack")
            .args(args)
            .env("PATH", bin.path())
            .env("CARGO_TARGET_DIR", target.path())
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{file}: {stderr}");
        assert!(stderr.contains(reason) && stderr.lines().count() == 1, "{file}: {stderr}");
        assert!(!refused.exists(), "{file}: an FMU folder was written");
    }
}
