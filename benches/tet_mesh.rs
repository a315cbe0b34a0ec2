//! Single-thread throughput of the tetrahedral mesher (tets/s, optimization included) on peer
//! boundaries that no one here wrote: `../shared/data/peer-boundaries/region_L1_<name>.off` for
//! the thin reservoir layer (`reservoir_W`, 3842 triangles, ~5.4k tets) and the overburden
//! (`overburden_W`, 3622 triangles, ~18.5k tets). Skips with a note when ../shared is absent.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use georecipe::stages::tet_mesh::{RegionInput, SizeField, TetMeshOptions, mesh_region};

type Off = (Vec<[f64; 3]>, Vec<[u32; 3]>);

fn read_off(path: &str) -> Option<Off> {
    let text = std::fs::read_to_string(path).ok()?;
    let mut it = text
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty() && !l.starts_with('#'));
    if it.next()? != "OFF" {
        return None;
    }
    let counts: Vec<usize> = it
        .next()?
        .split_whitespace()
        .filter_map(|x| x.parse().ok())
        .collect();
    let mut v = Vec::new();
    for _ in 0..*counts.first()? {
        let c: Vec<f64> = it
            .next()?
            .split_whitespace()
            .filter_map(|x| x.parse().ok())
            .collect();
        v.push([*c.first()?, *c.get(1)?, *c.get(2)?]);
    }
    let mut f = Vec::new();
    for _ in 0..*counts.get(1)? {
        let c: Vec<u32> = it
            .next()?
            .split_whitespace()
            .filter_map(|x| x.parse().ok())
            .collect();
        f.push([*c.get(1)?, *c.get(2)?, *c.get(3)?]);
    }
    Some((v, f))
}

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("tet_mesh");
    g.sample_size(10);
    for name in ["reservoir_W", "overburden_W"] {
        let path = format!(
            "{}/../shared/data/peer-boundaries/region_L1_{name}.off",
            env!("CARGO_MANIFEST_DIR")
        );
        let Some((vertices, boundary)) = read_off(&path) else {
            eprintln!("skipping: ../shared is absent");
            return;
        };
        let input = RegionInput {
            name: name.into(),
            vertices,
            boundary,
            embedded: vec![],
        };
        let size = SizeField::default();
        let opts = TetMeshOptions::default();
        let tets = match mesh_region(&input, &size, &opts) {
            Ok(out) => out.tets.len(),
            Err(e) => {
                eprintln!("skipping: {e}");
                return;
            }
        };
        g.throughput(Throughput::Elements(tets as u64));
        g.bench_function(format!("{name} single thread"), |b| {
            b.iter(|| mesh_region(&input, &size, &opts))
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
