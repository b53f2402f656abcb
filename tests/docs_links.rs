//! The documentation's links hold: in README.md, ARCHITECTURE.md, BENCHMARKS.md and every
//! `docs/guide/*.md`, each relative Markdown link `[text](path)`, `[text](path#anchor)`,
//! same-file `[text](#anchor)`, image `![alt](path)` and reference definition `[id]: path`
//! points to an existing file, and each `#anchor` matches a heading of its target under
//! GitHub's slug rule (lowercase; characters other than letters, digits, spaces, hyphens and
//! underscores removed, non-ASCII letters kept; spaces to hyphens; a repeated slug gets `-1`,
//! `-2`, ...). Links to `http://`, `https://` and `mailto:` are not checked, nor anything in
//! fenced code blocks or inline code. README.md stays at most 12 000 bytes: the rest belongs in
//! the guide. Every failure names the file, the line and the link.

use std::collections::{HashMap, HashSet};
use std::fs;
use std::path::{Path, PathBuf};

/// README's size limit, bytes.
const README_MAX: usize = 12_000;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The checked files: the three root pages and every chapter of the guide.
fn documents() -> Vec<PathBuf> {
    let root = root();
    let mut files: Vec<PathBuf> = ["README.md", "ARCHITECTURE.md", "BENCHMARKS.md"]
        .iter()
        .map(|f| root.join(f))
        .collect();
    let guide = root.join("docs/guide");
    let mut chapters: Vec<PathBuf> = fs::read_dir(&guide)
        .unwrap_or_else(|e| panic!("{}: {e}", guide.display()))
        .map(|entry| entry.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "md"))
        .collect();
    chapters.sort();
    files.extend(chapters);
    files
}

/// A fence opening or closing a code block: its character and length.
fn fence(line: &str) -> Option<(char, usize)> {
    let trimmed = line.trim_start_matches(' ');
    if line.len() - trimmed.len() > 3 {
        return None;
    }
    let c = trimmed.chars().next()?;
    if c != '`' && c != '~' {
        return None;
    }
    let n = trimmed.chars().take_while(|&x| x == c).count();
    (n >= 3).then_some((c, n))
}

/// The lines of `text` outside fenced code blocks, with their 1-based numbers.
fn prose_lines(text: &str) -> Vec<(usize, &str)> {
    let mut open: Option<(char, usize)> = None;
    let mut lines = Vec::new();
    for (i, line) in text.lines().enumerate() {
        match (open, fence(line)) {
            (None, Some(f)) => open = Some(f),
            (Some((c, n)), Some((c2, n2))) if c == c2 && n2 >= n => open = None,
            (None, None) => lines.push((i + 1, line)),
            _ => {}
        }
    }
    lines
}

/// `line` with its inline code spans (`` `...` ``, ``` ``...`` ```) blanked out.
fn without_code_spans(line: &str) -> String {
    let chars: Vec<char> = line.chars().collect();
    let mut out = String::with_capacity(line.len());
    let mut i = 0;
    while i < chars.len() {
        if chars[i] != '`' {
            out.push(chars[i]);
            i += 1;
            continue;
        }
        let n = chars[i..].iter().take_while(|&&c| c == '`').count();
        // the closing run: exactly n backticks
        let mut j = i + n;
        let mut close = None;
        while j < chars.len() {
            if chars[j] == '`' {
                let m = chars[j..].iter().take_while(|&&c| c == '`').count();
                if m == n {
                    close = Some(j + m);
                    break;
                }
                j += m;
            } else {
                j += 1;
            }
        }
        match close {
            Some(end) => {
                out.push(' ');
                i = end;
            }
            None => {
                out.extend(&chars[i..i + n]);
                i += n;
            }
        }
    }
    out
}

/// The link targets of one line of prose: `](target)` of links and images, and `[id]: target`.
fn link_targets(line: &str) -> Vec<String> {
    let line = without_code_spans(line);
    let mut targets = Vec::new();
    let trimmed = line.trim_start();
    if trimmed.starts_with('[') {
        if let Some(end) = trimmed.find("]:") {
            let target = trimmed[end + 2..].split_whitespace().next().unwrap_or("");
            targets.push(target.trim_matches(|c| c == '<' || c == '>').to_string());
        }
    }
    let mut rest = line.as_str();
    while let Some(at) = rest.find("](") {
        let after = &rest[at + 2..];
        // up to the parenthesis closing this one (balanced parentheses inside are allowed)
        let mut depth = 0usize;
        let mut end = None;
        for (k, c) in after.char_indices() {
            match c {
                '(' => depth += 1,
                ')' if depth == 0 => {
                    end = Some(k);
                    break;
                }
                ')' => depth -= 1,
                _ => {}
            }
        }
        let Some(end) = end else { break };
        let inside = after[..end].trim();
        let target = if let Some(stripped) = inside.strip_prefix('<') {
            stripped.split('>').next().unwrap_or("")
        } else {
            // a title follows the destination after a space
            inside.split_whitespace().next().unwrap_or("")
        };
        targets.push(target.to_string());
        rest = &after[end..];
    }
    targets
}

