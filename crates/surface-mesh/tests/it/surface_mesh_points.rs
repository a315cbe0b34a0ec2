//! Fixed interior points (where wells cross a patch): each becomes a mesh node at its documented
//! index, bit for bit, among well-shaped triangles, on flat and curved supports, beside holes and
//! constraints; points given twice or on a loop node are merged; points outside the patch, on a
//! boundary or constraint segment, or off the support are errors naming the point and its place.

use surface_mesh_common::*;
use test_support::surface_mesh_common;

use proptest::prelude::*;
use std::f64::consts::PI;
use surface_mesh::quality::{c_ratio, stats};
use surface_mesh::{
    PatchInput, SurfaceMeshError, SurfaceMeshOutput, SurfaceSize, mesh_patch, verify,
};

fn flat(offset: [f64; 3]) -> Grid<impl Fn(f64, f64) -> [f64; 3]> {
    Grid {
        nx: 3,
        ny: 2,
        u: (0.0, 1000.0),
        v: (0.0, 1000.0),
        f: |x, y| [x, y, -500.0],
        offset,
    }
}

/// The flat 1000 m square with 50 m border segments (80 loop nodes) and `points`.
fn square_with(off: [f64; 3], points: Vec<[f64; 3]>) -> PatchInput {
    let g = flat(off);
    PatchInput {
        name: "square with points".into(),
        support: g.support(),
        loops: vec![g.border_loop(20, 20)],
        constraints: vec![],
        points,
        facets: Vec::new(),
    }
}

fn bits(p: &[f64; 3]) -> [u64; 3] {
    p.map(f64::to_bits)
}

/// The smallest angle (degrees) of a triangle of `out`.
fn min_angle(out: &SurfaceMeshOutput, t: &[u32; 3]) -> f64 {
    let p = t.map(|v| out.nodes[v as usize]);
    (0..3)
        .map(|i| {
            let (a, b, c) = (p[i], p[(i + 1) % 3], p[(i + 2) % 3]);
            let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
            let w = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
            let d = u[0] * w[0] + u[1] * w[1] + u[2] * w[2];
            let nu = (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]).sqrt();
            let nw = (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt();
            (d / (nu * nw)).clamp(-1.0, 1.0).acos().to_degrees()
        })
        .fold(180.0, f64::min)
}

/// The smallest angle of the triangles round node `v`, and how many there are.
fn min_angle_round(out: &SurfaceMeshOutput, v: u32) -> (f64, usize) {
    let round: Vec<f64> = out
        .triangles
        .iter()
        .filter(|t| t.contains(&v))
        .map(|t| min_angle(out, t))
        .collect();
    (round.iter().copied().fold(180.0, f64::min), round.len())
}

fn min_angle_all(out: &SurfaceMeshOutput) -> f64 {
    out.triangles
        .iter()
        .map(|t| min_angle(out, t))
        .fold(180.0, f64::min)
}

fn has_edge(out: &SurfaceMeshOutput, a: u32, b: u32) -> bool {
    out.triangles
        .iter()
        .any(|t| t.contains(&a) && t.contains(&b))
}

/// Whether `e` names the patch, contains every one of `words`, and is located at `at`.
fn assert_error(e: &SurfaceMeshError, words: &[&str], at: [f64; 3]) {
    let msg = e.to_string();
    assert!(msg.contains("surface mesh of patch"), "{msg}");
    for w in words {
        assert!(msg.contains(w), "`{w}` missing from: {msg}");
    }
    assert_eq!(e.at.map(|p| bits(&p)), Some(bits(&at)), "{msg}");
}

#[test]
fn a_point_inside_a_flat_square_becomes_a_node_at_its_index_among_well_shaped_triangles() {
    for off in [[0.0; 3], UTM] {
        let g = flat(off);
        // Anywhere in a support triangle, on a support edge (y = 500), at a support vertex.
        for (u, v) in [(437.3, 561.9), (500.0, 500.0), (1000.0 / 3.0, 500.0)] {
            let p = g.at(u, v);
            let input = square_with(off, vec![p]);
            let (out, _) = mesh_and_check(&input, &uniform(50.0), 1.03, 1.4);
            // After the 80 loop nodes, bit for bit, and nowhere else.
            assert_eq!(bits(&out.nodes[80]), bits(&p));
            assert_eq!(out.nodes.iter().filter(|q| bits(q) == bits(&p)).count(), 1);
            let (round, n) = min_angle_round(&out, 80);
            let all = min_angle_all(&out);
            assert!(n >= 5, "{n} triangles round the point");
            assert!(
                round >= 40.0 && round >= 0.9 * all,
                "({u}, {v}): smallest angle {round:.1}° round the point, {all:.1}° in the mesh"
            );
        }
    }
}

