//! `fmuResourceLocation` → a directory path (FMI 2.0.4 §2.1.5, RFC 3986 / RFC 8089), in every
//! form importers pass:
//!
//! - `file:///abs/dir`, `file:/abs/dir`, `file://localhost/abs/dir` (any case of `file` and
//!   `localhost`), with or without a trailing slash, query and fragment ignored;
//! - Windows drives: `file:///C:/dir/resources`, `file:/C:/dir`, `file://localhost/C:/dir`,
//!   `file://C:/dir`, `file:C:/dir`, the old `C|` form, and backslashes inside the URI;
//! - percent-encoding (`%20`, UTF-8 sequences such as `%C3%A9`), decoded once;
//! - UNC: `file://server/share/dir` and `file:////server/share/dir` become `\\server\share\dir`
//!   on Windows; other systems refuse a remote host with a message;
//! - a plain absolute path, as some tools pass it (`C:\dir\resources`, `\\server\share`,
//!   `/abs/dir`): taken as it is, not percent-decoded.
//!
//! The parser is a pure function of the string and the [`PathStyle`] of the target system, so
//! the Windows mapping is unit-tested on every system. It never chops a fixed prefix (fmi.md
//! pitfall 2).

use std::path::PathBuf;

/// The path conventions a location is mapped to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PathStyle {
    /// `/`-separated absolute paths (Linux, macOS).
    Posix,
    /// Drive letters, `\` separators and UNC shares.
    Windows,
}

impl PathStyle {
    /// The style of the system this library runs on.
    pub const HOST: Self = if cfg!(windows) {
        Self::Windows
    } else {
        Self::Posix
    };
}

/// Decodes a resource location into a local path of this system ([`PathStyle::HOST`]).
///
/// # Errors
/// As [`location_to_path`].
pub fn uri_to_path(uri: &str) -> Result<PathBuf, String> {
    location_to_path(uri, PathStyle::HOST).map(PathBuf::from)
}

/// Decodes a resource location (a `file:` URI or a plain absolute path) into a path in the
/// conventions of `style`, without a trailing separator (but for a root such as `/` or `C:\`).
///
/// # Errors
/// A message naming the location for: an empty location, a scheme other than `file`, a
/// remote host on a system without UNC paths, a relative path, bad percent-encoding, bytes
/// that are not UTF-8 or a NUL byte.
pub fn location_to_path(location: &str, style: PathStyle) -> Result<String, String> {
    let fail = |why: &str| Err(format!("'{location}': {why}"));
    if location.is_empty() {
        return fail("empty resource location");
    }
    if let Some(path) = plain_path(location, style) {
        return Ok(finish(path.to_string(), style));
    }
    let rest = match location.split_once(':') {
        Some((scheme, rest)) if scheme.eq_ignore_ascii_case("file") => rest,
        Some((scheme, _)) if scheme.len() > 1 && is_scheme(scheme) => {
            return fail(&format!(
                "unsupported URI scheme '{scheme}' (expected file:)"
            ))
        }
        _ => return fail("neither a file: URI nor an absolute path"),
    };
    // query and fragment are not part of the path
    let rest = rest.split(['?', '#']).next().unwrap_or("");
    // some Windows tools write backslashes into URIs
    let rest = if style == PathStyle::Windows {
        rest.replace('\\', "/")
    } else {
        rest.to_string()
    };
    let (host, path) = match rest.strip_prefix("//") {
        Some(after) => match after.find('/') {
            Some(i) => (&after[..i], &after[i..]),
            // `file://localhost`: the root
            None => (after, "/"),
        },
        None => ("", rest.as_str()),
    };
    let mut path = percent_decode(path).map_err(|e| format!("'{location}': {e}"))?;
    if path.contains('\0') {
        return fail("contains a NUL byte");
    }
    let mut host = percent_decode(host).map_err(|e| format!("'{location}': {e}"))?;
    if style == PathStyle::Windows && is_drive(&host) {
        // `file://C:/dir`: the drive was written where the host goes
        path = format!("/{host}{path}");
        host.clear();
    } else if style == PathStyle::Windows && host.is_empty() && is_drive(&path) {
        // `file:C:/dir`
        path = format!("/{path}");
    }
    if !(host.is_empty() || host.eq_ignore_ascii_case("localhost")) {
        return match style {
            PathStyle::Windows => Ok(finish(format!("//{host}{path}"), style)),
            PathStyle::Posix => fail(&format!(
                "remote host '{host}' is not supported here (a UNC share is reachable only \
                 on Windows); pass a local path, file:///dir"
            )),
        };
    }
    if !path.starts_with('/') {
        return fail("does not name an absolute path");
    }
    match style {
        PathStyle::Windows => {
            if path.starts_with("//") {
                // `file:////server/share`: a UNC path in the path part
                let share = path.trim_start_matches('/');
                if share.is_empty() {
                    return fail("does not name a directory");
                }
                return Ok(finish(format!("//{share}"), style));
            }
            let bare = &path[1..];
            if is_drive(bare) {
                let drive = bare[..1].to_string();
                return Ok(finish(format!("{drive}:{}", &bare[2..]), style));
            }
            Ok(finish(path, style))
        }
        PathStyle::Posix => Ok(finish(path, style)),
    }
}

