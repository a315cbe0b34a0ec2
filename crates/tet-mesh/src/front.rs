//! The advancing front: oriented triangles whose right-hand normal points into the part of the
//! region not yet meshed, with a priority queue (smallest face first, ties by id so the order is
//! deterministic) and a uniform grid over face bounding boxes for the locality queries of the
//! exact validity tests. A face is found by its canonical rotation, so the two sides of an
//! embedded triangle are two distinct front faces. A second grid over the same cells holds the
//! front's nodes (each once, in the cell of its position), so the wide candidate search of a
//! stuck face scans nodes, not the several cells each face's box covers.
//!
//! Cost at scale: cells list live faces only (a removed face leaves its cells at once), a query
//! de-duplicates by cell position rather than by a per-face stamp, so it reads nothing indexed
//! by face id; and the face grid doubles its cells when faces outgrow them (interior sizes grow
//! away from the boundary that set the first cell size), so faces meet and queries visit a
//! bounded number of cells whatever the region's size.

use std::cmp::Reverse;
use std::collections::{BinaryHeap, HashMap, HashSet};
use std::hash::{BuildHasherDefault, Hasher};

use super::verify::canon;

type P = [f64; 3];

/// Face-grid cells per node-grid cell along each axis.
const NODE_CELLS: usize = 2;

/// The face grid is coarsened when live faces meet more than this many cells each on average
/// (about 2.5 per axis: faces about twice the cell size)...
const COARSEN_AT: usize = 16;
/// ... and the front has at least this many faces (small fronts are cheap anyway).
const COARSEN_MIN_FACES: usize = 1024;

/// One face listed in one grid cell. `first` has bit k set when the face's cell range starts at
/// this cell along axis k: a box query reports the face only in the first cell of the overlap of
/// the two ranges (where, along each axis, the face starts or the query does), so each face comes
/// out once without a per-face "already listed" stamp — the query reads only the cell lists,
/// never an array indexed by face id, whose random accesses dominated on large regions.
#[derive(Clone, Copy)]
struct Entry {
    id: u32,
    first: u8,
}

pub struct Front {
    pub faces: Vec<[u32; 3]>,
    pub alive: Vec<bool>,
    map: FaceMap<u32>,
    heap: BinaryHeap<Reverse<(u64, u32)>>,
    /// Dense grid over the region's bounding box; points outside clamp to the border cells
    /// (monotone, so box overlaps are preserved). Cells list live faces only: a removed face
    /// leaves its cells at once (order-preserving), so no query skips dead entries.
    cells: Vec<Vec<Entry>>,
    dims: [usize; 3],
    origin: P,
    inv_cell: f64,
    /// The box's extent, for re-gridding.
    ext: P,
    /// Grid entries (face, cell) of live faces: their mean per face says whether the faces have
    /// outgrown the cells (see `coarsen`).
    entries: usize,
    /// The first grid's cell, which the node grids keep for good.
    inv_cell0: f64,
    dims0: [usize; 3],
    /// Per face: the linear indices of the first and last cells of its range.
    range: Vec<[u32; 2]>,
    pub n_alive: usize,
    /// Nodes by cell: exactly the nodes with live faces (a node leaves its cell when its last
    /// live face is removed).
    node_cells: Vec<Vec<u32>>,
    /// Live front faces using each node.
    node_deg: Vec<u32>,
    /// Per node: its node-grid cell (set when it is listed).
    node_cell: Vec<u32>,
    /// The node grids' cells: `NODE_CELLS`³ face-grid cells each (points are stored once, so
    /// coarser cells cost nothing at insertion and make wide searches visit far fewer cells).
    ndims: [usize; 3],
    /// Every node ever placed (input vertices and interior nodes), by cell: for back-tracking.
    all_nodes: Vec<Vec<u32>>,
}

