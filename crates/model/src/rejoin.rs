//! Rejoining the patches a discarded trace split: a surface is cut into patches along every
//! intersection curve, but where a trim discarded the other surface (the part of a horizon
//! beyond the surface it onlaps, the part of a fault above the horizon it stops at), the curve
//! bounds nothing. Its two sides face one region; kept apart, they make a curve every mesh must
//! follow, and where the trace ends at the kept part of its surface it runs into a kept curve at
//! a small angle: the strip between the two is a fraction of a metre wide, and its triangles and
//! tets are flat.
//!
//! It decides: two kept patches of one surface are one where they share a curve edge that
//! * is an edge of exactly these two triangles among the kept patches of the surface,
//! * is not a crease (the caller's test, the one the patches were cut at),
//! * and is an edge of no kept patch of any other surface, by exact coordinates (splitting copies
//!   the points of a curve bit for bit into every surface along it).
//!
//! A joined patch keeps the name of its first part in the given (canonical) order, so no other
//! patch is renamed; its triangles are its parts', ascending.

use crate::intersect::split::SplitSurface;
use crate::patches::{Patch, extract};
use crate::point_key;
use crate::union_find::UnionFind;

/// An edge by the exact coordinates of its ends, smaller key first.
type EdgeKey = [[u64; 3]; 2];

/// `kept` (surface index, patch of `splits[surface]`) with the patches of each surface joined
/// across the curve edges no other surface keeps; `crease(surface, (t, u))` says whether two
/// triangles of that surface's split meet at a crease. The second value counts the patches that
/// were joined into another.
pub fn rejoin(
    kept: Vec<(usize, Patch)>,
    splits: &[SplitSurface],
    crease: &dyn Fn(usize, (u32, u32)) -> bool,
) -> (Vec<(usize, Patch)>, usize) {
    // Every use of a curve edge by a kept patch: (surface, edge, patch, triangle), sorted.
    let mut uses: Vec<(usize, [u32; 2], usize, u32)> = Vec::new();
    for (k, (i, p)) in kept.iter().enumerate() {
        let split = &splits[*i];
        for &t in &p.triangles {
            let tri = split.mesh.triangles[t as usize];
            for j in 0..3 {
                let (a, b) = (tri[j], tri[(j + 1) % 3]);
                let e = [a.min(b), a.max(b)];
                if split.curve_edges.binary_search(&e).is_ok() {
                    uses.push((*i, e, k, t));
                }
            }
        }
    }
    uses.sort_unstable();
    let key = |i: usize, e: [u32; 2]| -> EdgeKey {
        let v = &splits[i].mesh.vertices;
        let (a, b) = (point_key(&v[e[0] as usize]), point_key(&v[e[1] as usize]));
        if a <= b { [a, b] } else { [b, a] }
    };
    let mut held: Vec<(EdgeKey, usize)> = uses.iter().map(|u| (key(u.0, u.1), u.0)).collect();
    held.sort_unstable();
    held.dedup();
    let elsewhere = |i: usize, e: [u32; 2]| {
        let k = key(i, e);
        let from = held.partition_point(|h| h.0 < k);
        held[from..]
            .iter()
            .take_while(|h| h.0 == k)
            .any(|h| h.1 != i)
    };
    let mut sets = UnionFind::new(kept.len());
    for run in uses.chunk_by(|x, y| (x.0, x.1) == (y.0, y.1)) {
        let [x, y] = run else {
            continue;
        };
        if x.2 != y.2 && !crease(x.0, (x.3, y.3)) && !elsewhere(x.0, x.1) {
            sets.union(x.2, y.2);
        }
    }
    join(kept, splits, &mut sets)
}

/// The patches of `kept` joined by `sets`: each set in place of its first member.
fn join(
    kept: Vec<(usize, Patch)>,
    splits: &[SplitSurface],
    sets: &mut UnionFind,
) -> (Vec<(usize, Patch)>, usize) {
    let n = kept.len();
    let first: Vec<usize> = (0..n).map(|k| sets.find(k)).collect();
    let mut members: Vec<Vec<u32>> = vec![Vec::new(); n];
    let mut slots: Vec<Option<(usize, Patch)>> = kept.into_iter().map(Some).collect();
    let mut joined = 0;
    for k in 0..n {
        if first[k] != k {
            let (_, p) = slots[k].take().expect("each patch is taken once");
            members[first[k]].extend(p.triangles);
            joined += 1;
        }
    }
    let out = (slots.into_iter().enumerate())
        .filter_map(|(k, slot)| {
            let (i, p) = slot?;
            if members[k].is_empty() {
                return Some((i, p));
            }
            let mut triangles = p.triangles;
            triangles.append(&mut members[k]);
            triangles.sort_unstable();
            let mut whole = extract(&splits[i].mesh, vec![triangles]).remove(0);
            whole.name = p.name;
            Some((i, whole))
        })
        .collect();
    (out, joined)
}

