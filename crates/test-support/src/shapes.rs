//! Small shapes for the tests of every crate.

/// The box `[lo, hi]` as eight corners (corner `i` takes `hi` on axis `k` where bit `k` of `i` is
/// set) and twelve triangles, two per side, with normals pointing out of the box.
pub fn cuboid(lo: [f64; 3], hi: [f64; 3]) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let corners = (0..8)
        .map(|i| [0, 1, 2].map(|k| if (i >> k) & 1 == 1 { hi[k] } else { lo[k] }))
        .collect();
    let quads: [[u32; 4]; 6] = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    let triangles = quads
        .iter()
        .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
        .collect();
    (corners, triangles)
}

/// The cube `[0, side]³`, each side split into `n` × `n` squares of two triangles, normals
/// pointing out; each vertex once.
pub fn gridded_cube(n: u32, side: f64) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let mut ids = std::collections::BTreeMap::new();
    let (mut vertices, mut triangles) = (Vec::new(), Vec::new());
    let step = side / n as f64;
    for k in 0..3 {
        let (u, v) = ((k + 1) % 3, (k + 2) % 3);
        for at in [0, n] {
            for i in 0..n {
                for j in 0..n {
                    let mut id = |a: u32, b: u32| {
                        let mut p = [0u32; 3];
                        (p[k], p[u], p[v]) = (at, a, b);
                        *ids.entry(p).or_insert_with(|| {
                            vertices.push(p.map(|c| c as f64 * step));
                            vertices.len() as u32 - 1
                        })
                    };
                    let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
                    if at > 0 {
                        triangles.extend([[a, b, c], [a, c, d]]);
                    } else {
                        triangles.extend([[a, c, b], [a, d, c]]);
                    }
                }
            }
        }
    }
    (vertices, triangles)
}

/// Half a cylinder of radius 150 m about the y axis, 600 m long, from y = 0, in `n` facets
/// round (two triangles each): an open sheet bent by 180°.
pub fn half_cylinder(n: u32) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let r = 150.0;
    let mut corners = Vec::new();
    for y in [0.0, 600.0] {
        for i in 0..=n {
            let a = std::f64::consts::PI * f64::from(i) / f64::from(n);
            corners.push([r * a.cos(), y, r * a.sin()]);
        }
    }
    let triangles = (0..n)
        .flat_map(|i| [[i, i + n + 2, i + 1], [i, i + n + 1, i + n + 2]])
        .collect();
    (corners, triangles)
}

/// The unit octahedron as six corners, ±x (0, 1), ±y (2, 3), ±z (4, 5), and eight triangles with
/// normals pointing out of it.
pub fn octahedron() -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let corners = vec![
        [1.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
    ];
    let triangles = [(0, 2), (2, 1), (1, 3), (3, 0)]
        .into_iter()
        .flat_map(|(x, y)| [[x, y, 4], [y, x, 5]])
        .collect();
    (corners, triangles)
}

/// The [`octahedron`] filled by eight positive tets around one more node, `centre` (node 6, which
/// must lie inside it), one per face in the face order.
pub fn octahedron_ball(centre: [f64; 3]) -> (Vec<[f64; 3]>, Vec<[u32; 4]>) {
    let (mut nodes, faces) = octahedron();
    nodes.push(centre);
    let tets = faces.iter().map(|&[a, b, c]| [b, a, c, 6]).collect();
    (nodes, tets)
}

/// A ramp: a ribbon between radii 4 and 5 that winds `turn_deg` round the z axis in steps of
/// `step_deg`, rising 0.5 per turn, its triangles facing up. Past a full turn its border crosses
/// itself in map view.
pub fn ramp(turn_deg: f64, step_deg: f64) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let segs = (turn_deg / step_deg).round() as u32;
    let mut vertices = Vec::new();
    for i in 0..=segs {
        let a = (step_deg * i as f64).to_radians();
        let z = 0.5 * a / std::f64::consts::TAU;
        vertices.push([4.0 * a.cos(), 4.0 * a.sin(), z]);
        vertices.push([5.0 * a.cos(), 5.0 * a.sin(), z]);
    }
    let triangles = (0..segs)
        .flat_map(|i| {
            let (inner, outer) = (2 * i, 2 * i + 1);
            [[inner, outer, outer + 2], [inner, outer + 2, inner + 2]]
        })
        .collect();
    (vertices, triangles)
}
