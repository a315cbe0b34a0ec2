//! The tetrahedral mesher on boundaries no one here wrote: the six regions of the didactic model
//! meshed by Gmsh (`../shared/data/peer-boundaries/region_L1_*.off`), with the dangling fault's
//! triangles taken from `didactic_L1_surface.msh` as embedded faces where the meta file says so.
//! Each region must mesh and pass `verify`; per-region figures are printed.

use std::time::Instant;

use tet_mesh::{SizeField, TetMeshOptions, mesh_region, verify};

use peer_support::{peer_dir, peer_region};
use test_support::peer_support;

fn run(name: &str) {
    let Some(dir) = peer_dir() else { return };
    let input = peer_region(&dir, name).unwrap_or_else(|e| panic!("{e}"));
    let t0 = Instant::now();
    let out = mesh_region(&input, &SizeField::default(), &TetMeshOptions::default())
        .unwrap_or_else(|e| panic!("{e}"));
    let dt = t0.elapsed().as_secs_f64();
    verify(&input, &out).expect("verify");
    let s = &out.stats;
    eprintln!(
        "{name}: {} boundary + {} embedded triangles -> {} tets, {:.2} s ({:.0} tets/s), mean ratio min {:.3} avg {:.3}, min dihedral {:.1} deg, backtracks {}",
        input.boundary.len(),
        input.embedded.len(),
        s.tets,
        dt,
        s.tets as f64 / dt,
        s.min_mean_ratio,
        s.avg_mean_ratio,
        s.min_dihedral_deg,
        s.backtracks
    );
    let n_in = input.vertices.len() as u32;
    let bad: Vec<&[u32; 4]> = out
        .tets
        .iter()
        .filter(|t| {
            let [a, b, c, d] = t.map(|i| out.nodes[i as usize]);
            tet_mesh::quality::mean_ratio(&a, &b, &c, &d) < 0.05
        })
        .collect();
    let all_input = bad.iter().filter(|t| t.iter().all(|&v| v < n_in)).count();
    eprintln!(
        "{name}: {} tets below mean ratio 0.05, {all_input} of them with only boundary nodes",
        bad.len()
    );
    assert!(s.min_mean_ratio > 0.0);
    // The quality bars, met on every region since the optimizer (flips, smoothing, insertion):
    // normalised mean ratio at least 0.3 and dihedral angles at least 10 degrees everywhere.
    assert!(
        s.min_mean_ratio >= 0.3,
        "{name}: min mean ratio {}",
        s.min_mean_ratio
    );
    assert!(
        s.min_dihedral_deg >= 10.0,
        "{name}: min dihedral {}",
        s.min_dihedral_deg
    );
    // Averages on the same boundaries (bench_peers.py, L1): TetGen pq1.2/15YA 0.837 and Gmsh
    // HXT 0.795 in the over/underburden, HXT 0.668 and TetGen 0.660 in the reservoir layer
    // (measured here: 0.849-0.853, and 0.640 (W) / 0.679 (E) in the reservoir).
    let floor = if name.starts_with("reservoir") {
        0.63
    } else {
        0.84
    };
    assert!(
        s.avg_mean_ratio >= floor,
        "{name}: average mean ratio {}",
        s.avg_mean_ratio
    );
    // Measured: on the reservoirs every tet below 0.05 has only boundary nodes (none the
    // optimizer could move); elsewhere at most 0.1% of the tets are below 0.05.
    assert!(
        (bad.len() - all_input) * 500 <= out.tets.len(),
        "too many poor tets with an interior node"
    );
}

#[test]
fn peer_region_underburden_w_meshes_and_verifies() {
    run("underburden_W");
}
#[test]
fn peer_region_reservoir_w_meshes_and_verifies() {
    run("reservoir_W");
}
#[test]
fn peer_region_overburden_w_meshes_and_verifies() {
    run("overburden_W");
}
#[test]
fn peer_region_underburden_e_with_its_dangling_fault_meshes_and_verifies() {
    run("underburden_E");
}
#[test]
fn peer_region_reservoir_e_with_its_dangling_fault_meshes_and_verifies() {
    run("reservoir_E");
}
#[test]
fn peer_region_overburden_e_with_its_dangling_fault_meshes_and_verifies() {
    run("overburden_E");
}
