//! serde deserialization from the spanned tree, with every error located.
//!
//! Each node boundary stamps its location and YAML path on an error that has none,
//! so a `missing key` lands on its mapping, an `unknown key` on the key itself and
//! a wrong type on the value. Only unit enum variants are supported: the raw types
//! never use externally tagged, untagged or flattened enums (they ruin messages).

use std::fmt::{self, Display};

use serde::de::{self, DeserializeSeed, IntoDeserializer, Unexpected, Visitor};

use crate::error::{ErrorKind, Location};
use crate::path::Path;
use crate::yaml::{Key, Node, Value};

/// A deserialization error, located once it crosses a node boundary (boxed: it
/// travels through every `Result` of the deserializer).
#[derive(Debug)]
pub(crate) struct DeError(Box<Located>);

/// The contents of a [`DeError`].
#[derive(Debug)]
pub(crate) struct Located {
    pub(crate) kind: ErrorKind,
    pub(crate) location: Option<Location>,
    pub(crate) path: Option<Path>,
}

impl std::ops::Deref for DeError {
    type Target = Located;

    fn deref(&self) -> &Located {
        &self.0
    }
}

impl DeError {
    fn new(kind: ErrorKind) -> Self {
        Self(Box::new(Located {
            kind,
            location: None,
            path: None,
        }))
    }

    fn locate(mut self, location: Location, path: &Path) -> Self {
        if self.0.location.is_none() {
            self.0.location = Some(location);
            self.0.path = Some(path.clone());
        }
        self
    }

    /// Takes the contents out.
    pub(crate) fn into_inner(self) -> Located {
        *self.0
    }
}

impl Display for DeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.kind.fmt(f)
    }
}

impl std::error::Error for DeError {}

impl de::Error for DeError {
    fn custom<T: Display>(msg: T) -> Self {
        Self::new(ErrorKind::Invalid(msg.to_string()))
    }

    fn invalid_type(unexpected: Unexpected<'_>, expected: &dyn de::Expected) -> Self {
        Self::new(ErrorKind::InvalidType {
            expected: friendly_expected(&expected.to_string()),
            found: describe_unexpected(&unexpected),
        })
    }

    fn invalid_value(unexpected: Unexpected<'_>, expected: &dyn de::Expected) -> Self {
        Self::new(ErrorKind::OutOfRange {
            expected: friendly_expected(&expected.to_string()),
            found: describe_unexpected(&unexpected),
        })
    }

    fn invalid_length(len: usize, expected: &dyn de::Expected) -> Self {
        Self::new(ErrorKind::InvalidType {
            expected: friendly_expected(&expected.to_string()),
            found: format!("a list of {len}"),
        })
    }

    fn unknown_variant(variant: &str, expected: &'static [&'static str]) -> Self {
        Self::new(ErrorKind::UnknownValue {
            value: variant.to_string(),
            expected: one_of(expected),
            did_you_mean: closest(variant, expected.iter().copied()),
        })
    }

    fn unknown_field(field: &str, expected: &'static [&'static str]) -> Self {
        Self::new(ErrorKind::UnknownKey {
            key: field.to_string(),
            expected: one_of(expected),
            did_you_mean: closest(field, expected.iter().copied()),
        })
    }

    fn missing_field(field: &'static str) -> Self {
        Self::new(ErrorKind::MissingKey(field.to_string()))
    }
}

/// Formats names as "`a`, `b`, `c`".
pub(crate) fn one_of<'a>(names: impl IntoIterator<Item = &'a &'a str>) -> String {
    names
        .into_iter()
        .map(|n| format!("`{n}`"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The candidate closest to `word` by edit distance, if it is close enough to be a typo.
pub(crate) fn closest<'a>(word: &str, candidates: impl Iterator<Item = &'a str>) -> Option<String> {
    candidates
        .map(|c| (edit_distance(word, c), c))
        .filter(|&(d, c)| d <= 2.max(c.len() / 3) && d < c.len())
        .min_by_key(|&(d, _)| d)
        .map(|(_, c)| c.to_string())
}

fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let substitution = diagonal + usize::from(ca != cb);
            diagonal = row[j + 1];
            row[j + 1] = substitution.min(row[j] + 1).min(diagonal + 1);
        }
    }
    row[b.len()]
}

/// serde names Rust types ("f64", "u64"); users read YAML.
fn friendly_expected(expected: &str) -> String {
    match expected {
        "f64" | "f32" => "a number".into(),
        "u64" => format!("a whole number from 0 to {}", u64::MAX),
        "u32" => format!("a whole number from 0 to {}", u32::MAX),
        "i64" | "i32" => "a whole number".into(),
        "a boolean" | "bool" => "`true` or `false`".into(),
        "a sequence" => "a list".into(),
        other => other.into(),
    }
}

