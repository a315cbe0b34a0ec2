//! `mesh_patch_with_progress`: what it tells a progress bar (one fixed total, `done` that only
//! grows and ends at the total, a few hundred calls at most, reports all along the work), and
//! that watching leaves the mesh bit for bit the same.

use std::cell::RefCell;

use surface_mesh::{PatchInput, mesh_patch_refined, mesh_patch_with_progress};
use surface_mesh_common::*;
use test_support::progress::assert_a_good_bar;
use test_support::surface_mesh_common;

#[test]
fn the_surface_mesher_reports_growing_progress_that_ends_at_its_total() {
    let g = Grid {
        nx: 12,
        ny: 10,
        u: (0.0, 3000.0),
        v: (0.0, 2500.0),
        f: wavy,
        offset: UTM,
    };
    let input = PatchInput {
        name: "wavy".into(),
        support: g.support(),
        loops: vec![g.border_loop(60, 50)],
        constraints: vec![],
        points: vec![],
        facets: Vec::new(),
    };
    let (size, tolerances) = (uniform(50.0), geom::Tolerances::default());
    let seen = RefCell::new(Vec::new());
    let out = mesh_patch_with_progress(&input, &size, &tolerances, &[], &|done, total| {
        seen.borrow_mut().push((done, total))
    })
    .expect("meshes");
    assert!(out.nodes.len() > 2000, "{} nodes", out.nodes.len());
    assert_a_good_bar("surface", &seen.into_inner());
    assert_eq!(
        out,
        mesh_patch_refined(&input, &size, &tolerances, &[]).expect("meshes"),
        "watching changed the mesh"
    );
}
