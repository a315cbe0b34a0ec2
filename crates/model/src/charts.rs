//! Charts: cutting a patch that cannot be flattened onto one plane into pieces that can.
//!
//! The surface mesher flattens each patch onto the plane of its mean normal. That needs every
//! triangle to face that plane (normal within 90° of the mean, with a margin for the metric's
//! stretch); a tube, a closed lens, a salt wall, a cup or a dome down to its flanks does not.
//! Such a patch is cut along seams into charts, and each chart is meshed on its own; the seams
//! become curves that the charts' meshes share, so the FE mesh of the patch is conforming.
//!
//! Decisions and why:
//! - A patch is kept whole when every triangle faces within `Tolerances::chart_angle_deg` of the
//!   patch's area-weighted mean normal: every horizon, fault and box side of an ordinary model,
//!   so models that flatten are not touched.
//! - Otherwise each triangle is labelled with the axis direction (±x, ±y, ±z) it faces most
//!   (within 54.7° of it, whatever the surface): one method for every topology, spheres, tubes,
//!   cups and tori alike, with no global parametrization. The labels are then smoothed (a
//!   triangle takes the label that two of its neighbours share, when it faces within the chart
//!   angle of that axis) so seams do not zigzag, and each connected piece of one label that
//!   faces within the chart angle of a neighbouring piece's axis is merged into it, smallest
//!   first, so that noise in the normals leaves no islands.
//! - Labels are computed once on the whole imported surface, not per patch: where a curve
//!   crosses a seam, the charts of the patches on both sides then end at the same point of it
//!   (per patch, seam ends a metre apart made metre-long curve pieces and elements).
//! - Where a curve clips a chart near its tip, the patch keeps a wedge of it that meets the
//!   curve along a few metres between long seams (`merge_wedges` gives it to the chart beside
//!   it, per patch: that only removes seam ends).
//! - A chart never touches itself at a vertex only (`unpinch` gives the smaller fans there to a
//!   neighbouring chart): its boundary loops must not touch. Nor does a seam cut off a lobe of
//!   it behind a sliver of a neck (`widen_necks` gives the lobe to the chart across the seam):
//!   its surface mesh would hold a needle across the neck. Nor does its border cross itself on
//!   the chart's own plane (`untwist` moves the triangles on the crossing to a chart beside
//!   them): it would be flattened by a Tutte embedding that squeezes it, and folds. Giving a
//!   pinched fan away after untwisting can double a border back again (on the smoothed channel's
//!   underside: 37 triangles moved, then one fan made a crossing, and its 13,335 triangles
//!   folded under a Tutte embedding), so the two alternate until untwisting moves nothing, at
//!   most [`UNTWIST_PASSES`] times; and a moved triangle takes along the few triangles that
//!   would leave its new chart touching itself at its corner (`gaps`), else `unpinch` gives it
//!   back on every pass.
//! - Seams run along support edges: no point is constructed, and the triangles are the patch's
//!   own. Seam curves are not features, so the topology does not end curves at their kinks.
//! - Normals are those of the original (imported) triangles each split triangle lies in, as for
//!   creases: the slivers of splitting have no reliable normal of their own. Labels and merges
//!   are measures steering where seams go, not orientation decisions; ties go to the lower axis
//!   and the lower triangle index, so the result is the same on every machine.

mod gaps;
mod necks;
mod twists;
mod wedges;

use geom::TriMesh;
pub(crate) use geom::adjacency::{NONE, across_edges, stars};
use geom::predicates::{cross, dot, sub};
pub use necks::widen_necks;
pub use twists::untwist;
pub use wedges::merge_wedges;

/// The six axis directions, in label order.
const AXES: [[f64; 3]; 6] = [
    [1.0, 0.0, 0.0],
    [-1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, -1.0, 0.0],
    [0.0, 0.0, 1.0],
    [0.0, 0.0, -1.0],
];

/// Most alternations of `untwist` and `unpinch` on one patch. In the geology corpus the second
/// moves nothing (the channels' bodies and a lens of `two_lenses` move triangles in the first);
/// before a moved triangle took the gap it left along (`gaps`), the smoothed channel's body
/// moved one triangle to and fro on every pass.
pub const UNTWIST_PASSES: usize = 4;

