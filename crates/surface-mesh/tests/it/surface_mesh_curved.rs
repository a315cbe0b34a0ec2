//! Surface mesher on curved supports that defeat height-field meshers: the didactic wavy
//! horizon, a fault dipping 85°, a recumbent (S-shaped, overturned) fold, a hemisphere cap, and a
//! coarse support of long thin triangles like gOcad exports. All at UTM offsets too.

use surface_mesh_common::*;
use test_support::surface_mesh_common;

use geom::TriMesh;
use geom::predicates::dist;
use std::f64::consts::PI;
use surface_mesh::PatchInput;

fn shift(p: [f64; 3], off: [f64; 3]) -> [f64; 3] {
    [p[0] + off[0], p[1] + off[1], p[2] + off[2]]
}

#[test]
fn the_wavy_didactic_horizon_meshes_on_its_support() {
    for off in [[0.0; 3], UTM] {
        let g = Grid {
            nx: 50,
            ny: 50,
            u: (0.0, 4000.0),
            v: (0.0, 4000.0),
            f: wavy,
            offset: off,
        };
        let input = PatchInput {
            name: "wavy horizon".into(),
            support: g.support(),
            loops: vec![g.border_loop(40, 40)],
            constraints: vec![],
            points: Vec::new(),
            facets: Vec::new(),
        };
        let (out, q) = mesh_and_check(&input, &uniform(100.0), 1.03, 1.6);
        assert!(q.triangles > 3000);
        // Nodes follow the wave: the support is within 80 m of -1200.
        assert!(
            out.nodes
                .iter()
                .all(|p| (p[2] + 1200.0).abs() <= 80.0 + 1e-6)
        );
    }
}

#[test]
fn a_fault_dipping_85_degrees_meshes_like_a_flat_patch() {
    let dip = 85f64.to_radians();
    for off in [[0.0; 3], UTM] {
        // u along strike (y), v down dip.
        let g = Grid {
            nx: 6,
            ny: 4,
            u: (0.0, 2000.0),
            v: (0.0, 1500.0),
            f: move |u, v| [1000.0 + v * dip.cos(), u, -200.0 - v * dip.sin()],
            offset: off,
        };
        let input = PatchInput {
            name: "steep fault".into(),
            support: g.support(),
            loops: vec![g.border_loop(40, 30)],
            constraints: vec![],
            points: Vec::new(),
            facets: Vec::new(),
        };
        let (_, q) = mesh_and_check(&input, &uniform(50.0), 1.03, 1.5);
        assert!(q.triangles > 2000);
    }
}

/// A recumbent fold in the xz-plane: three horizontal limbs 600 m long stacked 300 m apart,
/// joined by two hinges of radius 150 m (a Z with round hinges), as a function of u in [0, 5]
/// (one unit per limb or hinge). The limbs overlap in every direction: no height field anywhere.
pub(crate) fn z_curve(u: f64) -> [f64; 2] {
    let (l, r) = (600.0, 150.0);
    let k = (u.floor() as i64).clamp(0, 4);
    let t = u - k as f64;
    match k {
        0 => [-l + l * t, 0.0],
        1 => {
            let a = -PI / 2.0 + PI * t;
            [r * a.cos(), r + r * a.sin()]
        }
        2 => [-l * t, 2.0 * r],
        3 => {
            let a = -PI / 2.0 + PI * t;
            [-l - r * a.cos(), 3.0 * r + r * a.sin()]
        }
        _ => [-l + l * t, 4.0 * r],
    }
}

