//! The `beam-impact` command's side of the house: [`args`] declares the subcommands and options,
//! one file per subcommand turns them into calls of the library, [`common`] holds what they
//! share. Nothing here computes physics or encodes a log.

pub mod args;
mod bench;
mod campaign;
pub mod common;
mod completions;
mod damping;
mod fatigue;
mod modes;
mod pack;
mod report;
mod run;
mod sea;
mod sweep;
pub mod usage;
mod verify;
mod vessel_build;

use args::Command;
use beam_impact::{Result, Scenario};

/// What a subcommand ended with, for the exit code.
pub enum Outcome {
    /// Done (a run's numbers trusted, or no run).
    Done,
    /// A run completed but its numbers are not trusted, and `--strict` asked to say so.
    Untrusted,
    /// Stopped by Ctrl-C after writing what was done.
    Interrupted,
}

/// Runs one subcommand.
pub fn execute(command: Command) -> Result<Outcome> {
    let done = |r: Result<()>| r.map(|()| Outcome::Done);
    match command {
        Command::Run(args) => match run::run(&args)? {
            false if args.strict => Ok(Outcome::Untrusted),
            _ => Ok(Outcome::Done),
        },
        Command::Scenario => {
            // Every field annotated, then the `[fatigue]` section commented out with its defaults.
            let toml = Scenario::default().to_toml();
            let mut text = beam_impact::model::parameters::annotate_toml(&toml);
            if !toml.lines().any(|l| l.trim() == "[fatigue]") {
                text.push_str(&beam_impact::model::fatigue_fields::section_comment());
            }
            done(common::emit(&text))
        }
        Command::Damping { file, set, figures } => done(damping::damping(file.as_deref(), &set, figures.as_deref())),
        Command::Modes { file, set, out } => done(modes::modes(file.as_deref(), &set, &out)),
        Command::Pack { out, library, no_zigbuild, platforms, windows_library, darwin_library, scenario, ssp } => {
            done(pack::pack(&pack::Request {
                out,
                library,
                no_zigbuild,
                platforms,
                windows_library,
                darwin_library,
                scenario,
                ssp,
            }))
        }
        Command::Report { file, fatigue: true, curve, .. } => done(report::fatigue(&file, curve.as_deref())),
        Command::Report { file, out, csv, html, .. } => {
            done(report::report(&file, out, csv.as_deref(), html.as_deref()))
        }
        Command::Bench { runs } => done(bench::bench(runs)),
        Command::Verify { file, set, json, tolerance } => {
            done(verify::verify(file.as_deref(), &set, json.as_deref(), tolerance))
        }
        Command::Sweep(args) => done(sweep::sweep(&args)),
        Command::Campaign(args) => campaign::campaign(&args),
        Command::Sea { file, set, duration, out, sample_interval } => {
            done(sea::sea(&file, &set, duration, &out, sample_interval))
        }
        Command::Completions { shell } => done(completions::completions(shell)),
        Command::Fatigue(args) => done(fatigue::fatigue(&args)),
    }
}