/// Smoothing passes over the labels (each can only shorten seams).
const SMOOTHING_PASSES: usize = 4;

/// Whether a piece of surface (its triangles `mesh` and their unit `normals`, a zero vector where
/// a triangle has none) must be cut into charts: some triangle faces further than `max_deg` from
/// the area-weighted mean normal.
pub fn needs_charts(mesh: &TriMesh, normals: &[[f64; 3]], max_deg: f64) -> bool {
    !mesh.triangles.is_empty() && !faces_one_way(mesh, normals, max_deg.to_radians().cos())
}

/// The chart of every triangle of a whole surface (`mesh`, unit `normals`): an id shared by the
/// triangles of one chart (the smallest triangle index in it). Computed on the imported surface
/// rather than on each patch, so that where a curve crosses a seam, the charts on both sides
/// end at the same point of it.
pub fn chart_labels(mesh: &TriMesh, normals: &[[f64; 3]], max_deg: f64) -> Vec<u32> {
    let n = mesh.triangles.len();
    let cos_max = max_deg.to_radians().cos();
    let adj = neighbours(mesh);
    let fits = |t: usize, a: usize| dot(&normals[t], &AXES[a]) >= cos_max;
    let mut label: Vec<usize> = normals.iter().map(nearest_axis).collect();
    for _ in 0..SMOOTHING_PASSES {
        for t in 0..n {
            if let Some(a) = shared_label(&adj[t], &label)
                && a != label[t]
                && fits(t, a)
            {
                label[t] = a;
            }
        }
    }
    let mut pieces = Pieces::new(&adj, &label, normals, mesh);
    pieces.merge_compatible(&adj, cos_max);
    (0..n as u32).map(|t| pieces.root(t)).collect()
}

/// The connected groups of `mesh`'s triangles (across manifold edges) with equal `label`,
/// ascending within, ordered by their first triangle.
pub fn connected_groups(mesh: &TriMesh, label: impl Fn(u32) -> u32) -> Vec<Vec<u32>> {
    let n = mesh.triangles.len();
    let adj = neighbours(mesh);
    let mut group = vec![u32::MAX; n];
    let mut out: Vec<Vec<u32>> = Vec::new();
    for seed in 0..n as u32 {
        if group[seed as usize] != u32::MAX {
            continue;
        }
        let g = out.len() as u32;
        let mut members = vec![seed];
        group[seed as usize] = g;
        let mut k = 0;
        while k < members.len() {
            let t = members[k];
            k += 1;
            for &u in &adj[t as usize] {
                if group[u as usize] == u32::MAX && label(u) == label(t) {
                    group[u as usize] = g;
                    members.push(u);
                }
            }
        }
        members.sort_unstable();
        out.push(members);
    }
    out
}

/// Most rounds of [`unpinch`]: each moves whole fans, and a pinch it cannot remove is left to
/// the surface mesher to report.
const UNPINCH_ROUNDS: usize = 8;

/// Reassigns triangles so that no group of `mesh`'s triangles (`group` per triangle) meets
/// itself at a vertex only: around every vertex, the triangles of one group must form a single
/// fan (edge-connected through edges at that vertex), or the group's boundary would touch itself
/// there, which a chart's loops may not. Every fan but the largest (the first on ties) moves to
/// the group across its first edge at the vertex. Returns whether any pinch is left.
pub fn unpinch(mesh: &TriMesh, group: &mut [u32]) -> bool {
    let star = stars(mesh);
    for _ in 0..UNPINCH_ROUNDS {
        let mut moved = false;
        for (v, ts) in star.iter().enumerate() {
            moved |= unpinch_at(mesh, v as u32, ts, group);
        }
        if !moved {
            return false;
        }
    }
    true
}

