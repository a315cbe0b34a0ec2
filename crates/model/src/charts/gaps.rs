//! Gaps: the few triangles of other charts that part a chart's fans round one vertex.
//!
//! A chart must be one fan round each of its vertices (`unpinch`). When a triangle joins a
//! chart across one edge, its far corner may touch the same chart again, a triangle or two
//! round the vertex: the chart is then pinched there. Giving the triangle back undoes the move,
//! and where the move was made to mend a crossing (`untwist`), the two alternate for ever: on the
//! smoothed channel's tip, a needle moved to the chart beside it and came back on every pass,
//! and the chart it came back to kept a border that crossed itself on its plane.
//!
//! Decisions and why:
//! - The gap is closed instead: the triangles between the joined triangle and the chart's next
//!   fan round the vertex, the shorter way round, join the chart too. Closing only adds
//!   triangles to a chart, beside the one that joined it.
//! - Only a short gap, of at most [`MAX_GAP`] triangles, is closed, and the caller takes it only
//!   where every one of its triangles faces the chart as any member must: a long gap is not a
//!   pinch left by one triangle, and a triangle facing away has no place in the chart.
//! - The walk goes round the vertex across shared edges in a fixed order and is bounded, so the
//!   gap is the same on every machine, and a border or a non-manifold edge ends it.

use super::NONE;
use geom::TriMesh;

/// Most triangles a gap may hold to be closed.
pub const MAX_GAP: usize = 4;

/// Most steps of a walk round one vertex.
const MAX_STEPS: usize = 256;

/// The triangles between triangle `t` of chart `group[t]` and the next fan of that chart round
/// `t`'s corner `v`, the shorter way round, when the chart is more than one fan there and the
/// gap holds at most [`MAX_GAP`] triangles; `across` is [`super::across_edges`] of `mesh`.
pub fn gap_at(
    mesh: &TriMesh,
    across: &[[u32; 3]],
    group: &[u32],
    t: u32,
    v: u32,
) -> Option<Vec<u32>> {
    let chart = group[t as usize];
    let fan = own_fan(mesh, across, group, t, v);
    let mut best: Option<Vec<u32>> = None;
    for edge in edges_at(mesh, t, v) {
        let mut gap = Vec::new();
        let (mut cur, mut e) = (t, edge);
        let end = loop {
            let next = across[cur as usize][e];
            if next == NONE || gap.len() > MAX_GAP {
                break None;
            }
            if group[next as usize] == chart {
                break Some(next);
            }
            gap.push(next);
            let Some(k) = other_edge_at(mesh, across, next, v, cur) else {
                break None;
            };
            (cur, e) = (next, k);
        };
        let closes = end.is_some_and(|u| !fan.contains(&u)) && !gap.is_empty();
        if closes && best.as_ref().is_none_or(|b| gap.len() < b.len()) {
            best = Some(gap);
        }
    }
    best
}

/// The triangles of `t`'s chart edge-connected to `t` round its corner `v`.
fn own_fan(mesh: &TriMesh, across: &[[u32; 3]], group: &[u32], t: u32, v: u32) -> Vec<u32> {
    let chart = group[t as usize];
    let mut fan = vec![t];
    for edge in edges_at(mesh, t, v) {
        let (mut cur, mut e) = (t, edge);
        for _ in 0..MAX_STEPS {
            let next = across[cur as usize][e];
            if next == NONE || group[next as usize] != chart || fan.contains(&next) {
                break;
            }
            fan.push(next);
            let Some(k) = other_edge_at(mesh, across, next, v, cur) else {
                break;
            };
            (cur, e) = (next, k);
        }
    }
    fan
}

/// The two edges of triangle `t` at its corner `v` (edge `k` runs from corner `k` to `k + 1`).
fn edges_at(mesh: &TriMesh, t: u32, v: u32) -> Vec<usize> {
    let tri = mesh.triangles[t as usize];
    match tri.iter().position(|&x| x == v) {
        Some(i) => vec![i, (i + 2) % 3],
        None => Vec::new(),
    }
}

/// The edge of triangle `t` at corner `v` that it does not share with `from`.
fn other_edge_at(mesh: &TriMesh, across: &[[u32; 3]], t: u32, v: u32, from: u32) -> Option<usize> {
    let edges = edges_at(mesh, t, v);
    let shared = edges
        .iter()
        .filter(|&&k| across[t as usize][k] == from)
        .count();
    if shared != 1 {
        return None;
    }
    edges.into_iter().find(|&k| across[t as usize][k] != from)
}

#[cfg(test)]
mod tests {
    use super::super::across_edges;
    use super::*;

    /// A fan of `n` triangles round vertex 0 at the origin, its rim on the unit circle: closed
    /// round it when `closed`, else spread over a half turn.
    fn fan(n: usize, closed: bool) -> TriMesh {
        let rim = if closed { n } else { n + 1 };
        let turn = if closed { 1.0 } else { 0.5 };
        let mut v = vec![[0.0, 0.0, 0.0]];
        for k in 0..rim {
            let a = std::f64::consts::TAU * turn * k as f64 / n as f64;
            v.push([a.cos(), a.sin(), 0.0]);
        }
        let t = (0..n)
            .map(|k| [0, 1 + k as u32, 1 + ((k + 1) % rim) as u32])
            .collect();
        TriMesh::new(v, t)
    }

    #[test]
    fn the_gap_between_two_fans_of_a_chart_is_the_shorter_way_round() {
        let m = fan(8, true);
        let across = across_edges(&m);
        // Chart 1 holds triangles 0, 1 and 4: fans {0, 1} and {4}, parted by {2, 3} one way
        // and {5, 6, 7} the other.
        let group = [1, 1, 0, 0, 1, 0, 0, 0];
        assert_eq!(gap_at(&m, &across, &group, 4, 0), Some(vec![3, 2]));
        assert_eq!(gap_at(&m, &across, &group, 1, 0), Some(vec![2, 3]));
    }

    #[test]
    fn a_chart_that_is_one_fan_round_the_vertex_has_no_gap() {
        let m = fan(8, true);
        let across = across_edges(&m);
        let group = [1, 1, 1, 0, 0, 0, 0, 0];
        assert_eq!(gap_at(&m, &across, &group, 1, 0), None);
        assert_eq!(gap_at(&m, &across, &group, 0, 0), None);
    }

    #[test]
    fn a_long_gap_or_one_open_to_the_border_is_not_closed() {
        let closed = fan(12, true);
        let across = across_edges(&closed);
        // Chart 1's two fans are five triangles apart either way.
        let group = [1, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0];
        assert_eq!(gap_at(&closed, &across, &group, 0, 0), None);
        // On an open fan, the way past the border reaches no fan at all, and the way round
        // is five triangles long.
        let open = fan(7, false);
        let across = across_edges(&open);
        let group = [1, 0, 0, 0, 0, 0, 1];
        assert_eq!(gap_at(&open, &across, &group, 0, 0), None);
        assert_eq!(gap_at(&open, &across, &group, 6, 0), None);
        // Two triangles apart, the way round is closed, not the way past the border.
        let group = [1, 0, 0, 1, 0, 0, 0];
        assert_eq!(gap_at(&open, &across, &group, 3, 0), Some(vec![2, 1]));
    }
}