/// `%XX` escapes decoded (a link to `my%20file.md` names `my file.md`).
fn percent_decode(s: &str) -> String {
    let bytes = s.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' && i + 2 < bytes.len() {
            let hex = std::str::from_utf8(&bytes[i + 1..i + 3]).ok();
            if let Some(b) = hex.and_then(|h| u8::from_str_radix(h, 16).ok()) {
                out.push(b);
                i += 3;
                continue;
            }
        }
        out.push(bytes[i]);
        i += 1;
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// GitHub's slug of a heading's text: lowercase, characters other than letters, digits,
/// spaces, hyphens and underscores removed, spaces to hyphens.
fn slug(heading: &str) -> String {
    // a link in a heading contributes its text only
    let mut text = String::new();
    let mut rest = heading;
    while let Some(at) = rest.find("](") {
        text.push_str(&rest[..at]);
        let after = &rest[at + 2..];
        rest = after.find(')').map_or("", |end| &after[end + 1..]);
    }
    text.push_str(rest);
    text.trim()
        .to_lowercase()
        .chars()
        .filter(|&c| c.is_alphanumeric() || c == ' ' || c == '-' || c == '_')
        .map(|c| if c == ' ' { '-' } else { c })
        .collect()
}

/// Every anchor the headings of `text` define, repeated slugs numbered as GitHub does.
fn anchors(text: &str) -> HashSet<String> {
    let mut seen: HashMap<String, usize> = HashMap::new();
    let mut out = HashSet::new();
    let mut add = |heading: &str| {
        let base = slug(heading);
        let mut n = *seen.get(&base).unwrap_or(&0);
        let mut candidate = base.clone();
        while out.contains(&candidate) {
            n += 1;
            candidate = format!("{base}-{n}");
        }
        seen.insert(base, n);
        out.insert(candidate);
    };
    let lines = prose_lines(text);
    for (k, &(number, line)) in lines.iter().enumerate() {
        if let Some(heading) = atx_heading(line) {
            add(&heading);
            continue;
        }
        // a setext heading: a paragraph line underlined by = or -
        let under = line.trim_end();
        let is_underline = under.len() - under.trim_start_matches(' ').len() <= 3
            && !under.trim().is_empty()
            && (under.trim().chars().all(|c| c == '=') || under.trim().chars().all(|c| c == '-'));
        if is_underline && k > 0 {
            let (prev_number, prev) = lines[k - 1];
            let prev_is_text = prev_number + 1 == number
                && !prev.trim().is_empty()
                && atx_heading(prev).is_none()
                && !prev.trim_start().starts_with('|')
                && !prev.trim_start().starts_with("- ")
                && !prev.trim_start().starts_with("* ");
            if prev_is_text {
                add(prev.trim());
            }
        }
    }
    out
}

/// The text of an ATX heading (`## Title ##`), if `line` is one.
fn atx_heading(line: &str) -> Option<String> {
    let trimmed = line.trim_start_matches(' ');
    if line.len() - trimmed.len() > 3 {
        return None;
    }
    let level = trimmed.chars().take_while(|&c| c == '#').count();
    if !(1..=6).contains(&level) {
        return None;
    }
    let rest = &trimmed[level..];
    if !rest.is_empty() && !rest.starts_with(' ') && !rest.starts_with('\t') {
        return None;
    }
    let rest = rest.trim();
    // an optional closing sequence of #s after a space
    let closed = rest.trim_end_matches('#');
    let text = if closed.len() < rest.len() && (closed.is_empty() || closed.ends_with(' ')) {
        closed.trim_end()
    } else {
        rest
    };
    Some(text.to_string())
}

