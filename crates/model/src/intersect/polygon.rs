//! Triangulating the pieces of a split triangle: ear clipping of a simple polygon (collinear runs
//! allowed) and edge flips that remove slivers without touching locked (curve) edges. Validity
//! is decided by exact `orient2d` on the given 2D coordinates; a shape measure only chooses among
//! valid options. Both run in about O(n²) for a polygon of n vertices, so a box side crossed by
//! a curve of thousands of points is fine.

use geom::{Orientation, orient2d};
use std::collections::HashMap;
use std::hash::{BuildHasherDefault, DefaultHasher};

/// Shape quality of a triangle in 2D: twice its area over the sum of its squared edge lengths
/// (a measure for choosing among valid ears or flips; no decision of validity rests on it).
pub fn ear_quality(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    let (u, v, w) = (
        [a[0] - b[0], a[1] - b[1]],
        [c[0] - b[0], c[1] - b[1]],
        [c[0] - a[0], c[1] - a[1]],
    );
    let area2 = (u[0] * v[1] - u[1] * v[0]).abs();
    let sum = u[0] * u[0] + u[1] * u[1] + v[0] * v[0] + v[1] * v[1] + w[0] * w[0] + w[1] * w[1];
    if sum > 0.0 { area2 / sum } else { 0.0 }
}

/// Ear clipping of a simple polygon given counter-clockwise (w.r.t. `sign`), allowing collinear
/// runs: an ear is a strictly convex corner whose closed triangle holds no other polygon vertex.
/// Of the ears, the best shaped is clipped first. `None` when no ear exists (not a simple
/// counter-clockwise polygon).
pub fn ear_clip(
    poly: &[u32],
    pt: &dyn Fn(u32) -> [f64; 2],
    sign: Orientation,
) -> Option<Vec<[u32; 3]>> {
    let n = poly.len();
    if n < 3 {
        return Some(Vec::new());
    }
    let xy: Vec<[f64; 2]> = poly.iter().map(|&v| pt(v)).collect();
    let mut prev: Vec<usize> = (0..n).map(|i| (i + n - 1) % n).collect();
    let mut next: Vec<usize> = (0..n).map(|i| (i + 1) % n).collect();
    let mut alive = vec![true; n];
    let ear = |i: usize, prev: &[usize], next: &[usize], alive: &[bool]| -> Option<f64> {
        let (a, c) = (prev[i], next[i]);
        let (pa, pb, pc) = (xy[a], xy[i], xy[c]);
        if orient2d(&pa, &pb, &pc) != sign {
            return None;
        }
        let blocked = (0..n).any(|k| {
            alive[k]
                && k != a
                && k != i
                && k != c
                && poly[k] != poly[a]
                && poly[k] != poly[i]
                && poly[k] != poly[c]
                && [
                    orient2d(&pa, &pb, &xy[k]),
                    orient2d(&pb, &pc, &xy[k]),
                    orient2d(&pc, &pa, &xy[k]),
                ]
                .iter()
                .all(|&o| o != sign.flip())
        });
        (!blocked).then(|| ear_quality(pa, pb, pc))
    };
    let mut q: Vec<Option<f64>> = (0..n).map(|i| ear(i, &prev, &next, &alive)).collect();
    let mut out = Vec::with_capacity(n - 2);
    let mut remaining = n;
    while remaining > 3 {
        let pick = |q: &[Option<f64>], alive: &[bool]| {
            (0..n)
                .filter_map(|i| if alive[i] { q[i].map(|x| (x, i)) } else { None })
                .max_by(|x, y| x.0.total_cmp(&y.0).then(y.1.cmp(&x.1)))
                .map(|x| x.1)
        };
        let best = match pick(&q, &alive) {
            Some(b) => b,
            None => {
                // Cached states only miss ears unblocked by earlier clips: refresh once.
                for i in 0..n {
                    if alive[i] {
                        q[i] = ear(i, &prev, &next, &alive);
                    }
                }
                pick(&q, &alive)?
            }
        };
        let (a, c) = (prev[best], next[best]);
        out.push([poly[a], poly[best], poly[c]]);
        alive[best] = false;
        remaining -= 1;
        next[a] = c;
        prev[c] = a;
        q[a] = ear(a, &prev, &next, &alive);
        q[c] = ear(c, &prev, &next, &alive);
    }
    let i = (0..n).find(|&i| alive[i])?;
    let (a, c) = (prev[i], next[i]);
    if orient2d(&xy[a], &xy[i], &xy[c]) != sign {
        return None;
    }
    out.push([poly[a], poly[i], poly[c]]);
    Some(out)
}