impl Front {
    /// A front over the box `lo..hi` with grid cells of about `cell` (enlarged to keep the grid
    /// under a million cells).
    pub fn new(lo: P, hi: P, cell: f64) -> Self {
        let mut cell = if cell.is_finite() && cell > 0.0 {
            cell
        } else {
            1.0
        };
        let ext = [0, 1, 2].map(|k| {
            if (hi[k] - lo[k]).is_finite() {
                (hi[k] - lo[k]).max(0.0)
            } else {
                0.0
            }
        });
        let dims_for =
            |c: f64| ext.map(|e| ((e / c).floor() as usize).saturating_add(1).min(1 << 20));
        let mut dims = dims_for(cell);
        while dims[0].saturating_mul(dims[1]).saturating_mul(dims[2]) > 1_000_000 {
            cell *= 1.5;
            dims = dims_for(cell);
        }
        let nd = dims.map(|d| d.div_ceil(NODE_CELLS));
        Front {
            faces: Vec::new(),
            alive: Vec::new(),
            map: FaceMap::default(),
            heap: BinaryHeap::new(),
            cells: vec![Vec::new(); dims[0] * dims[1] * dims[2]],
            dims,
            origin: lo,
            inv_cell: 1.0 / cell,
            ext,
            entries: 0,
            inv_cell0: 1.0 / cell,
            dims0: dims,
            range: Vec::new(),
            n_alive: 0,
            node_cells: vec![Vec::new(); nd[0] * nd[1] * nd[2]],
            node_deg: Vec::new(),
            node_cell: Vec::new(),
            ndims: nd,
            all_nodes: vec![Vec::new(); nd[0] * nd[1] * nd[2]],
        }
    }

    #[inline]
    fn cell_of(&self, p: &P) -> [usize; 3] {
        let mut c = [0usize; 3];
        for k in 0..3 {
            let v = ((p[k] - self.origin[k]) * self.inv_cell).floor();
            c[k] = if v.is_nan() || v < 0.0 {
                0
            } else {
                (v as usize).min(self.dims[k] - 1)
            };
        }
        c
    }

    #[inline]
    fn index(&self, x: usize, y: usize, z: usize) -> usize {
        x + self.dims[0] * (y + self.dims[1] * z)
    }

    /// The cell coordinates of a linear cell index.
    #[inline]
    fn coords(&self, i: usize) -> [usize; 3] {
        let (x, yz) = (i % self.dims[0], i / self.dims[0]);
        [x, yz % self.dims[1], yz / self.dims[1]]
    }

    /// The node-grid cell of `p`: `NODE_CELLS`³ cells of the first face grid (the node grids
    /// never change, even when the face grid is coarsened).
    #[inline]
    fn ncell(&self, p: &P) -> [usize; 3] {
        let mut c = [0usize; 3];
        for k in 0..3 {
            let v = ((p[k] - self.origin[k]) * self.inv_cell0).floor();
            c[k] = if v.is_nan() || v < 0.0 {
                0
            } else {
                (v as usize).min(self.dims0[k] - 1)
            } / NODE_CELLS;
        }
        c
    }

    #[inline]
    fn nindex(&self, c: [usize; 3]) -> usize {
        c[0] + self.ndims[0] * (c[1] + self.ndims[1] * c[2])
    }

    /// Id of the live face with exactly this orientation, if any.
    #[inline]
    pub fn find(&self, f: [u32; 3]) -> Option<u32> {
        self.map.get(&canon(f)).copied()
    }

    /// Add an oriented face; `key` orders the queue (smaller first).
    pub fn add(&mut self, f: [u32; 3], key: f64, pts: &[P]) -> u32 {
        let id = self.faces.len() as u32;
        self.faces.push(f);
        self.alive.push(true);
        self.map.insert(canon(f), id);
        self.heap.push(Reverse((key.max(0.0).to_bits(), id)));
        self.n_alive += 1;
        for &v in &f {
            let i = v as usize;
            if self.node_deg.len() <= i {
                self.node_deg.resize(i + 1, 0);
                self.node_cell.resize(i + 1, 0);
            }
            self.node_deg[i] += 1;
            if self.node_deg[i] == 1 {
                let k = self.nindex(self.ncell(&pts[i]));
                self.node_cell[i] = k as u32;
                self.node_cells[k].push(v);
            }
        }
        self.range.push([0, 0]);
        self.insert(id, pts);
        if self.n_alive >= COARSEN_MIN_FACES && self.entries > COARSEN_AT * self.n_alive {
            self.coarsen(pts);
        }
        id
    }

