//! The source tree has no import cycles, and the mechanics core's layers depend one way.
//!
//! Every `.rs` file under `src/` is read as text. A file *uses* another when one of its `use`
//! lines or inline paths (`crate::…`, `super::…`, `self::…`, or a path through one of its own
//! child modules) names an item of a module that lives in the other file: the path is followed
//! module by module as far as the module tree goes, and the file of the last module reached is
//! the target (`crate::mechanics::model::Model` → `src/mechanics/model/…`). Declaring a child
//! (`mod x;`) is not a use. Comments and string literals are skipped.
//!
//! Checked:
//! - no strongly connected set of two or more files (a cycle of any length);
//! - inside `src/mechanics/`, files of a layer use only their own layer and the layers below it
//!   (`LAYERS`, lowest first), and the core uses nothing of the crate outside `mechanics` and
//!   `math` (it knows nothing of FMI, XML, zip or the spec).
//!
//! Run alone: `cargo test --test import_cycles`. A failure lists each cycle with the lines that
//! make it.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The mechanics layers, lowest first: a file of layer k may use layers 0..=k only. Files
/// directly in `src/mechanics/` (the facade `mod.rs`) sit above every layer.
const LAYERS: &[&str] = &["linalg", "model", "step", "run"];

/// A module of a crate: its path from the crate root and the file that holds it.
struct Module {
    file: PathBuf,
}

/// One use of a module in another file.
#[derive(Clone)]
struct Use {
    from: PathBuf,
    to: PathBuf,
    line: usize,
    text: String,
}

#[derive(Clone, Debug, PartialEq)]
enum Tok {
    Ident(String),
    Sep,   // ::
    Open,  // {
    Close, // }
    Semi,
    Comma,
    Star,
    Other,
}

/// Tokens of Rust source with their line numbers; comments, strings and char literals dropped.
fn tokens(src: &str) -> Vec<(Tok, usize)> {
    let b = src.as_bytes();
    let mut out = Vec::new();
    let (mut i, mut line) = (0, 1);
    while i < b.len() {
        let c = b[i];
        if c == b'\n' {
            line += 1;
            i += 1;
        } else if c == b'/' && b.get(i + 1) == Some(&b'/') {
            while i < b.len() && b[i] != b'\n' {
                i += 1;
            }
        } else if c == b'/' && b.get(i + 1) == Some(&b'*') {
            let mut depth = 0;
            while i < b.len() {
                if b[i] == b'/' && b.get(i + 1) == Some(&b'*') {
                    depth += 1;
                    i += 2;
                } else if b[i] == b'*' && b.get(i + 1) == Some(&b'/') {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    line += usize::from(b[i] == b'\n');
                    i += 1;
                }
            }
        } else if c == b'r' && matches!(b.get(i + 1), Some(b'"') | Some(b'#')) && {
            let mut j = i + 1;
            while b.get(j) == Some(&b'#') {
                j += 1;
            }
            b.get(j) == Some(&b'"')
        } {
            // raw string r#"…"#
            let mut hashes = 0;
            i += 1;
            while b[i] == b'#' {
                hashes += 1;
                i += 1;
            }
            i += 1;
            loop {
                if i >= b.len() {
                    break;
                }
                if b[i] == b'"'
                    && b[i + 1..]
                        .iter()
                        .take(hashes)
                        .filter(|&&x| x == b'#')
                        .count()
                        == hashes
                {
                    i += 1 + hashes;
                    break;
                }
                line += usize::from(b[i] == b'\n');
                i += 1;
            }
        } else if c == b'"' {
            i += 1;
            while i < b.len() && b[i] != b'"' {
                if b[i] == b'\\' {
                    i += 1;
                }
                line += usize::from(b.get(i) == Some(&b'\n'));
                i += 1;
            }
            i += 1;
        } else if c == b'\'' {
            // a char literal ('x', '\n', '\''), else a lifetime
            if b.get(i + 1) == Some(&b'\\') {
                i += 2;
                while i < b.len() && b[i] != b'\'' {
                    i += 1;
                }
                i += 1;
            } else if b.get(i + 2) == Some(&b'\'') {
                i += 3;
            } else {
                let s = std::str::from_utf8(&b[i + 1..]).unwrap_or("");
                let n = s.chars().next().map_or(1, char::len_utf8);
                if b.get(i + 1 + n) == Some(&b'\'') {
                    i += 2 + n;
                } else {
                    i += 1;
                }
            }
        } else if c.is_ascii_alphabetic() || c == b'_' {
            let start = i;
            while i < b.len() && (b[i].is_ascii_alphanumeric() || b[i] == b'_') {
                i += 1;
            }
            out.push((Tok::Ident(src[start..i].to_string()), line));
        } else if c == b':' && b.get(i + 1) == Some(&b':') {
            out.push((Tok::Sep, line));
            i += 2;
        } else {
            let t = match c {
                b'{' => Tok::Open,
                b'}' => Tok::Close,
                b';' => Tok::Semi,
                b',' => Tok::Comma,
                b'*' => Tok::Star,
                _ => Tok::Other,
            };
            if !c.is_ascii_whitespace() {
                out.push((t, line));
            }
            i += if c.is_ascii() {
                1
            } else {
                src[i..].chars().next().map_or(1, char::len_utf8)
            };
        }
    }
    out
}

