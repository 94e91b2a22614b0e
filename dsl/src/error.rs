//! Scenario errors: where (file, line, column, YAML path) and what (an [`ErrorKind`]).

use std::fmt;

/// A 1-based line and column in a scenario file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, serde::Serialize)]
pub struct Location {
    /// Line, starting at 1.
    pub line: usize,
    /// Column in characters, starting at 1.
    pub column: usize,
}

impl Location {
    /// A location from 1-based line and column.
    pub const fn new(line: usize, column: usize) -> Self {
        Self { line, column }
    }

    pub(crate) fn from_marker(marker: saphyr_parser::Marker) -> Self {
        Self::new(marker.line().max(1), marker.col() + 1)
    }
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}", self.line, self.column)
    }
}

/// `bytes` as UTF-8 text, or the location of the first byte that is not UTF-8.
pub fn utf8_text(bytes: &[u8]) -> Result<&str, Location> {
    std::str::from_utf8(bytes).map_err(|e| {
        // The prefix up to the error is valid UTF-8.
        end_of(&String::from_utf8_lossy(&bytes[..e.valid_up_to()]))
    })
}

/// Where `text` ends: the line and column of the character after it.
pub(crate) fn end_of(text: &str) -> Location {
    let last_line = text.rsplit('\n').next().unwrap_or_default();
    Location::new(text.matches('\n').count() + 1, last_line.chars().count() + 1)
}

/// One problem in a scenario file.
///
/// Displays as `file:line:col: error: path: message`, the form editors and CI
/// annotators pick up.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{file}:{location}: error: {}{kind}", path_prefix(.path))]
pub struct Error {
    /// The file as the user named it.
    pub file: String,
    /// Where in the file.
    pub location: Location,
    /// The YAML path of the offending node (`field.masses.gamma`, `requirements[2].id`);
    /// empty for the document root.
    pub path: String,
    /// What is wrong.
    pub kind: ErrorKind,
}

fn path_prefix(path: &str) -> String {
    if path.is_empty() {
        String::new()
    } else {
        format!("{path}: ")
    }
}

/// What is wrong with a scenario. Messages are lowercase fragments.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ErrorKind {
    /// A file the scenario imports could not be read.
    #[error("failed to read {file}: {reason}")]
    Io {
        /// The file, as the scenario resolves it.
        file: String,
        /// Why, as the operating system says.
        reason: String,
    },
    /// A file the scenario imports is malformed; the error is located in that file.
    #[error("{0}")]
    Import(String),
    /// The text is not valid YAML, or uses YAML features the language excludes.
    #[error("{0}")]
    Syntax(String),
    /// A key appears twice in one mapping.
    #[error("duplicate key `{key}` (first given at {first})")]
    DuplicateKey {
        /// The repeated key.
        key: String,
        /// Where it was first given.
        first: Location,
    },
    /// A key the language does not define at this place.
    #[error("unknown key `{key}`; expected one of {expected}{}", suggestion(.did_you_mean))]
    UnknownKey {
        /// The key found.
        key: String,
        /// The keys allowed here, formatted.
        expected: String,
        /// The closest allowed key, when one is close.
        did_you_mean: Option<String>,
    },
    /// A name (a method, a metric, a kind) the language does not define.
    #[error("unknown value `{value}`; expected one of {expected}{}", suggestion(.did_you_mean))]
    UnknownValue {
        /// The name found.
        value: String,
        /// The names allowed here, formatted.
        expected: String,
        /// The closest allowed name, when one is close.
        did_you_mean: Option<String>,
    },
    /// A required key is absent.
    #[error("missing key `{0}`")]
    MissingKey(String),
    /// A value of the wrong type (a string where a number belongs).
    #[error("expected {expected}, found {found}")]
    InvalidType {
        /// What the language expects.
        expected: String,
        /// What the file holds.
        found: String,
    },
    /// A value of the right type outside its allowed range.
    #[error("expected {expected}, found {found}")]
    OutOfRange {
        /// The allowed range, in words.
        expected: String,
        /// The value found.
        found: String,
    },
    /// An id given twice where ids must be unique.
    #[error("duplicate id `{id}` (first given at {first})")]
    DuplicateId {
        /// The repeated id.
        id: String,
        /// Where it was first given.
        first: Location,
    },
    /// A reference to something that does not exist.
    #[error("{0}")]
    DanglingReference(String),
    /// A scenario that would need more memory or runs than sightline allows.
    #[error("{0}")]
    TooLarge(String),
    /// Keys that cannot be combined, or a combination the language rejects.
    #[error("{0}")]
    Invalid(String),
    /// A key that would change nothing that is simulated or measured in this
    /// scenario (its kind of world ignores it, or the settings around it do);
    /// the message says why.
    #[error("has no effect: {0}")]
    NoEffect(String),
}

fn suggestion(did_you_mean: &Option<String>) -> String {
    did_you_mean
        .as_ref()
        .map(|s| format!(" (did you mean `{s}`?)"))
        .unwrap_or_default()
}

/// All problems found in one file, in source order.
#[derive(Debug, Clone, PartialEq)]
pub struct Errors(pub Vec<Error>);

impl fmt::Display for Errors {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, error) in self.0.iter().enumerate() {
            if i > 0 {
                writeln!(f)?;
            }
            write!(f, "{error}")?;
        }
        Ok(())
    }
}

impl std::error::Error for Errors {}

/// Something a scenario's run leaves out or cannot vouch for, though it runs:
/// an element of an imported file that is dropped, a type read by its name, a
/// trace that does not cover the run. The CLI prints each on stderr, and the
/// evidence lists them.
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize)]
pub struct Warning {
    /// The file it is about, as named to the compiler or joined to the
    /// scenario's directory.
    pub file: String,
    /// Where in that file.
    pub location: Location,
    /// What, a lowercase fragment.
    pub message: String,
}

impl fmt::Display for Warning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}: warning: {}", self.file, self.location, self.message)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn displays_as_file_line_col() {
        let error = Error {
            file: "s.yaml".into(),
            location: Location::new(3, 7),
            path: "field.masses.gamma".into(),
            kind: ErrorKind::OutOfRange {
                expected: "a number ≥ 0".into(),
                found: "-3".into(),
            },
        };
        assert_eq!(
            error.to_string(),
            "s.yaml:3:7: error: field.masses.gamma: expected a number ≥ 0, found -3"
        );
    }

    #[test]
    fn invalid_utf8_is_located_at_its_first_bad_byte() {
        assert_eq!(utf8_text(b"a\nb"), Ok("a\nb"));
        assert_eq!(utf8_text(b"ab\nc\xc3\xa9d\xff"), Err(Location::new(2, 4)));
    }

    #[test]
    fn unknown_key_suggests_the_closest() {
        let kind = ErrorKind::UnknownKey {
            key: "gama".into(),
            expected: "`gamma`, `epsilon0`".into(),
            did_you_mean: Some("gamma".into()),
        };
        assert_eq!(
            kind.to_string(),
            "unknown key `gama`; expected one of `gamma`, `epsilon0` (did you mean `gamma`?)"
        );
    }
}
