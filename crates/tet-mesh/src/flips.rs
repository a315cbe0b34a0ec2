//! Topological flips that raise the worst quality of the tets they touch: the 2-3 face flip and
//! edge removal (the 3-2 flip, the 4-4 flip and in general an edge of `n` tets replaced by the
//! `2n - 4` tets over the best triangulation of its ring, found by dynamic programming over the
//! ring polygon — Klincsek's max-min triangulation).
//!
//! A flip never removes a protected face (boundary or embedded) or an edge of one, and is accepted
//! only when every new tet is positive by the exact `orient3d` and the worst mean ratio strictly
//! improves — so flipping always terminates and never inverts a tet.

use super::complex::Complex;

/// A flip must raise the worst quality by at least this much (avoids cycling on ties).
const GAIN: f64 = 1e-6;
/// Rings larger than this are not tried (quality of such rings rarely improves by removal).
const MAX_RING: usize = 8;
/// For the average, only the 3-2 and 4-4 flips (the ring's triangulations are then 1 and 2).
const MEAN_MAX_RING: usize = 4;

/// Try to improve the tet in slot `t` by a flip of one of its faces or edges. Returns true when
/// a flip was made (the slot may then hold another tet).
pub fn improve_tet(cx: &mut Complex, t: u32, scratch: &mut Scratch) -> bool {
    if !cx.alive[t as usize] {
        return false;
    }
    let tv = cx.tets[t as usize];
    // Longest edges first: a sliver's two long opposite edges are the ones whose removal frees
    // it, so fewer ring triangulations are computed in vain (a 6 % faster 640k-tet region, and
    // a slightly better one). The sort is stable: ties keep the fixed order.
    let edges = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)];
    let len2 = edges.map(|e| {
        let (p, q) = (cx.nodes[tv[e.0] as usize], cx.nodes[tv[e.1] as usize]);
        (0..3).map(|k| (p[k] - q[k]).powi(2)).sum::<f64>()
    });
    let mut order = [0, 1, 2, 3, 4, 5];
    order.sort_by(|&x, &y| len2[y].total_cmp(&len2[x]));
    for e in order.map(|k| edges[k]) {
        if remove_edge(cx, tv[e.0], tv[e.1], scratch) {
            return true;
        }
    }
    for f in super::verify::outward_faces(tv) {
        if flip23(cx, t, [f[0], f[2], f[1]]) {
            return true;
        }
    }
    false
}

#[derive(Default)]
pub struct Scratch {
    ring: Vec<u32>,
    ring_tets: Vec<u32>,
    best: Vec<f64>,
    split: Vec<usize>,
}

/// 2-3 flip of the face `f` of tet `t` (`f` oriented so that `t`'s fourth node is on its
/// positive side): the two tets sharing it become three around the edge joining their apexes.
pub fn flip23(cx: &mut Complex, t: u32, f: [u32; 3]) -> bool {
    if cx.face_protected(f) {
        return false;
    }
    let tv = cx.tets[t as usize];
    let Some(&d) = tv.iter().find(|v| !f.contains(v)) else {
        return false;
    };
    let Some(u) = cx.across(f, t) else {
        return false;
    };
    let uv = cx.tets[u as usize];
    let Some(&e) = uv.iter().find(|v| !f.contains(v)) else {
        return false;
    };
    let old = cx.shape[t as usize].min(cx.shape[u as usize]);
    let [a, b, c] = f;
    let new = [[e, d, a, b], [e, d, b, c], [e, d, c, a]];
    // Below the old worst a new tet is -∞ without its sines: the flip fails either way.
    let q = new
        .iter()
        .map(|&n| cx.quality_above(n, old + GAIN))
        .fold(f64::INFINITY, f64::min);
    if q <= old + GAIN || !new.iter().all(|&n| cx.positive(n)) {
        return false;
    }
    cx.remove_tet(t);
    cx.remove_tet(u);
    for n in new {
        cx.add_tet(n);
    }
    true
}

