//! Candidate triangle pairs: pairs whose closed bounding boxes overlap. Triangles outside the
//! other surface's box are dropped; the rest are ordered along a Morton (Z-order) curve of their
//! box centres and packed in runs of [`CLUSTER`] into cluster boxes; an R-tree (rstar) of
//! cluster boxes per surface is built and the two trees are descended together; each pair of
//! overlapping clusters is then expanded triangle by triangle. Boxes only cull, with closed
//! comparisons on the exact input coordinates, so a pair that can touch is never lost: the
//! Morton order only decides which triangles share a cluster (speed, never correctness). The
//! output is sorted, so it depends neither on the tree layout nor on the thread count.
//! Clustering makes the bulk load about `CLUSTER` times cheaper than one tree entry per triangle.

use geom::{BBox, TriMesh};
use rayon::prelude::*;
use rstar::{AABB, RTree, RTreeObject};

/// Triangles per cluster (leaf entry of the R-tree).
pub const CLUSTER: usize = 8;

/// A box with the index of what it bounds (a cluster).
struct Entry {
    env: AABB<[f64; 3]>,
    index: u32,
}

impl RTreeObject for Entry {
    type Envelope = AABB<[f64; 3]>;
    fn envelope(&self) -> Self::Envelope {
        self.env
    }
}

fn tri_box(m: &TriMesh, t: usize) -> BBox {
    let mut b = BBox::empty();
    if let Some(tri) = m.triangles.get(t) {
        for &v in tri {
            if let Some(p) = m.vertices.get(v as usize) {
                b.add(p);
            }
        }
    }
    b
}

/// Spread the low 21 bits of `v` to every third bit.
fn spread(v: u64) -> u64 {
    let mut x = v & 0x1f_ffff;
    x = (x | (x << 32)) & 0x1f00000000ffff;
    x = (x | (x << 16)) & 0x1f0000ff0000ff;
    x = (x | (x << 8)) & 0x100f00f00f00f00f;
    x = (x | (x << 4)) & 0x10c30c30c30c30c3;
    (x | (x << 2)) & 0x1249249249249249
}

fn morton(b: &BBox, frame: &BBox) -> u64 {
    let mut code = 0;
    for k in 0..3 {
        let ext = frame.max[k] - frame.min[k];
        let c = 0.5 * (b.min[k] + b.max[k]);
        let u = if ext > 0.0 {
            ((c - frame.min[k]) / ext).clamp(0.0, 1.0)
        } else {
            0.0
        };
        code |= spread((u * 2_097_151.0) as u64) << k;
    }
    code
}

/// The triangles of `m` whose boxes meet `limit`, with their boxes, in Morton order, and their
/// clusters (index range into that list, and cluster box).
struct Clusters {
    tris: Vec<(u32, BBox)>,
    entries: Vec<Entry>,
}

fn clusters(m: &TriMesh, limit: &BBox) -> Clusters {
    let mut keyed: Vec<(u64, u32)> = (0..m.triangles.len())
        .into_par_iter()
        .with_min_len(4096)
        .filter_map(|t| {
            let b = tri_box(m, t);
            (!b.is_empty() && b.overlaps(limit)).then(|| (morton(&b, limit), t as u32))
        })
        .collect();
    keyed.par_sort_unstable();
    let tris: Vec<(u32, BBox)> = keyed
        .par_iter()
        .with_min_len(4096)
        .map(|&(_, t)| (t, tri_box(m, t as usize)))
        .collect();
    let entries = tris
        .chunks(CLUSTER)
        .enumerate()
        .map(|(i, c)| {
            let b = c.iter().fold(BBox::empty(), |acc, (_, b)| acc.union(b));
            Entry {
                env: AABB::from_corners(b.min, b.max),
                index: i as u32,
            }
        })
        .collect();
    Clusters { tris, entries }
}

/// The triangles of cluster `c`.
fn run(tris: &[(u32, BBox)], c: u32) -> &[(u32, BBox)] {
    let s = c as usize * CLUSTER;
    tris.get(s..(s + CLUSTER).min(tris.len())).unwrap_or(&[])
}

/// All `(triangle of a, triangle of b)` pairs whose bounding boxes overlap, sorted.
pub fn candidate_pairs(a: &TriMesh, b: &TriMesh) -> Vec<(u32, u32)> {
    let (ba, bb) = (a.bbox(), b.bbox());
    if ba.is_empty() || bb.is_empty() || !ba.overlaps(&bb) {
        return Vec::new();
    }
    // Both sides are clustered in the frame of the common part of the two boxes.
    let mut frame = ba;
    for k in 0..3 {
        frame.min[k] = ba.min[k].max(bb.min[k]);
        frame.max[k] = ba.max[k].min(bb.max[k]);
    }
    let (ca, cb) = rayon::join(|| clusters(a, &frame), || clusters(b, &frame));
    if ca.entries.is_empty() || cb.entries.is_empty() {
        return Vec::new();
    }
    let (ta, tb) = rayon::join(
        || RTree::bulk_load(ca.entries),
        || RTree::bulk_load(cb.entries),
    );
    let cluster_pairs: Vec<(u32, u32)> = ta
        .intersection_candidates_with_other_tree(&tb)
        .map(|(x, y)| (x.index, y.index))
        .collect();
    let mut pairs: Vec<(u32, u32)> = cluster_pairs
        .par_iter()
        .flat_map_iter(|&(x, y)| {
            let (ra, rb) = (run(&ca.tris, x), run(&cb.tris, y));
            ra.iter().flat_map(move |(i, bi)| {
                rb.iter()
                    .filter(move |(_, bj)| bi.overlaps(bj))
                    .map(move |(j, _)| (*i, *j))
            })
        })
        .collect();
    pairs.par_sort_unstable();
    pairs
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_triangles_with_overlapping_boxes_are_paired() {
        let a = TriMesh::new(
            vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [10.0, 0.0, 0.0],
                [11.0, 0.0, 0.0],
                [10.0, 1.0, 0.0],
            ],
            vec![[0, 1, 2], [3, 4, 5]],
        );
        let b = TriMesh::new(
            vec![[1.0, 0.0, -1.0], [1.0, 1.0, 1.0], [0.5, 0.0, 1.0]],
            vec![[0, 1, 2]],
        );
        assert_eq!(candidate_pairs(&a, &b), vec![(0, 0)]);
    }

    #[test]
    fn clustered_candidates_equal_the_brute_force_pairs() {
        let grid = |n: usize, f: &dyn Fn(usize, usize) -> [f64; 3]| {
            let mut m = TriMesh::default();
            for j in 0..=n {
                for i in 0..=n {
                    m.vertices.push(f(i, j));
                }
            }
            let id = |i: usize, j: usize| (j * (n + 1) + i) as u32;
            for j in 0..n {
                for i in 0..n {
                    m.triangles.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
                    m.triangles.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
                }
            }
            m
        };
        let a = grid(30, &|i, j| {
            [i as f64, j as f64, (i as f64 * 0.7).sin() * 2.0]
        });
        let b = grid(25, &|i, k| {
            [
                3.0 + 0.9 * i as f64 + 0.1 * k as f64,
                0.5 + i as f64,
                k as f64 * 0.4 - 5.0,
            ]
        });
        let mut brute = Vec::new();
        for i in 0..a.triangles.len() {
            for j in 0..b.triangles.len() {
                if a.triangle_bbox(i).overlaps(&b.triangle_bbox(j)) {
                    brute.push((i as u32, j as u32));
                }
            }
        }
        assert!(!brute.is_empty());
        assert_eq!(candidate_pairs(&a, &b), brute);
    }
}
