//! Surface-mesh quality on the configurations that decide the seed's Table 1: a fine border graded
//! into a coarse interior, a fine curve meeting a coarse one at a corner, a thin strip between two
//! curves, and the single-segment strip of the seed's refinement (a).

use test_support::surface_mesh_common;

use surface_mesh::quality::{c_ratio, stats};
use surface_mesh::{PatchInput, SurfaceSize, mesh_patch};
use surface_mesh_common::{Grid, UTM, mesh_and_check};

fn flat(u: (f64, f64), v: (f64, f64)) -> Grid<impl Fn(f64, f64) -> [f64; 3]> {
    Grid {
        nx: 8,
        ny: 8,
        u,
        v,
        f: |x, y| [x, y, -1200.0],
        offset: UTM,
    }
}

/// The recipe default: 200 m surfaces, volume growth 1.3.
fn recipe_size() -> SurfaceSize {
    SurfaceSize {
        size: 200.0,
        min_size: 2.0,
        max_size: 2000.0,
        growth: 1.3,
    }
}

/// A loop along the rectangle's border with the given node counts on its bottom, right, top and
/// left sides (counter-clockwise from the bottom-left corner).
fn border(
    g: &Grid<impl Fn(f64, f64) -> [f64; 3]>,
    bottom: usize,
    right: usize,
    top: usize,
    left: usize,
) -> Vec<[f64; 3]> {
    let (u0, u1) = g.u;
    let (v0, v1) = g.v;
    let mut l = Vec::new();
    for k in 0..bottom {
        l.push(g.at(u0 + (u1 - u0) * k as f64 / bottom as f64, v0));
    }
    for k in 0..right {
        l.push(g.at(u1, v0 + (v1 - v0) * k as f64 / right as f64));
    }
    for k in 0..top {
        l.push(g.at(u1 - (u1 - u0) * k as f64 / top as f64, v1));
    }
    for k in 0..left {
        l.push(g.at(u0, v1 - (v1 - v0) * k as f64 / left as f64));
    }
    l
}

#[test]
fn a_25_m_border_graded_into_a_200_m_interior_stays_near_equilateral() {
    let g = flat((0.0, 2000.0), (0.0, 2000.0));
    let input = PatchInput {
        name: "flat 2000 m, 25 m border, 200 m inside".into(),
        support: g.support(),
        loops: vec![border(&g, 80, 80, 80, 80)],
        constraints: vec![],
        points: Vec::new(),
        facets: Vec::new(),
    };
    // Gmsh's frontal-Delaunay (algorithm 6) on the same square and sizes: mean 1.048 at growth
    // 1.3, 1.030 at 1.15.
    let (out, q) = mesh_and_check(&input, &recipe_size(), 1.035, 2.0);
    assert!(q.pct_above_1_5 == 0.0, "{q:?}");
    // Graded: far more triangles than a uniform 200 m mesh (~230), far fewer than 25 m (~14800).
    assert!(
        out.triangles.len() > 1500 && out.triangles.len() < 8000,
        "{q:?}"
    );
}

