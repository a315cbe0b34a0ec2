//! The sharpest angle a region's boundary leaves its tets. Where the mesh's surface triangles
//! (region boundaries, embedded faults) meet along an edge, the tets of a region between two
//! triangles that are consecutive round that edge fill the angle between them exactly, so one of
//! them has a dihedral angle at the edge no larger than it. The smallest such angle over a
//! region's edges therefore bounds the region's smallest dihedral angle from above, whatever the
//! mesher does: a horizon onlapping another at 1° leaves 1° where they meet, and a fault meeting
//! a horizon at 20° leaves 20°. Table 2 gives it beside the minimum, so that a region below the
//! quality bars says whether its boundary allows more.
//!
//! Measures, not decisions: plain floating point. An edge with one triangle (a free border of a
//! fault) bounds nothing, nor does a node out of range or not finite (an inconsistent mesh is
//! measured, never a panic). Edges are found in a sorted list, not a hash map, and of equal
//! angles the place first in coordinate order is kept, so the result is the same for any
//! thread count.

use std::f64::consts::TAU;

use super::measures::TET_EDGES;
use super::node;
use geom::mesh::VolumeMesh;
use geom::predicates::{cross, dot, sub};

/// The sharpest angle (degrees) round an edge of a region's surface triangles that its tets
/// fill, and the midpoint of that edge.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bound {
    pub deg: f64,
    pub at: [f64; 3],
}

/// Per region (index order), the sharpest angle its surface triangles leave its tets, or `None`
/// for a region whose tets touch no edge where two surface triangles meet. Tets are measured in
/// parallel chunks; the sharpest is kept by angle, then place, so any split gives the same.
pub fn dihedral_bounds(mesh: &VolumeMesh) -> Vec<Option<Bound>> {
    use rayon::prelude::*;
    let fans = Fans::new(mesh);
    let none = || vec![None; mesh.regions.len()];
    (mesh
        .tets
        .par_chunks(CHUNK)
        .zip(mesh.tet_region.par_chunks(CHUNK)))
    .map(|(tets, regions)| {
        let mut best = none();
        for (tet, &region) in tets.iter().zip(regions) {
            if let Some(slot) = best.get_mut(region as usize) {
                for b in tet_bounds(mesh, &fans, tet) {
                    keep_sharper(slot, b);
                }
            }
        }
        best
    })
    .reduce(none, |mut a, b| {
        for (slot, b) in a.iter_mut().zip(b) {
            if let Some(b) = b {
                keep_sharper(slot, b);
            }
        }
        a
    })
}

/// Tets per parallel task.
const CHUNK: usize = 16384;

/// The angles round the edges of `tet` where two or more surface triangles meet.
fn tet_bounds<'a>(
    mesh: &'a VolumeMesh,
    fans: &'a Fans,
    tet: &'a [u32; 4],
) -> impl Iterator<Item = Bound> + 'a {
    TET_EDGES.iter().filter_map(move |&(i, j, k, l)| {
        let (a, b) = (tet[i], tet[j]);
        let deg = sector_deg(mesh, [a, b], fans.thirds(a, b)?, [tet[k], tet[l]])?;
        if !deg.is_finite() {
            return None;
        }
        let (p, q) = (node(mesh, a), node(mesh, b));
        let at = [0, 1, 2].map(|m| 0.5 * (p[m] + q[m]));
        Some(Bound { deg, at })
    })
}

/// Puts `b` in `slot` when it is sharper (or as sharp, at a place first in coordinate order).
pub(super) fn keep_sharper(slot: &mut Option<Bound>, b: Bound) {
    let sharper = |s: &Bound| {
        b.deg.total_cmp(&s.deg).then_with(|| {
            (b.at.iter().zip(&s.at)).fold(std::cmp::Ordering::Equal, |o, (x, y)| {
                o.then(x.total_cmp(y))
            })
        })
    };
    if slot.as_ref().is_none_or(|s| sharper(s).is_lt()) {
        *slot = Some(b);
    }
}

/// The surface triangles round each edge: (lower node, higher node, third node), sorted.
struct Fans {
    list: Vec<(u32, u32, u32)>,
    on_surface: Vec<bool>,
}