/// `location` itself when it is a plain absolute path of `style` (not a URI).
fn plain_path(location: &str, style: PathStyle) -> Option<&str> {
    match style {
        PathStyle::Posix => location.starts_with('/').then_some(location),
        PathStyle::Windows => {
            let b = location.as_bytes();
            let drive = b.len() >= 3
                && b[0].is_ascii_alphabetic()
                && b[1] == b':'
                && (b[2] == b'\\' || b[2] == b'/');
            let unc = location.starts_with("\\\\");
            (drive || unc || location.starts_with('\\')).then_some(location)
        }
    }
}

/// `C:` or `C|` (optionally followed by `/`), the start of a drive path.
fn is_drive(s: &str) -> bool {
    let b = s.as_bytes();
    b.len() >= 2
        && b[0].is_ascii_alphabetic()
        && (b[1] == b':' || b[1] == b'|')
        && (b.len() == 2 || b[2] == b'/')
}

/// An RFC 3986 scheme: a letter, then letters, digits, `+`, `-`, `.`.
fn is_scheme(s: &str) -> bool {
    let mut chars = s.chars();
    chars.next().is_some_and(|c| c.is_ascii_alphabetic())
        && chars.all(|c| c.is_ascii_alphanumeric() || "+-.".contains(c))
}

/// Separators of `style`, no trailing separator but at a root.
fn finish(path: String, style: PathStyle) -> String {
    match style {
        PathStyle::Posix => {
            let t = path.trim_end_matches('/');
            if t.is_empty() {
                "/".into()
            } else {
                t.into()
            }
        }
        PathStyle::Windows => {
            let p = path.replace('/', "\\");
            let t = p.trim_end_matches('\\');
            let b = t.as_bytes();
            if t.is_empty() {
                "\\".into()
            } else if b.len() == 2 && b[1] == b':' {
                format!("{t}\\")
            } else {
                t.into()
            }
        }
    }
}

fn percent_decode(s: &str) -> Result<String, String> {
    let bytes = s.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' {
            let v = bytes
                .get(i + 1..i + 3)
                .and_then(|h| std::str::from_utf8(h).ok())
                .filter(|h| h.bytes().all(|c| c.is_ascii_hexdigit()))
                .and_then(|h| u8::from_str_radix(h, 16).ok());
            match v {
                Some(v) => out.push(v),
                None => return Err(format!("bad percent-encoding at byte {i}")),
            }
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    String::from_utf8(out).map_err(|_| "percent-encoding that does not decode to UTF-8".into())
}