/// [`unpinch`] at one vertex `v` with incident triangles `ts`: returns whether a fan moved.
fn unpinch_at(mesh: &TriMesh, v: u32, ts: &[u32], group: &mut [u32]) -> bool {
    // The other end of each edge at v, per incident triangle.
    let ends = |t: u32| {
        let tri = mesh.triangles[t as usize];
        let k = tri.iter().position(|&x| x == v).unwrap_or(0);
        [tri[(k + 1) % 3], tri[(k + 2) % 3]]
    };
    let touch = |a: u32, b: u32| ends(a).iter().any(|e| ends(b).contains(e));
    // Fans: components of same-group triangles through shared edges at v.
    let mut fan = vec![usize::MAX; ts.len()];
    let mut fans: Vec<Vec<usize>> = Vec::new();
    for i in 0..ts.len() {
        if fan[i] != usize::MAX {
            continue;
        }
        fan[i] = fans.len();
        let mut members = vec![i];
        let mut k = 0;
        while k < members.len() {
            let a = members[k];
            k += 1;
            for j in 0..ts.len() {
                if fan[j] == usize::MAX
                    && group[ts[j] as usize] == group[ts[a] as usize]
                    && touch(ts[a], ts[j])
                {
                    fan[j] = fan[i];
                    members.push(j);
                }
            }
        }
        fans.push(members);
    }
    let mut moved = false;
    for (f, members) in fans.iter().enumerate() {
        let g = group[ts[members[0]] as usize];
        let largest = fans
            .iter()
            .enumerate()
            .filter(|(_, m)| group[ts[m[0]] as usize] == g)
            .max_by(|a, b| a.1.len().cmp(&b.1.len()).then(b.0.cmp(&a.0)))
            .map(|(k, _)| k);
        if largest == Some(f) {
            continue;
        }
        let across = members.iter().find_map(|&a| {
            (0..ts.len()).find(|&j| group[ts[j] as usize] != g && touch(ts[a], ts[j]))
        });
        if let Some(j) = across {
            let to = group[ts[j] as usize];
            for &a in members {
                group[ts[a] as usize] = to;
            }
            moved = true;
        }
    }
    moved
}

/// Whether every triangle faces within the angle of `cos_max` of the area-weighted mean normal.
fn faces_one_way(mesh: &TriMesh, normals: &[[f64; 3]], cos_max: f64) -> bool {
    let mut mean = [0.0; 3];
    for (t, nt) in normals.iter().enumerate() {
        let a = area(mesh, t);
        for k in 0..3 {
            mean[k] += a * nt[k];
        }
    }
    let len = dot(&mean, &mean).sqrt();
    len > 0.0
        && normals
            .iter()
            .all(|nt| *nt == [0.0; 3] || dot(nt, &mean) >= cos_max * len)
}

fn area(mesh: &TriMesh, t: usize) -> f64 {
    let [a, b, c] = mesh.corners(t);
    let n = cross(&sub(b, a), &sub(c, a));
    0.5 * dot(&n, &n).sqrt()
}

/// The length of triangle `t`'s edge `k` (from corner `k` to corner `k + 1`).
fn edge_length(mesh: &TriMesh, t: u32, k: usize) -> f64 {
    let tri = mesh.triangles[t as usize];
    geom::predicates::dist(
        &mesh.vertices[tri[k] as usize],
        &mesh.vertices[tri[(k + 1) % 3] as usize],
    )
}

/// `sum += w * n`.
fn add(sum: &mut [f64; 3], n: &[f64; 3], w: f64) {
    for k in 0..3 {
        sum[k] += w * n[k];
    }
}

/// The axis a unit normal faces most (the lowest on ties; axis 0 for a zero normal).
fn nearest_axis(n: &[f64; 3]) -> usize {
    let mut best = 0;
    for (a, axis) in AXES.iter().enumerate().skip(1) {
        if dot(n, axis) > dot(n, &AXES[best]) {
            best = a;
        }
    }
    best
}

/// A label shared by at least two of the given neighbours (the lowest such, if several).
fn shared_label(adj: &[u32], label: &[usize]) -> Option<usize> {
    let mut count = [0u8; 6];
    for &u in adj {
        count[label[u as usize]] += 1;
    }
    (0..6).find(|&a| count[a] >= 2)
}

/// The triangles across each triangle's manifold edges (edges that exactly two triangles of the
/// patch share), ascending.
fn neighbours(mesh: &TriMesh) -> Vec<Vec<u32>> {
    across_edges(mesh)
        .into_iter()
        .map(|across| {
            let mut adj: Vec<u32> = across.into_iter().filter(|&u| u != NONE).collect();
            adj.sort_unstable();
            adj
        })
        .collect()
}

