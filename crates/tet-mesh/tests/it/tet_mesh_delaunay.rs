//! The Delaunay method of the tetrahedral mesher (the default): boundary recovery without a node
//! on a boundary face, embedded faces kept through refinement, the same result both ways round,
//! and agreement with the advancing front on what the mesh must be.

use test_support::paths;
use tet_mesh::{
    Method, RegionInput, SizeField, TetMeshOptions, TetMeshOutput, mesh_region, verify,
};

type P = [f64; 3];

/// Orient every triangle of a convex shell so its normal points away from `centre`.
fn outward(pts: &[P], tris: &mut [[u32; 3]], centre: P) {
    for t in tris.iter_mut() {
        let [a, b, c] = t.map(|i| pts[i as usize]);
        let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
        let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
        let n = [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ];
        let g = [0, 1, 2].map(|k| (a[k] + b[k] + c[k]) / 3.0 - centre[k]);
        if n[0] * g[0] + n[1] * g[1] + n[2] * g[2] < 0.0 {
            t.swap(1, 2);
        }
    }
}

/// The box `[0, w] x [0, l] x [0, h]` with both long sides split into `n` columns. The bottom is
/// a regular zigzag strip; the top is two fans of needles (from the first point of one row to
/// every point of the other and back), a triangulation no Delaunay tetrahedralization contains.
pub(crate) fn box_with_fanned_top(n: u32, w: f64, l: f64, h: f64, origin: P) -> RegionInput {
    let mut pts: Vec<P> = Vec::new();
    let mut id = |x: f64, y: f64, z: f64| {
        pts.push([origin[0] + x, origin[1] + y, origin[2] + z]);
        (pts.len() - 1) as u32
    };
    let step = w / n as f64;
    let row = |y: f64, z: f64, id: &mut dyn FnMut(f64, f64, f64) -> u32| {
        (0..=n)
            .map(|i| id(i as f64 * step, y, z))
            .collect::<Vec<u32>>()
    };
    let a = row(0.0, h, &mut id); // top, y = 0
    let b = row(l, h, &mut id); // top, y = l
    let c = row(0.0, 0.0, &mut id); // bottom, y = 0
    let d = row(l, 0.0, &mut id); // bottom, y = l
    let n = n as usize;
    let mut tris: Vec<[u32; 3]> = Vec::new();
    for i in 0..n {
        // Long sides (y = 0 and y = l) and the bottom: regular strips.
        tris.push([a[i], a[i + 1], c[i]]);
        tris.push([a[i + 1], c[i + 1], c[i]]);
        tris.push([b[i], b[i + 1], d[i]]);
        tris.push([b[i + 1], d[i + 1], d[i]]);
        tris.push([c[i], c[i + 1], d[i]]);
        tris.push([c[i + 1], d[i + 1], d[i]]);
        // Top: fan from a[0] over the b row, then fan from b[n] over the a row.
        tris.push([a[0], b[i], b[i + 1]]);
        tris.push([b[n], a[i], a[i + 1]]);
    }
    // Short sides.
    tris.push([a[0], b[0], c[0]]);
    tris.push([b[0], d[0], c[0]]);
    tris.push([a[n], b[n], c[n]]);
    tris.push([b[n], d[n], c[n]]);
    // The fan from a[0] over the b row and the one from b[n] over the a row share the diagonal
    // a[0]-b[n]; drop the degenerate ones (a[0] a[0] .. and b[n] b[n] ..).
    tris.retain(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2]);
    let centre = [
        origin[0] + w / 2.0,
        origin[1] + l / 2.0,
        origin[2] + h / 2.0,
    ];
    outward(&pts, &mut tris, centre);
    RegionInput {
        name: "fanned box".into(),
        vertices: pts,
        boundary: tris,
        embedded: vec![],
        lines: Vec::new(),
    }
}

fn mesh_with(input: &RegionInput, method: Method) -> TetMeshOutput {
    let opts = TetMeshOptions {
        method,
        ..TetMeshOptions::default()
    };
    let out = mesh_region(input, &SizeField::default(), &opts).unwrap_or_else(|e| panic!("{e}"));
    verify(input, &out).expect("verify");
    out
}

