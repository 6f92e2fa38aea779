//! `beam-impact pack`: builds the library for glibc 2.17 (linked by cargo-zigbuild's zig) or
//! takes the host build, and packs the FMI 2.0 and FMI 3.0 FMUs (with `--ssp` also
//! GangwayOnVessel.ssp).

use std::path::{Path, PathBuf};
use std::time::Instant;

use beam_impact::fmi::pack::Platform;
use beam_impact::{Error, Result};

use beam_impact::record::output::shown;

use super::common::{emit, io};

/// What `pack` is asked for (the command line's options).
pub struct Request {
    /// Output directory (DIR/fmi2/BeamImpact.fmu, DIR/fmi3/BeamImpact.fmu).
    pub out: PathBuf,
    /// The Linux library to pack as it is.
    pub library: Option<PathBuf>,
    /// Pack the host build rather than a glibc 2.17 build.
    pub no_zigbuild: bool,
    /// `all` or a list of platform names.
    pub platforms: String,
    /// The Windows DLL to pack as it is.
    pub windows_library: Option<PathBuf>,
    /// The macOS universal2 dylib to pack as it is.
    pub darwin_library: Option<PathBuf>,
    /// The scenario file to pack as the FMUs' starting scenario (issue 30).
    pub scenario: Option<PathBuf>,
    /// Also write DIR/GangwayOnVessel.ssp: the FMI 2 FMU and the vessel-motion FMU built for the
    /// same platforms (issue 31).
    pub ssp: bool,
}

/// Packs the FMUs for the platforms asked for. Linux: `library`, or else the glibc 2.17 build
/// that cargo-zigbuild makes when it is on PATH (and `no_zigbuild` is not set), or else the host
/// build next to this executable. Windows and macOS: the file given, or else the cross build of
/// `scripts/cross-build.sh` (the toolchain checked first: one line naming what is missing). The
/// builds run here, in the CLI, not in `fmi::pack`: that module is part of the shared library
/// loaded into every FMU host, which has no business spawning cargo; `fmi::pack` packs the files
/// it is given. The packed descriptions' `generationTool` names the git commit of the source tree
/// this executable was built from (also when the binaries are given as files). With a scenario
/// file, both FMUs start from it ([`beam_impact::fmi::pack::PackedScenario`], issue 30). With
/// `ssp`, also `GangwayOnVessel.ssp` ([`beam_impact::ssp`], issue 31): the vessel-motion library
/// is built for the same platforms (`vessel_build.rs`) before anything is written.
pub fn pack(request: &Request) -> Result<()> {
    let platforms = Platform::parse_list(&request.platforms)?;
    for (given, option, platform) in [
        (request.library.is_some(), "--library", Platform::Linux),
        (request.windows_library.is_some(), "--windows-library", Platform::Windows),
        (request.darwin_library.is_some(), "--darwin-library", Platform::Darwin),
    ] {
        if given && !platforms.contains(&platform) {
            return Err(Error::Other(format!(
                "{option} is given but --platforms `{}` has no {}",
                request.platforms,
                platform.name()
            )));
        }
    }
    // Every output goes through the output guard's checks before anything is built or written:
    // a link at DIR/GangwayOnVessel.ssp was refused only after both FMUs had been replaced.
    beam_impact::fmi::pack::check_outputs(&request.out)?;
    if request.ssp {
        beam_impact::ssp::archive::check_output(&request.out)?;
    }
    // The scenario is read, validated and checked for an FMU before anything is built.
    // With --ssp a scenario's [sea] goes to the vessel FMU (issue 42): its sea state and deck points
    // as the SSD's bindings of the vessel's parameters, its RAO table as the vessel FMU's resource;
    // the BeamImpact FMU starts from the rest of the scenario (its supports move as the vessel says).
    let mut sea_bindings = Vec::new();
    let mut raos = beam_impact::ssp::vessel::EXAMPLE_RAOS.to_string();
    let packed = match &request.scenario {
        Some(path) => {
            let mut scenario = super::common::read_scenario(path)?;
            let source = match path.file_name() {
                Some(name) if path.as_os_str() != "-" => name.to_string_lossy().into_owned(),
                _ => "standard input".to_string(),
            };
            if let (true, Some(sea)) = (request.ssp, scenario.sea.take()) {
                sea_bindings = beam_impact::ssp::vessel::sea_bindings(&sea)?;
                raos = beam_impact::ssp::vessel::rao_resource(&sea, &read_raos(Path::new(&sea.raos))?)?;
            }
            Some(beam_impact::fmi::pack::PackedScenario::new(&scenario, &source)?)
        }
        None => None,
    };
    // Every binary given is checked from its metadata (a regular file of at most 1 GiB) before
    // anything is built or read: a huge or sparse file is refused at once (issue 27).
    for path in [&request.library, &request.windows_library, &request.darwin_library].into_iter().flatten() {
        beam_impact::fmi::pack::check_binary_file(path)?;
    }
    // Every cross build's toolchain is checked before anything is built.
    let needs_cross = (platforms.contains(&Platform::Windows) && request.windows_library.is_none())
        || (platforms.contains(&Platform::Darwin) && request.darwin_library.is_none());
    let toolchain = if needs_cross { Some(cross_toolchain(&platforms)?) } else { None };
    let mut binaries = Vec::new();
    for platform in platforms {
        let path = match platform {
            Platform::Linux => linux_library(request.library.clone(), request.no_zigbuild)?,
            Platform::Windows => match &request.windows_library {
                Some(path) => path.clone(),
                None => cross_build(toolchain.as_ref(), "x86_64-pc-windows-gnu", platform)?,
            },
            Platform::Darwin => match &request.darwin_library {
                Some(path) => path.clone(),
                None => cross_build(toolchain.as_ref(), "universal2-apple-darwin", platform)?,
            },
        };
        binaries.push((platform, path));
    }
    let tool = beam_impact::fmi::description::generation_tool(git_commit().as_deref());
    // With --ssp the SSD is made first (a description it cannot be written for stops here), then
    // the vessel-motion libraries are built before anything is written (a failed build leaves no
    // FMU behind), in a scratch folder removed afterwards.
    let ssd = if request.ssp {
        let table = packed
            .as_ref()
            .map_or_else(beam_impact::fmi::variables::table, |p| beam_impact::fmi::variables::table_for(&p.scenario));
        Some(beam_impact::ssp::ssd::system_structure(&table, &tool, &sea_bindings)?)
    } else {
        None
    };
    let scratch = std::env::temp_dir().join(format!("beam-impact-vessel-{}", std::process::id()));
    let vessel = if request.ssp {
        let platforms: Vec<Platform> = binaries.iter().map(|(p, _)| *p).collect();
        let built = super::vessel_build::build_all(&platforms, &scratch, toolchain.as_deref(), request.no_zigbuild);
        if built.is_err() {
            let _ = std::fs::remove_dir_all(&scratch);
        }
        Some(built?)
    } else {
        None
    };
    let written = beam_impact::fmi::pack::pack_platforms_with(&binaries, &request.out, &tool, packed.as_ref())
        .and_then(|fmus| match (&ssd, &vessel) {
            (Some(ssd), Some(vessel)) => {
                let ssp = beam_impact::ssp::archive::write_ssp(&request.out, ssd, &fmus[0], vessel, &raos)?;
                Ok(fmus.into_iter().chain(std::iter::once(ssp)).collect())
            }
            _ => Ok(fmus),
        });
    if vessel.is_some() {
        let _ = std::fs::remove_dir_all(&scratch);
    }
    for path in written? {
        emit(&format!("wrote {}\n", shown(&path)))?;
    }
    Ok(())
}

