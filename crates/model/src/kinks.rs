//! Where a polyline has a corner. A vertex of a curve is a kink when the curve turns there by
//! more than `Tolerances::kink_angle_deg` between its two edges, and by more than
//! [`REACH_SHARE`] of it between the chords to the points one reach back and one reach forward
//! along it, the reach being the longer of the two edges.
//!
//! Why the reach: a jog far shorter than the edges around it turns sharply edge to edge but
//! turns back within the reach. A curve that crosses a cap (a sliver triangle standing in its
//! surface, as a repair of a T-junction leaves one) climbs the cap's wall and comes down within
//! a metre: 46-77° edge to edge, 0-1.2° over the reach (one 14°). Cut at each turn, it left
//! curves of a few centimetres and needle elements on them. A corner of the geometry turns over
//! any reach, so it stays a corner. The reach scales with the data's own edges, so no length
//! enters the tolerances.
//!
//! Why a share: a bend spread over edges of uneven length turns over the reach by less than
//! between its edges (of the TKC kimberlite pipes' curves' 32 turns of 30-47° edge to edge, 30
//! turn 12-30° over the reach, two 3-5°). Asked for the whole kink angle over the reach, one such curve lost a
//! corner its neighbours' meshes needed, and two bodies' meshes met along an edge there.

use geom::predicates::dist;

/// The share of the kink angle a kink must turn over the reach (module doc).
pub const REACH_SHARE: f64 = 0.5;

/// Turn angle at `b` on the path a→b→c, in degrees (`None` for a zero-length side).
pub(crate) fn turn_deg(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3]) -> Option<f64> {
    let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let v = [c[0] - b[0], c[1] - b[1], c[2] - b[2]];
    let nu = (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]).sqrt();
    let nv = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if nu == 0.0 || nv == 0.0 {
        return None;
    }
    let c = ((u[0] * v[0] + u[1] * v[1] + u[2] * v[2]) / (nu * nv)).clamp(-1.0, 1.0);
    Some(c.acos().to_degrees())
}

/// Whether the polyline through `v` is kinked there (module doc). `back` and `fwd` give its
/// points outwards from `v`, the edge neighbours first, and end where the curve does.
pub(crate) fn is_kink(
    v: &[f64; 3],
    back: impl IntoIterator<Item = [f64; 3]>,
    fwd: impl IntoIterator<Item = [f64; 3]>,
    kink_deg: f64,
) -> bool {
    let (mut back, mut fwd) = (back.into_iter(), fwd.into_iter());
    let (Some(a), Some(c)) = (back.next(), fwd.next()) else {
        return false;
    };
    if !turn_deg(&a, v, &c).is_some_and(|d| d > kink_deg) {
        return false;
    }
    let reach = dist(&a, v).max(dist(v, &c));
    let (pa, pc) = (along(v, a, back, reach), along(v, c, fwd, reach));
    turn_deg(&pa, v, &pc).is_some_and(|d| d > REACH_SHARE * kink_deg)
}

/// The point at arc length `reach` from `v` along the polyline `v`, `first`, `rest`…, or its
/// last point when it is shorter.
fn along(
    v: &[f64; 3],
    first: [f64; 3],
    rest: impl Iterator<Item = [f64; 3]>,
    reach: f64,
) -> [f64; 3] {
    let mut at = dist(v, &first);
    let mut cur = first;
    for next in rest {
        if at >= reach {
            break;
        }
        let seg = dist(&cur, &next);
        if at + seg >= reach && seg > 0.0 {
            let t = (reach - at) / seg;
            return [0, 1, 2].map(|k| cur[k] + t * (next[k] - cur[k]));
        }
        at += seg;
        cur = next;
    }
    cur
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kinked(points: &[[f64; 3]], i: usize) -> bool {
        let back = points[..i].iter().rev().copied();
        let fwd = points[i + 1..].iter().copied();
        is_kink(&points[i], back, fwd, 30.0)
    }

    #[test]
    fn a_corner_of_the_geometry_is_a_kink() {
        let l = [[0.0, 0.0, 0.0], [100.0, 0.0, 0.0], [100.0, 100.0, 0.0]];
        assert!(kinked(&l, 1));
    }

    #[test]
    fn a_corner_with_a_short_edge_next_to_it_is_still_a_kink() {
        let l = [
            [0.0, 0.0, 0.0],
            [100.0, 0.0, 0.0],
            [100.0, 1.0, 0.0],
            [100.0, 100.0, 0.0],
        ];
        assert!(kinked(&l, 1));
        assert!(!kinked(&l, 2));
    }

    #[test]
    fn a_jog_far_shorter_than_the_edges_around_it_is_not_a_kink() {
        // Climbs a 0.5 m wall over 0.1 m, then runs on: each turn is near 80° edge to edge.
        let l = [
            [0.0, 0.0, 0.0],
            [70.0, 0.0, 0.0],
            [70.1, 0.0, 0.5],
            [140.0, 0.0, 0.2],
        ];
        assert!(!kinked(&l, 1));
        assert!(!kinked(&l, 2));
    }

    #[test]
    fn a_bend_that_partly_straightens_within_the_reach_is_still_a_kink() {
        // 35° edge to edge at the origin, then back 20° a metre on: 17° over the reach.
        let (c35, s35) = (35f64.to_radians().cos(), 35f64.to_radians().sin());
        let (c15, s15) = (15f64.to_radians().cos(), 15f64.to_radians().sin());
        let l = [
            [-10.0, 0.0, 0.0],
            [0.0, 0.0, 0.0],
            [c35, s35, 0.0],
            [c35 + 10.0 * c15, s35 + 10.0 * s15, 0.0],
        ];
        assert!(kinked(&l, 1));
    }

    #[test]
    fn a_straight_run_is_no_kink_and_an_end_is_never_one() {
        let l = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]];
        assert!(!kinked(&l, 1));
        assert!(!is_kink(&l[0], [], [l[1]], 30.0));
    }

    #[test]
    fn a_turn_back_over_a_short_curve_is_measured_to_its_ends() {
        // A hairpin: the reach runs past both ends, so the chords are to the ends.
        let l = [[0.0, 0.0, 0.0], [10.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        assert!(kinked(&l, 1));
    }
}
