//! COLLADA's element tree: unlike URDF, COLLADA keeps its numbers in element text, so this tree
//! keeps text (`crate::urdf`'s keeps lines instead); elements by id, and `#id` references.

use std::collections::HashMap;

use quick_xml::events::Event;
use quick_xml::Reader;

/// An element with its text (COLLADA keeps numbers in element text).
#[derive(Debug, Default)]
pub(super) struct Node {
    pub name: String,
    pub attrs: Vec<(String, String)>,
    pub children: Vec<Node>,
    pub text: String,
}

impl Node {
    pub fn attr(&self, key: &str) -> Option<&str> {
        self.attrs
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, v)| v.as_str())
    }
    pub fn first(&self, name: &str) -> Option<&Node> {
        self.children.iter().find(|c| c.name == name)
    }
    pub fn all<'a>(&'a self, name: &'a str) -> impl Iterator<Item = &'a Node> + 'a {
        self.children.iter().filter(move |c| c.name == name)
    }
    pub fn numbers<T: std::str::FromStr>(&self) -> Result<Vec<T>, String> {
        self.text
            .split_ascii_whitespace()
            .map(|s| {
                s.parse()
                    .map_err(|_| format!("<{}>: \"{s}\" is not a number", self.name))
            })
            .collect()
    }
}

/// The element tree of `text`.
pub(super) fn tree(text: &str) -> Result<Node, String> {
    let mut reader = Reader::from_str(text);
    let mut stack: Vec<Node> = vec![Node::default()];
    let element = |s: &quick_xml::events::BytesStart| -> Node {
        Node {
            name: String::from_utf8_lossy(s.local_name().as_ref()).into_owned(),
            attrs: s
                .attributes()
                .flatten()
                .map(|a| {
                    (
                        String::from_utf8_lossy(a.key.local_name().as_ref()).into_owned(),
                        a.unescape_value()
                            .map(|v| v.into_owned())
                            .unwrap_or_default(),
                    )
                })
                .collect(),
            ..Node::default()
        }
    };
    loop {
        match reader
            .read_event()
            .map_err(|e| format!("malformed XML: {e}"))?
        {
            Event::Start(s) => stack.push(element(&s)),
            Event::Empty(s) => {
                let n = element(&s);
                if let Some(top) = stack.last_mut() {
                    top.children.push(n);
                }
            }
            Event::Text(t) => {
                if let Some(top) = stack.last_mut() {
                    let s = t.unescape().map_err(|e| format!("malformed XML: {e}"))?;
                    top.text.push_str(&s);
                    top.text.push(' ');
                }
            }
            Event::End(_) => {
                let n = stack.pop().ok_or("malformed XML: unbalanced tags")?;
                stack
                    .last_mut()
                    .ok_or("malformed XML: unbalanced tags")?
                    .children
                    .push(n);
            }
            Event::Eof => break,
            _ => {}
        }
    }
    let mut doc = stack
        .pop()
        .filter(|_| stack.is_empty())
        .ok_or("malformed XML: an element is never closed")?;
    doc.children
        .pop()
        .filter(|r| r.name == "COLLADA")
        .ok_or_else(|| "not a COLLADA file (no <COLLADA> root)".to_string())
}

/// Every element with an `id`, by id.
pub(super) fn index<'a>(node: &'a Node, ids: &mut HashMap<&'a str, &'a Node>) {
    if let Some(id) = node.attr("id") {
        ids.insert(id, node);
    }
    for c in &node.children {
        index(c, ids);
    }
}

/// The element a `#id` URL points to.
pub(super) fn target<'a>(ids: &HashMap<&'a str, &'a Node>, url: Option<&str>) -> Option<&'a Node> {
    ids.get(url?.strip_prefix('#')?).copied()
}