#[test]
fn several_points_two_a_twentieth_of_the_size_apart_mesh_graded_round_them() {
    for off in [[0.0; 3], UTM] {
        let g = flat(off);
        let points = vec![
            g.at(400.0, 600.0),
            g.at(402.5, 600.0),
            g.at(700.0, 300.0),
            g.at(650.0, 720.0),
            g.at(150.0, 150.0),
        ];
        let input = square_with(off, points.clone());
        let (out, q) = mesh_and_check(&input, &uniform(50.0), 1.04, 1.6);
        for (k, p) in points.iter().enumerate() {
            assert_eq!(bits(&out.nodes[80 + k]), bits(p), "point {k}");
        }
        // The close pair is joined by an edge, with no needle round it: the mesh grades down to
        // their spacing (far more triangles than the ~950 of the square alone).
        assert!(has_edge(&out, 80, 81));
        for v in [80, 81] {
            let (round, _) = min_angle_round(&out, v);
            assert!(round >= 25.0, "smallest angle {round:.1}° round node {v}");
        }
        assert!(q.triangles > 1500, "{q:?}");
        assert_eq!(mesh_patch(&input, &uniform(50.0)).unwrap(), out);
    }
}

#[test]
fn points_computed_on_curved_support_triangles_become_nodes() {
    // A half cylinder of radius 300 m (9 facets per radian), points from the grid's triangles.
    for off in [[0.0; 3], UTM] {
        let g = Grid {
            nx: 27,
            ny: 6,
            u: (0.0, 3.0),
            v: (0.0, 1200.0),
            f: |u: f64, y| [300.0 * u.cos(), y, 300.0 * u.sin()],
            offset: off,
        };
        let points = vec![g.at(1.13, 417.0), g.at(2.01, 851.3), g.at(0.4, 150.0)];
        let input = PatchInput {
            name: "half cylinder with points".into(),
            support: g.support(),
            loops: vec![g.border_loop(18, 24)],
            constraints: vec![],
            points: points.clone(),
            facets: Vec::new(),
        };
        let (out, _) = mesh_and_check(&input, &uniform(50.0), 1.04, 1.6);
        let loop_nodes = 2 * (18 + 24);
        for (k, p) in points.iter().enumerate() {
            assert_eq!(bits(&out.nodes[loop_nodes + k]), bits(p), "point {k}");
            let (round, _) = min_angle_round(&out, (loop_nodes + k) as u32);
            assert!(round >= 35.0, "smallest angle {round:.1}° round point {k}");
        }
    }
    // A recumbent fold (flattened by a Tutte embedding): one point on each of the three stacked
    // limbs, above one another, and one in a hinge.
    for off in [[0.0; 3], UTM] {
        let g = Grid {
            nx: 100,
            ny: 8,
            u: (0.0, 5.0),
            v: (0.0, 1200.0),
            f: |u, y| {
                let c = crate::surface_mesh_curved::z_curve(u);
                [c[0], y, c[1] - 2000.0]
            },
            offset: off,
        };
        let points = vec![
            g.at(0.5, 600.0),
            g.at(2.5, 600.0),
            g.at(4.5, 600.0),
            g.at(1.5, 300.0),
        ];
        let input = PatchInput {
            name: "recumbent fold with points".into(),
            support: g.support(),
            loops: vec![g.border_loop(60, 24)],
            constraints: vec![],
            points: points.clone(),
            facets: Vec::new(),
        };
        assert_eq!(
            surface_mesh::flattening_method(&input.support).unwrap(),
            "tutte"
        );
        let (out, _) = mesh_and_check(&input, &uniform(50.0), 1.05, 1.7);
        let loop_nodes = 2 * (60 + 24);
        for (k, p) in points.iter().enumerate() {
            assert_eq!(bits(&out.nodes[loop_nodes + k]), bits(p), "point {k}");
            let (round, _) = min_angle_round(&out, (loop_nodes + k) as u32);
            assert!(round >= 30.0, "smallest angle {round:.1}° round point {k}");
        }
    }
    // A hemisphere cap of radius 1000 m: points as barycentric combinations of support corners.
    for off in [[0.0; 3], UTM] {
        let support = crate::surface_mesh_curved::cap(12, 1000.0, PI / 2.0, off);
        let n = 6 * 12;
        let first = support.vertices.len() - n;
        let rim: Vec<[f64; 3]> = support.vertices[first..].to_vec();
        let on = |t: usize, w: [f64; 3]| {
            let [a, b, c] = support.corners(t);
            [0, 1, 2].map(|k| w[0] * a[k] + w[1] * b[k] + w[2] * c[k])
        };
        let points = vec![on(40, [0.2, 0.3, 0.5]), on(300, [0.6, 0.25, 0.15])];
        let input = PatchInput {
            name: "hemisphere cap with points".into(),
            support: support.clone(),
            loops: vec![rim],
            constraints: vec![],
            points: points.clone(),
            facets: Vec::new(),
        };
        let (out, _) = mesh_and_check(&input, &uniform(90.0), 1.06, 1.8);
        for (k, p) in points.iter().enumerate() {
            assert_eq!(bits(&out.nodes[n + k]), bits(p), "point {k}");
        }
    }
}

