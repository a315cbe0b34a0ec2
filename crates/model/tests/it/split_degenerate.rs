//! The degenerate shapes the split once refused: a closed loop or a whole curve inside one face,
//! a fault ending on another fault (a T-junction inside a horizon face, the three surfaces
//! sharing the point), a curve point exactly on another curve inside a face (a fault vertex on
//! a box side, on the horizon's curve there), and curve points on the edges of a zero-area
//! triangle. Every case is split in both orders of the surfaces and of the intersections, and
//! must give the same surfaces.

use crate::intersect_support;

use geom::{BBox, TriMesh};
use intersect_support::{assert_sound, both, grid};
use model::intersect::split::{Side, SplitSurface, split, split_model};
use model::intersect::{Intersection, box_sides};
use model::patches::patches;
use std::collections::BTreeMap;

const X0: f64 = 500_000.0;
const Y0: f64 = 7_000_000.0;

/// Split every surface with `split_model`, then again with surfaces and intersections
/// reversed; both runs must agree surface by surface. Each result is checked sound.
fn split_both_orders(
    surfaces: &[(&str, &TriMesh)],
    xs: &[Intersection],
) -> BTreeMap<String, SplitSurface> {
    let fwd = split_model(surfaces, xs).unwrap_or_else(|e| panic!("splits: {e}"));
    let rs: Vec<(&str, &TriMesh)> = surfaces.iter().rev().copied().collect();
    let rx: Vec<Intersection> = xs.iter().rev().cloned().collect();
    let rev = split_model(&rs, &rx).unwrap_or_else(|e| panic!("splits reversed: {e}"));
    let mut out = BTreeMap::new();
    for ((name, mesh), s) in surfaces.iter().zip(fwd) {
        let r = rs
            .iter()
            .position(|(n, _)| n == name)
            .map(|i| &rev[i])
            .expect("same surfaces");
        assert_eq!(s.mesh, r.mesh, "{name}: the same mesh in both orders");
        assert_eq!(s.curve_edges, r.curve_edges, "{name}: the same curve edges");
        assert_eq!(s.parent, r.parent, "{name}: the same parents");
        assert_sound(mesh, &s);
        out.insert(name.to_string(), s);
    }
    out
}

/// The vertex of `s` at exactly `p`, if any.
fn vertex_at(s: &SplitSurface, p: [f64; 3]) -> Option<u32> {
    s.mesh
        .vertices
        .iter()
        .position(|q| q.map(f64::to_bits) == p.map(f64::to_bits))
        .map(|v| v as u32)
}

fn curve_degree(s: &SplitSurface, v: u32) -> usize {
    s.curve_edges.iter().filter(|e| e.contains(&v)).count()
}

/// A coarse horizon: two triangles of 200 m, gently tilted.
fn coarse_horizon() -> TriMesh {
    grid(1, 1, |i, j| {
        [
            X0 + 200.0 * i as f64,
            Y0 + 200.0 * j as f64,
            -100.0 + 3.0 * i as f64 + 2.0 * j as f64,
        ]
    })
}

#[test]
fn a_small_pyramid_piercing_one_horizon_face_cuts_a_closed_loop_inside_it() {
    let h = coarse_horizon();
    // Apex above the horizon, base square below it, all well inside the lower triangle.
    let (cx, cy) = (X0 + 130.3, Y0 + 40.7);
    let p = TriMesh::new(
        vec![
            [cx - 10.0, cy - 9.0, -140.0],
            [cx + 11.0, cy - 10.0, -140.0],
            [cx + 10.0, cy + 9.5, -140.0],
            [cx - 9.5, cy + 10.0, -140.0],
            [cx + 0.3, cy - 0.2, -40.0],
        ],
        vec![[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]],
    );
    let x = both("h", &h, "p", &p).expect("meets");
    assert_eq!(x.curves.len(), 1);
    assert!(x.curves[0].closed, "a closed loop");
    assert!(
        x.curves[0]
            .points
            .iter()
            .all(|q| matches!(q.on_a, model::intersect::Location::Face(0))),
        "every loop point is inside face 0 of h"
    );
    let out = split_both_orders(&[("h", &h), ("p", &p)], &[x]);
    let sh = &out["h"];
    assert_eq!(sh.curve_edges.len(), 4, "the loop is four edges of h");
    let ps = patches("h", sh);
    assert_eq!(ps.len(), 2, "the loop cuts a disc out of the horizon");
    let sizes: Vec<usize> = ps.iter().map(|p| p.triangles.len()).collect();
    assert!(sizes.contains(&2), "the disc is two triangles: {sizes:?}");
    assert_eq!(
        patches("p", &out["p"]).len(),
        2,
        "apex and base of the pyramid"
    );
}

