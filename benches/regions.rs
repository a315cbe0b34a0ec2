//! Region-finding benchmark on RINGMesh's modelA4 (11 surfaces, 50 patches, ~50k triangles,
//! 8 regions): weld, radial sort, shells, exterior and nesting decisions, naming.
//!
//! Run: `cargo bench --bench regions` (skipped with a note when ../shared is absent).

use criterion::{Criterion, criterion_group, criterion_main};
use geom::TriMesh;
use gocad::import::{ImportOptions, import_surfaces};
use model::regions::{Dangling, PatchIn, RegionOptions, find_regions_with};
use std::collections::{BTreeMap, BTreeSet};
use std::hint::black_box;
use test_support::paths;

fn model_a4() -> Option<(Vec<PatchIn>, BTreeSet<String>)> {
    let path = paths::shared("data/gocad/ringmesh__RINGMesh/tests/data/modelA4.ml")?;
    let bytes = std::fs::read(&path).expect("read modelA4.ml");
    let opts = ImportOptions {
        skip_other_types: true,
        ..Default::default()
    };
    let surfaces = import_surfaces(&bytes, "modelA4.ml", &opts)
        .map_err(|e| eprintln!("skipping: modelA4.ml does not import: {e}"))
        .ok()?;
    let mut patches = Vec::new();
    let mut faults = BTreeSet::new();
    for s in &surfaces {
        for (k, part) in s.parts.iter().enumerate() {
            if part
                .model_tface
                .as_ref()
                .is_some_and(|m| m.1.contains("fault"))
            {
                faults.insert(s.name.clone());
            }
            let mut map: BTreeMap<u32, u32> = BTreeMap::new();
            let (mut vertices, mut triangles) = (Vec::new(), Vec::new());
            for (t, tri) in s.mesh.triangles.iter().enumerate() {
                if s.triangle_part[t] as usize == k {
                    triangles.push(tri.map(|v| {
                        *map.entry(v).or_insert_with(|| {
                            vertices.push(s.mesh.vertices[v as usize]);
                            (vertices.len() - 1) as u32
                        })
                    }));
                }
            }
            patches.push(PatchIn {
                chart_of: None,
                name: format!("{}/{}", s.name, part.name),
                surface: s.name.clone(),
                mesh: TriMesh::new(vertices, triangles),
            });
        }
    }
    Some((patches, faults))
}

fn regions(c: &mut Criterion) {
    let Some((patches, faults)) = model_a4() else {
        return;
    };
    let opts = RegionOptions {
        dangling: Dangling::Surfaces(faults),
    };
    let triangles: usize = patches.iter().map(|p| p.mesh.triangles.len()).sum();
    eprintln!("modelA4: {} patches, {triangles} triangles", patches.len());
    let mut g = c.benchmark_group("regions");
    g.sample_size(10);
    g.bench_function("find_regions_modelA4", |b| {
        b.iter(|| find_regions_with(black_box(&patches), &[], &opts).expect("regions"))
    });
    g.finish();
}

criterion_group!(benches, regions);
criterion_main!(benches);
