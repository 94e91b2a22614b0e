//! A spanned YAML tree: every node knows where it came from.
//!
//! serde loaders for YAML lose the source position once parsing is done, yet most
//! scenario errors (an out-of-range value, a dangling reference) are found later.
//! We build our own tree from saphyr-parser's events, keep the position of every
//! key and value, and deserialize from the tree (see `de.rs`). Compile passes then
//! point at any node by its YAML path.
//!
//! Scalars resolve by the YAML 1.2 core schema: `true`/`false`, `null`/`~`/empty,
//! integers (decimal, `0x`, `0o`), floats (including `.inf`, `.nan`). A quoted
//! scalar is always a string, so `"1"` never becomes a number and `no` never
//! becomes `false`. Tags (`!!float`, `!!str`, `!custom`) are refused: a value means
//! what it says, written plainly.
//!
//! Building is linear in the size of the text: duplicate keys are found through a
//! set per mapping. A document holds at most [`MAX_NODES`] nodes, aliases
//! expanded, nested at most [`MAX_DEPTH`] levels, at most [`MAX_KEYS`] keys per
//! mapping.

use std::collections::HashMap;
use std::collections::hash_map::Entry;

use saphyr_parser::{Event, Parser, ScalarStyle, Span, Tag};

use crate::error::{ErrorKind, Location, end_of};
use crate::path::Path;

/// One YAML value with the position of its first character.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Node {
    pub(crate) value: Value,
    pub(crate) location: Location,
}

/// The value of a [`Node`].
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Value {
    Null,
    Bool(bool),
    /// Integers are kept exactly, wide enough for any `u64` (seeds).
    Int(i128),
    Float(f64),
    Str(String),
    Seq(Vec<Node>),
    /// Keys in source order; duplicates are rejected while building.
    Map(Vec<(Key, Node)>),
}

/// A mapping key (always a string scalar) and its position.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Key {
    pub(crate) name: String,
    pub(crate) location: Location,
}

impl Node {
    pub(crate) fn new(value: Value, location: Location) -> Self {
        Self { value, location }
    }

    /// The entry for `key` when this node is a mapping that holds it.
    pub(crate) fn get(&self, key: &str) -> Option<&Node> {
        match &self.value {
            Value::Map(entries) => entries.iter().find(|(k, _)| k.name == key).map(|(_, v)| v),
            _ => None,
        }
    }

    /// The nodes in this tree, keys included, as [`MAX_NODES`] counts them.
    pub(crate) fn size(&self) -> usize {
        1 + match &self.value {
            Value::Seq(items) => items.iter().map(Node::size).sum(),
            Value::Map(entries) => entries.iter().map(|(_, v)| 1 + v.size()).sum(),
            _ => 0,
        }
    }

    /// A short description of the node's type for messages ("a mapping", "string \"x\"").
    pub(crate) fn describe(&self) -> String {
        match &self.value {
            Value::Null => "null".into(),
            Value::Bool(b) => format!("boolean `{b}`"),
            Value::Int(i) => format!("integer `{i}`"),
            Value::Float(f) => format!("number `{f}`"),
            Value::Str(s) => format!("string \"{s}\""),
            Value::Seq(_) => "a list".into(),
            Value::Map(_) => "a mapping".into(),
        }
    }

    /// A node holding `value` (a `vary` value set into a tree), every part at `location`.
    pub(crate) fn from_json(value: &serde_json::Value, location: Location) -> Self {
        use serde_json::Value as J;
        let value = match value {
            J::Null => Value::Null,
            J::Bool(b) => Value::Bool(*b),
            J::Number(n) => match (n.as_i64(), n.as_u64()) {
                (Some(i), _) => Value::Int(i.into()),
                (None, Some(u)) => Value::Int(u.into()),
                (None, None) => Value::Float(n.as_f64().unwrap_or(f64::NAN)),
            },
            J::String(s) => Value::Str(s.clone()),
            J::Array(items) => Value::Seq(items.iter().map(|v| Node::from_json(v, location)).collect()),
            J::Object(entries) => Value::Map(
                entries
                    .iter()
                    .map(|(k, v)| {
                        let key = Key {
                            name: k.clone(),
                            location,
                        };
                        (key, Node::from_json(v, location))
                    })
                    .collect(),
            ),
        };
        Node::new(value, location)
    }

