//! Reading the scenario a user names: a TOML file, or its text, with the support-motion file its
//! `[motion] file` names (inside the scenario's folder), and a motion file given by path. Shared
//! by the CLI (`run`, `sweep`, `pack`, ...) and the Python package's `beam_impact.run`, so both
//! accept and refuse the same files with the same messages. Files are opened through the bounded
//! readers of [`crate::record::output`]: never a FIFO waited on, never more than their limit read.
//! What does not stop the run (motion rows that disagree with the row before them) is handed back
//! as warning lines for the caller to show.

use std::path::{Path, PathBuf};

use crate::error::{Error, Result};
use crate::model::Scenario;
use crate::record::output::{check_size, open_input, open_regular_input, read_bounded, shown, MAX_SCENARIO_BYTES};

/// Reads and validates the scenario file `path` (missing fields take their defaults) with its
/// motion file; warnings are appended to `warnings`.
pub fn read_file(path: &Path, warnings: &mut Vec<String>) -> Result<Scenario> {
    let file = open_input(path, "cannot read scenario")?;
    let text = check_size(&file, MAX_SCENARIO_BYTES, "the scenario")
        .and_then(|()| read_bounded(file, MAX_SCENARIO_BYTES, "the scenario"))
        .map_err(|source| io("cannot read scenario", path, source))?;
    from_text(&text, &shown(path), path.parent().unwrap_or(Path::new("")), warnings)
}

/// Reads a scenario from its TOML `text` (`name` in messages); its motion file, if it names one,
/// is read from `folder` (or below it).
pub fn from_text(text: &str, name: &str, folder: &Path, warnings: &mut Vec<String>) -> Result<Scenario> {
    if text.len() as u64 > MAX_SCENARIO_BYTES {
        return Err(Error::Other(format!(
            "{name}: {} bytes of scenario, more than the limit of {MAX_SCENARIO_BYTES}",
            text.len()
        )));
    }
    let mut scenario = Scenario::from_toml(text, name)?;
    if !scenario.motion.file.is_empty() {
        let motion = motion_file_of_scenario(&scenario.motion.file, folder)?;
        load_motion(&mut scenario, &motion, warnings)?;
    }
    if let Some(file) = scenario.sea.as_ref().map(|s| s.raos.clone()) {
        let path = file_of_scenario("sea.raos", &file, folder, "")?;
        load_raos(&mut scenario, &path)?;
    }
    Ok(scenario)
}

/// Where a scenario file's `[motion] file` points: a relative path inside the scenario's folder
/// (its folder or below, no `..`), resolved against that folder. A stranger's scenario can reach
/// nothing else (`/proc/self/environ`, `../../etc/shadow`); the user's own motion file anywhere
/// is given with `--motion PATH`.
pub fn motion_file_of_scenario(file: &str, folder: &Path) -> Result<PathBuf> {
    file_of_scenario("motion.file", file, folder, "; give any other file with --motion PATH")
}

/// Where a file a scenario names (`field`: `motion.file`, `sea.raos`) points: a relative path
/// inside the scenario's folder (see [`motion_file_of_scenario`]); `hint` ends the refusal.
pub fn file_of_scenario(field: &'static str, file: &str, folder: &Path, hint: &str) -> Result<PathBuf> {
    use std::path::Component;
    let relative = Path::new(file);
    let inside = relative.components().all(|c| matches!(c, Component::Normal(_) | Component::CurDir));
    if !inside || file.contains('\0') || file.is_empty() {
        return Err(Error::invalid(
            field,
            format!("a path relative to the scenario file's folder, inside it (no absolute path, no `..`{hint})"),
            format!("'{}'", crate::model::motion_table::quote_cell(file)),
        ));
    }
    Ok(folder.join(relative))
}

/// Largest RAO file read, bytes (32 MiB: a VERES file of 180 headings x 1000 frequencies is
/// 25 MB), checked from the file's size before it is read.
pub const MAX_RAO_BYTES: u64 = 32 << 20;

/// Reads the vessel's RAO file `path` (`[sea] raos`: our CSV or VERES `.re1`) into the
/// scenario's sea with its SHA-256, and checks the sea against it (its frequencies and headings).
pub fn load_raos(scenario: &mut Scenario, path: &Path) -> Result<()> {
    let file = open_regular_input(path, "cannot read RAO file")?;
    let text = check_size(&file, MAX_RAO_BYTES, "the RAO file")
        .and_then(|()| read_bounded(file, MAX_RAO_BYTES, "the RAO file"))
        .map_err(|source| io("cannot read RAO file", path, source))?;
    attach_raos(scenario, path, &text)
}

/// [`load_raos`] with the RAO file's `text` already read from `path` (a cluster's worker gets the
/// text its caller read, issue 43): the table parsed into the scenario's sea with its SHA-256 and
/// the sea checked against it.
pub fn attach_raos(scenario: &mut Scenario, path: &Path, text: &str) -> Result<()> {
    use sha2::Digest;
    let table =
        crate::model::sea::RaoTable::parse(text).map_err(|e| Error::Other(format!("RAO file {}: {e}", shown(path))))?;
    let hash: String = sha2::Sha256::digest(text.as_bytes()).iter().map(|b| format!("{b:02x}")).collect();
    let Some(sea) = scenario.sea.as_mut() else { return Ok(()) };
    sea.raos = path.display().to_string();
    sea.rao_sha256 = hash;
    sea.check_against(&table)?;
    sea.rao_table = Some(std::sync::Arc::new(table));
    Ok(())
}

/// Largest motion file read, bytes (256 MiB: about 1.3 million rows of ten numbers, 22 minutes
/// at 1 ms), checked from the file's size before it is read.
pub const MAX_MOTION_BYTES: u64 = 256 << 20;

/// Reads the support-motion file `path` (`run --motion`, `[motion] file`) into the scenario: its
/// rows checked (one line of error naming the row), and the rows that disagree with the motion
/// before them appended to `warnings` (the run uses them as given).
pub fn load_motion(scenario: &mut Scenario, path: &Path, warnings: &mut Vec<String>) -> Result<()> {
    let file = open_regular_input(path, "cannot read motion file")?;
    let text = check_size(&file, MAX_MOTION_BYTES, "the motion file")
        .and_then(|()| read_bounded(file, MAX_MOTION_BYTES, "the motion file"))
        .map_err(|source| io("cannot read motion file", path, source))?;
    let table = crate::model::motion_table::MotionTable::parse(&text)
        .map_err(|e| Error::Other(format!("motion file {}: {e}", shown(path))))?;
    let mismatches = table.mismatches();
    if let Some(first) = mismatches.first() {
        warnings.push(format!(
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

fn io(action: &'static str, path: &Path, source: std::io::Error) -> Error {
    Error::Io { action, path: shown(path), source }
}
