//! Surface mesher on flat and simple patches: a square, a square with a hole, a dangling
//! constraint, graded boundary nodes, and a self-intersecting loop (an error naming the place).

use surface_mesh_common::*;
use test_support::surface_mesh_common;

use surface_mesh::{PatchInput, SurfaceSize, mesh_patch};

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

#[test]
fn a_flat_square_with_four_discretized_sides_meshes_into_near_equilateral_triangles() {
    for off in [[0.0; 3], UTM] {
        let g = flat(off);
        let input = PatchInput {
            name: "flat square".into(),
            support: g.support(),
            loops: vec![g.border_loop(20, 20)],
            constraints: vec![],
            points: Vec::new(),
            facets: Vec::new(),
        };
        let (out, q) = mesh_and_check(&input, &uniform(50.0), 1.06, 1.6);
        assert!(
            q.triangles > 600 && q.triangles < 1100,
            "{} triangles",
            q.triangles
        );
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
            points: Vec::new(),
            facets: Vec::new(),
        };
        let (out, _) = mesh_and_check(&input, &uniform(50.0), 1.08, 1.7);
        // No triangle centroid inside the hole.
        for t in &out.triangles {
            let c: Vec<f64> = (0..2)
                .map(|k| {
                    t.iter()
                        .map(|&v| out.nodes[v as usize][k] - off[k])
                        .sum::<f64>()
                        / 3.0
                })
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
        let trace: Vec<[f64; 3]> = (0..=8)
            .map(|k| g.at(300.0 + 50.0 * k as f64, 480.0 + 5.0 * k as f64))
            .collect();
        let from_border: Vec<[f64; 3]> =
            vec![g.at(0.0, 250.0), g.at(60.0, 260.0), g.at(120.0, 280.0)];
        let input = PatchInput {
            name: "dangling fault trace".into(),
            support: g.support(),
            loops: vec![g.border_loop(20, 20)],
            constraints: vec![trace.clone(), from_border],
            points: Vec::new(),
            facets: Vec::new(),
        };
        let (out, _) = mesh_and_check(&input, &uniform(50.0), 1.08, 1.8);
        // The border-touching constraint starts on loop node 75 (left side, 250 m up): shared.
        let loop_nodes = 80;
        assert_eq!(
            out.nodes[loop_nodes].map(f64::to_bits),
            trace[0].map(f64::to_bits)
        );
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
        let input = PatchInput {
            name: "graded boundary".into(),
            support: g.support(),
            loops: vec![l],
            constraints: vec![],
            points: Vec::new(),
            facets: Vec::new(),
        };
        let size = SurfaceSize {
            size: 100.0,
            min_size: 5.0,
            max_size: 200.0,
            growth: 1.25,
        };
        let (out, _) = mesh_and_check(&input, &size, 1.12, 2.2);
        // Small triangles near the fine corner, large ones far from it.
        let edge = |t: &[u32; 3]| {
            let a = out.nodes[t[0] as usize];
            let b = out.nodes[t[1] as usize];
            ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt()
        };
        let near = out
            .triangles
            .iter()
            .filter(|t| {
                out.nodes[t[0] as usize][0] - off[0] < 30.0
                    && out.nodes[t[0] as usize][1] - off[1] < 30.0
            })
            .map(edge)
            .fold(0.0, f64::max);
        let far = out
            .triangles
            .iter()
            .filter(|t| out.nodes[t[0] as usize][1] - off[1] > 800.0)
            .map(edge)
            .fold(0.0, f64::max);
        assert!(near < 40.0 && far > 70.0, "near {near} far {far}");
    }
}

#[test]
fn a_self_intersecting_loop_is_an_error_naming_the_patch_and_the_place() {
    for off in [[0.0; 3], UTM] {
        let g = flat(off);
        let bow = vec![
            g.at(100.0, 100.0),
            g.at(900.0, 900.0),
            g.at(900.0, 100.0),
            g.at(100.0, 900.0),
        ];
        let input = PatchInput {
            name: "bow tie".into(),
            support: g.support(),
            loops: vec![bow],
            constraints: vec![],
            points: Vec::new(),
            facets: Vec::new(),
        };
        let e = mesh_patch(&input, &uniform(50.0)).unwrap_err();
        let at = e.at.expect("a place");
        assert!(
            (at[0] - off[0] - 500.0).abs() < 1e-6 && (at[1] - off[1] - 500.0).abs() < 1e-6,
            "{e}"
        );
        let msg = e.to_string();
        assert!(
            msg.contains("bow tie") && msg.contains("intersect"),
            "{msg}"
        );
    }
}