impl Fans {
    fn new(mesh: &VolumeMesh) -> Fans {
        let mut on_surface = vec![false; mesh.nodes.len()];
        let mut list = Vec::with_capacity(3 * mesh.triangles.len());
        for t in &mesh.triangles {
            for (a, b, c) in [(t[0], t[1], t[2]), (t[1], t[2], t[0]), (t[2], t[0], t[1])] {
                list.push((a.min(b), a.max(b), c));
            }
            for &v in t {
                if let Some(s) = on_surface.get_mut(v as usize) {
                    *s = true;
                }
            }
        }
        list.sort_unstable();
        // A triangle listed twice (a fault's two sides) is one face round the edge.
        list.dedup();
        Fans { list, on_surface }
    }

    /// The third nodes of the surface triangles on edge `ab`, when there are two or more.
    fn thirds(&self, a: u32, b: u32) -> Option<&[(u32, u32, u32)]> {
        let on = |v: u32| self.on_surface.get(v as usize).copied().unwrap_or(false);
        if !on(a) || !on(b) {
            return None;
        }
        let key = (a.min(b), a.max(b));
        let lo = self.list.partition_point(|e| (e.0, e.1) < key);
        let hi = lo + self.list[lo..].partition_point(|e| (e.0, e.1) == key);
        (hi - lo >= 2).then(|| &self.list[lo..hi])
    }
}

/// The angle (degrees) between the two surface triangles round edge `ab` (third nodes `thirds`)
/// that enclose the tet whose other corners are `kl`: the gap, round the edge, that holds the
/// middle of the tet's own angle there. `None` for a degenerate edge.
fn sector_deg(
    mesh: &VolumeMesh,
    ab: [u32; 2],
    thirds: &[(u32, u32, u32)],
    kl: [u32; 2],
) -> Option<f64> {
    let a = node(mesh, ab[0]);
    let axis = sub(&node(mesh, ab[1]), &a);
    let len = dot(&axis, &axis).sqrt();
    if len.is_nan() || len <= 0.0 {
        return None;
    }
    let u = axis.map(|x| x / len);
    let across = |v: u32| {
        let w = sub(&node(mesh, v), &a);
        let s = dot(&w, &u);
        [w[0] - s * u[0], w[1] - s * u[1], w[2] - s * u[2]]
    };
    let e1 = unit(across(thirds[0].2))?;
    let e2 = cross(&u, &e1);
    let angle = |v: u32| {
        let w = across(v);
        dot(&w, &e2).atan2(dot(&w, &e1)).rem_euclid(TAU)
    };
    let mut fan: Vec<f64> = thirds.iter().map(|t| angle(t.2)).collect();
    fan.sort_by(f64::total_cmp);
    let (p, q) = (angle(kl[0]), angle(kl[1]));
    let d = (q - p).rem_euclid(TAU);
    let mid = if d <= TAU / 2.0 {
        p + d / 2.0
    } else {
        q + (TAU - d) / 2.0
    }
    .rem_euclid(TAU);
    // The gap starting at the last triangle at or before `mid` (cyclically).
    let i = fan.partition_point(|&x| x <= mid);
    let start = if i == 0 {
        fan[fan.len() - 1] - TAU
    } else {
        fan[i - 1]
    };
    let end = if i == fan.len() { fan[0] + TAU } else { fan[i] };
    Some((end - start).to_degrees())
}

