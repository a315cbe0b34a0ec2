//! Incremental rebuilds of the shipped example, proven: each test edits the recipe (or an input)
//! of an already built copy and asserts exactly which nodes re-ran and which did not.

use crate::common_cli;
use common_cli::*;

fn ran_after(s: &Scratch, from: &str, to: &str) -> (Vec<String>, serde_json::Value) {
    s.edit(from, to);
    let (ok, r, err) = s.build(&[]);
    assert!(ok, "{err}");
    (nodes_in_state(&r, "ran"), r)
}

fn assert_none_ran(ran: &[String], all: &[String], what: impl Fn(&str) -> bool) {
    for n in all.iter().filter(|n| what(n)) {
        assert!(!ran.contains(n), "`{n}` re-ran");
    }
}

#[test]
fn one_region_size_reruns_that_region_its_surfaces_their_curves_and_neighbours_only() {
    let s = Scratch::didactic_built();
    let (ran, r) = ran_after(
        &s,
        "[regions]",
        "[mesh.regions.underburden_W]\nsize = 150.0\n\n[regions]",
    );
    // Its patches at 150 m: every one of them, and the curves on their borders, re-ran.
    for must in [
        "tet_mesh:underburden_W",
        "surface_mesh:box.zmin#1",
        "mesh",
        "export",
    ] {
        assert!(
            ran.contains(&must.to_string()),
            "`{must}` did not re-run: {ran:?}"
        );
    }
    assert!(ran.iter().any(|n| n.starts_with("discretize:")));
    // Nothing above the reservoir and nothing before the model's curves.
    assert_none_ran(&ran, &all_nodes(&r), |n| {
        n.starts_with("import:")
            || n.starts_with("intersect:")
            || n.starts_with("curve:")
            || n == "model"
            || n.starts_with("tet_mesh:overburden")
            || n.starts_with("surface_mesh:H1#")
            || n.starts_with("surface_mesh:box.zmax#")
    });
}

#[test]
fn one_surface_size_reruns_its_patches_their_curves_and_the_overburden_only() {
    let s = Scratch::didactic_built();
    let (ran, r) = ran_after(
        &s,
        "[mesh.curves]",
        "[mesh.surfaces]\n\"box.zmax\" = { size = 150.0 }\n\n[mesh.curves]",
    );
    let all = all_nodes(&r);
    for n in all
        .iter()
        .filter(|n| n.starts_with("surface_mesh:box.zmax#"))
    {
        assert!(ran.contains(n), "`{n}` did not re-run");
    }
    assert!(
        ran.iter()
            .filter(|n| n.starts_with("discretize:"))
            .all(|n| n.contains("box.zmax")),
        "only the curves of the top of the box re-ran: {ran:?}"
    );
    assert_none_ran(&ran, &all, |n| {
        n == "model"
            || n.starts_with("tet_mesh:reservoir")
            || n.starts_with("tet_mesh:underburden")
            || n.starts_with("surface_mesh:H")
            || n.starts_with("surface_mesh:box.zmin#")
    });
}

#[test]
fn a_subdivision_change_that_gives_the_same_curve_nodes_is_cut_off_after_the_curves() {
    let s = Scratch::didactic_built();
    // 100 m and 99.999 m give every F2 curve the same number of equal segments.
    let (ran, r) = ran_after(
        &s,
        "\"F2\" = { size = 100.0 }",
        "\"F2\" = { size = 99.999 }",
    );
    assert!(!ran.is_empty());
    assert!(
        ran.iter()
            .all(|n| n.starts_with("discretize:") && n.contains("F2")),
        "only the F2 curves re-ran: {ran:?}"
    );
    let cut = nodes_in_state(&r, "cut off");
    assert!(
        cut.iter().any(|n| n.starts_with("surface_mesh:")),
        "the patches below them were cut off: {cut:?}"
    );
}

