//! Surface mesher throughput: triangles per second on the didactic wavy horizon
//! (z = -1200 + 80 sin(x/900) cos(y/1100)) over 3700 × 3700 m at UTM offsets, single thread, at
//! 25 m (~50k triangles); plus the seed's refinements 200/100/50 m for the quality table, and the
//! same horizon with a 25 m border graded into a 200 m interior (the reservoir horizons of the
//! seed's refinement (d)).

use test_support::surface_mesh_common;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use surface_mesh::quality::stats;
use surface_mesh::{PatchInput, SurfaceSize, mesh_patch};
use surface_mesh_common::{Grid, UTM, uniform, wavy};

fn input(size: f64) -> PatchInput {
    let g = Grid {
        nx: 60,
        ny: 60,
        u: (0.0, 3700.0),
        v: (0.0, 3700.0),
        f: wavy,
        offset: UTM,
    };
    let n = (3700.0 / size).round() as usize;
    PatchInput {
        name: format!("wavy {size} m"),
        support: g.support(),
        loops: vec![g.border_loop(n, n)],
        constraints: vec![],
        points: Vec::new(),
        facets: Vec::new(),
    }
}

/// VRTX/PVRTX and TRGL lines of a one-TFACE TSurf (bench fixture reader).
fn read_tsurf(text: &str) -> geom::TriMesh {
    let mut ids = std::collections::BTreeMap::new();
    let mut vs = Vec::new();
    let mut ts = Vec::new();
    for line in text.lines() {
        let f: Vec<&str> = line.split_whitespace().collect();
        let num = |k: usize| {
            f.get(k)
                .and_then(|x| x.parse::<f64>().ok())
                .unwrap_or(f64::NAN)
        };
        match f.first() {
            Some(&"VRTX") | Some(&"PVRTX") => {
                ids.insert(f.get(1).copied().unwrap_or("").to_string(), vs.len() as u32);
                vs.push([num(2), num(3), num(4)]);
            }
            Some(&"TRGL") => {
                let id = |k: usize| {
                    ids.get(f.get(k).copied().unwrap_or(""))
                        .copied()
                        .unwrap_or(0)
                };
                ts.push([id(1), id(2), id(3)]);
            }
            _ => {}
        }
    }
    geom::TriMesh::new(vs, ts)
}

fn bench(c: &mut Criterion) {
    for size in [200.0, 100.0, 50.0, 25.0] {
        let inp = input(size);
        let t0 = std::time::Instant::now();
        let out = mesh_patch(&inp, &uniform(size)).expect("meshes");
        let secs = t0.elapsed().as_secs_f64();
        let q = stats(&out.nodes, &out.triangles);
        eprintln!(
            "| {} | {} | {:.4} | {:.4} | {:.3} | {:.2} | {:.2} | {:.3} s |",
            inp.name, q.triangles, q.mean, q.sd, q.max, q.pct_above_1_15, q.pct_above_1_5, secs
        );
    }
    {
        let inp = input(25.0);
        let graded = SurfaceSize {
            size: 200.0,
            min_size: 2.0,
            max_size: 2000.0,
            growth: 1.3,
        };
        let t0 = std::time::Instant::now();
        let out = mesh_patch(&inp, &graded).expect("meshes");
        let secs = t0.elapsed().as_secs_f64();
        let q = stats(&out.nodes, &out.triangles);
        eprintln!(
            "| wavy 25 m border, 200 m inside | {} | {:.4} | {:.4} | {:.3} | {:.2} | {:.2} | {:.3} s |",
            q.triangles, q.mean, q.sd, q.max, q.pct_above_1_15, q.pct_above_1_5, secs
        );
    }
    // The shipped didactic horizon H1 (irregular gOcad-like support at UTM coordinates),
    // regenerated at the seed's four refinements with `retriangulate`.
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/recipes/data/didactic/H1_top_reservoir.ts"
    );
    if let Ok(text) = std::fs::read_to_string(path) {
        let h1 = read_tsurf(&text);
        for size in [200.0, 100.0, 50.0, 25.0] {
            let t0 = std::time::Instant::now();
            let m = surface_mesh::retriangulate(&h1, size).expect("retriangulates");
            let secs = t0.elapsed().as_secs_f64();
            let q = stats(&m.vertices, &m.triangles);
            eprintln!(
                "| didactic H1 {size} m | {} | {:.4} | {:.4} | {:.3} | {:.2} | {:.2} | {:.3} s |",
                q.triangles, q.mean, q.sd, q.max, q.pct_above_1_15, q.pct_above_1_5, secs
            );
        }
    }
    let inp = input(25.0);
    let tris = mesh_patch(&inp, &uniform(25.0))
        .expect("meshes")
        .triangles
        .len();
    let mut g = c.benchmark_group("surface_mesh");
    g.sample_size(10);
    g.throughput(Throughput::Elements(tris as u64));
    g.bench_function("wavy_horizon_25m_triangles", |b| {
        b.iter(|| mesh_patch(&inp, &uniform(25.0)).expect("meshes"))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
