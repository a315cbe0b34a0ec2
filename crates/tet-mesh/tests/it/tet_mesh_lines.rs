//! Embedded line segments (well paths): each becomes a chain of tet edges on it, whatever its
//! shape (straight through a box, a deviated polyline ending inside, crossing a Delaunay face at
//! its midpoint, polylines sharing a vertex, grazing a fault), and a segment that crosses a
//! triangle or leaves the region is refused with its coordinates. Every mesh is checked here from
//! its tets alone, besides `verify`.

use std::collections::{BTreeMap, BTreeSet};
use std::time::Instant;

use geom::predicates::{Orientation, orient2d, signed_volume};
use tet_mesh::{
    Method, RegionInput, SizeField, TetMeshOptions, TetMeshOutput, mesh_region, verify,
};

type P = [f64; 3];

/// A box's boundary, each side split into `n` x `n` squares of two triangles (outward), vertices
/// shared through their lattice coordinates; more vertices (segment ends) may be added.
struct Boxed {
    lo: P,
    hi: P,
    n: i64,
    ids: BTreeMap<[i64; 3], u32>,
    vertices: Vec<P>,
    boundary: Vec<[u32; 3]>,
}

impl Boxed {
    fn new(lo: P, hi: P, n: i64) -> Boxed {
        let mut b = Boxed {
            lo,
            hi,
            n,
            ids: BTreeMap::new(),
            vertices: Vec::new(),
            boundary: Vec::new(),
        };
        for axis in 0..3 {
            let (u, w) = ((axis + 1) % 3, (axis + 2) % 3);
            for side in [0, n] {
                for i in 0..n {
                    for j in 0..n {
                        let mut q = |a: i64, c: i64| {
                            let mut l = [0; 3];
                            l[axis] = side;
                            l[u] = a;
                            l[w] = c;
                            b.lattice(l)
                        };
                        let (p00, p10, p11, p01) =
                            (q(i, j), q(i + 1, j), q(i + 1, j + 1), q(i, j + 1));
                        // The normal u x w points along +axis: reversed on the low side.
                        if side == n {
                            b.boundary.extend([[p00, p10, p11], [p00, p11, p01]]);
                        } else {
                            b.boundary.extend([[p00, p11, p10], [p00, p01, p11]]);
                        }
                    }
                }
            }
        }
        b
    }

    /// The boundary vertex at lattice coordinates `l` (0..=n on each axis).
    fn lattice(&mut self, l: [i64; 3]) -> u32 {
        if let Some(&i) = self.ids.get(&l) {
            return i;
        }
        let (lo, hi, n) = (self.lo, self.hi, self.n as f64);
        let p = [0, 1, 2].map(|k| lo[k] + (hi[k] - lo[k]) * l[k] as f64 / n);
        let i = self.point(p);
        self.ids.insert(l, i);
        i
    }

    /// A new vertex at `p`.
    fn point(&mut self, p: P) -> u32 {
        self.vertices.push(p);
        (self.vertices.len() - 1) as u32
    }

    fn volume(&self) -> f64 {
        (0..3).map(|k| self.hi[k] - self.lo[k]).product()
    }

    fn input(self, name: &str, embedded: Vec<[u32; 3]>, lines: Vec<[u32; 2]>) -> RegionInput {
        RegionInput {
            name: name.into(),
            vertices: self.vertices,
            boundary: self.boundary,
            embedded,
            lines,
        }
    }
}

/// A polyline through the given vertices, as segments.
fn polyline(vs: &[u32]) -> Vec<[u32; 2]> {
    vs.windows(2).map(|w| [w[0], w[1]]).collect()
}

/// Whether `p` lies on the segment `ab`, to within 1e-9 of its length (float, independent of
/// the mesher's exact test).
fn near_segment(a: &P, b: &P, p: &P) -> bool {
    let d = [0, 1, 2].map(|k| b[k] - a[k]);
    let l2: f64 = d.iter().map(|x| x * x).sum();
    let t = (0..3).map(|k| (p[k] - a[k]) * d[k]).sum::<f64>() / l2;
    let q = [0, 1, 2].map(|k| a[k] + t * d[k]);
    let e: f64 = (0..3).map(|k| (p[k] - q[k]).powi(2)).sum::<f64>().sqrt();
    (0.0..=1.0).contains(&t) && e <= 1e-9 * l2.sqrt()
}

