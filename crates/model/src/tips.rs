//! How fine the curves must be where two of them leave a corner of a patch under a small angle.
//!
//! A wedge's corner holds a thin triangle whatever the size (`width` does not refine into
//! wedges), but how thin depends on the nodes beside the corner. Where the two curves leaving
//! it get nodes at like distances, the corner's triangle is about isosceles, with the wedge's
//! angle at its tip: the best the wedge allows. Where one of them has a node a few metres from
//! the corner (a short curve, or a bend of its polyline: two surfaces crossing again and again
//! near an onlap's tip leave both) and the other has its first node a whole element on, the
//! triangle between is a needle, far thinner than the wedge: 0.0007 in mean ratio where the
//! wedge allows 0.06, and the tets on it as bad.
//!
//! Decisions and why:
//! - A corner is two consecutive curves of a patch's loop. Their angle is taken between the
//!   chords from the corner to each curve's point at the size asked (below), so it is the angle
//!   the first nodes will see.
//! - Under [`TIP_ANGLE`], and where one curve's first point past the corner is [`MISMATCH`]
//!   times farther than the other's, the corner asks both curves for the distance to the
//!   nearer: the other end of a short curve, or a polyline vertex, where the curve's
//!   discretization may put a node (it splits segments at vertices where curves run close, as
//!   they do at a wedge's tip). Graded with the model's other curve sizes (`curvature`) over
//!   every curve nearby, the two sides of the wedge, and a curve continuing a short one, grow
//!   from it alike (sizes on the two curves alone, not graded over the others, left the
//!   corpus's downlap at 0.8° and its touching horizons at 3.7°).
//! - Wider corners leave room for the surface mesher's own interior nodes, and first points at
//!   like distances give the wedge's best triangle already: refining those only adds elements.
//! - No recipe size enters: a length longer than a curve's size asks nothing of it.

use crate::clearance::arc_lengths;
use crate::{Curve, CurveUse, PatchBoundary};
use geom::predicates::{dist, dot, sub};

/// A curve at a corner: the curve, its arc lengths, and whether the corner is its last point.
type Side<'a> = (&'a Curve, &'a [f64], bool);

/// Only corners sharper than this (degrees) ask anything of their curves.
pub const TIP_ANGLE: f64 = 30.0;

/// Corners ask only where one curve's first point is this many times farther than the other's:
/// nodes at like distances make the wedge's best triangle already.
pub const MISMATCH: f64 = 4.0;

/// Per curve, the places `[x, y, z, size]` of the sharp corners at its ends, with the size each
/// asks (see the module doc).
pub fn tip_sizes(curves: &[Curve], bounds: &[PatchBoundary]) -> Vec<Vec<[f64; 4]>> {
    let arcs = arc_lengths(curves);
    let mut out = vec![Vec::new(); curves.len()];
    // A curve of the loop, with the corner at its end in loop order (`at_end`) or its start.
    let side = |c: CurveUse, at_end: bool| -> Option<Side<'_>> {
        let curve = curves.get(c.curve as usize)?;
        let arc = arcs.get(c.curve as usize)?;
        Some((curve, arc.as_slice(), at_end != c.reversed))
    };
    for lp in bounds
        .iter()
        .flat_map(|b| &b.loops)
        .filter(|lp| lp.len() > 1)
    {
        for k in 0..lp.len() {
            // Loop order: `u` ends at the corner, `w` starts there.
            let (u, w) = (lp[k], lp[(k + 1) % lp.len()]);
            let (Some(a), Some(b)) = (side(u, true), side(w, false)) else {
                continue;
            };
            if let Some((corner, size)) = sharp_corner(a, b) {
                let place = [corner[0], corner[1], corner[2], size];
                out[u.curve as usize].push(place);
                out[w.curve as usize].push(place);
            }
        }
    }
    for places in &mut out {
        places.sort_by(|p, q| p.partial_cmp(q).unwrap_or(std::cmp::Ordering::Equal));
        places.dedup();
    }
    out
}

/// The corner and the size it asks, when two curves leave it under less than [`TIP_ANGLE`]: the distance along them
/// to the first point of either past the corner (the other end of a short curve, or a vertex of
/// a polyline, where its discretization may put a node).
fn sharp_corner(a: Side, b: Side) -> Option<([f64; 3], f64)> {
    let (fa, fb) = (first_point(&a), first_point(&b));
    let short = fa.min(fb);
    if !(short > 0.0 && short.is_finite()) || fa.max(fb) < MISMATCH * short {
        return None;
    }
    let corner = at_arc(a, 0.0)?;
    let (pa, pb) = (at_arc(a, short)?, at_arc(b, short)?);
    let (da, db) = (sub(&pa, &corner), sub(&pb, &corner));
    let (la, lb) = (dist(&pa, &corner), dist(&pb, &corner));
    if la == 0.0 || lb == 0.0 {
        return None;
    }
    let cos = (dot(&da, &db) / (la * lb)).clamp(-1.0, 1.0);
    (cos.acos().to_degrees() < TIP_ANGLE).then_some((corner, short))
}