    /// The node as JSON (for sweep values and `where` filters), keys in source order.
    pub(crate) fn to_json(&self) -> serde_json::Value {
        use serde_json::Value as J;
        match &self.value {
            Value::Null => J::Null,
            Value::Bool(b) => J::Bool(*b),
            Value::Int(i) => i64::try_from(*i)
                .map(J::from)
                .or_else(|_| u64::try_from(*i).map(J::from))
                .unwrap_or_else(|_| J::String(i.to_string())),
            Value::Float(f) => serde_json::Number::from_f64(*f).map_or(J::Null, J::Number),
            Value::Str(s) => J::String(s.clone()),
            Value::Seq(items) => J::Array(items.iter().map(Node::to_json).collect()),
            Value::Map(entries) => J::Object(entries.iter().map(|(k, v)| (k.name.clone(), v.to_json())).collect()),
        }
    }
}

/// A problem found while reading YAML text, before any scenario meaning is applied.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct ParseError {
    pub(crate) location: Location,
    /// The YAML path of the innermost mapping or list being read.
    pub(crate) path: Path,
    pub(crate) kind: ErrorKind,
}

/// Parses `source` (one YAML document) into a spanned tree.
///
/// An empty document is an error: a scenario always has content.
pub(crate) fn parse(source: &str) -> Result<Node, ParseError> {
    unprintable(source)?;
    let mut builder = Builder::default();
    let mut parser = Parser::new_from_str(source);
    while let Some(event) = parser.next_event() {
        let (event, span) = event.map_err(|e| ParseError {
            location: Location::from_marker(*e.marker()),
            path: builder.path(),
            kind: ErrorKind::Syntax(e.info().to_string()),
        })?;
        builder.on_event(event, span)?;
    }
    builder.finish()
}

/// Fails at the first character YAML 1.2 does not allow in a stream (its
/// `c-printable`: a control character but tab and line breaks, DEL, a C1
/// control but NEL, U+FFFE, U+FFFF), which the parser would pass on into the
/// evidence; written as an escape, [`Builder::reject_controls`] refuses it.
fn unprintable(source: &str) -> Result<(), ParseError> {
    let printable = |c: char| {
        matches!(c, '\t' | '\n' | '\r' | ' '..='~' | '\u{85}' | '\u{A0}'..='\u{D7FF}' | '\u{E000}'..='\u{FFFD}')
            || c >= '\u{10000}'
    };
    let Some((offset, c)) = source.char_indices().find(|&(_, c)| !printable(c)) else {
        return Ok(());
    };
    Err(ParseError {
        location: end_of(&source[..offset]),
        path: Path::root(),
        kind: ErrorKind::Syntax(format!(
            "U+{:04X} is not a character YAML allows in a file (a control character, which scenario text may not \
             hold)",
            u32::from(c)
        )),
    })
}

/// The most nodes a document may hold, aliases expanded: far more than any
/// scenario needs, and few enough that a file whose aliases multiply (nine
/// levels of nine aliases make 387 million nodes of 559 bytes) is refused in
/// bounded time and memory.
pub(crate) const MAX_NODES: usize = 1_000_000;

/// The most keys one mapping may hold: a scenario's widest mapping
/// (`sensor_models`) names a few dozen; the compiler looks keys up by name.
pub(crate) const MAX_KEYS: usize = 1000;

/// The deepest nesting of mappings and lists a document may have: a scenario
/// needs fewer than ten levels.
pub(crate) const MAX_DEPTH: usize = 64;

/// A container being filled while events arrive.
enum Open {
    Seq {
        items: Vec<Node>,
        location: Location,
        anchor: usize,
        /// The document's node count when it opened.
        first: usize,
    },
    Map {
        entries: Vec<(Key, Node)>,
        /// Where each key of `entries` is written, to find a duplicate at once.
        seen: HashMap<String, Location>,
        pending_key: Option<Key>,
        location: Location,
        anchor: usize,
        /// The document's node count when it opened.
        first: usize,
    },
}

