//! `simulate --outputs PATTERN[,PATTERN]`: which output columns to write. A pattern is a glob
//! on variable names: `*` matches any run of characters, `?` one character, everything else
//! itself (brackets too: `body.link1.R[1,2]` is a plain name). Patterns are separated by
//! commas outside brackets, so `body.*.R[1,1],system.*` is two patterns.

use triad::variables::Variable;

/// Splits `--outputs` values into patterns at commas outside `[...]`.
pub fn patterns(values: &[String]) -> Vec<String> {
    let mut out = Vec::new();
    for v in values {
        let (mut depth, mut cur) = (0i32, String::new());
        for c in v.chars() {
            match c {
                '[' => depth += 1,
                ']' => depth -= 1,
                ',' if depth <= 0 => {
                    out.push(std::mem::take(&mut cur));
                    continue;
                }
                _ => {}
            }
            cur.push(c);
        }
        out.push(cur);
    }
    out.into_iter()
        .map(|p| p.trim().to_string())
        .filter(|p| !p.is_empty())
        .collect()
}

/// Whether `name` matches the glob `pattern`.
pub fn matches(pattern: &str, name: &str) -> bool {
    let (p, n): (Vec<char>, Vec<char>) = (pattern.chars().collect(), name.chars().collect());
    // iterative glob with one backtracking point per star
    let (mut i, mut j, mut star, mut mark) = (0, 0, None, 0);
    while j < n.len() {
        if i < p.len() && (p[i] == '?' || p[i] == n[j]) {
            i += 1;
            j += 1;
        } else if i < p.len() && p[i] == '*' {
            star = Some(i);
            mark = j;
            i += 1;
        } else if let Some(s) = star {
            i = s + 1;
            mark += 1;
            j = mark;
        } else {
            return false;
        }
    }
    p[i..].iter().all(|&c| c == '*')
}

/// Indices into `outputs` of the columns to write, in table order; every pattern must match
/// at least one output.
pub fn select(outputs: &[&Variable], patterns: &[String]) -> Result<Vec<usize>, String> {
    if patterns.is_empty() {
        return Ok((0..outputs.len()).collect());
    }
    let unmatched: Vec<&String> = patterns
        .iter()
        .filter(|p| !outputs.iter().any(|v| matches(p, &v.name)))
        .collect();
    if !unmatched.is_empty() {
        let list: Vec<String> = unmatched.iter().map(|p| format!("\"{p}\"")).collect();
        return Err(format!(
            "--outputs: {} matches no output variable (see `triad describe MODEL`)",
            list.join(", ")
        ));
    }
    Ok((0..outputs.len())
        .filter(|&k| patterns.iter().any(|p| matches(p, &outputs[k].name)))
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn globs_and_splitting() {
        assert!(matches("body.*.r[1]", "body.link1.r[1]"));
        assert!(!matches("body.*.r[1]", "body.link1.r[2]"));
        assert!(matches("joint.*", "joint.elbow.qd"));
        assert!(matches("*.q", "joint.elbow.q"));
        assert!(!matches("*.q", "joint.elbow.qd"));
        assert!(matches("body.link?.R[1,2]", "body.link2.R[1,2]"));
        assert!(matches("*", ""));
        assert!(!matches("a", ""));
        assert_eq!(
            patterns(&["body.*.R[1,1],system.*".into(), " joint.*.q ".into()]),
            vec!["body.*.R[1,1]", "system.*", "joint.*.q"]
        );
    }
}
