//! BENCHMARKS.md is a reference page of current figures, not a log: it stays at most 15 kB
//! (history lives in git), and every figure section names the command that reproduces it.

#[test]
fn benchmarks_page_stays_a_reference() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("BENCHMARKS.md");
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(
        text.len() <= 15_000,
        "BENCHMARKS.md is {} bytes: keep the current figures only (≤ 15 kB)",
        text.len()
    );
    assert!(
        text.contains("## Commands"),
        "the table of commands is missing"
    );
}
