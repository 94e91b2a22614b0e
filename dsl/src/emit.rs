//! Spanned tree → YAML text: how a counterexample is written back as a scenario
//! file. Mappings are written in block style, lists without mappings in flow
//! style (`[0, 27]`), strings plain when the core schema reads them back as the
//! same string and double-quoted (JSON escapes) otherwise. Parsing the text gives
//! the same tree, locations aside.

use std::fmt::Write;

use saphyr_parser::ScalarStyle;

use crate::yaml::{Node, Value, resolve_scalar};

/// The YAML text of `node`, ending with a newline.
pub(crate) fn emit(node: &Node) -> String {
    let mut out = String::new();
    match &node.value {
        Value::Map(entries) if !entries.is_empty() => block_map(entries, 0, &mut out),
        Value::Seq(items) if !is_flow(node) => block_seq(items, 0, &mut out),
        _ => {
            out.push_str(&flow(node));
            out.push('\n');
        }
    }
    out
}

/// Whether `node` is written on one line: a scalar, an empty container, or a
/// list that holds no mapping.
fn is_flow(node: &Node) -> bool {
    match &node.value {
        Value::Map(entries) => entries.is_empty(),
        Value::Seq(items) => items
            .iter()
            .all(|item| !matches!(&item.value, Value::Map(e) if !e.is_empty())),
        _ => true,
    }
}

fn block_map(entries: &[(crate::yaml::Key, Node)], indent: usize, out: &mut String) {
    for (key, value) in entries {
        let _ = write!(out, "{:indent$}{}:", "", string(&key.name));
        if is_flow(value) {
            let _ = writeln!(out, " {}", flow(value));
        } else {
            out.push('\n');
            block(value, indent + 2, out);
        }
    }
}

fn block_seq(items: &[Node], indent: usize, out: &mut String) {
    for item in items {
        if is_flow(item) {
            let _ = writeln!(out, "{:indent$}- {}", "", flow(item));
        } else {
            // Write the item two columns deeper, then put the dash in the first
            // line's indentation: `- id: ego` followed by aligned keys.
            let mut nested = String::new();
            block(item, indent + 2, &mut nested);
            let _ = write!(out, "{:indent$}- {}", "", &nested[indent + 2..]);
        }
    }
}

fn block(node: &Node, indent: usize, out: &mut String) {
    match &node.value {
        Value::Map(entries) => block_map(entries, indent, out),
        Value::Seq(items) => block_seq(items, indent, out),
        _ => {
            let _ = writeln!(out, "{:indent$}{}", "", flow(node));
        }
    }
}

/// One node on one line.
fn flow(node: &Node) -> String {
    match &node.value {
        Value::Null => "null".into(),
        Value::Bool(b) => b.to_string(),
        Value::Int(i) => i.to_string(),
        Value::Float(f) if f.is_nan() => ".nan".into(),
        Value::Float(f) if f.is_infinite() => if *f > 0.0 { ".inf" } else { "-.inf" }.into(),
        // Debug keeps the decimal point of whole numbers (`6.0`), so a float
        // reads back as a float.
        Value::Float(f) => format!("{f:?}"),
        Value::Str(s) => string(s),
        Value::Seq(items) => format!("[{}]", items.iter().map(flow).collect::<Vec<_>>().join(", ")),
        Value::Map(entries) => format!(
            "{{{}}}",
            entries
                .iter()
                .map(|(k, v)| format!("{}: {}", string(&k.name), flow(v)))
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}

/// A string scalar: plain when that reads back as the same string, else quoted.
fn string(s: &str) -> String {
    let simple = s.chars().next().is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && s.chars().all(|c| c.is_ascii_alphanumeric() || "_-./".contains(c));
    match resolve_scalar(s, ScalarStyle::Plain) {
        Value::Str(read) if simple && read == s => s.to_string(),
        _ => serde_json::Value::String(s.to_string()).to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::yaml::parse;

    fn round_trip(source: &str) {
        let tree = parse(source).expect("valid YAML");
        let text = emit(&tree);
        let again = parse(&text).unwrap_or_else(|e| panic!("emitted text does not parse: {e:?}\n{text}"));
        assert_eq!(again.to_json(), tree.to_json(), "{text}");
        // Integers stay integers and floats floats, which JSON equality of
        // numbers would not show.
        assert_eq!(format!("{:?}", strip(&again)), format!("{:?}", strip(&tree)), "{text}");
    }

    /// The tree without locations, for comparing structure and scalar types.
    fn strip(node: &Node) -> Value {
        match &node.value {
            Value::Seq(items) => Value::Seq(
                items
                    .iter()
                    .map(|n| Node::new(strip(n), crate::Location::new(1, 1)))
                    .collect(),
            ),
            Value::Map(entries) => Value::Map(
                entries
                    .iter()
                    .map(|(k, v)| {
                        let key = crate::yaml::Key {
                            name: k.name.clone(),
                            location: crate::Location::new(1, 1),
                        };
                        (key, Node::new(strip(v), crate::Location::new(1, 1)))
                    })
                    .collect(),
            ),
            other => other.clone(),
        }
    }

    #[test]
    fn scalars_keep_their_type_and_text() {
        round_trip(
            "a: 1\nb: 1.0\nc: \"1\"\nd: no\ne: true\nf: ~\ng: .inf\nh: -2e-7\ni: \"a: b\"\nj: \"\"\nk: \"line\\nbreak\"\nl: sumo/x.xml\n\"1\": x\n",
        );
    }

    #[test]
    fn nested_lists_and_mappings_read_back() {
        round_trip(
            "agents:\n  - { id: ego, route: [a, b], speed: { target: 8.3 } }\n  - id: rsu\n    position: [1, 2]\nroads:\n  - { id: r, polyline: [[0, 1], [2, 3]] }\nempty: {}\nnone: []\nlists:\n  - - { a: 1 }\n    - 2\n",
        );
    }

    #[test]
    fn every_bundled_scenario_reads_back() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenarios");
        for entry in std::fs::read_dir(dir).expect("the bundled scenarios") {
            let path = entry.expect("a directory entry").path();
            if path.extension().is_some_and(|e| e == "yaml") {
                round_trip(&std::fs::read_to_string(&path).expect("a readable scenario"));
            }
        }
    }
}
