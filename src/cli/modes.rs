//! `beam-impact modes`: Figures 10-12 (natural modes) of a scenario, with Table 2's frequencies.

use std::path::Path;

use beam_impact::Result;

use super::common::emit;

/// Figures 10-12 of a scenario, with the frequencies of Table 2.
pub fn modes(file: Option<&Path>, set: &[String], out: &Path) -> Result<()> {
    // As every subcommand reads it: the file's, else the paper's, else with --set the default.
    let scenario = super::common::scenario_with_settings(file, set)?;
    // The model and its modes only: no time step is involved ("auto" element counts resolved as a
    // run resolves them).
    if let Some(path) = file {
        beam_impact::record::output::check_not_in_figure_folder("the scenario file", path, out)?;
    }
    let model = beam_impact::model::Model::new(&beam_impact::discretise::printed(&scenario)?)?;
    let modal = beam_impact::solver::ModalSystem::new(&model)?;
    let mut text = String::from("natural frequencies, rad/s (the first 5 of each column of Table 2):\n");
    for (name, modes) in [("arrestor", &modal.lower), ("bridge", &modal.upper), ("coupled", &modal.coupled)] {
        let values: Vec<String> = modes.omega.iter().take(5).map(|w| format!("{w:.2}")).collect();
        text += &format!("  {name:9} {}\n", values.join(", "));
    }
    text += "figures:\n";
    for file in beam_impact::replay::mode_figures::write_mode_figures(&model, &modal, out)? {
        text += &format!("  {}\n", beam_impact::record::output::shown(&file));
    }
    emit(&text)
}