fn describe_unexpected(unexpected: &Unexpected<'_>) -> String {
    match unexpected {
        Unexpected::Unit => "null".into(),
        Unexpected::Seq => "a list".into(),
        Unexpected::Map => "a mapping".into(),
        Unexpected::Str(s) => format!("string \"{s}\""),
        Unexpected::Signed(i) => format!("integer `{i}`"),
        Unexpected::Unsigned(u) => format!("integer `{u}`"),
        Unexpected::Float(f) => format!("number `{f}`"),
        Unexpected::Bool(b) => format!("boolean `{b}`"),
        // serde describes integers beyond 64 bits as "integer `…` as i128".
        Unexpected::Other(text) => text
            .trim_end_matches(" as i128")
            .trim_end_matches(" as u128")
            .to_string(),
        other => other.to_string(),
    }
}

/// Deserializes `T` from a node, locating any error.
pub(crate) fn from_node<'de, T: de::Deserialize<'de>>(node: &'de Node, path: &Path) -> Result<T, DeError> {
    T::deserialize(NodeDeserializer {
        node,
        path: path.clone(),
    })
}

struct NodeDeserializer<'de> {
    node: &'de Node,
    path: Path,
}

impl<'de> NodeDeserializer<'de> {
    fn locate(&self, error: DeError) -> DeError {
        error.locate(self.node.location, &self.path)
    }
}

impl<'de> de::Deserializer<'de> for NodeDeserializer<'de> {
    type Error = DeError;

    fn deserialize_any<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, DeError> {
        let result = match &self.node.value {
            Value::Null => visitor.visit_unit(),
            Value::Bool(b) => visitor.visit_bool(*b),
            Value::Int(i) => match (i64::try_from(*i), u64::try_from(*i)) {
                (Ok(i), _) => visitor.visit_i64(i),
                (_, Ok(u)) => visitor.visit_u64(u),
                _ => visitor.visit_i128(*i),
            },
            Value::Float(f) => visitor.visit_f64(*f),
            Value::Str(s) => visitor.visit_borrowed_str(s),
            Value::Seq(items) => {
                let mut seq = SeqAccess {
                    items: items.iter().enumerate(),
                    path: &self.path,
                };
                // A fixed-size target (a point) reads only its own items: any
                // left over is an error, never dropped.
                visitor.visit_seq(&mut seq).and_then(|value| match seq.items.len() {
                    0 => Ok(value),
                    rest => Err(de::Error::invalid_length(
                        items.len(),
                        &format!("a list of {}", items.len() - rest).as_str(),
                    )),
                })
            }
            Value::Map(entries) => visitor.visit_map(MapAccess {
                entries: entries.iter(),
                value: None,
                path: &self.path,
            }),
        };
        result.map_err(|e| self.locate(e))
    }

    fn deserialize_option<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, DeError> {
        match self.node.value {
            Value::Null => visitor.visit_none(),
            _ => visitor.visit_some(self),
        }
    }

    fn deserialize_newtype_struct<V: Visitor<'de>>(self, _name: &'static str, visitor: V) -> Result<V::Value, DeError> {
        visitor.visit_newtype_struct(self)
    }

    fn deserialize_enum<V: Visitor<'de>>(
        self,
        _name: &'static str,
        variants: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, DeError> {
        let result = match &self.node.value {
            Value::Str(s) => visitor.visit_enum(s.as_str().into_deserializer()),
            _ => Err(DeError::new(ErrorKind::InvalidType {
                expected: format!("one of {}", one_of(variants)),
                found: self.node.describe(),
            })),
        };
        result.map_err(|e| self.locate(e))
    }

    /// A section is a mapping: a list is not read into its fields in order
    /// (serde's default), which would take `record: [1]` for `{ point: 1 }`.
    fn deserialize_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        _fields: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, DeError> {
        match self.node.value {
            Value::Seq(_) => {
                let error = DeError::new(ErrorKind::InvalidType {
                    expected: "a mapping".into(),
                    found: self.node.describe(),
                });
                Err(self.locate(error))
            }
            _ => self.deserialize_any(visitor),
        }
    }

    serde::forward_to_deserialize_any! {
        bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string
        bytes byte_buf unit unit_struct seq tuple tuple_struct map
        identifier ignored_any
    }
}

struct SeqAccess<'de, 'p> {
    items: std::iter::Enumerate<std::slice::Iter<'de, Node>>,
    path: &'p Path,
}

impl<'de> de::SeqAccess<'de> for SeqAccess<'de, '_> {
    type Error = DeError;

    fn next_element_seed<T: DeserializeSeed<'de>>(&mut self, seed: T) -> Result<Option<T::Value>, DeError> {
        match self.items.next() {
            None => Ok(None),
            Some((index, node)) => seed
                .deserialize(NodeDeserializer {
                    node,
                    path: self.path.index(index),
                })
                .map(Some),
        }
    }

    fn size_hint(&self) -> Option<usize> {
        Some(self.items.len())
    }
}

struct MapAccess<'de, 'p> {
    entries: std::slice::Iter<'de, (Key, Node)>,
    value: Option<(&'de Key, &'de Node)>,
    path: &'p Path,
}