/// The crate's source directory (the cross builds and the glibc 2.17 build run there).
fn source_dir() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The source's git commit (12 hex digits, `+dirty` when tracked files differ from it), or
/// `None` when there is no git or no repository.
fn git_commit() -> Option<String> {
    let git = |args: &[&str]| {
        std::process::Command::new("git")
            .arg("-C")
            .arg(source_dir())
            .args(args)
            .stderr(std::process::Stdio::null())
            .output()
            .ok()
            .filter(|o| o.status.success())
            .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
    };
    // Only the source's own repository (not one it happens to sit in, e.g. a home directory
    // under git holding ~/.cargo/registry).
    let top = git(&["rev-parse", "--show-toplevel"])?;
    if std::fs::canonicalize(&top).ok()? != std::fs::canonicalize(source_dir()).ok()? {
        return None;
    }
    let commit = git(&["rev-parse", "--short=12", "HEAD"]).filter(|c| !c.is_empty())?;
    let dirty = git(&["status", "--porcelain", "--untracked-files=no"]).is_some_and(|s| !s.is_empty());
    Some(if dirty { format!("{commit}+dirty") } else { commit })
}

/// The cross toolchain of scripts/cross-toolchain.sh: `$BEAM_IMPACT_CROSS_DIR`, else `.cross/` in
/// the source, else `~/.cache/beam-impact-cross/toolchain` (where scripts/cross-check.sh keeps
/// it); an error in one line naming what is missing and how to install it.
fn cross_toolchain(platforms: &[Platform]) -> Result<PathBuf> {
    let script = source_dir().join("scripts").join("cross-build.sh");
    let names: Vec<&str> = platforms.iter().filter(|p| **p != Platform::Linux).map(|p| p.name()).collect();
    let names = names.join(" and ");
    if !script.is_file() {
        return Err(Error::Other(format!(
            "cannot cross-build the {names} binary: the crate's source {} is gone (pass --windows-library / \
             --darwin-library)",
            shown(source_dir())
        )));
    }
    let cache = std::env::var_os("XDG_CACHE_HOME")
        .map(PathBuf::from)
        .or_else(|| std::env::var_os("HOME").map(|home| Path::new(&home).join(".cache")))
        .map(|cache| cache.join("beam-impact-cross").join("toolchain"));
    let candidates: Vec<PathBuf> = match std::env::var_os("BEAM_IMPACT_CROSS_DIR") {
        Some(dir) => vec![PathBuf::from(dir)],
        None => std::iter::once(source_dir().join(".cross")).chain(cache).collect(),
    };
    let complete = |dir: &Path| {
        dir.join("bin").join("rustc").is_file() && dir.join("venv").join("bin").join("cargo-zigbuild").is_file()
    };
    candidates.iter().find(|dir| complete(dir)).cloned().ok_or_else(|| {
        let looked: Vec<String> = candidates.iter().map(|d| shown(d)).collect();
        Error::Other(format!(
            "cannot cross-build the {names} binary: no cross toolchain (rustc wrapper and cargo-zigbuild) in {}: run \
             scripts/cross-toolchain.sh (downloads about 240 MB once), or pass --windows-library / --darwin-library",
            looked.join(" or ")
        ))
    })
}