/// Remove the edge `ab` when the best triangulation of its ring beats the tets around it.
pub fn remove_edge(cx: &mut Complex, a: u32, b: u32, s: &mut Scratch) -> bool {
    remove_edge_for(cx, a, b, s, Goal::Worst)
}

/// What the re-triangulation of an edge's ring must raise.
#[derive(Clone, Copy)]
enum Goal {
    /// The worst shape of the tets (max-min).
    Worst,
    /// `Σ (mean ratio − level)` over the tets (so the region's average, `level`, rises when the
    /// sum does), with no new tet's shape below both the worst of the old ones and `floor`.
    Mean { level: f64, floor: f64 },
}

/// [`remove_edge`] for `goal`: Klincsek's dynamic programming over the ring polygon, with the
/// triangles' values combined by `min` (worst) or `+` (mean).
fn remove_edge_for(cx: &mut Complex, a: u32, b: u32, s: &mut Scratch, goal: Goal) -> bool {
    if cx.edge_protected(a, b) {
        return false;
    }
    // For the mean, the ring's size first, without building it: most rings are too large.
    let too_large = matches!(goal, Goal::Mean { .. })
        && cx.node_tets[a as usize]
            .iter()
            .filter(|&&t| cx.tets[t as usize].contains(&b))
            .count()
            > MEAN_MAX_RING;
    if too_large || !cx.edge_ring(a, b, &mut s.ring, &mut s.ring_tets) {
        return false;
    }
    let n = s.ring.len();
    if n > MAX_RING {
        return false;
    }
    let worst = s
        .ring_tets
        .iter()
        .map(|&t| cx.shape[t as usize])
        .fold(f64::INFINITY, f64::min);
    let (old, identity) = match goal {
        Goal::Worst => (worst, f64::INFINITY),
        Goal::Mean { level, .. } => (
            s.ring_tets
                .iter()
                .map(|&t| cx.mean_ratio[t as usize] - level)
                .sum(),
            0.0,
        ),
    };
    let combine = |x: f64, y: f64| match goal {
        Goal::Worst => x.min(y),
        Goal::Mean { .. } => x + y,
    };
    // best[i*n+j]: the best value of a triangulation of the sub-polygon r_i..r_j.
    s.best.clear();
    s.best.resize(n * n, identity);
    s.split.clear();
    s.split.resize(n * n, usize::MAX);
    let ring = &s.ring;
    let tri_q = |i: usize, k: usize, j: usize| -> f64 {
        let (ri, rk, rj) = (ring[i], ring[k], ring[j]);
        let (x, y) = ([ri, rk, rj, b], [ri, rj, rk, a]);
        match goal {
            // A triangle whose tets are not above the old worst cannot be in a triangulation
            // that beats it: it is valued -∞ without its sines (same result, the thin layers'
            // flips were most of their time).
            Goal::Worst => match cx.quality_above(x, old + GAIN) {
                f64::NEG_INFINITY => f64::NEG_INFINITY,
                qx => qx.min(cx.quality_above(y, old + GAIN)),
            },
            Goal::Mean { level, floor } => {
                let ((qx, mx), (qy, my)) = (cx.measures(x), cx.measures(y));
                if qx.min(qy) < worst.min(floor) {
                    f64::NEG_INFINITY
                } else {
                    mx + my - 2.0 * level
                }
            }
        }
    };
    for len in 2..n {
        for i in 0..n - len {
            let j = i + len;
            let mut bq = f64::NEG_INFINITY;
            let mut bk = usize::MAX;
            for k in i + 1..j {
                // The sides' value bounds the whole (`min`, or `+` with a -∞): a split that
                // cannot beat the best so far is not valued (nearly all, in a ring that fails).
                let sides = combine(s.best[i * n + k], s.best[k * n + j]);
                let bound = match goal {
                    Goal::Worst => sides,
                    Goal::Mean { .. } if sides == f64::NEG_INFINITY => sides,
                    Goal::Mean { .. } => f64::INFINITY,
                };
                if bound <= bq {
                    continue;
                }
                let q = combine(sides, tri_q(i, k, j));
                if q > bq {
                    bq = q;
                    bk = k;
                }
            }
            s.best[i * n + j] = bq;
            s.split[i * n + j] = bk;
        }
    }
    if s.best[n - 1] <= old + GAIN {
        return false;
    }
    // Collect the triangles of the best triangulation (explicit stack, no recursion).
    let mut tris: Vec<[u32; 3]> = Vec::with_capacity(n - 2);
    let mut stack = vec![(0usize, n - 1)];
    while let Some((i, j)) = stack.pop() {
        if j - i < 2 {
            continue;
        }
        let k = s.split[i * n + j];
        if k == usize::MAX {
            return false;
        }
        tris.push([ring[i], ring[k], ring[j]]);
        stack.push((i, k));
        stack.push((k, j));
    }
    let mut new = Vec::with_capacity(2 * tris.len());
    for [ri, rk, rj] in tris {
        new.push([ri, rk, rj, b]);
        new.push([ri, rj, rk, a]);
    }
    if !new.iter().all(|&t| cx.positive(t)) {
        return false;
    }
    let old_tets = std::mem::take(&mut s.ring_tets);
    for &t in &old_tets {
        cx.remove_tet(t);
    }
    s.ring_tets = old_tets;
    for t in new {
        cx.add_tet(t);
    }
    true
}

