//! What every subcommand shares: reading a scenario (file, paper or default, with `--set`),
//! writing to standard output, I/O errors with the path, and one bounded line per error.

use std::io::Write;
use std::path::{Path, PathBuf};

use beam_impact::record::output::{
    check_size, open_input, open_regular_input, read_bounded, shown, MAX_SCENARIO_BYTES,
};
use beam_impact::{Error, Result, Scenario};

/// An error as one line of bounded length (shared with the FMU's logger messages).
pub use beam_impact::error::bounded_line;

/// Reads and validates a scenario file (missing fields take their defaults); `-` is the standard
/// input. A FIFO or socket is refused rather than waited on.
pub fn read_scenario(path: &Path) -> Result<Scenario> {
    let (text, folder, name) = if path.as_os_str() == "-" {
        let text = read_bounded(std::io::stdin().lock(), MAX_SCENARIO_BYTES, "the scenario")
            .map_err(|source| io("cannot read scenario", Path::new("standard input"), source))?;
        // A scenario from standard input names its motion file relative to the current folder.
        (text, Path::new(""), "standard input".to_string())
    } else {
        let file = open_input(path, "cannot read scenario")?;
        let text = check_size(&file, MAX_SCENARIO_BYTES, "the scenario")
            .and_then(|()| read_bounded(file, MAX_SCENARIO_BYTES, "the scenario"))
            .map_err(|source| io("cannot read scenario", path, source))?;
        (text, path.parent().unwrap_or(Path::new("")), shown(path))
    };
    let mut scenario = Scenario::from_toml(&text, &name)?;
    if !scenario.motion.file.is_empty() {
        let motion = motion_file_of_scenario(&scenario.motion.file, folder)?;
        load_motion(&mut scenario, &motion)?;
    }
    Ok(scenario)
}

/// Where a scenario file's `[motion] file` points: a relative path inside the scenario's folder
/// (its folder or below, no `..`), resolved against that folder. A stranger's scenario can reach
/// nothing else (`/proc/self/environ`, `../../etc/shadow`); the user's own motion file anywhere
/// is given with `--motion PATH`.
pub fn motion_file_of_scenario(file: &str, folder: &Path) -> Result<PathBuf> {
    use std::path::Component;
    let relative = Path::new(file);
    let inside = relative.components().all(|c| matches!(c, Component::Normal(_) | Component::CurDir));
    if !inside || file.contains('\0') {
        return Err(Error::invalid(
            "motion.file",
            "a path relative to the scenario file's folder, inside it (no absolute path, no `..`; give any other \
             file with --motion PATH)",
            format!("'{}'", beam_impact::model::motion_table::quote_cell(file)),
        ));
    }
    Ok(folder.join(relative))
}

/// Largest motion file read, bytes (256 MiB: about 1.3 million rows of ten numbers, 22 minutes
/// at 1 ms), checked from the file's size before it is read.
pub const MAX_MOTION_BYTES: u64 = 256 << 20;

/// Reads the support-motion file `path` (`run --motion`, `[motion] file`) into the scenario: its
/// rows checked (one line of error naming the row), and the rows that disagree with the motion
/// before them reported on standard error (the run uses them as given).
pub fn load_motion(scenario: &mut Scenario, path: &Path) -> Result<()> {
    let file = open_regular_input(path, "cannot read motion file")?;
    let text = check_size(&file, MAX_MOTION_BYTES, "the motion file")
        .and_then(|()| read_bounded(file, MAX_MOTION_BYTES, "the motion file"))
        .map_err(|source| io("cannot read motion file", path, source))?;
    let table = beam_impact::model::motion_table::MotionTable::parse(&text)
        .map_err(|e| Error::Other(format!("motion file {}: {e}", shown(path))))?;
    let mismatches = table.mismatches();
    if let Some(first) = mismatches.first() {
        warn(&format!(
            "motion file {}: {} row(s) disagree with the row before them (row {}: {}); they are used as given",
            shown(path),
            mismatches.len(),
            first.row,
            first.mismatch
        ));
    }
    scenario.motion.file = path.display().to_string();
    scenario.motion.table = Some(std::sync::Arc::new(table));
    Ok(())
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
