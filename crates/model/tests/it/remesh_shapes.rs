//! Re-triangulating a surface of any shape (`model::remesh`): closed bodies, tubes, creased
//! boxes and surfaces of two TFACEs, at UTM coordinates. Each result is checked as a surface:
//! every edge held by two triangles running it opposite ways (or one, on a border kept as it
//! was), every node on the old support, corners and kept vertices bit for bit.

use geom::predicates::{cross, dot, sub};
use geom::{Tolerances, TriMesh};
use model::remesh::{Remeshed, remesh};
use std::collections::BTreeMap;
use test_support::shapes::gridded_cube;

const X: f64 = 512_345.0;
const Y: f64 = 7_004_321.0;
const Z: f64 = -1_500.0;

fn at_utm(p: [f64; 3]) -> [f64; 3] {
    [X + p[0], Y + p[1], Z + p[2]]
}

/// A sphere of radius `r` about the UTM origin: an octahedron's faces split `n` × `n` and pushed
/// onto the sphere, normals out.
fn sphere(r: f64, n: u32) -> TriMesh {
    let corners = [
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, -1.0, 0.0],
    ];
    let mut ids: BTreeMap<[i64; 3], u32> = BTreeMap::new();
    let (mut vertices, mut triangles) = (Vec::new(), Vec::new());
    for k in 0..4 {
        for pole in [1.0, -1.0] {
            let (a, b, c) = (corners[k], corners[(k + 1) % 4], [0.0, 0.0, pole]);
            let mut id = |i: u32, j: u32| {
                let (u, v) = (f64::from(i) / f64::from(n), f64::from(j) / f64::from(n));
                let p: [f64; 3] = [0, 1, 2].map(|d| a[d] * (1.0 - u - v) + b[d] * u + c[d] * v);
                let key = p.map(|x| (x * 1e9).round() as i64);
                *ids.entry(key).or_insert_with(|| {
                    let l = dot(&p, &p).sqrt();
                    vertices.push(at_utm(p.map(|x| r * x / l)));
                    vertices.len() as u32 - 1
                })
            };
            for i in 0..n {
                for j in 0..n - i {
                    let (p, q, s) = (id(i, j), id(i + 1, j), id(i, j + 1));
                    let mut tris = vec![[p, q, s]];
                    if i + j + 1 < n {
                        tris.push([q, id(i + 1, j + 1), s]);
                    }
                    for t in tris {
                        triangles.push(if pole > 0.0 { t } else { [t[0], t[2], t[1]] });
                    }
                }
            }
        }
    }
    TriMesh::new(vertices, triangles)
}

/// An open vertical tube of radius `r` and height `h`, `n` facets round, normals out.
fn tube(r: f64, h: f64, n: u32) -> TriMesh {
    let mut vertices = Vec::new();
    for z in [0.0, h] {
        for i in 0..n {
            let a = std::f64::consts::TAU * f64::from(i) / f64::from(n);
            vertices.push(at_utm([r * a.cos(), r * a.sin(), z]));
        }
    }
    let triangles = (0..n)
        .flat_map(|i| {
            let j = (i + 1) % n;
            [[i, j, j + n], [i, j + n, i + n]]
        })
        .collect();
    TriMesh::new(vertices, triangles)
}

/// The directed edges of `m` and how often each occurs.
fn directed(m: &TriMesh) -> BTreeMap<[u32; 2], u32> {
    let mut d = BTreeMap::new();
    for t in &m.triangles {
        for k in 0..3 {
            *d.entry([t[k], t[(k + 1) % 3]]).or_insert(0) += 1;
        }
    }
    d
}

/// The border edges of `m` (held by one triangle), and whether every other edge is held by two
/// triangles running it opposite ways.
fn border_and_manifold(m: &TriMesh) -> (usize, bool) {
    let d = directed(m);
    let mut border = 0;
    let mut manifold = true;
    for (&[a, b], &n) in &d {
        let back = d.get(&[b, a]).copied().unwrap_or(0);
        manifold &= n == 1 && back <= 1;
        border += usize::from(back == 0);
    }
    (border, manifold)
}

