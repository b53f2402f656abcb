//! `<default>` classes: the attributes an element takes from its class and the classes above
//! it, and the class each element has.
//!
//! The top-level `<default>` is the class `main`; a nested `<default class="C">` is a class
//! whose unset attributes come from its parent class. An element's class is its `class`
//! attribute, else the `childclass` of the nearest enclosing `<body>` or `<frame>` (the body's
//! own, for its joints, geoms and sites), else `main`. An attribute is looked up on the element,
//! then on the class's default of that element kind (`<default class="C"><joint .../>`), then
//! on each class above it. The orientation of a geom or site (`quat`, `euler`, `axisangle`,
//! `xyaxes`, `zaxis`) is one attribute: the element's own, if it gives any, wins whole.

use std::collections::HashMap;

use super::xml::Node;
use crate::spec::{did_you_mean, Problem};

/// The orientation attributes, one of which places a frame.
pub(super) const ORIENTATIONS: [&str; 5] = ["quat", "axisangle", "euler", "xyaxes", "zaxis"];

/// One class: its parent class and its default element of each kind.
#[derive(Debug)]
struct Class<'a> {
    parent: Option<usize>,
    kinds: HashMap<&'a str, &'a Node>,
}

/// Every class of the document.
#[derive(Debug)]
pub(super) struct Classes<'a> {
    classes: Vec<Class<'a>>,
    by_name: HashMap<&'a str, usize>,
}

impl<'a> Classes<'a> {
    /// The classes of the `<default>` elements under `root`; duplicate class names are problems.
    pub fn read(root: &'a Node, problems: &mut Vec<Problem>) -> Self {
        let mut out = Classes {
            classes: vec![Class {
                parent: None,
                kinds: HashMap::new(),
            }],
            by_name: HashMap::from([("main", 0)]),
        };
        for d in root.all("default") {
            out.fill(d, 0, problems);
        }
        out
    }

    /// Adds the defaults of `node` to class `class`, and its nested classes below it.
    fn fill(&mut self, node: &'a Node, class: usize, problems: &mut Vec<Problem>) {
        for child in &node.children {
            if child.name != "default" {
                self.classes[class].kinds.insert(&child.name, child);
                continue;
            }
            let Some(name) = child.attr("class") else {
                problems.push(child.problem("a nested <default> needs a class attribute"));
                continue;
            };
            if self.by_name.contains_key(name) {
                problems.push(child.problem(format!("class \"{name}\" is defined twice")));
                continue;
            }
            self.classes.push(Class {
                parent: Some(class),
                kinds: HashMap::new(),
            });
            let id = self.classes.len() - 1;
            self.by_name.insert(name, id);
            self.fill(child, id, problems);
        }
    }

    /// The class named `name`, or a problem at `at` naming the classes there are.
    pub fn find(&self, name: &str, at: &Node) -> Result<usize, Problem> {
        self.by_name.get(name).copied().ok_or_else(|| {
            at.problem(format!(
                "class \"{name}\" is not defined by any <default>{}",
                did_you_mean(name, self.by_name.keys().copied())
            ))
        })
    }

    /// The class of `node` given the class its enclosing body passes down (`inherited`): its
    /// `class` attribute, else `inherited`.
    pub fn of(&self, node: &Node, inherited: usize) -> Result<usize, Problem> {
        match node.attr("class") {
            Some(c) => self.find(c, node),
            None => Ok(inherited),
        }
    }

    /// The attributes of `node` with those of its class `class` behind them.
    pub fn attrs<'b>(&'b self, node: &'b Node, class: usize) -> Attrs<'b> {
        let mut chain = Vec::new();
        let mut at = Some(class);
        while let Some(c) = at {
            if let Some(d) = self.classes[c].kinds.get(node.name.as_str()) {
                chain.push(*d);
            }
            at = self.classes[c].parent;
        }
        Attrs { node, chain }
    }
}

impl<'a> Classes<'a> {
    /// The default elements of any of the element kinds `kinds` of class `class` and the
    /// classes above it, nearest class first and, within a class, the later element first (the
    /// order in which an attribute is looked up). MuJoCo's actuator elements (`general`,
    /// `motor`, `position`, …) all write one actuator default per class.
    pub fn defaults_of(&self, class: usize, kinds: &[&str]) -> Vec<&'a Node> {
        let mut out = Vec::new();
        let mut at = Some(class);
        while let Some(c) = at {
            let mut own: Vec<&Node> = kinds
                .iter()
                .filter_map(|k| self.classes[c].kinds.get(k).copied())
                .collect();
            own.sort_by_key(|n| std::cmp::Reverse(n.line));
            out.extend(own);
            at = self.classes[c].parent;
        }
        out
    }
}

