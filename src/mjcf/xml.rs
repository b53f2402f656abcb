//! The MJCF document as an element tree (`crate::import::xml`) with the file and line of every
//! element, its `<include file>` elements replaced by the children of the included file's root
//! (read relative to the including file; an include cycle, a missing or malformed file is a
//! problem at the `<include>`).

use std::path::{Path, PathBuf};
use std::rc::Rc;

use crate::import::xml::{parse, Element};
use crate::spec::Problem;

/// An element of the document, with its file and line.
pub(super) type Node = Element;

impl Element {
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

/// Marks `element` and everything below it as read from `file`.
fn from_file(element: &mut Element, file: &Rc<str>) {
    element.file = Rc::clone(file);
    for c in &mut element.children {
        from_file(c, file);
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
    let mut root = root;
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
            Ok(mut r) => {
                from_file(&mut r, &shown);
                r
            }
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
