//! The `sightline` command line. Only this binary touches the file system,
//! stdout, stderr and the exit code; the libraries return data.

use std::process::ExitCode;

use clap::Parser;

mod cli;
mod cmd;
mod evidence;
mod exit;
mod files;
mod input;
mod output;
mod summary;
mod template;

fn main() -> ExitCode {
    let cli = cli::Cli::parse();
    // A panic is a defect in sightline: the hook has printed it; exit 3, not 101.
    match std::panic::catch_unwind(|| cmd::dispatch(cli)) {
        Ok(Ok(exit)) => exit.into(),
        Ok(Err(error)) => {
            eprintln!("error: {error:#}");
            exit::Exit::Internal.into()
        }
        Err(_) => {
            eprintln!("error: internal error in sightline; please report it with the scenario file");
            exit::Exit::Internal.into()
        }
    }
}
