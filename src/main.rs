//! The `sightline` command line. Only this binary touches the file system,
//! stdout, stderr and the exit code; the libraries return data.

use std::process::ExitCode;

use clap::Parser;

use crate::terminal::{printable, stderr};

mod cli;
mod cmd;
mod evidence;
mod exit;
mod files;
mod input;
mod output;
mod signals;
mod staging;
mod summary;
mod system;
mod template;
mod terminal;

fn main() -> ExitCode {
    let cli = cli::Cli::parse();
    if let Err(error) = signals::install() {
        stderr!("error: failed to handle interrupting signals: {error}");
        return exit::Exit::Internal.into();
    }
    // A panic is a defect in sightline: the hook has printed it; exit 3, not 101.
    let ended = std::panic::catch_unwind(|| cmd::dispatch(cli));
    // A signal being handled ends the process itself, with its own status,
    // once it has removed what this run staged: wait for it rather than
    // report what its clean-up did to this run.
    signals::with_pending(|_| ());
    match ended {
        Ok(Ok(exit)) => exit.into(),
        Ok(Err(error)) => {
            report(format_args!("error: {error:#}"));
            exit::Exit::Internal.into()
        }
        // A stream closed by its reader (`sightline check … | head -1`) makes
        // printing panic: the output could not be written (exit 3), which is
        // no defect, and stderr may be gone too.
        Err(payload)
            if payload
                .downcast_ref::<String>()
                .is_some_and(|m| m.starts_with("failed printing to std")) =>
        {
            exit::Exit::Internal.into()
        }
        Err(_) => {
            report(format_args!(
                "error: internal error in sightline; please report it with the scenario file"
            ));
            exit::Exit::Internal.into()
        }
    }
}

/// Writes a last line to stderr, if stderr is still there.
fn report(line: std::fmt::Arguments<'_>) {
    use std::io::Write;
    let _ = writeln!(std::io::stderr(), "{}", printable(&line.to_string()));
}
