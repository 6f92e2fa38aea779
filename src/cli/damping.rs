//! `beam-impact damping`: the damping study of Appendix A, with its figures on request.

use std::path::Path;

use beam_impact::Result;

use super::common::{emit, scenario_with_settings};

pub fn damping(file: Option<&Path>, set: &[String], figures: Option<&Path>) -> Result<()> {
    use beam_impact::studies::damping::{run_with_histories, table, RATIOS};
    let scenario = scenario_with_settings(file, set)?;
    let Some(dir) = figures else {
        let rows = beam_impact::studies::damping::run(&scenario, &RATIOS)?;
        return emit(&table(&rows));
    };
    let runs = run_with_histories(&scenario, &RATIOS)?;
    let rows: Vec<_> = runs.iter().map(|r| (r.scenario.damping_ratio, r.summary.clone())).collect();
    let mut text = table(&rows);
    text += "\nfigures (of this FE model, not of the paper's simplified Figure A1 model):\n";
    for file in beam_impact::replay::damping_figures::write_damping_figures(&scenario, &runs, dir)? {
        text += &format!("  {}\n", beam_impact::record::output::shown(&file));
    }
    emit(&text)
}
