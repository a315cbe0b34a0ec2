//! Polyline assembly: the contact segments of all triangle pairs form a graph whose nodes are
//! point keys; this module walks it, iteratively (no recursion, so a curve of any length is
//! fine), into curves. Open curves run between nodes of degree other than 2: surface borders
//! (degree 1) and branch points (degree ≥ 3, future topological vertices). What is left are
//! closed loops. Everything is canonical and decided on keys only: open curves start at their
//! smaller end; closed loops start at their smallest key and go on towards the smaller of its
//! two neighbours; curves are sorted by their key sequence.

use super::key::PointKey;

/// One assembled curve, by keys. For a closed loop the first point is not repeated and segment
/// `i` joins point `i` to point `i + 1 (mod n)`; for an open curve segment `i` joins points `i`
/// and `i + 1`. `faces[i]` is the (triangle of a, triangle of b) pair of segment `i`.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub struct KeyCurve {
    pub points: Vec<PointKey>,
    pub closed: bool,
    pub faces: Vec<(u32, u32)>,
}

/// Walk the segments `(k0, k1, faces)` (any order, duplicates allowed: a duplicate keeps its
/// smallest face pair) into canonical curves.
pub fn assemble(segments: &[(PointKey, PointKey, (u32, u32))]) -> Vec<KeyCurve> {
    let mut nodes: Vec<PointKey> = segments.iter().flat_map(|s| [s.0, s.1]).collect();
    nodes.sort_unstable();
    nodes.dedup();
    let id = |k: &PointKey| nodes.binary_search(k).unwrap_or(0);
    let mut edges: Vec<(usize, usize, (u32, u32))> = segments
        .iter()
        .filter(|s| s.0 != s.1)
        .map(|s| {
            let (x, y) = (id(&s.0), id(&s.1));
            (x.min(y), x.max(y), s.2)
        })
        .collect();
    edges.sort_unstable();
    edges.dedup_by(|e, f| e.0 == f.0 && e.1 == f.1);

    // Incidence lists in CSR form, each sorted by (neighbour, edge).
    let mut deg = vec![0usize; nodes.len()];
    for e in &edges {
        deg[e.0] += 1;
        deg[e.1] += 1;
    }
    let mut start = vec![0usize; nodes.len() + 1];
    for n in 0..nodes.len() {
        start[n + 1] = start[n] + deg[n];
    }
    let mut inc: Vec<(usize, usize)> = vec![(0, 0); start[nodes.len()]];
    let mut fill = start.clone();
    for (ei, e) in edges.iter().enumerate() {
        inc[fill[e.0]] = (e.1, ei);
        fill[e.0] += 1;
        inc[fill[e.1]] = (e.0, ei);
        fill[e.1] += 1;
    }
    for n in 0..nodes.len() {
        inc[start[n]..start[n + 1]].sort_unstable();
    }

    let mut used = vec![false; edges.len()];
    let mut curves = Vec::new();
    let walk = |from: usize, first_edge: usize, used: &mut Vec<bool>| {
        let mut pts = vec![from];
        let mut faces = Vec::new();
        let (mut cur, mut e) = (from, first_edge);
        loop {
            used[e] = true;
            let (x, y, f) = edges[e];
            let next = if x == cur { y } else { x };
            pts.push(next);
            faces.push(f);
            if deg[next] != 2 || next == from {
                break;
            }
            match inc[start[next]..start[next + 1]]
                .iter()
                .find(|(_, ei)| !used[*ei])
            {
                Some(&(_, ei)) => {
                    cur = next;
                    e = ei;
                }
                None => break,
            }
        }
        (pts, faces)
    };

    for n in 0..nodes.len() {
        if deg[n] == 2 {
            continue;
        }
        for &(_, ei) in &inc[start[n]..start[n + 1]] {
            if !used[ei] {
                let (pts, faces) = walk(n, ei, &mut used);
                curves.push(open_curve(&nodes, pts, faces));
            }
        }
    }
    for n in 0..nodes.len() {
        for &(_, ei) in &inc[start[n]..start[n + 1]] {
            if !used[ei] {
                let (mut pts, faces) = walk(n, ei, &mut used);
                if pts.len() > 1 && pts.first() == pts.last() {
                    pts.pop();
                    curves.push(closed_curve(&nodes, pts, faces));
                } else {
                    curves.push(open_curve(&nodes, pts, faces));
                }
            }
        }
    }
    curves.sort();
    curves
}

