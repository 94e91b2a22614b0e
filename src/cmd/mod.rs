//! One module per subcommand.

mod check;
mod export;
mod falsify;
mod merge;
mod replay;
mod run;
mod schema;
mod selftest;
mod shard;

use crate::cli::{Cli, Command};
use crate::exit::Exit;

/// Runs the parsed command. `Err` is an internal error (exit 3).
pub fn dispatch(cli: Cli) -> anyhow::Result<Exit> {
    match cli.command {
        Command::Run(args) => run::run(&args),
        Command::Falsify(args) => falsify::falsify(&args),
        Command::Merge(args) => merge::merge(&args),
        Command::Check { files, shards } => Ok(check::check(&files, shards.unwrap_or(1))),
        Command::Schema { markdown } => schema::schema(markdown),
        Command::Export(args) => export::export(&args),
        Command::Selftest => Ok(selftest::selftest()),
        Command::Replay { file } => Ok(replay::replay(&file)),
    }
}
