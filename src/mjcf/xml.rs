//! The MJCF document as an element tree with the file and line of every element, its
//! `<include file>` elements replaced by the children of the included file's root (read
//! relative to the including file; an include cycle, a missing or malformed file is a problem
//! at the `<include>`).

use std::path::{Path, PathBuf};
use std::rc::Rc;

use crate::import::xml::{parse, Element};
use crate::spec::Problem;

/// One element: name, attributes in document order, children, file and line.
#[derive(Clone, Debug)]
pub(super) struct Node {
    pub name: String,
    pub attrs: Vec<(String, String)>,
    pub children: Vec<Node>,
    /// 1-based line in `file`.
    pub line: usize,
    /// The file it was read from, as shown in messages; empty for the main file.
    pub file: Rc<str>,
}

impl Node {
    /// The value of attribute `key`.
    pub fn attr(&self, key: &str) -> Option<&str> {
        self.attrs
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, v)| v.as_str())
    }

    /// The children named `name`.
    pub fn all<'a>(&'a self, name: &'a str) -> impl Iterator<Item = &'a Node> + 'a {
        self.children.iter().filter(move |c| c.name == name)
    }

    /// Where the element is, for messages: `line 7: <joint name="elbow">`, or
    /// `line 7 of arm.xml: <joint>` in an included file.
    pub fn at(&self) -> String {
        let name = self
            .attr("name")
            .map_or_else(String::new, |n| format!(" name=\"{n}\""));
        if self.file.is_empty() {
            format!("line {}: <{}{name}>", self.line, self.name)
        } else {
            format!("line {} of {}: <{}{name}>", self.line, self.file, self.name)
        }
    }

    /// A problem at this element.
    pub fn problem(&self, message: impl Into<String>) -> Problem {
        Problem::new(self.at(), message)
    }
}

/// The tree of `element` read from `file`.
fn tree(element: Element, file: &Rc<str>) -> Node {
    Node {
        name: element.name,
        attrs: element.attrs,
        children: element
            .children
            .into_iter()
            .map(|c| tree(c, file))
            .collect(),
        line: element.line,
        file: Rc::clone(file),
    }
}

/// Reads the main file's text `text` (at `path`) into its root, includes expanded.
///
/// # Errors
/// The problems: malformed XML (with its line), a root that is not `<mujoco>`, an include that
/// cannot be read or that includes itself.
pub(super) fn read(text: &str, path: &Path) -> Result<Node, Vec<Problem>> {
    let root =
        parse(text).map_err(|(line, msg)| vec![Problem::new(format!("line {line}"), msg)])?;
    let mut root = tree(root, &Rc::from(""));
    if root.name != "mujoco" {
        return Err(vec![
            root.problem("the root element of an MJCF file is <mujoco>")
        ]);
    }
    let mut problems = Vec::new();
    let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
    let mut stack = vec![path.to_path_buf()];
    expand(&mut root, &dir, &mut stack, &mut problems);
    if problems.is_empty() {
        Ok(root)
    } else {
        Err(problems)
    }
}

/// Replaces every `<include>` below `node` by the children of its file's root.
fn expand(node: &mut Node, dir: &Path, stack: &mut Vec<PathBuf>, problems: &mut Vec<Problem>) {
    let children = std::mem::take(&mut node.children);
    for mut child in children {
        if child.name != "include" {
            expand(&mut child, dir, stack, problems);
            node.children.push(child);
            continue;
        }
        let Some(file) = child.attr("file") else {
            problems.push(child.problem("<include> needs a file attribute"));
            continue;
        };
        let path = dir.join(file);
        if stack.contains(&path) {
            problems.push(child.problem(format!(
                "<include file=\"{file}\"> includes a file that is already being read (an include cycle)"
            )));
            continue;
        }
        let text = match std::fs::read_to_string(&path) {
            Ok(t) => t,
            Err(e) => {
                problems.push(child.problem(format!(
                    "<include file=\"{file}\">: cannot read {}: {e}",
                    path.display()
                )));
                continue;
            }
        };
        let shown: Rc<str> = Rc::from(path.to_string_lossy().as_ref());
        let root = match parse(&text) {
            Ok(r) => tree(r, &shown),
            Err((line, msg)) => {
                problems.push(Problem::new(format!("line {line} of {shown}"), msg));
                continue;
            }
        };
        if root.name != "mujoco" {
            problems.push(root.problem("the root element of an included MJCF file is <mujoco>"));
            continue;
        }
        let inner = path.parent().map(Path::to_path_buf).unwrap_or_default();
        stack.push(path);
        let mut root = root;
        expand(&mut root, &inner, stack, problems);
        stack.pop();
        node.children.extend(root.children);
    }
}