#[test]
fn changing_an_imported_surface_reruns_its_import_and_what_depends_on_its_geometry() {
    let s = Scratch::didactic_built();
    let f = s.path("data/didactic/F2_dangling.ts");
    let text = std::fs::read_to_string(&f).unwrap();
    // Move the fault's first vertex by a metre: a real change of the geometry.
    let first = text
        .lines()
        .find(|l| l.starts_with("VRTX") || l.starts_with("PVRTX"))
        .expect("a vertex line")
        .to_string();
    let mut parts: Vec<String> = first.split_whitespace().map(String::from).collect();
    let x: f64 = parts[2].parse().unwrap();
    parts[2] = format!("{}", x + 1.0);
    std::fs::write(&f, text.replacen(&first, &parts.join(" "), 1)).unwrap();
    let (ok, r, err) = s.build(&[]);
    assert!(ok, "{err}");
    let ran = nodes_in_state(&r, "ran");
    for must in ["import:F2", "intersect:F2/H1", "model", "export"] {
        assert!(
            ran.contains(&must.to_string()),
            "`{must}` did not re-run: {ran:?}"
        );
    }
    assert_none_ran(&ran, &all_nodes(&r), |n| {
        n.starts_with("import:") && n != "import:F2"
            || n.starts_with("intersect:") && !n.contains("F2")
            || n.starts_with("surface:box")
    });
}

#[test]
fn a_trim_reruns_the_model_and_only_the_meshes_of_what_it_removed_or_touched() {
    let s = Scratch::didactic_built();
    // What the shipped example has before the edit (nothing runs: every node is cached).
    let (ok, before, err) = s.build(&[]);
    assert!(ok, "{err}");
    let f2_before: Vec<String> = all_nodes(&before)
        .into_iter()
        .filter(|n| n.starts_with("surface_mesh:F2#"))
        .collect();
    assert_eq!(
        f2_before.len(),
        3,
        "F2 above, inside and below the reservoir"
    );
    // Keep only the part of the dangling fault F2 below the top of the reservoir.
    let (ran, r) = ran_after(
        &s,
        "[output]",
        "[[trim]]\nsurface = \"F2\"\nkeep = { below = \"H1\" }\n\n[output]",
    );
    let all = all_nodes(&r);
    let f2_after: Vec<&String> = all
        .iter()
        .filter(|n| n.starts_with("surface_mesh:F2#"))
        .collect();
    assert_eq!(
        f2_after.len(),
        2,
        "the F2 patch above H1 is gone: {f2_after:?}"
    );
    for must in ["model", "tet_mesh:overburden_E", "mesh", "export"] {
        assert!(
            ran.contains(&must.to_string()),
            "`{must}` did not re-run: {ran:?}"
        );
    }
    // Only F2's own curves and patches may be re-meshed, and only the region that held the
    // removed patch is re-meshed: the reservoir and underburden keep their F2 faces.
    assert_none_ran(&ran, &all, |n| {
        n.starts_with("discretize:") && !n.starts_with("discretize:F2")
            || n.starts_with("surface_mesh:") && !n.starts_with("surface_mesh:F2#")
            || n.starts_with("tet_mesh:") && n != "tet_mesh:overburden_E"
            || n.starts_with("import:")
            || n.starts_with("intersect:")
    });
}

#[test]
fn choosing_the_front_for_one_region_reruns_only_that_region_the_mesh_and_the_export() {
    let s = Scratch::didactic_built();
    let tets = |r: &serde_json::Value| {
        r["nodes"]
            .as_array()
            .unwrap()
            .iter()
            .find(|n| n["name"] == "tet_mesh:underburden_W")
            .expect("the region's node")["counts"]["tets"]
            .as_u64()
            .unwrap()
    };
    let (ok, before, err) = s.build(&[]);
    assert!(ok, "{err}");
    let (ran, after) = ran_after(
        &s,
        "[regions]",
        "[mesh.regions.underburden_W]\ntet_method = \"front\"\n\n[regions]",
    );
    assert_eq!(ran, vec!["export", "mesh", "tet_mesh:underburden_W"]);
    // The front places its own nodes: a different mesh of the same region (fewer tets).
    assert!(
        tets(&after) < tets(&before),
        "{} -> {}",
        tets(&before),
        tets(&after)
    );
    // Back to the default: the region re-runs (its settings are now keyed under
    // `mesh.regions`), makes the first mesh again, and the mesh and export are cut off.
    let (ran, again) = ran_after(&s, "tet_method = \"front\"", "tet_method = \"delaunay\"");
    assert_eq!(ran, vec!["tet_mesh:underburden_W"]);
    assert_eq!(tets(&again), tets(&before));
}

