//! Surface mesher on flat and simple patches: a square, a square with a hole, a dangling
//! constraint, graded boundary nodes, and a self-intersecting loop (an error naming the place).

mod surface_mesh_common;
use surface_mesh_common::*;

use georecipe::stages::surface_mesh::{PatchInput, SurfaceSize, mesh_patch};

fn flat(offset: [f64; 3]) -> Grid<impl Fn(f64, f64) -> [f64; 3]> {
    Grid { nx: 3, ny: 2, u: (0.0, 1000.0), v: (0.0, 1000.0), f: |x, y| [x, y, -500.0], offset }
}

#[test]
fn a_flat_square_with_four_discretized_sides_meshes_into_near_equilateral_triangles() {
    for off in [[0.0; 3], UTM] {
        let g = flat(off);
        let input = PatchInput {
            name: "flat square".into(),
            support: g.support(),
            loops: vec![g.border_loop(20, 20)],
            constraints: vec![],
        };
        let (out, q) = mesh_and_check(&input, &uniform(50.0), 1.06, 1.6);
        assert!(q.triangles > 600 && q.triangles < 1100, "{} triangles", q.triangles);
        // Every node on the plane z = -500 exactly (the support is flat).
        assert!(out.nodes.iter().all(|p| (p[2] + 500.0).abs() < 1e-9));
    }
}

#[test]
fn a_square_with_a_hole_leaves_the_hole_empty() {
    for off in [[0.0; 3], UTM] {
        let g = flat(off);
        let input = PatchInput {
            name: "square with hole".into(),
            support: g.support(),
            loops: vec![g.border_loop(20, 20), g.hole(500.0, 500.0, 200.0, 25)],
            constraints: vec![],
        };
        let (out, _) = mesh_and_check(&input, &uniform(50.0), 1.08, 1.7);
        // No triangle centroid inside the hole.
        for t in &out.triangles {
            let c: Vec<f64> = (0..2)
                .map(|k| t.iter().map(|&v| out.nodes[v as usize][k] - off[k]).sum::<f64>() / 3.0)
                .collect();
            let r = ((c[0] - 500.0).powi(2) + (c[1] - 500.0).powi(2)).sqrt();
            assert!(r > 190.0, "a triangle sits in the hole at r = {r}");
        }
    }
}

#[test]
fn a_dangling_constraint_polyline_becomes_interior_edges() {
    for off in [[0.0; 3], UTM] {
        let g = flat(off);
        let trace: Vec<[f64; 3]> = (0..=8).map(|k| g.at(300.0 + 50.0 * k as f64, 480.0 + 5.0 * k as f64)).collect();
        let from_border: Vec<[f64; 3]> = vec![g.at(0.0, 250.0), g.at(60.0, 260.0), g.at(120.0, 280.0)];
        let input = PatchInput {
            name: "dangling fault trace".into(),
            support: g.support(),
            loops: vec![g.border_loop(20, 20)],
            constraints: vec![trace.clone(), from_border],
        };
        let (out, _) = mesh_and_check(&input, &uniform(50.0), 1.08, 1.8);
        // The border-touching constraint starts on loop node 75 (left side, 250 m up): shared.
        let loop_nodes = 80;
        assert_eq!(out.nodes[loop_nodes].map(f64::to_bits), trace[0].map(f64::to_bits));
    }
}

#[test]
fn graded_boundary_nodes_give_a_graded_valid_mesh() {
    for off in [[0.0; 3], UTM] {
        let g = flat(off);
        // Bottom side graded from 10 m to ~200 m, others uniform 100 m.
        let mut bottom = vec![0.0];
        let mut h: f64 = 10.0;
        while bottom[bottom.len() - 1] + h < 1000.0 - h * 0.5 {
            let x = bottom[bottom.len() - 1] + h;
            bottom.push(x);
            h = (h * 1.25).min(200.0);
        }
        let mut l: Vec<[f64; 3]> = bottom.iter().map(|&x| g.at(x, 0.0)).collect();
        for k in 0..10 {
            l.push(g.at(1000.0, 100.0 * k as f64));
        }
        for k in 0..10 {
            l.push(g.at(1000.0 - 100.0 * k as f64, 1000.0));
        }
        // Left side graded the same way towards the fine corner at the origin.
        for &y in bottom.iter().rev() {
            if y < 1000.0 && y > 0.0 {
                l.push(g.at(0.0, y));
            }
        }
        l.insert(l.len() - (bottom.len() - 1), g.at(0.0, 1000.0));
        let input = PatchInput { name: "graded boundary".into(), support: g.support(), loops: vec![l], constraints: vec![] };
        let size = SurfaceSize { size: 100.0, min_size: 5.0, max_size: 200.0, growth: 1.25 };
        let (out, _) = mesh_and_check(&input, &size, 1.12, 2.2);
        // Small triangles near the fine corner, large ones far from it.
        let edge = |t: &[u32; 3]| {
            let a = out.nodes[t[0] as usize];
            let b = out.nodes[t[1] as usize];
            ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt()
        };
        let near = out.triangles.iter().filter(|t| out.nodes[t[0] as usize][0] - off[0] < 30.0 && out.nodes[t[0] as usize][1] - off[1] < 30.0).map(edge).fold(0.0, f64::max);
        let far = out.triangles.iter().filter(|t| out.nodes[t[0] as usize][1] - off[1] > 800.0).map(edge).fold(0.0, f64::max);
        assert!(near < 40.0 && far > 70.0, "near {near} far {far}");
    }
}

#[test]
fn a_self_intersecting_loop_is_an_error_naming_the_patch_and_the_place() {
    for off in [[0.0; 3], UTM] {
        let g = flat(off);
        let bow = vec![g.at(100.0, 100.0), g.at(900.0, 900.0), g.at(900.0, 100.0), g.at(100.0, 900.0)];
        let input = PatchInput { name: "bow tie".into(), support: g.support(), loops: vec![bow], constraints: vec![] };
        let e = mesh_patch(&input, &uniform(50.0)).unwrap_err();
        let at = e.at.expect("a place");
        assert!((at[0] - off[0] - 500.0).abs() < 1e-6 && (at[1] - off[1] - 500.0).abs() < 1e-6, "{e}");
        let msg = e.to_string();
        assert!(msg.contains("bow tie") && msg.contains("intersect"), "{msg}");
    }
}

#[test]
fn a_loop_node_off_the_support_is_an_error_with_its_place() {
    let g = flat([0.0; 3]);
    let mut l = g.border_loop(10, 10);
    l[3][2] += 1.0;
    let input = PatchInput { name: "lifted node".into(), support: g.support(), loops: vec![l.clone()], constraints: vec![] };
    let e = mesh_patch(&input, &uniform(100.0)).unwrap_err();
    assert_eq!(e.at, Some(l[3]), "{e}");
    assert!(e.to_string().contains("off the support"));
}
