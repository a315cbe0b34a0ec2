//! Stage `topology`: the combinatorial structure of a triangulated surface that later stages walk,
//! in the spirit of the seed's DCEL-like structure, extended to non-manifold edges, dangling fins,
//! holes and disconnected pieces.
//!
//! Half-edge `h = 3t + k` runs from corner `k` to corner `k+1` of triangle `t`, so the next and
//! previous half-edges of a triangle are arithmetic. Undirected edges are numbered in the sorted
//! order of their endpoints; each lists the half-edges (hence triangles) on it, in triangle order,
//! so an edge with three or more triangles is as easy to walk as a manifold one. Every vertex lists
//! its edges. Patches are the connected pieces of triangles joined across edges that carry exactly
//! two triangles (and, with parts, the same part on both sides): non-manifold edges, surface
//! borders and part seams all bound patches. Each patch has boundary loops (one outer, the others
//! inner = holes); corners (BSTONE vertices, kinks sharper than `Tolerances::kink_angle_deg`, and
//! vertices where the boundary branches or changes kind) split loops into curves.
//!
//! Everything is built with explicit loops and queues (no recursion) in index order, so the result
//! is deterministic.

mod boundary;
mod curves;

pub use boundary::BoundaryLoop;
pub use curves::Curve;

use geom::{Tolerances, TriMesh};
use serde::{Deserialize, Serialize};

pub const NONE: u32 = u32::MAX;

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SurfaceTopology {
    vertex_count: usize,
    triangles: Vec<[u32; 3]>,
    edges: Vec<[u32; 2]>,
    he_edge: Vec<u32>,
    edge_start: Vec<u32>,
    edge_hes: Vec<u32>,
    vert_start: Vec<u32>,
    vert_edges: Vec<u32>,
    triangle_patch: Vec<u32>,
    patch_start: Vec<u32>,
    patch_tris: Vec<u32>,
    /// Part of each triangle when built with parts (patch seams), else empty.
    triangle_part: Vec<u32>,
    loops: Vec<BoundaryLoop>,
    patch_loops: Vec<Vec<u32>>,
    corners: Vec<u32>,
    curves: Vec<Curve>,
    loop_curves: Vec<Vec<(u32, bool)>>,
}

impl SurfaceTopology {
    /// Builds the topology of `mesh`; `bstones` are vertices that must be corners.
    pub fn build(mesh: &TriMesh, bstones: &[u32], tol: &Tolerances) -> SurfaceTopology {
        Self::build_with_parts(mesh, &[], bstones, tol)
    }

