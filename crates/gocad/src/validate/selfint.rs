//! Self-intersection search: a broad phase over triangle boxes proposes candidate pairs (a box
//! test can only skip pairs that cannot touch), and the exact `geom::contact` decides each pair
//! by the canonical vertices the two share. The broad phase is a uniform grid of boxes when
//! triangle sizes are even (the usual case, and the fastest), else an R-tree traversed against
//! itself. Pairs are judged in parallel; the result is sorted, so it does not depend on the
//! thread count.

use super::checks::TriStatus;
use geom::contact::{Contact, Tri, triangle_contact};
use rayon::prelude::*;
use rstar::primitives::{GeomWithData, Rectangle};
use rstar::{AABB, Envelope, RTree};

type Entry = GeomWithData<Rectangle<[f64; 3]>, u32>;

fn tri_box(v: &[[f64; 3]], tri: &[u32; 3]) -> AABB<[f64; 3]> {
    let [a, b, c] = tri.map(|i| v[i as usize]);
    let lo = [
        a[0].min(b[0]).min(c[0]),
        a[1].min(b[1]).min(c[1]),
        a[2].min(b[2]).min(c[2]),
    ];
    let hi = [
        a[0].max(b[0]).max(c[0]),
        a[1].max(b[1]).max(c[1]),
        a[2].max(b[2]).max(c[2]),
    ];
    AABB::from_corners(lo, hi)
}

/// How two `Ok` triangles meet, by the canonical vertices they share. A vertex `u` shares with
/// `t` is taken at `t`'s position (the two may differ by up to the merge distance), so the two
/// agree on where the shared vertex is.
pub fn judge(v: &[[f64; 3]], canon: &[u32], t: &[u32; 3], u: &[u32; 3]) -> Contact {
    let ct = t.map(|i| canon[i as usize]);
    let cu = u.map(|i| canon[i as usize]);
    let tp = t.map(|i| &v[i as usize]);
    let up = [0, 1, 2].map(|j| match ct.iter().position(|&c| c == cu[j]) {
        Some(i) => tp[i],
        None => &v[u[j] as usize],
    });
    triangle_contact(&Tri { ids: ct, pts: tp }, &Tri { ids: cu, pts: up })
}

/// All intersecting pairs `(t, u, contact)` with `t < u`, sorted.
pub fn find(
    v: &[[f64; 3]],
    tris: &[[u32; 3]],
    canon: &[u32],
    status: &[TriStatus],
) -> Vec<(u32, u32, Contact)> {
    let ok: Vec<u32> = (0..tris.len() as u32)
        .filter(|&t| status[t as usize] == TriStatus::Ok)
        .collect();
    let boxes: Vec<AABB<[f64; 3]>> = ok.iter().map(|&t| tri_box(v, &tris[t as usize])).collect();
    let mut hits = match grid_pairs(v, tris, canon, &ok, &boxes) {
        Some(h) => h,
        None => rtree_pairs(v, tris, canon, &ok, &boxes),
    };
    hits.sort_unstable_by_key(|h| (h.0, h.1));
    hits
}

/// Most cells one triangle box may cover before the grid gives way to the R-tree.
const MAX_CELLS_PER_BOX: u64 = 512;
/// Boxes over that limit the grid tolerates (they are then compared with every box).
const MAX_BIG_BOXES: usize = 64;

