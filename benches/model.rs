//! Model benchmark: the seed's didactic example (two horizons 35 m apart, a
//! through-going fault and a dangling fault, in a 5000 × 5000 × 2500 m box) at about 100 000
//! triangles per surface, built without import: every pair the shipped recipe intersects, then
//! `split_model`, `patches`, `inside_box` and `find_regions_with`, the sequence of the `model`
//! operation (`src/plan/ops/model.rs`). Target: under 1 s.
//!
//! The surfaces come from the same generator as the shipped data (`examples/make_didactic.rs`,
//! included below) at a higher density, written as TSurf text and imported outside the timing.
//!
//! Run: `cargo bench --bench model`.

use test_support::didactic as make_didactic;

use criterion::{Criterion, criterion_group, criterion_main};
use geom::{BBox, TriMesh};
use gocad::import::{ImportOptions, import_surface};
use model::intersect::split::{SplitSurface, split_model};
use model::intersect::{Intersection, SurfaceRef, box_sides, intersect};
use model::patches::{inside_box, patches};
use model::regions::{PatchIn, RegionModel, RegionOptions, find_regions_with};
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
type Named = Vec<(String, TriMesh)>;
type Pairs = Vec<(String, String)>;

fn inputs() -> (Named, Pairs) {
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
                    chart_of: None,
                    name: p.name,
                    surface: name.clone(),
                    mesh: p.mesh,
                });
            }
        }
    }
    kept
}

/// The recipe's `[regions]` points, which name the six regions.
fn names() -> Vec<(String, [f64; 3])> {
    [
        ("overburden_W", [500500.0, 7001000.0, -600.0]),
        ("overburden_E", [504000.0, 7001000.0, -600.0]),
        ("reservoir_W", [500500.0, 7001000.0, -1191.6]),
        ("reservoir_E", [504000.0, 7001000.0, -1264.9]),
        ("underburden_W", [500500.0, 7001000.0, -2000.0]),
        ("underburden_E", [504000.0, 7001000.0, -2000.0]),
    ]
    .iter()
    .map(|(n, p)| (n.to_string(), *p))
    .collect()
}

fn regions(kept: &[PatchIn]) -> RegionModel {
    let opts = RegionOptions::with_faults(["F1", "F2"]);
    find_regions_with(kept, &names(), &opts).unwrap_or_else(|e| panic!("regions: {e}"))
}

fn model(surfaces: &[(String, TriMesh)], pairs: &[(String, String)]) -> RegionModel {
    let xs = intersect_all(surfaces, pairs);
    let split = split_all(surfaces, &xs);
    let kept = patches_in_box(surfaces, &split);
    regions(&kept)
}

/// CPU seconds used so far by the whole process (every thread), from `/proc/self/stat` (user +
/// system, in USER_HZ = 100 ticks per second); `None` where that file does not exist. Wall
/// time on a shared machine overstates the work, so the setup prints both.
fn cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    // Fields after the parenthesised command name; utime and stime are fields 14 and 15.
    let rest = stat.rsplit_once(')')?.1;
    let f: Vec<&str> = rest.split_whitespace().collect();
    let ticks: f64 = f.get(11)?.parse::<f64>().ok()? + f.get(12)?.parse::<f64>().ok()?;
    Some(ticks / 100.0)
}

/// Runs `f` `n` times; prints its mean wall and CPU time; returns the last result.
fn timed<T>(what: &str, n: u32, mut f: impl FnMut() -> T) -> T {
    let (t, c) = (Instant::now(), cpu_seconds());
    let mut out = None;
    for _ in 0..n {
        out = Some(black_box(f()));
    }
    let wall = t.elapsed().as_secs_f64() / n as f64;
    let cpu = match (c, cpu_seconds()) {
        (Some(a), Some(b)) => format!("{:.3} s", (b - a) / n as f64),
        _ => "unknown".into(),
    };
    eprintln!("{what}: wall {wall:.3} s, cpu {cpu} (mean of {n})");
    out.expect("n >= 1")
}

fn bench(c: &mut Criterion) {
    let (surfaces, pairs) = inputs();
    // A few timed passes per stage, to say where the time goes.
    let n = 3;
    let xs = timed("intersect", n, || intersect_all(&surfaces, &pairs));
    let split = timed("split", n, || split_all(&surfaces, &xs));
    let kept = timed("patches", n, || patches_in_box(&surfaces, &split));
    let m = timed("regions", n, || regions(&kept));
    timed("model", n, || model(&surfaces, &pairs));
    eprintln!(
        "{} pairs, {} patches, {} regions",
        pairs.len(),
        kept.len(),
        m.regions.len()
    );
    assert_eq!(m.regions.len(), 6, "3 layers on each side of F1");
    let mut named: Vec<&str> = m.regions.iter().map(|r| r.name.as_str()).collect();
    named.sort_unstable();
    let mut want: Vec<String> = names().into_iter().map(|n| n.0).collect();
    want.sort_unstable();
    assert_eq!(named, want, "every recipe point names its region");

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