/// Encodes a local absolute path as `file:///…` (the form fmpy passes; on Windows
/// `file:///C:/dir`), percent-encoding everything except unreserved characters and `/`.
#[must_use]
pub fn path_to_uri(path: &std::path::Path) -> String {
    let text = path.to_string_lossy();
    let text = if cfg!(windows) {
        let t = text.replace('\\', "/");
        if t.starts_with("//") {
            t
        } else {
            format!("/{t}")
        }
    } else {
        text.into_owned()
    };
    let mut s = String::from("file://");
    for b in text.bytes() {
        if b.is_ascii_alphanumeric() || b"-._~/".contains(&b) || (cfg!(windows) && b == b':') {
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
    use PathStyle::{Posix, Windows};

    fn ok(location: &str, style: PathStyle) -> String {
        location_to_path(location, style).unwrap_or_else(|e| panic!("{location}: {e}"))
    }

    #[test]
    fn posix_forms() {
        let want = "/tmp/a b/resources";
        for uri in [
            "file:///tmp/a%20b/resources",
            "file:///tmp/a%20b/resources/",
            "file:/tmp/a%20b/resources",
            "file://localhost/tmp/a%20b/resources",
            "FILE://LOCALHOST/tmp/a%20b/resources/",
            "file:/tmp/a b/resources",
            "file:///tmp/a%20b/resources?x=1#frag",
            "/tmp/a b/resources",
            "/tmp/a b/resources/",
        ] {
            assert_eq!(ok(uri, Posix), want.replace("//", "/"), "{uri}");
        }
        assert_eq!(ok("file:///", Posix), "/");
        assert_eq!(ok("file://localhost", Posix), "/");
        assert_eq!(ok("file:///tmp/%C3%A9t%C3%A9", Posix), "/tmp/été");
        assert_eq!(ok("file:///tmp/été", Posix), "/tmp/été");
        // a plain path is taken as it is: '%' is a legal file-name character
        assert_eq!(ok("/tmp/100%/x", Posix), "/tmp/100%/x");
    }

    #[test]
    fn windows_forms() {
        let want = r"C:\dir one\resources";
        for uri in [
            "file:///C:/dir%20one/resources",
            "file:///C:/dir%20one/resources/",
            "file:/C:/dir%20one/resources",
            "file://localhost/C:/dir%20one/resources",
            "file://LocalHost/C:/dir%20one/resources/",
            "file://C:/dir%20one/resources",
            "file:C:/dir%20one/resources",
            "file:///C|/dir%20one/resources",
            r"file:///C:\dir%20one\resources\",
            r"C:\dir one\resources",
            r"C:\dir one\resources\",
            "C:/dir one/resources",
        ] {
            assert_eq!(ok(uri, Windows), want, "{uri}");
        }
        assert_eq!(ok("file:///c:/", Windows), r"c:\");
        assert_eq!(ok("file:///D:", Windows), r"D:\");
        assert_eq!(
            ok("file:///C:/Users/Jos%C3%A9/%E6%A8%A1%E5%9E%8B", Windows),
            r"C:\Users\José\模型"
        );
        // UNC shares
        for uri in [
            "file://server/share/dir/resources",
            "file://server/share/dir/resources/",
            "file:////server/share/dir/resources",
            "file://///server/share/dir/resources",
            r"\\server\share\dir\resources",
        ] {
            assert_eq!(ok(uri, Windows), r"\\server\share\dir\resources", "{uri}");
        }
        assert_eq!(
            ok("file://my%20server/share%201", Windows),
            r"\\my server\share 1"
        );
        // rooted, no drive (the current drive)
        assert_eq!(ok("file:///tmp/x", Windows), r"\tmp\x");
    }

    #[test]
    fn malformed_locations_are_refused() {
        for (bad, style, why) in [
            ("", Posix, "empty"),
            ("", Windows, "empty"),
            ("http://x/y", Posix, "scheme"),
            ("https://server/C:/x", Windows, "scheme"),
            ("file://server/share", Posix, "remote host 'server'"),
            ("file:rel/path", Posix, "absolute"),
            ("file:rel/path", Windows, "absolute"),
            ("rel/path", Posix, "neither"),
            (r"C:\dir", Posix, "neither"),
            ("dir\\x", Windows, "neither"),
            ("file:///a%2", Posix, "percent"),
            ("file:///a%zz/b", Posix, "percent"),
            ("file:///a%+1/b", Windows, "percent"),
            ("file:///a%FF/b", Posix, "UTF-8"),
            ("file:///a%00b", Posix, "NUL"),
            ("file:////", Windows, "directory"),
        ] {
            let e = location_to_path(bad, style).expect_err(bad);
            assert!(e.contains(why), "{bad} ({style:?}): {e}");
            assert!(e.contains(bad), "the message names the location: {e}");
        }
    }

    #[test]
    fn host_round_trip() {
        let dir = std::env::temp_dir().join("a b é%");
        assert_eq!(uri_to_path(&path_to_uri(&dir)).unwrap(), dir);
        assert_eq!(
            uri_to_path("file:///tmp/a%20b").unwrap(),
            PathBuf::from(if cfg!(windows) {
                r"\tmp\a b"
            } else {
                "/tmp/a b"
            })
        );
    }
}