/// Edge flips among the triangles of one split triangle: an unlocked edge shared by two
/// triangles is flipped when both new triangles are strictly positive (exact `orient2d`) and
/// the worse of the two improves. This removes the slivers ear clipping leaves next to points
/// that lie, up to the rounding of constructed coordinates, on a line through others.
/// Terminates: each flip raises the sorted vector of qualities; capped anyway.
pub fn improve(
    tris: &mut [[u32; 3]],
    locked: &[[u32; 2]],
    pt: &dyn Fn(u32) -> [f64; 2],
    sign: Orientation,
) {
    let q = |t: &[u32; 3]| ear_quality(pt(t[0]), pt(t[1]), pt(t[2]));
    let pos = |a: u32, b: u32, c: u32| orient2d(&pt(a), &pt(b), &pt(c)) == sign;
    let mut locked: Vec<[u32; 2]> = locked.to_vec();
    locked.sort_unstable();
    let is_locked = |a: u32, b: u32| locked.binary_search(&[a.min(b), a.max(b)]).is_ok();
    // Which triangle holds each directed edge: looked up, never iterated, so a hash map with a
    // fixed (unseeded) hasher cannot make the result depend on anything but the input.
    let mut owner: HashMap<(u32, u32), usize, BuildHasherDefault<DefaultHasher>> =
        HashMap::with_capacity_and_hasher(3 * tris.len(), Default::default());
    let mut edges: Vec<(u32, u32)> = Vec::with_capacity(3 * tris.len());
    for (i, t) in tris.iter().enumerate() {
        for k in 0..3 {
            owner.insert((t[k], t[(k + 1) % 3]), i);
            edges.push((t[k], t[(k + 1) % 3]));
        }
    }
    let third = |t: &[u32; 3], a: u32, b: u32| {
        (0..3)
            .find(|&k| t[k] == a && t[(k + 1) % 3] == b)
            .map(|k| t[(k + 2) % 3])
    };
    // Every undirected edge once, largest last: popped in ascending order.
    let mut stack: Vec<(u32, u32)> = edges.into_iter().filter(|&(a, b)| a < b).collect();
    stack.sort_unstable();
    stack.dedup();
    stack.reverse();
    let mut budget = 20 * tris.len() + 100;
    while let Some((a, b)) = stack.pop() {
        if is_locked(a, b) {
            continue;
        }
        let (Some(&i), Some(&j)) = (owner.get(&(a, b)), owner.get(&(b, a))) else {
            continue;
        };
        let (Some(c), Some(d)) = (third(&tris[i], a, b), third(&tris[j], b, a)) else {
            continue;
        };
        let (n1, n2) = ([a, d, c], [d, b, c]);
        if !(pos(a, d, c) && pos(d, b, c) && q(&n1).min(q(&n2)) > q(&tris[i]).min(q(&tris[j]))) {
            continue;
        }
        for t in [tris[i], tris[j]] {
            for k in 0..3 {
                owner.remove(&(t[k], t[(k + 1) % 3]));
            }
        }
        tris[i] = n1;
        tris[j] = n2;
        for (idx, t) in [(i, n1), (j, n2)] {
            for k in 0..3 {
                owner.insert((t[k], t[(k + 1) % 3]), idx);
            }
        }
        for (x, y) in [(a, d), (d, b), (b, c), (c, a)] {
            stack.push((x.min(y), x.max(y)));
        }
        budget -= 1;
        if budget == 0 {
            break;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_square_with_collinear_side_points_is_clipped_into_positive_triangles() {
        let pts: Vec<[f64; 2]> = vec![[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]];
        let pt = |v: u32| pts[v as usize];
        let tris = ear_clip(&[0, 1, 2, 3, 4], &pt, Orientation::Positive).expect("simple polygon");
        assert_eq!(tris.len(), 3);
        for t in &tris {
            assert_eq!(
                orient2d(&pt(t[0]), &pt(t[1]), &pt(t[2])),
                Orientation::Positive
            );
        }
    }

    #[test]
    fn a_clockwise_polygon_has_no_ear() {
        let pts: Vec<[f64; 2]> = vec![[0.0, 0.0], [0.0, 1.0], [1.0, 1.0], [1.0, 0.0]];
        let pt = |v: u32| pts[v as usize];
        assert_eq!(ear_clip(&[0, 1, 2, 3], &pt, Orientation::Positive), None);
    }

    #[test]
    fn a_sliver_next_to_a_nearly_collinear_point_is_flipped_away_unless_locked() {
        // (0, 1, 2) is a sliver: 2 lies 1e-3 above the edge 0-1; the kite 0-3-1-2 is convex.
        let pts: Vec<[f64; 2]> = vec![[0.0, 0.0], [2.0, 0.0], [1.0, 1e-3], [1.0, -1.0]];
        let pt = |v: u32| pts[v as usize];
        let mut tris = vec![[0, 3, 1], [0, 1, 2]];
        improve(&mut tris, &[], &pt, Orientation::Positive);
        assert!(
            tris.iter().all(|t| !(t.contains(&0) && t.contains(&1))),
            "{tris:?}"
        );
        assert!(
            tris.iter()
                .all(|t| orient2d(&pt(t[0]), &pt(t[1]), &pt(t[2])) == Orientation::Positive)
        );
        let pts2: Vec<[f64; 2]> = vec![[0.0, 0.0], [1.0, -1e-3], [2.0, 0.0], [1.0, 1.0]];
        let pt2 = |v: u32| pts2[v as usize];
        let mut t2 = vec![[0, 1, 2], [0, 2, 3]];
        let mut locked = t2.clone();
        improve(&mut locked, &[[0, 2]], &pt2, Orientation::Positive);
        assert_eq!(locked, t2, "locked edge stays");
        improve(&mut t2, &[], &pt2, Orientation::Positive);
        assert!(
            t2.iter().all(|t| !(t.contains(&0) && t.contains(&2))),
            "edge 0-2 flipped to 1-3: {t2:?}"
        );
    }
}