fn unit(v: [f64; 3]) -> Option<[f64; 3]> {
    let n = dot(&v, &v).sqrt();
    (n > 0.0 && n.is_finite()).then(|| v.map(|x| x / n))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::quality::tet_min_dihedral_deg;
    use geom::mesh::{RegionGroup, SurfaceGroup, SurfaceKind};

    /// One region of `tets` over `nodes`, with `triangles` as its surface triangles.
    fn mesh(nodes: Vec<[f64; 3]>, tets: Vec<[u32; 4]>, triangles: Vec<[u32; 3]>) -> VolumeMesh {
        VolumeMesh {
            nodes,
            tet_region: vec![0; tets.len()],
            tets,
            regions: vec![RegionGroup {
                name: "r".into(),
                material: None,
                properties: Default::default(),
            }],
            triangle_group: vec![0; triangles.len()],
            triangles,
            surface_groups: vec![SurfaceGroup {
                name: "s".into(),
                kind: SurfaceKind::Other,
            }],
            ..Default::default()
        }
    }

    fn faces(t: [u32; 4]) -> Vec<[u32; 3]> {
        vec![
            [t[0], t[1], t[2]],
            [t[0], t[1], t[3]],
            [t[0], t[2], t[3]],
            [t[1], t[2], t[3]],
        ]
    }

    /// A flat tet: its apex 0.3 above the base's centroid, so it has a small dihedral angle.
    fn flat() -> (Vec<[f64; 3]>, [u32; 4]) {
        let nodes = vec![
            [0.0, 0.0, 0.0],
            [4.0, 0.0, 0.0],
            [0.0, 3.0, 0.0],
            [1.3, 1.0, 0.3],
        ];
        (nodes, [0, 1, 2, 3])
    }

    #[test]
    fn a_tet_whose_faces_are_all_surface_triangles_is_bounded_by_its_own_smallest_angle() {
        let (nodes, t) = flat();
        let own = tet_min_dihedral_deg(&nodes[0], &nodes[1], &nodes[2], &nodes[3]);
        let b = dihedral_bounds(&mesh(nodes, vec![t], faces(t)))[0].expect("a bound");
        assert!((b.deg - own).abs() < 1e-9, "{} against {own}", b.deg);
        assert!(b.deg < 15.0, "{}", b.deg);
    }

    #[test]
    fn a_region_with_one_surface_triangle_has_no_bound() {
        let (nodes, t) = flat();
        assert_eq!(
            dihedral_bounds(&mesh(nodes, vec![t], vec![[0, 1, 2]])),
            [None]
        );
    }

    #[test]
    fn an_embedded_triangle_splits_the_angle_round_its_edges_between_the_tets_on_its_sides() {
        // The flat tet mirrored below its base: the base is an embedded triangle, each tet's
        // angle at the base's edges is a sector of its own, and the bound is the flat one's.
        let (mut nodes, t) = flat();
        nodes.push([1.3, 1.0, -2.0]);
        let u = [0, 2, 1, 4];
        let mut triangles = faces(t);
        triangles.extend(faces(u).into_iter().filter(|f| f != &[0, 2, 1]));
        let own = tet_min_dihedral_deg(&nodes[0], &nodes[1], &nodes[2], &nodes[3]);
        let b = dihedral_bounds(&mesh(nodes, vec![t, u], triangles))[0].expect("a bound");
        assert!((b.deg - own).abs() < 1e-9, "{} against {own}", b.deg);
    }

    #[test]
    fn a_cube_of_six_tets_is_bounded_by_its_right_angles() {
        let nodes: Vec<[f64; 3]> = (0..8)
            .map(|i| [(i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64])
            .collect();
        // Six tets round the diagonal 0-7, through the paths 0 → 7 along the axes.
        let tets = vec![
            [0, 1, 3, 7],
            [0, 1, 5, 7],
            [0, 2, 3, 7],
            [0, 2, 6, 7],
            [0, 4, 5, 7],
            [0, 4, 6, 7],
        ];
        // The cube's faces, two triangles each, split through node 0 or node 7.
        let triangles = vec![
            [0, 1, 3],
            [0, 3, 2],
            [0, 1, 5],
            [0, 5, 4],
            [0, 2, 6],
            [0, 6, 4],
            [7, 3, 1],
            [7, 1, 5],
            [7, 3, 2],
            [7, 2, 6],
            [7, 5, 4],
            [7, 4, 6],
        ];
        let b = dihedral_bounds(&mesh(nodes, tets, triangles))[0].expect("a bound");
        assert!((b.deg - 90.0).abs() < 1e-9, "{}", b.deg);
    }

    #[test]
    fn a_tet_or_triangle_naming_a_node_out_of_range_bounds_nothing() {
        let (nodes, t) = flat();
        let mut triangles = faces(t);
        triangles.push([0, 1, 99]);
        let mut m = mesh(nodes, vec![t, [0, 1, 2, 77]], triangles);
        m.nodes[3] = [f64::NAN; 3];
        assert_eq!(dihedral_bounds(&m), [None]);
    }
}
