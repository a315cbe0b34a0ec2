//! Scenario tests of `model::intersect`: each surface pair is run in both orders (see
//! `intersect_support::both`) and every curve point is checked against its triangles.

use crate::intersect_support;

use geom::{BBox, TriMesh};
use intersect_support::{both, grid};
use model::intersect::{IntersectError, Location, PointKey, SurfaceRef, box_sides, intersect};

fn quad(p: [[f64; 3]; 4]) -> TriMesh {
    TriMesh::new(p.to_vec(), vec![[0, 1, 2], [0, 2, 3]])
}

fn flat(n: usize, step: f64) -> TriMesh {
    grid(n, n, |i, j| [i as f64 * step, j as f64 * step, 0.0])
}

#[test]
fn two_crossing_planes_meet_in_one_open_curve_from_border_to_border() {
    let a = flat(10, 1.0);
    let b = quad([
        [3.3, -1.0, -5.0],
        [3.3, 11.0, -5.0],
        [3.3, 11.0, 5.0],
        [3.3, -1.0, 5.0],
    ]);
    let x = both("horizon", &a, "fault", &b).expect("no coplanar contact");
    assert_eq!((x.a.as_str(), x.b.as_str()), ("fault", "horizon"));
    assert_eq!(x.curves.len(), 1);
    let c = &x.curves[0];
    assert!(!c.closed);
    let ys: Vec<f64> = c.points.iter().map(|p| p.xyz[1]).collect();
    let (y0, y1) = (ys[0].min(ys[ys.len() - 1]), ys[0].max(ys[ys.len() - 1]));
    assert!(
        y0.abs() < 1e-12 && (y1 - 10.0).abs() < 1e-12,
        "ends on the horizon's border: {ys:?}"
    );
    assert!(
        c.points
            .iter()
            .all(|p| (p.xyz[0] - 3.3).abs() < 1e-12 && p.xyz[2] == 0.0)
    );
    assert!(x.touches.is_empty());
}

#[test]
fn a_bump_poking_through_a_plane_makes_one_closed_loop() {
    let bump = grid(24, 24, |i, j| {
        let (x, y) = (-3.0 + 0.25 * i as f64, -3.0 + 0.25 * j as f64);
        [x, y, 2.0 * (-(x * x + y * y)).exp() - 1.0 + 0.013]
    });
    let plane = grid(3, 3, |i, j| {
        [
            -5.0 + 10.0 / 3.0 * i as f64,
            -5.0 + 10.0 / 3.0 * j as f64,
            0.0,
        ]
    });
    let x = both("bump", &bump, "plane", &plane).expect("no coplanar contact");
    assert_eq!(x.curves.len(), 1);
    let c = &x.curves[0];
    assert!(c.closed);
    assert_eq!(c.segments_faces.len(), c.points.len());
    for p in &c.points {
        let r = (p.xyz[0].powi(2) + p.xyz[1].powi(2)).sqrt();
        assert!((0.7..0.95).contains(&r), "radius {r} of {:?}", p.key);
        assert!(p.xyz[2].abs() < 1e-12);
    }
}

#[test]
fn a_horizon_crossing_a_fault_at_utm_coordinates_gives_one_curve_on_both_surfaces() {
    let (x0, y0) = (512_345.0, 7_012_345.0);
    let horizon = grid(60, 60, |i, j| {
        let (x, y) = (x0 + 3.5 * i as f64, y0 + 3.5 * j as f64);
        [
            x,
            y,
            -1000.0 + 2.0 * ((x - x0) / 17.0).sin() + 1.5 * ((y - y0) / 23.0).cos(),
        ]
    });
    let fault = grid(50, 8, |i, k| {
        let z = -1012.0 + 3.0 * k as f64;
        let y = y0 - 5.0 + 4.5 * i as f64;
        [x0 + 101.0 + 0.35 * (z + 1000.0) + 0.02 * (y - y0), y, z]
    });
    let x = both("top", &horizon, "f1", &fault).expect("no coplanar contact");
    assert_eq!(x.curves.len(), 1);
    let c = &x.curves[0];
    assert!(!c.closed);
    assert!(c.points.len() > 60, "{} points", c.points.len());
    let first = c.points[0].xyz;
    let last = c.points[c.points.len() - 1].xyz;
    let (lo, hi) = if first[1] < last[1] {
        (first, last)
    } else {
        (last, first)
    };
    assert!(
        lo[1] == y0 && hi[1] == y0 + 210.0,
        "ends on the horizon's border: {first:?} {last:?}"
    );
}

