//! The element size field: how long an edge should be at a point of the patch.
//!
//! With g = growth - 1, the x_i the given loop and constraint nodes and points, and h_i their local
//! segment length (mean of the adjacent given segments; for a point, the target size clamped to
//! [min, max], lowered to the distance to the nearest other given node, see `points`):
//!   up(x) = min_i(h_i + g·|x - x_i|), down(x) = max_i(h_i - g·|x - x_i|),
//!   h(x) = clamp(min(up(x), max(size, down(x))), min_size, max_size).
//! So sizes start from the boundary discretization and change away from it by at most g per unit
//! of length in either direction (a Lipschitz bound, which gives the 2:1-like balance of the
//! seed's octree without a tree to balance): a fine boundary grows towards `size`, and a boundary
//! coarser than `size` shrinks towards it instead of meeting tiny triangles. Where a fine and a
//! coarse boundary meet (a 25 m horizon curve ending on a 200 m box edge), `up` wins: the fine
//! curve keeps elements of its own size all along, instead of fans of slivers hanging from a few
//! coarse points near the corner.
//! Curvature: each support vertex where the support's normal turns faster than `CURVE_ANGLE` per
//! element of the target size adds an up-only node with h = CURVE_ANGLE / κ (κ: the largest
//! normal turn per unit length across the vertex's edges, from the dihedral angles of the support
//! facets). So hinges of tight folds get smaller elements that follow them, as in the seed's
//! octree refinement for curvature. The width a bend is spread over is at least half the reach of
//! the edge's neighbours, so the small pieces a curve cuts from the facets it crosses do not pass
//! for tight hinges.
//! The minimum over nodes is found with an R-tree: the nearest node bounds the answer, so only
//! nodes within that bound's reach are visited; no query is made when none could matter.

use geom::TriMesh;
use geom::predicates::{cross, dist, dot, sub};
use rstar::RTree;
use rstar::primitives::GeomWithData;
use std::collections::BTreeMap;

/// Largest turn of the surface normal (radians) across one element: 0.35 rad is about 20°.
pub const CURVE_ANGLE: f64 = 0.35;