fn volume(out: &TetMeshOutput) -> f64 {
    out.tets
        .iter()
        .map(|t| {
            let [a, b, c, d] = t.map(|i| out.nodes[i as usize]);
            geom::predicates::signed_volume(&a, &b, &c, &d)
        })
        .sum()
}

#[test]
fn a_top_made_of_needle_fans_is_recovered_through_holes_without_falling_back_to_the_front() {
    let input = box_with_fanned_top(12, 12.0, 3.0, 2.0, [0.0; 3]);
    let out = mesh_with(&input, Method::Delaunay);
    assert!(
        out.stats.recovered_faces > 0,
        "the fans should not be Delaunay faces"
    );
    assert_eq!(out.stats.fallback, None);
    assert!((volume(&out) - 72.0).abs() < 1e-9 * 72.0);
}

#[test]
fn the_fanned_box_and_its_mirror_image_are_both_recovered_and_fill_the_same_volume() {
    let input = box_with_fanned_top(12, 12.0, 3.0, 2.0, [0.0; 3]);
    let mut mirror = input.clone();
    for p in &mut mirror.vertices {
        p[2] = -p[2];
    }
    for t in &mut mirror.boundary {
        t.swap(1, 2);
    }
    let a = mesh_with(&input, Method::Delaunay);
    let b = mesh_with(&mirror, Method::Delaunay);
    // The regular strips are cospherical, so which diagonals the Delaunay tetrahedralization
    // picks there depends on the insertion order: the counts may differ by a few, not the result.
    for m in [&a, &b] {
        assert!(m.stats.recovered_faces > 0);
        assert_eq!(m.stats.fallback, None);
    }
    assert!((volume(&a) - volume(&b)).abs() < 1e-9 * volume(&a));
}

#[test]
fn the_fanned_box_at_utm_coordinates_is_recovered_too() {
    let input = box_with_fanned_top(12, 1200.0, 300.0, 200.0, [512_345.25, 7_003_125.5, -1500.0]);
    let out = mesh_with(&input, Method::Delaunay);
    assert!(out.stats.recovered_faces > 0);
    assert_eq!(out.stats.fallback, None);
}

#[test]
fn delaunay_and_front_meshes_of_the_fanned_box_have_comparable_quality() {
    let input = box_with_fanned_top(16, 16.0, 4.0, 3.0, [0.0; 3]);
    let d = mesh_with(&input, Method::Delaunay);
    let f = mesh_with(&input, Method::Front);
    eprintln!("delaunay {:?}\nfront {:?}", d.stats, f.stats);
    assert!(d.stats.recovered_faces > 0 && d.stats.fallback.is_none());
    // Both fill the box (`verify` checked each against the enclosed volume); the Delaunay mesh,
    // whose needle top went through a hole meshed by the front, must be about as good.
    assert!((volume(&d) - volume(&f)).abs() < 1e-9 * volume(&f));
    assert!(
        (d.stats.avg_mean_ratio - f.stats.avg_mean_ratio).abs() < 0.1,
        "averages {} and {}",
        d.stats.avg_mean_ratio,
        f.stats.avg_mean_ratio
    );
    assert!(d.stats.min_mean_ratio >= 0.5 * f.stats.min_mean_ratio);
}

