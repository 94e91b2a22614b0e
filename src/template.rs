//! `--template DIR`: an organisation's page templates, read from disk for
//! `sightline_reports::Templates`, which checks them before anything runs.

use std::io::ErrorKind;
use std::path::Path;
use std::sync::Arc;

use sightline_reports::{Page, Templates};

use crate::files::{TEXT_LIMIT, read_regular};

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
        eprintln!("{}: error: failed to read the template set: {problem}", dir.display());
        return None;
    }
    let root = dir.to_path_buf();
    let load =
        move |name: &str| match through_link(&root, name).and_then(|()| read_regular(&root.join(name), TEXT_LIMIT)) {
            Ok(bytes) => String::from_utf8(bytes)
                .map(Some)
                .map_err(|_| std::io::Error::new(ErrorKind::InvalidData, "the file is not UTF-8 text")),
            Err(error) if error.kind() == ErrorKind::NotFound => Ok(None),
            Err(error) => Err(error),
        };
    Templates::custom(page, &dir.display().to_string(), Arc::new(load))
        .inspect_err(|error| eprintln!("{error}"))
        .ok()
}

/// Refuses template `name` of the set in `root` when it, or a folder on its
/// way, is a symbolic link: a link could show any file the process can read
/// (`/proc/self/environ`) in the page. `NotFound` when it is not there.
fn through_link(root: &Path, name: &str) -> std::io::Result<()> {
    let mut path = root.to_path_buf();
    for (end, segment) in name.split('/').scan(0, |end, segment| {
        *end += segment.len() + 1;
        Some((*end - 1, segment))
    }) {
        path.push(segment);
        if std::fs::symlink_metadata(&path)?.file_type().is_symlink() {
            return Err(std::io::Error::new(
                ErrorKind::InvalidInput,
                format!(
                    "`{}` is a symbolic link: a set's templates are read where they are, never through a link",
                    &name[..end]
                ),
            ));
        }
    }
    Ok(())
}