/// `#[path = "…"]` values by the line of the attribute.
fn path_attrs(src: &str) -> Vec<(usize, String)> {
    src.lines()
        .enumerate()
        .filter_map(|(k, l)| {
            let l = l.trim();
            let rest = l.strip_prefix("#[path")?;
            let q1 = rest.find('"')?;
            let q2 = rest[q1 + 1..].find('"')? + q1 + 1;
            Some((k + 1, rest[q1 + 1..q2].to_string()))
        })
        .collect()
}

/// The module a token of a file lies in: the file's own module, or an inline `mod x { … }`
/// inside it (tracked by brace depth).
struct Scopes {
    root: Vec<String>,
    /// Open inline modules: (module path, brace depth at which it closes).
    stack: Vec<(Vec<String>, usize)>,
    depth: usize,
}

impl Scopes {
    fn new(root: &[String]) -> Self {
        Self {
            root: root.to_vec(),
            stack: Vec::new(),
            depth: 0,
        }
    }

    /// The module of the current token.
    fn here(&self) -> Vec<String> {
        self.stack
            .last()
            .map_or_else(|| self.root.clone(), |(p, _)| p.clone())
    }

    /// Whether the current token is outside every inline module.
    fn at_top(&self) -> bool {
        self.stack.is_empty()
    }

    /// Takes token `k` into account; returns the path of the inline module it opens, if any.
    fn step(&mut self, toks: &[(Tok, usize)], k: usize) -> Option<Vec<String>> {
        match &toks[k].0 {
            Tok::Open => self.depth += 1,
            Tok::Close => {
                self.depth = self.depth.saturating_sub(1);
                if self.stack.last().is_some_and(|(_, d)| *d == self.depth) {
                    self.stack.pop();
                }
            }
            Tok::Ident(w) if w == "mod" => {
                if let (Some((Tok::Ident(m), _)), Some((Tok::Open, _))) =
                    (toks.get(k + 1), toks.get(k + 2))
                {
                    let mut p = self.here();
                    p.push(m.clone());
                    self.stack.push((p.clone(), self.depth));
                    return Some(p);
                }
            }
            _ => {}
        }
        None
    }
}