#[test]
fn a_loop_node_off_the_support_is_an_error_with_its_place() {
    let g = flat([0.0; 3]);
    let mut l = g.border_loop(10, 10);
    l[3][2] += 1.0;
    let input = PatchInput {
        name: "lifted node".into(),
        support: g.support(),
        loops: vec![l.clone()],
        constraints: vec![],
        points: Vec::new(),
        facets: Vec::new(),
    };
    let e = mesh_patch(&input, &uniform(100.0)).unwrap_err();
    assert_eq!(e.at, Some(l[3]), "{e}");
    assert!(e.to_string().contains("off the support"));
}

#[test]
fn meshing_twice_gives_the_same_mesh_bit_for_bit() {
    let g = flat(UTM);
    let trace: Vec<[f64; 3]> = (0..=4)
        .map(|k| g.at(300.0 + 50.0 * k as f64, 480.0))
        .collect();
    let input = PatchInput {
        name: "twice".into(),
        support: g.support(),
        loops: vec![g.border_loop(17, 23), g.hole(700.0, 300.0, 100.0, 13)],
        constraints: vec![trace],
        points: Vec::new(),
        facets: Vec::new(),
    };
    let a = mesh_patch(&input, &uniform(45.0)).unwrap();
    let b = mesh_patch(&input, &uniform(45.0)).unwrap();
    assert_eq!(a, b);
}

#[test]
fn a_constraint_that_leaves_the_patch_is_an_error_with_a_place() {
    let g = flat([0.0; 3]);
    let input = PatchInput {
        name: "escaping trace".into(),
        support: g.support(),
        loops: vec![g.border_loop(10, 10)],
        // From inside the square through its top side towards a point outside (still on the
        // support, which extends nowhere beyond: the end is off the support).
        constraints: vec![vec![g.at(500.0, 900.0), [550.0, 1100.0, -500.0]]],
        points: Vec::new(),
        facets: Vec::new(),
    };
    let e = mesh_patch(&input, &uniform(100.0)).unwrap_err();
    assert!(
        e.at.is_some() && e.to_string().contains("escaping trace"),
        "{e}"
    );
}

#[test]
fn a_constraint_crossing_the_boundary_on_the_support_is_an_intersection_error() {
    let g = Grid {
        nx: 4,
        ny: 4,
        u: (-500.0, 1500.0),
        v: (-500.0, 1500.0),
        f: |x, y| [x, y, -500.0],
        offset: [0.0; 3],
    };
    let square: Vec<[f64; 3]> = flat([0.0; 3]).border_loop(10, 10);
    let input = PatchInput {
        name: "crossing trace".into(),
        support: g.support(),
        loops: vec![square],
        constraints: vec![vec![g.at(500.0, 850.0), g.at(530.0, 1150.0)]],
        points: Vec::new(),
        facets: Vec::new(),
    };
    let e = mesh_patch(&input, &uniform(100.0)).unwrap_err();
    let at = e.at.expect("a place");
    assert!(
        (at[1] - 1000.0).abs() < 1e-6 && (at[0] - 515.0).abs() < 1e-6,
        "{e}"
    );
    assert!(
        e.to_string().contains("crossing trace") && e.to_string().contains("intersect"),
        "{e}"
    );
}

#[test]
fn invalid_sizes_are_refused_with_the_values() {
    let g = flat([0.0; 3]);
    let input = PatchInput {
        name: "sizes".into(),
        support: g.support(),
        loops: vec![g.border_loop(4, 4)],
        constraints: vec![],
        points: Vec::new(),
        facets: Vec::new(),
    };
    let e = mesh_patch(
        &input,
        &SurfaceSize {
            size: -1.0,
            min_size: 0.0,
            max_size: 10.0,
            growth: 1.2,
        },
    )
    .unwrap_err();
    assert!(e.to_string().contains("size -1"), "{e}");
    let e = mesh_patch(
        &input,
        &SurfaceSize {
            size: 10.0,
            min_size: 0.0,
            max_size: 10.0,
            growth: 0.5,
        },
    )
    .unwrap_err();
    assert!(e.to_string().contains("growth 0.5"), "{e}");
}