/// Up-only size nodes from the support's curvature (see the module doc), for vertices where the
/// curvature size is below `size`.
///
/// One edge's estimate h = CURVE_ANGLE · len / angle trusts that edge's facets; on a split support
/// a sliver a few centimetres wide with a facet-level kink of under a degree would ask for metre
/// elements. So an estimate counts only if the normal really turns by `CURVE_ANGLE` near it: the
/// dihedral angles of the support edges whose midpoints lie within h/2 must add up to at least
/// half of `CURVE_ANGLE` (half: a disk centred at the end of a bend sees only half of it); else h
/// grows (in proportion, as it would across parallel creases) until they do or it reaches `size`. A smooth bend faceted finely or coarsely passes unchanged (the creases
/// across a disk of diameter h turn the normal by about CURVE_ANGLE by construction); an isolated
/// shallow kink does not refine at all.
pub fn curvature_nodes(support: &TriMesh, normals: &[[f64; 3]], size: f64) -> Vec<([f64; 3], f64)> {
    let mut edges: BTreeMap<(u32, u32), u32> = BTreeMap::new();
    for (t, tri) in support.triangles.iter().enumerate() {
        for i in 0..3 {
            edges.insert((tri[i], tri[(i + 1) % 3]), t as u32);
        }
    }
    // The normal turns by the dihedral angle over about the mean of the two facets' widths
    // across the edge (their heights over it: long thin facets stay meaningful), and over no
    // less than half the reach of the edge's ends' neighbours across it: a curve cuts small
    // pieces from the facets it crosses, and a bend between two such pieces is the bend of the
    // whole facets around them, not a tight hinge (on a faceted tube it would ask for metre
    // elements).
    let height =
        |t: u32, elen: f64| geom::trimesh::triangle_area(support.corners(t as usize)) * 2.0 / elen;
    let mut ring: Vec<Vec<u32>> = vec![Vec::new(); support.vertices.len()];
    for tri in &support.triangles {
        for i in 0..3 {
            let (a, b) = (tri[i], tri[(i + 1) % 3]);
            ring[a as usize].push(b);
            ring[b as usize].push(a);
        }
    }
    for r in &mut ring {
        r.sort_unstable();
        r.dedup();
    }
    let reach = |a: u32, b: u32| {
        let pa = &support.vertices[a as usize];
        let e = sub(&support.vertices[b as usize], pa);
        let elen = dot(&e, &e).sqrt();
        ring[a as usize]
            .iter()
            .chain(&ring[b as usize])
            .map(|&w| {
                let c = cross(&sub(&support.vertices[w as usize], pa), &e);
                dot(&c, &c).sqrt() / elen
            })
            .fold(0.0, f64::max)
    };
    let origin = support.vertices.first().copied().unwrap_or([0.0; 3]);
    // (a, b, edge length, dihedral angle, single-edge estimate of h) of every bent interior edge.
    let mut bent = Vec::new();
    for (&(a, b), &t) in &edges {
        if a > b {
            continue;
        }
        let Some(&u) = edges.get(&(b, a)) else {
            continue;
        };
        let (n1, n2) = (normals[t as usize], normals[u as usize]);
        let angle = dot(&n1, &n2).clamp(-1.0, 1.0).acos();
        let (pa, pb) = (support.vertices[a as usize], support.vertices[b as usize]);
        let e = sub(&pb, &pa);
        let elen = dot(&e, &e).sqrt();
        if !(elen > 0.0) || !(angle > 0.0) {
            continue;
        }
        let len = ((height(t, elen) + height(u, elen)) / 2.0).max(0.5 * reach(a, b));
        bent.push((a, b, elen, angle, CURVE_ANGLE * len / angle));
    }
    let mid = |a: u32, b: u32| {
        let (pa, pb) = (support.vertices[a as usize], support.vertices[b as usize]);
        [0, 1, 2].map(|k| (pa[k] + pb[k]) * 0.5 - origin[k])
    };
    let turns: Tree = RTree::bulk_load(
        bent.iter()
            .map(|&(a, b, _, angle, _)| GeomWithData::new(mid(a, b), angle))
            .collect(),
    );
    let mut out = Vec::new();
    for &(a, b, elen, _, h0) in &bent {
        if !(h0 < size) {
            continue;
        }
        let m = mid(a, b);
        let mut h = h0;
        for _ in 0..16 {
            let r = h * 0.5;
            let turn: f64 = turns.locate_within_distance(m, r * r).map(|x| x.data).sum();
            let need = 0.5 * CURVE_ANGLE;
            if turn >= need * (1.0 - 1e-9) || !(h < size) {
                break;
            }
            h *= (need / turn.max(1e-3 * need)).min(4.0);
        }
        if !(h < size) {
            continue;
        }
        // Nodes along the edge, about h apart (at most 64 per edge).
        let (pa, pb) = (support.vertices[a as usize], support.vertices[b as usize]);
        let e = sub(&pb, &pa);
        let n = ((elen / h).ceil() as usize).clamp(1, 64);
        for k in 0..=n {
            let s = k as f64 / n as f64;
            out.push(([pa[0] + s * e[0], pa[1] + s * e[1], pa[2] + s * e[2]], h));
        }
    }
    out
}

type Tree = RTree<GeomWithData<[f64; 3], f64>>;

pub struct SizeField {
    origin: [f64; 3],
    /// The given nodes with their local sizes.
    tree: Tree,
    /// Curvature nodes: they only bound sizes from above, after the boundary terms.
    curv: Tree,
    hmin_nodes: f64,
    hmax_nodes: f64,
    hmin_curv: f64,
    /// Refinements near features: their points, size and slope (no steeper than `slope`).
    feat: Vec<(Tree, f64, f64)>,
    slope: f64,
    size: f64,
    min_size: f64,
    max_size: f64,
}

fn build(nodes: &[([f64; 3], f64)], origin: [f64; 3]) -> Tree {
    RTree::bulk_load(
        nodes
            .iter()
            .map(|(p, h)| {
                GeomWithData::new([p[0] - origin[0], p[1] - origin[1], p[2] - origin[2]], *h)
            })
            .collect(),
    )
}