/// Runs `scripts/cross-build.sh TRIPLE OUT` with `toolchain`; returns OUT
/// (`target/cross/BeamImpact-<platform>.<ext>` in the source).
fn cross_build(toolchain: Option<&PathBuf>, triple: &str, platform: Platform) -> Result<PathBuf> {
    let toolchain = toolchain.ok_or_else(|| Error::Other("no cross toolchain".into()))?;
    let script = source_dir().join("scripts").join("cross-build.sh");
    let dir = source_dir().join("target").join("cross");
    std::fs::create_dir_all(&dir).map_err(|source| io("cannot create", &dir, source))?;
    let out = dir.join(format!("BeamImpact-{}.{}", platform.name(), platform.extension()));
    super::common::note(&format!(
        "beam-impact: cross-building the {} binary ({triple}) with {}",
        platform.name(),
        shown(&script)
    ));
    let started = Instant::now();
    let status = std::process::Command::new("sh")
        .arg(&script)
        .arg(triple)
        .arg(&out)
        .env("BEAM_IMPACT_CROSS_DIR", toolchain)
        .status()
        .map_err(|source| io("cannot run", &script, source))?;
    if !status.success() {
        return Err(Error::Other(format!(
            "`scripts/cross-build.sh {triple}` failed ({status}; its output is above): the {} binary was not built",
            platform.name()
        )));
    }
    super::common::note(&format!("beam-impact: built {} in {:.0} s", shown(&out), started.elapsed().as_secs_f64()));
    Ok(out)
}

