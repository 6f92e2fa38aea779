//! `beam-impact`: run the paper scenario or a user scenario, print the comparison with the
//! paper, write FMUs, replay logs, benchmark. Thin: the options are parsed in `cli::args`, each
//! subcommand is a file of `cli/`, and everything they compute happens in the library.

mod cli;

use std::process::ExitCode;

use clap::Parser;

use cli::args::{Cli, Command};
use cli::common::bounded_line;
use cli::Outcome;

/// Exit code of a run that completed but whose numbers are not trusted (with `--strict`).
const UNTRUSTED: u8 = 3;

fn main() -> ExitCode {
    std::panic::set_hook(Box::new(|info| {
        cli::common::note(&format!("beam-impact: internal error: {info}"));
    }));
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        // Help and version print as clap prints them; a usage error is one bounded line like
        // every other error (it echoed a 120 KB argument three times over seven lines).
        Err(e) if !e.use_stderr() => e.exit(),
        Err(e) => {
            let text = e.to_string();
            cli::common::note(&format!("beam-impact: {}", bounded_line(text.trim().trim_start_matches("error: "))));
            return ExitCode::from(2);
        }
    };
    match cli::execute(cli.command.unwrap_or(Command::Run(cli.run))) {
        Ok(Outcome::Done) => ExitCode::SUCCESS,
        Ok(Outcome::Untrusted) => ExitCode::from(UNTRUSTED),
        Err(e) => {
            cli::common::note(&format!("beam-impact: {}", bounded_line(&e.to_string())));
            ExitCode::from(2)
        }
    }
}
