//! A minimal element tree of an XML document with the line of every element (quick-xml):
//! enough for URDF and MJCF, whose content lives in elements and attributes, never in text.

use std::rc::Rc;

use quick_xml::events::{BytesStart, Event};
use quick_xml::Reader;

/// One element: name, attributes in document order, children, its line (1-based) and the file
/// it was read from (empty for the file being read; set by readers that join files).
#[derive(Clone, Debug, Default)]
pub(crate) struct Element {
    pub name: String,
    pub attrs: Vec<(String, String)>,
    pub children: Vec<Element>,
    pub line: usize,
    pub file: Rc<str>,
}

impl Element {
    /// The value of attribute `key`.
    pub fn attr(&self, key: &str) -> Option<&str> {
        self.attrs
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, v)| v.as_str())
    }

    /// The children named `name`.
    pub fn all<'a>(&'a self, name: &'a str) -> impl Iterator<Item = &'a Element> + 'a {
        self.children.iter().filter(move |c| c.name == name)
    }

    /// The first child named `name`.
    pub fn first(&self, name: &str) -> Option<&Element> {
        self.children.iter().find(|c| c.name == name)
    }
}

/// 1-based line of byte offset `pos` in `text`.
fn line_of(text: &str, pos: usize) -> usize {
    1 + text.as_bytes()[..pos.min(text.len())]
        .iter()
        .filter(|&&b| b == b'\n')
        .count()
}

/// An element from a start tag (attributes unescaped).
fn element(start: &BytesStart, line: usize) -> Result<Element, String> {
    let name = String::from_utf8_lossy(start.local_name().as_ref()).into_owned();
    let mut attrs = Vec::new();
    for a in start.attributes() {
        let a = a.map_err(|e| format!("element <{name}>: bad attribute: {e}"))?;
        let key = String::from_utf8_lossy(a.key.local_name().as_ref()).into_owned();
        let value = a
            .unescape_value()
            .map_err(|e| format!("element <{name}>: attribute {key}: {e}"))?;
        attrs.push((key, value.into_owned()));
    }
    Ok(Element {
        name,
        attrs,
        children: Vec::new(),
        line,
        file: Rc::from(""),
    })
}

/// Parses `text` into its root element.
///
/// # Errors
/// `(line, message)` for malformed XML (unclosed or mismatched tags, bad attributes, no root).
pub(crate) fn parse(text: &str) -> Result<Element, (usize, String)> {
    let mut reader = Reader::from_str(text);
    let mut stack: Vec<Element> = Vec::new();
    let mut root: Option<Element> = None;
    loop {
        let at = usize::try_from(reader.buffer_position()).unwrap_or(usize::MAX);
        let event = reader
            .read_event()
            .map_err(|e| (line_of(text, at), format!("malformed XML: {e}")))?;
        // the line of the tag's '<' (the reader has passed any whitespace before it)
        let here = || line_of(text, at + leading_space(&text[at.min(text.len())..]));
        match event {
            Event::Start(s) => stack.push(element(&s, here()).map_err(|m| (here(), m))?),
            Event::Empty(s) => {
                let e = element(&s, here()).map_err(|m| (here(), m))?;
                match stack.last_mut() {
                    Some(parent) => parent.children.push(e),
                    None if root.is_none() => root = Some(e),
                    None => return Err((here(), "more than one root element".into())),
                }
            }
            Event::End(_) => {
                let Some(e) = stack.pop() else {
                    return Err((here(), "closing tag without an opening one".into()));
                };
                match stack.last_mut() {
                    Some(parent) => parent.children.push(e),
                    None if root.is_none() => root = Some(e),
                    None => return Err((here(), "more than one root element".into())),
                }
            }
            Event::Eof => break,
            _ => {}
        }
    }
    if let Some(open) = stack.last() {
        return Err((
            open.line,
            format!("element <{}> is never closed", open.name),
        ));
    }
    root.ok_or((1, "the document has no root element".into()))
}

/// Bytes of whitespace at the start of `s`.
fn leading_space(s: &str) -> usize {
    s.len() - s.trim_start().len()
}