    /// Like `build`, but edges between triangles of different parts (TFACEs) bound patches too.
    /// `triangle_part` may be empty (one part).
    pub fn build_with_parts(
        mesh: &TriMesh,
        triangle_part: &[u32],
        bstones: &[u32],
        tol: &Tolerances,
    ) -> SurfaceTopology {
        let nv = mesh.vertices.len();
        // Triangles pointing outside the vertex list are kept out (they cannot be walked).
        let triangles: Vec<[u32; 3]> = mesh.triangles.clone();
        let valid = |t: &[u32; 3]| t.iter().all(|&i| (i as usize) < nv);
        let nh = triangles.len() * 3;

        // Half-edges bucketed by their lower endpoint (counting sort), then by the upper one.
        let mut count = vec![0u32; nv + 1];
        for t in triangles.iter().filter(|t| valid(t)) {
            for k in 0..3 {
                count[t[k].min(t[(k + 1) % 3]) as usize + 1] += 1;
            }
        }
        for i in 0..nv {
            count[i + 1] += count[i];
        }
        let mut fill = count.clone();
        let mut edge_hes = vec![0u32; count[nv] as usize];
        for (ti, t) in triangles.iter().enumerate() {
            if !valid(t) {
                continue;
            }
            for k in 0..3 {
                let lo = t[k].min(t[(k + 1) % 3]) as usize;
                edge_hes[fill[lo] as usize] = (ti * 3 + k) as u32;
                fill[lo] += 1;
            }
        }
        drop(fill);
        let hi_of = |h: u32| {
            let t = &triangles[(h / 3) as usize];
            let k = (h % 3) as usize;
            t[k].max(t[(k + 1) % 3])
        };
        for v in 0..nv {
            edge_hes[count[v] as usize..count[v + 1] as usize]
                .sort_unstable_by_key(|&h| (hi_of(h), h));
        }
        let mut he_edge = vec![NONE; nh];
        let mut edges: Vec<[u32; 2]> = Vec::new();
        let mut edge_start: Vec<u32> = Vec::new();
        for v in 0..nv {
            let (a, b) = (count[v] as usize, count[v + 1] as usize);
            let mut i = a;
            while i < b {
                let hi = hi_of(edge_hes[i]);
                let e = edges.len() as u32;
                edges.push([v as u32, hi]);
                edge_start.push(i as u32);
                while i < b && hi_of(edge_hes[i]) == hi {
                    he_edge[edge_hes[i] as usize] = e;
                    i += 1;
                }
            }
        }
        edge_start.push(edge_hes.len() as u32);
        drop(count);

        // Vertex -> edges.
        let mut vert_start = vec![0u32; nv + 1];
        for e in &edges {
            vert_start[e[0] as usize + 1] += 1;
            if e[1] != e[0] {
                vert_start[e[1] as usize + 1] += 1;
            }
        }
        for i in 0..nv {
            vert_start[i + 1] += vert_start[i];
        }
        let mut vfill = vert_start.clone();
        let mut vert_edges = vec![0u32; vert_start[nv] as usize];
        for (ei, e) in edges.iter().enumerate() {
            for (j, &v) in e.iter().enumerate() {
                if j == 1 && e[1] == e[0] {
                    continue;
                }
                vert_edges[vfill[v as usize] as usize] = ei as u32;
                vfill[v as usize] += 1;
            }
        }
        drop(vfill);

        let mut topo = SurfaceTopology {
            vertex_count: nv,
            triangles,
            edges,
            he_edge,
            edge_start,
            edge_hes,
            vert_start,
            vert_edges,
            triangle_patch: Vec::new(),
            patch_start: Vec::new(),
            patch_tris: Vec::new(),
            triangle_part: triangle_part.to_vec(),
            loops: Vec::new(),
            patch_loops: Vec::new(),
            corners: Vec::new(),
            curves: Vec::new(),
            loop_curves: Vec::new(),
        };
        topo.build_patches();
        topo.build_loops(mesh);
        topo.build_corners_and_curves(mesh, bstones, tol);
        topo
    }

    fn build_patches(&mut self) {
        let nt = self.triangles.len();
        let mut patch = vec![NONE; nt];
        let mut order: Vec<u32> = Vec::with_capacity(nt);
        let mut starts = Vec::new();
        let mut stack: Vec<u32> = Vec::new();
        for seed in 0..nt {
            if patch[seed] != NONE || self.he_edge[seed * 3] == NONE {
                continue;
            }
            let p = starts.len() as u32;
            starts.push(order.len() as u32);
            patch[seed] = p;
            stack.push(seed as u32);
            while let Some(t) = stack.pop() {
                order.push(t);
                for k in 0..3 {
                    let h = t * 3 + k;
                    if let Some(o) = self.across(h) {
                        let ot = (o / 3) as usize;
                        if patch[ot] == NONE {
                            patch[ot] = p;
                            stack.push(ot as u32);
                        }
                    }
                }
            }
            let s = *starts.last().unwrap_or(&0) as usize;
            order[s..].sort_unstable();
        }
        starts.push(order.len() as u32);
        self.triangle_patch = patch;
        self.patch_start = starts;
        self.patch_tris = order;
    }

    /// The half-edge on the other side of `h` when its edge joins two triangles of one patch
    /// (exactly two triangles, same part), else `None`.
    pub fn across(&self, h: u32) -> Option<u32> {
        let e = *self.he_edge.get(h as usize)?;
        if e == NONE {
            return None;
        }
        let hs = self.edge_half_edges(e);
        let o = match hs {
            [a, b] if *a == h => *b,
            [a, b] if *b == h => *a,
            _ => return None,
        };
        if !self.triangle_part.is_empty() {
            let pa = self.triangle_part.get((h / 3) as usize);
            let pb = self.triangle_part.get((o / 3) as usize);
            if pa != pb {
                return None;
            }
        }
        Some(o)
    }