#[test]
fn sizes_asking_a_patch_for_millions_of_points_are_refused_at_once_with_the_estimate() {
    // A square kilometre at half a metre (for 50 m): millions of points, where the refinement
    // would run for minutes.
    let g = flat(UTM);
    let input = PatchInput {
        name: "typo".into(),
        support: g.support(),
        loops: vec![g.border_loop(20, 20)],
        constraints: vec![],
        points: Vec::new(),
        facets: Vec::new(),
    };
    let e = mesh_patch(&input, &uniform(0.5)).unwrap_err();
    let e = e.to_string();
    assert!(
        e.contains("million points over its 1.000 km²") && e.contains("over the 2 million"),
        "{e}"
    );
    assert!(e.contains("elements of 0.500 inside"), "{e}");
}

#[test]
fn a_clockwise_outer_loop_still_gives_triangles_oriented_like_the_support() {
    let g = flat(UTM);
    let mut l = g.border_loop(12, 12);
    l.reverse();
    let input = PatchInput {
        name: "clockwise".into(),
        support: g.support(),
        loops: vec![l],
        constraints: vec![],
        points: Vec::new(),
        facets: Vec::new(),
    };
    let (out, _) = mesh_and_check(&input, &uniform(80.0), 1.06, 1.6);
    // The support faces +z: every triangle's normal must too.
    for t in &out.triangles {
        let [a, b, c] = t.map(|v| out.nodes[v as usize]);
        let nz = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        assert!(nz > 0.0);
    }
}

#[test]
fn a_closed_support_is_refused_because_it_must_come_split_into_patches() {
    use geom::TriMesh;
    let v = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ];
    let tet = TriMesh::new(v.clone(), vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]]);
    let input = PatchInput {
        name: "lens".into(),
        support: tet,
        loops: vec![vec![v[0], v[1], v[2]]],
        constraints: vec![],
        points: Vec::new(),
        facets: Vec::new(),
    };
    let e = mesh_patch(&input, &uniform(0.1)).unwrap_err();
    assert!(
        e.to_string().contains("lens") && e.to_string().contains("closed"),
        "{e}"
    );
}

#[test]
fn a_support_with_a_zero_area_needle_triangle_still_meshes_through_the_tutte_flattening() {
    use surface_mesh::flattening_method;
    // A 2 × 2 grid over [0, 1000]², with a T-junction at the middle of the interior edge
    // (500, 0)-(500, 500) closed by a needle triangle of zero area, as repairs of gOcad exports do.
    for off in [[0.0; 3], UTM] {
        let p = |x: f64, y: f64| [x + off[0], y + off[1], -500.0];
        let mut vs = Vec::new();
        for j in 0..3 {
            for i in 0..3 {
                vs.push(p(500.0 * i as f64, 500.0 * j as f64));
            }
        }
        vs.push(p(500.0, 250.0)); // m = 9, on the edge 1-4
        let mut ts = vec![];
        for j in 0..2u32 {
            for i in 0..2u32 {
                let (a, b, c, d) = (j * 3 + i, j * 3 + i + 1, j * 3 + i + 4, j * 3 + i + 3);
                ts.push([a, b, c]);
                ts.push([a, c, d]);
            }
        }
        // Triangle [0, 1, 4] is split at m into [0, 1, 9] and [0, 9, 4]; its neighbour across
        // 1-4 stays whole, so the T-junction is closed by the needle [1, 4, 9].
        ts[0] = [0, 1, 9];
        ts.push([0, 9, 4]);
        ts.push([1, 4, 9]);
        let support = geom::TriMesh::new(vs, ts);
        // No relaxing makes the needle a triangle in 3D: the projection is not mended.
        assert_eq!(flattening_method(&support).unwrap(), "tutte");
        let border = square_border(p);
        let input = PatchInput {
            name: "needle support".into(),
            support,
            loops: vec![border],
            constraints: vec![],
            points: Vec::new(),
            facets: Vec::new(),
        };
        mesh_and_check(&input, &uniform(100.0), 1.06, 1.6);
    }
}