#[derive(Default)]
struct Builder {
    stack: Vec<Open>,
    /// Each anchored node, with its size in nodes.
    anchors: HashMap<usize, (Node, usize)>,
    documents: usize,
    root: Option<Node>,
    /// Nodes in the document so far, aliases expanded.
    nodes: usize,
}

impl Builder {
    fn on_event(&mut self, event: Event<'_>, span: Span) -> Result<(), ParseError> {
        let location = Location::from_marker(span.start);
        match event {
            Event::StreamStart | Event::StreamEnd | Event::DocumentEnd | Event::Nothing => Ok(()),
            Event::DocumentStart(_) => {
                self.documents += 1;
                if self.documents > 1 {
                    return Err(ParseError {
                        location,
                        path: Path::root(),
                        kind: ErrorKind::Syntax("a scenario file holds one YAML document; found a second `---`".into()),
                    });
                }
                Ok(())
            }
            Event::Alias(id) => {
                let (node, size) = self.anchors.get(&id).cloned().ok_or_else(|| ParseError {
                    location,
                    path: self.path(),
                    kind: ErrorKind::Syntax("alias refers to an unknown anchor".into()),
                })?;
                self.count(size, location)?;
                self.push(node)
            }
            Event::Scalar(text, style, anchor, tag) => {
                self.reject_tag(tag.as_deref(), location)?;
                self.reject_controls(&text, location)?;
                self.count(1, location)?;
                let value = resolve_scalar(&text, style);
                let node = Node::new(value, location);
                self.remember(anchor, &node, 1);
                self.push(node)
            }
            Event::SequenceStart(anchor, tag) => {
                self.reject_tag(tag.as_deref(), location)?;
                self.open(location)?;
                self.stack.push(Open::Seq {
                    items: Vec::new(),
                    location,
                    anchor,
                    first: self.nodes,
                });
                Ok(())
            }
            Event::MappingStart(anchor, tag) => {
                self.reject_tag(tag.as_deref(), location)?;
                self.open(location)?;
                self.stack.push(Open::Map {
                    entries: Vec::new(),
                    seen: HashMap::new(),
                    pending_key: None,
                    location,
                    anchor,
                    first: self.nodes,
                });
                Ok(())
            }
            Event::SequenceEnd | Event::MappingEnd => {
                let (node, anchor, first) = match self.stack.pop() {
                    Some(Open::Seq {
                        items,
                        location,
                        anchor,
                        first,
                    }) => (Node::new(Value::Seq(items), location), anchor, first),
                    Some(Open::Map {
                        entries,
                        location,
                        anchor,
                        first,
                        ..
                    }) => (Node::new(Value::Map(entries), location), anchor, first),
                    None => unreachable!("the parser balances start and end events"),
                };
                self.count(1, location)?;
                self.remember(anchor, &node, self.nodes - first);
                self.push(node)
            }
        }
    }

    /// Counts `size` more nodes in the document, refusing it past [`MAX_NODES`].
    fn count(&mut self, size: usize, location: Location) -> Result<(), ParseError> {
        self.nodes = self.nodes.saturating_add(size);
        if self.nodes > MAX_NODES {
            return Err(ParseError {
                location,
                path: self.path(),
                kind: ErrorKind::TooLarge(format!(
                    "the document holds more than {MAX_NODES} nodes, its aliases expanded; a scenario needs far fewer"
                )),
            });
        }
        Ok(())
    }

    /// Refuses a mapping or list opened at `location` past [`MAX_DEPTH`] levels.
    fn open(&self, location: Location) -> Result<(), ParseError> {
        if self.stack.len() >= MAX_DEPTH {
            return Err(ParseError {
                location,
                path: self.path(),
                kind: ErrorKind::TooLarge(format!(
                    "mappings and lists nest more than {MAX_DEPTH} levels deep; a scenario needs fewer than ten"
                )),
            });
        }
        Ok(())
    }