/// Reads the module tree of the crate rooted at `root_file`.
fn module_tree(root_file: &Path) -> BTreeMap<Vec<String>, Module> {
    let mut mods = BTreeMap::new();
    let mut todo = vec![(Vec::<String>::new(), root_file.to_path_buf())];
    while let Some((path, file)) = todo.pop() {
        let src =
            std::fs::read_to_string(&file).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
        let toks = tokens(&src);
        let attrs = path_attrs(&src);
        let name = file.file_stem().unwrap().to_string_lossy().into_owned();
        let dir = file.parent().unwrap().to_path_buf();
        let mod_dir = if ["mod", "lib", "main"].contains(&name.as_str()) {
            dir.clone()
        } else {
            dir.join(&name)
        };
        mods.insert(path.clone(), Module { file: file.clone() });
        let mut scopes = Scopes::new(&path);
        for k in 0..toks.len() {
            if let Some(inline) = scopes.step(&toks, k) {
                mods.insert(inline, Module { file: file.clone() });
                continue;
            }
            let (Tok::Ident(w), Some((Tok::Ident(m), line)), Some((Tok::Semi, _))) =
                (&toks[k].0, toks.get(k + 1), toks.get(k + 2))
            else {
                continue;
            };
            if w != "mod" || !scopes.at_top() {
                continue;
            }
            let mut here = path.clone();
            here.push(m.clone());
            let attr = attrs
                .iter()
                .rev()
                .find(|(l, _)| *l < *line && *line - *l <= 2)
                .map(|(_, p)| p.clone());
            let child = match attr {
                Some(p) => dir.join(p),
                None => {
                    let a = mod_dir.join(format!("{m}.rs"));
                    if a.exists() {
                        a
                    } else {
                        mod_dir.join(m).join("mod.rs")
                    }
                }
            };
            todo.push((here, child));
        }
    }
    mods
}

/// Expands a `use` tree starting at `toks[k]` into its paths; returns the index after `;`.
fn use_paths(
    toks: &[(Tok, usize)],
    mut k: usize,
    prefix: Vec<String>,
    out: &mut Vec<Vec<String>>,
) -> usize {
    let mut cur = prefix.clone();
    while k < toks.len() {
        match &toks[k].0 {
            Tok::Ident(w) if w == "as" => k += 1, // skip the alias
            Tok::Ident(w) => cur.push(w.clone()),
            Tok::Sep | Tok::Star | Tok::Other => {}
            Tok::Open => {
                k = use_paths(toks, k + 1, cur.clone(), out);
                cur = prefix.clone();
                // after a group: `,` or `}` or `;`
                match toks.get(k).map(|t| &t.0) {
                    Some(Tok::Close) => return k + 1,
                    Some(Tok::Semi) => return k + 1,
                    _ => {}
                }
                continue;
            }
            Tok::Comma => {
                if cur.len() > prefix.len() {
                    out.push(cur.clone());
                }
                cur = prefix.clone();
            }
            Tok::Close | Tok::Semi => {
                if cur.len() > prefix.len() || cur.len() == prefix.len() && !prefix.is_empty() {
                    out.push(cur.clone());
                }
                return k + 1;
            }
        }
        k += 1;
    }
    k
}

/// The module a path names, as far as the module tree goes, seen from module `here`.
fn resolve<'a>(
    mods: &'a BTreeMap<Vec<String>, Module>,
    lib: Option<&'a BTreeMap<Vec<String>, Module>>,
    here: &[String],
    path: &[String],
) -> Option<&'a Module> {
    let (mut tree, mut base, mut rest) = (mods, here.to_vec(), path);
    match path.first().map(String::as_str) {
        Some("crate") => {
            base.clear();
            rest = &path[1..];
        }
        Some("self") => rest = &path[1..],
        Some("super") => {
            while rest.first().map(String::as_str) == Some("super") {
                base.pop()?;
                rest = &rest[1..];
            }
        }
        Some("triad") if lib.is_some() => {
            tree = lib.unwrap();
            base.clear();
            rest = &path[1..];
        }
        Some(first) => {
            let mut child = here.to_vec();
            child.push(first.to_string());
            if !mods.contains_key(&child) {
                return None; // another crate, a local item or a type
            }
        }
        None => return None,
    }
    for seg in rest {
        let mut next = base.clone();
        next.push(seg.clone());
        if tree.contains_key(&next) {
            base = next;
        } else {
            break;
        }
    }
    tree.get(&base)
}