/// Connected pieces of one label, as a union-find over triangles with, per piece root, its axis,
/// its area and the smallest cosine of any of its triangles to each axis.
struct Pieces {
    up: Vec<u32>,
    axis: Vec<usize>,
    area: Vec<f64>,
    min_cos: Vec<[f64; 6]>,
    members: Vec<Vec<u32>>,
}

impl Pieces {
    fn new(adj: &[Vec<u32>], label: &[usize], normals: &[[f64; 3]], mesh: &TriMesh) -> Pieces {
        let n = label.len();
        let mut p = Pieces {
            up: (0..n as u32).collect(),
            axis: label.to_vec(),
            area: (0..n).map(|t| area(mesh, t)).collect(),
            min_cos: normals
                .iter()
                .map(|nt| AXES.map(|a| if *nt == [0.0; 3] { 1.0 } else { dot(nt, &a) }))
                .collect(),
            members: (0..n as u32).map(|t| vec![t]).collect(),
        };
        for t in 0..n {
            for &u in &adj[t] {
                if label[u as usize] == label[t] {
                    p.union(t as u32, u, label[t]);
                }
            }
        }
        p
    }

    fn root(&mut self, mut t: u32) -> u32 {
        while self.up[t as usize] != t {
            let g = self.up[self.up[t as usize] as usize];
            self.up[t as usize] = g;
            t = g;
        }
        t
    }

    /// Joins the pieces of `t` and `u` under the smaller root, which takes `axis`.
    fn union(&mut self, t: u32, u: u32, axis: usize) {
        let (a, b) = (self.root(t), self.root(u));
        if a == b {
            return;
        }
        let (keep, gone) = (a.min(b), a.max(b));
        self.up[gone as usize] = keep;
        self.axis[keep as usize] = axis;
        self.area[keep as usize] += self.area[gone as usize];
        let gone_cos = self.min_cos[gone as usize];
        for (k, c) in self.min_cos[keep as usize].iter_mut().enumerate() {
            *c = c.min(gone_cos[k]);
        }
        let moved = std::mem::take(&mut self.members[gone as usize]);
        self.members[keep as usize].extend(moved);
    }

