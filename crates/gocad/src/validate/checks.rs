//! The combinatorial and exact per-entity checks of the black-list: coincident vertices (the
//! canonical vertex of every vertex), unreferenced vertices, degenerate triangles (exactly
//! collinear corners), duplicate triangles, and the edge table from which inconsistent
//! orientation and non-manifold edges are read.
//!
//! Adjacency is taken on canonical vertices (coincident vertices merged), so the seams between
//! TFACEs that repeat their vertices are seen as the shared edges they are geometrically.

use geom::Tolerances;
use geom::contact::collinear;

/// For every vertex, the smallest index of the vertices coincident with it. With
/// `merge_distance == 0` coincident means equal coordinates (exact); otherwise within that
/// Euclidean distance (transitively, by union-find over a grid of cells of that size).
pub fn canonical_vertices(v: &[[f64; 3]], tol: &Tolerances) -> Vec<u32> {
    let n = v.len();
    let mut order: Vec<u32> = (0..n as u32).collect();
    let key = |i: u32| v[i as usize];
    order.sort_unstable_by(|&a, &b| {
        let (p, q) = (key(a), key(b));
        p[0].total_cmp(&q[0])
            .then(p[1].total_cmp(&q[1]))
            .then(p[2].total_cmp(&q[2]))
            .then(a.cmp(&b))
    });
    let mut parent: Vec<u32> = (0..n as u32).collect();
    fn find(parent: &mut [u32], mut x: u32) -> u32 {
        while parent[x as usize] != x {
            let g = parent[parent[x as usize] as usize];
            parent[x as usize] = g;
            x = g;
        }
        x
    }
    fn union(parent: &mut [u32], a: u32, b: u32) {
        let (ra, rb) = (find(parent, a), find(parent, b));
        if ra != rb {
            let (lo, hi) = if ra < rb { (ra, rb) } else { (rb, ra) };
            parent[hi as usize] = lo;
        }
    }
    let d = tol.merge_distance;
    if d > 0.0 {
        // Cells a hair larger than d (so rounding of c / side cannot split a pair at distance d
        // by two cells): vertices within d of each other are in the same or adjacent cells.
        let side = d * (1.0 + 1e-9);
        let cell = |p: [f64; 3]| p.map(|c| (c / side).floor() as i64);
        let mut cells: Vec<([i64; 3], u32)> = (0..n as u32).map(|i| (cell(key(i)), i)).collect();
        cells.sort_unstable();
        for &(c, i) in &cells {
            let p = key(i);
            for dx in -1..=1i64 {
                for dy in -1..=1i64 {
                    for dz in -1..=1i64 {
                        let nc = [
                            c[0].saturating_add(dx),
                            c[1].saturating_add(dy),
                            c[2].saturating_add(dz),
                        ];
                        let start = cells.partition_point(|e| e.0 < nc);
                        for &(ec, j) in &cells[start..] {
                            if ec != nc {
                                break;
                            }
                            if j <= i {
                                continue;
                            }
                            let q = key(j);
                            let dd = (q[0] - p[0]).powi(2)
                                + (q[1] - p[1]).powi(2)
                                + (q[2] - p[2]).powi(2);
                            if dd <= d * d {
                                union(&mut parent, i, j);
                            }
                        }
                    }
                }
            }
        }
    } else {
        for w in order.windows(2) {
            if key(w[0]) == key(w[1]) {
                union(&mut parent, w[0], w[1]);
            }
        }
    }
    (0..n as u32).map(|i| find(&mut parent, i)).collect()
}

/// Why a triangle takes no part in adjacency.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum TriStatus {
    Ok,
    /// Two corners are the same (canonical) vertex, or the three are exactly collinear.
    Degenerate,
    /// Same canonical vertex set as the earlier triangle `0`.
    DuplicateOf(u32),
}

/// Classifies every triangle (degenerate, duplicate of an earlier one, or ok).
pub fn triangle_status(v: &[[f64; 3]], tris: &[[u32; 3]], canon: &[u32]) -> Vec<TriStatus> {
    let mut status = vec![TriStatus::Ok; tris.len()];
    let mut keys: Vec<([u32; 3], u32)> = Vec::with_capacity(tris.len());
    for (t, tri) in tris.iter().enumerate() {
        let c = tri.map(|i| canon[i as usize]);
        let [a, b, d] = tri.map(|i| &v[i as usize]);
        if c[0] == c[1] || c[1] == c[2] || c[0] == c[2] || collinear(a, b, d) {
            status[t] = TriStatus::Degenerate;
            continue;
        }
        let mut k = c;
        k.sort_unstable();
        keys.push((k, t as u32));
    }
    keys.sort_unstable();
    for w in keys.chunk_by(|a, b| a.0 == b.0) {
        for e in &w[1..] {
            status[e.1 as usize] = TriStatus::DuplicateOf(w[0].1);
        }
    }
    status
}

/// One triangle side on an undirected canonical edge.
#[derive(Clone, Copy, Debug)]
pub struct Side {
    /// `lo << 32 | hi` of the canonical endpoints.
    pub key: u64,
    pub tri: u32,
    /// Which side of the triangle: corner `k` to corner `k+1`.
    pub k: u8,
    /// Whether the triangle runs from `lo` to `hi` along the edge.
    pub forward: bool,
}

/// The sides of all `Ok` triangles, grouped by edge (sorted by key, then triangle).
pub fn edge_sides(tris: &[[u32; 3]], canon: &[u32], status: &[TriStatus]) -> Vec<Side> {
    // Counting sort by the lower endpoint, then a small sort inside each bucket: the same order
    // as sorting by (key, tri, k), in linear time for meshes of bounded degree.
    let nv = canon.len();
    let side = |t: usize, k: usize| {
        let tri = &tris[t];
        let a = canon[tri[k] as usize];
        let b = canon[tri[(k + 1) % 3] as usize];
        let (lo, hi) = if a < b { (a, b) } else { (b, a) };
        Side {
            key: (u64::from(lo) << 32) | u64::from(hi),
            tri: t as u32,
            k: k as u8,
            forward: a < b,
        }
    };
    let mut start = vec![0usize; nv + 1];
    for (t, _) in tris
        .iter()
        .enumerate()
        .filter(|(t, _)| status[*t] == TriStatus::Ok)
    {
        for k in 0..3 {
            start[(side(t, k).key >> 32) as usize + 1] += 1;
        }
    }
    for i in 0..nv {
        start[i + 1] += start[i];
    }
    let mut fill = start.clone();
    let empty = Side {
        key: 0,
        tri: 0,
        k: 0,
        forward: false,
    };
    let mut sides = vec![empty; start[nv]];
    for (t, _) in tris
        .iter()
        .enumerate()
        .filter(|(t, _)| status[*t] == TriStatus::Ok)
    {
        for k in 0..3 {
            let sd = side(t, k);
            let lo = (sd.key >> 32) as usize;
            sides[fill[lo]] = sd;
            fill[lo] += 1;
        }
    }
    for v in 0..nv {
        sides[start[v]..start[v + 1]].sort_unstable_by_key(|s| (s.key, s.tri, s.k));
    }
    sides
}

/// Endpoints of an edge key.
pub fn key_vertices(key: u64) -> [u32; 2] {
    [(key >> 32) as u32, key as u32]
}