/// Exactly on the line `ab`: the three coordinate projections of `a, b, p` are flat.
fn exactly_collinear(a: &P, b: &P, p: &P) -> bool {
    [(1, 2), (2, 0), (0, 1)]
        .iter()
        .all(|&(i, j)| orient2d(&[a[i], a[j]], &[b[i], b[j]], &[p[i], p[j]]) == Orientation::Zero)
}

/// Meshes `input` (Delaunay), checks it with `verify` and from its tets alone: every segment is
/// a chain of tet edges from its first vertex to its second through nodes on it, the tets fill
/// `volume`. Prints the figures; returns the mesh.
fn mesh_and_check(input: &RegionInput, volume: f64) -> TetMeshOutput {
    let t0 = Instant::now();
    let out = mesh_region(input, &SizeField::default(), &TetMeshOptions::default())
        .unwrap_or_else(|e| panic!("{e}"));
    let secs = t0.elapsed().as_secs_f64();
    verify(input, &out).expect("verify");
    let mut edges: BTreeSet<[u32; 2]> = BTreeSet::new();
    for t in &out.tets {
        for (i, j) in [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)] {
            edges.insert([t[i].min(t[j]), t[i].max(t[j])]);
        }
    }
    assert_eq!(out.lines.len(), input.lines.len());
    let mut exact = 0;
    let mut inner = 0;
    for (k, (chain, &[u, v])) in out.lines.iter().zip(&input.lines).enumerate() {
        assert_eq!((chain[0], chain[chain.len() - 1]), (u, v), "segment {k}");
        let (a, b) = (input.vertices[u as usize], input.vertices[v as usize]);
        for w in chain.windows(2) {
            assert!(
                edges.contains(&[w[0].min(w[1]), w[0].max(w[1])]),
                "segment {k}: {w:?}"
            );
        }
        for &x in &chain[1..chain.len() - 1] {
            let p = out.nodes[x as usize];
            assert!(near_segment(&a, &b, &p), "segment {k}: node {x} at {p:?}");
            exact += exactly_collinear(&a, &b, &p) as usize;
            inner += 1;
        }
    }
    let total: f64 = out
        .tets
        .iter()
        .map(|t| {
            let [a, b, c, d] = t.map(|i| out.nodes[i as usize]);
            signed_volume(&a, &b, &c, &d)
        })
        .sum();
    assert!(
        (total - volume).abs() <= 1e-9 * volume,
        "{total} vs {volume}"
    );
    let s = &out.stats;
    eprintln!(
        "{}: {} segments, {} tets, {} nodes on segments ({} split to recover, {} pieces by \
         flips, {} exactly collinear of {inner}), min dihedral {:.1}°, min mean ratio {:.3}, \
         {secs:.3}s",
        input.name,
        input.lines.len(),
        s.tets,
        s.line_nodes,
        s.line_splits,
        s.line_flips,
        exact,
        s.min_dihedral_deg,
        s.min_mean_ratio
    );
    assert!(s.min_dihedral_deg > 0.0);
    out
}

#[test]
fn a_vertical_well_through_a_box_from_top_to_bottom_becomes_a_chain_of_edges_exactly_on_it() {
    let mut b = Boxed::new([0.0; 3], [10.0, 10.0, 10.0], 4);
    let (top, bottom) = (b.lattice([2, 2, 4]), b.lattice([2, 2, 0]));
    let volume = b.volume();
    let input = b.input("vertical well", vec![], vec![[top, bottom]]);
    let out = mesh_and_check(&input, volume);
    let chain = &out.lines[0];
    // Divided to the boundary's size (2.5), every node exactly on the vertical line.
    assert!(chain.len() >= 4, "{chain:?}");
    for &x in chain {
        let p = out.nodes[x as usize];
        assert_eq!((p[0], p[1]), (5.0, 5.0));
    }
}

