//! `beam-impact pack`: builds the library for glibc 2.17 (linked by cargo-zigbuild's zig) or
//! takes the host build, and packs the FMI 2.0 and FMI 3.0 FMUs.

use std::path::{Path, PathBuf};
use std::time::Instant;

use beam_impact::{Error, Result};

use super::common::{emit, io};

/// Packs `library`, or else the glibc 2.17 build that cargo-zigbuild makes when it is on PATH (and
/// `no_zigbuild` is not set), or else the host build next to this executable. The build runs here,
/// in the CLI, not in `fmi::pack`: that module is part of the shared library loaded into every
/// FMU host, which has no business spawning cargo; `fmi::pack` packs the file it is given.
pub fn pack(out: &Path, library: Option<PathBuf>, no_zigbuild: bool) -> Result<()> {
    /// The build's target: x86_64 Linux, linked against glibc 2.17 symbols (manylinux2014: loads
    /// on RHEL 7/8, Ubuntu 20.04, Debian 11 and later); as zig names it.
    const TARGET: &str = "x86_64-unknown-linux-gnu.2.17";
    const ZIG_TARGET: &str = "x86_64-linux-gnu.2.17";

    /// An executable named `name` in a directory of PATH.
    fn on_path(name: &str) -> Option<PathBuf> {
        use std::os::unix::fs::PermissionsExt;
        let paths = std::env::var_os("PATH")?;
        std::env::split_paths(&paths)
            .map(|dir| dir.join(name))
            .find(|p| p.metadata().is_ok_and(|m| m.is_file() && m.permissions().mode() & 0o111 != 0))
    }

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
                source.display()
            )));
        }
        let cargo = std::env::var_os("CARGO").map(PathBuf::from).or_else(|| on_path("cargo")).ok_or_else(|| {
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
        eprintln!("beam-impact: building the library for glibc 2.17 (linked by {})", zigbuild.display());
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
                linker.display()
            )));
        }
        let built = target_dir.join("release").join("libbeam_impact.so");
        let library = zig_dir.join("libbeam_impact.so");
        std::fs::copy(&built, &library).map_err(|source| io("cannot copy", &built, source))?;
        eprintln!(
            "beam-impact: built {} for glibc 2.17 in {:.1} s",
            library.display(),
            started.elapsed().as_secs_f64()
        );
        Ok(library)
    }

    /// Writes an executable script (mode 755).
    fn write_executable(path: &Path, text: &str) -> Result<()> {
        use std::os::unix::fs::PermissionsExt;
        std::fs::write(path, text)
            .and_then(|()| std::fs::set_permissions(path, std::fs::Permissions::from_mode(0o755)))
            .map_err(|source| io("cannot write", path, source))
    }

    let library = match library {
        Some(path) => path,
        None => {
            let zig = if no_zigbuild { None } else { on_path("cargo-zigbuild") };
            match zig {
                Some(zig) => zigbuild(&zig)?,
                None => {
                    if !no_zigbuild {
                        eprintln!(
                            "beam-impact: warning: cargo-zigbuild is not on PATH: packing the host build, which needs \
                             this machine's glibc or newer (pip install ziglang cargo-zigbuild for a glibc 2.17 build)"
                        );
                    }
                    host_library()?
                }
            }
        }
    };
    for path in beam_impact::fmi::pack::pack(&library, out)? {
        emit(&format!("wrote {}\n", path.display()))?;
    }
    Ok(())
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
            exe.display()
        ))
    })
}