    /// Refuses any tag: `!!float 1` would otherwise be read as the integer 1.
    /// Fails on a control character in a scalar as read, escapes decoded:
    /// one but tab and line feed (C0, DEL, C1), U+FFFE, U+FFFF, or a
    /// bidirectional embedding, override or isolate (U+202A–U+202E,
    /// U+2066–U+2069). A scenario's text reaches terminals, reports and XML,
    /// where such a character would overwrite or reorder what is shown (or,
    /// in XML, cannot be written at all).
    fn reject_controls(&self, text: &str, location: Location) -> Result<(), ParseError> {
        let control = |c: char| {
            matches!(c, '\0'..='\u{8}' | '\u{B}'..='\u{1F}' | '\u{7F}'..='\u{9F}' | '\u{FFFE}' | '\u{FFFF}')
                || matches!(c, '\u{202A}'..='\u{202E}' | '\u{2066}'..='\u{2069}')
        };
        match text.chars().find(|&c| control(c)) {
            None => Ok(()),
            Some(c) => Err(ParseError {
                location,
                path: self.path(),
                kind: ErrorKind::Invalid(format!(
                    "the text holds U+{:04X}, a control character: scenario text is shown in terminals, reports and \
                     XML, where it would hide or reorder what is shown; leave it out",
                    u32::from(c)
                )),
            }),
        }
    }

    fn reject_tag(&self, tag: Option<&Tag>, location: Location) -> Result<(), ParseError> {
        let Some(tag) = tag else { return Ok(()) };
        // As written: `!!float`, not the resolved `tag:yaml.org,2002:float`.
        let written = match tag.handle.as_str() {
            "tag:yaml.org,2002:" => format!("!!{}", tag.suffix),
            "!" => format!("!{}", tag.suffix),
            handle => format!("{handle}{}", tag.suffix),
        };
        Err(ParseError {
            location,
            path: self.path(),
            kind: ErrorKind::Syntax(format!(
                "YAML tags such as `{written}` are not supported; write the value plainly (quoted for a string)"
            )),
        })
    }

    /// Keeps an anchored node of `size` nodes for the aliases that follow.
    fn remember(&mut self, anchor: usize, node: &Node, size: usize) {
        if anchor != 0 {
            self.anchors.insert(anchor, (node.clone(), size));
        }
    }

    /// Places a finished node into its parent (or makes it the root).
    fn push(&mut self, node: Node) -> Result<(), ParseError> {
        if let Some(Open::Map { pending_key: None, .. }) = self.stack.last() {
            let key = self.key(node)?;
            if let Some(Open::Map { pending_key, .. }) = self.stack.last_mut() {
                *pending_key = Some(key);
            }
            return Ok(());
        }
        match self.stack.last_mut() {
            None => self.root = Some(node),
            Some(Open::Seq { items, .. }) => items.push(node),
            Some(Open::Map {
                entries, pending_key, ..
            }) => {
                let key = pending_key.take().expect("a key was stored before its value");
                entries.push((key, node));
            }
        }
        Ok(())
    }

    /// Turns a scalar node in key position into a key of the innermost mapping,
    /// rejecting complex and duplicate keys.
    fn key(&mut self, node: Node) -> Result<Key, ParseError> {
        let name = match node.value {
            Value::Str(s) => s,
            Value::Int(i) => i.to_string(),
            Value::Float(f) => f.to_string(),
            Value::Bool(b) => b.to_string(),
            Value::Null | Value::Seq(_) | Value::Map(_) => {
                return Err(ParseError {
                    location: node.location,
                    path: self.path(),
                    kind: ErrorKind::Syntax(format!("a mapping key must be a plain name, found {}", node.describe())),
                });
            }
        };
        let Some(Open::Map { seen, .. }) = self.stack.last_mut() else {
            unreachable!("a key is read inside a mapping")
        };
        let full = seen.len() >= MAX_KEYS;
        match seen.entry(name.clone()) {
            Entry::Vacant(_) if full => {
                return Err(ParseError {
                    location: node.location,
                    path: self.path(),
                    kind: ErrorKind::TooLarge(format!(
                        "a mapping holds more than {MAX_KEYS} keys; a scenario's widest names a few dozen"
                    )),
                });
            }
            Entry::Vacant(slot) => {
                slot.insert(node.location);
            }
            Entry::Occupied(first) => {
                let first = *first.get();
                return Err(ParseError {
                    location: node.location,
                    path: self.path(),
                    kind: ErrorKind::DuplicateKey { key: name, first },
                });
            }
        }
        Ok(Key {
            name,
            location: node.location,
        })
    }

