//! Self-intersection search: an R-tree of triangle boxes proposes candidate pairs (a box test can
//! only skip pairs that cannot touch), and the exact tests of `intersect` decide each pair. The
//! candidate pairs come from one traversal of the tree against itself; they are judged in
//! parallel in bounded batches, and the result is sorted, so it does not depend on the thread count.

use super::checks::TriStatus;
use super::intersect::{Contact, disjoint_pair, edge_pair, vertex_pair};
use rayon::prelude::*;
use rstar::primitives::{GeomWithData, Rectangle};
use rstar::{AABB, RTree};


type Entry = GeomWithData<Rectangle<[f64; 3]>, u32>;

fn tri_box(v: &[[f64; 3]], tri: &[u32; 3]) -> AABB<[f64; 3]> {
    let [a, b, c] = tri.map(|i| v[i as usize]);
    let lo = [a[0].min(b[0]).min(c[0]), a[1].min(b[1]).min(c[1]), a[2].min(b[2]).min(c[2])];
    let hi = [a[0].max(b[0]).max(c[0]), a[1].max(b[1]).max(c[1]), a[2].max(b[2]).max(c[2])];
    AABB::from_corners(lo, hi)
}

/// Judges one pair of `Ok` triangles by the canonical vertices they share.
pub fn judge(v: &[[f64; 3]], canon: &[u32], t: &[u32; 3], u: &[u32; 3]) -> Contact {
    let ct = t.map(|i| canon[i as usize]);
    let cu = u.map(|i| canon[i as usize]);
    let p = |i: u32| &v[i as usize];
    let mut buf = [(0usize, 0usize); 3];
    let mut n = 0;
    for i in 0..3 {
        for j in 0..3 {
            if ct[i] == cu[j] && n < 3 {
                buf[n] = (i, j);
                n += 1;
            }
        }
    }
    match &buf[..n] {
        [] => disjoint_pair(t.map(p), u.map(p)),
        [(i, j)] => {
            let (a, b) = (t[(i + 1) % 3], t[(i + 2) % 3]);
            let (c, d) = (u[(j + 1) % 3], u[(j + 2) % 3]);
            vertex_pair(p(t[*i]), p(a), p(b), p(c), p(d))
        }
        [(i0, j0), (i1, _)] => {
            let a = t[3 - i0 - i1];
            let j2 = (0..3).find(|&j| cu[j] != ct[*i0] && cu[j] != ct[*i1]).unwrap_or(*j0);
            edge_pair(p(t[*i0]), p(t[*i1]), p(a), p(u[j2]))
        }
        _ => Contact::None,
    }
}

/// All intersecting pairs `(t, u, contact)` with `t < u`, sorted.
pub fn find(v: &[[f64; 3]], tris: &[[u32; 3]], canon: &[u32], status: &[TriStatus]) -> Vec<(u32, u32, Contact)> {
    let entries: Vec<Entry> = tris
        .iter()
        .enumerate()
        .filter(|(t, _)| status[*t] == TriStatus::Ok)
        .map(|(t, tri)| {
            let b = tri_box(v, tri);
            GeomWithData::new(Rectangle::from_aabb(b), t as u32)
        })
        .collect();
    let tree = RTree::bulk_load(entries);
    // A simultaneous traversal of the tree with itself proposes each overlapping pair (both ways);
    // pairs are judged in parallel in fixed-size batches, so memory stays bounded.
    const BATCH: usize = 1 << 18;
    let mut batch: Vec<(u32, u32)> = Vec::with_capacity(BATCH);
    let mut hits: Vec<(u32, u32, Contact)> = Vec::new();
    let judge_batch = |batch: &[(u32, u32)], hits: &mut Vec<(u32, u32, Contact)>| {
        let found: Vec<(u32, u32, Contact)> = batch
            .par_iter()
            .with_min_len(4096)
            .filter_map(|&(t, u)| {
                let c = judge(v, canon, &tris[t as usize], &tris[u as usize]);
                (c != Contact::None).then_some((t, u, c))
            })
            .collect();
        hits.extend(found);
    };
    for (a, b) in tree.intersection_candidates_with_other_tree(&tree) {
        if a.data < b.data {
            batch.push((a.data, b.data));
            if batch.len() == BATCH {
                judge_batch(&batch, &mut hits);
                batch.clear();
            }
        }
    }
    judge_batch(&batch, &mut hits);
    hits.sort_unstable_by_key(|h| (h.0, h.1));
    hits
}
