//! `--template DIR`: an organisation's page templates, read from disk for
//! `sightline_reports::Templates`, which checks them before anything runs.

use std::io::ErrorKind;
use std::path::Path;
use std::sync::Arc;

use sightline_reports::{Page, Templates};

use crate::files::{TEXT_LIMIT, read_beneath};
use crate::terminal::stderr;

/// The templates of `page`: the bundled ones, or the set in `dir`. `None`
/// (after printing why) when the set cannot be used.
pub fn templates(dir: Option<&Path>, page: Page) -> Option<Templates> {
    let Some(dir) = dir else {
        return Some(Templates::bundled(page));
    };
    if !dir.is_dir() {
        let problem = if dir.exists() {
            "not a directory"
        } else {
            "no such directory"
        };
        stderr!("{}: error: failed to read the template set: {problem}", dir.display());
        return None;
    }
    let root = dir.to_path_buf();
    // A link could show any file the process can read (`/proc/self/environ`)
    // in the page: a set's templates are read where they are.
    let load = move |name: &str| match read_beneath(&root, name, TEXT_LIMIT) {
        Ok(bytes) => String::from_utf8(bytes)
            .map(Some)
            .map_err(|_| std::io::Error::new(ErrorKind::InvalidData, "the file is not UTF-8 text")),
        Err(error) if error.kind() == ErrorKind::NotFound => Ok(None),
        Err(error) => Err(error),
    };
    Templates::custom(page, &dir.display().to_string(), Arc::new(load))
        .inspect_err(|error| stderr!("{error}"))
        .ok()
}
