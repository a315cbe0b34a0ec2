//! `mesh_region_with_progress`: what it tells a progress bar (one fixed total, `done` that only
//! grows and ends at the total, a few hundred calls at most, reports all along the work rather
//! than at its ends), for both methods, nothing like an end when it fails, and that watching
//! leaves the mesh bit for bit the same.

use std::cell::RefCell;

use crate::tet_mesh_quality::{build_size, case};
use test_support::progress::assert_a_good_bar;
use tet_mesh::{
    Method, RegionInput, SizeField, TetMeshOptions, TetMeshOutput, mesh_region,
    mesh_region_with_progress,
};

/// The shipped example's east overburden with the dangling fault in it, at the build's sizes.
fn region() -> (RegionInput, SizeField) {
    (case("shipped_overburden_E"), build_size())
}

/// Meshes with and without a watcher; returns the reports and the mesh, after checking that
/// the two meshes are the same.
fn watched(method: Method) -> (Vec<(u64, u64)>, TetMeshOutput) {
    let (input, size) = region();
    let opts = TetMeshOptions {
        method,
        ..TetMeshOptions::default()
    };
    let seen = RefCell::new(Vec::new());
    let out = mesh_region_with_progress(&input, &size, &opts, &|done, total| {
        seen.borrow_mut().push((done, total))
    })
    .expect("meshes");
    let plain = mesh_region(&input, &size, &opts).expect("meshes");
    assert_eq!(out.nodes, plain.nodes, "{method:?}: watching moved nodes");
    assert_eq!(out.tets, plain.tets, "{method:?}: watching changed tets");
    (seen.into_inner(), out)
}

#[test]
fn the_delaunay_mesher_reports_growing_progress_that_ends_at_its_total() {
    let (seen, out) = watched(Method::Delaunay);
    assert!(out.stats.fallback.is_none(), "{:?}", out.stats.fallback);
    assert!(out.stats.new_nodes > 1000, "{:?}", out.stats);
    assert_a_good_bar("delaunay", &seen);
}

#[test]
fn the_advancing_front_reports_growing_progress_that_ends_at_its_total() {
    let (seen, out) = watched(Method::Front);
    assert!(out.stats.new_nodes > 1000, "{:?}", out.stats);
    assert_a_good_bar("front", &seen);
}

#[test]
fn a_region_that_cannot_be_meshed_never_reports_its_end() {
    let (mut input, size) = region();
    // One boundary triangle turned inside out: the boundary is no longer closed and oriented.
    input.boundary[0].swap(1, 2);
    let seen = RefCell::new(Vec::new());
    let result = mesh_region_with_progress(&input, &size, &TetMeshOptions::default(), &|d, t| {
        seen.borrow_mut().push((d, t))
    });
    assert!(result.is_err());
    let seen = seen.into_inner();
    assert!(seen.iter().all(|&(d, t)| d < t), "{seen:?}");
}