/// The broken links of the Markdown file `path` (its text `text`), each as
/// `file:line: link: what is wrong`.
fn broken_links(path: &Path, text: &str) -> Vec<String> {
    let shown = path
        .strip_prefix(root())
        .unwrap_or(path)
        .display()
        .to_string();
    let dir = path.parent().unwrap();
    let mut cache: HashMap<PathBuf, HashSet<String>> = HashMap::new();
    let mut problems = Vec::new();
    for (number, line) in prose_lines(text) {
        for target in link_targets(line) {
            let lower = target.to_ascii_lowercase();
            if lower.starts_with("http://")
                || lower.starts_with("https://")
                || lower.starts_with("mailto:")
            {
                continue;
            }
            let mut problem = |what: String| {
                problems.push(format!("{shown}:{number}: ({target}): {what}"));
            };
            if target.is_empty() {
                problem("empty link".into());
                continue;
            }
            let (file, anchor) = match target.split_once('#') {
                Some((f, a)) => (f, Some(a)),
                None => (target.as_str(), None),
            };
            let file = percent_decode(file);
            let resolved = if file.is_empty() {
                path.to_path_buf()
            } else if file.starts_with('/') {
                problem("absolute path: write it relative to this file".into());
                continue;
            } else {
                dir.join(&file)
            };
            if !resolved.exists() {
                let looked = resolved.strip_prefix(root()).unwrap_or(&resolved);
                problem(format!("{} does not exist", looked.display()));
                continue;
            }
            let Some(anchor) = anchor else { continue };
            if resolved.extension().is_none_or(|x| x != "md") {
                problem("an anchor into a file that is not Markdown".into());
                continue;
            }
            let anchor = percent_decode(anchor);
            let known = cache
                .entry(resolved.clone())
                .or_insert_with(|| anchors(&fs::read_to_string(&resolved).unwrap_or_default()));
            if !known.contains(&anchor) {
                let mut list: Vec<&String> = known.iter().collect();
                list.sort();
                problem(format!(
                    "no heading of {} has the slug #{anchor} (its slugs: {})",
                    if file.is_empty() { "this file" } else { &file },
                    list.iter()
                        .map(|s| format!("#{s}"))
                        .collect::<Vec<_>>()
                        .join(", ")
                ));
            }
        }
    }
    problems
}

#[test]
fn every_relative_link_and_anchor_resolves() {
    let mut problems = Vec::new();
    for path in documents() {
        let text = fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        problems.extend(broken_links(&path, &text));
    }
    assert!(
        problems.is_empty(),
        "{} broken link(s) in the documentation:\n{}",
        problems.len(),
        problems.join("\n")
    );
}

#[test]
fn readme_stays_short() {
    let path = root().join("README.md");
    let size = fs::metadata(&path).unwrap().len() as usize;
    assert!(
        size <= README_MAX,
        "README.md is {size} bytes (at most {README_MAX}): move the detail into a chapter of docs/guide/"
    );
}

#[test]
fn slugs_follow_githubs_rule() {
    assert_eq!(slug("Work–precision"), "workprecision");
    assert_eq!(slug("What `system.energy` is"), "what-systemenergy-is");
    assert_eq!(
        slug("Shapes from a URDF: `--contacts`"),
        "shapes-from-a-urdf---contacts"
    );
    assert_eq!(
        slug("Mechanics design (decided)"),
        "mechanics-design-decided"
    );
    assert_eq!(slug("Größe und Maß_2"), "größe-und-maß_2");
    assert_eq!(
        slug("See [the guide](docs/guide/README.md)"),
        "see-the-guide"
    );
    let text = "# A\n\n## Notes\n\n```\n## Not a heading\n```\n\n### Notes ###\n\nNotes\n-----\n";
    let found = anchors(text);
    for a in ["a", "notes", "notes-1", "notes-2"] {
        assert!(found.contains(a), "{a} missing from {found:?}");
    }
    assert!(!found.contains("not-a-heading"), "{found:?}");
}

#[test]
fn a_broken_link_is_reported_with_file_and_line() {
    let dir = std::env::temp_dir().join(format!("triad_docs_links_{}", std::process::id()));
    fs::create_dir_all(&dir).unwrap();
    let other = dir.join("other.md");
    fs::write(&other, "# Other page\n\n## A section\n").unwrap();
    let page = dir.join("page.md");
    let text = "# Page\n\
                [fine](other.md#a-section) and [fine too](#page) `[not a link](nowhere.md)`\n\
                ![missing image](missing.png)\n\
                ```\n[in a fence](nowhere.md)\n```\n\
                [bad anchor](other.md#no-such-section) [bad here](#nope) [web](https://x.org/y)\n";
    fs::write(&page, text).unwrap();
    let problems = broken_links(&page, text);
    fs::remove_dir_all(&dir).unwrap();
    assert_eq!(problems.len(), 3, "{problems:#?}");
    assert!(
        problems[0].contains("page.md:3: (missing.png)"),
        "{}",
        problems[0]
    );
    assert!(
        problems[1].contains("page.md:7: (other.md#no-such-section)"),
        "{}",
        problems[1]
    );
    assert!(
        problems[2].contains("page.md:7: (#nope)"),
        "{}",
        problems[2]
    );
}