#[test]
fn a_fine_curve_ending_on_a_coarse_one_keeps_its_size_up_to_the_corner() {
    // The bottom side is a 25 m curve; the other three are 200 m curves, as where a reservoir
    // horizon meets a box edge. Triangles on the 25 m side must not fan out from a few coarse
    // points near the corners.
    let g = flat((0.0, 1600.0), (0.0, 1200.0));
    let input = PatchInput {
        name: "25 m bottom, 200 m elsewhere".into(),
        support: g.support(),
        loops: vec![border(&g, 64, 6, 8, 6)],
        constraints: vec![],
        points: Vec::new(),
        facets: Vec::new(),
    };
    // The triangles on the two 200 m edges next to the corners cannot be good (a 200 m edge
    // beside 25 m elements); they are the only bad ones.
    let (out, q) = mesh_and_check(&input, &recipe_size(), 1.05, 3.0);
    let left_or_right = |p: &[[f64; 3]; 3]| {
        (0..3).any(|i| {
            let (a, b) = (p[i][0] - UTM[0], p[(i + 1) % 3][0] - UTM[0]);
            (a == 0.0 && b == 0.0) || (a == 1600.0 && b == 1600.0)
        })
    };
    let mut bad_inside = Vec::new();
    for t in &out.triangles {
        let p = t.map(|v| out.nodes[v as usize]);
        let g = [0, 1].map(|k| (p[0][k] + p[1][k] + p[2][k]) / 3.0 - UTM[k]);
        let near_a_corner = g[1] < 400.0 && (g[0] < 300.0 || g[0] > 1300.0);
        if c_ratio(&p[0], &p[1], &p[2]) > 1.5 && !(near_a_corner || left_or_right(&p)) {
            bad_inside.push((g, c_ratio(&p[0], &p[1], &p[2])));
        }
    }
    assert!(bad_inside.is_empty(), "{bad_inside:?} {q:?}");
    // Every triangle with an edge on the bottom side is well shaped.
    let y0 = UTM[1];
    let mut on_bottom = 0;
    for t in &out.triangles {
        let p = t.map(|v| out.nodes[v as usize]);
        let edge_on_bottom = (0..3).any(|i| p[i][1] == y0 && p[(i + 1) % 3][1] == y0);
        if edge_on_bottom {
            on_bottom += 1;
            let c = c_ratio(&p[0], &p[1], &p[2]);
            let x = (p[0][0] + p[1][0] + p[2][0]) / 3.0 - UTM[0];
            // The two corner triangles also touch a 200 m edge.
            if x > 50.0 && x < 1550.0 {
                assert!(c < 1.3, "bottom triangle at x = {x:.0}: c/c* {c:.3}");
            }
        }
    }
    assert_eq!(on_bottom, 64);
}

#[test]
fn a_35_m_strip_between_curves_at_its_width_has_no_bad_triangle() {
    // 5000 m × 35 m, long sides at 40 m (the strip rule of refinement (b)), short sides one edge.
    let g = flat((0.0, 5000.0), (0.0, 35.0));
    let input = PatchInput {
        name: "strip 5000 x 35 m at 40 m".into(),
        support: g.support(),
        loops: vec![border(&g, 125, 1, 125, 1)],
        constraints: vec![],
        points: Vec::new(),
        facets: Vec::new(),
    };
    let (_, q) = mesh_and_check(&input, &recipe_size(), 1.2, 1.25);
    assert_eq!(q.pct_above_1_5, 0.0);
}

#[test]
fn a_strip_with_single_segment_ends_and_coarse_sides_is_meshed_validly_and_no_worse_than_forced() {
    // The seed's refinement (a): 35 m strip with 200 m curves on both long sides. Every triangle
    // must use two nodes of one side and one of the other; aligned nodes force c/c* =
    // (200² + 35²) / (√3 · 200 · 35) = 3.40, and the mesher must not do worse than that.
    let g = flat((0.0, 2000.0), (0.0, 35.0));
    let input = PatchInput {
        name: "strip 2000 x 35 m at 200 m".into(),
        support: g.support(),
        loops: vec![border(&g, 10, 1, 10, 1)],
        constraints: vec![],
        points: Vec::new(),
        facets: Vec::new(),
    };
    let forced = (200.0f64.powi(2) + 35.0f64.powi(2)) / (3f64.sqrt() * 200.0 * 35.0);
    let (out, q) = mesh_and_check(&input, &recipe_size(), forced + 1e-6, forced + 1e-6);
    assert_eq!(out.nodes.len(), 22, "no node can help inside a 35 m strip");
    assert!(q.max > 3.0);
}

#[test]
fn the_surface_growth_is_capped_whatever_the_volume_growth_allows() {
    // Growth 3.0 (a slope of 2 per unit length) must mesh like the capped growth: the surface
    // mesher grades at most MAX_SURFACE_GROWTH per element.
    let g = flat((0.0, 2000.0), (0.0, 2000.0));
    let input = PatchInput {
        name: "flat, growth 3".into(),
        support: g.support(),
        loops: vec![border(&g, 80, 80, 80, 80)],
        constraints: vec![],
        points: Vec::new(),
        facets: Vec::new(),
    };
    let fast = SurfaceSize {
        growth: 3.0,
        ..recipe_size()
    };
    let a = mesh_patch(&input, &fast).expect("meshes");
    let b = mesh_patch(&input, &recipe_size()).expect("meshes");
    assert_eq!(a, b);
    let q = stats(&a.nodes, &a.triangles);
    assert!(q.mean <= 1.035, "{q:?}");
}
