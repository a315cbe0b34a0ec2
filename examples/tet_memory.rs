//! Peak memory and speed of the tetrahedral mesher alone, on one closed boundary (.off) and an
//! optional file of embedded triangles (.off, vertices matched by exact coordinates): what issue 6
//! bounds (at most 300 bytes per tet at peak). Embedded vertices inside the region are added. The peak resident set is reset just before
//! `mesh_region` (Linux `clear_refs`), so reading the input and the output do not count; the
//! figure is the peak during meshing minus the resident set before it. One thread.
//!
//! usage: cargo run --release --example tet_memory -- BOUNDARY.off [EMBEDDED.off] [front]

use std::collections::HashMap;
use std::time::Instant;

use georecipe::mesh::read::read_by_extension;
use georecipe::stages::tet_mesh::{Method, RegionInput, SizeField, TetMeshOptions, mesh_region};

fn status_kb(key: &str) -> Option<u64> {
    let s = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = s.lines().find(|l| l.starts_with(key))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

fn read(path: &str) -> georecipe::mesh::read::BoundaryMesh {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{path}: {e}"));
    read_by_extension(path, &bytes).unwrap_or_else(|e| panic!("{e}"))
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let Some(boundary) = args.first() else {
        eprintln!("usage: tet_memory BOUNDARY.off [EMBEDDED.off] [front]");
        std::process::exit(2);
    };
    let b = read(boundary);
    let mut input = RegionInput {
        name: boundary.clone(),
        vertices: b.vertices,
        boundary: b.triangles,
        embedded: vec![],
    };
    // One closed shell: orient it outward by the sign of its enclosed volume.
    let vol: f64 = input
        .boundary
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| input.vertices[i as usize]);
            a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                + a[2] * (b[0] * c[1] - b[1] * c[0])
        })
        .sum();
    if vol < 0.0 {
        input.boundary.iter_mut().for_each(|t| t.swap(1, 2));
    }
    if let Some(e) = args.get(1).filter(|a| a.ends_with(".off")) {
        let e = read(e);
        // Fault vertices inside the region are not boundary vertices: they are added.
        let mut index: HashMap<[u64; 3], u32> = input
            .vertices
            .iter()
            .enumerate()
            .map(|(i, p)| (p.map(f64::to_bits), i as u32))
            .collect();
        for t in &e.triangles {
            let f = t.map(|i| {
                let p = e.vertices[i as usize];
                *index.entry(p.map(f64::to_bits)).or_insert_with(|| {
                    input.vertices.push(p);
                    (input.vertices.len() - 1) as u32
                })
            });
            input.embedded.push(f);
        }
    }
    let method = if args.iter().any(|a| a == "front") {
        Method::Front
    } else {
        Method::Delaunay
    };
    let opts = TetMeshOptions {
        method,
        ..TetMeshOptions::default()
    };
    let before = status_kb("VmRSS:").unwrap_or(0);
    let reset = std::fs::write("/proc/self/clear_refs", "5").is_ok();
    let t0 = Instant::now();
    let out = mesh_region(&input, &SizeField::default(), &opts).unwrap_or_else(|e| panic!("{e}"));
    let secs = t0.elapsed().as_secs_f64();
    let peak = status_kb("VmHWM:").unwrap_or(0);
    let tets = out.tets.len();
    let extra = peak.saturating_sub(before) * 1024;
    println!(
        "{boundary}: {tets} tets in {secs:.3} s ({:.0} tets/s, {method:?}{}), peak {} MB over {} MB before: {:.0} B/tet{}; MR avg {:.4} min {:.3}, min dihedral {:.1}",
        tets as f64 / secs,
        out.stats
            .fallback
            .as_deref()
            .map(|f| format!(", fell back: {f}"))
            .unwrap_or_default(),
        peak / 1024,
        before / 1024,
        extra as f64 / tets as f64,
        if reset {
            ""
        } else {
            " (peak not reset: includes reading)"
        },
        out.stats.avg_mean_ratio,
        out.stats.min_mean_ratio,
        out.stats.min_dihedral_deg
    );
}