#[test]
fn layers_on_one_reservoir_rerun_it_its_surfaces_their_curves_and_neighbours_only() {
    let s = Scratch::didactic_built();
    let (ran, r) = ran_after(
        &s,
        "[regions]",
        "[mesh.regions.reservoir_W]\nlayers = 1\n\n[regions]",
    );
    for must in [
        "tet_mesh:reservoir_W",
        "tet_mesh:overburden_W",
        "tet_mesh:underburden_W",
        "discretize:F1/H1",
        "mesh",
        "export",
    ] {
        assert!(
            ran.contains(&must.to_string()),
            "`{must}` did not re-run: {ran:?}"
        );
    }
    // The thickness is the model's own measure: nothing up to the model's curves re-runs, nor
    // the box's top and floor, out of the layer's reach, nor the eastern side of the box.
    assert_none_ran(&ran, &all_nodes(&r), |n| {
        n.starts_with("import:")
            || n.starts_with("intersect:")
            || n.starts_with("curve:")
            || n == "model"
            || n.starts_with("surface_mesh:box.zmax#")
            || n.starts_with("surface_mesh:box.zmin#")
            || n.starts_with("surface_mesh:box.xmax#")
    });
    // Two layers instead of one: the same kind of nodes, none of those.
    let (again, r) = ran_after(&s, "layers = 1", "layers = 2");
    assert!(again.contains(&"tet_mesh:reservoir_W".to_string()));
    assert_none_ran(&again, &all_nodes(&r), |n| {
        n == "model" || n.starts_with("surface_mesh:box.zmax#")
    });
}

#[test]
fn an_aspect_on_one_layered_reservoir_reruns_its_meshes_and_its_neighbours_tets_only() {
    let s = Scratch::didactic_built();
    s.edit(
        "[regions]",
        "[mesh.regions.reservoir_W]\nlayers = 2\n\n[regions]",
    );
    let (ok, _, err) = s.build(&[]);
    assert!(ok, "{err}");
    let (ran, r) = ran_after(&s, "layers = 2", "layers = 2\naspect = 4");
    // Its top and base coarsen, its sides are meshed stretched across it, so it and the regions
    // sharing those patches re-run.
    for must in [
        "tet_mesh:reservoir_W",
        "tet_mesh:overburden_W",
        "tet_mesh:underburden_W",
        "mesh",
        "export",
    ] {
        assert!(
            ran.contains(&must.to_string()),
            "`{must}` did not re-run: {ran:?}"
        );
    }
    assert!(ran.iter().any(|n| n.starts_with("surface_mesh:H1#")));
    assert!(ran.iter().any(|n| n.starts_with("surface_mesh:box.xmin#")));
    // Not the model nor anything before it, nor the eastern reservoir and the box's top and
    // floor, beyond its reach. Its curves across the layer keep the count's size: the curves
    // of the box's vertical edges do not re-run.
    assert_none_ran(&ran, &all_nodes(&r), |n| {
        n.starts_with("import:")
            || n.starts_with("intersect:")
            || n.starts_with("curve:")
            || n == "model"
            || n == "tet_mesh:reservoir_E"
            || n.starts_with("surface_mesh:box.zmax#")
            || n.starts_with("surface_mesh:box.zmin#")
            || n.starts_with("discretize:box.xmin/box.ymin")
    });
    // A different aspect re-runs the same region and no model.
    let (again, r) = ran_after(&s, "aspect = 4", "aspect = 2");
    assert!(again.contains(&"tet_mesh:reservoir_W".to_string()));
    assert_none_ran(&again, &all_nodes(&r), |n| {
        n == "model" || n == "tet_mesh:reservoir_E"
    });
}
