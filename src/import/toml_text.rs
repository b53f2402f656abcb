//! The TOML text of an imported spec: the spec's own serialisation with numbers in their
//! shortest round-trip form (`1e-10` rather than `0.0000000001`), so reading it back gives the
//! same spec and the same FMU.

/// `line` with every float written in the shorter of its two round-trip forms (`1e-10`, not
/// `0.0000000001`); lines holding strings are left as they are.
pub(crate) fn shortest_numbers(line: &str) -> String {
    if line.contains(['"', '\'']) || !line.contains('=') {
        return line.to_string();
    }
    let mut out = String::with_capacity(line.len());
    let mut token = String::new();
    let flush = |token: &mut String, out: &mut String| {
        let short = token
            .parse::<f64>()
            .ok()
            .filter(|_| token.contains('.'))
            .map(|x| format!("{x:?}"))
            .filter(|s| s.len() < token.len());
        out.push_str(short.as_deref().unwrap_or(token));
        token.clear();
    };
    for c in line.chars() {
        if c.is_ascii_alphanumeric() || matches!(c, '.' | '-' | '+' | '_') {
            token.push(c);
        } else {
            flush(&mut token, &mut out);
            out.push(c);
        }
    }
    flush(&mut token, &mut out);
    out
}
