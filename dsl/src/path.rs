//! YAML paths: `field.masses.gamma`, `requirements[2].check`.

use std::fmt;

/// One step into a YAML tree.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub(crate) enum Segment {
    Key(String),
    Index(usize),
}

/// A path from the document root to a node.
#[derive(Debug, Clone, Default, PartialEq, Eq, Hash)]
pub(crate) struct Path(Vec<Segment>);

impl Path {
    /// The document root.
    pub(crate) fn root() -> Self {
        Self::default()
    }

    /// This path extended by a mapping key.
    pub(crate) fn key(&self, key: &str) -> Self {
        let mut segments = self.0.clone();
        segments.push(Segment::Key(key.to_string()));
        Self(segments)
    }

    /// This path extended by a list index.
    pub(crate) fn index(&self, index: usize) -> Self {
        let mut segments = self.0.clone();
        segments.push(Segment::Index(index));
        Self(segments)
    }

    /// This path extended by `segment`.
    pub(crate) fn push(mut self, segment: Segment) -> Self {
        self.0.push(segment);
        self
    }

    pub(crate) fn segments(&self) -> &[Segment] {
        &self.0
    }

    /// Parses a dotted key path as written in `sweep` and `where` (`fusion.method`).
    /// Returns `None` when a segment is empty.
    pub(crate) fn parse_dotted(text: &str) -> Option<Self> {
        let segments: Option<Vec<_>> = text
            .split('.')
            .map(|s| (!s.is_empty()).then(|| Segment::Key(s.to_string())))
            .collect();
        segments.map(Self)
    }
}

impl fmt::Display for Path {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, segment) in self.0.iter().enumerate() {
            match segment {
                Segment::Key(key) if i == 0 => write!(f, "{key}")?,
                Segment::Key(key) => write!(f, ".{key}")?,
                Segment::Index(index) => write!(f, "[{index}]")?,
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn displays_keys_and_indices() {
        let path = Path::root().key("requirements").index(2).key("check");
        assert_eq!(path.to_string(), "requirements[2].check");
    }

    #[test]
    fn parses_dotted_paths() {
        assert_eq!(
            Path::parse_dotted("fusion.method"),
            Some(Path::root().key("fusion").key("method"))
        );
        assert_eq!(Path::parse_dotted("fusion..method"), None);
    }
}