#[test]
fn a_point_given_twice_or_on_a_loop_or_constraint_node_is_that_node() {
    let g = flat(UTM);
    let trace: Vec<[f64; 3]> = (0..=4)
        .map(|k| g.at(300.0 + 50.0 * k as f64, 480.0))
        .collect();
    let (p, q) = (g.at(620.0, 250.0), g.at(250.0, 700.0));
    let loop_ = g.border_loop(20, 20);
    let input = PatchInput {
        name: "merged points".into(),
        support: g.support(),
        loops: vec![loop_.clone()],
        constraints: vec![trace.clone()],
        points: vec![p, loop_[7], p, trace[2], q],
        facets: Vec::new(),
    };
    let (out, _) = mesh_and_check(&input, &uniform(50.0), 1.04, 1.6);
    // 80 loop nodes, 5 trace nodes, then p and q only.
    assert_eq!(bits(&out.nodes[7]), bits(&loop_[7]));
    assert_eq!(bits(&out.nodes[82]), bits(&trace[2]));
    assert_eq!(bits(&out.nodes[85]), bits(&p));
    assert_eq!(bits(&out.nodes[86]), bits(&q));
    for x in [p, q, loop_[7], trace[2]] {
        assert_eq!(out.nodes.iter().filter(|n| bits(n) == bits(&x)).count(), 1);
    }
}

#[test]
fn verify_refuses_a_mesh_without_a_given_point_at_its_index() {
    let g = flat(UTM);
    let p = g.at(437.3, 561.9);
    let with = square_with(UTM, vec![p]);
    let without = mesh_patch(&square_with(UTM, vec![]), &uniform(50.0)).unwrap();
    let e = verify(&with, &without, 1e-6).unwrap_err();
    assert!(e.to_string().contains("output node 80"), "{e}");
    // The point's node renumbered after a generated node: not at its documented index.
    let mut out = mesh_patch(&with, &uniform(50.0)).unwrap();
    verify(&with, &out, 1e-6).unwrap();
    out.nodes.swap(80, 81);
    for t in &mut out.triangles {
        for v in t.iter_mut() {
            *v = match *v {
                80 => 81,
                81 => 80,
                x => x,
            };
        }
    }
    let e = verify(&with, &out, 1e-6).unwrap_err();
    assert!(e.to_string().contains("output node 80"), "{e}");
}

