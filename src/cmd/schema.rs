//! `sightline schema [--markdown]`

use crate::exit::Exit;
use crate::output::say;

/// Prints the JSON Schema (or the Markdown field reference) on stdout.
pub fn schema(markdown: bool) -> anyhow::Result<Exit> {
    if markdown {
        say(sightline_dsl::reference_markdown().trim_end());
    } else {
        say(serde_json::to_string_pretty(&sightline_dsl::schema())?);
    }
    Ok(Exit::Pass)
}