/// Broad phase on a uniform grid (cell ≈ 1.5 x the mean box size): every box is listed in the
/// cells it covers, and a pair is proposed only by the cell holding the lower corner of the two
/// boxes' intersection, so each overlapping pair is proposed exactly once. Returns `None` when
/// the boxes are too uneven for a grid (the R-tree takes over).
fn grid_pairs(
    v: &[[f64; 3]],
    tris: &[[u32; 3]],
    canon: &[u32],
    ok: &[u32],
    boxes: &[AABB<[f64; 3]>],
) -> Option<Vec<(u32, u32, Contact)>> {
    if boxes.is_empty() {
        return Some(Vec::new());
    }
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    let mut mean = 0.0;
    for b in boxes {
        let (l, u) = (b.lower(), b.upper());
        for k in 0..3 {
            lo[k] = lo[k].min(l[k]);
            hi[k] = hi[k].max(u[k]);
        }
        mean += (u[0] - l[0]).max(u[1] - l[1]).max(u[2] - l[2]);
    }
    mean /= boxes.len() as f64;
    let span = (hi[0] - lo[0]).max(hi[1] - lo[1]).max(hi[2] - lo[2]);
    let mut h = 1.5 * mean;
    if !(h.is_finite() && h > 0.0) {
        h = if span > 0.0 { span } else { 1.0 };
    }
    h = h.max(span / f64::from(1u32 << 20));
    // (x - lo) / h is never negative, so the saturating cast is the floor.
    let cell = |x: f64, k: usize| -> u64 { (((x - lo[k]) / h) as u64).min((1 << 21) - 1) };
    let key = |c: [u64; 3]| (c[0] << 42) | (c[1] << 21) | c[2];
    let mut big: Vec<usize> = Vec::new();
    let mut entries: Vec<(u64, u32)> = Vec::new();
    // Lower cell of every box: the cell of the lower corner of two boxes' intersection is the
    // component-wise maximum of their lower cells (the cell map is monotone).
    let mut low_cell: Vec<[u64; 3]> = Vec::with_capacity(boxes.len());
    for (i, b) in boxes.iter().enumerate() {
        let (l, u) = (b.lower(), b.upper());
        let c0 = [cell(l[0], 0), cell(l[1], 1), cell(l[2], 2)];
        low_cell.push(c0);
        let c1 = [cell(u[0], 0), cell(u[1], 1), cell(u[2], 2)];
        let n = (c1[0] - c0[0] + 1) * (c1[1] - c0[1] + 1) * (c1[2] - c0[2] + 1);
        if n > MAX_CELLS_PER_BOX {
            big.push(i);
            if big.len() > MAX_BIG_BOXES {
                return None;
            }
            continue;
        }
        for x in c0[0]..=c1[0] {
            for y in c0[1]..=c1[1] {
                for z in c0[2]..=c1[2] {
                    entries.push((key([x, y, z]), i as u32));
                }
            }
        }
    }
    entries.par_sort_unstable();
    let mut starts: Vec<usize> = Vec::new();
    for (i, e) in entries.iter().enumerate() {
        if i == 0 || entries[i - 1].0 != e.0 {
            starts.push(i);
        }
    }
    starts.push(entries.len());
    let judge_ids = |i: usize, j: usize| -> Option<(u32, u32, Contact)> {
        let (t, u) = (ok[i].min(ok[j]), ok[i].max(ok[j]));
        let c = judge(v, canon, &tris[t as usize], &tris[u as usize]);
        (c != Contact::None).then_some((t, u, c))
    };
    let mut hits: Vec<(u32, u32, Contact)> = starts
        .par_windows(2)
        .with_min_len(256)
        .flat_map_iter(|w| {
            let group = &entries[w[0]..w[1]];
            let here = group[0].0;
            let mut local = Vec::new();
            for (x, &(_, a)) in group.iter().enumerate() {
                for &(_, b) in &group[x + 1..] {
                    let (ba, bb) = (&boxes[a as usize], &boxes[b as usize]);
                    if !ba.intersects(bb) {
                        continue;
                    }
                    let (ca, cb) = (low_cell[a as usize], low_cell[b as usize]);
                    let corner = [ca[0].max(cb[0]), ca[1].max(cb[1]), ca[2].max(cb[2])];
                    if key(corner) != here {
                        continue;
                    }
                    if let Some(hit) = judge_ids(a as usize, b as usize) {
                        local.push(hit);
                    }
                }
            }
            local
        })
        .collect();
    // Big boxes against every other box (each big–big pair once).
    for (bi, &i) in big.iter().enumerate() {
        let found: Vec<(u32, u32, Contact)> = (0..boxes.len())
            .into_par_iter()
            .filter(|&j| j != i && boxes[i].intersects(&boxes[j]) && !big[..bi].contains(&j))
            .filter_map(|j| judge_ids(i, j))
            .collect();
        hits.extend(found);
    }
    Some(hits)
}

/// Broad phase by a traversal of an R-tree against itself, judged in bounded parallel batches.
fn rtree_pairs(
    v: &[[f64; 3]],
    tris: &[[u32; 3]],
    canon: &[u32],
    ok: &[u32],
    boxes: &[AABB<[f64; 3]>],
) -> Vec<(u32, u32, Contact)> {
    let entries: Vec<Entry> = ok
        .iter()
        .zip(boxes)
        .map(|(&t, b)| GeomWithData::new(Rectangle::from_aabb(*b), t))
        .collect();
    let tree = RTree::bulk_load(entries);
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
    hits
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::validate::checks::{canonical_vertices, triangle_status};
    use geom::Tolerances;

    /// A deterministic soup of small and a few large triangles that cross each other.
    fn soup(n: usize, big: usize) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
        let mut x: u64 = 0x2545_F491_4F6C_DD1D;
        let mut rnd = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x % 1_000_000) as f64 / 1000.0
        };
        let mut v = Vec::new();
        let mut t = Vec::new();
        for i in 0..n + big {
            let s = if i < n { 8.0 } else { 900.0 };
            let o = [rnd(), rnd(), rnd() / 10.0];
            let b = v.len() as u32;
            v.push(o);
            v.push([
                o[0] + s * rnd() / 1000.0,
                o[1] + s * rnd() / 1000.0,
                o[2] + s * rnd() / 1000.0,
            ]);
            v.push([
                o[0] - s * rnd() / 1000.0,
                o[1] + s * rnd() / 1000.0,
                o[2] - s * rnd() / 1000.0,
            ]);
            t.push([b, b + 1, b + 2]);
        }
        (v, t)
    }

    type Hits = Vec<(u32, u32, Contact)>;

    fn both(n: usize, big: usize) -> (Option<Hits>, Hits) {
        let (v, t) = soup(n, big);
        let canon = canonical_vertices(&v, &Tolerances::default());
        let status = triangle_status(&v, &t, &canon);
        let ok: Vec<u32> = (0..t.len() as u32)
            .filter(|&i| status[i as usize] == TriStatus::Ok)
            .collect();
        let boxes: Vec<_> = ok.iter().map(|&i| tri_box(&v, &t[i as usize])).collect();
        let mut g = grid_pairs(&v, &t, &canon, &ok, &boxes);
        if let Some(g) = g.as_mut() {
            g.sort_unstable_by_key(|h| (h.0, h.1));
        }
        let mut r = rtree_pairs(&v, &t, &canon, &ok, &boxes);
        r.sort_unstable_by_key(|h| (h.0, h.1));
        (g, r)
    }

    #[test]
    fn the_grid_and_the_rtree_propose_the_same_intersections() {
        let (g, r) = both(3000, 20);
        assert!(!r.is_empty());
        assert_eq!(g.expect("grid handles 20 big boxes"), r);
    }

    #[test]
    fn too_many_big_boxes_fall_back_to_the_rtree() {
        let (g, r) = both(5000, 100);
        assert!(g.is_none());
        assert!(!r.is_empty());
    }
}
