//! Which patches lie within a distance of another surface all over: a contact that the files draw
//! twice, centimetres apart (two bodies built each on its own along a shared face, a body's top
//! drawn along a horizon). Between such a patch and the surface it hugs lies a region as thin as
//! the gap, which no element spans; discarding the patch leaves the other surface as the
//! contact. A patch hugs a surface when each of its vertices and of its triangles' centroids is
//! within the distance of that one surface (a measure, in floating point, as `area_below` is).
//!
//! Patches that hug one surface and share border edges are taken together, and discarded only
//! when the border of the whole lies on that surface (every end of its border edges is a vertex
//! of it, which splitting shares bit for bit): then the other surface closes what they leave
//! open. A group whose border leaves the surface (it runs on along a crease of its own) stays.

use super::TrimPatch;
use super::near::triangle_distance;
use super::side::{EdgeBits, bits, edge_uses};
use crate::union_find::UnionFind;
use geom::TriMesh;
use rstar::primitives::{GeomWithData, Rectangle};
use rstar::{AABB, RTree};
use std::collections::{BTreeMap, BTreeSet};

/// A triangle's box, with its surface and triangle indices.
type Boxed = GeomWithData<Rectangle<[f64; 3]>, (u32, u32)>;

/// The triangles of every surface, indexed by their boxes.
struct Nearby<'s, 'a> {
    surfaces: &'s [(&'a str, &'a TriMesh)],
    tree: RTree<Boxed>,
}

impl<'s, 'a> Nearby<'s, 'a> {
    fn new(surfaces: &'s [(&'a str, &'a TriMesh)]) -> Nearby<'s, 'a> {
        let mut items = Vec::new();
        for (s, (_, mesh)) in surfaces.iter().enumerate() {
            let nv = mesh.vertices.len();
            for (t, tri) in mesh.triangles.iter().enumerate() {
                if tri.iter().any(|&v| v as usize >= nv) {
                    continue;
                }
                let c = mesh.corners(t);
                let lo = [0, 1, 2].map(|k| c[0][k].min(c[1][k]).min(c[2][k]));
                let hi = [0, 1, 2].map(|k| c[0][k].max(c[1][k]).max(c[2][k]));
                items.push(GeomWithData::new(
                    Rectangle::from_corners(lo, hi),
                    (s as u32, t as u32),
                ));
            }
        }
        Nearby {
            surfaces,
            tree: RTree::bulk_load(items),
        }
    }

    /// The surfaces other than `own` that come within `d` of `p`, by index.
    fn within(&self, p: &[f64; 3], d: f64, own: &str) -> BTreeSet<u32> {
        let envelope = AABB::from_corners(p.map(|x| x - d), p.map(|x| x + d));
        let mut out = BTreeSet::new();
        for item in self.tree.locate_in_envelope_intersecting(envelope) {
            let (s, t) = item.data;
            let (name, mesh) = self.surfaces[s as usize];
            if name == own || out.contains(&s) {
                continue;
            }
            let [a, b, c] = mesh.corners(t as usize);
            if triangle_distance(p, a, b, c) <= d {
                out.insert(s);
            }
        }
        out
    }

    /// The first surface (in the order given) other than the patch's own that every vertex and
    /// triangle centroid of `p` lies within `d` of.
    fn hugged(&self, p: &TrimPatch, d: f64) -> Option<&'a str> {
        let m = p.mesh;
        let centroids = (0..m.triangles.len()).map(|t| super::centroid(m.corners(t)));
        let mut common: Option<BTreeSet<u32>> = None;
        for q in m.vertices.iter().copied().chain(centroids) {
            let here = self.within(&q, d, p.surface);
            let left: BTreeSet<u32> = match common {
                None => here,
                Some(c) => c.intersection(&here).copied().collect(),
            };
            if left.is_empty() {
                return None;
            }
            common = Some(left);
        }
        let first = *common?.iter().next()?;
        Some(self.surfaces[first as usize].0)
    }
}

/// Of the patches `selected` (indices into `patches`), those to discard as hugging another
/// surface within `d`, each with that surface's name (see the module doc), in patch order. The
/// other surfaces are their patches still kept (`keep`): a part already discarded closes
/// nothing.
pub fn hugging<'a>(
    patches: &[TrimPatch<'a>],
    keep: &[bool],
    selected: &[usize],
    d: f64,
) -> Vec<(usize, &'a str)> {
    let kept: Vec<(&'a str, &'a TriMesh)> = (patches.iter().zip(keep))
        .filter(|(_, k)| **k)
        .map(|(p, _)| (p.surface, p.mesh))
        .collect();
    let surfaces = kept.as_slice();
    let near = Nearby::new(surfaces);
    let hugs: Vec<(usize, &str)> = (selected.iter())
        .filter_map(|&i| Some((i, near.hugged(&patches[i], d)?)))
        .collect();
    // Join hugging patches of one pair of surfaces that share an edge.
    let mut groups = UnionFind::new(hugs.len());
    let mut by_edge: BTreeMap<EdgeBits, usize> = BTreeMap::new();
    for (k, (i, other)) in hugs.iter().enumerate() {
        let mut edges = BTreeMap::new();
        edge_uses(patches[*i].mesh, &mut edges);
        for e in edges.into_keys() {
            if let Some(&j) = by_edge.get(&e)
                && hugs[j].1 == *other
                && patches[hugs[j].0].surface == patches[*i].surface
            {
                groups.union(j, k);
            }
            by_edge.insert(e, k);
        }
    }
    let mut members: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
    for k in 0..hugs.len() {
        members.entry(groups.find(k)).or_default().push(k);
    }
    let mut out = Vec::new();
    for group in members.values() {
        let other = hugs[group[0]].1;
        let on: BTreeSet<[u64; 3]> = (surfaces.iter())
            .filter(|(n, _)| *n == other)
            .flat_map(|(_, m)| m.vertices.iter().map(bits))
            .collect();
        let mut edges = BTreeMap::new();
        for &k in group {
            edge_uses(patches[hugs[k].0].mesh, &mut edges);
        }
        let closed_by_other = (edges.iter())
            .filter(|(_, n)| **n % 2 == 1)
            .all(|((a, b), _)| on.contains(a) && on.contains(b));
        if closed_by_other {
            out.extend(group.iter().map(|&k| hugs[k]));
        }
    }
    out.sort();
    out
}
