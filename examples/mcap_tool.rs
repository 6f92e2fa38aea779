//! Drives the MCAP recorder, report and benchmark before the CLI is wired:
//! `mcap_tool run PATH`, `mcap_tool report PATH [DIR]`, `mcap_tool bench [RUNS]`,
//! `mcap_tool slow PATH` (a long run that flushes often, for the kill test).

use std::path::Path;

use beam_impact::record::bench;
use beam_impact::record::mcap::McapRecorder;
use beam_impact::replay::report;
use beam_impact::{Scenario, Simulation};

fn main() -> beam_impact::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match args.first().map(String::as_str) {
        Some("run") => {
            let path = Path::new(args.get(1).map_or("paper.mcap", String::as_str));
            let mut recorder = McapRecorder::create(path)?;
            let summary = Simulation::new(&Scenario::default())?.run(&mut recorder)?;
            println!("{} steps to {}", summary.steps, path.display());
        }
        Some("report") => {
            let path = Path::new(&args[1]);
            let dir = args.get(2).map_or_else(|| report::default_out_dir(path), Into::into);
            report::report(path, &dir, &mut std::io::stdout())?;
        }
        Some("bench") => {
            let runs = args.get(1).map_or(5, |s| s.parse().unwrap_or(5));
            print!("{}", bench::recording_benchmark(runs)?);
        }
        _ => eprintln!("usage: mcap_tool run PATH | report PATH [DIR] | bench [RUNS]"),
    }
    Ok(())
}