    /// List face `id` in the cells its bounding box meets.
    fn insert(&mut self, id: u32, pts: &[P]) {
        let f = self.faces[id as usize];
        let (lo, hi) = bbox_of(f.iter().map(|&i| &pts[i as usize]));
        let (cl, ch) = (self.cell_of(&lo), self.cell_of(&hi));
        self.range[id as usize] = [
            self.index(cl[0], cl[1], cl[2]) as u32,
            self.index(ch[0], ch[1], ch[2]) as u32,
        ];
        for z in cl[2]..=ch[2] {
            for y in cl[1]..=ch[1] {
                for x in cl[0]..=ch[0] {
                    let first =
                        (x == cl[0]) as u8 | ((y == cl[1]) as u8) << 1 | ((z == cl[2]) as u8) << 2;
                    let i = self.index(x, y, z);
                    self.cells[i].push(Entry { id, first });
                    self.entries += 1;
                }
            }
        }
    }

    /// The faces have outgrown the cells (interior sizes grow away from the boundary, which set
    /// the first cell size): double the cell size and list the live faces again, in id order so
    /// each cell keeps insertion order. Each face then meets about 8× fewer cells, and queries
    /// (boxes of a few local sizes) visit 8× fewer cells: without it both grow with the ratio of
    /// interior to boundary sizes, which is what made large regions slower per tetrahedron.
    fn coarsen(&mut self, pts: &[P]) {
        let cell = 2.0 / self.inv_cell;
        let dims = self
            .ext
            .map(|e| ((e / cell).floor() as usize).saturating_add(1).min(1 << 20));
        if dims == self.dims {
            return;
        }
        self.dims = dims;
        self.inv_cell = 1.0 / cell;
        self.cells = vec![Vec::new(); dims[0] * dims[1] * dims[2]];
        self.entries = 0;
        for id in 0..self.faces.len() as u32 {
            if self.alive[id as usize] {
                self.insert(id, pts);
            }
        }
    }

    /// Record a node (never moved afterwards) for `nodes_near`.
    pub fn add_node(&mut self, v: u32, p: &P) {
        let k = self.nindex(self.ncell(p));
        self.all_nodes[k].push(v);
    }

    /// Every recorded node whose cell meets the box `lo..hi` (a superset of the nodes in it).
    pub fn nodes_near(&self, lo: &P, hi: &P, out: &mut Vec<u32>) {
        out.clear();
        let (cl, ch) = (self.ncell(lo), self.ncell(hi));
        for z in cl[2]..=ch[2] {
            for y in cl[1]..=ch[1] {
                for x in cl[0]..=ch[0] {
                    out.extend_from_slice(&self.all_nodes[self.nindex([x, y, z])]);
                }
            }
        }
    }

    pub fn remove(&mut self, id: u32) {
        let i = id as usize;
        if !self.alive.get(i).copied().unwrap_or(false) {
            return;
        }
        self.alive[i] = false;
        self.map.remove(&canon(self.faces[i]));
        self.n_alive -= 1;
        for v in self.faces[i] {
            let w = v as usize;
            self.node_deg[w] -= 1;
            if self.node_deg[w] == 0 {
                let cell = &mut self.node_cells[self.node_cell[w] as usize];
                if let Some(at) = cell.iter().position(|&u| u == v) {
                    cell.remove(at);
                }
            }
        }
        let [a, b] = self.range[i];
        let (cl, ch) = (self.coords(a as usize), self.coords(b as usize));
        for z in cl[2]..=ch[2] {
            for y in cl[1]..=ch[1] {
                for x in cl[0]..=ch[0] {
                    let c = self.index(x, y, z);
                    let cell = &mut self.cells[c];
                    if let Some(at) = cell.iter().position(|e| e.id == id) {
                        cell.remove(at);
                        self.entries -= 1;
                    }
                }
            }
        }
    }

    /// Put a live face back in the queue (after it was popped and could not be meshed yet).
    pub fn requeue(&mut self, id: u32, key: f64) {
        if self.alive[id as usize] {
            self.heap.push(Reverse((key.max(0.0).to_bits(), id)));
        }
    }

    /// The live face with the smallest key.
    pub fn pop(&mut self) -> Option<u32> {
        while let Some(Reverse((_, id))) = self.heap.pop() {
            if self.alive[id as usize] {
                return Some(id);
            }
        }
        None
    }