/// Every use between two different files of the crate rooted at `root_file`.
fn uses(
    root_file: &Path,
    lib: Option<&BTreeMap<Vec<String>, Module>>,
) -> (BTreeMap<Vec<String>, Module>, Vec<Use>) {
    let mods = module_tree(root_file);
    let mut found = Vec::new();
    let files: BTreeMap<&PathBuf, &Vec<String>> = mods
        .iter()
        .filter(|(p, m)| {
            mods.iter()
                .all(|(q, n)| n.file != m.file || q.len() >= p.len())
        })
        .map(|(p, m)| (&m.file, p))
        .collect();
    for (file, fpath) in files {
        let src = std::fs::read_to_string(file).unwrap();
        let toks = tokens(&src);
        let mut scopes = Scopes::new(fpath);
        let mut k = 0;
        while k < toks.len() {
            let here = scopes.here();
            let line = toks[k].1;
            let mut record = |p: &[String]| {
                if let Some(m) = resolve(&mods, lib, &here, p) {
                    found.push(Use {
                        from: file.clone(),
                        to: m.file.clone(),
                        line,
                        text: p.join("::"),
                    });
                }
            };
            if scopes.step(&toks, k).is_some() || matches!(toks[k].0, Tok::Open | Tok::Close) {
                k += 1;
                continue;
            }
            match &toks[k].0 {
                Tok::Ident(w) if w == "use" => {
                    let mut paths = Vec::new();
                    let end = use_paths(&toks, k + 1, Vec::new(), &mut paths);
                    for p in paths {
                        record(&p);
                    }
                    k = end;
                    continue;
                }
                Tok::Ident(first) if toks.get(k + 1).map(|t| &t.0) == Some(&Tok::Sep) => {
                    // an inline path a::b::c (not preceded by `::`)
                    let after_sep = k > 0 && toks[k - 1].0 == Tok::Sep;
                    if !after_sep {
                        let mut p = vec![first.clone()];
                        let mut j = k + 1;
                        while toks.get(j).map(|t| &t.0) == Some(&Tok::Sep) {
                            match toks.get(j + 1).map(|t| &t.0) {
                                Some(Tok::Ident(s)) => p.push(s.clone()),
                                _ => break,
                            }
                            j += 2;
                        }
                        record(&p);
                        k = j;
                        continue;
                    }
                }
                _ => {}
            }
            k += 1;
        }
    }
    found.retain(|u| u.from != u.to);
    (mods, found)
}

/// Strongly connected sets of two or more files (Tarjan).
fn cycles(edges: &BTreeMap<PathBuf, BTreeSet<PathBuf>>) -> Vec<Vec<PathBuf>> {
    struct T<'a> {
        edges: &'a BTreeMap<PathBuf, BTreeSet<PathBuf>>,
        index: BTreeMap<&'a PathBuf, usize>,
        low: BTreeMap<&'a PathBuf, usize>,
        on: BTreeSet<&'a PathBuf>,
        stack: Vec<&'a PathBuf>,
        out: Vec<Vec<PathBuf>>,
    }
    fn visit<'a>(t: &mut T<'a>, v: &'a PathBuf) {
        let n = t.index.len();
        t.index.insert(v, n);
        t.low.insert(v, n);
        t.stack.push(v);
        t.on.insert(v);
        for w in t.edges.get(v).into_iter().flatten() {
            if !t.index.contains_key(w) {
                visit(t, w);
                let lw = t.low[w];
                let lv = t.low.get_mut(v).unwrap();
                *lv = (*lv).min(lw);
            } else if t.on.contains(w) {
                let iw = t.index[w];
                let lv = t.low.get_mut(v).unwrap();
                *lv = (*lv).min(iw);
            }
        }
        if t.low[v] == t.index[v] {
            let mut scc = Vec::new();
            loop {
                let w = t.stack.pop().unwrap();
                t.on.remove(w);
                scc.push(w.clone());
                if w == v {
                    break;
                }
            }
            if scc.len() > 1 {
                scc.sort();
                t.out.push(scc);
            }
        }
    }
    let mut t = T {
        edges,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        on: BTreeSet::new(),
        stack: Vec::new(),
        out: Vec::new(),
    };
    for v in edges.keys() {
        if !t.index.contains_key(v) {
            visit(&mut t, v);
        }
    }
    t.out
}