#[test]
fn a_deviated_well_of_twenty_segments_ending_inside_the_region_is_embedded() {
    let mut b = Boxed::new([0.0; 3], [100.0, 100.0, 100.0], 8);
    let mut path = vec![b.lattice([4, 4, 8])];
    let mut p = [50.0, 50.0, 100.0];
    for i in 1..=20 {
        // Building up inclination along a fixed azimuth, 4.1 m a station.
        let (inc, azi) = ((0.06 * i as f64).min(1.0), 0.7f64);
        p = [
            p[0] + 4.1 * inc.sin() * azi.cos(),
            p[1] + 4.1 * inc.sin() * azi.sin(),
            p[2] - 4.1 * inc.cos(),
        ];
        path.push(b.point(p));
    }
    let volume = b.volume();
    let input = b.input("deviated well", vec![], polyline(&path));
    let out = mesh_and_check(&input, volume);
    assert_eq!(out.lines.len(), 20);
}

#[test]
fn a_segment_whose_midpoint_lies_on_a_delaunay_face_is_embedded() {
    // The triangle p1 p2 p3 (a polyline's vertices, in the plane z = 1) is a face of the
    // Delaunay tetrahedralization: spheres through it centred on (1, 1, 1 + s), |s| small, hold
    // no vertex, as u and v stand 3 away. The well from u to v crosses it at its midpoint
    // (1, 1, 1), exactly.
    let mut b = Boxed::new([-10.0; 3], [12.0; 3], 2);
    let ring = [[2.0, 0.5, 1.0], [1.0, 2.5, 1.0], [0.0, 0.5, 1.0]].map(|p| b.point(p));
    let (u, v) = (b.point([1.0, 1.0, -2.0]), b.point([1.0, 1.0, 4.0]));
    let volume = b.volume();
    let mut lines = vec![[u, v]];
    lines.extend(polyline(&ring));
    let input = b.input("midpoint on a face", vec![], lines);
    let out = mesh_and_check(&input, volume);
    let mid = out.lines[0]
        .iter()
        .any(|&x| out.nodes[x as usize] == [1.0, 1.0, 1.0]);
    eprintln!("a node at the midpoint: {mid}");
}

#[test]
fn two_polylines_sharing_an_end_vertex_meet_there_at_an_acute_angle_and_both_are_embedded() {
    let mut b = Boxed::new([0.0; 3], [40.0, 40.0, 40.0], 4);
    let top = b.lattice([2, 2, 4]);
    let junction = b.point([20.0, 20.0, 22.5]);
    let main = [top, b.point([20.5, 19.75, 31.0]), junction];
    // Two branches leaving the junction 20° apart.
    let (s, c) = (10f64.to_radians().sin(), 10f64.to_radians().cos());
    let left = [
        junction,
        b.point([20.0 - 6.0 * s, 20.0, 22.5 - 6.0 * c]),
        b.point([20.0 - 15.0 * s, 20.0, 22.5 - 15.0 * c]),
    ];
    let right = [
        junction,
        b.point([20.0 + 6.0 * s, 20.0, 22.5 - 6.0 * c]),
        b.point([20.0 + 15.0 * s, 20.0, 22.5 - 15.0 * c]),
    ];
    let volume = b.volume();
    let mut lines = polyline(&main);
    lines.extend(polyline(&left));
    lines.extend(polyline(&right));
    let input = b.input("branches", vec![], lines);
    mesh_and_check(&input, volume);
}

