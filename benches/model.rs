//! Model benchmark (issue 4): the seed's didactic example (two horizons 35 m apart, a
//! through-going fault and a dangling fault, in a 5000 × 5000 × 2500 m box) at about 100 000
//! triangles per surface, built without import: every pair the shipped recipe intersects, then
//! `split_model`, `patches`, `inside_box` and `find_regions_with`, the sequence of the `model`
//! operation (`src/plan/ops/model.rs`). Target: under 1 s.
//!
//! The surfaces come from the same generator as the shipped data (`examples/make_didactic.rs`,
//! included below) at a higher density, written as TSurf text and imported outside the timing.
//!
//! Run: `cargo bench --bench model`.

#[allow(dead_code)]
#[path = "../examples/make_didactic.rs"]
mod make_didactic;

use criterion::{Criterion, criterion_group, criterion_main};
use georecipe::geom::{BBox, TriMesh};
use georecipe::stages::import::{ImportOptions, import_surface};
use georecipe::stages::intersect::split::{SplitSurface, split_model};
use georecipe::stages::intersect::{Intersection, SurfaceRef, box_sides, intersect};
use georecipe::stages::patches::{inside_box, patches};
use georecipe::stages::regions::{PatchIn, RegionModel, RegionOptions, find_regions_with};
use std::hint::black_box;
use std::time::Instant;

const TRIANGLES: usize = 100_000;

/// The recipe's surface names by generated file.
const NAMES: [(&str, &str); 4] = [
    ("H1_top_reservoir.ts", "H1"),
    ("H2_base_reservoir.ts", "H2"),
    ("F1_through.ts", "F1"),
    ("F2_dangling.ts", "F2"),
];

fn bbox() -> BBox {
    BBox {
        min: [500_000.0, 7_000_000.0, -2500.0],
        max: [505_000.0, 7_005_000.0, 0.0],
    }
}

/// The model's surfaces in name order (as the `model` operation receives them), and the pairs
/// `recipes/didactic.toml` intersects: every pair among H1, H2, F1 and the six box sides (box
/// sides not with each other), plus F2 with each horizon; each pair sorted, the list sorted.
fn inputs() -> (Vec<(String, TriMesh)>, Vec<(String, String)>) {
    let mut surfaces: Vec<(String, TriMesh)> = Vec::new();
    for (file, text, _, _) in make_didactic::didactic_files(Some(TRIANGLES)) {
        let name = NAMES
            .iter()
            .find(|(f, _)| *f == file)
            .map(|(_, n)| *n)
            .expect("a known file");
        let s = import_surface(text.as_bytes(), file, &ImportOptions::default())
            .unwrap_or_else(|e| panic!("{file} imports: {e}"));
        eprintln!("{name}: {} triangles", s.mesh.triangles.len());
        surfaces.push((name.to_string(), s.mesh));
    }
    surfaces.extend(box_sides(&bbox()));
    surfaces.sort_by(|a, b| a.0.cmp(&b.0));
    let all = ["H1", "H2", "F1"];
    let sides: Vec<String> = surfaces
        .iter()
        .filter(|s| s.0.starts_with("box."))
        .map(|s| s.0.clone())
        .collect();
    let mut pairs: Vec<(String, String)> = Vec::new();
    let mut add = |a: &str, b: &str| {
        let (a, b) = if a < b { (a, b) } else { (b, a) };
        pairs.push((a.to_string(), b.to_string()));
    };
    for (i, a) in all.iter().enumerate() {
        for b in &all[i + 1..] {
            add(a, b);
        }
        for s in &sides {
            add(a, s);
        }
    }
    add("F2", "H1");
    add("F2", "H2");
    pairs.sort();
    pairs.dedup();
    (surfaces, pairs)
}

fn intersect_all(surfaces: &[(String, TriMesh)], pairs: &[(String, String)]) -> Vec<Intersection> {
    let r = |n: &str| {
        let (name, mesh) = surfaces.iter().find(|s| s.0 == n).expect("known surface");
        SurfaceRef { name, mesh }
    };
    pairs
        .iter()
        .map(|(a, b)| intersect(r(a), r(b)).unwrap_or_else(|e| panic!("{a} x {b}: {e}")))
        .collect()
}

fn split_all(surfaces: &[(String, TriMesh)], xs: &[Intersection]) -> Vec<SplitSurface> {
    let named: Vec<(&str, &TriMesh)> = surfaces.iter().map(|(n, m)| (n.as_str(), m)).collect();
    split_model(&named, xs).unwrap_or_else(|e| panic!("splits: {e}"))
}

fn patches_in_box(surfaces: &[(String, TriMesh)], split: &[SplitSurface]) -> Vec<PatchIn> {
    let b = bbox();
    let mut kept = Vec::new();
    for ((name, _), s) in surfaces.iter().zip(split) {
        for p in patches(name, s) {
            if inside_box(&p, &b) {
                kept.push(PatchIn {
                    name: p.name,
                    surface: name.clone(),
                    mesh: p.mesh,
                });
            }
        }
    }
    kept
}

fn regions(kept: &[PatchIn]) -> RegionModel {
    let opts = RegionOptions::with_faults(["F1", "F2"]);
    find_regions_with(kept, &[], &opts).unwrap_or_else(|e| panic!("regions: {e}"))
}

fn model(surfaces: &[(String, TriMesh)], pairs: &[(String, String)]) -> RegionModel {
    let xs = intersect_all(surfaces, pairs);
    let split = split_all(surfaces, &xs);
    let kept = patches_in_box(surfaces, &split);
    regions(&kept)
}

fn bench(c: &mut Criterion) {
    let (surfaces, pairs) = inputs();
    // One timed pass per stage, to say where the time goes.
    let t = Instant::now();
    let xs = intersect_all(&surfaces, &pairs);
    let t_x = t.elapsed();
    let t = Instant::now();
    let split = split_all(&surfaces, &xs);
    let t_s = t.elapsed();
    let t = Instant::now();
    let kept = patches_in_box(&surfaces, &split);
    let t_p = t.elapsed();
    let t = Instant::now();
    let m = regions(&kept);
    let t_r = t.elapsed();
    eprintln!(
        "{} pairs, {} patches, {} regions; intersect {t_x:?}, split {t_s:?}, patches {t_p:?}, regions {t_r:?}",
        pairs.len(),
        kept.len(),
        m.regions.len()
    );
    assert_eq!(m.regions.len(), 6, "3 layers on each side of F1");

    let mut g = c.benchmark_group("model");
    g.sample_size(10);
    g.bench_function("didactic_100k_intersect", |b| {
        b.iter(|| intersect_all(black_box(&surfaces), &pairs))
    });
    g.bench_function("didactic_100k_split", |b| {
        b.iter(|| split_all(black_box(&surfaces), &xs))
    });
    g.bench_function("didactic_100k_patches", |b| {
        b.iter(|| patches_in_box(black_box(&surfaces), &split))
    });
    g.bench_function("didactic_100k_regions", |b| {
        b.iter(|| regions(black_box(&kept)))
    });
    g.bench_function("didactic_100k_model", |b| {
        b.iter(|| model(black_box(&surfaces), &pairs))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
