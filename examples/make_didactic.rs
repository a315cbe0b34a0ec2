//! Writes the data of the shipped examples `recipes/didactic.toml` and `didactic_wells.toml`
//! (the generators are `test_support::didactic`, the seed paper's didactic model at UTM-sized
//! coordinates, and `test_support::didactic_wells`, its two wells).
//!
//! Usage: `cargo run --example make_didactic -- recipes/data/didactic` (the shipped data), or
//! `cargo run --example make_didactic -- --triangles 100000 /tmp/dense` for about 100 000
//! triangles per surface (the geometry of `benches/model.rs`).

use std::path::PathBuf;
use test_support::didactic::{Density, didactic_files};
use test_support::didactic_wells::didactic_wells;

fn main() {
    let mut out = PathBuf::from("recipes/data/didactic");
    let mut target: Density = None;
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        if a == "--triangles" {
            let n = args.next().and_then(|n| n.parse::<usize>().ok());
            match n {
                Some(n) if n >= 2 => target = Some(n),
                _ => {
                    eprintln!("--triangles needs a whole number >= 2 (triangles per surface)");
                    std::process::exit(2);
                }
            }
        } else {
            out = PathBuf::from(a);
        }
    }
    std::fs::create_dir_all(&out)
        .unwrap_or_else(|e| panic!("cannot create {}: {e}", out.display()));
    for (file, text, nv, nt) in didactic_files(target) {
        let path = out.join(file);
        std::fs::write(&path, text)
            .unwrap_or_else(|e| panic!("cannot write {}: {e}", path.display()));
        println!("wrote {} ({nv} vertices, {nt} triangles)", path.display());
    }
    for (file, text, stations) in didactic_wells() {
        let path = out.join(file);
        std::fs::write(&path, text)
            .unwrap_or_else(|e| panic!("cannot write {}: {e}", path.display()));
        println!("wrote {} ({stations} stations)", path.display());
    }
}