/// The arc length from the corner to a curve's next point (0 for a curve without one).
fn first_point((_, arc, from_end): &Side) -> f64 {
    let total = arc.last().copied().unwrap_or(0.0);
    match (from_end, arc.len()) {
        (_, 0 | 1) => 0.0,
        (false, _) => arc[1],
        (true, n) => total - arc[n - 2],
    }
}

/// The point of a curve at arc length `s` from the corner (its last point when `from_end`).
fn at_arc((c, arc, from_end): Side, s: f64) -> Option<[f64; 3]> {
    let total = *arc.last()?;
    let s = if from_end { total - s } else { s }.clamp(0.0, total);
    let k = arc
        .partition_point(|&x| x < s)
        .clamp(1, arc.len().max(2) - 1);
    let (p, q) = (c.points.get(k - 1)?, c.points.get(k)?);
    let span = arc[k] - arc[k - 1];
    let f = if span > 0.0 {
        (s - arc[k - 1]) / span
    } else {
        0.0
    };
    Some([0, 1, 2].map(|i| p[i] + f * (q[i] - p[i])))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::clearance::tests::curve;

    fn use_(curve: u32, reversed: bool) -> CurveUse {
        CurveUse { curve, reversed }
    }

    /// A wedge 2° wide at the origin: its upper side a curve 6 m long, then one on to x = 2000;
    /// its lower side one curve back to the origin; a straight side closing it at x = 2000.
    fn wedge() -> (Vec<Curve>, PatchBoundary) {
        let up = |x: f64| [x, x * 1f64.to_radians().tan(), 0.0];
        let down = |x: f64| [x, -x * 1f64.to_radians().tan(), 0.0];
        let curves = vec![
            curve("short", vec![up(0.0), up(6.0)]),
            curve("upper", vec![up(6.0), up(700.0), up(2000.0)]),
            curve("side", vec![up(2000.0), down(2000.0)]),
            curve("lower", vec![down(0.0), down(900.0), down(2000.0)]),
        ];
        let bound = PatchBoundary {
            loops: vec![vec![
                use_(0, false),
                use_(1, false),
                use_(2, false),
                use_(3, true),
            ]],
            constraints: Vec::new(),
        };
        (curves, bound)
    }

    #[test]
    fn a_short_curve_at_a_wedges_tip_asks_both_sides_for_its_length_there() {
        let (curves, bound) = wedge();
        let t = tip_sizes(&curves, &[bound]);
        let want = [
            0.0,
            0.0,
            0.0,
            dist(&curves[0].points[0], &curves[0].points[1]),
        ];
        assert_eq!(t[0], vec![want], "the short curve");
        assert_eq!(t[3], vec![want], "the wedge's other side");
        assert!(
            t[1].is_empty() && t[2].is_empty(),
            "straight on, and square corners: {t:?}"
        );
    }

    #[test]
    fn a_wide_corner_asks_nothing_of_its_curves() {
        let (mut curves, bound) = wedge();
        // The lower side turned down to 40° below the upper one.
        let low = |x: f64| [x, -x * 39f64.to_radians().tan(), 0.0];
        curves[3].points = vec![low(0.0), low(900.0), low(2000.0)];
        curves[2].points[1] = low(2000.0);
        let t = tip_sizes(&curves, &[bound]);
        assert!(t.iter().all(Vec::is_empty), "{t:?}");
    }

    #[test]
    fn a_polyline_vertex_near_the_tip_of_either_side_sets_the_size() {
        // The lower side has a bend 1 m from the tip, where its discretization may put a node.
        let (mut curves, bound) = wedge();
        let down = |x: f64| [x, -x * 1f64.to_radians().tan(), 0.0];
        curves[3].points.insert(1, down(1.0));
        let t = tip_sizes(&curves, &[bound]);
        let size = t[0].first().expect("a place")[3];
        assert!((size - dist(&[0.0; 3], &down(1.0))).abs() < 1e-12, "{size}");
        assert_eq!(t[0], t[3]);
    }

    #[test]
    fn first_points_at_like_distances_ask_nothing() {
        // A bend of the lower side 3 m from the tip, half the short curve's 6 m.
        let (mut curves, bound) = wedge();
        curves[3]
            .points
            .insert(1, [3.0, -3.0 * 1f64.to_radians().tan(), 0.0]);
        assert!(tip_sizes(&curves, &[bound]).iter().all(Vec::is_empty));
    }
}
