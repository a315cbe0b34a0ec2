//! The model's topology (the `model` crate) on small hand-made models at UTM magnitudes: a box cut
//! by one horizon, and the same with a fault that dangles across the horizon. Checks the curve
//! names, the topological vertices, every patch's loops, the dangling trace as a constraint,
//! and that nothing depends on the order the patches come in.

use geom::{BBox, Tolerances, TriMesh};
use model::intersect::split::split_model;
use model::intersect::{SurfaceRef, box_sides, intersect};
use model::patches::{inside_box, patches};
use model::regions::PatchIn;
use model::{Curve, CurveUse, ModelTopology, PatchBoundary, build_topology};

const X: f64 = 500_000.0;
const Y: f64 = 7_000_000.0;

fn bbox() -> BBox {
    BBox {
        min: [X, Y, -2000.0],
        max: [X + 1000.0, Y + 1000.0, 0.0],
    }
}

/// A flat horizon at z = -1000 reaching beyond the box, as 2 triangles.
fn horizon() -> TriMesh {
    TriMesh::new(
        vec![
            [X - 100.0, Y - 100.0, -1000.0],
            [X + 1100.0, Y - 100.0, -1000.0],
            [X + 1100.0, Y + 1100.0, -1000.0],
            [X - 100.0, Y + 1100.0, -1000.0],
        ],
        vec![[0, 1, 2], [0, 2, 3]],
    )
}

/// A vertical fault inside the box (x = X+500, y in [Y+300, Y+700], z in [-1400, -600]).
fn fault() -> TriMesh {
    let x = X + 500.0;
    TriMesh::new(
        vec![
            [x, Y + 300.0, -1400.0],
            [x, Y + 700.0, -1400.0],
            [x, Y + 700.0, -600.0],
            [x, Y + 300.0, -600.0],
        ],
        vec![[0, 1, 2], [0, 2, 3]],
    )
}

