//! The page: `viewer/page.html` with the style, three.js, the viewer script and the payload
//! inlined, so that the one file works offline.

/// The page template (placeholders `{{TITLE}}`, `{{STYLE}}`, `{{THREE}}`, `{{VIEWER}}`,
/// `{{PAYLOAD}}`).
const TEMPLATE: &str = include_str!("../../viewer/page.html");
/// The page's style sheet.
const STYLE: &str = include_str!("../../viewer/viewer.css");
/// three.js, bundled by `scripts/vendor_three.sh` (MIT; `viewer/vendor/three.LICENSE`).
const THREE: &str = include_str!("../../viewer/vendor/three.bundle.min.js");
/// The viewer: scene set-up, playback, controls, signal panel.
const VIEWER: &str = include_str!("../../viewer/viewer.js");

/// Where the payload sits in the page.
const PAYLOAD_OPEN: &str = "<script type=\"application/json\" id=\"triad-data\">";

fn escape_text(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// A script's text made safe inside `<script>`: a `</script` would end the element early.
fn script(js: &str) -> String {
    js.replace("</script", "<\\/script")
}

/// The page of a payload (from [`super::payload::encode`]) titled `title`.
#[must_use]
pub fn page(title: &str, payload: &str) -> String {
    // in JSON a '<' can only be inside a string, where \u003c means the same
    let payload = payload.replace('<', "\\u003c");
    TEMPLATE
        .replace("{{TITLE}}", &escape_text(title))
        .replace("{{STYLE}}", STYLE)
        .replace("{{THREE}}", &script(THREE))
        .replace("{{VIEWER}}", &script(VIEWER))
        .replacen("{{PAYLOAD}}", &payload, 1)
}

/// The payload JSON embedded in a page made by [`page`].
#[must_use]
pub fn payload_of(html: &str) -> Option<&str> {
    let start = html.find(PAYLOAD_OPEN)? + PAYLOAD_OPEN.len();
    let len = html[start..].find("</script>")?;
    Some(&html[start..start + len])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_payload_comes_back_and_scripts_stay_closed() {
        assert!(TEMPLATE.contains(PAYLOAD_OPEN));
        let html = page("a <b>", "{\"x\":\"</script>\"}");
        assert!(html.contains("<title>a &lt;b&gt; - triad replay</title>"));
        let back = payload_of(&html).unwrap();
        assert_eq!(back, "{\"x\":\"\\u003c/script>\"}");
        let v: serde_json::Value = serde_json::from_str(back).unwrap();
        assert_eq!(v["x"], "</script>");
        assert!(!THREE.contains("</script") && !VIEWER.contains("</script"));
    }
}