/// The box [0, 10]^3 with a dangling square fault at z = 5 over [2, 8]^2 (two triangles).
fn box_with_fault() -> (Boxed, Vec<[u32; 3]>) {
    let mut b = Boxed::new([0.0; 3], [10.0; 3], 4);
    let q = [[2.0, 2.0], [8.0, 2.0], [8.0, 8.0], [2.0, 8.0]].map(|[x, y]| b.point([x, y, 5.0]));
    (b, vec![[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
}

#[test]
fn a_well_grazing_a_fault_a_millionth_of_the_box_above_it_is_embedded_without_touching_it() {
    let (mut b, fault) = box_with_fault();
    // Over the fault's inside, from one side to the other, 1e-5 (1e-6 of the box) above it.
    let (u, v) = (
        b.point([3.0, 1.0, 5.0 + 1e-5]),
        b.point([6.0, 9.0, 5.0 + 1e-5]),
    );
    let volume = b.volume();
    let input = b.input("grazing well", fault, vec![[u, v]]);
    let out = mesh_and_check(&input, volume);
    for &x in &out.lines[0] {
        assert!(out.nodes[x as usize][2] > 5.0);
    }
}

#[test]
fn a_well_crossing_a_fault_is_refused_naming_its_end_coordinates() {
    let (mut b, fault) = box_with_fault();
    let (u, v) = (b.point([5.0, 5.0, 8.0]), b.point([5.5, 4.5, 2.0]));
    let input = b.input("crossing well", fault, vec![[u, v]]);
    let e = mesh_region(&input, &SizeField::default(), &TetMeshOptions::default()).unwrap_err();
    assert!(e.message.contains("line segment 0"), "{e}");
    assert!(
        e.message.contains("[5.0, 5.0, 8.0] to [5.5, 4.5, 2.0]"),
        "{e}"
    );
    assert!(e.message.contains("meets embedded triangle"), "{e}");
    assert_eq!(e.at, Some([5.0, 5.0, 8.0]));
}

#[test]
fn a_well_partly_or_wholly_outside_the_region_is_refused() {
    let mut b = Boxed::new([0.0; 3], [10.0; 3], 2);
    let inner = b.point([5.0, 5.0, 5.0]);
    let (out1, out2) = (b.point([5.0, 5.0, 15.0]), b.point([12.0, 5.0, 15.0]));
    let partly = RegionInput {
        lines: vec![[inner, out1]],
        ..b.input("outside", vec![], vec![])
    };
    let e = mesh_region(&partly, &SizeField::default(), &TetMeshOptions::default()).unwrap_err();
    assert!(
        e.message.contains("[5.0, 5.0, 5.0] to [5.0, 5.0, 15.0]"),
        "{e}"
    );
    assert!(e.message.contains("meets boundary triangle"), "{e}");
    let wholly = RegionInput {
        lines: vec![[out1, out2]],
        ..partly.clone()
    };
    let e = mesh_region(&wholly, &SizeField::default(), &TetMeshOptions::default()).unwrap_err();
    assert!(e.message.contains("lies outside the region"), "{e}");
}

#[test]
fn a_well_across_the_notch_of_an_l_shaped_region_between_two_boundary_vertices_is_outside() {
    // An L: the box [0, 2] x [0, 2] x [0, 1] without the quarter [1, 2] x [1, 2]. Its boundary
    // from the unit cubes' faces that no other cube shares.
    let cells = [[0, 0, 0], [1, 0, 0], [0, 1, 0]];
    let mut ids: BTreeMap<[i64; 3], u32> = BTreeMap::new();
    let mut vertices: Vec<P> = Vec::new();
    let mut id = |l: [i64; 3], vertices: &mut Vec<P>| {
        *ids.entry(l).or_insert_with(|| {
            vertices.push(l.map(|c| c as f64));
            (vertices.len() - 1) as u32
        })
    };
    let mut boundary = Vec::new();
    for c in &cells {
        for axis in 0..3 {
            for dir in [0i64, 1] {
                let mut nb = *c;
                nb[axis] += 2 * dir - 1;
                if cells.contains(&nb) {
                    continue;
                }
                let (u, w) = ((axis + 1) % 3, (axis + 2) % 3);
                let corner = |a: i64, b: i64| {
                    let mut l = *c;
                    l[axis] += dir;
                    l[u] += a;
                    l[w] += b;
                    l
                };
                let q = [corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1)]
                    .map(|l| id(l, &mut vertices));
                if dir == 1 {
                    boundary.extend([[q[0], q[1], q[2]], [q[0], q[2], q[3]]]);
                } else {
                    boundary.extend([[q[0], q[2], q[1]], [q[0], q[3], q[2]]]);
                }
            }
        }
    }
    // From the corner (2, 1, 0) to the corner (1, 2, 1): across the missing quarter.
    let (a, c) = (ids[&[2, 1, 0]], ids[&[1, 2, 1]]);
    let input = RegionInput {
        name: "L".into(),
        vertices,
        boundary,
        embedded: vec![],
        lines: vec![[a, c]],
    };
    let e = mesh_region(&input, &SizeField::default(), &TetMeshOptions::default()).unwrap_err();
    assert!(e.message.contains("lies outside the region"), "{e}");
    // From the corner (2, 0, 0) to the corner (0, 1, 1), through the L's long arm: inside.
    let inside = RegionInput {
        lines: vec![[ids[&[2, 0, 0]], ids[&[0, 1, 1]]]],
        ..input
    };
    let out = mesh_and_check(&inside, 3.0);
    assert_eq!(out.lines.len(), 1);
}

#[test]
fn the_advancing_front_refuses_a_well_saying_it_cannot_be_embedded() {
    let mut b = Boxed::new([0.0; 3], [10.0; 3], 2);
    let (u, v) = (b.point([4.0, 4.0, 4.0]), b.point([6.0, 6.0, 6.0]));
    let input = b.input("front", vec![], vec![[u, v]]);
    let opts = TetMeshOptions {
        method: Method::Front,
        ..TetMeshOptions::default()
    };
    let e = mesh_region(&input, &SizeField::default(), &opts).unwrap_err();
    assert_eq!(e.region, "front");
    assert!(
        e.message
            .contains("the well cannot be embedded in this region"),
        "{e}"
    );
}

#[test]
fn a_region_without_wells_meshes_exactly_as_before_and_reports_no_chains() {
    let b = Boxed::new([0.0; 3], [10.0; 3], 3);
    let input = b.input("plain", vec![], vec![]);
    let out = mesh_region(&input, &SizeField::default(), &TetMeshOptions::default()).unwrap();
    assert!(out.lines.is_empty());
    assert_eq!((out.stats.line_nodes, out.stats.line_splits), (0, 0));
}

/// A deterministic stream of numbers in [0, 1) (a linear congruential generator).
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

#[test]
fn forty_wells_stacked_close_and_crossing_in_plan_view_are_all_embedded() {
    // Each well lies in its own horizontal plane, 0.2 apart, in a box whose sides are squares
    // of 5: the Delaunay tetrahedralization of their ends misses most of them.
    let mut b = Boxed::new([0.0; 3], [10.0; 3], 2);
    let mut rng = Lcg(7);
    let mut lines = Vec::new();
    for i in 0..40 {
        let z = 1.0 + 0.2 * i as f64;
        let mut end = || [1.0 + 8.0 * rng.next(), 1.0 + 8.0 * rng.next(), z];
        let (p, q) = (end(), end());
        lines.push([b.point(p), b.point(q)]);
    }
    let volume = b.volume();
    let input = b.input("stacked wells", vec![], lines);
    let out = mesh_and_check(&input, volume);
    assert!(
        out.stats.line_splits + out.stats.line_flips > 0,
        "{:?}",
        out.stats
    );
}

#[test]
fn a_well_starting_inside_a_boundary_recovery_hole_is_inserted_again_and_embedded() {
    // The needle fans of this box's top are no Delaunay faces: the tets under them go to holes
    // the front fills with the boundary's vertices only. The well's upper end sits in there.
    let mut input = crate::tet_mesh_delaunay::box_with_fanned_top(12, 12.0, 3.0, 2.0, [0.0; 3]);
    let n = input.vertices.len() as u32;
    input.vertices.extend([[4.3, 1.8, 1.77], [4.3, 1.8, 0.3]]);
    input.lines = vec![[n, n + 1]];
    let out = mesh_and_check(&input, 72.0);
    assert!(out.stats.recovered_faces > 0);
}
