//! `sightline schema [--markdown]`

use crate::exit::Exit;

/// Prints the JSON Schema (or the Markdown field reference) on stdout.
pub fn schema(markdown: bool) -> anyhow::Result<Exit> {
    if markdown {
        print!("{}", sightline_dsl::reference_markdown());
    } else {
        println!("{}", serde_json::to_string_pretty(&sightline_dsl::schema())?);
    }
    Ok(Exit::Pass)
}