#[test]
fn a_plane_through_mesh_vertices_puts_every_curve_point_on_a_vertex() {
    let a = flat(10, 1.0);
    // The quad's diagonal crosses z = 0 at (3, 5, 0), a vertex of `a`.
    let b = quad([
        [3.0, -1.0, -6.0],
        [3.0, 11.0, -6.0],
        [3.0, 11.0, 6.0],
        [3.0, -1.0, 6.0],
    ]);
    let x = both("a", &a, "b", &b).expect("no coplanar contact");
    assert_eq!(x.curves.len(), 1);
    let c = &x.curves[0];
    assert_eq!(c.points.len(), 11);
    for p in &c.points {
        assert!(matches!(p.on_a, Location::Vertex(_)), "{:?}", p.key);
        assert_eq!((p.xyz[0], p.xyz[2]), (3.0, 0.0));
    }
}

#[test]
fn a_plane_containing_mesh_edges_gives_a_curve_along_those_edges() {
    // `a` is the plane z = x - 0.5 with a grid line exactly at x = 0.5, lying in `b` (z = 0).
    let a = grid(6, 8, |i, j| {
        let x = -1.0 + 0.5 * i as f64;
        [x, 0.5 * j as f64, x - 0.5]
    });
    let b = grid(3, 3, |i, j| {
        [-3.0 + 2.0 * i as f64, -3.0 + 3.0 * j as f64, 0.0]
    });
    let x = both("a", &a, "b", &b).expect("no coplanar contact");
    assert_eq!(x.curves.len(), 1);
    let c = &x.curves[0];
    for p in &c.points {
        assert_eq!((p.xyz[0], p.xyz[2]), (0.5, 0.0), "{:?}", p.key);
        assert!(
            matches!(p.on_a, Location::Vertex(_) | Location::Edge(..)),
            "{:?}",
            p.key
        );
    }
    assert!(
        c.points
            .iter()
            .any(|p| matches!(p.key, PointKey::EdgeEdge { .. })),
        "b's edges cross a's edges"
    );
    assert_eq!(c.points.first().map(|p| p.xyz[1]), Some(0.0));
    assert_eq!(c.points.last().map(|p| p.xyz[1]), Some(4.0));
}

#[test]
fn a_fault_sharing_its_bottom_row_of_vertices_with_a_horizon_meets_it_at_shared_vertices() {
    let a = flat(6, 1.0);
    let b = grid(6, 3, |j, k| [2.0, j as f64, k as f64]);
    let x = both("horizon", &a, "fault", &b).expect("no coplanar contact");
    assert_eq!(x.curves.len(), 1);
    assert_eq!(x.curves[0].points.len(), 7);
    assert!(
        x.curves[0]
            .points
            .iter()
            .all(|p| matches!(p.key, PointKey::VertexVertex { .. }))
    );
}

/// Tangent contact at a vertex is reported as a touch point, not as a curve.
#[test]
fn a_peak_touching_a_plane_at_one_vertex_is_a_touch_not_a_curve() {
    let a = flat(6, 1.0);
    let apex = [2.5, 2.5, 0.0];
    let b = TriMesh::new(
        vec![
            apex,
            [1.0, 1.0, 2.0],
            [4.0, 1.0, 2.0],
            [4.0, 4.0, 2.0],
            [1.0, 4.0, 2.0],
        ],
        vec![[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 1]],
    );
    let x = both("plane", &a, "peak", &b).expect("no coplanar contact");
    assert!(x.curves.is_empty());
    assert_eq!(x.touches.len(), 1);
    assert_eq!(x.touches[0].xyz, apex);
    assert_eq!(x.a, "peak");
    assert_eq!(x.touches[0].on_a, Location::Vertex(0));
    assert!(
        matches!(x.touches[0].on_b, Location::Edge(..)),
        "the apex lies on a grid diagonal"
    );
}

