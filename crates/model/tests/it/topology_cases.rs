//! Surface topology on small meshes: a square with a hole, two pieces, a non-manifold fin,
//! kink corners, BSTONE corners, the walkers, and a real model with TFACE patches.

use geom::{Tolerances, TriMesh};
use gocad::import::{ImportOptions, import_surface};
use model::topology::SurfaceTopology;
use test_support::paths;

/// An n x n cell grid on [0, n]^2 (z = 0), cells listed row by row, minus the `holes` cells.
fn grid(n: u32, holes: &[(u32, u32)]) -> TriMesh {
    let mut v = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            v.push([i as f64, j as f64, 0.0]);
        }
    }
    let mut t = Vec::new();
    for j in 0..n {
        for i in 0..n {
            if holes.contains(&(i, j)) {
                continue;
            }
            let a = j * (n + 1) + i;
            t.push([a, a + 1, a + n + 2]);
            t.push([a, a + n + 2, a + n + 1]);
        }
    }
    TriMesh::new(v, t)
}

fn tol() -> Tolerances {
    Tolerances::default()
}

#[test]
fn a_square_with_a_hole_has_one_patch_an_outer_and_an_inner_loop() {
    let m = grid(3, &[(1, 1)]);
    let topo = SurfaceTopology::build(&m, &[], &tol());
    assert_eq!(topo.patch_count(), 1);
    let loops = topo.patch_loops(0);
    assert_eq!(loops.len(), 2);
    let outer = &topo.boundary_loops()[loops[0] as usize];
    let inner = &topo.boundary_loops()[loops[1] as usize];
    assert!(outer.outer && !inner.outer);
    assert_eq!(outer.vertices.len(), 12);
    assert_eq!(inner.vertices.len(), 4);
    assert!(outer.closed && inner.closed);
    let mut hole: Vec<u32> = inner.vertices.clone();
    hole.sort();
    assert_eq!(hole, vec![5, 6, 9, 10]);
    // 4 outer corners + 4 hole corners, each loop split into 4 curves.
    assert_eq!(topo.corners().len(), 8);
    assert_eq!(topo.curves().len(), 8);
}

#[test]
fn two_disconnected_pieces_are_two_patches_with_one_loop_each() {
    let mut m = grid(1, &[]);
    let off = m.vertices.len() as u32;
    for p in m.vertices.clone() {
        m.vertices.push([p[0] + 5.0, p[1], p[2]]);
    }
    m.triangles
        .extend([[off, off + 1, off + 3], [off, off + 3, off + 2]]);
    let topo = SurfaceTopology::build(&m, &[], &tol());
    assert_eq!(topo.patch_count(), 2);
    assert_eq!(topo.patch_triangles(0), &[0, 1]);
    assert_eq!(topo.patch_triangles(1), &[2, 3]);
    assert_eq!(topo.patch_loops(0).len(), 1);
    assert_eq!(topo.patch_loops(1).len(), 1);
}

#[test]
fn a_fin_of_three_triangles_on_one_edge_is_non_manifold_and_bounds_three_patches() {
    let v = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.5, 1.0, 0.0],
        [0.5, -1.0, 0.0],
        [0.5, 0.0, 1.0],
    ];
    let m = TriMesh::new(v, vec![[0, 1, 2], [1, 0, 3], [0, 1, 4]]);
    let topo = SurfaceTopology::build(&m, &[], &tol());
    let e = topo.edge_between(0, 1).unwrap();
    assert!(topo.is_non_manifold_edge(e));
    assert_eq!(
        topo.triangles_around_edge(e).collect::<Vec<_>>(),
        vec![0, 1, 2]
    );
    assert_eq!(topo.patch_count(), 3);
    // The fin edge is one curve shared by the three loops; its ends are corners.
    assert!(topo.corners().contains(&0) && topo.corners().contains(&1));
    let fin_curve = topo
        .curves()
        .iter()
        .position(|c| c.vertices == vec![0, 1])
        .expect("fin curve");
    let uses = (0..topo.boundary_loops().len() as u32)
        .filter(|&l| {
            topo.loop_curves(l)
                .iter()
                .any(|&(c, _)| c as usize == fin_curve)
        })
        .count();
    assert_eq!(uses, 3);
}

#[test]
fn kink_corners_split_a_square_loop_into_four_curves() {
    let m = grid(2, &[]);
    let topo = SurfaceTopology::build(&m, &[], &tol());
    assert_eq!(topo.corners(), &[0, 2, 6, 8]);
    assert_eq!(topo.curves().len(), 4);
    assert!(
        topo.curves()
            .iter()
            .all(|c| !c.closed && c.vertices.len() == 3)
    );
    // A kink threshold above 90 degrees leaves one closed curve.
    let blunt = Tolerances {
        kink_angle_deg: 95.0,
        ..tol()
    };
    let topo = SurfaceTopology::build(&m, &[], &blunt);
    assert!(topo.corners().is_empty());
    assert_eq!(topo.curves().len(), 1);
    assert!(topo.curves()[0].closed);
    assert_eq!(topo.curves()[0].vertices.len(), 8);
}