#[cfg(test)]
mod tests {
    use super::*;
    use geom::TriMesh;
    use std::collections::BTreeMap;

    /// A unit square of two triangles across its diagonal 0-2, lifted to height `z`, split
    /// there by a curve: a patch per triangle.
    fn square(z: f64) -> (SplitSurface, Vec<Patch>) {
        let mesh = TriMesh::new(
            vec![[0.0, 0.0, z], [1.0, 0.0, z], [1.0, 1.0, z], [0.0, 1.0, z]],
            vec![[0, 1, 2], [0, 2, 3]],
        );
        let split = SplitSurface {
            mesh,
            parent: vec![0, 1],
            vertex_of: BTreeMap::new(),
            vertex_of_each: Vec::new(),
            crossings: Vec::new(),
            curve_edges: vec![[0, 2]],
        };
        let patches = crate::patches::patches("s", &split);
        (split, patches)
    }

    /// A vertical triangle standing on the square's diagonal (at height 0), as another surface.
    fn standing() -> (SplitSurface, Patch) {
        let mesh = TriMesh::new(
            vec![[0.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.5, 0.5, 1.0]],
            vec![[0, 1, 2]],
        );
        let split = SplitSurface {
            mesh,
            parent: vec![0],
            vertex_of: BTreeMap::new(),
            vertex_of_each: Vec::new(),
            crossings: Vec::new(),
            curve_edges: vec![[0, 1]],
        };
        let patch = crate::patches::patches("f", &split).remove(0);
        (split, patch)
    }

    fn never(_: usize, _: (u32, u32)) -> bool {
        false
    }

    #[test]
    fn two_patches_whose_curve_nothing_else_keeps_are_one_under_the_first_name() {
        let (split, patches) = square(0.0);
        assert_eq!(patches.len(), 2);
        let first = patches[0].name.clone();
        let kept = patches.into_iter().map(|p| (0, p)).collect();
        let (out, joined) = rejoin(kept, &[split], &never);
        assert_eq!(joined, 1);
        assert_eq!(out.len(), 1);
        let (i, p) = &out[0];
        assert_eq!((*i, p.name.as_str()), (0, first.as_str()));
        assert_eq!(p.triangles, vec![0, 1]);
        assert_eq!(p.mesh.vertices.len(), 4);
        assert_eq!(p.mesh.triangles.len(), 2);
    }

    #[test]
    fn a_curve_another_surface_keeps_still_parts_them_whichever_comes_first() {
        let (square, patches) = square(0.0);
        let (wall, fin) = standing();
        let splits = [square, wall];
        let mut kept: Vec<(usize, Patch)> = patches.into_iter().map(|p| (0, p)).collect();
        kept.push((1, fin.clone()));
        let (out, joined) = rejoin(kept, &splits, &never);
        assert_eq!((out.len(), joined), (3, 0));
        // The other surface first, its split first too.
        let (square, patches) = self::square(0.0);
        let (wall, _) = standing();
        let splits = [wall, square];
        let mut kept = vec![(0, fin)];
        kept.extend(patches.into_iter().map(|p| (1, p)));
        let (out, joined) = rejoin(kept, &splits, &never);
        assert_eq!((out.len(), joined), (3, 0));
    }

    #[test]
    fn another_surface_near_the_curve_but_not_on_it_does_not_part_them() {
        // The standing triangle's base is on the diagonal of a square at height 0; this square
        // is a hair above it, so the two share no point.
        let (square, patches) = square(1e-12);
        let (wall, fin) = standing();
        let mut kept: Vec<(usize, Patch)> = patches.into_iter().map(|p| (0, p)).collect();
        kept.push((1, fin));
        let (out, joined) = rejoin(kept, &[square, wall], &never);
        assert_eq!((out.len(), joined), (2, 1));
    }

    #[test]
    fn a_crease_still_parts_them() {
        let (split, patches) = square(0.0);
        let kept = patches.into_iter().map(|p| (0, p)).collect();
        let (out, joined) = rejoin(kept, &[split], &|_, _| true);
        assert_eq!((out.len(), joined), (2, 0));
    }
}