fn open_curve(nodes: &[PointKey], mut pts: Vec<usize>, mut faces: Vec<(u32, u32)>) -> KeyCurve {
    let n = pts.len();
    let reverse = if pts[0] != pts[n - 1] {
        pts[n - 1] < pts[0]
    } else {
        n > 2 && pts[n - 2] < pts[1]
    };
    if reverse {
        pts.reverse();
        faces.reverse();
    }
    KeyCurve {
        points: pts.into_iter().map(|i| nodes[i]).collect(),
        closed: false,
        faces,
    }
}

fn closed_curve(nodes: &[PointKey], pts: Vec<usize>, faces: Vec<(u32, u32)>) -> KeyCurve {
    let n = pts.len();
    let r = (0..n).min_by_key(|&i| pts[i]).unwrap_or(0);
    let mut p: Vec<usize> = (0..n).map(|i| pts[(i + r) % n]).collect();
    let mut f: Vec<(u32, u32)> = (0..n).map(|i| faces[(i + r) % n]).collect();
    if n > 2 && p[n - 1] < p[1] {
        p[1..].reverse();
        f.reverse();
    }
    KeyCurve {
        points: p.into_iter().map(|i| nodes[i]).collect(),
        closed: true,
        faces: f,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn k(i: u32) -> PointKey {
        PointKey::EdgeFace {
            a: (i, i + 1),
            b: 0,
        }
    }

    #[test]
    fn shuffled_segments_of_a_chain_make_one_open_curve_from_its_smaller_end() {
        let segs = vec![
            (k(3), k(2), (3, 0)),
            (k(0), k(1), (1, 0)),
            (k(2), k(1), (2, 0)),
        ];
        let c = assemble(&segs);
        assert_eq!(c.len(), 1);
        assert_eq!(c[0].points, vec![k(0), k(1), k(2), k(3)]);
        assert_eq!(c[0].faces, vec![(1, 0), (2, 0), (3, 0)]);
        assert!(!c[0].closed);
    }

    #[test]
    fn a_ring_becomes_a_closed_loop_starting_at_its_smallest_key() {
        let segs = vec![
            (k(5), k(7), (0, 0)),
            (k(7), k(6), (1, 0)),
            (k(6), k(9), (2, 0)),
            (k(9), k(5), (3, 0)),
        ];
        let c = assemble(&segs);
        assert_eq!(c.len(), 1);
        assert!(c[0].closed);
        assert_eq!(c[0].points, vec![k(5), k(7), k(6), k(9)]);
        assert_eq!(c[0].faces, vec![(0, 0), (1, 0), (2, 0), (3, 0)]);
    }

    #[test]
    fn a_branch_point_ends_three_curves() {
        let segs = vec![
            (k(0), k(1), (0, 0)),
            (k(1), k(2), (0, 0)),
            (k(1), k(3), (0, 0)),
        ];
        let c = assemble(&segs);
        assert_eq!(c.len(), 3);
        assert!(c.iter().all(|c| c.points.len() == 2 && !c.closed));
    }

    #[test]
    fn a_chain_of_a_hundred_thousand_segments_is_walked_without_recursion() {
        let segs: Vec<_> = (0..100_000u32)
            .map(|i| (k(2 * i), k(2 * i + 2), (i, 0)))
            .collect();
        let c = assemble(&segs);
        assert_eq!(c.len(), 1);
        assert_eq!(c[0].points.len(), 100_001);
    }
}