/// A cube of side `s` with `n` squares per side edge, two triangles per square, and a dangling
/// rectangle inside it with `m` columns, triangulated as two needle fans (not Delaunay either).
fn cube_with_fanned_fault(n: u32, s: f64, m: usize) -> RegionInput {
    let (mut pts, tris) = test_support::shapes::gridded_cube(n, s);
    // The fault: the rectangle x in [0.2 s, 0.8 s], y = 0.5 s, z in [0.3 s, 0.6 s] (tips inside).
    let mut row = |z: f64| {
        (0..=m)
            .map(|i| {
                pts.push([s * (0.2 + 0.6 * i as f64 / m as f64), 0.5 * s, z * s]);
                (pts.len() - 1) as u32
            })
            .collect::<Vec<u32>>()
    };
    let lo = row(0.3);
    let hi = row(0.6);
    let mut embedded = Vec::new();
    for i in 0..m {
        embedded.push([lo[0], hi[i], hi[i + 1]]);
        if i > 0 || m == 1 {
            embedded.push([hi[m], lo[i], lo[i + 1]]);
        }
    }
    embedded.push([hi[m], lo[0], lo[1]]);
    embedded.sort_unstable();
    embedded.dedup();
    RegionInput {
        name: "cube with fanned fault".into(),
        vertices: pts,
        boundary: tris,
        embedded,
        lines: Vec::new(),
    }
}

#[test]
fn a_dangling_fault_of_needles_is_recovered_and_keeps_a_tet_on_each_side() {
    let input = cube_with_fanned_fault(6, 60.0, 8);
    let out = mesh_with(&input, Method::Delaunay);
    assert_eq!(out.stats.fallback, None);
    assert!(
        out.stats.recovered_faces > 0,
        "the fault's needles should not be Delaunay faces"
    );
    // `verify` (above) has checked each embedded triangle is a face on both sides; the interior
    // was refined around it, so nodes were added off the fault.
    assert!(out.stats.new_nodes > 0);
}

/// The cube `[0, s]³` (two triangles a side), shifted to `origin`, and inside it a dangling
/// fault given as a chequerboard: on a `k × k` grid in a plane dipping 60°, the lower left half
/// of every cell, so that the triangles touch only at their corners and every gap between them
/// is a cell's other half (a thresholded slip map, or a fault stick export).
fn cube_with_chequerboard_fault(s: f64, k: usize, origin: P) -> RegionInput {
    let (mut pts, tris) = test_support::shapes::cuboid([0.0; 3], [s; 3]);
    let (cos, sin) = (60f64.to_radians().cos(), 60f64.to_radians().sin());
    let base = pts.len();
    for i in 0..=k {
        for j in 0..=k {
            let (u, v) = (i as f64 / k as f64 - 0.5, j as f64 / k as f64 - 0.5);
            let (u, v) = (0.6 * s * u, 0.6 * s * v);
            pts.push([0.5 * s + v * cos, 0.5 * s + u, 0.5 * s + v * sin]);
        }
    }
    let at = |i: usize, j: usize| (base + i * (k + 1) + j) as u32;
    let embedded = (0..k)
        .flat_map(|i| (0..k).map(move |j| [at(i, j), at(i + 1, j), at(i, j + 1)]))
        .collect();
    for p in &mut pts {
        for c in 0..3 {
            p[c] += origin[c];
        }
    }
    RegionInput {
        name: "cube with chequerboard fault".into(),
        vertices: pts,
        boundary: tris,
        embedded,
        lines: Vec::new(),
    }
}

#[test]
fn a_chequerboard_fault_whose_diagonals_delaunay_chose_the_other_way_is_recovered_by_flips() {
    // The grid's cells are cocircular: the Delaunay tetrahedralization splits about half of them
    // along the other diagonal, through a gap. Flipping that diagonal recovers each such
    // triangle; the hundreds that were missing made the recovery give way to the front, which
    // failed on this cube (and on the example's overburden with such a fault in it).
    for origin in [[0.0; 3], [512_345.25, 7_003_125.5, -1500.0]] {
        let input = cube_with_chequerboard_fault(800.0, 40, origin);
        let cube = RegionInput {
            embedded: Vec::new(),
            ..input.clone()
        };
        let out = mesh_with(&input, Method::Delaunay);
        assert_eq!(out.stats.fallback, None, "at {origin:?}");
        // The cube's own sides are no Delaunay faces in places: the fault adds next to none.
        let alone = mesh_with(&cube, Method::Delaunay).stats.recovered_faces;
        assert!(
            out.stats.recovered_faces <= alone + 16,
            "{} triangles went through holes at {origin:?}, {alone} without the fault",
            out.stats.recovered_faces
        );
    }
}