    /// Live faces whose bounding-box cells meet the box `lo..hi`, each once, in an order fixed
    /// by the history of the front (callers only use order-independent results): cell order
    /// (z, y, x), and within a cell the order of insertion.
    pub fn query(&mut self, lo: &P, hi: &P, out: &mut Vec<u32>) {
        out.clear();
        let (cl, ch) = (self.cell_of(lo), self.cell_of(hi));
        for z in cl[2]..=ch[2] {
            let fz = if z == cl[2] { 4 } else { 0 };
            for y in cl[1]..=ch[1] {
                let fy = if y == cl[1] { 2 } else { 0 };
                let row = self.index(0, y, z);
                for x in cl[0]..=ch[0] {
                    let fx = if x == cl[0] { 1 } else { 0 };
                    // Axes along which this cell is the query's first: a face is reported here
                    // when, along every other axis, its range starts here.
                    let need = 7 & !(fx | fy | fz);
                    for e in &self.cells[row + x] {
                        if e.first & need == need {
                            out.push(e.id);
                        }
                    }
                }
            }
        }
    }
}

impl Front {
    /// Nodes of live front faces whose cell meets the box `lo..hi` (so every such node inside
    /// the box, and some near it), each once, in cell order.
    pub fn query_nodes(&mut self, lo: &P, hi: &P, out: &mut Vec<u32>) {
        out.clear();
        let (cl, ch) = (self.ncell(lo), self.ncell(hi));
        for z in cl[2]..=ch[2] {
            for y in cl[1]..=ch[1] {
                for x in cl[0]..=ch[0] {
                    out.extend_from_slice(&self.node_cells[self.nindex([x, y, z])]);
                }
            }
        }
    }
}

/// A map keyed by triangles (node triples), hashed with a multiply-xorshift over the 32-bit
/// words: the front's lookups are on the hot path and the keys are not adversarial. Never
/// iterated, so its order reaches no output.
pub type FaceMap<V> = HashMap<[u32; 3], V, BuildHasherDefault<WordHasher>>;

/// A set of node ids or tuples hashed as [`FaceMap`] is, for the meshers' hot loops; never
/// iterated into an output.
pub type WordSet<K> = HashSet<K, BuildHasherDefault<WordHasher>>;

#[derive(Default)]
pub struct WordHasher(u64);

impl Hasher for WordHasher {
    #[inline]
    fn finish(&self) -> u64 {
        let h = self.0 ^ (self.0 >> 29);
        h.wrapping_mul(0xbf58_476d_1ce4_e5b9) ^ (h >> 32)
    }
    #[inline]
    fn write(&mut self, bytes: &[u8]) {
        let mut chunks = bytes.chunks_exact(4);
        for c in &mut chunks {
            self.write_u32(u32::from_le_bytes([c[0], c[1], c[2], c[3]]));
        }
        for &b in chunks.remainder() {
            self.write_u32(b as u32);
        }
    }
    #[inline]
    fn write_u32(&mut self, i: u32) {
        self.0 = (self.0.rotate_left(23) ^ i as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15);
    }
    #[inline]
    fn write_usize(&mut self, i: usize) {
        self.write_u32(i as u32);
        self.write_u32((i >> 32) as u32);
    }
}

