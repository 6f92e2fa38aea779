//! What every subcommand shares: reading a scenario (file, paper or default, with `--set`),
//! writing to standard output, I/O errors with the path, and one bounded line per error.

use std::io::Write;
use std::path::{Path, PathBuf};

use beam_impact::record::output::{read_bounded, shown, MAX_SCENARIO_BYTES};
use beam_impact::scenario_file;
use beam_impact::{Error, Result, Scenario};

/// An error as one line of bounded length (shared with the FMU's logger messages).
pub use beam_impact::error::bounded_line;

/// Reads and validates a scenario file (missing fields take their defaults); `-` is the standard
/// input. A FIFO or socket is refused rather than waited on. Warnings go to standard error.
pub fn read_scenario(path: &Path) -> Result<Scenario> {
    let mut warnings = Vec::new();
    let scenario = if path.as_os_str() == "-" {
        let text = read_bounded(std::io::stdin().lock(), MAX_SCENARIO_BYTES, "the scenario")
            .map_err(|source| io("cannot read scenario", Path::new("standard input"), source))?;
        // A scenario from standard input names its motion file relative to the current folder.
        scenario_file::from_text(&text, "standard input", Path::new(""), &mut warnings)
    } else {
        scenario_file::read_file(path, &mut warnings)
    };
    warnings.iter().for_each(|w| warn(w));
    scenario
}

/// Reads the support-motion file `path` (`run --motion`) into the scenario
/// ([`scenario_file::load_motion`]); its warnings go to standard error.
pub fn load_motion(scenario: &mut Scenario, path: &Path) -> Result<()> {
    let mut warnings = Vec::new();
    let loaded = scenario_file::load_motion(scenario, path, &mut warnings);
    warnings.iter().for_each(|w| warn(w));
    loaded
}

pub fn io(action: &'static str, path: &Path, source: std::io::Error) -> Error {
    Error::Io { action, path: shown(path), source }
}

/// Prints `beam-impact: warning: MESSAGE` (one bounded line) to standard error; a standard error
/// that cannot be written (`2>/dev/full`, a closed pipe) loses the warning, never the run.
pub fn warn(message: &str) {
    let line = format!("beam-impact: warning: {}\n", bounded_line(message));
    let _ = std::io::stderr().lock().write_all(line.as_bytes());
}

/// Prints `line` to standard error, ignoring a failure (see [`warn`]).
pub fn note(line: &str) {
    let _ = std::io::stderr().lock().write_all(format!("{line}\n").as_bytes());
}

/// Writes to standard output; a reader that went away (`| head`) ends the output quietly.
pub fn emit(text: &str) -> Result<()> {
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => {
            Err(io("cannot write", Path::new("standard output"), e))
        }
        _ => Ok(()),
    }
}

/// The scenario of a subcommand: the file's, else the paper's, else (with `--set` and no file)
/// the default, with the `--set` changes, as `run` reads it.
pub fn scenario_with_settings(file: Option<&Path>, set: &[String]) -> Result<Scenario> {
    let settings = beam_impact::studies::sweep::parse_settings(set)?;
    let mut scenario = match file {
        Some(path) => read_scenario(path)?,
        None if settings.is_empty() => Scenario::paper(),
        None => Scenario::default(),
    };
    beam_impact::studies::sweep::apply_settings(&mut scenario, &settings)?;
    Ok(scenario)
}

/// The units sidecars (`FILE.units.json`, [`beam_impact::vocabulary::units_path`]) of data files
/// written to regular files: one per distinct sidecar path, each naming the files it describes.
/// A data file going to a device or standard output has none.
pub fn units_sidecars(data_files: &[&Path]) -> Vec<(PathBuf, Vec<String>)> {
    let mut sidecars: Vec<(PathBuf, Vec<String>)> = Vec::new();
    for file in data_files {
        let is_special = file.as_os_str() == "-" || std::fs::metadata(file).is_ok_and(|m| !m.is_file());
        if is_special {
            continue;
        }
        let sidecar = beam_impact::vocabulary::units_path(file);
        let name = file.file_name().map_or_else(String::new, |n| n.to_string_lossy().into_owned());
        match sidecars.iter_mut().find(|(path, _)| *path == sidecar) {
            Some((_, describes)) => describes.push(name),
            None => sidecars.push((sidecar, vec![name])),
        }
    }
    sidecars
}

/// Writes the units sidecars of [`units_sidecars`] (each through the output guard, replaced only
/// when complete); returns their paths.
pub fn write_units_sidecars(
    sidecars: &[(PathBuf, Vec<String>)],
    columns: &[(String, &str)],
    former: &[(String, String)],
) -> Result<Vec<PathBuf>> {
    let mut written = Vec::new();
    for (path, describes) in sidecars {
        let mut file = beam_impact::record::output::OutputFile::create(path, false, "cannot create units sidecar")?;
        file.write_all(beam_impact::vocabulary::units_document(describes, columns, former).as_bytes())
            .map_err(|source| io("cannot write units sidecar", path, source))?;
        file.commit()?;
        written.push(path.clone());
    }
    Ok(written)
}

/// An executable named `name` in a directory of PATH.
pub fn on_path(name: &str) -> Option<PathBuf> {
    use std::os::unix::fs::PermissionsExt;
    let paths = std::env::var_os("PATH")?;
    std::env::split_paths(&paths)
        .map(|dir| dir.join(name))
        .find(|p| p.metadata().is_ok_and(|m| m.is_file() && m.permissions().mode() & 0o111 != 0))
}

/// A progress bar over `len` things (`what`: "scenarios", "events"), redrawn every second so the
/// elapsed time moves while the first ones run (indicatif draws only on a terminal; without one
/// the command's last line gives its wall time).
pub fn progress_bar(len: usize, what: &str) -> indicatif::ProgressBar {
    let bar = indicatif::ProgressBar::new(len as u64);
    bar.set_style(
        indicatif::ProgressStyle::with_template(&format!(
            "{{bar:40}} {{pos}}/{{len}} {what}, {{elapsed}} ({{eta}} left)"
        ))
        .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    bar.enable_steady_tick(std::time::Duration::from_secs(1));
    bar
}