/// Vertices minus edges plus faces.
fn euler(m: &TriMesh) -> i64 {
    let edges: std::collections::BTreeSet<[u32; 2]> = (directed(m).keys())
        .map(|&[a, b]| [a.min(b), a.max(b)])
        .collect();
    m.vertices.len() as i64 - edges.len() as i64 + m.triangles.len() as i64
}

/// The distance from `p` to the triangle `abc`.
fn to_triangle(p: &[f64; 3], [a, b, c]: [[f64; 3]; 3]) -> f64 {
    let n = cross(&sub(&b, &a), &sub(&c, &a));
    let nl = dot(&n, &n).sqrt();
    let inside = [(a, b), (b, c), (c, a)]
        .iter()
        .all(|(u, v)| dot(&cross(&sub(v, u), &sub(p, u)), &n) >= 0.0);
    if inside {
        return (dot(&sub(p, &a), &n) / nl).abs();
    }
    [(a, b), (b, c), (c, a)]
        .iter()
        .map(|(u, v)| {
            let e = sub(v, u);
            let t = (dot(&sub(p, u), &e) / dot(&e, &e)).clamp(0.0, 1.0);
            let q = [0, 1, 2].map(|k| u[k] + t * e[k]);
            let d = sub(p, &q);
            dot(&d, &d).sqrt()
        })
        .fold(f64::INFINITY, f64::min)
}

/// The farthest any node of `new` lies from the support `old`.
fn farthest_off(old: &TriMesh, new: &TriMesh) -> f64 {
    (new.vertices.iter())
        .map(|p| {
            (old.triangles.iter())
                .map(|t| to_triangle(p, t.map(|v| old.vertices[v as usize])))
                .fold(f64::INFINITY, f64::min)
        })
        .fold(0.0, f64::max)
}

/// The mean edge length of `m`.
fn mean_edge(m: &TriMesh) -> f64 {
    let d = directed(m);
    let sum: f64 = (d.keys())
        .map(|&[a, b]| {
            let e = sub(&m.vertices[a as usize], &m.vertices[b as usize]);
            dot(&e, &e).sqrt()
        })
        .sum();
    sum / d.len() as f64
}

fn remeshed(name: &str, m: &TriMesh, parts: &[u32], keep: &[u32], size: f64) -> Remeshed {
    remesh(name, m, parts, keep, size, &Tolerances::default())
        .unwrap_or_else(|e| panic!("{name}: {e}"))
}

#[test]
fn a_closed_sphere_with_no_border_retriangulates_into_a_closed_surface_on_its_support() {
    let old = sphere(400.0, 12);
    let new = remeshed("ball", &old, &[], &[], 60.0);
    let (border, manifold) = border_and_manifold(&new.mesh);
    assert_eq!(border, 0, "a closed surface stays closed");
    assert!(manifold, "every edge twice, opposite ways: one orientation");
    assert_eq!(euler(&new.mesh), 2, "a sphere");
    let off = farthest_off(&old, &new.mesh);
    assert!(off < 1e-6, "a node {off} m off the support");
    let h = mean_edge(&new.mesh);
    assert!((40.0..80.0).contains(&h), "mean edge {h}");
    assert!(new.parts.iter().all(|&p| p == 0));
}

#[test]
fn an_open_tube_keeps_its_two_borders_where_they_were() {
    let old = tube(150.0, 600.0, 24);
    let new = remeshed("tube", &old, &[], &[], 40.0);
    let (border, manifold) = border_and_manifold(&new.mesh);
    assert!(manifold);
    assert_eq!(euler(&new.mesh), 0, "an annulus");
    // Both rims resampled at about 40 m on the old rims' 24 chords (each 39 m long).
    assert!((40..=60).contains(&border), "{border} border edges");
    for p in &new.mesh.vertices {
        let (dz_bottom, dz_top) = ((p[2] - Z).abs(), (p[2] - Z - 600.0).abs());
        let on_rim = dz_bottom == 0.0 || dz_top == 0.0;
        assert!(
            on_rim || (p[2] > Z && p[2] < Z + 600.0),
            "{p:?} beyond the rims"
        );
    }
    assert!(farthest_off(&old, &new.mesh) < 1e-6);
}

