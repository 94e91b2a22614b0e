//! A small XML writer over quick-xml: elements opened and closed in order,
//! every attribute value escaped, numbers written one way.

use quick_xml::Writer;
use quick_xml::events::{BytesDecl, BytesEnd, BytesStart, Event};

/// An XML document being written, indented by two spaces.
pub(crate) struct Xml {
    writer: Writer<Vec<u8>>,
    open: Vec<&'static str>,
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
        }
    }

    /// Opens `name`; [`Self::end`] closes it.
    pub(crate) fn start(&mut self, name: &'static str, attributes: Attributes<'_>) {
        let element = element(name, attributes);
        write(&mut self.writer, Event::Start(element));
        self.open.push(name);
    }

    /// Writes `name` with no content.
    pub(crate) fn empty(&mut self, name: &'static str, attributes: Attributes<'_>) {
        let element = element(name, attributes);
        write(&mut self.writer, Event::Empty(element));
    }

    /// Closes the element opened last.
    pub(crate) fn end(&mut self) {
        let name = self.open.pop().expect("an element is open: `end` follows its `start`");
        write(&mut self.writer, Event::End(BytesEnd::new(name)));
    }

    /// The document, every element closed, with a final newline.
    pub(crate) fn finish(mut self) -> String {
        while !self.open.is_empty() {
            self.end();
        }
        let mut bytes = self.writer.into_inner();
        bytes.push(b'\n');
        String::from_utf8(bytes).expect("the document is written from UTF-8 strings")
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
        let text = xml.finish();
        assert!(
            text.contains(r#"<a name="&lt;b&gt; &amp; &quot;c&quot; &apos;d&apos;">"#),
            "{text}"
        );
        assert!(text.contains(r#"<e x="0" y="0.333333333" z="0"/>"#), "{text}");
        assert!(text.ends_with("</a>\n"), "{text}");
    }

    #[test]
    fn numbers_have_no_exponent() {
        assert_eq!(num(1e21), "1000000000000000000000");
        assert_eq!(num(2.5e-7), "0.00000025");
        assert_eq!(num(-1.75), "-1.75");
    }
}