fn all_uses() -> Vec<Use> {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let (lib, mut found) = uses(&src.join("lib.rs"), None);
    let (_, bin) = uses(&src.join("main.rs"), Some(&lib));
    found.extend(bin);
    found
}

fn rel(p: &Path) -> String {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    p.strip_prefix(root).unwrap_or(p).display().to_string()
}

#[test]
fn no_two_files_use_each_other_in_a_cycle() {
    let found = all_uses();
    let mut edges: BTreeMap<PathBuf, BTreeSet<PathBuf>> = BTreeMap::new();
    for u in &found {
        edges
            .entry(u.from.clone())
            .or_default()
            .insert(u.to.clone());
    }
    let sccs = cycles(&edges);
    let mut report = String::new();
    for scc in &sccs {
        report.push_str(&format!("\ncycle of {} files:\n", scc.len()));
        for u in found
            .iter()
            .filter(|u| scc.contains(&u.from) && scc.contains(&u.to))
        {
            report.push_str(&format!(
                "  {}:{} uses {} ({})\n",
                rel(&u.from),
                u.line,
                rel(&u.to),
                u.text
            ));
        }
    }
    assert!(sccs.is_empty(), "{} import cycle(s):{report}", sccs.len());
}

/// The layer of a file under `src/mechanics/`: its index in `LAYERS`, `LAYERS.len()` for the
/// facade; `None` outside the core.
fn layer(p: &Path) -> Option<usize> {
    let core = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/mechanics");
    let rest = p.strip_prefix(&core).ok()?;
    let first = rest
        .components()
        .next()?
        .as_os_str()
        .to_string_lossy()
        .into_owned();
    Some(
        LAYERS
            .iter()
            .position(|l| *l == first)
            .unwrap_or(LAYERS.len()),
    )
}

#[test]
fn mechanics_layers_depend_one_way_and_on_nothing_outside() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let core = root.join("mechanics");
    for l in LAYERS {
        assert!(
            core.join(l).join("mod.rs").exists(),
            "layer folder src/mechanics/{l}/mod.rs is missing"
        );
    }
    let mut bad = Vec::new();
    for u in all_uses() {
        let Some(from) = layer(&u.from) else { continue };
        match layer(&u.to) {
            Some(to) if to > from => bad.push(format!(
                "{}:{} ({}) uses {} ({}): {}",
                rel(&u.from),
                u.line,
                LAYERS[from],
                rel(&u.to),
                LAYERS.get(to).copied().unwrap_or("the facade"),
                u.text
            )),
            Some(_) => {}
            None if u.to == root.join("math.rs") => {}
            None => bad.push(format!(
                "{}:{} uses {} outside the core: {}",
                rel(&u.from),
                u.line,
                rel(&u.to),
                u.text
            )),
        }
    }
    assert!(
        bad.is_empty(),
        "uses against the layer order:\n{}",
        bad.join("\n")
    );
}

#[test]
fn the_reader_sees_uses_of_every_kind() {
    // the checker itself: a use line with a group, an alias, a super chain, an inline
    // crate path and a child-module path are all found
    let found = all_uses();
    let lib = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/lib.rs");
    assert!(found.len() > 200, "only {} uses found", found.len());
    assert!(found.iter().all(|u| u.from != lib || u.text.is_empty()));
    assert!(found.iter().any(|u| u.text.starts_with("super::super::")));
    assert!(found.iter().any(|u| u.text.starts_with("crate::")));
    assert!(found.iter().any(|u| u.text.starts_with("triad::")));
    let toks =
        tokens("use a::{b::{C, D as E}, f}; // use x::y;\nlet s = \"crate::z\"; let c = '\"';");
    let mut paths = Vec::new();
    use_paths(&toks, 1, Vec::new(), &mut paths);
    assert_eq!(
        paths,
        vec![vec!["a", "b", "C"], vec!["a", "b", "D"], vec!["a", "f"]]
    );
    assert!(!toks
        .iter()
        .any(|(t, _)| *t == Tok::Ident("z".into()) || *t == Tok::Ident("x".into())));
}