#[test]
fn a_point_outside_the_patch_is_an_error_naming_the_point_and_its_place() {
    // The support reaches 500 m beyond the square on every side.
    let g = Grid {
        nx: 4,
        ny: 4,
        u: (-500.0, 1500.0),
        v: (-500.0, 1500.0),
        f: |x, y| [x, y, -500.0],
        offset: UTM,
    };
    let outside = g.at(1200.0, 300.0);
    let input = PatchInput {
        name: "point outside".into(),
        support: g.support(),
        loops: vec![flat(UTM).border_loop(10, 10)],
        constraints: vec![],
        points: vec![g.at(500.0, 500.0), outside],
        facets: Vec::new(),
    };
    let e = mesh_patch(&input, &uniform(100.0)).unwrap_err();
    assert_error(
        &e,
        &["point outside", "point 1 lies outside the patch"],
        outside,
    );
}

#[test]
fn a_point_on_a_boundary_segment_between_its_nodes_is_an_error_naming_the_segment() {
    for off in [[0.0; 3], UTM] {
        let g = flat(off);
        // 100 m segments: (250, 0) lies on the third segment of the bottom side.
        let on = g.at(250.0, 0.0);
        let mut input = square_with(off, vec![g.at(500.0, 500.0), on]);
        input.loops = vec![g.border_loop(10, 10)];
        let e = mesh_patch(&input, &uniform(100.0)).unwrap_err();
        assert_error(&e, &["point 1 lies on segment 2 of loop 0"], on);
    }
}

#[test]
fn a_point_far_off_the_support_is_an_error_naming_the_point() {
    let g = flat(UTM);
    let mut above = g.at(400.0, 400.0);
    above[2] += 5.0;
    let input = square_with(UTM, vec![above]);
    let e = mesh_patch(&input, &uniform(50.0)).unwrap_err();
    assert_error(&e, &["point 0 is 5.000e0 off the support"], above);
}

#[test]
fn a_point_a_rounding_away_from_a_node_is_an_error_asking_for_the_node_itself() {
    let g = flat(UTM);
    let loop_ = g.border_loop(20, 20);
    // Loop node 6 is (300, 0): lifted into the patch by a nanometre.
    let mut near_node = loop_[6];
    near_node[1] += 1e-9;
    let e = mesh_patch(&square_with(UTM, vec![near_node]), &uniform(50.0)).unwrap_err();
    assert_error(
        &e,
        &["point 0 is", "from node 6 (a loop node)", "bit-identical"],
        near_node,
    );
    let p = g.at(500.0, 500.0);
    let mut near_point = p;
    near_point[0] += 1e-9;
    let e = mesh_patch(&square_with(UTM, vec![p, near_point]), &uniform(50.0)).unwrap_err();
    assert_error(&e, &["point 0 is", "from point 1", "bit-identical"], p);
    let e = mesh_patch(
        &square_with(UTM, vec![[f64::NAN, 0.0, 0.0]]),
        &uniform(50.0),
    )
    .unwrap_err();
    assert!(e.to_string().contains("point 0 is not finite"), "{e}");
}

#[test]
fn points_round_a_hole_become_nodes_and_a_point_in_the_hole_lies_outside() {
    for off in [[0.0; 3], UTM] {
        let g = flat(off);
        let points = vec![g.at(500.0, 250.0), g.at(150.0, 150.0), g.at(850.0, 800.0)];
        let input = PatchInput {
            name: "points round a hole".into(),
            support: g.support(),
            loops: vec![g.border_loop(20, 20), g.hole(500.0, 500.0, 200.0, 25)],
            constraints: vec![],
            points: points.clone(),
            facets: Vec::new(),
        };
        let (out, _) = mesh_and_check(&input, &uniform(50.0), 1.06, 1.7);
        for (k, p) in points.iter().enumerate() {
            assert_eq!(bits(&out.nodes[105 + k]), bits(p), "point {k}");
        }
        let in_hole = g.at(520.0, 470.0);
        let mut input = input;
        input.points.push(in_hole);
        let e = mesh_patch(&input, &uniform(50.0)).unwrap_err();
        assert_error(&e, &["point 3 lies outside the patch"], in_hole);
    }
}