/// min_i(h_i + slope·|q - x_i|), visiting only nodes that can beat the current bound `cap`.
fn up(tree: &Tree, hmin: f64, slope: f64, q: [f64; 3], cap: f64) -> f64 {
    let Some(n) = tree.nearest_neighbor(q) else {
        return cap;
    };
    let d = dist(n.geom(), &q);
    let mut best = (n.data + slope * d).min(cap);
    let reach = (best - hmin) / slope;
    if reach > d {
        for m in tree.locate_within_distance(q, reach * reach) {
            best = best.min(m.data + slope * dist(m.geom(), &q));
        }
    }
    best
}

impl SizeField {
    /// As [`SizeField::new`], also bounded by the sizes `refine` asks for near their features,
    /// each growing no faster than this field's own slope.
    pub fn with_refinements(mut self, refine: &[geom::refine::Refinement]) -> SizeField {
        for r in refine.iter().filter(|r| !r.points.is_empty()) {
            let nodes: Vec<([f64; 3], f64)> = r.points.iter().map(|p| (*p, r.size)).collect();
            let slope = r.slope.min(self.slope).max(1e-9);
            self.feat.push((build(&nodes, self.origin), r.size, slope));
        }
        self
    }

    /// `nodes`: (position, local size) of the given boundary and constraint nodes and points;
    /// `curvature`: up-only nodes from `curvature_nodes`.
    pub fn new(
        nodes: &[([f64; 3], f64)],
        curvature: &[([f64; 3], f64)],
        origin: [f64; 3],
        size: f64,
        min_size: f64,
        max_size: f64,
        growth: f64,
    ) -> SizeField {
        let hmin = |n: &[([f64; 3], f64)]| n.iter().map(|n| n.1).fold(f64::INFINITY, f64::min);
        SizeField {
            origin,
            tree: build(nodes, origin),
            curv: build(curvature, origin),
            hmin_nodes: hmin(nodes),
            hmax_nodes: nodes.iter().map(|n| n.1).fold(0.0, f64::max),
            hmin_curv: hmin(curvature),
            feat: Vec::new(),
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
            return self
                .feat
                .iter()
                .fold(h.min(self.hmin_nodes).min(self.hmin_curv), |h, f| {
                    h.min(f.1)
                })
                .clamp(self.min_size, self.max_size);
        }
        // down(x) can only raise h above `size` if some node is coarser than `size`, and only
        // from within reach.
        if self.hmax_nodes > h {
            let reach = (self.hmax_nodes - h) / self.slope;
            let mut low = h;
            for m in self.tree.locate_within_distance(q, reach * reach) {
                low = low.max(m.data - self.slope * dist(m.geom(), &q));
            }
            h = low;
        }
        // up(x) bounds everything: a fine boundary node keeps its size next to a coarse one.
        if self.hmin_nodes < h {
            h = up(&self.tree, self.hmin_nodes, self.slope, q, h);
        }
        // Curvature last: a tight hinge needs small elements whatever the boundary says.
        if self.hmin_curv < h {
            h = up(&self.curv, self.hmin_curv, self.slope, q, h);
        }
        for (tree, hmin, slope) in &self.feat {
            if *hmin < h {
                h = up(tree, *hmin, *slope, q, h);
            }
        }
        h.clamp(self.min_size, self.max_size)
    }
}

/// The sizes a support's curvature alone asks for, graded at the steepest growth a surface
/// mesh allows ([`crate::MAX_SURFACE_GROWTH`]): what a patch's mesh would refine to near a
/// point of its border, for the curves that are that border and are discretized before it.
pub struct CurvatureSizes {
    field: Option<SizeField>,
    cap: f64,
}

impl CurvatureSizes {
    /// The curvature sizes of `support` below `cap` (larger ones are not computed).
    pub fn new(support: &TriMesh, cap: f64) -> CurvatureSizes {
        let nodes = curvature_nodes(support, &support.unit_normals(), cap);
        let origin = support.vertices.first().copied().unwrap_or([0.0; 3]);
        let growth = crate::MAX_SURFACE_GROWTH;
        let field =
            (!nodes.is_empty()).then(|| SizeField::new(&[], &nodes, origin, cap, 0.0, cap, growth));
        CurvatureSizes { field, cap }
    }