#[test]
fn refinement_never_dissolves_a_dangling_fault_whose_tip_it_goes_round() {
    // A fine boundary makes the refinement insert many points around the fault's tips, where a
    // cavity could wrap round the tip edge and swallow both sides of a fault triangle.
    let input = cube_with_fanned_fault(6, 60.0, 40);
    let out = mesh_with(&input, Method::Delaunay);
    assert_eq!(out.stats.fallback, None);
    assert!(
        out.stats.new_nodes > 50,
        "{} new nodes",
        out.stats.new_nodes
    );
}

#[test]
fn the_delaunay_method_is_deterministic() {
    let input = cube_with_fanned_fault(6, 60.0, 8);
    let a = mesh_with(&input, Method::Delaunay);
    let b = mesh_with(&input, Method::Delaunay);
    assert_eq!(a.nodes, b.nodes);
    assert_eq!(a.tets, b.tets);
}

#[test]
fn the_worst_tets_of_a_thin_layer_meshed_by_gmsh_are_raised_by_flips_up_to_0_8() {
    // Gmsh's L1 boundary of the peer model's 35 m reservoir (west block) at 100 m sizes: almost
    // every node is on the boundary. With flips only below 0.5, as in thick regions, its worst
    // tet had a mean ratio of 0.375; flips and contractions up to 0.8 raise it to 0.43.
    let Some(path) = paths::shared("data/peer-boundaries/region_L1_reservoir_W.off") else {
        return;
    };
    let bytes = std::fs::read(&path).expect("read");
    let b =
        geom::mesh::read::read_by_extension(&path.display().to_string(), &bytes).expect("reads");
    let mut input = RegionInput {
        name: "L1 reservoir_W".into(),
        vertices: b.vertices,
        boundary: b.triangles,
        embedded: vec![],
        lines: Vec::new(),
    };
    let o = input.vertices[0];
    let vol: f64 = input
        .boundary
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| input.vertices[i as usize]);
            geom::predicates::signed_volume(&o, &a, &b, &c)
        })
        .sum();
    if vol < 0.0 {
        input.boundary.iter_mut().for_each(|t| t.swap(1, 2));
    }
    let out = mesh_with(&input, Method::Delaunay);
    assert!(out.stats.min_mean_ratio >= 0.4, "{:?}", out.stats);
    assert!(out.stats.min_dihedral_deg >= 15.0, "{:?}", out.stats);
}

/// A box `2 half` wide round a flattened ellipsoid (semi-axes `axes`) faceted coarsely in `rings`
/// rows of `sectors` quads, both centred at `origin`: the host of a lens, with the lens as an
/// inner shell. The facets by the lens's rim are long and low, so the boundary points alone leave
/// many of them out of the Delaunay tetrahedralization.
fn host_of_a_lens(origin: P, half: P, axes: P, (rings, sectors): (u32, u32)) -> (RegionInput, f64) {
    use std::f64::consts::PI;
    let mut pts: Vec<P> = Vec::new();
    let mut boundary: Vec<[u32; 3]> = Vec::new();
    let lo = [0, 1, 2].map(|k| origin[k] - half[k]);
    let hi = [0, 1, 2].map(|k| origin[k] + half[k]);
    let (corners, outer) = test_support::shapes::cuboid(lo, hi);
    pts.extend(corners);
    boundary.extend(outer);
    let top = pts.len() as u32;
    pts.push([origin[0], origin[1], origin[2] + axes[2]]);
    let ring0 = pts.len() as u32;
    for r in 1..rings {
        let t = PI * f64::from(r) / f64::from(rings);
        for s in 0..sectors {
            let a = 2.0 * PI * f64::from(s) / f64::from(sectors);
            pts.push([
                origin[0] + axes[0] * t.sin() * a.cos(),
                origin[1] + axes[1] * t.sin() * a.sin(),
                origin[2] + axes[2] * t.cos(),
            ]);
        }
    }
    let bottom = pts.len() as u32;
    pts.push([origin[0], origin[1], origin[2] - axes[2]]);
    let at = |r: u32, s: u32| ring0 + (r - 1) * sectors + s % sectors;
    let mut lens = Vec::new();
    for s in 0..sectors {
        lens.push([top, at(1, s), at(1, s + 1)]);
        lens.push([bottom, at(rings - 1, s + 1), at(rings - 1, s)]);
        for r in 1..rings - 1 {
            lens.push([at(r, s), at(r + 1, s), at(r + 1, s + 1)]);
            lens.push([at(r, s), at(r + 1, s + 1), at(r, s + 1)]);
        }
    }
    // The lens's triangles face into it: away from the host.
    outward(&pts, &mut lens, origin);
    let mut lens_volume = 0.0;
    for t in &mut lens {
        let [a, b, c] = t.map(|i| pts[i as usize]);
        lens_volume += geom::predicates::signed_volume(&origin, &a, &b, &c);
        t.swap(1, 2);
    }
    boundary.extend(lens);
    let box_volume = 8.0 * half[0] * half[1] * half[2];
    let input = RegionInput {
        name: "host".into(),
        vertices: pts,
        boundary,
        embedded: Vec::new(),
        lines: Vec::new(),
    };
    (input, box_volume - lens_volume)
}

