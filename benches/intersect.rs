//! Benchmark of `model::intersect`: two generated surfaces of ~1 million triangles each
//! (707 × 707 grids at UTM coordinates), a wavy horizon and a tilted fault crossing it.
//! Target: under 1.5 s per intersection.

use criterion::{Criterion, criterion_group, criterion_main};
use geom::TriMesh;
use model::intersect::{SurfaceRef, intersect};
use std::hint::black_box;

fn grid(n: usize, f: impl Fn(usize, usize) -> [f64; 3]) -> TriMesh {
    let mut vertices = Vec::with_capacity((n + 1) * (n + 1));
    for j in 0..=n {
        for i in 0..=n {
            vertices.push(f(i, j));
        }
    }
    let id = |i: usize, j: usize| (j * (n + 1) + i) as u32;
    let mut triangles = Vec::with_capacity(2 * n * n);
    for j in 0..n {
        for i in 0..n {
            triangles.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            triangles.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    TriMesh::new(vertices, triangles)
}

/// A horizon over 7 km × 7 km with 10 m cells, and a fault dipping ~70° that crosses it.
fn surfaces() -> (TriMesh, TriMesh) {
    let (x0, y0) = (500_000.0, 7_000_000.0);
    let horizon = grid(707, |i, j| {
        let (x, y) = (i as f64 * 10.0, j as f64 * 10.0);
        [
            x0 + x,
            y0 + y,
            -2000.0 + 40.0 * (x / 700.0).sin() * (y / 900.0).cos() + 0.001 * x,
        ]
    });
    let fault = grid(707, |i, k| {
        let y = -100.0 + i as f64 * 10.2;
        let z = -3000.0 + k as f64 * 2.9;
        [x0 + 3500.0 + 0.36 * (z + 2000.0) + 0.05 * y, y0 + y, z]
    });
    (horizon, fault)
}

/// Two horizons over the same 7 km × 7 km footprint that cross each other along many curves.
fn crossing_horizons() -> (TriMesh, TriMesh) {
    let (x0, y0) = (500_000.0, 7_000_000.0);
    let h1 = grid(707, |i, j| {
        let (x, y) = (i as f64 * 10.0, j as f64 * 10.0);
        [
            x0 + x,
            y0 + y,
            -2000.0 + 40.0 * (x / 700.0).sin() * (y / 900.0).cos(),
        ]
    });
    let h2 = grid(707, |i, j| {
        let (x, y) = (i as f64 * 10.0 + 3.0, j as f64 * 10.0 + 7.0);
        [x0 + x, y0 + y, -1995.0 + 20.0 * (x / 500.0 + 1.0).sin()]
    });
    (h1, h2)
}

fn bench(c: &mut Criterion) {
    let (h, f) = surfaces();
    let x = intersect(
        SurfaceRef {
            name: "horizon",
            mesh: &h,
        },
        SurfaceRef {
            name: "fault",
            mesh: &f,
        },
    )
    .expect("no coplanar contact");
    let pts: usize = x.curves.iter().map(|c| c.points.len()).sum();
    eprintln!(
        "{} + {} triangles: {} curves, {pts} points",
        h.triangles.len(),
        f.triangles.len(),
        x.curves.len()
    );
    let mut g = c.benchmark_group("intersect");
    g.sample_size(10);
    g.bench_function("two_1M_triangle_surfaces", |b| {
        b.iter(|| {
            intersect(
                SurfaceRef {
                    name: "horizon",
                    mesh: black_box(&h),
                },
                SurfaceRef {
                    name: "fault",
                    mesh: black_box(&f),
                },
            )
        })
    });
    g.bench_function("split_1M_triangle_horizon_along_the_fault_curve", |b| {
        b.iter(|| {
            model::intersect::split::split(black_box(&h), &x, model::intersect::split::Side::B)
        })
    });
    let (h1, h2) = crossing_horizons();
    let x = intersect(
        SurfaceRef {
            name: "h1",
            mesh: &h1,
        },
        SurfaceRef {
            name: "h2",
            mesh: &h2,
        },
    )
    .expect("no coplanar contact");
    let pts: usize = x.curves.iter().map(|c| c.points.len()).sum();
    eprintln!(
        "two crossing horizons: {} curves, {pts} points",
        x.curves.len()
    );
    g.bench_function("two_1M_triangle_horizons_crossing_many_times", |b| {
        b.iter(|| {
            intersect(
                SurfaceRef {
                    name: "h1",
                    mesh: black_box(&h1),
                },
                SurfaceRef {
                    name: "h2",
                    mesh: black_box(&h2),
                },
            )
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
