//! The error collector shared by the compile passes, and the declarations that
//! failed to compile.

use std::collections::HashSet;

use crate::de::DeError;
use crate::error::{Error, ErrorKind, Location};
use crate::path::{Path, Segment};
use crate::raw::range::{self, Range};
use crate::yaml::{Node, Value};

/// Collects located errors while a pass walks one spanned tree.
pub(super) struct Context<'a> {
    pub(super) file: &'a str,
    pub(super) tree: &'a Node,
    pub(super) errors: Vec<Error>,
    /// Whether the run writes an OSI trace (`Options::osi`), which the
    /// resource model then bounds.
    pub(super) osi: bool,
    /// Whether the scenario declares a `system_under_test` (a sweep point's
    /// tree leaves the section out), whose checks read `areas`.
    pub(super) driven: bool,
    /// Declarations whose own errors are recorded: known, but not compiled.
    failed: HashSet<(Declaration, String)>,
}

/// A kind of declaration that others name by id.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub(super) enum Declaration {
    /// An entry of `roads`, named by routes.
    Road,
    /// An entry of `sensor_models`, named by agents.
    SensorModel,
}

impl<'a> Context<'a> {
    pub(super) fn new(file: &'a str, tree: &'a Node) -> Self {
        Self {
            file,
            tree,
            errors: Vec::new(),
            osi: false,
            driven: false,
            failed: HashSet::new(),
        }
    }

    /// Notes that the declaration `id` failed to compile, after its errors are
    /// recorded: a reference to it is then not reported as missing, since the
    /// cause is the declaration, not the reference.
    pub(super) fn declaration_failed(&mut self, kind: Declaration, id: &str) {
        self.failed.insert((kind, id.to_string()));
    }

    /// Whether `id` is a declaration that failed to compile.
    pub(super) fn is_failed(&self, kind: Declaration, id: &str) -> bool {
        self.failed.contains(&(kind, id.to_string()))
    }

    /// Whether the file gives the node at `path`.
    pub(super) fn has(&self, path: &Path) -> bool {
        has(self.tree, path)
    }

    /// Records an error at the deepest node of `path` that exists in the tree.
    pub(super) fn error(&mut self, path: &Path, kind: ErrorKind) {
        self.error_at(locate(self.tree, path), path, kind);
    }

    /// Records an error at the key that ends `path` (an unknown or misspelt name),
    /// rather than at its value.
    pub(super) fn error_at_key(&mut self, path: &Path, kind: ErrorKind) {
        self.error_at(locate_key(self.tree, path), path, kind);
    }

    /// Records an error at an explicit location.
    pub(super) fn error_at(&mut self, location: Location, path: &Path, kind: ErrorKind) {
        self.errors.push(Error {
            file: self.file.to_string(),
            location,
            path: path.to_string(),
            kind,
        });
    }

    /// Records an out-of-range error unless `ok`; returns `ok`.
    pub(super) fn expect(&mut self, ok: bool, path: &Path, expected: &str, found: f64) -> bool {
        if !ok {
            self.error(
                path,
                ErrorKind::OutOfRange {
                    expected: expected.to_string(),
                    found: found.to_string(),
                },
            );
        }
        ok
    }

    /// Checks a number within its physical `range`. The error names the bound
    /// the value passes (`a number > 0`, `a number ≤ 150`), or the whole range
    /// for NaN.
    pub(super) fn within(&mut self, path: &Path, value: f64, range: Range) -> bool {
        if range.contains(value) {
            return true;
        }
        let expected = if value.is_nan() {
            range.words()
        } else if value >= range.max {
            range.upper()
        } else {
            range.lower()
        };
        // 1e308 as written, not as 309 digits.
        let found = if value != 0.0 && !(1.0e-4..1.0e15).contains(&value.abs()) {
            format!("{value:e}")
        } else {
            value.to_string()
        };
        self.error(path, ErrorKind::OutOfRange { expected, found });
        false
    }

    /// Checks each coordinate of each point of a list.
    pub(super) fn points_within(&mut self, path: &Path, points: &[[f64; 2]], range: Range) -> bool {
        let mut ok = true;
        for (i, point) in points.iter().enumerate() {
            for (axis, &v) in point.iter().enumerate() {
                ok &= self.within(&path.index(i).index(axis), v, range);
            }
        }
        ok
    }

    /// Checks a probability in [0, 1].
    pub(super) fn probability(&mut self, path: &Path, value: f64) -> bool {
        self.expect(range::PROBABILITY.contains(value), path, "a number from 0 to 1", value)
    }

    /// Checks a finite number.
    pub(super) fn finite(&mut self, path: &Path, value: f64) -> bool {
        self.expect(value.is_finite(), path, "a finite number", value)
    }

    /// Turns a deserialization error into a located [`Error`].
    pub(super) fn de_error(&self, error: DeError) -> Error {
        let error = error.into_inner();
        Error {
            file: self.file.to_string(),
            location: error.location.unwrap_or(self.tree.location),
            path: error.path.map(|p| p.to_string()).unwrap_or_default(),
            kind: error.kind,
        }
    }

    /// Returns the collected errors, or `value` when there are none.
    pub(super) fn finish<T>(mut self, value: Option<T>) -> Result<T, Vec<Error>> {
        match value {
            Some(value) if self.errors.is_empty() => Ok(value),
            _ => {
                if self.errors.is_empty() {
                    // Every pass records why it gives up; never fail silently if one does not.
                    self.error(
                        &Path::root(),
                        ErrorKind::Invalid("the scenario could not be compiled (a defect in sightline)".into()),
                    );
                }
                Err(self.errors)
            }
        }
    }
}

/// Whether `tree` has a node at `path`.
pub(super) fn has(tree: &Node, path: &Path) -> bool {
    deepest(tree, path.segments()).1
}

/// The location of the deepest node on `path` present in `tree`.
pub(super) fn locate(tree: &Node, path: &Path) -> Location {
    deepest(tree, path.segments()).0.location
}

/// The location of the key that ends `path`, or of the deepest node on it when
/// the key is not there.
pub(super) fn locate_key(tree: &Node, path: &Path) -> Location {
    if let Some((Segment::Key(last), parent)) = path.segments().split_last()
        && let (parent, true) = deepest(tree, parent)
        && let Value::Map(entries) = &parent.value
        && let Some((key, _)) = entries.iter().find(|(k, _)| &k.name == last)
    {
        return key.location;
    }
    locate(tree, path)
}

/// The deepest node on `segments`, and whether it is the node they name.
fn deepest<'a>(tree: &'a Node, segments: &[Segment]) -> (&'a Node, bool) {
    let mut node = tree;
    for segment in segments {
        let next = match (segment, &node.value) {
            (Segment::Key(key), Value::Map(_)) => node.get(key),
            (Segment::Index(i), Value::Seq(items)) => items.get(*i),
            _ => None,
        };
        match next {
            Some(next) => node = next,
            None => return (node, false),
        }
    }
    (node, true)
}
