//! Cutting one triangle along curve chains that do not cross each other: each chain runs from
//! the triangle's border to its border (through any number of inner points) or ends inside it
//! (a dangling fault end, joined to a polygon vertex it sees by an extra, non-curve edge). The
//! polygon is cut chain by chain; each piece is then ear-clipped by the caller. Every decision
//! (which piece a chain enters, which vertex a dangling end sees) is an exact `orient2d` test.

use super::SplitError;
use crate::geom::{Orientation, orient2d};
use std::collections::BTreeMap;

/// Polygons (vertex cycles) and locked edges (sorted vertex pairs).
pub(super) type Pieces = (Vec<Vec<u32>>, Vec<[u32; 2]>);

/// The pieces of polygon `boundary` (oriented as `sign` in `pt`) cut along the chords `segs`
/// (sorted, deduplicated, none a piece of the boundary), and the chains' edges (to lock).
pub(super) fn cut(
    boundary: &[u32],
    segs: &[[u32; 2]],
    pt: &dyn Fn(u32) -> [f64; 2],
    sign: Orientation,
    err: &dyn Fn(&str, u32) -> SplitError,
) -> Result<Pieces, SplitError> {
    let on_boundary = |v: u32| boundary.contains(&v);
    let mut adj: BTreeMap<u32, Vec<u32>> = BTreeMap::new();
    for s in segs {
        adj.entry(s[0]).or_default().push(s[1]);
        adj.entry(s[1]).or_default().push(s[0]);
    }
    for (&v, n) in &adj {
        if !on_boundary(v) && n.len() > 2 {
            return Err(err("curves branch inside this face", v));
        }
    }
    let mut used = vec![false; segs.len()];
    let seg_id = |a: u32, b: u32| segs.binary_search(&[a.min(b), a.max(b)]).ok();
    let mut chains: Vec<Vec<u32>> = Vec::new();
    for (&start, nbrs) in &adj {
        if !on_boundary(start) {
            continue;
        }
        for &first in nbrs {
            let Some(s0) = seg_id(start, first) else {
                continue;
            };
            if used[s0] {
                continue;
            }
            used[s0] = true;
            let mut chain = vec![start, first];
            let mut cur = first;
            while !on_boundary(cur) {
                let prev = chain[chain.len() - 2];
                let next = adj
                    .get(&cur)
                    .and_then(|n| n.iter().copied().find(|&w| w != prev));
                let Some(next) = next else {
                    break; // a dangling end, joined to the polygon below
                };
                if let Some(s) = seg_id(cur, next) {
                    used[s] = true;
                }
                chain.push(next);
                cur = next;
            }
            chains.push(chain);
        }
    }
    if let Some(i) = used.iter().position(|u| !u) {
        return Err(err("a curve lies entirely inside this face", segs[i][0]));
    }
    // Cut the polygon along each chain.
    let mut polys: Vec<Vec<u32>> = vec![boundary.to_vec()];
    for chain in &chains {
        let mut chain = chain.clone();
        let s = chain[0];
        let pi = polys.iter().position(|p| {
            p.contains(&s)
                && (!on_boundary(chain[chain.len() - 1]) || p.contains(&chain[chain.len() - 1]))
                && chain_inside(p, &chain, pt, sign)
        });
        let Some(pi) = pi else {
            return Err(err("curves cross inside this face", s));
        };
        let last = chain[chain.len() - 1];
        if !on_boundary(last) {
            // A dangling end: join it to a polygon vertex it sees, so the chain cuts the piece.
            let w = bridge(&polys[pi], &chain, pt, sign)
                .ok_or_else(|| err("a curve ending inside this face could not be joined", last))?;
            chain.push(w);
        }
        let e = chain[chain.len() - 1];
        let p = polys.swap_remove(pi);
        let (i, j) = (
            p.iter().position(|&v| v == s).unwrap_or(0),
            p.iter().position(|&v| v == e).unwrap_or(0),
        );
        let m = p.len();
        // First piece: boundary from e to s, then the chain from s to e (without repeats).
        let mut p1: Vec<u32> = (0..m)
            .map(|k| p[(j + k) % m])
            .take_while(|&v| v != s)
            .collect();
        p1.extend(chain[..chain.len() - 1].iter().copied());
        let mut p2: Vec<u32> = (0..m)
            .map(|k| p[(i + k) % m])
            .take_while(|&v| v != e)
            .collect();
        p2.extend(
            chain[1..]
                .iter()
                .rev()
                .copied()
                .collect::<Vec<_>>()
                .into_iter()
                .take(chain.len() - 1),
        );
        polys.push(p1);
        polys.push(p2);
    }
    let locked: Vec<[u32; 2]> = chains
        .iter()
        .flat_map(|c| c.windows(2).map(|w| [w[0].min(w[1]), w[0].max(w[1])]))
        .collect();
    Ok((polys, locked))
}

