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
    // `beam-impact sweeep` is a mistyped subcommand, not a scenario file named `sweeep`.
    let args: Vec<std::ffi::OsString> = std::env::args_os().collect();
    if let Some(e) = cli::usage::mistyped_subcommand(&args) {
        return usage_error(&e);
    }
    let cli = match Cli::try_parse_from(&args) {
        Ok(cli) => cli,
        // Help and version print as clap prints them, to standard output.
        Err(e) if !e.use_stderr() => e.exit(),
        Err(e) => return usage_error(&e),
    };
    match cli::execute(cli.command.unwrap_or(Command::Run(cli.run))) {
        Ok(Outcome::Done) => ExitCode::SUCCESS,
        Ok(Outcome::Untrusted) => ExitCode::from(UNTRUSTED),
        // As a shell reports a process stopped by SIGINT: 128 + 2.
        Ok(Outcome::Interrupted) => ExitCode::from(130),
        Err(e) => {
            cli::common::note(&format!("beam-impact: {}", bounded_line(&e.to_string())));
            ExitCode::from(2)
        }
    }
}

/// A usage error (an unknown option or subcommand, a missing or bad value): clap's lines as clap
/// writes them, its `tip:` and `Usage:` included, each over-long word cut (a 120 KB argument was
/// echoed three times), exit code 2. Errors of the input are one line each (above).
fn usage_error(e: &clap::Error) -> ExitCode {
    cli::common::note(&cli::usage::bounded_usage(&e.to_string()));
    ExitCode::from(2)
}
