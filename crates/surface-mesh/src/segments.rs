//! Exact 2D segment intersection over a set of segments (loop and constraint edges, or a
//! flattened support border): an R-tree of segment boxes proposes candidate pairs, exact
//! `orient2d` decides. Segments that share an end point (bit-identical) may touch there and only
//! there; any other contact, including collinear overlap, is a crossing.

use geom::{Orientation, orient2d};
use rstar::primitives::{GeomWithData, Rectangle};
use rstar::{AABB, RTree};

type Seg = ([f64; 2], [f64; 2]);

/// Whether `c` (collinear with `a b`) lies on the closed segment `a b`.
fn on_segment(a: &[f64; 2], b: &[f64; 2], c: &[f64; 2]) -> bool {
    a[0].min(b[0]) <= c[0]
        && c[0] <= a[0].max(b[0])
        && a[1].min(b[1]) <= c[1]
        && c[1] <= a[1].max(b[1])
}

/// Whether two closed segments share any point (exact).
pub fn touch(s: &Seg, t: &Seg) -> bool {
    let (a, b) = (&s.0, &s.1);
    let (c, d) = (&t.0, &t.1);
    let o1 = orient2d(a, b, c);
    let o2 = orient2d(a, b, d);
    let o3 = orient2d(c, d, a);
    let o4 = orient2d(c, d, b);
    use Orientation::Zero;
    if o1 != o2 && o3 != o4 && o1 != Zero && o2 != Zero && o3 != Zero && o4 != Zero {
        return true;
    }
    (o1 == Zero && on_segment(a, b, c))
        || (o2 == Zero && on_segment(a, b, d))
        || (o3 == Zero && on_segment(c, d, a))
        || (o4 == Zero && on_segment(c, d, b))
}

/// Whether two segments conflict: touching anywhere except at one shared end point.
pub fn conflict(s: &Seg, t: &Seg) -> bool {
    let shared = [(s.0, t.0), (s.0, t.1), (s.1, t.0), (s.1, t.1)]
        .iter()
        .filter(|(p, q)| p == q)
        .count();
    if shared >= 2 {
        return true; // the same segment twice
    }
    if shared == 0 {
        return touch(s, t);
    }
    // One shared end point: conflict only if collinear and overlapping beyond it.
    let (p, a, b) = if s.0 == t.0 {
        (s.0, s.1, t.1)
    } else if s.0 == t.1 {
        (s.0, s.1, t.0)
    } else if s.1 == t.0 {
        (s.1, s.0, t.1)
    } else {
        (s.1, s.0, t.0)
    };
    if orient2d(&p, &a, &b) != Orientation::Zero {
        return false;
    }
    // Collinear: overlap iff a and b are on the same side of p.
    let da = [a[0] - p[0], a[1] - p[1]];
    let db = [b[0] - p[0], b[1] - p[1]];
    (da[0] * db[0] + da[1] * db[1]) > 0.0
}

/// The first conflicting pair (i < j, smallest i then j), if any.
pub fn first_crossing(segs: &[Seg]) -> Option<(usize, usize)> {
    let items: Vec<GeomWithData<Rectangle<[f64; 2]>, usize>> = segs
        .iter()
        .enumerate()
        .map(|(i, s)| GeomWithData::new(Rectangle::from_corners(s.0, s.1), i))
        .collect();
    let tree = RTree::bulk_load(items);
    let mut best: Option<(usize, usize)> = None;
    for (i, s) in segs.iter().enumerate() {
        if best.is_some_and(|b| b.0 < i) {
            break;
        }
        let env = AABB::from_corners(
            [s.0[0].min(s.1[0]), s.0[1].min(s.1[1])],
            [s.0[0].max(s.1[0]), s.0[1].max(s.1[1])],
        );
        for it in tree.locate_in_envelope_intersecting(env) {
            let j = it.data;
            if j <= i {
                continue;
            }
            if conflict(s, &segs[j]) {
                best = match best {
                    Some(b) if b <= (i, j) => Some(b),
                    _ => Some((i, j)),
                };
            }
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn consecutive_loop_edges_do_not_conflict_but_a_bow_tie_does() {
        let sq = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        let segs: Vec<Seg> = (0..4).map(|i| (sq[i], sq[(i + 1) % 4])).collect();
        assert_eq!(first_crossing(&segs), None);
        let bow = [[0.0, 0.0], [1.0, 1.0], [1.0, 0.0], [0.0, 1.0]];
        let segs: Vec<Seg> = (0..4).map(|i| (bow[i], bow[(i + 1) % 4])).collect();
        assert_eq!(first_crossing(&segs), Some((0, 2)));
    }

    #[test]
    fn a_collinear_fold_back_at_a_shared_node_conflicts() {
        let s = ([0.0, 0.0], [2.0, 0.0]);
        let t = ([2.0, 0.0], [1.0, 0.0]);
        assert!(conflict(&s, &t));
        let u = ([2.0, 0.0], [3.0, 0.0]);
        assert!(!conflict(&s, &u));
    }
}
