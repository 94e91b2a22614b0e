//! What sightline writes on a terminal: every line on stdout and stderr goes
//! through [`printable`], so that no name it echoes can drive the terminal.

use std::borrow::Cow;

/// `eprintln!` through [`printable`]: every line sightline writes on stderr.
macro_rules! stderr {
    ($($arg:tt)*) => {
        eprintln!("{}", $crate::terminal::printable(&format!($($arg)*)))
    };
}
pub(crate) use stderr;

/// `text` with each control character but a line break and a tab written as
/// its escape (`\u{1b}`): a file name on the command line cannot move the
/// cursor, recolour the terminal or forge a line of a CI log.
pub fn printable(text: &str) -> Cow<'_, str> {
    let hidden = |c: char| c.is_control() && c != '\n' && c != '\t';
    if !text.contains(hidden) {
        return Cow::Borrowed(text);
    }
    Cow::Owned(
        text.chars()
            .map(|c| {
                if hidden(c) {
                    c.escape_unicode().to_string()
                } else {
                    c.to_string()
                }
            })
            .collect(),
    )
}

#[cfg(test)]
mod tests {
    use super::printable;

    #[test]
    fn control_characters_are_escaped_but_line_breaks_and_tabs() {
        assert_eq!(printable("a\u{1b}[2Jb.yaml"), "a\\u{1b}[2Jb.yaml");
        assert_eq!(printable("x\ry\u{7}"), "x\\u{d}y\\u{7}");
        assert_eq!(printable("line\n\tnext: ok"), "line\n\tnext: ok");
    }
}