#[test]
fn bstone_vertices_are_corners_even_on_a_straight_boundary() {
    let m = grid(2, &[]);
    let blunt = Tolerances {
        kink_angle_deg: 95.0,
        ..tol()
    };
    let topo = SurfaceTopology::build(&m, &[1, 7], &blunt);
    assert_eq!(topo.corners(), &[1, 7]);
    assert_eq!(topo.curves().len(), 2);
    assert!(topo.curves().iter().all(|c| c.vertices.len() == 5));
}

#[test]
fn walkers_agree_on_triangles_half_edges_and_vertices() {
    let m = grid(2, &[]);
    let topo = SurfaceTopology::build(&m, &[], &tol());
    assert_eq!(topo.edge_count(), 16);
    for t in 0..topo.triangle_count() as u32 {
        let tri = topo.triangle(t);
        for (k, e) in topo.edges_of_triangle(t).into_iter().enumerate() {
            let h = SurfaceTopology::half_edge(t, k as u32);
            assert_eq!(topo.edge_of(h), e);
            assert_eq!(topo.origin(h), tri[k]);
            assert_eq!(topo.target(h), tri[(k + 1) % 3]);
            assert_eq!(
                SurfaceTopology::next_half_edge(SurfaceTopology::prev_half_edge(h)),
                h
            );
            assert!(topo.triangles_around_edge(e).any(|x| x == t));
            let [a, b] = topo.edge_vertices(e);
            assert!(
                topo.edges_around_vertex(a).contains(&e)
                    && topo.edges_around_vertex(b).contains(&e)
            );
        }
    }
    // The centre vertex of the 2x2 grid has 6 edges (the grid diagonals run one way).
    assert_eq!(topo.edges_around_vertex(4).len(), 6);
}

#[test]
fn a_bowtie_vertex_where_two_loops_touch_is_a_corner_and_both_loops_close() {
    // Two triangles sharing only vertex 0.
    let v = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [-1.0, 0.0, 0.0],
        [-1.0, -1.0, 0.0],
    ];
    let m = TriMesh::new(v, vec![[0, 1, 2], [0, 3, 4]]);
    let topo = SurfaceTopology::build(&m, &[], &tol());
    assert_eq!(topo.patch_count(), 2);
    assert!(
        topo.boundary_loops()
            .iter()
            .all(|l| l.closed && l.vertices.len() == 3)
    );
    assert!(topo.corners().contains(&0));
}

#[test]
fn the_split_cube_box_has_two_tface_patches_when_built_with_parts() {
    let Some(path) = paths::shared("data/gocad/ringmesh__RINGMesh/tests/data/split_cube.ml") else {
        return;
    };
    let bytes = std::fs::read(&path).expect("read");
    let opts = ImportOptions {
        object: Some("box".into()),
        skip_other_types: true,
        ..Default::default()
    };
    let s = import_surface(&bytes, "split_cube.ml", &opts).unwrap();
    let whole = SurfaceTopology::build(&s.mesh, &s.bstones, &tol());
    assert_eq!(whole.patch_count(), 1);
    let parts = SurfaceTopology::build_with_parts(&s.mesh, &s.triangle_part, &s.bstones, &tol());
    assert_eq!(parts.patch_count(), 2);
    // The seam at z = 0.3 (depth) is one closed square loop in each part: 4 corner vertices.
    for p in 0..2 {
        assert_eq!(parts.patch_loops(p).len(), 1);
    }
}

fn shared_surface(path: &str, object: Option<&str>) -> Option<gocad::import::ImportedSurface> {
    let file = paths::shared(&format!("data/gocad/{path}"))?;
    let bytes = std::fs::read(file).expect("read");
    let opts = ImportOptions {
        object: object.map(Into::into),
        skip_other_types: true,
        ..Default::default()
    };
    Some(import_surface(&bytes, path, &opts).expect("imports"))
}

#[test]
fn a_closed_kimberlite_body_is_one_patch_without_boundary() {
    let Some(s) = shared_surface(
        "simpeg-research__Astic-2020-JointInversion/Geology_Surfaces/PK2.ts",
        None,
    ) else {
        return;
    };
    let topo = SurfaceTopology::build(&s.mesh, &s.bstones, &tol());
    assert_eq!(topo.patch_count(), 1);
    assert!(topo.boundary_loops().is_empty());
    assert!(topo.curves().is_empty());
    // Euler characteristic of a sphere: V - E + F = 2.
    assert_eq!(
        s.mesh.vertices.len() as i64 - topo.edge_count() as i64 + topo.triangle_count() as i64,
        2
    );
}

#[test]
fn a_real_fault_has_one_outer_loop_split_at_its_bstones() {
    let path =
        "SCECcode__CFM/CFM5_release_2017/obj/CFM5_all/GVFA-WWFZ-EAST-Scodie_Lineament-CFM1.ts";
    let Some(s) = shared_surface(path, None) else {
        return;
    };
    let topo = SurfaceTopology::build(&s.mesh, &s.bstones, &tol());
    assert_eq!(topo.patch_count(), 1);
    assert_eq!(topo.boundary_loops().len(), 1);
    assert!(topo.boundary_loops()[0].outer && topo.boundary_loops()[0].closed);
    assert!(s.bstones.iter().all(|b| topo.corners().contains(b)));
    assert!(topo.curves().len() >= s.bstones.len());
}
