//! The element size field: how long an edge should be at a point of the patch.
//!
//! With g = growth - 1, the x_i the given loop and constraint nodes and h_i their local segment
//! length (mean of the adjacent given segments):
//!   up(x) = min_i(h_i + g·|x - x_i|), down(x) = max_i(h_i - g·|x - x_i|),
//!   h(x) = clamp(max(min(size, up(x)), down(x)), min_size, max_size).
//! So sizes start from the boundary discretization and change away from it by at most g per unit
//! of length in either direction (a Lipschitz bound, which gives the 2:1-like balance of the
//! seed's octree without a tree to balance): a fine boundary grows towards `size`, and a boundary
//! coarser than `size` shrinks towards it instead of meeting tiny triangles.
//! The minimum over boundary nodes is found with an R-tree: the nearest node bounds the answer,
//! so only nodes within that bound's reach are visited.

use rstar::RTree;
use rstar::primitives::GeomWithData;

pub struct SizeField {
    origin: [f64; 3],
    tree: RTree<GeomWithData<[f64; 3], f64>>,
    hmin_nodes: f64,
    hmax_nodes: f64,
    slope: f64,
    size: f64,
    min_size: f64,
    max_size: f64,
}

impl SizeField {
    /// `nodes`: (position, local size) of the given boundary and constraint nodes.
    pub fn new(
        nodes: &[([f64; 3], f64)],
        origin: [f64; 3],
        size: f64,
        min_size: f64,
        max_size: f64,
        growth: f64,
    ) -> SizeField {
        let items: Vec<_> = nodes
            .iter()
            .map(|(p, h)| {
                GeomWithData::new([p[0] - origin[0], p[1] - origin[1], p[2] - origin[2]], *h)
            })
            .collect();
        let hmin_nodes = nodes.iter().map(|n| n.1).fold(f64::INFINITY, f64::min);
        let hmax_nodes = nodes.iter().map(|n| n.1).fold(0.0, f64::max);
        SizeField {
            origin,
            tree: RTree::bulk_load(items),
            hmin_nodes,
            hmax_nodes,
            slope: (growth - 1.0).max(0.0),
            size,
            min_size,
            max_size,
        }
    }

    /// The target edge length at `x`.
    pub fn at(&self, x: &[f64; 3]) -> f64 {
        let q = [
            x[0] - self.origin[0],
            x[1] - self.origin[1],
            x[2] - self.origin[2],
        ];
        let mut h = self.size;
        if self.slope <= 1e-12 {
            return h.min(self.hmin_nodes).clamp(self.min_size, self.max_size);
        }
        // up(x) can only lower h below `size` if some node is finer than `size`.
        if self.hmin_nodes < h
            && let Some(n) = self.tree.nearest_neighbor(q)
        {
            let d = dist(n.geom(), &q);
            let mut best = n.data + self.slope * d;
            let bound = best.min(h);
            let reach = (bound - self.hmin_nodes) / self.slope;
            if reach > d {
                for m in self.tree.locate_within_distance(q, reach * reach) {
                    best = best.min(m.data + self.slope * dist(m.geom(), &q));
                }
            }
            h = h.min(best);
        }
        // down(x) can only raise h if some node is coarser than h, and only from within reach.
        if self.hmax_nodes > h {
            let reach = (self.hmax_nodes - h) / self.slope;
            let mut low = h;
            for m in self.tree.locate_within_distance(q, reach * reach) {
                low = low.max(m.data - self.slope * dist(m.geom(), &q));
            }
            h = low;
        }
        h.clamp(self.min_size, self.max_size)
    }
}

fn dist(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}
