//! `beam-impact completions SHELL`: the shell's completion script, made by clap_complete from the
//! declarations of `args.rs`, to standard output.

use clap::CommandFactory;
use clap_complete::Shell;

use beam_impact::Result;

use super::args::Cli;
use super::common::emit;

/// Prints the completion script of `shell`.
pub fn completions(shell: Shell) -> Result<()> {
    let mut script = Vec::new();
    clap_complete::generate(shell, &mut Cli::command(), "beam-impact", &mut script);
    emit(&String::from_utf8_lossy(&script))
}