#[test]
fn a_recumbent_fold_that_is_no_height_field_meshes_without_folds() {
    for off in [[0.0; 3], UTM] {
        let g = fold_grid(off);
        let input = PatchInput {
            name: "recumbent fold".into(),
            support: g.support(),
            loops: vec![g.border_loop(60, 24)],
            constraints: vec![],
            points: Vec::new(),
            facets: Vec::new(),
        };
        let (out, q) = mesh_and_check(&input, &uniform(50.0), 1.04, 1.6);
        assert!(q.triangles > 1500);
        // All three stacked limbs are meshed: nodes above one another at x = -300.
        let z = |p: &[f64; 3]| p[2] - off[2] + 2000.0;
        for level in [0.0, 300.0, 600.0] {
            assert!(
                out.nodes
                    .iter()
                    .any(|p| (p[0] - off[0] + 300.0).abs() < 60.0 && (z(p) - level).abs() < 1.0),
                "no node on the limb at z = {level}"
            );
        }
    }
}

/// A disk triangulation mapped onto a sphere cap: ring k has 6k vertices.
pub(crate) fn cap(rings: usize, radius: f64, max_polar: f64, off: [f64; 3]) -> TriMesh {
    let mut vs = vec![shift([0.0, 0.0, radius], off)];
    let mut start = vec![0usize];
    for k in 1..=rings {
        start.push(vs.len());
        let a = max_polar * k as f64 / rings as f64;
        for j in 0..6 * k {
            let phi = 2.0 * PI * j as f64 / (6 * k) as f64;
            vs.push(shift(
                [
                    radius * a.sin() * phi.cos(),
                    radius * a.sin() * phi.sin(),
                    radius * a.cos(),
                ],
                off,
            ));
        }
    }
    let mut ts = Vec::new();
    for k in 0..rings {
        // Merge ring k (n0 vertices) and ring k+1 (n1) by angle.
        let n0 = if k == 0 { 1 } else { 6 * k };
        let n1 = 6 * (k + 1);
        let (s0, s1) = (start[k], start[k + 1]);
        if k == 0 {
            for j in 0..n1 {
                ts.push([0, (s1 + j) as u32, (s1 + (j + 1) % n1) as u32]);
            }
            continue;
        }
        let (mut i, mut j) = (0usize, 0usize);
        while i < n0 || j < n1 {
            let ai = (i as f64) / n0 as f64;
            let aj = (j as f64) / n1 as f64;
            let adv_outer = j < n1 && (i >= n0 || aj + 0.5 / n1 as f64 <= ai + 0.5 / n0 as f64);
            let a = (s0 + i % n0) as u32;
            let b = (s1 + j % n1) as u32;
            if adv_outer {
                let c = (s1 + (j + 1) % n1) as u32;
                ts.push([a, b, c]);
                j += 1;
            } else {
                let c = (s0 + (i + 1) % n0) as u32;
                ts.push([a, b, c]);
                i += 1;
            }
        }
    }
    TriMesh::new(vs, ts)
}

#[test]
fn a_hemisphere_cap_meshes_with_nodes_on_the_sphere_facets() {
    for off in [[0.0; 3], UTM] {
        let rings = 12;
        let support = cap(rings, 1000.0, PI / 2.0, off);
        // The rim: the outer ring's vertices (on the support's border), every second one.
        let n = 6 * rings;
        let first = support.vertices.len() - n;
        let rim: Vec<[f64; 3]> = (0..n)
            .step_by(1)
            .map(|j| support.vertices[first + j])
            .collect();
        let input = PatchInput {
            name: "hemisphere cap".into(),
            support,
            loops: vec![rim],
            constraints: vec![],
            points: Vec::new(),
            facets: Vec::new(),
        };
        let (out, q) = mesh_and_check(&input, &uniform(90.0), 1.06, 1.8);
        assert!(q.triangles > 300);
        // All nodes close to the sphere (the support is a faceted sphere).
        for p in &out.nodes {
            let r = ((p[0] - off[0]).powi(2) + (p[1] - off[1]).powi(2) + (p[2] - off[2]).powi(2))
                .sqrt();
            assert!(r > 960.0 && r < 1000.0 + 1e-6, "r = {r}");
        }
    }
}

