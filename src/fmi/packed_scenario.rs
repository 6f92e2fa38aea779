//! The FMU's own starting scenario (`pack --scenario FILE.toml`, issue 30): what `pack` writes as
//! `resources/scenario.toml`, checked to read back as it was.

use super::{description, resource};
use crate::error::{Error, Result};
use crate::Scenario;

/// A scenario packed as the FMU's starting scenario (`pack --scenario FILE.toml`, issue 30): the
/// scenario, the name of the file it came from and the text of `resources/scenario.toml`.
#[derive(Clone, Debug)]
pub struct PackedScenario {
    /// The scenario, as the FMU reads it back.
    pub scenario: Scenario,
    /// The file it came from, as the documentation names it (its file name).
    pub source: String,
    /// `resources/scenario.toml`: a comment line naming the source, then the scenario with every
    /// field ([`Scenario::to_toml`]).
    pub text: String,
}

impl PackedScenario {
    /// The starting scenario of an FMU from `scenario` (read and validated from the file `source`):
    /// refused with one line where the FMU could not take it as it is (a support motion from a
    /// file: an FMU's motion is its inputs) or would not read it back to the same scenario.
    pub fn new(scenario: &Scenario, source: &str) -> Result<PackedScenario> {
        let refuse = |why: String| Error::Other(format!("--scenario {source} cannot be packed: {why}"));
        if !scenario.motion.is_unset() {
            return Err(refuse(
                "its [motion] is for the CLI; an FMU takes the supports' motion as its inputs (upper.hinge_heave, \
                 lower.clamp_heave, lower.clamp_rotation and their rates): leave [motion] out"
                    .into(),
            ));
        }
        if scenario.sea.is_some() {
            return Err(refuse(
                "its [sea] is for the CLI (the record becomes a motion table there); an FMU takes the supports' motion \
                 as its inputs (upper.hinge_heave, lower.clamp_heave, lower.clamp_rotation and their rates): leave [sea] \
                 out, or write the record with `beam-impact sea` and feed it to the inputs"
                    .into(),
            ));
        }
        // The file's name as a comment: no line break or control character may end the comment.
        let shown = crate::error::bounded_line(source);
        let text = format!(
            "# The starting scenario of this FMU (issue 30), packed by {} from {shown}.\n# Read at \
             instantiation; parameters set by the importer override its uniform fields.\n{}",
            description::generation_tool(None),
            scenario.to_toml()
        );
        let back = resource::scenario_from_bytes(text.as_bytes()).map_err(refuse)?;
        if back != *scenario {
            return Err(refuse("it does not read back to the same scenario from its TOML".into()));
        }
        Ok(PackedScenario { scenario: back, source: source.to_string(), text })
    }
}
