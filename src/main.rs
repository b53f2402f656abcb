//! The `triad` command line (placeholder; the CLI work replaces it).
fn main() {
    println!("triad {}", env!("CARGO_PKG_VERSION"));
}