#[test]
fn coplanar_overlap_is_an_error_naming_both_surfaces_and_coordinates() {
    let a = flat(4, 1.0);
    let b = grid(2, 2, |i, j| [1.5 + i as f64, 0.5 + j as f64, 0.0]);
    let e = both("alpha", &a, "beta", &b).expect_err("coplanar overlap");
    let IntersectError::Coplanar {
        a: na,
        b: nb,
        contacts,
    } = &e
    else {
        panic!("{e}")
    };
    assert_eq!((na.as_str(), nb.as_str()), ("alpha", "beta"));
    assert!(!contacts.is_empty());
    for c in contacts {
        assert!(
            (1.5..=3.5).contains(&c.at[0]) && (0.5..=2.5).contains(&c.at[1]) && c.at[2] == 0.0,
            "{c:?}"
        );
    }
    let msg = e.to_string();
    assert!(msg.contains("`alpha`") && msg.contains("`beta`"), "{msg}");
    let at = contacts[0].at;
    assert!(
        msg.contains(&format!("({}, {}, {})", at[0], at[1], at[2])),
        "{msg}"
    );
}

#[test]
fn a_wavy_horizon_crosses_the_four_vertical_box_sides_and_not_the_top_or_bottom() {
    let b = BBox {
        min: [500_000.0, 7_000_000.0, -50.0],
        max: [500_100.0, 7_000_100.0, 50.0],
    };
    let horizon = grid(30, 30, |i, j| {
        let (x, y) = (499_990.0 + 4.0 * i as f64, 6_999_990.0 + 4.0 * j as f64);
        [
            x,
            y,
            5.0 * ((x - 500_000.0) / 13.0).sin() * ((y - 7_000_000.0) / 29.0).cos(),
        ]
    });
    for (name, side) in box_sides(&b) {
        let x = both("top", &horizon, &name, &side).expect("no coplanar contact");
        let expected = if name.starts_with("box.z") { 0 } else { 1 };
        assert_eq!(x.curves.len(), expected, "{name}");
        for c in &x.curves {
            assert!(!c.closed, "{name}");
            assert!(c.points.len() > 20, "{name}: {} points", c.points.len());
        }
    }
}

#[test]
fn adjacent_box_sides_meet_along_their_common_box_edge_only() {
    let b = BBox {
        min: [0.0, 0.0, 0.0],
        max: [3.0, 2.0, 1.0],
    };
    let sides = box_sides(&b);
    for (i, (ni, si)) in sides.iter().enumerate() {
        for (nj, sj) in sides.iter().skip(i + 1) {
            let x = both(ni, si, nj, sj).expect("no coplanar contact");
            let opposite = ni[..5] == nj[..5];
            assert_eq!(x.curves.len(), usize::from(!opposite), "{ni} × {nj}");
            for c in &x.curves {
                assert_eq!(c.points.len(), 2, "{ni} × {nj}");
                assert!(
                    c.points
                        .iter()
                        .all(|p| matches!(p.key, PointKey::VertexVertex { .. }))
                );
            }
        }
    }
}

#[test]
fn a_curve_of_a_hundred_thousand_segments_is_assembled_without_stack_overflow() {
    let strip = grid(50_000, 1, |i, j| [i as f64, j as f64, 0.0]);
    let plane = quad([
        [-1.0, 0.37, -1.0],
        [50_001.0, 0.37, -1.0],
        [50_001.0, 0.37, 1.0],
        [-1.0, 0.37, 1.0],
    ]);
    let x = std::thread::Builder::new()
        .stack_size(256 * 1024)
        .spawn(move || {
            intersect(
                SurfaceRef {
                    name: "strip",
                    mesh: &strip,
                },
                SurfaceRef {
                    name: "wall",
                    mesh: &plane,
                },
            )
        })
        .expect("thread")
        .join()
        .expect("no stack overflow")
        .expect("no coplanar contact");
    assert_eq!(x.curves.len(), 1);
    assert_eq!(x.curves[0].segments_faces.len(), 100_000);
}

#[test]
fn a_triangle_pointing_at_a_missing_vertex_is_an_error_naming_the_surface() {
    let a = TriMesh::new(
        vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        vec![[0, 1, 7]],
    );
    let b = flat(2, 1.0);
    let e = intersect(
        SurfaceRef {
            name: "broken",
            mesh: &a,
        },
        SurfaceRef {
            name: "ok",
            mesh: &b,
        },
    )
    .unwrap_err();
    assert!(
        matches!(
            e,
            IntersectError::BadVertexIndex {
                triangle: 0,
                vertex: 7,
                ..
            }
        ),
        "{e}"
    );
    assert!(e.to_string().contains("`broken`"));
}