#[test]
fn a_short_fault_wholly_inside_one_face_is_inserted_as_a_dangling_curve() {
    let h = coarse_horizon();
    let f = TriMesh::new(
        vec![
            [X0 + 120.0, Y0 + 20.0, -130.0],
            [X0 + 150.0, Y0 + 35.0, -130.0],
            [X0 + 150.0, Y0 + 35.0, -70.0],
            [X0 + 120.0, Y0 + 20.0, -70.0],
        ],
        vec![[0, 1, 2], [0, 2, 3]],
    );
    let x = both("f", &f, "h", &h).expect("meets");
    assert_eq!(x.curves.len(), 1);
    let sh = split(&h, &x, Side::B).unwrap_or_else(|e| panic!("{e}"));
    assert_sound(&h, &sh);
    let segs: usize = x.curves[0].segments_faces.len();
    assert_eq!(sh.curve_edges.len(), segs);
    assert_eq!(patches("h", &sh).len(), 1, "a dangling curve cuts nothing");
    let sf = split(&f, &x, Side::A).unwrap_or_else(|e| panic!("{e}"));
    assert_sound(&f, &sf);
    assert_eq!(
        patches("f", &sf).len(),
        2,
        "the horizon cuts the fault in two"
    );
}

/// A horizon, a through-going wall `f` across x, and a wall `g` across y that ends on `f`,
/// sharing the two vertices of its end edge with `f` (a conforming fault contact).
fn t_junction() -> (TriMesh, TriMesh, TriMesh) {
    let h = grid(4, 4, |i, j| {
        [
            X0 + 50.0 * i as f64,
            Y0 + 50.0 * j as f64,
            -100.0 + 0.7 * i as f64 + 0.4 * j as f64,
        ]
    });
    let fy = |k: usize| Y0 - 20.0 + 41.3 * k as f64;
    let fx = |y: f64| X0 + 104.1 + 0.02 * (y - Y0);
    let f = grid(6, 1, |k, l| {
        let y = fy(k);
        [fx(y), y, -160.0 + 120.0 * l as f64]
    });
    // g runs from x < 0 (outside h) to f's vertical edge at k = 3.
    let (ye, xe) = (fy(3), fx(fy(3)));
    let g = grid(2, 1, |k, l| {
        let x = [X0 - 30.0, X0 + 40.0, xe][k];
        let y = if k == 2 { ye } else { ye + 0.01 * (x - xe) };
        [x, y, -160.0 + 120.0 * l as f64]
    });
    (h, f, g)
}

#[test]
fn a_fault_ending_on_another_meets_it_at_a_t_junction_inside_a_horizon_face() {
    let (h, f, g) = t_junction();
    let xs = vec![
        both("h", &h, "f", &f).expect("meets"),
        both("h", &h, "g", &g).expect("meets"),
        both("f", &f, "g", &g).expect("meets"),
    ];
    assert!(xs.iter().all(|x| x.curves.len() == 1), "one curve each");
    let out = split_both_orders(&[("h", &h), ("f", &f), ("g", &g)], &xs);
    // The end of g's curve on h: where g's end edge (an edge of f too) crosses h.
    let gh = &xs[1].curves[0].points;
    let end = [gh[0].clone(), gh[gh.len() - 1].clone()]
        .into_iter()
        .find(|p| matches!(p.on_b, model::intersect::Location::Face(_)))
        .expect("g's curve ends inside a face of h (h is side b of g x h)");
    let sh = &out["h"];
    let v = *sh.vertex_of_each[1].get(&end.key).expect("a vertex of h");
    let at = sh.mesh.vertices[v as usize];
    assert_eq!(
        curve_degree(sh, v),
        3,
        "f's curve passes, g's curve ends: a T"
    );
    assert_eq!(
        patches("h", sh).len(),
        3,
        "f cuts h in two, g cuts one half again"
    );
    for n in ["f", "g"] {
        let s = &out[n];
        let w = vertex_at(s, at).unwrap_or_else(|| panic!("{n} has the T point bit for bit"));
        assert!(curve_degree(s, w) >= 3, "{n}: curves meet at the T point");
    }
    // g reaches past the west border of h, so their curve dangles on g.
    assert_eq!(patches("g", &out["g"]).len(), 1);
    // g's border runs along f's vertex column from bottom to top and cuts f in two; h is
    // narrower than f, so its curve dangles on f.
    assert_eq!(patches("f", &out["f"]).len(), 2);
}

