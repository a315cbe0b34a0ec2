//! Measures the memory the import stages need per triangle: reads a gOcad file, then imports,
//! validates and builds the topology of its surface, and prints the growth of the process's peak
//! resident set (VmHWM) over what it held once the file's bytes were read.
//!
//! Usage: `cargo run --release --example import_memory -- FILE.ts` (Linux: reads /proc/self/status)

use geom::Tolerances;
use gocad::{import, validate};
use model::topology;

fn peak_kib() -> u64 {
    let s = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    s.lines()
        .find(|l| l.starts_with("VmHWM:"))
        .and_then(|l| l.split_whitespace().nth(1))
        .and_then(|v| v.parse().ok())
        .unwrap_or(0)
}

fn main() {
    let Some(path) = std::env::args().nth(1) else {
        eprintln!("usage: import_memory FILE.ts");
        std::process::exit(2);
    };
    let bytes = std::fs::read(&path).unwrap_or_else(|e| {
        eprintln!("cannot read {path}: {e}");
        std::process::exit(1);
    });
    let base = peak_kib();
    let t0 = std::time::Instant::now();
    let s = import::import_surface(&bytes, &path, &import::ImportOptions::default())
        .unwrap_or_else(|e| {
            eprintln!("{e}");
            std::process::exit(1);
        });
    let tol = Tolerances::default();
    let report = validate::validate(&s, &tol);
    let topo = topology::SurfaceTopology::build(&s.mesh, &s.bstones, &tol);
    let secs = t0.elapsed().as_secs_f64();
    let n = s.mesh.triangles.len() as f64;
    let grown = peak_kib().saturating_sub(base) as f64 * 1024.0;
    println!(
        "{} triangles, {} findings, {} curves in {:.2}s; peak growth {:.0} B/triangle (file bytes excluded)",
        s.mesh.triangles.len(),
        report.findings.len(),
        topo.curves().len(),
        secs,
        grown / n
    );
}
