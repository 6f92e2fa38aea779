//! `pack --ssp`: builds the vessel-motion FMU's library from its C source (embedded in this
//! executable, [`beam_impact::ssp::vessel::SOURCE`]) for each platform the BeamImpact FMUs carry:
//! with zig (`cargo-zigbuild zig cc`, the compiler `pack` links with) for Linux (glibc 2.17),
//! Windows (x86-64, MinGW) and macOS (x86-64 and arm64, joined into a universal2 dylib), or with
//! the host's `cc` for Linux when zig is absent or `--no-zigbuild` is given. Compiling spawns
//! processes, so it lives here in the CLI, not in the library loaded into FMU hosts.

use std::path::{Path, PathBuf};

use beam_impact::fmi::pack::Platform;
use beam_impact::record::output::{create_output_dir, OutputFile};
use beam_impact::ssp::vessel;
use beam_impact::{Error, Result};

use super::common::io;

/// The compiler flags every build shares: C99, warnings on (the source compiles clean), only
/// the FMI functions exported (fmi2_abi.h marks them).
const FLAGS: [&str; 6] = ["-shared", "-O2", "-std=c99", "-Wall", "-Wextra", "-fvisibility=hidden"];

/// The compiler for a platform: zig's cc through cargo-zigbuild (its path), or the host's cc.
enum Compiler {
    Zig(PathBuf),
    Host(PathBuf),
}

/// Finds cargo-zigbuild: on PATH, else in the cross toolchain's venv (`toolchain`).
fn zig(toolchain: Option<&Path>) -> Option<PathBuf> {
    super::common::on_path("cargo-zigbuild")
        .or_else(|| toolchain.map(|t| t.join("venv").join("bin").join("cargo-zigbuild")).filter(|p| p.is_file()))
}

/// Builds the library for each platform in `dir` (created through the output guard); returns
/// (platform, library path) in the order given. `no_zigbuild` builds the Linux library with the
/// host's cc.
pub fn build_all(
    platforms: &[Platform],
    dir: &Path,
    toolchain: Option<&Path>,
    no_zigbuild: bool,
) -> Result<Vec<(Platform, PathBuf)>> {
    create_output_dir(dir, "cannot create directory")?;
    let source = dir.join("vessel_motion.c");
    write_text(&source, vessel::SOURCE)?;
    write_text(&dir.join("fmi2_abi.h"), vessel::ABI_HEADER)?;
    let mut built = Vec::new();
    for &platform in platforms {
        let zig = zig(toolchain);
        let compiler = match (platform, zig) {
            (Platform::Linux, Some(zig)) if !no_zigbuild => Compiler::Zig(zig),
            (Platform::Linux, _) => {
                Compiler::Host(super::common::on_path("cc").or_else(|| super::common::on_path("gcc")).ok_or_else(
                    || Error::Other("cannot build the vessel-motion library for linux: no cc or gcc on PATH".into()),
                )?)
            }
            (_, Some(zig)) => Compiler::Zig(zig),
            (_, None) => {
                return Err(Error::Other(format!(
                "cannot build the vessel-motion library for {}: no cargo-zigbuild on PATH or in the cross toolchain \
                     (pip install ziglang cargo-zigbuild)",
                platform.name()
            )))
            }
        };
        let out = dir.join(format!("{}-{}.{}", vessel::MODEL_IDENTIFIER, platform.name(), platform.extension()));
        match platform {
            Platform::Linux => {
                let target = matches!(compiler, Compiler::Zig(_)).then_some("x86_64-linux-gnu.2.17");
                compile(&compiler, target, &source, &out, &["-fPIC", "-lm"])?;
            }
            Platform::Windows => compile(&compiler, Some("x86_64-windows-gnu"), &source, &out, &[])?,
            Platform::Darwin => {
                let mut slices = Vec::new();
                // The BeamImpact dylib's minimum macOS versions (scripts/cross-build.sh), and an
                // install name that is not the scratch folder's.
                let install_name = format!("-Wl,-install_name,@rpath/{}.dylib", vessel::MODEL_IDENTIFIER);
                for (target, arch) in [("x86_64-macos.10.12", "x86_64"), ("aarch64-macos.11.0", "arm64")] {
                    let slice = dir.join(format!("{}-{arch}.dylib", vessel::MODEL_IDENTIFIER));
                    compile(&compiler, Some(target), &source, &slice, &[install_name.as_str()])?;
                    slices.push(std::fs::read(&slice).map_err(|source| io("cannot read", &slice, source))?);
                }
                let universal = vessel::universal_dylib(&slices).map_err(Error::Other)?;
                let mut file = OutputFile::create(&out, false, "cannot write")?;
                std::io::Write::write_all(&mut file, &universal).map_err(|source| io("cannot write", &out, source))?;
                file.commit()?;
            }
        }
        built.push((platform, out));
    }
    Ok(built)
}

/// Writes a text file through the output guard.
fn write_text(path: &Path, text: &str) -> Result<()> {
    let mut file = OutputFile::create(path, false, "cannot write")?;
    std::io::Write::write_all(&mut file, text.as_bytes()).map_err(|source| io("cannot write", path, source))?;
    file.commit()
}

/// Compiles `source` into the shared library `out` (for zig's `target`), the compiler's output
/// passed through; an error names the command.
fn compile(compiler: &Compiler, target: Option<&str>, source: &Path, out: &Path, extra: &[&str]) -> Result<()> {
    let mut command = match compiler {
        Compiler::Zig(zig) => {
            let mut c = std::process::Command::new(zig);
            c.args(["zig", "cc", "--"]);
            c
        }
        Compiler::Host(cc) => std::process::Command::new(cc),
    };
    if let Some(target) = target {
        command.args(["-target", target]);
    }
    command.args(FLAGS).arg(source).arg("-o").arg(out).args(extra);
    let shown = format!("{command:?}").replace('"', "");
    let status = command.status().map_err(|e| Error::Other(format!("cannot run `{shown}`: {e}")))?;
    if !status.success() {
        return Err(Error::Other(format!(
            "`{shown}` failed ({status}; its output is above): the vessel-motion library was not built"
        )));
    }
    Ok(())
}