#[test]
fn a_fault_vertex_on_a_box_side_and_on_the_horizon_curve_there_is_shared_by_all_three() {
    let b = BBox {
        min: [X0, Y0, -300.0],
        max: [X0 + 300.0, Y0 + 300.0, 0.0],
    };
    let (side_name, side) = box_sides(&b).swap_remove(0);
    assert_eq!(side_name, "box.xmin");
    // A flat horizon at z = -100 whose grid lines miss x = X0 and y = Y0 + 150.
    let h = grid(4, 4, |i, j| {
        [
            X0 - 30.0 + 80.0 * i as f64,
            Y0 - 10.0 + 80.0 * j as f64,
            -100.0,
        ]
    });
    // A vertical fault through (X0, Y0 + 150, -100), one of its vertices, with a column of
    // vertices in the box side and a row in the horizon.
    let f = grid(2, 2, |i, k| {
        let x = X0 - 50.0 + 50.0 * i as f64;
        [x, Y0 + 150.0 + 0.25 * (x - X0), -150.0 + 50.0 * k as f64]
    });
    let p = [X0, Y0 + 150.0, -100.0];
    assert_eq!(f.vertices[4], p);
    let xs = vec![
        both("h", &h, &side_name, &side).expect("meets"),
        both("f", &f, &side_name, &side).expect("meets"),
        both("f", &f, "h", &h).expect("meets"),
    ];
    let out = split_both_orders(&[("h", &h), ("f", &f), (&side_name, &side)], &xs);
    for (n, s) in &out {
        let v = vertex_at(s, p).unwrap_or_else(|| panic!("{n} has the fault vertex"));
        assert_eq!(curve_degree(s, v), 4, "{n}: two curves cross at the vertex");
    }
    // The fault is small: on the horizon and on the box side its curve dangles at both ends;
    // the horizon reaches beyond the box side, so their curve dangles on the horizon.
    assert_eq!(patches(&side_name, &out[side_name.as_str()]).len(), 2);
    assert_eq!(patches("h", &out["h"]).len(), 1);
    // The box side cuts the fault in two; the horizon, which stops at x = X0 - 30 inside the
    // fault's west half, cuts only the east half.
    assert_eq!(patches("f", &out["f"]).len(), 3);
}

#[test]
fn curve_points_on_the_edges_of_a_zero_area_triangle_keep_the_surface_conforming() {
    // c lies on edge a-b: the triangle a-b-c has zero area; a wall at x = X0 + 2.5 crosses it.
    let h = TriMesh::new(
        vec![
            [X0, Y0, -100.0],
            [X0 + 10.0, Y0, -100.0],
            [X0 + 5.0, Y0, -100.0],
            [X0 + 5.0, Y0 + 10.0, -100.0],
            [X0 + 5.0, Y0 - 10.0, -100.0],
        ],
        vec![[0, 4, 1], [0, 1, 2], [0, 2, 3], [2, 1, 3]],
    );
    let w = grid(1, 1, |i, k| {
        [
            X0 + 2.5,
            Y0 - 20.0 + 40.0 * i as f64,
            -150.0 + 100.0 * k as f64,
        ]
    });
    let x = both("h", &h, "w", &w).expect("meets");
    assert_eq!(x.degenerate_a, vec![1], "the zero-area triangle is skipped");
    let s = split(&h, &x, Side::A).unwrap_or_else(|e| panic!("{e}"));
    let mut directed = std::collections::BTreeSet::new();
    for t in &s.mesh.triangles {
        for k in 0..3 {
            assert!(directed.insert((t[k], t[(k + 1) % 3])), "conforming: {t:?}");
        }
    }
    for (t, &p) in s.parent.iter().enumerate() {
        let [a, b, c] = s.mesh.corners(t);
        let cross = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        assert_eq!(
            cross == 0.0,
            p == 1,
            "triangle {t}: zero area iff from the sliver"
        );
    }
    for e in &s.curve_edges {
        assert!(directed.contains(&(e[0], e[1])) || directed.contains(&(e[1], e[0])));
    }
    // Only the outer border is unmatched: its four edges, two of them split by the curve.
    let unmatched = directed
        .iter()
        .filter(|&&(a, b)| !directed.contains(&(b, a)))
        .count();
    assert_eq!(
        unmatched, 6,
        "the sliver is re-triangulated with its neighbours' points"
    );
}