    /// The YAML path of the innermost open mapping or list.
    fn path(&self) -> Path {
        let mut path = Path::root();
        for frame in self.stack.iter().take(self.stack.len().saturating_sub(1)) {
            path = match frame {
                Open::Seq { items, .. } => path.index(items.len()),
                Open::Map {
                    pending_key: Some(key), ..
                } => path.key(&key.name),
                // A mapping used as a key: rejected when it closes.
                Open::Map { pending_key: None, .. } => path,
            };
        }
        path
    }

    fn finish(self) -> Result<Node, ParseError> {
        self.root.ok_or(ParseError {
            location: Location::new(1, 1),
            path: Path::root(),
            kind: ErrorKind::Syntax("the file is empty; a scenario starts with `sightline: 1`".into()),
        })
    }
}

/// Resolves an untagged scalar by the YAML 1.2 core schema.
pub(crate) fn resolve_scalar(text: &str, style: ScalarStyle) -> Value {
    if style != ScalarStyle::Plain {
        return Value::Str(text.to_string());
    }
    match text {
        "" | "~" | "null" | "Null" | "NULL" => Value::Null,
        "true" | "True" | "TRUE" => Value::Bool(true),
        "false" | "False" | "FALSE" => Value::Bool(false),
        ".inf" | ".Inf" | ".INF" | "+.inf" | "+.Inf" | "+.INF" => Value::Float(f64::INFINITY),
        "-.inf" | "-.Inf" | "-.INF" => Value::Float(f64::NEG_INFINITY),
        ".nan" | ".NaN" | ".NAN" => Value::Float(f64::NAN),
        _ => parse_number(text).unwrap_or_else(|| Value::Str(text.to_string())),
    }
}

