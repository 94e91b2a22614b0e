//! The parts of the page that make it a document an assessor files: its
//! control (id, version, date, who wrote, reviewed and approved it), the
//! result of the tool's self-test run in this process, and the scenario file
//! verbatim.

use std::collections::HashMap;

use serde::Serialize;
use sightline_dsl::{Document, Scenario};

use crate::results::Results;
use crate::sha256_hex;

/// The document-control table and the paper the page is laid out for.
#[derive(Serialize)]
pub(crate) struct DocumentView {
    /// (name, value) rows.
    pub(crate) control: Vec<(&'static str, String)>,
    /// The CSS `@page` size: `A4` or `letter`.
    pub(crate) paper: &'static str,
}

/// A document id: `SL-` and the first 16 hex digits of the SHA-256 of
/// `content` as JSON without its `execution`, so that the same run gives the
/// same id on any machine and any change to what it found, to the scenario or
/// to the tool gives another.
pub(crate) fn content_id(mut content: serde_json::Value) -> String {
    if let Some(object) = content.as_object_mut() {
        object.remove("execution");
    }
    let text = serde_json::to_string(&content).expect("a JSON value serializes");
    format!("SL-{}", &sha256_hex(text.as_bytes())[..16])
}

/// The document id of a run's report: [`content_id`] of its results.json
/// with every file the run read named by its content, not its path: each
/// string that is an input's path as results.json writes it (the scenario's
/// `path`, each input's `path`, a warning's `file`) counts as
/// `sha256:` and that input's hash. How the scenario was named on the
/// command line (`sc/x.yaml`, `./sc/x.yaml`, an absolute path, another
/// folder) then changes nothing; a changed byte of any input does.
pub(super) fn document_id(results: &Results) -> String {
    let mut content = serde_json::to_value(results).expect("results serialize to JSON");
    let hashes: HashMap<&str, &str> = (results.inputs.iter())
        .map(|input| (input.path.as_str(), input.sha256.as_str()))
        .collect();
    name_by_content(&mut content, &hashes);
    content_id(content)
}

/// Replaces every string of `value` that is a key of `hashes` (a path) by
/// `sha256:` and its value.
fn name_by_content(value: &mut serde_json::Value, hashes: &HashMap<&str, &str>) {
    match value {
        serde_json::Value::String(text) => {
            if let Some(hash) = hashes.get(text.as_str()) {
                *text = format!("sha256:{hash}");
            }
        }
        serde_json::Value::Array(items) => items.iter_mut().for_each(|item| name_by_content(item, hashes)),
        serde_json::Value::Object(fields) => fields.values_mut().for_each(|field| name_by_content(field, hashes)),
        _ => {}
    }
}

/// A run's document control.
pub(super) fn document(results: &Results, scenario: &Scenario) -> DocumentView {
    control(document_id(results), &results.execution.started, &scenario.document)
}

/// The document-control table of a page with id `id`, dated the day of
/// `started` (RFC 3339), with the scenario's `document` section (a field left
/// out or blank shows as not given).
pub(crate) fn control(id: String, started: &str, d: &Document) -> DocumentView {
    // A field given blank (`version: ""`) says no more than one left out.
    let given = |v: &Option<String>| match v {
        Some(v) if !v.trim().is_empty() => v.clone(),
        _ => "— (not given: `document` in the scenario)".into(),
    };
    let date = started.get(..10).unwrap_or_default().to_string();
    DocumentView {
        control: vec![
            ("Document id", id),
            ("Version", given(&d.version)),
            ("Date", date),
            ("Author", given(&d.author)),
            ("Reviewer", given(&d.reviewer)),
            ("Approver", given(&d.approver)),
            (
                "Paper",
                match d.paper {
                    sightline_dsl::Paper::A4 => "A4".into(),
                    sightline_dsl::Paper::Letter => "US Letter".into(),
                },
            ),
        ],
        paper: d.paper.css(),
    }
}

/// The tool's self-test, run in this process: every known answer of the
/// engine and the oracles (`sightline selftest`).
#[derive(Serialize)]
pub(super) struct SelftestView {
    held: usize,
    total: usize,
    rows: Vec<[String; 6]>,
}

pub(super) fn selftest() -> SelftestView {
    let cases: Vec<_> = sightline_engine::known_answers()
        .into_iter()
        .chain(sightline_oracles::known_answers())
        .collect();
    SelftestView {
        held: cases.iter().filter(|c| c.holds()).count(),
        total: cases.len(),
        rows: cases
            .iter()
            .map(|c| {
                [
                    c.id.to_string(),
                    c.what.to_string(),
                    format!("{:?}", c.expected),
                    format!("{:?}", c.got),
                    format!("{:?}", c.tolerance),
                    if c.holds() { "pass" } else { "fail" }.to_string(),
                ]
            })
            .collect(),
    }
}

/// The scenario file as written, with its SHA-256, for the appendix.
#[derive(Serialize)]
pub(super) struct AppendixView {
    path: String,
    sha256: String,
    /// How many lines, whatever ends them.
    lines: usize,
    /// The file's text, exactly.
    text: String,
    /// The text line by line, each with its line end, so that a page can show
    /// every end as the file has it.
    content: Vec<TextLine>,
    /// The line ends in words: `LF`, `CR LF`, `CR`, or each kind counted.
    endings: String,
    /// Whether the text starts with a byte-order mark (U+FEFF).
    bom: bool,
}

/// One line of a text and what ends it.
#[derive(Debug, PartialEq, Serialize)]
struct TextLine {
    text: String,
    /// `null` for a last line that no line break ends.
    end: Option<LineEnd>,
}

/// A line break as a file writes it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "lowercase")]
enum LineEnd {
    Lf,
    CrLf,
    Cr,
}

impl LineEnd {
    fn bytes(self) -> &'static str {
        match self {
            LineEnd::Lf => "\n",
            LineEnd::CrLf => "\r\n",
            LineEnd::Cr => "\r",
        }
    }