#[test]
fn a_fault_ending_inside_another_faults_faces_meets_it_at_one_point_on_all_three_surfaces() {
    let h = grid(4, 4, |i, j| {
        [
            X0 + 50.0 * i as f64,
            Y0 + 50.0 * j as f64,
            -100.0 + 0.7 * i as f64 + 0.4 * j as f64,
        ]
    });
    // f is the vertical plane x = X0 + 104 + (y - Y0) / 4, every vertex exactly on it.
    let fx = |y: f64| X0 + 104.0 + (y - Y0) / 4.0;
    let f = grid(6, 1, |k, l| {
        let y = Y0 - 20.0 + 40.0 * k as f64;
        [fx(y), y, -160.0 + 120.0 * l as f64]
    });
    // g's end edge lies in f's plane between two of f's vertex columns: no shared vertex.
    let (ye, xe) = (Y0 + 102.0, fx(Y0 + 102.0));
    let g = grid(2, 1, |k, l| {
        let x = [X0 - 30.0, X0 + 40.0, xe][k];
        let y = if k == 2 { ye } else { ye + 0.01 * (x - xe) };
        [x, y, -160.0 + 120.0 * l as f64]
    });
    let xs = vec![
        both("h", &h, "f", &f).expect("meets"),
        both("h", &h, "g", &g).expect("meets"),
        both("f", &f, "g", &g).expect("meets"),
    ];
    assert!(xs.iter().all(|x| x.curves.len() == 1), "one curve each");
    let out = split_both_orders(&[("h", &h), ("f", &f), ("g", &g)], &xs);
    let gh = &xs[1].curves[0].points;
    let end = [gh[0].clone(), gh[gh.len() - 1].clone()]
        .into_iter()
        .find(|p| matches!(p.on_b, model::intersect::Location::Face(_)))
        .expect("g's curve ends inside a face of h");
    let sh = &out["h"];
    let v = *sh.vertex_of_each[1].get(&end.key).expect("a vertex of h");
    let at = sh.mesh.vertices[v as usize];
    assert_eq!(
        curve_degree(sh, v),
        3,
        "f's curve is split where g's curve ends"
    );
    assert_eq!(patches("h", sh).len(), 3);
    let sf = &out["f"];
    let w = vertex_at(sf, at).expect("f has the T point bit for bit");
    assert_eq!(
        curve_degree(sf, w),
        4,
        "on f, the curves of h and g cross there"
    );
    assert_eq!(sf.crossings, vec![w]);
    // g's border crosses f from bottom to top; h is narrower than f, so its curve dangles.
    assert_eq!(patches("f", sf).len(), 2);
    let sg = &out["g"];
    let u = vertex_at(sg, at).expect("g has the T point bit for bit");
    assert_eq!(
        curve_degree(sg, u),
        3,
        "on g, h's curve meets the border along f"
    );
}