#[test]
fn a_non_finite_coordinate_is_an_error_not_a_silent_miss() {
    let a = TriMesh::new(
        vec![[0.0; 3], [f64::NAN, 0.0, 0.0], [0.0, 1.0, 0.0]],
        vec![[0, 1, 2]],
    );
    let b = flat(2, 1.0);
    let e = intersect(
        SurfaceRef {
            name: "nan",
            mesh: &a,
        },
        SurfaceRef {
            name: "ok",
            mesh: &b,
        },
    )
    .unwrap_err();
    assert!(
        matches!(e, IntersectError::NonFinite { vertex: 1, .. }),
        "{e}"
    );
}

#[test]
fn a_surface_cannot_be_intersected_with_itself() {
    let a = flat(2, 1.0);
    let e = intersect(
        SurfaceRef {
            name: "x",
            mesh: &a,
        },
        SurfaceRef {
            name: "x",
            mesh: &a,
        },
    )
    .unwrap_err();
    assert!(matches!(e, IntersectError::SameSurface { .. }));
}

#[test]
fn zero_area_triangles_are_skipped_and_listed() {
    let a = TriMesh::new(
        vec![
            [0.0, 0.0, 0.0],
            [4.0, 0.0, 0.0],
            [0.0, 4.0, 0.0],
            [2.0, 0.0, 0.0],
        ],
        vec![[0, 1, 2], [0, 3, 1]],
    );
    let b = quad([
        [1.0, -1.0, -1.0],
        [1.0, 5.0, -1.0],
        [1.0, 5.0, 1.0],
        [1.0, -1.0, 1.0],
    ]);
    let x = both("a", &a, "b", &b).expect("no coplanar contact");
    assert_eq!(x.degenerate_a, vec![1]);
    assert_eq!(x.curves.len(), 1);
}

#[test]
fn the_result_does_not_depend_on_the_thread_count() {
    let a = grid(80, 80, |i, j| {
        let (x, y) = (500_000.0 + 2.5 * i as f64, 7_000_000.0 + 2.5 * j as f64);
        [
            x,
            y,
            3.0 * ((x - 500_000.0) / 11.0).sin() + 2.0 * ((y - 7_000_000.0) / 7.0).cos(),
        ]
    });
    let b = grid(40, 10, |i, k| {
        [
            500_000.0 + 5.0 * i as f64,
            7_000_100.0 + 0.5 * (k as f64 - 5.0),
            k as f64 - 5.0,
        ]
    });
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("pool");
        pool.install(|| {
            intersect(
                SurfaceRef {
                    name: "h",
                    mesh: &a,
                },
                SurfaceRef {
                    name: "f",
                    mesh: &b,
                },
            )
        })
    };
    let one = run(1).expect("no coplanar contact");
    assert!(!one.curves.is_empty());
    assert_eq!(Ok(one), run(3));
}

/// The usual case where the box is the horizon's own extent: the horizon's border edges lie in
/// the vertical box sides, and each side meets it along exactly that border.
#[test]
fn a_horizon_spanning_exactly_the_box_meets_each_vertical_side_along_its_border() {
    let horizon = grid(20, 20, |i, j| {
        let (x, y) = (500_000.0 + 5.0 * i as f64, 7_000_000.0 + 5.0 * j as f64);
        [
            x,
            y,
            3.0 * ((x - 500_000.0) / 9.0).sin() + ((y - 7_000_000.0) / 4.0).cos(),
        ]
    });
    let b = BBox {
        min: [500_000.0, 7_000_000.0, -10.0],
        max: [500_100.0, 7_000_100.0, 10.0],
    };
    for (name, side) in box_sides(&b) {
        let x = both("top", &horizon, &name, &side).expect("no coplanar contact");
        if name.starts_with("box.z") {
            assert!(x.curves.is_empty(), "{name}");
            continue;
        }
        assert_eq!(x.curves.len(), 1, "{name}");
        let c = &x.curves[0];
        assert!(c.points.len() >= 21, "{name}: {} points", c.points.len());
        let (axis, value) = match name.as_str() {
            "box.xmin" => (0, b.min[0]),
            "box.xmax" => (0, b.max[0]),
            "box.ymin" => (1, b.min[1]),
            _ => (1, b.max[1]),
        };
        assert!(
            c.points.iter().all(|p| p.xyz[axis] == value),
            "{name}: every point exactly on the side"
        );
    }
}