#[test]
fn a_lens_rim_of_long_low_facets_is_recovered_by_flips_rather_than_holes() {
    // The same lens in boxes of four sizes. In the box 3 km wide the front cannot fill the holes
    // by the rim however far they are widened: they are filled by their own Delaunay meshes and
    // by cones from their kernels.
    let origin = [502_100.0, 7_001_900.0, -1000.0];
    for half in [
        [1200.0, 1000.0, 400.0],
        [1500.0, 1200.0, 500.0],
        [1500.0, 1500.0, 500.0],
        [2000.0, 2000.0, 600.0],
    ] {
        let (input, expected) = host_of_a_lens(origin, half, [900.0, 600.0, 150.0], (14, 40));
        let out = mesh_with(&input, Method::Delaunay);
        assert_eq!(out.stats.fallback, None, "box {half:?}");
        assert!(
            out.stats.flipped_faces > 10 * out.stats.recovered_faces,
            "box {half:?}: flips {} against holes {}",
            out.stats.flipped_faces,
            out.stats.recovered_faces
        );
        assert!((volume(&out) - expected).abs() < 1e-9 * expected);
    }
}

#[test]
fn holes_whose_front_gets_stuck_are_widened_until_it_fills_them() {
    // The lens's facets moved by a few per cent: the holes flips leave by the rim are ones the
    // front gets stuck in; widened round each stuck place, they are filled, and the region keeps
    // its Delaunay mesh instead of falling back to the front.
    let origin = [502_100.0, 7_001_900.0, -1000.0];
    let axes = [900.0, 600.0, 150.0];
    for seed in 0..4u64 {
        let (mut input, expected) = host_of_a_lens(origin, [1200.0, 1000.0, 400.0], axes, (14, 40));
        let mut x = seed.wrapping_mul(2_654_435_761).wrapping_add(12_345);
        for p in input.vertices.iter_mut().skip(8) {
            for k in 0..3 {
                x = x
                    .wrapping_mul(6_364_136_223_846_793_005)
                    .wrapping_add(1_442_695_040_888_963_407);
                let u = (x >> 11) as f64 / (1u64 << 53) as f64;
                p[k] += (u - 0.5) * 0.06 * axes[k] / 14.0;
            }
        }
        // The box's corners stay put; the lens's volume changes with its points, the box's not.
        let out = mesh_with(&input, Method::Delaunay);
        assert_eq!(out.stats.fallback, None, "seed {seed}");
        assert!(
            out.stats.recovered_faces > 0,
            "seed {seed}: no hole to widen"
        );
        let box_volume = 8.0 * 1200.0 * 1000.0 * 400.0;
        assert!(
            volume(&out) < box_volume && volume(&out) > expected * 0.9,
            "seed {seed}"
        );
    }
}