/// An element's attributes, its class's defaults behind them.
#[derive(Debug)]
pub(super) struct Attrs<'b> {
    /// The element itself.
    pub node: &'b Node,
    /// Its class's default elements, nearest first.
    chain: Vec<&'b Node>,
}

impl<'b> Attrs<'b> {
    /// The attributes of `node` with the default elements `chain` (nearest first) behind them.
    pub fn with_chain(node: &'b Node, chain: Vec<&'b Node>) -> Self {
        Attrs { node, chain }
    }

    /// The default elements behind the element, nearest first.
    pub fn chain(&self) -> &[&'b Node] {
        &self.chain
    }

    /// The attributes of `node` alone (an element that takes no defaults).
    pub fn own(node: &'b Node) -> Self {
        Attrs {
            node,
            chain: Vec::new(),
        }
    }

    /// The value of `key` and the element that gives it (the element or a default).
    pub fn get(&self, key: &str) -> Option<(&'b str, &'b Node)> {
        std::iter::once(self.node)
            .chain(self.chain.iter().copied())
            .find_map(|n| n.attr(key).map(|v| (v, n)))
    }

    /// The value of `key`.
    pub fn text(&self, key: &str) -> Option<&'b str> {
        self.get(key).map(|(v, _)| v)
    }

    /// The element whose orientation attributes count (the element's own if it gives any,
    /// else the nearest default that does).
    pub fn orientation_source(&self) -> &'b Node {
        std::iter::once(self.node)
            .chain(self.chain.iter().copied())
            .find(|n| ORIENTATIONS.iter().any(|k| n.attr(k).is_some()))
            .unwrap_or(self.node)
    }

    /// The numbers of `key` (`None` when absent): `n` of them, or between `min` and `n` when
    /// `min < n` (MuJoCo fills the rest from its defaults).
    pub fn numbers(&self, key: &str, min: usize, n: usize) -> Result<Option<Vec<f64>>, Problem> {
        match self.get(key) {
            None => Ok(None),
            Some((text, from)) => numbers_of(text, key, min, n, self.node, from).map(Some),
        }
    }

    /// One number (`default` when absent).
    pub fn number(&self, key: &str, default: f64) -> Result<f64, Problem> {
        Ok(self.numbers(key, 1, 1)?.map_or(default, |v| v[0]))
    }

    /// `N` numbers (`default` when absent).
    pub fn array<const N: usize>(&self, key: &str, default: [f64; N]) -> Result<[f64; N], Problem> {
        Ok(self
            .numbers(key, N, N)?
            .map_or(default, |v| std::array::from_fn(|i| v[i])))
    }

    /// A keyword among `allowed` (`default` when absent).
    pub fn keyword(
        &self,
        key: &str,
        allowed: &[&'b str],
        default: &'b str,
    ) -> Result<&'b str, Problem> {
        match self.get(key) {
            None => Ok(default),
            Some((v, from)) => allowed.iter().copied().find(|a| *a == v).ok_or_else(|| {
                problem_at(
                    self.node,
                    from,
                    format!("{key}=\"{v}\": expected one of {}", allowed.join(", ")),
                )
            }),
        }
    }
}

/// A problem at `node` about a value that `from` (the node or one of its defaults) gives.
fn problem_at(node: &Node, from: &Node, message: String) -> Problem {
    if std::ptr::eq(node, from) {
        node.problem(message)
    } else {
        node.problem(format!("{message} (from the default at {})", from.at()))
    }
}

/// The numbers of `text` (attribute `key` of `node`, given by `from`): between `min` and `n`
/// finite numbers.
pub(super) fn numbers_of(
    text: &str,
    key: &str,
    min: usize,
    n: usize,
    node: &Node,
    from: &Node,
) -> Result<Vec<f64>, Problem> {
    let mut out = Vec::new();
    for word in text.split_whitespace() {
        match word.parse::<f64>() {
            Ok(x) if x.is_finite() => out.push(x),
            _ => {
                return Err(problem_at(
                    node,
                    from,
                    format!("{key}=\"{text}\": \"{word}\" is not a finite number"),
                ))
            }
        }
    }
    if out.len() < min || out.len() > n {
        let want = if min == n {
            format!("{n}")
        } else {
            format!("{min} to {n}")
        };
        return Err(problem_at(
            node,
            from,
            format!(
                "{key}=\"{text}\": expected {want} numbers, found {}",
                out.len()
            ),
        ));
    }
    Ok(out)
}
