use triad::fmu::contract::*;
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let s = Spec::from_path(std::path::Path::new(&args[1])).unwrap();
    let (d, st) = s.lower().unwrap();
    let t = table(&d, &st);
    println!(
        "{} {}",
        s.canonical_json(),
        triad::fmu::guid::guid(&s.canonical_json(), &t)
    );
    let s2 = Spec::from_str(&s.canonical_json(), Format::Json, "x").unwrap();
    let (d, st) = s2.lower().unwrap();
    let t = table(&d, &st);
    println!(
        "{} {}",
        s2.canonical_json(),
        triad::fmu::guid::guid(&s2.canonical_json(), &t)
    );
    if args.len() > 2 {
        let p = triad::package::build_fmu(
            std::path::Path::new(&args[1]),
            std::path::Path::new(&args[2]),
        )
        .unwrap();
        println!("{}", p.display());
    }
}