#[test]
fn a_strip_whose_rim_curls_under_it_in_one_tooth_meshes_through_a_mended_projection() {
    use surface_mesh::flattening_method;
    // A 1000 m by 300 m strip of 100 m cells, as the top of a long body whose south rim bends
    // down (its first row of cells dips at 39°), with a tooth on that rim: one triangle whose
    // tip curls 60 m further down and 40 m back under the strip, as a stair-stepped seam leaves
    // along a body's rim (facing 124° from up, 85° from the cell beside it). Its tip is in no
    // other triangle. Projected, the tooth turns over: before, the whole strip went to a Tutte
    // embedding.
    for off in [[0.0; 3], UTM] {
        let p = |x: f64, y: f64, z: f64| [x + off[0], y + off[1], z - 500.0];
        let (nx, ny) = (10u32, 3u32);
        let id = |i: u32, j: u32| j * (nx + 1) + i;
        let mut vs = Vec::new();
        for j in 0..=ny {
            for i in 0..=nx {
                let dip = if j == 0 { -80.0 } else { 0.0 };
                vs.push(p(100.0 * i as f64, 100.0 * j as f64, dip));
            }
        }
        let tip = vs.len() as u32;
        vs.push(p(450.0, 40.0, -140.0));
        let mut ts = Vec::new();
        for j in 0..ny {
            for i in 0..nx {
                ts.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
                ts.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
        ts.push([id(5, 0), id(4, 0), tip]);
        let support = geom::TriMesh::new(vs.clone(), ts);
        assert_eq!(flattening_method(&support).unwrap(), "relaxed");
        let mut border: Vec<[f64; 3]> = (0..=4).map(|i| vs[id(i, 0) as usize]).collect();
        border.push(vs[tip as usize]);
        border.extend((5..=nx).map(|i| vs[id(i, 0) as usize]));
        border.extend((1..=ny).map(|j| vs[id(nx, j) as usize]));
        border.extend((0..nx).rev().map(|i| vs[id(i, ny) as usize]));
        border.extend((1..ny).rev().map(|j| vs[id(0, j) as usize]));
        // Nodes every fifth of a border edge, on the support's own edges.
        let nodes = (0..border.len())
            .flat_map(|k| {
                let (a, b) = (border[k], border[(k + 1) % border.len()]);
                (0..5).map(move |s| [0, 1, 2].map(|c| a[c] + (b[c] - a[c]) * s as f64 / 5.0))
            })
            .collect();
        let input = PatchInput {
            name: "strip with a curled tooth".into(),
            support,
            loops: vec![nodes],
            constraints: vec![],
            points: Vec::new(),
            facets: Vec::new(),
        };
        mesh_and_check(&input, &uniform(20.0), 1.05, 2.0);
    }
}

#[test]
fn a_hole_whose_rim_overhangs_its_neighbour_is_not_flattened_by_projection() {
    use surface_mesh::flattening_method;
    // A 1000 m square with a sliver hole P1 P2 P3: the part left of the hole reaches P2, 100 m up
    // and 50 m right of the line P1 P3 that bounds the part on the right, so the left part
    // overhangs the right one. Projected on the plane, every triangle keeps its orientation and
    // the border does not cross, but the hole turns the wrong way: the two parts overlap there.
    for off in [[0.0; 3], UTM] {
        let p = |x: f64, y: f64, z: f64| [x + off[0], y + off[1], z - 500.0];
        let vs = vec![
            p(0.0, 0.0, 0.0),       // 0 A
            p(1000.0, 0.0, 0.0),    // 1 B
            p(1000.0, 1000.0, 0.0), // 2 C
            p(0.0, 1000.0, 0.0),    // 3 D
            p(500.0, 0.0, 0.0),     // 4 E
            p(500.0, 1000.0, 0.0),  // 5 F
            p(500.0, 200.0, 0.0),   // 6 P1
            p(550.0, 500.0, 100.0), // 7 P2
            p(500.0, 800.0, 0.0),   // 8 P3
        ];
        let ts = vec![
            [0, 4, 6],
            [0, 6, 7],
            [0, 7, 3],
            [3, 7, 8],
            [3, 8, 5],
            [4, 1, 6],
            [1, 2, 6],
            [6, 2, 8],
            [8, 2, 5],
        ];
        let support = geom::TriMesh::new(vs.clone(), ts);
        assert_eq!(flattening_method(&support).unwrap(), "tutte");
        let border = square_border(|x, y| p(x, y, 0.0));
        let input = PatchInput {
            name: "overhanging hole".into(),
            support,
            loops: vec![border, vec![vs[6], vs[7], vs[8]]],
            constraints: vec![],
            points: Vec::new(),
            facets: Vec::new(),
        };
        let (out, _) = mesh_and_check(&input, &uniform(100.0), 1.2, 3.0);
        // The sliver stays a hole: the mesh uses P1 P2 and P2 P3 on the left, P3 P1 on the right.
        let at = |q: [f64; 3]| out.nodes.iter().position(|n| *n == q).unwrap() as u32;
        let (p1, p2, p3) = (at(vs[6]), at(vs[7]), at(vs[8]));
        let has = |a: u32, b: u32| {
            out.triangles
                .iter()
                .any(|t| (0..3).any(|i| t[i] == a && t[(i + 1) % 3] == b))
        };
        assert!(has(p1, p2) && has(p2, p3) && has(p3, p1), "the hole's rim");
    }
}

/// A 1000 m square whose triangular hole P Q R touches the outer border at P = (500, 0): the
/// loops, and the support cut to the patch, are pinched there.
fn pinched(off: [f64; 3]) -> (geom::TriMesh, Vec<Vec<[f64; 3]>>) {
    let p = |x: f64, y: f64| [x + off[0], y + off[1], -500.0];
    let (a, b, c, d) = (
        p(0.0, 0.0),
        p(1000.0, 0.0),
        p(1000.0, 1000.0),
        p(0.0, 1000.0),
    );
    let (pp, q, r) = (p(500.0, 0.0), p(600.0, 300.0), p(400.0, 300.0));
    let support = geom::TriMesh::new(
        vec![a, b, c, d, pp, q, r],
        vec![
            [0, 4, 6],
            [4, 1, 5],
            [1, 2, 5],
            [2, 3, 5],
            [5, 3, 6],
            [6, 3, 0],
        ],
    );
    let outer = square_border(p);
    let along = |u: &[f64; 3], v: &[f64; 3], t: f64| {
        [u[0] + t * (v[0] - u[0]), u[1] + t * (v[1] - u[1]), -500.0]
    };
    let hole = vec![
        pp,
        along(&pp, &q, 1.0 / 3.0),
        along(&pp, &q, 2.0 / 3.0),
        q,
        along(&q, &r, 0.5),
        r,
        along(&r, &pp, 1.0 / 3.0),
        along(&r, &pp, 2.0 / 3.0),
    ];
    debug_assert_eq!(outer[5], pp);
    (support, vec![outer, hole])
}

#[test]
fn a_hole_touching_the_outer_border_at_one_node_meshes_with_one_fan_per_side() {
    for off in [[0.0; 3], UTM] {
        let (cut, loops) = pinched(off);
        for support in [cut, flat(off).support()] {
            let input = PatchInput {
                name: "pinched".into(),
                support,
                loops: loops.clone(),
                constraints: vec![],
                points: Vec::new(),
                facets: Vec::new(),
            };
            let (out, _) = mesh_and_check(&input, &uniform(100.0), 1.2, 3.0);
            // The pinch node is given once and its triangles form two fans, none inside the hole.
            let pinch = loops[1][0];
            assert_eq!(out.nodes.iter().filter(|n| **n == pinch).count(), 1);
            let inside_hole = out.triangles.iter().any(|t| {
                let m = t.iter().fold([0.0; 2], |m, &v| {
                    let n = out.nodes[v as usize];
                    [m[0] + n[0] / 3.0, m[1] + n[1] / 3.0]
                });
                let (x, y) = (m[0] - off[0], m[1] - off[1]);
                y > 0.0 && y < 300.0 && (x - 500.0).abs() < y / 3.0
            });
            assert!(!inside_hole, "a triangle lies in the hole");
        }
    }
}

#[test]
fn a_loop_repeating_a_node_next_to_itself_is_an_error_naming_the_node() {
    let (support, mut loops) = pinched([0.0; 3]);
    let twice = loops[1][1];
    loops[1].insert(1, twice);
    let input = PatchInput {
        name: "stutter".into(),
        support,
        loops,
        constraints: vec![],
        points: Vec::new(),
        facets: Vec::new(),
    };
    let e = mesh_patch(&input, &uniform(100.0)).unwrap_err();
    assert!(e.to_string().contains("zero-length segment"), "{e}");
    assert_eq!(e.at, Some(twice));
}

/// The border of the square [0, 1000]² through `p`, 100 m segments, counter-clockwise from the
/// origin.
fn square_border(p: impl Fn(f64, f64) -> [f64; 3]) -> Vec<[f64; 3]> {
    (0..40)
        .map(|k| {
            let s = 1000.0 * (k % 10) as f64 / 10.0;
            match k / 10 {
                0 => p(s, 0.0),
                1 => p(1000.0, s),
                2 => p(1000.0 - s, 1000.0),
                _ => p(0.0, 1000.0 - s),
            }
        })
        .collect()
}