#[test]
fn a_cube_in_one_tface_keeps_its_corners_and_its_creases() {
    let (v, t) = gridded_cube(2, 300.0);
    let old = TriMesh::new(v.into_iter().map(at_utm).collect(), t);
    let new = remeshed("cube", &old, &[], &[], 50.0);
    let (border, manifold) = border_and_manifold(&new.mesh);
    assert_eq!(border, 0);
    assert!(manifold);
    assert_eq!(euler(&new.mesh), 2);
    for corner in 0..8 {
        let c = at_utm([0, 1, 2].map(|k| if (corner >> k) & 1 == 1 { 300.0 } else { 0.0 }));
        assert!(new.mesh.vertices.contains(&c), "corner {c:?} lost");
    }
    // No triangle cuts across an edge of the cube: its three nodes lie on one side.
    for t in &new.mesh.triangles {
        let p = t.map(|v| new.mesh.vertices[v as usize]);
        let on_one_side = (0..3).any(|k| {
            let o = [X, Y, Z][k];
            p.iter().all(|q| q[k] == o) || p.iter().all(|q| q[k] == o + 300.0)
        });
        assert!(on_one_side, "{p:?} bends across a crease");
    }
}

#[test]
fn two_tfaces_keep_the_border_between_them_and_a_kept_vertex_stays_bit_for_bit() {
    // A flat 800 m square of 8 × 8 cells, its left half one TFACE and its right half another;
    // one vertex in the left half is a corner mark to keep.
    let n = 8u32;
    let mut vertices = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let wobble = 0.01 * f64::from((i * 7 + j * 3) % 5);
            vertices.push(at_utm([
                100.0 * f64::from(i) + wobble,
                100.0 * f64::from(j),
                0.0,
            ]));
        }
    }
    let (mut triangles, mut parts) = (Vec::new(), Vec::new());
    for j in 0..n {
        for i in 0..n {
            let a = j * (n + 1) + i;
            triangles.extend([[a, a + 1, a + n + 2], [a, a + n + 2, a + n + 1]]);
            parts.extend([u32::from(i >= n / 2); 2]);
        }
    }
    let old = TriMesh::new(vertices, triangles);
    let keep = 2 * (n + 1) + 2;
    let new = remeshed("sheet", &old, &parts, &[keep], 45.0);
    assert!(new.mesh.vertices.contains(&old.vertices[keep as usize]));
    assert!(farthest_off(&old, &new.mesh) < 1e-6);
    let (_, manifold) = border_and_manifold(&new.mesh);
    assert!(manifold);
    // Triangles of each part, and every edge between the two parts on the old border (the
    // column of vertices i = 4, whose x wobbles by centimetres).
    assert!(new.parts.contains(&0) && new.parts.contains(&1));
    let border_x = |y: f64| {
        let j = ((y - Y) / 100.0).floor().clamp(0.0, f64::from(n - 1)) as u32;
        let (a, b) = (j * (n + 1) + n / 2, (j + 1) * (n + 1) + n / 2);
        let (pa, pb) = (old.vertices[a as usize], old.vertices[b as usize]);
        pa[0] + (pb[0] - pa[0]) * (y - pa[1]) / (pb[1] - pa[1])
    };
    let mut between = 0;
    let side: BTreeMap<[u32; 2], u32> = (new.mesh.triangles.iter().zip(&new.parts))
        .flat_map(|(t, &p)| (0..3).map(move |k| ([t[k], t[(k + 1) % 3]], p)))
        .collect();
    for (&[a, b], &p) in &side {
        if side.get(&[b, a]).is_some_and(|&q| q != p) {
            between += 1;
            for v in [a, b] {
                let q = new.mesh.vertices[v as usize];
                assert!(
                    (q[0] - border_x(q[1])).abs() < 1e-6,
                    "{q:?} off the TFACE border"
                );
            }
        }
    }
    assert!(
        between >= 2 * 16,
        "{between} directed edges between the TFACEs"
    );
}
