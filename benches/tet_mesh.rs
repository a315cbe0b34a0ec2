//! Single-thread throughput of the tetrahedral mesher (tets/s, optimization and `verify`
//! included; the default method, Delaunay with local recovery) on peer boundaries that no one
//! here wrote (`../shared/data/peer-boundaries/`, meshed by Gmsh at level L1). Three scales:
//! - `reservoir_W` (thin layer) and `overburden_W` alone;
//! - `all six L1 regions` (~150k tets): the six regions one after the other, the dangling fault's
//!   triangles embedded where `didactic_L1_meta.json` says;
//! - `cube62` (~0.94M tets): a 6.2 km cube with 100 m boundary triangles on a structured grid,
//!   built here so a fresh checkout rebuilds it. Its squares are cospherical, so about a quarter
//!   of its triangles are not Delaunay faces: the Delaunay method gives way to the advancing front
//!   at once, and this scale measures the front. Run it alone, it takes about a minute:
//!   `cargo bench --bench tet_mesh -- cube62`.
//!
//! The comparison with TetGen and Gmsh HXT at L2/L3 (0.6M and 2.2M tets) is made by
//! `benches/peers/tet_regions.sh` on the boundaries `bench_peers.py` writes (see
//! `benches/peers/README.md`), and the mesher's own peak memory by `examples/tet_memory.rs`.
//!
//! Skips with a note when ../shared is absent.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use tet_mesh::{RegionInput, SizeField, TetMeshOptions, mesh_region};

use peer_support::{peer_dir, peer_region};
use test_support::peer_support;

const REGIONS: [&str; 6] = [
    "overburden_E",
    "overburden_W",
    "reservoir_E",
    "reservoir_W",
    "underburden_E",
    "underburden_W",
];

/// The cube `[0, n·step]^3`, each side split into `n x n` squares of two triangles, oriented
/// outward (a boundary any checkout can rebuild; `n = 62` gives about a million tets).
fn cube(n: u32, step: f64) -> RegionInput {
    let (vertices, boundary) = test_support::shapes::gridded_cube(n, n as f64 * step);
    RegionInput {
        name: format!("cube{n}"),
        vertices,
        boundary,
        embedded: vec![],
        lines: Vec::new(),
    }
}

fn mesh_all(inputs: &[RegionInput], size: &SizeField, opts: &TetMeshOptions) -> Option<usize> {
    let mut tets = 0;
    for input in inputs {
        match mesh_region(input, size, opts) {
            Ok(out) => tets += out.tets.len(),
            Err(e) => {
                eprintln!("skipping: {e}");
                return None;
            }
        }
    }
    Some(tets)
}

fn bench(c: &mut Criterion) {
    let size = SizeField::default();
    let opts = TetMeshOptions::default();
    let Some(dir) = peer_dir() else { return };
    let all = match REGIONS
        .iter()
        .map(|n| peer_region(&dir, n))
        .collect::<Result<Vec<_>, _>>()
    {
        Ok(all) => all,
        Err(e) => {
            eprintln!("skipping: {e}");
            return;
        }
    };
    let mut g = c.benchmark_group("tet_mesh");
    g.sample_size(10);
    let mut cases: Vec<(String, Vec<RegionInput>)> = ["reservoir_W", "overburden_W"]
        .iter()
        .filter_map(|n| all.iter().find(|r| r.name == *n))
        .map(|r| (format!("{} single thread", r.name), vec![r.clone()]))
        .collect();
    cases.push(("all six L1 regions single thread".into(), all.clone()));
    cases.push(("cube62 single thread".into(), vec![cube(62, 100.0)]));
    for (label, inputs) in &cases {
        // Mesh once for the tet count (criterion's filter still applies to the timing below; the
        // big case is only meshed when selected).
        if !criterion_selects(label) {
            continue;
        }
        let Some(tets) = mesh_all(inputs, &size, &opts) else {
            return;
        };
        eprintln!("{label}: {tets} tets");
        g.throughput(Throughput::Elements(tets as u64));
        g.bench_function(label.as_str(), |b| {
            b.iter(|| mesh_all(inputs, &size, &opts))
        });
    }
    g.finish();
}

/// Whether to mesh `label` once for its tet count: criterion's own filter (a regex) still
/// decides what is timed; this only keeps the minutes-long million-tet case out unless the
/// command line names it (`-- cube62`).
fn criterion_selects(label: &str) -> bool {
    if !label.contains("cube62") {
        return true;
    }
    std::env::args()
        .skip(1)
        .any(|a| !a.starts_with('-') && a.contains("cube"))
}

/// `cube(30, 100.0)` (10,800 boundary triangles) with `n` small triangles embedded apart from
/// each other on a lattice inside it (a fault imported as loose pieces).
fn cube_with_loose_pieces(n: usize) -> RegionInput {
    let mut input = cube(30, 100.0);
    let side = (n as f64).cbrt().ceil() as usize;
    for k in 0..n {
        let [i, j, l] = [k % side, (k / side) % side, k / (side * side)];
        let at = [i, j, l].map(|c| 150.0 + c as f64 * 2700.0 / side as f64);
        let first = input.vertices.len() as u32;
        input.vertices.extend([
            at,
            [at[0] + 10.0, at[1], at[2]],
            [at[0], at[1] + 10.0, at[2] + 3.0],
        ]);
        input.embedded.push([first, first + 1, first + 2]);
    }
    input
}

/// The input check alone on many loose embedded pieces: each is tested for lying inside the
/// region, which must not cost a scan of the whole boundary per piece.
fn check(c: &mut Criterion) {
    let input = cube_with_loose_pieces(5000);
    tet_mesh::check_input(&input).expect("a valid input");
    let mut g = c.benchmark_group("tet_mesh_check");
    g.sample_size(10);
    g.bench_function("5000 loose embedded triangles in a cube of 10800", |b| {
        b.iter(|| tet_mesh::check_input(&input))
    });
    g.finish();
}

criterion_group!(benches, bench, check);
criterion_main!(benches);