#[test]
fn a_coarse_support_of_long_thin_triangles_is_meshed_finely_on_it() {
    for off in [[0.0; 3], UTM] {
        // 2 × 30 cells over 3000 × 3000 m: triangles 1500 m by 100 m.
        let g = Grid {
            nx: 2,
            ny: 30,
            u: (0.0, 3000.0),
            v: (0.0, 3000.0),
            f: wavy,
            offset: off,
        };
        let input = PatchInput {
            name: "gOcad-like coarse support".into(),
            support: g.support(),
            loops: vec![g.border_loop(40, 40)],
            constraints: vec![],
            points: Vec::new(),
            facets: Vec::new(),
        };
        mesh_and_check(&input, &uniform(75.0), 1.04, 1.6);
    }
}

#[test]
fn the_recumbent_fold_support_needs_and_gets_a_fold_free_tutte_flattening() {
    use surface_mesh::flattening_method;
    assert_eq!(
        flattening_method(&fold_grid(UTM).support()).unwrap(),
        "tutte"
    );
    let horizon = Grid {
        nx: 10,
        ny: 10,
        u: (0.0, 4000.0),
        v: (0.0, 4000.0),
        f: wavy,
        offset: UTM,
    };
    assert_eq!(flattening_method(&horizon.support()).unwrap(), "plane");
}

#[test]
fn a_tight_fold_hinge_gets_smaller_triangles_than_the_flat_limbs() {
    let g = Grid {
        nx: 100,
        ny: 8,
        u: (0.0, 5.0),
        v: (0.0, 1200.0),
        f: |u, y| {
            let c = z_curve(u);
            [c[0], y, c[1]]
        },
        offset: UTM,
    };
    // Boundary at ~100 m; target 150 m: the hinges (radius 150 m) ask for ~52 m.
    let input = PatchInput {
        name: "fold hinges".into(),
        support: g.support(),
        loops: vec![g.border_loop(30, 12)],
        constraints: vec![],
        points: Vec::new(),
        facets: Vec::new(),
    };
    let size = surface_mesh::SurfaceSize {
        size: 150.0,
        min_size: 10.0,
        max_size: 300.0,
        growth: 1.2,
    };
    let (out, _) = mesh_and_check(&input, &size, 1.08, 2.0);
    let mean_edge = |pick: &dyn Fn(&[f64; 3]) -> bool| {
        let (mut s, mut n) = (0.0, 0);
        for t in &out.triangles {
            let [a, b, c] = t.map(|v| out.nodes[v as usize]);
            let g = [
                (a[0] + b[0] + c[0]) / 3.0 - UTM[0],
                0.0,
                (a[2] + b[2] + c[2]) / 3.0,
            ];
            if pick(&g) {
                s += ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt();
                n += 1;
            }
        }
        s / n.max(1) as f64
    };
    let hinge = mean_edge(&|g| g[0] > 100.0); // right hinge, x in (100, 150]
    let limb = mean_edge(&|g| g[0] < -200.0 && g[0] > -450.0 && (g[2] - 300.0).abs() < 10.0); // middle limb
    assert!(hinge < 0.75 * limb, "hinge {hinge} limb {limb}");
}