pub fn bbox_of<'a>(it: impl Iterator<Item = &'a P>) -> (P, P) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in it {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    (lo, hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 4x4 grid of unit squares (two triangles each) in the plane z = 0, and one node above.
    fn sheet() -> (Vec<P>, Vec<[u32; 3]>) {
        let mut pts = Vec::new();
        for j in 0..5 {
            for i in 0..5 {
                pts.push([i as f64, j as f64, 0.0]);
            }
        }
        pts.push([2.0, 2.0, 3.0]);
        let mut tris = Vec::new();
        for j in 0..4u32 {
            for i in 0..4u32 {
                let a = i + 5 * j;
                tris.push([a, a + 1, a + 6]);
                tris.push([a, a + 6, a + 5]);
            }
        }
        (pts, tris)
    }

    #[test]
    fn the_wide_node_search_lists_each_live_front_node_once_and_drops_nodes_left_without_faces() {
        let (pts, tris) = sheet();
        let mut front = Front::new([0.0; 3], [4.0, 4.0, 3.0], 0.5);
        let ids: Vec<u32> = tris.iter().map(|&t| front.add(t, 1.0, &pts)).collect();
        let mut out = Vec::new();
        front.query_nodes(&[-1.0; 3], &[5.0, 5.0, 4.0], &mut out);
        let mut sorted = out.clone();
        sorted.sort_unstable();
        sorted.dedup();
        assert_eq!(sorted.len(), out.len(), "a node listed twice");
        assert_eq!(sorted, (0..25).collect::<Vec<u32>>());
        // Remove the two triangles at the corner (0, 0): node 0 has no live face left.
        front.remove(ids[0]);
        front.remove(ids[1]);
        front.query_nodes(&[-1.0; 3], &[5.0, 5.0, 4.0], &mut out);
        assert!(!out.contains(&0));
        assert!(out.contains(&1) && out.contains(&5) && out.contains(&6));
        // Faces: the removed ones are gone from the box query, the others are there once.
        let mut faces = Vec::new();
        front.query(&[-1.0; 3], &[5.0, 5.0, 4.0], &mut faces);
        faces.sort_unstable();
        assert_eq!(faces, ids[2..].to_vec());
    }

    #[test]
    fn after_coarsening_a_box_query_lists_every_live_face_meeting_it_once_and_no_removed_face() {
        // Triangles of growing size (up to 8 cells across) scattered over a 40-cell box, so the
        // faces outgrow the cells and the grid is coarsened while they are added.
        let mut seed = 12345u64;
        let mut rnd = move || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut pts: Vec<P> = Vec::new();
        let mut tris = Vec::new();
        for i in 0..3000u32 {
            let s = 0.5 + 8.0 * i as f64 / 3000.0;
            let o = [rnd() * 40.0, rnd() * 40.0, rnd() * 40.0];
            for _ in 0..3 {
                pts.push([0, 1, 2].map(|k| o[k] + s * rnd()));
            }
            tris.push([3 * i, 3 * i + 1, 3 * i + 2]);
        }
        let mut front = Front::new([0.0; 3], [50.0; 3], 1.0);
        let ids: Vec<u32> = tris.iter().map(|&t| front.add(t, 1.0, &pts)).collect();
        assert!(front.inv_cell < 1.0, "the grid was not coarsened");
        for &id in ids.iter().step_by(3) {
            front.remove(id);
        }
        let mut out = Vec::new();
        for _ in 0..50 {
            let c = [rnd() * 45.0, rnd() * 45.0, rnd() * 45.0];
            let r = 0.5 + 4.0 * rnd();
            let (lo, hi) = (c.map(|x| x - r), c.map(|x| x + r));
            front.query(&lo, &hi, &mut out);
            let mut sorted = out.clone();
            sorted.sort_unstable();
            sorted.dedup();
            assert_eq!(sorted.len(), out.len(), "a face listed twice");
            for (i, &id) in ids.iter().enumerate() {
                let (flo, fhi) = bbox_of(tris[i].iter().map(|&v| &pts[v as usize]));
                let meets = (0..3).all(|k| flo[k] <= hi[k] && fhi[k] >= lo[k]);
                let live = i % 3 != 0;
                if live && meets {
                    assert!(sorted.binary_search(&id).is_ok(), "face {id} missed");
                }
                if !live {
                    assert!(
                        sorted.binary_search(&id).is_err(),
                        "removed face {id} listed"
                    );
                }
            }
        }
    }

    #[test]
    fn the_back_tracking_node_search_finds_every_recorded_node_in_its_box() {
        let (pts, _) = sheet();
        let mut front = Front::new([0.0; 3], [4.0, 4.0, 3.0], 0.5);
        for (v, p) in pts.iter().enumerate() {
            front.add_node(v as u32, p);
        }
        let (lo, hi) = ([1.5, 1.5, -0.5], [2.5, 2.5, 3.5]);
        let mut out = Vec::new();
        front.nodes_near(&lo, &hi, &mut out);
        for (v, p) in pts.iter().enumerate() {
            if (0..3).all(|k| lo[k] <= p[k] && p[k] <= hi[k]) {
                assert!(out.contains(&(v as u32)), "node {v} at {p:?} missed");
            }
        }
        assert!(out.contains(&25) && out.contains(&12));
        assert!(!out.contains(&0), "a far node listed");
    }
}