    pub fn vertex_count(&self) -> usize {
        self.vertex_count
    }
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }
    pub fn edge_count(&self) -> usize {
        self.edges.len()
    }
    pub fn triangle(&self, t: u32) -> [u32; 3] {
        self.triangles[t as usize]
    }
    /// Endpoints of edge `e`, lower index first.
    pub fn edge_vertices(&self, e: u32) -> [u32; 2] {
        self.edges[e as usize]
    }
    /// Half-edges on edge `e`, in triangle order.
    pub fn edge_half_edges(&self, e: u32) -> &[u32] {
        let (a, b) = (
            self.edge_start[e as usize] as usize,
            self.edge_start[e as usize + 1] as usize,
        );
        &self.edge_hes[a..b]
    }
    /// Triangles around edge `e` (one for a border, two inside, three or more on a non-manifold edge).
    pub fn triangles_around_edge(&self, e: u32) -> impl Iterator<Item = u32> + '_ {
        self.edge_half_edges(e).iter().map(|h| h / 3)
    }
    pub fn edge_triangle_count(&self, e: u32) -> usize {
        self.edge_half_edges(e).len()
    }
    pub fn is_non_manifold_edge(&self, e: u32) -> bool {
        self.edge_triangle_count(e) >= 3
    }
    /// Edge of each side of triangle `t`, in corner order (side k: corner k to corner k+1).
    pub fn edges_of_triangle(&self, t: u32) -> [u32; 3] {
        let b = t as usize * 3;
        [self.he_edge[b], self.he_edge[b + 1], self.he_edge[b + 2]]
    }
    pub fn half_edge(t: u32, k: u32) -> u32 {
        t * 3 + k
    }
    pub fn next_half_edge(h: u32) -> u32 {
        h - h % 3 + (h % 3 + 1) % 3
    }
    pub fn prev_half_edge(h: u32) -> u32 {
        h - h % 3 + (h % 3 + 2) % 3
    }
    pub fn edge_of(&self, h: u32) -> u32 {
        self.he_edge[h as usize]
    }
    pub fn origin(&self, h: u32) -> u32 {
        self.triangles[(h / 3) as usize][(h % 3) as usize]
    }
    pub fn target(&self, h: u32) -> u32 {
        self.triangles[(h / 3) as usize][((h % 3 + 1) % 3) as usize]
    }
    /// Edges incident to vertex `v`, in edge order.
    pub fn edges_around_vertex(&self, v: u32) -> &[u32] {
        let (a, b) = (
            self.vert_start[v as usize] as usize,
            self.vert_start[v as usize + 1] as usize,
        );
        &self.vert_edges[a..b]
    }
    /// The edge joining `a` and `b`, if any.
    pub fn edge_between(&self, a: u32, b: u32) -> Option<u32> {
        let (lo, hi) = (a.min(b), a.max(b));
        self.edges_around_vertex(lo)
            .iter()
            .copied()
            .find(|&e| self.edges[e as usize] == [lo, hi])
    }
    pub fn patch_count(&self) -> usize {
        self.patch_start.len().saturating_sub(1)
    }
    /// Triangles of patch `p`, sorted.
    pub fn patch_triangles(&self, p: u32) -> &[u32] {
        let (a, b) = (
            self.patch_start[p as usize] as usize,
            self.patch_start[p as usize + 1] as usize,
        );
        &self.patch_tris[a..b]
    }
    pub fn patch_of_triangle(&self, t: u32) -> u32 {
        self.triangle_patch[t as usize]
    }
    /// All boundary loops, ordered by patch then by first half-edge.
    pub fn boundary_loops(&self) -> &[BoundaryLoop] {
        &self.loops
    }
    /// Loops (indices into `boundary_loops`) of patch `p`, outer first.
    pub fn patch_loops(&self, p: u32) -> &[u32] {
        &self.patch_loops[p as usize]
    }
    /// Topological vertices on the boundary, sorted.
    pub fn corners(&self) -> &[u32] {
        &self.corners
    }
    /// Curves: polylines between corners (closed when a loop has no corner), each once.
    pub fn curves(&self) -> &[Curve] {
        &self.curves
    }
    /// The curves of loop `l` in loop order, with `true` when the curve runs against the loop.
    pub fn loop_curves(&self, l: u32) -> &[(u32, bool)] {
        &self.loop_curves[l as usize]
    }
    /// Heap bytes held (capacities), for memory budgets.
    pub fn heap_bytes(&self) -> usize {
        4 * (self.he_edge.capacity()
            + self.edge_start.capacity()
            + self.edge_hes.capacity()
            + self.vert_start.capacity()
            + self.vert_edges.capacity()
            + self.triangle_patch.capacity()
            + self.patch_start.capacity()
            + self.patch_tris.capacity()
            + self.triangle_part.capacity()
            + self.corners.capacity())
            + 12 * self.triangles.capacity()
            + 8 * self.edges.capacity()
            + self
                .loops
                .iter()
                .map(|l| 8 * l.vertices.capacity() + 64)
                .sum::<usize>()
            + self
                .curves
                .iter()
                .map(|c| 4 * c.vertices.capacity() + 32)
                .sum::<usize>()
    }
}