    /// Merges each piece, smallest area first, into the neighbouring piece with the longest
    /// shared border among those whose axis it faces within the chart angle.
    fn merge_compatible(&mut self, adj: &[Vec<u32>], cos_max: f64) {
        let n = self.up.len() as u32;
        let mut order: Vec<u32> = (0..n).filter(|&t| self.root(t) == t).collect();
        order.sort_by(|&a, &b| {
            self.area[a as usize]
                .total_cmp(&self.area[b as usize])
                .then(a.cmp(&b))
        });
        for r in order {
            let r = self.root(r);
            let mut shared: Vec<(u32, u32)> = Vec::new();
            for &t in &self.members[r as usize].clone() {
                for &u in &adj[t as usize] {
                    let q = self.root(u);
                    if q != r {
                        shared.push((q, 1));
                    }
                }
            }
            shared.sort_unstable();
            let mut best: Option<(u32, u32)> = None;
            for run in shared.chunk_by(|x, y| x.0 == y.0) {
                let (q, len) = (run[0].0, run.len() as u32);
                let axis = self.axis[q as usize];
                if self.min_cos[r as usize][axis] >= cos_max && best.is_none_or(|b| len > b.1) {
                    best = Some((q, len));
                }
            }
            if let Some((q, _)) = best {
                let axis = self.axis[q as usize];
                self.union(r, q, axis);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A closed octahedron-like sphere: a UV sphere of `rings` × `segs` with two poles.
    fn sphere(rings: usize, segs: usize) -> TriMesh {
        use std::f64::consts::{PI, TAU};
        let mut v = vec![[0.0, 0.0, 1.0]];
        for i in 1..rings {
            let th = PI * i as f64 / rings as f64;
            for k in 0..segs {
                let ph = TAU * (k as f64 + 0.5 * (i % 2) as f64) / segs as f64;
                v.push([th.sin() * ph.cos(), th.sin() * ph.sin(), th.cos()]);
            }
        }
        v.push([0.0, 0.0, -1.0]);
        let ring = |i: usize, k: usize| (1 + (i - 1) * segs + k % segs) as u32;
        let south = v.len() as u32 - 1;
        let mut t = Vec::new();
        for k in 0..segs {
            t.push([0, ring(1, k), ring(1, k + 1)]);
            t.push([ring(rings - 1, k), south, ring(rings - 1, k + 1)]);
        }
        for i in 1..rings - 1 {
            for k in 0..segs {
                t.push([ring(i, k), ring(i + 1, k), ring(i + 1, k + 1)]);
                t.push([ring(i, k), ring(i + 1, k + 1), ring(i, k + 1)]);
            }
        }
        TriMesh::new(v, t)
    }

    /// The charts of a whole surface as the model cuts a patch: one group when it needs none.
    fn charts(mesh: &TriMesh, normals: &[[f64; 3]], max_deg: f64) -> Vec<Vec<u32>> {
        if !needs_charts(mesh, normals, max_deg) {
            return vec![(0..mesh.triangles.len() as u32).collect()];
        }
        let labels = chart_labels(mesh, normals, max_deg);
        connected_groups(mesh, |t| labels[t as usize])
    }

    /// Every chart's triangles face within `deg` of the chart's mean normal.
    fn each_faces_one_way(m: &TriMesh, normals: &[[f64; 3]], groups: &[Vec<u32>], deg: f64) {
        let cos = deg.to_radians().cos();
        for g in groups {
            let sub_mesh = TriMesh::new(
                m.vertices.clone(),
                g.iter().map(|&t| m.triangles[t as usize]).collect(),
            );
            let ns: Vec<_> = g.iter().map(|&t| normals[t as usize]).collect();
            assert!(faces_one_way(&sub_mesh, &ns, cos), "chart {g:?}");
        }
    }

    #[test]
    fn a_flat_patch_stays_whole() {
        let m = TriMesh::new(
            vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [1.0, 1.0, 0.1],
                [0.0, 1.0, 0.0],
            ],
            vec![[0, 1, 2], [0, 2, 3]],
        );
        assert_eq!(charts(&m, &m.unit_normals(), 60.0), vec![vec![0, 1]]);
    }

    #[test]
    fn a_sphere_is_cut_into_six_charts_that_each_face_one_way() {
        let m = sphere(24, 48);
        let ns = m.unit_normals();
        let groups = charts(&m, &ns, 60.0);
        assert_eq!(
            groups.len(),
            6,
            "{:?}",
            groups.iter().map(Vec::len).collect::<Vec<_>>()
        );
        let total: usize = groups.iter().map(Vec::len).sum();
        assert_eq!(total, m.triangles.len());
        each_faces_one_way(&m, &ns, &groups, 75.0);
    }

    #[test]
    fn a_tube_is_cut_into_four_quarter_charts() {
        // A vertical tube; its ends are borders.
        use std::f64::consts::TAU;
        let (segs, rings) = (40, 10);
        let mut v = Vec::new();
        for i in 0..=rings {
            for k in 0..segs {
                let a = TAU * k as f64 / segs as f64;
                v.push([a.cos(), a.sin(), i as f64 * 0.3]);
            }
        }
        let id = |i: usize, k: usize| (i * segs + k % segs) as u32;
        let mut t = Vec::new();
        for i in 0..rings {
            for k in 0..segs {
                t.push([id(i, k), id(i, k + 1), id(i + 1, k + 1)]);
                t.push([id(i, k), id(i + 1, k + 1), id(i + 1, k)]);
            }
        }
        let m = TriMesh::new(v, t);
        let ns = m.unit_normals();
        let groups = charts(&m, &ns, 60.0);
        assert_eq!(groups.len(), 4);
        each_faces_one_way(&m, &ns, &groups, 60.0);
    }

    #[test]
    fn a_group_meeting_itself_at_a_vertex_gives_a_fan_to_its_neighbour() {
        // Four triangles around vertex 0, groups A B A B: A and B each touch themselves at 0.
        let m = TriMesh::new(
            vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [-1.0, 0.0, 0.0],
                [0.0, -1.0, 0.0],
            ],
            vec![[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 1]],
        );
        let mut group = vec![0, 1, 0, 1];
        assert!(!unpinch(&m, &mut group));
        // Each group ends as one fan: triangles 3 and 0 meet across edge 0-1, 1 and 2 across 0-3.
        let groups = connected_groups(&m, |t| group[t as usize]);
        assert_eq!(groups, vec![vec![0, 3], vec![1, 2]], "{group:?}");
    }
}