/// A horizon cut by a reverse fault that dies out at the origin: polar rings round the fault's
/// tip, the sector angle stretched so that the horizon turns `turn` degrees round the tip, and
/// lifted along it so that the lips (the slit along the negative x axis) are `throw` apart at the
/// rim. With `turn` above 360 the lips overlap in map view, as a reverse fault's do.
fn horizon_round_a_fault_tip(turn: f64, throw: f64, rings: u32, sectors: u32) -> PatchInput {
    let radius = 1000.0;
    let at = |r: f64, s: u32| {
        let a = f64::from(s) / f64::from(sectors) - 0.5;
        let phi = (turn * a).to_radians();
        shift([r * phi.cos(), r * phi.sin(), throw * a * r / radius], UTM)
    };
    let mut vertices = vec![shift([0.0; 3], UTM)];
    for k in 1..=rings {
        let r = radius * f64::from(k) / f64::from(rings);
        vertices.extend((0..=sectors).map(|s| at(r, s)));
    }
    let id = |k: u32, s: u32| 1 + (k - 1) * (sectors + 1) + s;
    let mut triangles = Vec::new();
    for s in 0..sectors {
        triangles.push([0, id(1, s), id(1, s + 1)]);
        for k in 1..rings {
            triangles.push([id(k, s), id(k + 1, s), id(k + 1, s + 1)]);
            triangles.push([id(k, s), id(k + 1, s + 1), id(k, s + 1)]);
        }
    }
    // The loop: up one lip, round the rim, down the other lip, in coarse steps.
    let mut border = vec![shift([0.0; 3], UTM)];
    border.extend((1..=4).map(|k| at(radius * f64::from(k) / 4.0, 0)));
    border.extend((1..24).map(|s| at(radius, s * sectors / 24)));
    border.extend(
        (1..=4)
            .rev()
            .map(|k| at(radius * f64::from(k) / 4.0, sectors)),
    );
    PatchInput {
        name: "horizon at a fault tip".into(),
        support: TriMesh::new(vertices, triangles),
        loops: vec![border],
        constraints: vec![],
        points: Vec::new(),
        facets: Vec::new(),
    }
}

#[test]
fn a_horizon_whose_lips_overlap_round_a_reverse_fault_tip_meshes_without_folds() {
    // Round the tip the horizon turns more than a full turn: a coarse mesh's triangle there
    // spans more than 180° on the support while it spans less in the flattening, and folds.
    // Lips 30 m apart in height, overlapping by 0.5° to 4° in map view.
    for turn in [360.5, 362.0, 364.0] {
        let input = horizon_round_a_fault_tip(turn, 30.0, 12, 96);
        let out = surface_mesh::mesh_patch(&input, &uniform(600.0))
            .unwrap_or_else(|e| panic!("turn {turn}: {e}"));
        assert!(out.triangles.len() > 8, "turn {turn}");
    }
}

/// The recumbent fold of `a_recumbent_fold_that_is_no_height_field_meshes_without_folds` on a
/// 100 × 8 grid.
fn fold_grid(off: [f64; 3]) -> Grid<impl Fn(f64, f64) -> [f64; 3]> {
    Grid {
        nx: 100,
        ny: 8,
        u: (0.0, 5.0),
        v: (0.0, 1200.0),
        f: |u, y| {
            let c = z_curve(u);
            [c[0], y, c[1] - 2000.0]
        },
        offset: off,
    }
}

/// The fold's support with a hole cut out of its middle (flat) limb that touches the border at
/// one vertex, cell corner (50, 0): the triangle of cell (50, 0) away from the border and the
/// cells (50..54, 1..4) are removed. Returns the support and the hole's loop, along the removed
/// triangles' edges in steps of at most 50 m.
fn fold_with_a_hole_touching_its_border(off: [f64; 3]) -> (TriMesh, Vec<[f64; 3]>) {
    let fold = fold_grid(off);
    let mut support = fold.support();
    let cell = |i: usize, j: usize| 2 * (j * 100 + i);
    let mut cut = vec![cell(50, 0) + 1];
    for j in 1..4 {
        for i in 50..54 {
            cut.extend([cell(i, j), cell(i, j) + 1]);
        }
    }
    support.triangles = (0..support.triangles.len())
        .filter(|t| !cut.contains(t))
        .map(|t| support.triangles[t])
        .collect();
    // Corners of the hole in grid units, round from the pinch.
    let corners = [(50, 0), (51, 1), (54, 1), (54, 4), (50, 4), (50, 1)];
    let mut hole = Vec::new();
    for k in 0..corners.len() {
        let (a, b) = (corners[k], corners[(k + 1) % corners.len()]);
        let param = |(i, j): (i32, i32)| (0.05 * f64::from(i), 150.0 * f64::from(j));
        let ((u0, v0), (u1, v1)) = (param(a), param(b));
        let steps = (dist(&fold.at(u0, v0), &fold.at(u1, v1)) / 50.0).ceil() as usize;
        for s in 0..steps {
            let t = s as f64 / steps as f64;
            hole.push(fold.at(u0 + t * (u1 - u0), v0 + t * (v1 - v0)));
        }
    }
    (support, hole)
}

