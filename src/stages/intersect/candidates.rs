//! Candidate triangle pairs: pairs whose closed bounding boxes overlap, found by a simultaneous
//! descent of two R-trees (rstar) of triangle boxes. Boxes only cull: a pair that can touch always
//! overlaps (closed comparisons on the exact input coordinates), so no contact is ever lost here.
//! Triangles outside the other surface's box are left out of the trees. The output is sorted, so
//! it does not depend on the tree layout or on the thread count.

use crate::geom::{BBox, TriMesh};
use rstar::{AABB, RTree, RTreeObject};

/// A triangle's bounding box in an R-tree.
struct TriBox {
    env: AABB<[f64; 3]>,
    index: u32,
}

impl RTreeObject for TriBox {
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

fn boxes_within(m: &TriMesh, limit: &BBox) -> Vec<TriBox> {
    (0..m.triangles.len())
        .filter_map(|t| {
            let b = tri_box(m, t);
            (!b.is_empty() && b.overlaps(limit)).then(|| TriBox {
                env: AABB::from_corners(b.min, b.max),
                index: t as u32,
            })
        })
        .collect()
}

/// All `(triangle of a, triangle of b)` pairs whose bounding boxes overlap, sorted.
pub fn candidate_pairs(a: &TriMesh, b: &TriMesh) -> Vec<(u32, u32)> {
    let (ba, bb) = (a.bbox(), b.bbox());
    if ba.is_empty() || bb.is_empty() || !ba.overlaps(&bb) {
        return Vec::new();
    }
    let (boxes_a, boxes_b) = rayon::join(|| boxes_within(a, &bb), || boxes_within(b, &ba));
    if boxes_a.is_empty() || boxes_b.is_empty() {
        return Vec::new();
    }
    let (ta, tb) = rayon::join(|| RTree::bulk_load(boxes_a), || RTree::bulk_load(boxes_b));
    let mut pairs: Vec<(u32, u32)> = ta
        .intersection_candidates_with_other_tree(&tb)
        .map(|(x, y)| (x.index, y.index))
        .collect();
    pairs.sort_unstable();
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
}
