//! `impact`: the command line. Glue only: it parses flags into validated
//! settings, calls the engines and studies, and formats what they return.
//!
//! Exit status: 0 success; 2 invalid input (one line on stderr naming the flag
//! or field and the allowed range; nothing on stdout, no file written); 1 a
//! run that could not finish (the message says why and what to change).

mod args;
mod calibrate;
mod compare;
mod cost;
mod diagram;
mod explore;
mod flags;
mod jobs;
mod merge;
mod output;
mod reproduce;
mod run;
mod settings;
mod sweep;

use args::{Cli, Command};
use clap::Parser;
use std::process::ExitCode;

/// Bad input: reported on one line with exit status 2.
#[derive(Debug)]
pub struct InputError(pub String);

impl std::fmt::Display for InputError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for InputError {}

/// Shorthand for an input error.
pub fn input(msg: impl Into<String>) -> anyhow::Error {
    anyhow::Error::new(InputError(msg.into()))
}

/// clap's message up to its usage block, folded onto one line: what the
/// command line prints for a malformed command, and what the explorer's
/// API answers.
pub fn clap_message(e: &clap::Error) -> String {
    let text = e.render().to_string();
    let message: Vec<&str> = text
        .lines()
        .take_while(|l| !l.trim_start().starts_with("Usage:") && !l.starts_with("For more"))
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect();
    format!("{} (see --help)", message.join(" "))
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            use clap::error::ErrorKind;
            if matches!(
                e.kind(),
                ErrorKind::DisplayHelp
                    | ErrorKind::DisplayVersion
                    | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand
            ) {
                let _ = e.print();
                return ExitCode::SUCCESS;
            }
            eprintln!("{}", clap_message(&e));
            return ExitCode::from(2);
        }
    };
    let result = match cli.command {
        Command::Run(a) => run::run(a),
        Command::Sweep(a) => sweep::sweep(a),
        Command::Calibrate(a) => calibrate::calibrate(a),
        Command::Compare(a) => compare::compare(a),
        Command::Merge(a) => merge::merge(a),
        Command::Diagram(a) => diagram::diagram(a),
        Command::Reproduce(a) => reproduce::reproduce(a),
        Command::Cost(a) => cost::cost(a),
        Command::Explore(a) => explore::explore(a),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) if e.is::<InputError>() => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::from(1)
        }
    }
}