fn parse_number(text: &str) -> Option<Value> {
    if let Some(hex) = text.strip_prefix("0x") {
        return i128::from_str_radix(hex, 16).ok().map(Value::Int);
    }
    if let Some(oct) = text.strip_prefix("0o") {
        return i128::from_str_radix(oct, 8).ok().map(Value::Int);
    }
    let digits = text.strip_prefix(['-', '+']).unwrap_or(text);
    if !digits.starts_with(|c: char| c.is_ascii_digit() || c == '.') {
        return None;
    }
    if digits.bytes().all(|b| b.is_ascii_digit()) {
        // Beyond i128 an integer is still a number: keep it as a float.
        return Some(
            text.parse()
                .map_or_else(|_| Value::Float(text.parse().unwrap_or(f64::NAN)), Value::Int),
        );
    }
    text.parse::<f64>().ok().map(Value::Float)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn root(source: &str) -> Node {
        parse(source).expect("valid YAML")
    }

    #[test]
    fn scalars_resolve_by_the_core_schema() {
        let node = root("a: 1\nb: 1.5\nc: \"1\"\nd: no\ne: true\nf: ~\ng: .inf\nh: 0x10\ni: -2e3\n");
        let get = |k| node.get(k).unwrap().value.clone();
        assert_eq!(get("a"), Value::Int(1));
        assert_eq!(get("b"), Value::Float(1.5));
        assert_eq!(get("c"), Value::Str("1".into()));
        assert_eq!(get("d"), Value::Str("no".into()));
        assert_eq!(get("e"), Value::Bool(true));
        assert_eq!(get("f"), Value::Null);
        assert_eq!(get("g"), Value::Float(f64::INFINITY));
        assert_eq!(get("h"), Value::Int(16));
        assert_eq!(get("i"), Value::Float(-2000.0));
        let big = root("seed: 18446744073709551615\n");
        assert_eq!(big.get("seed").unwrap().value, Value::Int(u64::MAX.into()));
    }

    #[test]
    fn locations_are_one_based_line_and_column() {
        let node = root("top:\n  inner: [1, 2]\n");
        let inner = node.get("top").unwrap().get("inner").unwrap();
        assert_eq!(inner.location, Location::new(2, 10));
        let Value::Map(entries) = &node.get("top").unwrap().value else {
            panic!("a mapping")
        };
        assert_eq!(entries[0].0.location, Location::new(2, 3));
    }

    #[test]
    fn duplicate_keys_are_rejected_with_both_locations() {
        let err = parse("a: 1\nb: 2\na: 3\n").unwrap_err();
        assert_eq!(err.location, Location::new(3, 1));
        assert_eq!(err.path, Path::root());
        let nested = parse("top:\n  list:\n    - {k: 1, k: 2}\n").unwrap_err();
        assert_eq!(nested.path.to_string(), "top.list[0]");
        assert_eq!(
            err.kind,
            ErrorKind::DuplicateKey {
                key: "a".into(),
                first: Location::new(1, 1)
            }
        );
    }

    #[test]
    fn aliases_copy_the_anchored_node() {
        let node = root("a: &x {k: 1}\nb: *x\n");
        assert_eq!(node.get("b").unwrap().get("k").unwrap().value, Value::Int(1));
    }

    #[test]
    fn syntax_errors_carry_a_location() {
        let err = parse("a: [1, 2\nb: 3\n").unwrap_err();
        assert!(matches!(err.kind, ErrorKind::Syntax(_)));
        assert!(err.location.line >= 1);
    }

    #[test]
    fn empty_and_multi_document_files_are_rejected() {
        assert!(parse("").is_err());
        assert!(parse("a: 1\n---\nb: 2\n").is_err());
    }

    #[test]
    fn tags_are_rejected_core_schema_ones_too() {
        for source in [
            "a: !custom 1\n",
            "a: !!float 1\n",
            "a: !!str 1\n",
            "a: !!map {b: 1}\n",
            "a: !!seq [1]\n",
        ] {
            let err = parse(source).unwrap_err();
            assert_eq!(err.location, Location::new(1, 4), "{source}");
            let tag = source[3..].split(' ').next().unwrap();
            assert!(
                matches!(err.kind, ErrorKind::Syntax(ref m) if m.contains(&format!("`{tag}`"))),
                "{source}"
            );
        }
    }

    #[test]
    fn nesting_is_bounded() {
        let at_limit = format!("{}1{}", "[".repeat(MAX_DEPTH), "]".repeat(MAX_DEPTH));
        assert!(parse(&at_limit).is_ok());
        let beyond = format!("a: {}1{}", "{b: ".repeat(MAX_DEPTH), "}".repeat(MAX_DEPTH));
        let err = parse(&beyond).unwrap_err();
        assert!(matches!(err.kind, ErrorKind::TooLarge(_)));
        assert_eq!(err.path.to_string(), format!("a{}", ".b".repeat(MAX_DEPTH - 2)));
    }

    #[test]
    fn keys_per_mapping_are_bounded() {
        let keys = |n: usize| -> String { (0..n).map(|i| format!("  k{i}: 1\n")).collect() };
        let node = root(&format!("top:\n{}", keys(MAX_KEYS)));
        let Value::Map(entries) = &node.get("top").unwrap().value else {
            panic!("a mapping")
        };
        assert_eq!(entries.len(), MAX_KEYS);
        let duplicate = parse(&format!("top:\n{}  k7: 2\n", keys(MAX_KEYS))).unwrap_err();
        assert!(matches!(duplicate.kind, ErrorKind::DuplicateKey { .. }));
        let err = parse(&format!("top:\n{}", keys(200_000))).unwrap_err();
        assert!(matches!(err.kind, ErrorKind::TooLarge(_)));
        assert_eq!(
            (err.location, err.path.to_string()),
            (Location::new(MAX_KEYS + 2, 3), "top".into())
        );
    }
}
