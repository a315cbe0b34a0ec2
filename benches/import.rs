//! Import benchmarks: TSurf parse throughput (MB/s) on generated text, and import + validate +
//! topology of a generated 1M-triangle surface, with its memory per triangle from capacities.
//!
//! Run: `cargo bench --bench import`.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use geom::Tolerances;
use gocad::import::{ImportOptions, import_surface, parse_gocad};
use gocad::validate::validate;
use model::topology::SurfaceTopology;
use std::fmt::Write;
use std::hint::black_box;
use std::time::Instant;

/// A gently folded horizon at UTM magnitudes: an n x n cell grid, 2 n^2 triangles.
fn tsurf_text(n: u32) -> String {
    let mut s = String::with_capacity((n as usize + 1).pow(2) * 64 + 2 * (n as usize).pow(2) * 28);
    s.push_str("GOCAD TSurf 1\nHEADER {\nname: bench\n}\nGOCAD_ORIGINAL_COORDINATE_SYSTEM\nAXIS_UNIT \"m\" \"m\" \"m\"\nZPOSITIVE Depth\nEND_ORIGINAL_COORDINATE_SYSTEM\nTFACE\n");
    for j in 0..=n {
        for i in 0..=n {
            let x = 512_345.125 + f64::from(i) * 25.0 + f64::from(j % 7) * 0.013;
            let y = 7_012_345.5 + f64::from(j) * 25.0 + f64::from(i % 5) * 0.011;
            let z = 1500.0 + 120.0 * (x / 3000.0).sin() * (y / 2000.0).cos();
            let _ = writeln!(s, "VRTX {} {x:.6} {y:.6} {z:.6}", j * (n + 1) + i + 1);
        }
    }
    for j in 0..n {
        for i in 0..n {
            let a = j * (n + 1) + i + 1;
            let _ = writeln!(s, "TRGL {} {} {}", a, a + 1, a + n + 2);
            let _ = writeln!(s, "TRGL {} {} {}", a, a + n + 2, a + n + 1);
        }
    }
    s.push_str("END\n");
    s
}

fn parse_throughput(c: &mut Criterion) {
    let text = tsurf_text(300); // 180k triangles, about 9 MB
    let mut g = c.benchmark_group("tsurf_parse");
    g.throughput(Throughput::Bytes(text.len() as u64));
    g.sample_size(20);
    g.bench_function("parse_gocad", |b| {
        b.iter(|| parse_gocad(black_box(text.as_bytes()), "bench.ts").unwrap())
    });
    g.finish();
}

fn million_triangles(c: &mut Criterion) {
    let n = 708; // 2 * 708^2 = 1,002,528 triangles
    let text = tsurf_text(n);
    let tol = Tolerances::default();
    let opts = ImportOptions::default();
    {
        // One timed pass per phase (wall clock; the criterion figure below is the reference).
        let t0 = Instant::now();
        let parsed = parse_gocad(text.as_bytes(), "bench.ts").unwrap();
        let t1 = Instant::now();
        drop(parsed);
        let t2 = Instant::now();
        let s = import_surface(text.as_bytes(), "bench.ts", &opts).unwrap();
        let t3 = Instant::now();
        let r = validate(&s, &tol);
        let t4 = Instant::now();
        assert!(r.is_clean(), "{}", r.render_text());
        let topo = SurfaceTopology::build_with_parts(&s.mesh, &s.triangle_part, &s.bstones, &tol);
        let t5 = Instant::now();
        eprintln!(
            "1M phases: parse {:.2} s, import (parse + convert) {:.2} s, validate {:.2} s, topology {:.2} s",
            (t1 - t0).as_secs_f64(),
            (t3 - t2).as_secs_f64(),
            (t4 - t3).as_secs_f64(),
            (t5 - t4).as_secs_f64()
        );
        let t = s.mesh.triangles.len() as f64;
        eprintln!(
            "1M surface: {} triangles, {} MB text; memory held: surface {:.1} B/triangle + topology {:.1} B/triangle = {:.1} B/triangle",
            s.mesh.triangles.len(),
            text.len() / 1_000_000,
            s.heap_bytes() as f64 / t,
            topo.heap_bytes() as f64 / t,
            (s.heap_bytes() + topo.heap_bytes()) as f64 / t
        );
    }
    let mut g = c.benchmark_group("surface_1m");
    g.sample_size(10);
    g.bench_function("import_validate_topology", |b| {
        b.iter(|| {
            let s = import_surface(black_box(text.as_bytes()), "bench.ts", &opts).unwrap();
            let r = validate(&s, &tol);
            let topo =
                SurfaceTopology::build_with_parts(&s.mesh, &s.triangle_part, &s.bstones, &tol);
            black_box((r.findings.len(), topo.curves().len()))
        })
    });
    g.finish();
}

criterion_group!(benches, parse_throughput, million_triangles);
criterion_main!(benches);