#[test]
fn a_fault_ending_on_another_exactly_on_a_horizon_edge_meets_it_there_on_all_three_surfaces() {
    // As above, with a horizon row of vertices at y = Y0 + 102: the T point is on h's edge.
    let h = grid(4, 4, |i, j| {
        [
            X0 + 50.0 * i as f64,
            Y0 + 51.0 * j as f64,
            -100.0 + 0.7 * i as f64 + 0.4 * j as f64,
        ]
    });
    let fx = |y: f64| X0 + 104.0 + (y - Y0) / 4.0;
    let f = grid(6, 1, |k, l| {
        let y = Y0 - 20.0 + 40.0 * k as f64;
        [fx(y), y, -160.0 + 120.0 * l as f64]
    });
    let (ye, xe) = (Y0 + 102.0, fx(Y0 + 102.0));
    let g = grid(2, 1, |k, l| {
        let x = [X0 - 30.0, X0 + 40.0, xe][k];
        let y = if k == 2 { ye } else { ye + 0.01 * (x - xe) };
        [x, y, -160.0 + 120.0 * l as f64]
    });
    let xs = vec![
        both("h", &h, "f", &f).expect("meets"),
        both("h", &h, "g", &g).expect("meets"),
        both("f", &f, "g", &g).expect("meets"),
    ];
    let out = split_both_orders(&[("h", &h), ("f", &f), ("g", &g)], &xs);
    let gh = &xs[1].curves[0].points;
    let end = [gh[0].clone(), gh[gh.len() - 1].clone()]
        .into_iter()
        .find(|p| p.xyz[0] > X0 + 100.0)
        .expect("g's curve ends at f");
    assert!(
        matches!(end.on_b, model::intersect::Location::Edge(..)),
        "on an edge of h: {:?}",
        end.key
    );
    let sh = &out["h"];
    let v = *sh.vertex_of_each[1].get(&end.key).expect("a vertex of h");
    let at = sh.mesh.vertices[v as usize];
    assert_eq!(
        curve_degree(sh, v),
        3,
        "f's curve passes where g's curve ends"
    );
    assert_eq!(patches("h", sh).len(), 3);
    let sf = &out["f"];
    let w = vertex_at(sf, at).expect("f has the T point bit for bit");
    assert_eq!(
        curve_degree(sf, w),
        4,
        "on f, the curves of h and g cross there"
    );
    let sg = &out["g"];
    let u = vertex_at(sg, at).expect("g has the T point bit for bit");
    assert_eq!(curve_degree(sg, u), 3);
}

#[test]
fn eight_walls_crossing_in_one_horizon_face_meet_at_shared_crossings() {
    // One horizon cell of 400 m; eight vertical walls at different angles, some long (through
    // the cell), some short (ending inside it), each wall a strip of two triangles per 60 m.
    let h = grid(1, 1, |i, j| {
        [
            X0 + 400.0 * i as f64,
            Y0 + 400.0 * j as f64,
            -100.0 + 5.0 * i as f64 - 3.0 * j as f64,
        ]
    });
    let wall = |cx: f64, cy: f64, deg: f64, half: f64| {
        let (s, c) = deg.to_radians().sin_cos();
        let n = (2.0 * half / 60.0).ceil() as usize;
        grid(n, 1, |k, l| {
            let u = -half + 2.0 * half * k as f64 / n as f64;
            [X0 + cx + u * c, Y0 + cy + u * s, -170.0 + 140.0 * l as f64]
        })
    };
    let walls: Vec<(String, TriMesh)> = [
        (200.3, 190.7, 3.0, 300.0),
        (180.1, 210.9, 87.0, 300.0),
        (150.7, 160.2, 41.0, 320.0),
        (230.4, 250.6, 133.0, 320.0),
        (120.9, 260.3, 17.0, 90.0),
        (280.2, 130.8, 68.0, 110.0),
        (210.6, 300.1, 152.0, 130.0),
        (90.4, 110.5, 112.0, 70.0),
    ]
    .iter()
    .enumerate()
    .map(|(k, &(x, y, a, l))| (format!("w{k}"), wall(x, y, a, l)))
    .collect();
    let mut all: Vec<(String, TriMesh)> = vec![("h".to_string(), h)];
    all.extend(walls);
    let mut xs = Vec::new();
    for i in 0..all.len() {
        for j in i + 1..all.len() {
            let x = both(&all[i].0, &all[i].1, &all[j].0, &all[j].1).expect("no coplanar contact");
            if !x.curves.is_empty() {
                xs.push(x);
            }
        }
    }
    let refs: Vec<(&str, &TriMesh)> = all.iter().map(|(n, m)| (n.as_str(), m)).collect();
    let out = split_both_orders(&refs, &xs);
    let sh = &out["h"];
    assert!(sh.crossings.len() >= 10, "{} crossings", sh.crossings.len());
    for &v in &sh.crossings {
        let at = sh.mesh.vertices[v as usize];
        let on: Vec<&String> = out
            .iter()
            .filter(|(n, s)| *n != "h" && vertex_at(s, at).is_some())
            .map(|(n, _)| n)
            .collect();
        assert_eq!(
            on.len(),
            2,
            "crossing {at:?} is a vertex of two walls: {on:?}"
        );
    }
}
