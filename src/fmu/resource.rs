//! `fmuResourceLocation` → a directory path (FMI 2.0.4 §2.1.5, RFC 3986 / RFC 8089). Accepts
//! `file:///abs`, `file:/abs`, `file://localhost/abs`, `file://abs` hosts other than localhost
//! are rejected, percent-encoding is decoded, a trailing slash is ignored. Never chops a fixed
//! prefix (fmi.md pitfall 2).

use std::path::PathBuf;

/// Decodes a `file:` URI into a local path.
///
/// # Errors
/// A message for a non-`file` scheme, a remote host, bad percent-encoding or a relative path.
pub fn uri_to_path(uri: &str) -> Result<PathBuf, String> {
    let rest = match uri.split_once(':') {
        Some((scheme, rest)) if scheme.eq_ignore_ascii_case("file") => rest,
        Some((scheme, _)) if scheme.len() > 1 => {
            return Err(format!("unsupported URI scheme '{scheme}' in '{uri}'"))
        }
        _ => return Err(format!("'{uri}' is not a file: URI")),
    };
    // drop query and fragment
    let rest = rest.split(['?', '#']).next().unwrap_or("");
    let path = if let Some(after) = rest.strip_prefix("//") {
        // authority up to the next '/'
        let (host, path) = match after.find('/') {
            Some(i) => (&after[..i], &after[i..]),
            None => (after, ""),
        };
        if !(host.is_empty() || host.eq_ignore_ascii_case("localhost")) {
            return Err(format!("remote host '{host}' in '{uri}' is not supported"));
        }
        path
    } else {
        rest
    };
    if !path.starts_with('/') {
        return Err(format!("'{uri}' does not name an absolute path"));
    }
    let decoded = percent_decode(path)?;
    let trimmed = if decoded.len() > 1 {
        decoded.trim_end_matches('/')
    } else {
        &decoded
    };
    Ok(PathBuf::from(if trimmed.is_empty() {
        "/"
    } else {
        trimmed
    }))
}

fn percent_decode(s: &str) -> Result<String, String> {
    let bytes = s.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' {
            let hex = bytes
                .get(i + 1..i + 3)
                .and_then(|h| std::str::from_utf8(h).ok());
            let v = hex.and_then(|h| u8::from_str_radix(h, 16).ok());
            match v {
                Some(v) => out.push(v),
                None => return Err(format!("bad percent-encoding in '{s}'")),
            }
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    String::from_utf8(out).map_err(|_| format!("'{s}' does not decode to UTF-8"))
}

/// Encodes a local absolute path as `file:///…` (the form fmpy passes), percent-encoding
/// everything except unreserved characters and `/`.
#[must_use]
pub fn path_to_uri(path: &std::path::Path) -> String {
    let mut s = String::from("file://");
    for b in path.to_string_lossy().bytes() {
        if b.is_ascii_alphanumeric() || b"-._~/".contains(&b) {
            s.push(b as char);
        } else {
            s.push_str(&format!("%{b:02X}"));
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_form() {
        let want = PathBuf::from("/tmp/a b/resources");
        for uri in [
            "file:///tmp/a%20b/resources",
            "file:///tmp/a%20b/resources/",
            "file:/tmp/a%20b/resources",
            "file://localhost/tmp/a%20b/resources",
            "FILE://LOCALHOST/tmp/a%20b/resources/",
            "file:/tmp/a b/resources",
        ] {
            assert_eq!(uri_to_path(uri).unwrap(), want, "{uri}");
        }
        assert!(uri_to_path("http://x/y").is_err());
        assert!(uri_to_path("file://server/share").is_err());
        assert!(uri_to_path("file:rel/path").is_err());
        assert!(uri_to_path("file:///a%2").is_err());
        assert_eq!(uri_to_path(&path_to_uri(&want)).unwrap(), want);
    }
}