    /// The size at `x`; infinite where the curvature asks for none below the cap.
    pub fn at(&self, x: &[f64; 3]) -> f64 {
        match &self.field {
            Some(f) => Some(f.at(x))
                .filter(|&h| h < self.cap)
                .unwrap_or(f64::INFINITY),
            None => f64::INFINITY,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A half cylinder of radius 150 m faceted every 9°, 600 m long.
    fn half_cylinder() -> TriMesh {
        half_cylinder_with(20)
    }

    /// A half cylinder of radius 150 m in `n` facets, 600 m long.
    fn half_cylinder_with(n: u32) -> TriMesh {
        let (vs, ts) = test_support::shapes::half_cylinder(n);
        TriMesh::new(vs, ts)
    }

    #[test]
    fn a_sliver_with_a_shallow_kink_asks_for_no_refinement() {
        // A 1000 m square, flat except a 5 cm wide sliver strip along x = 500 whose far side is
        // 1 mm higher (a kink of about 1°, as splitting a support leaves behind).
        let vs = vec![
            [0.0, 0.0, 0.0],
            [500.0, 0.0, 0.0],
            [500.05, 0.0, 0.001],
            [1000.0, 0.0, 0.001],
            [0.0, 1000.0, 0.0],
            [500.0, 1000.0, 0.0],
            [500.05, 1000.0, 0.001],
            [1000.0, 1000.0, 0.001],
        ];
        let ts = vec![
            [0, 1, 5],
            [0, 5, 4],
            [1, 2, 6],
            [1, 6, 5],
            [2, 3, 7],
            [2, 7, 6],
        ];
        let m = TriMesh::new(vs, ts);
        let nodes = curvature_nodes(&m, &m.unit_normals(), 200.0);
        assert!(
            nodes.is_empty(),
            "{} nodes, h = {:?}",
            nodes.len(),
            nodes.first()
        );
    }

    #[test]
    fn a_finely_faceted_bend_still_bounds_the_size() {
        // A half cylinder of radius 150 m faceted every 1° (2.6 m facets): same bound as 9°.
        let m = half_cylinder_with(180);
        let nodes = curvature_nodes(&m, &m.unit_normals(), 200.0);
        assert!(!nodes.is_empty());
        for (_, h) in &nodes {
            assert!(*h > 40.0 && *h < 80.0, "h = {h}");
        }
    }

    #[test]
    fn a_tight_hinge_bounds_the_size_by_its_curvature() {
        let m = half_cylinder();
        let normals = m.unit_normals();
        let nodes = curvature_nodes(&m, &normals, 200.0);
        assert!(!nodes.is_empty());
        // Radius 150 m: h = 0.35 × 150 ≈ 52 m (facets make it a little coarser).
        for (_, h) in &nodes {
            assert!(*h > 40.0 && *h < 80.0, "h = {h}");
        }
        assert!(curvature_nodes(&m, &normals, 30.0).is_empty());
        let f = SizeField::new(
            &[([150.0, 0.0, 0.0], 200.0)],
            &nodes,
            [0.0; 3],
            200.0,
            1.0,
            1000.0,
            1.2,
        );
        assert!(f.at(&[0.0, 300.0, 150.0]) < 80.0);
    }

    #[test]
    fn curvature_sizes_follow_a_bend_and_grade_away_from_it_but_ask_nothing_of_a_plane() {
        let bend = CurvatureSizes::new(&half_cylinder(), 1000.0);
        // On the cylinder (radius 150 m): about 0.35 × 150 m, as the surface mesher refines.
        for y in [0.0, 300.0, 600.0] {
            let h = bend.at(&[0.0, y, 150.0]);
            assert!(h > 40.0 && h < 80.0, "h = {h} at y = {y}");
        }
        // 1 km off along its axis: graded at 0.15 per metre from the nearest bend.
        let far = bend.at(&[0.0, 1600.0, 150.0]);
        assert!(far > 150.0 && far < 240.0, "h = {far}");
        // Beyond the cap: no bound.
        assert_eq!(bend.at(&[0.0, 1.0e5, 150.0]), f64::INFINITY);
        let flat = TriMesh::new(
            vec![
                [0.0; 3],
                [1000.0, 0.0, 0.0],
                [1000.0, 1000.0, 0.0],
                [0.0, 1000.0, 0.0],
            ],
            vec![[0, 1, 2], [0, 2, 3]],
        );
        let plane = CurvatureSizes::new(&flat, 1000.0);
        assert_eq!(plane.at(&[500.0, 500.0, 0.0]), f64::INFINITY);
    }
}