/// Splits the surfaces along every pairwise intersection and keeps the patches in the box.
fn model_patches(with_fault: bool) -> Vec<PatchIn> {
    let mut surfaces: Vec<(String, TriMesh)> = vec![("H".to_string(), horizon())];
    if with_fault {
        surfaces.push(("F".to_string(), fault()));
    }
    surfaces.extend(box_sides(&bbox()));
    let mut xs = Vec::new();
    for i in 0..surfaces.len() {
        for j in i + 1..surfaces.len() {
            let (a, b) = (&surfaces[i], &surfaces[j]);
            if a.0.starts_with("box.") && b.0.starts_with("box.") {
                continue; // the box sides already share their edges
            }
            let x = intersect(
                SurfaceRef {
                    name: &a.0,
                    mesh: &a.1,
                },
                SurfaceRef {
                    name: &b.0,
                    mesh: &b.1,
                },
            )
            .expect("no coplanar contact");
            if !x.curves.is_empty() {
                xs.push(x);
            }
        }
    }
    let refs: Vec<(&str, &TriMesh)> = surfaces.iter().map(|(n, m)| (n.as_str(), m)).collect();
    let split = split_model(&refs, &xs).expect("splits");
    let mut kept = Vec::new();
    for ((name, _), s) in surfaces.iter().zip(&split) {
        for p in patches(name, s) {
            if inside_box(&p, &bbox()) {
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

fn names(t: &ModelTopology) -> Vec<&str> {
    t.curves.iter().map(|c| c.name.as_str()).collect()
}

#[test]
fn a_box_cut_by_a_horizon_has_twelve_vertices_and_twenty_named_curves() {
    let kept = model_patches(false);
    assert_eq!(kept.len(), 11, "H, zmin, zmax and four sides cut in two");
    let t = build_topology(&kept, &Tolerances::default()).expect("topology");
    assert_eq!(
        t.vertices.len(),
        12,
        "8 box corners + 4 where H meets the vertical edges"
    );
    assert_eq!(t.curves.len(), 20, "{:?}", names(&t));
    let n = names(&t);
    for c in [
        "H/box.xmin",
        "H/box.ymax",
        "box.xmin/box.ymin#1",
        "box.xmin/box.ymin#2",
        "box.xmin/box.zmin",
    ] {
        assert!(n.contains(&c), "{c} missing from {n:?}");
    }
    // The lower piece of a split vertical edge ranks first: its polyline starts lower.
    let lower = t
        .curves
        .iter()
        .find(|c| c.name == "box.xmin/box.ymin#1")
        .expect("curve");
    assert_eq!(lower.points[0], [X, Y, -2000.0]);
    assert_eq!(lower.points[lower.points.len() - 1], [X, Y, -1000.0]);
    for (p, b) in kept.iter().zip(&t.patches) {
        assert_eq!(b.loops.len(), 1, "{} has one loop", p.name);
        assert_eq!(b.loops[0].len(), 4, "{} is bounded by four curves", p.name);
        assert!(b.constraints.is_empty());
    }
}

#[test]
fn every_patch_loop_joins_end_to_start_in_the_patch_orientation() {
    let kept = model_patches(true);
    let t = build_topology(&kept, &Tolerances::default()).expect("topology");
    for (p, b) in kept.iter().zip(&t.patches) {
        for lp in &b.loops {
            let ends: Vec<([f64; 3], [f64; 3])> = lp
                .iter()
                .map(|u| {
                    let pts = &t.curves[u.curve as usize].points;
                    let (a, z) = (pts[0], pts[pts.len() - 1]);
                    if u.reversed { (z, a) } else { (a, z) }
                })
                .collect();
            for k in 0..ends.len() {
                assert_eq!(ends[k].1, ends[(k + 1) % ends.len()].0, "{}", p.name);
            }
            // The first curve use runs along the patch's own boundary half-edges.
            let u = lp[0];
            let pts = &t.curves[u.curve as usize].points;
            let (a, b) = if u.reversed {
                (pts[pts.len() - 1], pts[pts.len() - 2])
            } else {
                (pts[0], pts[1])
            };
            let ia = p
                .mesh
                .vertices
                .iter()
                .position(|v| *v == a)
                .expect("on patch");
            let ib = p
                .mesh
                .vertices
                .iter()
                .position(|v| *v == b)
                .expect("on patch");
            let runs = p
                .mesh
                .triangles
                .iter()
                .any(|t| (0..3).any(|k| t[k] == ia as u32 && t[(k + 1) % 3] == ib as u32));
            assert!(runs, "{}: loop against the triangles", p.name);
        }
    }
}

#[test]
fn a_dangling_fault_trace_is_a_constraint_of_the_horizon_patch_and_its_tips_are_free_curves() {
    let kept = model_patches(true);
    let t = build_topology(&kept, &Tolerances::default()).expect("topology");
    let n = names(&t);
    assert!(n.contains(&"F/H"), "{n:?}");
    let fh = n.iter().position(|c| *c == "F/H").expect("F/H") as u32;
    let h = kept.iter().position(|p| p.surface == "H").expect("H patch");
    assert_eq!(
        kept.iter().filter(|p| p.surface == "H").count(),
        1,
        "a dangling fault does not cut the horizon"
    );
    assert_eq!(t.patches[h].constraints, vec![fh]);
    // F is cut by H into an upper and a lower patch, each with a free border made of three
    // straight pieces between the rectangle's corners and the trace's ends (kinks are vertices).
    assert_eq!(kept.iter().filter(|p| p.surface == "F").count(), 2);
    let free: Vec<&&str> = n.iter().filter(|c| c.starts_with("F#")).collect();
    assert_eq!(free.len(), 6, "{n:?}");
    for (p, b) in kept
        .iter()
        .zip(&t.patches)
        .filter(|(p, _)| p.surface == "F")
    {
        assert_eq!(b.loops.len(), 1, "{}", p.name);
        assert_eq!(
            b.loops[0].len(),
            4,
            "{}: three free pieces and the trace",
            p.name
        );
    }
}

#[test]
fn names_and_curves_do_not_depend_on_the_order_of_the_patches() {
    let kept = model_patches(true);
    let t = build_topology(&kept, &Tolerances::default()).expect("topology");
    let mut rev = kept.clone();
    rev.reverse();
    let r = build_topology(&rev, &Tolerances::default()).expect("topology");
    assert_eq!(t.vertices, r.vertices);
    assert_eq!(names(&t), names(&r));
    for (a, b) in t.curves.iter().zip(&r.curves) {
        assert_eq!(a.points, b.points, "{}", a.name);
        assert_eq!(a.surfaces, b.surfaces);
    }
    // Patch boundaries match once the patch order is undone.
    let n = kept.len();
    for i in 0..n {
        assert_eq!(t.patches[i].constraints, r.patches[n - 1 - i].constraints);
        assert_eq!(t.patches[i].loops.len(), r.patches[n - 1 - i].loops.len());
    }
}

fn curve(k: usize) -> Curve {
    Curve {
        name: format!("c{k}"),
        surfaces: vec!["s".into()],
        patches: vec![0],
        points: vec![[k as f64, 0.0, 0.0], [k as f64 + 1.0, 0.0, 0.0]],
        closed: false,
        clearance: Vec::new(),
        curvature_size: Vec::new(),
        narrow_size: Vec::new(),
    }
}

fn uses(curves: &[u32]) -> Vec<CurveUse> {
    curves
        .iter()
        .map(|&curve| CurveUse {
            curve,
            reversed: false,
        })
        .collect()
}

#[test]
fn every_loop_gets_three_nodes_whatever_the_sizes_say() {
    let topo = ModelTopology {
        vertices: Vec::new(),
        curves: (0..7).map(curve).collect(),
        patches: vec![
            PatchBoundary {
                // A closed curve alone, and a loop of two curves (a hole).
                loops: vec![uses(&[0]), uses(&[1, 2])],
                constraints: Vec::new(),
            },
            PatchBoundary {
                // Three curves, and curve 2 again in a loop of three.
                loops: vec![uses(&[3, 4, 5]), uses(&[2, 5, 6])],
                constraints: Vec::new(),
            },
        ],
    };
    assert_eq!(topo.min_segments(), vec![3, 2, 2, 1, 1, 1, 1]);
}