/// One pass, in slot order over the tets below the region's average mean ratio (`level`, held
/// fixed through the pass), of 3-2 and 4-4 flips of their edges that raise that average, with
/// new tets above `floor` or the worst they replace. In a layer whose nodes are all on its
/// boundary the connectivity is the only freedom left, and max-min flips stop where the worst
/// tet can rise no more. Each flip raises `Σ mean ratio − level · count` by at least `GAIN`, so
/// passes end. Returns the number made.
pub fn mean_flip_pass(cx: &mut Complex, level: f64, floor: f64, s: &mut Scratch) -> usize {
    let mut made = 0;
    for t in 0..cx.tets.len() as u32 {
        if !cx.alive[t as usize] || cx.mean_ratio[t as usize] >= level {
            continue;
        }
        let tv = cx.tets[t as usize];
        for e in [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)] {
            if remove_edge_for(cx, tv[e.0], tv[e.1], s, Goal::Mean { level, floor }) {
                made += 1;
                break;
            }
        }
    }
    made
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two tets sharing a face, with apexes far apart: the 2-3 flip makes three better tets.
    #[test]
    fn a_flat_pair_of_tets_is_flipped_into_three_positive_better_ones() {
        let nodes = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.5, 0.9, 0.0],
            [0.5, 0.3, 0.1],
            [0.5, 0.3, -0.1],
        ];
        // [0,1,2,3] positive (3 above), [0,2,1,4] positive (4 below); both flat (mean ratio
        // about 0.36), the three tets around the edge 3-4 about 0.46.
        let tets = vec![[0, 1, 2, 3], [0, 2, 1, 4]];
        let mut cx = Complex::new(nodes, tets, 0, std::iter::empty());
        let before = cx.quality([0, 1, 2, 3]).min(cx.quality([0, 2, 1, 4]));
        assert!(flip23(&mut cx, 0, [0, 1, 2]));
        let (nodes, tets) = cx.into_parts();
        let cx2 = Complex::new(nodes, tets.clone(), 0, std::iter::empty());
        assert!(tets.iter().all(|&t| cx2.positive(t)));
        assert_eq!(tets.len(), 3);
        let after = tets.iter().map(|&t| cx2.quality(t)).fold(1.0, f64::min);
        assert!(after > before + 0.05, "{before} -> {after}");
    }

    #[test]
    fn a_protected_segment_edge_is_never_removed() {
        let nodes = vec![
            [0.5, 0.02, 0.5],
            [0.5, 0.02, -0.5],
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.5, 0.9, 0.0],
        ];
        let tets = vec![[1, 0, 2, 3], [1, 0, 3, 4], [1, 0, 4, 2]];
        let mut cx = Complex::new(nodes, tets, 0, std::iter::empty());
        cx.protect_edges([[0, 1]].into_iter());
        assert!(!remove_edge(&mut cx, 1, 0, &mut Scratch::default()));
        // Whatever else improving the tets does, the edge stays.
        improve_tet(&mut cx, 0, &mut Scratch::default());
        let (_, tets) = cx.into_parts();
        assert!(tets.iter().any(|t| t.contains(&0) && t.contains(&1)));
    }

    #[test]
    fn a_protected_face_is_never_flipped_away() {
        let nodes = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.5, 0.9, 0.0],
            [0.5, 0.3, 0.2],
            [0.5, 0.3, -0.2],
        ];
        let tets = vec![[0, 1, 2, 3], [0, 2, 1, 4]];
        let mut cx = Complex::new(nodes, tets, 0, [[0, 1, 2]].into_iter());
        assert!(!flip23(&mut cx, 0, [0, 1, 2]));
        assert!(!improve_tet(&mut cx, 0, &mut Scratch::default()));
    }

    /// Three fair tets around an edge whose 3-2 flip gives two flatter tets worth less in total: a flip
    /// for the average takes it only where one tet fewer is worth that (the region's average
    /// above the loss), and never when a new tet falls below both the old worst and the floor.
    #[test]
    fn a_flip_for_the_average_is_made_only_when_it_raises_the_average_above_the_floor() {
        let nodes = vec![
            [0.5, 0.3, 0.2],
            [0.5, 0.3, -0.2],
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.5, 0.9, 0.0],
        ];
        let tets = vec![[1, 0, 2, 3], [1, 0, 3, 4], [1, 0, 4, 2]];
        let build = || Complex::new(nodes.clone(), tets.clone(), 0, std::iter::empty());
        let cx = build();
        let three: f64 = (0..3).map(|t| cx.mean_ratio[t]).sum();
        let worst_three = (0..3).map(|t| cx.shape[t]).fold(f64::INFINITY, f64::min);
        let (q1, m1) = cx.measures([2, 3, 4, 0]);
        let (q2, m2) = cx.measures([2, 4, 3, 1]);
        let loss = three - (m1 + m2);
        assert!(loss > 0.3 && loss < 0.9, "{loss}");
        assert!(q1.min(q2) < worst_three, "{q1} {q2} {worst_three}");
        let mut s = Scratch::default();
        // Worth one tet at the level 0.95: made, two tets left.
        let mut cx = build();
        assert_eq!(mean_flip_pass(&mut cx, 0.95, 0.0, &mut s), 1);
        assert_eq!(cx.into_parts().1.len(), 2);
        // Not at the level 0.25 (below the loss) ...
        let mut cx = build();
        assert_eq!(mean_flip_pass(&mut cx, 0.25, 0.0, &mut s), 0);
        // ... nor under a floor above the new worst.
        let mut cx = build();
        assert_eq!(mean_flip_pass(&mut cx, 0.95, q1.min(q2) + 0.01, &mut s), 0);
    }

    /// Three tets around an edge that passes close to a ring edge (so one of them is flat): the
    /// 3-2 flip removes the edge.
    #[test]
    fn a_short_edge_with_three_tets_is_removed_by_a_3_2_flip() {
        let nodes = vec![
            [0.5, 0.02, 0.5],
            [0.5, 0.02, -0.5],
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.5, 0.9, 0.0],
        ];
        // edge (1 -> 0) points +z; ring 2,3,4 is counter-clockwise seen from +z.
        let tets = vec![[1, 0, 2, 3], [1, 0, 3, 4], [1, 0, 4, 2]];
        let mut cx = Complex::new(nodes, tets.clone(), 0, std::iter::empty());
        assert!(tets.iter().all(|&t| cx.positive(t)));
        let mut s = Scratch::default();
        assert!(remove_edge(&mut cx, 1, 0, &mut s));
        let (nodes, tets) = cx.into_parts();
        assert_eq!(tets.len(), 2);
        let cx2 = Complex::new(nodes, tets.clone(), 0, std::iter::empty());
        assert!(tets.iter().all(|&t| cx2.positive(t)));
    }
}