/// Closed segments `pq` and `rs` share a point (exact `orient2d` on the given coordinates).
fn segments_meet(p: [f64; 2], q: [f64; 2], r: [f64; 2], s: [f64; 2]) -> bool {
    let (o1, o2) = (orient2d(&p, &q, &r), orient2d(&p, &q, &s));
    let (o3, o4) = (orient2d(&r, &s, &p), orient2d(&r, &s, &q));
    let within = |a: [f64; 2], b: [f64; 2], x: [f64; 2]| {
        (0..2).all(|k| a[k].min(b[k]) <= x[k] && x[k] <= a[k].max(b[k]))
    };
    if o1 != Orientation::Zero && o1 == o2.flip() && o3 != Orientation::Zero && o3 == o4.flip() {
        return true;
    }
    (o1 == Orientation::Zero && within(p, q, r))
        || (o2 == Orientation::Zero && within(p, q, s))
        || (o3 == Orientation::Zero && within(r, s, p))
        || (o4 == Orientation::Zero && within(r, s, q))
}

/// A vertex `w` of polygon `p` (not on the chain) that the chain's dangling end sees: the
/// segment from the end to `w` enters `p` at `w` and meets no polygon edge and no chain
/// segment except at its own ends. The nearest such vertex (ties: smallest index).
fn bridge(
    p: &[u32],
    chain: &[u32],
    pt: &dyn Fn(u32) -> [f64; 2],
    sign: Orientation,
) -> Option<u32> {
    let end = chain[chain.len() - 1];
    let pe = pt(end);
    let m = p.len();
    let mut best: Option<(f64, u32)> = None;
    for &w in p {
        if chain.contains(&w) {
            continue;
        }
        let pw = pt(w);
        let clear_of_polygon = (0..m).all(|k| {
            let (a, b) = (p[k], p[(k + 1) % m]);
            a == w || b == w || !segments_meet(pe, pw, pt(a), pt(b))
        });
        let clear_of_chain = chain
            .windows(2)
            .all(|s| s[1] == end || !segments_meet(pe, pw, pt(s[0]), pt(s[1])));
        if clear_of_polygon && clear_of_chain && chain_inside(p, &[w, end], pt, sign) {
            let d = (pw[0] - pe[0]).powi(2) + (pw[1] - pe[1]).powi(2);
            if best.is_none_or(|(bd, bw)| d < bd || (d == bd && w < bw)) {
                best = Some((d, w));
            }
        }
    }
    best.map(|(_, w)| w)
}

/// Whether the chain leaves its first vertex into the interior of polygon `p` (at that vertex,
/// the chain's second point lies strictly inside the polygon's corner angle).
pub(super) fn chain_inside(
    p: &[u32],
    chain: &[u32],
    pt: &dyn Fn(u32) -> [f64; 2],
    sign: Orientation,
) -> bool {
    let m = p.len();
    let Some(i) = p.iter().position(|&v| v == chain[0]) else {
        return false;
    };
    let (prev, cur, next) = (pt(p[(i + m - 1) % m]), pt(p[i]), pt(p[(i + 1) % m]));
    let q = pt(chain[1]);
    let left_of = |a: &[f64; 2], b: &[f64; 2]| orient2d(a, b, &q) == sign;
    let convex = orient2d(&prev, &cur, &next) != sign.flip();
    if convex {
        left_of(&cur, &next) && left_of(&prev, &cur)
    } else {
        left_of(&cur, &next) || left_of(&prev, &cur)
    }
}