    fn name(self) -> &'static str {
        match self {
            LineEnd::Lf => "LF",
            LineEnd::CrLf => "CR LF",
            LineEnd::Cr => "CR",
        }
    }
}

pub(super) fn appendix(results: &Results, text: &str) -> AppendixView {
    let content = text_lines(text);
    AppendixView {
        path: results.scenario.path.clone(),
        sha256: results.scenario.sha256.clone(),
        lines: content.len(),
        text: text.to_string(),
        endings: endings(&content),
        content,
        bom: text.starts_with('\u{feff}'),
    }
}

/// `text` cut after each line break (LF, CR LF or a lone CR): the lines and
/// their ends hold every character of `text`, in order.
fn text_lines(text: &str) -> Vec<TextLine> {
    let mut lines = Vec::new();
    let mut rest = text;
    while !rest.is_empty() {
        let (line, tail) = rest.split_at(rest.find(['\r', '\n']).unwrap_or(rest.len()));
        let end = [LineEnd::CrLf, LineEnd::Lf, LineEnd::Cr]
            .into_iter()
            .find(|end| tail.starts_with(end.bytes()));
        lines.push(TextLine {
            text: line.to_string(),
            end,
        });
        rest = &tail[end.map_or(0, |e| e.bytes().len())..];
    }
    lines
}

/// The line ends of `lines` in words: one kind by its name, several each
/// counted, and a last line without one said.
fn endings(lines: &[TextLine]) -> String {
    let mut kinds: Vec<(LineEnd, usize)> = Vec::new();
    for end in lines.iter().filter_map(|line| line.end) {
        match kinds.iter_mut().find(|(kind, _)| *kind == end) {
            Some((_, n)) => *n += 1,
            None => kinds.push((end, 1)),
        }
    }
    let mut words = match kinds.as_slice() {
        [] => "no line break".to_string(),
        [(end, _)] => format!("{} on every line", end.name()),
        _ => {
            let counted: Vec<String> = kinds.iter().map(|(end, n)| format!("{n} {}", end.name())).collect();
            format!("mixed: {}", counted.join(", "))
        }
    };
    if lines.len() > 1 && lines.last().is_some_and(|line| line.end.is_none()) {
        words.push_str(if kinds.len() == 1 {
            " but the last, which has none"
        } else {
            "; the last line has none"
        });
    }
    words
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;

    fn line(text: &str, end: Option<LineEnd>) -> TextLine {
        TextLine { text: text.into(), end }
    }

    #[test]
    fn a_document_field_left_out_or_blank_is_not_given() {
        let document = Document {
            version: Some(String::new()),
            author: Some("  ".into()),
            reviewer: None,
            approver: Some("K. Lee".into()),
            ..Document::default()
        };
        let view = control("SL-0".into(), "2026-11-28T00:00:00Z", &document);
        let row = |name: &str| view.control.iter().find(|(n, _)| *n == name).map(|(_, v)| v.as_str());
        let not_given = Some("— (not given: `document` in the scenario)");
        assert_eq!(
            ["Version", "Author", "Reviewer", "Approver", "Date"].map(row),
            [not_given, not_given, not_given, Some("K. Lee"), Some("2026-11-28")]
        );
    }

    #[test]
    fn every_kind_of_line_break_ends_a_line() {
        use LineEnd::{Cr, CrLf, Lf};
        assert_eq!(text_lines(""), vec![]);
        assert_eq!(text_lines("\na: 1\n"), vec![line("", Some(Lf)), line("a: 1", Some(Lf))]);
        assert_eq!(
            text_lines("a\r\nb\r\n"),
            vec![line("a", Some(CrLf)), line("b", Some(CrLf))]
        );
        assert_eq!(text_lines("a\rb\r"), vec![line("a", Some(Cr)), line("b", Some(Cr))]);
        // A CR then an LF with a line between is two ends, not one.
        assert_eq!(
            text_lines("a\r\r\nb"),
            vec![line("a", Some(Cr)), line("", Some(CrLf)), line("b", None)]
        );
    }

    #[test]
    fn the_line_ends_are_said_in_words() {
        let words = |text: &str| endings(&text_lines(text));
        assert_eq!(words("a\nb\n"), "LF on every line");
        assert_eq!(words("a\r\nb\r\n"), "CR LF on every line");
        assert_eq!(words("a\rb\r"), "CR on every line");
        assert_eq!(words("a\nb\r\nc\n"), "mixed: 2 LF, 1 CR LF");
        assert_eq!(words("a\nb"), "LF on every line but the last, which has none");
        assert_eq!(words("a\nb\r\nc"), "mixed: 1 LF, 1 CR LF; the last line has none");
        assert_eq!(words("a"), "no line break");
    }

    proptest! {
        /// The lines and their ends, joined, are the text again.
        #[test]
        fn the_lines_hold_the_text_exactly(text in "[a\r\n ]{0,40}") {
            let lines = text_lines(&text);
            let joined: String = lines
                .iter()
                .map(|l| format!("{}{}", l.text, l.end.map_or("", LineEnd::bytes)))
                .collect();
            prop_assert_eq!(joined, text.clone());
            prop_assert!(lines.iter().all(|l| !l.text.contains(['\r', '\n'])));
            prop_assert!(lines.iter().rev().skip(1).all(|l| l.end.is_some()));
        }
    }
}