#[test]
fn points_beside_an_interior_constraint_become_nodes_and_a_point_on_it_is_an_error() {
    for off in [[0.0; 3], UTM] {
        let g = flat(off);
        let trace: Vec<[f64; 3]> = (0..=8)
            .map(|k| g.at(300.0 + 50.0 * k as f64, 480.0 + 5.0 * k as f64))
            .collect();
        let points = vec![g.at(420.0, 530.0), g.at(600.0, 420.0), g.at(200.0, 480.0)];
        let input = PatchInput {
            name: "points beside a trace".into(),
            support: g.support(),
            loops: vec![g.border_loop(20, 20)],
            constraints: vec![trace.clone()],
            points: points.clone(),
            facets: Vec::new(),
        };
        let (out, _) = mesh_and_check(&input, &uniform(50.0), 1.06, 1.7);
        for (k, p) in points.iter().enumerate() {
            assert_eq!(bits(&out.nodes[89 + k]), bits(p), "point {k}");
            let (round, _) = min_angle_round(&out, (89 + k) as u32);
            assert!(round >= 35.0, "smallest angle {round:.1}° round point {k}");
        }
        // Halfway along the trace's fourth segment.
        let on = g.at(475.0, 497.5);
        let mut input = input;
        input.points.push(on);
        let e = mesh_patch(&input, &uniform(50.0)).unwrap_err();
        assert_error(&e, &["point 3 lies on segment 3 of constraint 0"], on);
    }
}

proptest! {
    #![proptest_config(test_support::proptest_config(32))]
    #[test]
    fn random_points_in_random_star_shaped_patches_always_become_nodes(
        radii in proptest::collection::vec(0.6f64..1.0, 7..14),
        nodes in 30usize..90,
        points in proptest::collection::vec((0.0f64..1.0, -1.0f64..1.0), 1..8),
        size in 40.0f64..90.0,
        utm in any::<bool>(),
    ) {
        let off = if utm { UTM } else { [0.0; 3] };
        let g = Grid { nx: 30, ny: 30, u: (0.0, 3000.0), v: (0.0, 3000.0), f: wavy, offset: off };
        let (cx, cy, r0) = (1500.0, 1500.0, 1300.0);
        let k = radii.len();
        let rad = |a: f64| {
            let s = a / (2.0 * PI) * k as f64;
            let i = s.floor() as usize % k;
            let t = s - s.floor();
            let w = 0.5 - 0.5 * (PI * t).cos();
            r0 * (radii[i] * (1.0 - w) + radii[(i + 1) % k] * w)
        };
        let outer: Vec<[f64; 3]> = (0..nodes)
            .map(|j| {
                let a = 2.0 * PI * j as f64 / nodes as f64;
                g.at(cx + rad(a) * a.cos(), cy + rad(a) * a.sin())
            })
            .collect();
        let hole = g.hole(cx, cy, 150.0, 12);
        // A trace due east of the hole, points in the western half, between the hole and the
        // outer loop (at least 100 m from both).
        let trace: Vec<[f64; 3]> = (0..4).map(|j| g.at(cx + 300.0 + 60.0 * j as f64, cy)).collect();
        let pts: Vec<[f64; 3]> = points
            .iter()
            .map(|&(r, a)| {
                let (r, a) = (250.0 + r * 420.0, PI + a * 1.2);
                g.at(cx + r * a.cos(), cy + r * a.sin())
            })
            .collect();
        let input = PatchInput {
            name: "random points".into(),
            support: g.support(),
            loops: vec![outer, hole],
            constraints: vec![trace],
            points: pts.clone(),
            facets: Vec::new(),
        };
        let sz = SurfaceSize { size, min_size: 5.0, max_size: 400.0, growth: 1.3 };
        let out = mesh_patch(&input, &sz).map_err(|e| TestCaseError::fail(e.to_string()))?;
        let first = nodes + 12 + 4;
        for (k, p) in pts.iter().enumerate() {
            prop_assert_eq!(bits(&out.nodes[first + k]), bits(p), "point {}", k);
        }
        let q = stats(&out.nodes, &out.triangles);
        prop_assert!(q.mean < 1.12, "mean {}", q.mean);
        let worst_round = (first..first + pts.len())
            .flat_map(|v| out.triangles.iter().filter(move |t| t.contains(&(v as u32))))
            .map(|t| {
                let p = t.map(|v| out.nodes[v as usize]);
                c_ratio(&p[0], &p[1], &p[2])
            })
            .fold(0.0, f64::max);
        prop_assert!(worst_round < 2.0, "c/c* {} round a point", worst_round);
        prop_assert!(q.max < 3.0, "max {}: {:?}", q.max, worst(&out));
    }
}