#[test]
fn a_recumbent_fold_with_a_hole_touching_its_border_flattens_and_meshes() {
    for off in [[0.0; 3], UTM] {
        let (support, hole) = fold_with_a_hole_touching_its_border(off);
        let border = fold_grid(off).border_loop(60, 24);
        assert_eq!(border[30], hole[0], "the loops touch at the pinch, u = 2.5");
        // No plane projection is one to one, and a Tutte embedding must keep the pinch one point.
        assert_eq!(surface_mesh::flattening_method(&support).unwrap(), "tutte");
        let input = PatchInput {
            name: "fold with a hole touching its border".into(),
            support,
            loops: vec![border, hole.clone()],
            constraints: vec![],
            points: Vec::new(),
            facets: Vec::new(),
        };
        let (out, q) = mesh_and_check(&input, &uniform(50.0), 1.05, 1.8);
        assert!(q.triangles > 1500);
        assert_eq!(out.nodes.iter().filter(|n| **n == hole[0]).count(), 1);
    }
}

/// A square of 1 km (at `off`) in two triangles, the second split at a vertex 5 cm off the
/// middle of the diagonal and 0.5 m above it: the cap between that vertex and the diagonal
/// (triangle 1) stands at 84° to the square. Its border as a loop of 100 m segments.
fn square_with_a_cap(off: [f64; 3]) -> PatchInput {
    let p = |x: f64, y: f64, z: f64| shift([x, y, z], off);
    let vertices = vec![
        p(0.0, 0.0, 0.0),
        p(1000.0, 0.0, 0.0),
        p(1000.0, 1000.0, 0.0),
        p(0.0, 1000.0, 0.0),
        p(499.965, 500.035, 0.5),
    ];
    let triangles = vec![[0, 1, 2], [0, 2, 4], [2, 3, 4], [3, 0, 4]];
    let side = |a: [f64; 2], b: [f64; 2]| {
        (0..10).map(move |k| {
            let t = f64::from(k) / 10.0;
            p(a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), 0.0)
        })
    };
    let corners = [[0.0, 0.0], [1000.0, 0.0], [1000.0, 1000.0], [0.0, 1000.0]];
    let border = (0..4)
        .flat_map(|k| side(corners[k], corners[(k + 1) % 4]))
        .collect();
    PatchInput {
        name: "square with a cap".into(),
        support: TriMesh::new(vertices, triangles),
        loops: vec![border],
        constraints: vec![],
        points: Vec::new(),
        facets: Vec::new(),
    }
}

#[test]
fn a_cap_that_stands_for_the_surface_asks_for_no_small_triangles_at_its_wall() {
    for off in [[0.0; 3], UTM] {
        let mut input = square_with_a_cap(off);
        let (_, own) = mesh_and_check(&input, &uniform(100.0), 1.1, 1.6);
        input.facets = vec![(1, [0.0, 0.0, 1.0])];
        let (_, standing_for) = mesh_and_check(&input, &uniform(100.0), 1.1, 1.6);
        let mut flat = square_with_a_cap(off);
        flat.support.vertices[4][2] = off[2];
        let (_, plain) = mesh_and_check(&flat, &uniform(100.0), 1.1, 1.6);
        // Its own normal asks for smaller triangles at its wall (264 against 248; where a curve
        // cuts a cap, the pieces left beside the curve asked for 5 m against 250 m).
        assert!(own.triangles > plain.triangles, "{own:?} {plain:?}");
        assert!(standing_for.triangles < own.triangles);
        let (a, b) = (standing_for.triangles as f64, plain.triangles as f64);
        assert!((a - b).abs() <= 0.02 * b, "{a} against {b} without the cap");
    }
}