/// The Linux library: `library` as given, the glibc 2.17 build (cargo-zigbuild on PATH, not
/// `no_zigbuild`) or the host build.
fn linux_library(library: Option<PathBuf>, no_zigbuild: bool) -> Result<PathBuf> {
    /// The build's target: x86_64 Linux, linked against glibc 2.17 symbols (manylinux2014: loads
    /// on RHEL 7/8, Ubuntu 20.04, Debian 11 and later); as zig names it.
    const TARGET: &str = "x86_64-unknown-linux-gnu.2.17";
    const ZIG_TARGET: &str = "x86_64-linux-gnu.2.17";

    /// Builds the library for glibc 2.17 from the host build's compiled dependencies: cargo
    /// recompiles this crate alone as a cdylib, linked by `cargo-zigbuild zig cc` against
    /// glibc 2.17's symbols (a wrapper script written beside the build). Only the link differs
    /// from the host build (the Rust objects do not depend on glibc), so the dependencies are
    /// not built a second time for a `--target` of their own (`cargo zigbuild --target
    /// x86_64-unknown-linux-gnu.2.17` did that: 2.7 of the test command's 18 minutes).
    /// `tests/python/test_glibc.py` checks the symbols of the result. Returns a copy of the library
    /// in `<target>/zigbuild/`.
    fn zigbuild(zigbuild: &Path) -> Result<PathBuf> {
        let source = Path::new(env!("CARGO_MANIFEST_DIR"));
        let manifest = source.join("Cargo.toml");
        if !manifest.is_file() {
            return Err(Error::Other(format!(
                "cannot build the library for glibc 2.17: the crate's source {} is gone (pass --library FILE or \
                 --no-zigbuild)",
                shown(source)
            )));
        }
        let cargo = std::env::var_os("CARGO")
            .map(PathBuf::from)
            .or_else(|| super::common::on_path("cargo"))
            .ok_or_else(|| {
                Error::Other(
                    "cannot build the library for glibc 2.17: no cargo on PATH (pass --library FILE or --no-zigbuild)"
                        .into(),
                )
            })?;
        let target_dir = std::env::var_os("CARGO_TARGET_DIR").map_or_else(|| source.join("target"), PathBuf::from);
        let zig_dir = target_dir.join("zigbuild");
        std::fs::create_dir_all(&zig_dir).map_err(|source| io("cannot create", &zig_dir, source))?;
        let linker = zig_dir.join(format!("zigcc-{TARGET}.sh"));
        let script = format!(
            "#!/bin/sh\n# Written by `beam-impact pack`: links with zig against glibc 2.17's symbols.\nexec '{}' zig cc -- -g \
             -fno-sanitize=all -target {ZIG_TARGET} \"$@\"\n",
            zigbuild.display()
        );
        write_executable(&linker, &script)?;
        super::common::note(&format!(
            "beam-impact: building the library for glibc 2.17 (linked by {})",
            shown(zigbuild)
        ));
        let started = Instant::now();
        let status = std::process::Command::new(&cargo)
            .args(["rustc", "--release", "--lib", "--crate-type", "cdylib", "--manifest-path"])
            .arg(&manifest)
            .arg("--target-dir")
            .arg(&target_dir)
            .arg("--")
            .arg("-C")
            .arg(format!("linker={}", linker.display()))
            .status()
            .map_err(|source| io("cannot run", &cargo, source))?;
        if !status.success() {
            return Err(Error::Other(format!(
                "`cargo rustc --release --lib --crate-type cdylib -- -C linker={}` failed ({status}); --no-zigbuild \
                 packs the host build",
                shown(&linker)
            )));
        }
        let built = target_dir.join("release").join("libbeam_impact.so");
        let library = zig_dir.join("libbeam_impact.so");
        std::fs::copy(&built, &library).map_err(|source| io("cannot copy", &built, source))?;
        super::common::note(&format!(
            "beam-impact: built {} for glibc 2.17 in {:.1} s",
            shown(&library),
            started.elapsed().as_secs_f64()
        ));
        Ok(library)
    }

    /// Writes an executable script (mode 755).
    fn write_executable(path: &Path, text: &str) -> Result<()> {
        use std::os::unix::fs::PermissionsExt;
        std::fs::write(path, text)
            .and_then(|()| std::fs::set_permissions(path, std::fs::Permissions::from_mode(0o755)))
            .map_err(|source| io("cannot write", path, source))
    }

    Ok(match library {
        Some(path) => path,
        None => {
            let zig = if no_zigbuild { None } else { super::common::on_path("cargo-zigbuild") };
            match zig {
                Some(zig) => zigbuild(&zig)?,
                None => {
                    if !no_zigbuild {
                        super::common::warn(
                            "cargo-zigbuild is not on PATH: packing the host build, which needs this machine's glibc \
                             or newer (pip install ziglang cargo-zigbuild for a glibc 2.17 build)",
                        );
                    }
                    host_library()?
                }
            }
        }
    })
}

/// The host build of the library: beside the running executable (`cargo build`), or in its
/// `deps/` (`cargo test` builds it there only); an installed executable has none, so the error
/// says how to pack one.
pub fn host_library() -> Result<PathBuf> {
    let exe = std::env::current_exe().map_err(|source| Error::Io {
        action: "cannot locate",
        path: "the running executable".into(),
        source,
    })?;
    let beside = exe.with_file_name("libbeam_impact.so");
    let candidates = [beside.clone(), exe.with_file_name("deps").join("libbeam_impact.so")];
    candidates.into_iter().find(|p| p.is_file()).ok_or_else(|| {
        Error::Other(format!(
            "no libbeam_impact.so beside {} (an installed beam-impact carries no library): run `cargo run --release \
             -- pack` in the source tree, or pass --library PATH to a built libbeam_impact.so",
            shown(&exe)
        ))
    })
}

/// The text of a `[sea]`'s RAO file, read again for the vessel FMU's resource (bounded as
/// `scenario_file::load_raos` reads it).
fn read_raos(path: &Path) -> Result<String> {
    use beam_impact::record::output::{check_size, open_regular_input, read_bounded};
    let limit = beam_impact::scenario_file::MAX_RAO_BYTES;
    let file = open_regular_input(path, "cannot read RAO file")?;
    check_size(&file, limit, "the RAO file")
        .and_then(|()| read_bounded(file, limit, "the RAO file"))
        .map_err(|source| super::common::io("cannot read RAO file", path, source))
}