impl<'de> de::MapAccess<'de> for MapAccess<'de, '_> {
    type Error = DeError;

    fn next_key_seed<K: DeserializeSeed<'de>>(&mut self, seed: K) -> Result<Option<K::Value>, DeError> {
        let Some((key, value)) = self.entries.next() else {
            return Ok(None);
        };
        self.value = Some((key, value));
        let name: &'de str = &key.name;
        seed.deserialize(name.into_deserializer())
            .map(Some)
            .map_err(|e: DeError| e.locate(key.location, self.path))
    }

    fn next_value_seed<V: DeserializeSeed<'de>>(&mut self, seed: V) -> Result<V::Value, DeError> {
        let (key, node) = self.value.take().expect("serde asks for a value after its key");
        seed.deserialize(NodeDeserializer {
            node,
            path: self.path.key(&key.name),
        })
    }

    fn size_hint(&self) -> Option<usize> {
        Some(self.entries.len())
    }
}

#[cfg(test)]
mod tests {
    use serde::Deserialize;

    use super::*;
    use crate::yaml::parse;

    #[derive(Debug, Deserialize, PartialEq)]
    #[serde(deny_unknown_fields)]
    struct Inner {
        gamma: f64,
        #[serde(default)]
        count: u32,
    }

    #[derive(Debug, Deserialize, PartialEq)]
    #[serde(deny_unknown_fields, rename_all = "snake_case")]
    enum Method {
        Bayes,
        Dempster,
    }

    #[derive(Debug, Deserialize, PartialEq)]
    #[serde(deny_unknown_fields)]
    struct Outer {
        inner: Inner,
        method: Method,
        list: Option<Vec<f64>>,
    }

    fn load(source: &str) -> Result<Outer, DeError> {
        let node = Box::leak(Box::new(parse(source).unwrap()));
        from_node(node, &Path::root())
    }

    #[test]
    fn reads_a_valid_document() {
        let outer = load("inner: {gamma: 2}\nmethod: bayes\nlist: [1, 2.5]\n").unwrap();
        assert_eq!(outer.inner, Inner { gamma: 2.0, count: 0 });
        assert_eq!(outer.method, Method::Bayes);
        assert_eq!(outer.list, Some(vec![1.0, 2.5]));
    }

    #[test]
    fn unknown_key_points_at_the_key() {
        let err = load("inner:\n  gama: 2\nmethod: bayes\n").unwrap_err();
        assert_eq!(err.location, Some(Location::new(2, 3)));
        assert_eq!(err.path.as_ref().unwrap().to_string(), "inner");
        assert!(
            matches!(err.kind, ErrorKind::UnknownKey { ref did_you_mean, .. } if did_you_mean.as_deref() == Some("gamma"))
        );
    }

    #[test]
    fn wrong_type_points_at_the_value() {
        let err = load("inner:\n  gamma: high\nmethod: bayes\n").unwrap_err();
        assert_eq!(err.location, Some(Location::new(2, 10)));
        assert_eq!(err.path.as_ref().unwrap().to_string(), "inner.gamma");
        assert_eq!(err.kind.to_string(), "expected a number, found string \"high\"");
    }

    #[test]
    fn missing_key_points_at_the_mapping() {
        let err = load("inner:\n  count: 1\nmethod: bayes\n").unwrap_err();
        assert_eq!(err.location, Some(Location::new(2, 3)));
        assert_eq!(err.kind, ErrorKind::MissingKey("gamma".into()));
    }

    #[test]
    fn unknown_variant_lists_the_variants() {
        let err = load("inner: {gamma: 1}\nmethod: bayez\n").unwrap_err();
        assert_eq!(err.location, Some(Location::new(2, 9)));
        assert_eq!(
            err.kind.to_string(),
            "unknown value `bayez`; expected one of `bayes`, `dempster` (did you mean `bayes`?)"
        );
    }

    #[test]
    fn list_elements_carry_their_index() {
        let err = load("inner: {gamma: 1}\nmethod: bayes\nlist: [1, x]\n").unwrap_err();
        assert_eq!(err.path.as_ref().unwrap().to_string(), "list[1]");
        assert_eq!(err.location, Some(Location::new(3, 11)));
    }

    #[test]
    fn negative_count_is_out_of_range() {
        let err = load("inner: {gamma: 1, count: -1}\nmethod: bayes\n").unwrap_err();
        assert_eq!(
            err.kind.to_string(),
            "expected a whole number from 0 to 4294967295, found integer `-1`"
        );
    }

    #[test]
    fn edit_distance_counts_single_edits() {
        assert_eq!(edit_distance("gama", "gamma"), 1);
        assert_eq!(edit_distance("", "abc"), 3);
        assert_eq!(edit_distance("abc", "abc"), 0);
        assert_eq!(closest("xyz", ["gamma"].into_iter()), None);
    }
}
