//! A small XML writer over quick-xml: elements opened and closed in order,
//! every attribute value escaped, numbers written one way. A value holding a
//! character XML 1.0 does not allow (a control character but tab and line
//! breaks, U+FFFE, U+FFFF) cannot be written at all: the document is refused.

use quick_xml::Writer;
use quick_xml::events::{BytesDecl, BytesEnd, BytesStart, Event};

/// An XML document being written, indented by two spaces.
pub(crate) struct Xml {
    writer: Writer<Vec<u8>>,
    open: Vec<&'static str>,
    /// The first value written that XML 1.0 cannot hold.
    unwritable: Option<String>,
}

/// A value XML 1.0 cannot hold, escaped as Rust's debug format escapes a
/// string, and its first character XML does not allow.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Unwritable {
    /// The value, escaped.
    pub value: String,
    /// The character's code point.
    pub code: u32,
}

/// Whether XML 1.0 allows `c` in a document (its production `Char`; Rust's
/// strings hold no surrogate).
fn allowed(c: char) -> bool {
    matches!(c, '\t' | '\n' | '\r' | '\u{20}'..='\u{fffd}' | '\u{10000}'..)
}

/// An element's attributes: names and their values, unescaped.
pub(crate) type Attributes<'a> = &'a [(&'a str, String)];

impl Xml {
    /// A document with its XML declaration (version 1.0, UTF-8).
    pub(crate) fn new() -> Self {
        let mut writer = Writer::new_with_indent(Vec::new(), b' ', 2);
        write(&mut writer, Event::Decl(BytesDecl::new("1.0", Some("UTF-8"), None)));
        Self {
            writer,
            open: Vec::new(),
            unwritable: None,
        }
    }

    /// Opens `name`; [`Self::end`] closes it.
    pub(crate) fn start(&mut self, name: &'static str, attributes: Attributes<'_>) {
        self.check(attributes);
        let element = element(name, attributes);
        write(&mut self.writer, Event::Start(element));
        self.open.push(name);
    }

    /// Writes `name` with no content.
    pub(crate) fn empty(&mut self, name: &'static str, attributes: Attributes<'_>) {
        self.check(attributes);
        let element = element(name, attributes);
        write(&mut self.writer, Event::Empty(element));
    }

    /// Closes the element opened last.
    pub(crate) fn end(&mut self) {
        let name = self.open.pop().expect("an element is open: `end` follows its `start`");
        write(&mut self.writer, Event::End(BytesEnd::new(name)));
    }

    /// Keeps the first of `attributes`' values that XML cannot hold.
    fn check(&mut self, attributes: Attributes<'_>) {
        if self.unwritable.is_some() {
            return;
        }
        self.unwritable = attributes
            .iter()
            .find(|(_, value)| !value.chars().all(allowed))
            .map(|(_, value)| value.clone());
    }

    /// The document, every element closed, with a final newline; an error
    /// naming the first value XML 1.0 cannot hold, if one was written.
    pub(crate) fn finish(mut self) -> Result<String, Unwritable> {
        if let Some(value) = self.unwritable {
            let code = value.chars().find(|&c| !allowed(c)).map_or(0, u32::from);
            return Err(Unwritable {
                value: value.escape_debug().collect(),
                code,
            });
        }
        while !self.open.is_empty() {
            self.end();
        }
        let mut bytes = self.writer.into_inner();
        bytes.push(b'\n');
        Ok(String::from_utf8(bytes).expect("the document is written from UTF-8 strings"))
    }
}

fn element<'a>(name: &'a str, attributes: Attributes<'_>) -> BytesStart<'a> {
    let mut element = BytesStart::new(name);
    for (key, value) in attributes {
        // quick-xml escapes the value (`<`, `>`, `&`, `'`, `"`).
        element.push_attribute((*key, value.as_str()));
    }
    element
}

fn write(writer: &mut Writer<Vec<u8>>, event: Event<'_>) {
    writer.write_event(event).expect("writing into memory cannot fail");
}

/// A number as the files write it: rounded to 1e-9 (a nanometre, a
/// nanoradian), without a sign on zero and without an exponent.
pub(crate) fn num(value: f64) -> String {
    let rounded = (value * 1e9).round() / 1e9;
    if rounded == 0.0 {
        return "0".into();
    }
    format!("{rounded}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn attribute_values_are_escaped() {
        let mut xml = Xml::new();
        xml.start("a", &[("name", "<b> & \"c\" 'd'".into())]);
        xml.empty("e", &[("x", num(-0.0)), ("y", num(1.0 / 3.0)), ("z", num(1e-12))]);
        let text = xml.finish().unwrap();
        assert!(
            text.contains(r#"<a name="&lt;b&gt; &amp; &quot;c&quot; &apos;d&apos;">"#),
            "{text}"
        );
        assert!(text.contains(r#"<e x="0" y="0.333333333" z="0"/>"#), "{text}");
        assert!(text.ends_with("</a>\n"), "{text}");
    }

    #[test]
    fn a_value_xml_cannot_hold_refuses_the_document() {
        for (value, code) in [
            ("a\u{1b}[1m", 0x1b),
            ("\0", 0),
            ("x\u{fffe}", 0xfffe),
            ("\u{ffff}", 0xffff),
        ] {
            let mut xml = Xml::new();
            xml.start("a", &[("name", "fine".into())]);
            xml.empty("b", &[("x", "1".into()), ("id", value.into())]);
            let error = xml.finish().unwrap_err();
            assert_eq!(error.code, code, "{value:?}");
            assert_eq!(error.value, value.escape_debug().to_string());
            assert!(!error.value.chars().any(char::is_control), "{error:?}");
        }
        let mut xml = Xml::new();
        xml.empty(
            "a",
            &[("name", "tab\tline\nreturn\r \u{d7ff}\u{e000}\u{fffd}\u{10000}".into())],
        );
        assert!(xml.finish().is_ok());
    }

    #[test]
    fn numbers_have_no_exponent() {
        assert_eq!(num(1e21), "1000000000000000000000");
        assert_eq!(num(2.5e-7), "0.00000025");
        assert_eq!(num(-1.75), "-1.75");
    }
}
