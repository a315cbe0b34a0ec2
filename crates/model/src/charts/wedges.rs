//! Wedges and strips: a chart that a curve of the patch's border cuts off near the chart's tip,
//! so that the chart meets the border along a stretch far shorter than its seams; or that a curve
//! cuts into a strip along it, metres wide and hundreds long.
//!
//! Charts are labelled on the whole imported surface, before curves cut it into patches. Where a
//! curve (a box side cutting a salt dome, a horizon meeting it) passes near the point where three
//! charts meet, or clips the end of a chart's lobe, the patch keeps a wedge of that chart: two
//! seams that reach the curve metres apart, or one seam that leaves the curve and comes back to
//! it. Each seam end splits the curve, so the curve holds a piece of a few metres between seams
//! that run on for a hundred, and at the case's size the elements there are flat: on a salt dome
//! cut by the box's side, a wedge one support triangle wide met the cut along 6.4 m between
//! seams of 95 m, at a size of 250 m, and the tets there reached 7.5° (12.6° once it joined the
//! chart beside it; on an intrusion cutting an older body, four joined, and 10.7° became 16.3°).
//! Where the curve runs beside a seam instead, the patch keeps a strip: on a salt overhang whose
//! underside faces between two axes, a horizon cut a chart into a strip 330 m long and 2 to 12 m
//! wide along their contact; its elements were needles, and the tets on them reached 5.4° (8.7°
//! once it joined the chart beside it).
//!
//! Decisions and why:
//! - A wedge is a chart of a patch whose border edges (edges of the patch's own border) are
//!   shorter in all than [`WEDGE`] times its seam edges, and not absent: a chart with no border
//!   is an island or a closed body's chart, which the labelling already decided.
//! - A strip is a chart of a patch with a border whose area, times four, is under [`STRIP`] times
//!   its perimeter squared (about its width over its length): the overhang's strips have 0.03 and
//!   0.04, the other charts of its salt with a border 0.05 to 0.24. It joins a chart beside it as
//!   a wedge does, but always within the chart angle: it is no tip where its chart turns away.
//! - A wedge joins the chart beside it with which it shares the longest seam, among those with
//!   which the union is still a chart (each triangle faces within the chart angle of the union's
//!   mean normal, and it projects one to one): seams only disappear, so no two seam ends come
//!   closer than before. When no chart beside it can take it, it stays.
//! - A wedge under a tenth of the taker's area may face further, up to [`WEDGE_ANGLE_DEG`]: it
//!   lies where its own chart turns away, so it faces the taker at more than the chart angle
//!   (the salt dome's, 68°), and so small it barely moves the union's mean; the one-to-one
//!   projection is what the surface mesher needs, and it is checked.
//! - The taker of a chart under a tenth of its area is not checked again: the union's mean is
//!   within asin([`SMALL`]) (5.7°) of its own, so its triangles face it as they faced their own,
//!   within that. The overhang's strip moved the mean of a chart whose triangles reach 63.4°
//!   from it to 63.9°, past the chart angle; the projection is still checked.
//! - Only the patch changes: the patch across the curve keeps its seams, whose ends still split
//!   the curve, but no end is added anywhere. Across a box side or a discarded part, there is
//!   no patch across.
//! - Charts are visited smallest first (then by label), seams compared by length (then by the
//!   lower label), so the result is the same on every machine.

use super::twists::union_flattens;
use super::{NONE, across_edges, add, area, edge_length};
use geom::TriMesh;

/// A chart is a wedge when its border is shorter than this many times its seams. The salt dome's
/// wedge has 0.07; the charts of a band of a closed body between two horizons have 0.4 to 0.6.
/// Long charts (a tube's quarters, a channel's flanks) have less, and join another only where
/// the union is still a chart.
const WEDGE: f64 = 0.25;
/// A chart is a strip when four times its area is under this share of its perimeter squared
/// (about its width over its length); see the module doc.
const STRIP: f64 = 0.05;
/// The triangles of a wedge under [`SMALL`] times the area of the chart that takes it may face
/// this far from the union's mean normal (the chart's own triangles, and a larger wedge's, the
/// chart angle): such a wedge lies where its chart turns away from the chart beside it, it
/// hardly moves the mean, and the one-to-one projection of the union, checked as well, is what
/// the surface mesher needs. The salt dome's wedge, one support triangle, faces 68° away.
const WEDGE_ANGLE_DEG: f64 = 80.0;
/// See [`WEDGE_ANGLE_DEG`].
const SMALL: f64 = 0.1;

/// Gives each wedge of a patch to a chart beside it (see the module doc); `group` is the chart of
/// each of `mesh`'s triangles, `normals` their unit (or zero) normals. Returns how many wedges
/// joined another chart.
pub fn merge_wedges(
    mesh: &TriMesh,
    normals: &[[f64; 3]],
    max_deg: f64,
    group: &mut [u32],
) -> usize {
    let across = across_edges(mesh);
    let cos_max = max_deg.to_radians().cos();
    let mut merged = 0;
    while let Some((g, h)) = next_merge(mesh, normals, &across, group, cos_max) {
        for x in group.iter_mut().filter(|x| **x == g) {
            *x = h;
        }
        merged += 1;
    }
    merged
}

/// The chart of a patch, as [`merge_wedges`] measures it.
#[derive(Clone, Default)]
struct Chart {
    members: Vec<u32>,
    area: f64,
    /// The area-weighted sum of its normals.
    mean: [f64; 3],
    /// The length of its edges on the patch's border.
    border: f64,
    /// The length of its seam with each chart beside it, by label.
    seams: Vec<(u32, f64)>,
}

/// The first wedge, smallest first, that a chart beside it can take, and that chart.
fn next_merge(
    mesh: &TriMesh,
    normals: &[[f64; 3]],
    across: &[[u32; 3]],
    group: &[u32],
    cos_max: f64,
) -> Option<(u32, u32)> {
    let charts = measure(mesh, normals, across, group);
    // Each wedge or strip, and whether it is a wedge.
    let mut order: Vec<(usize, bool)> = (0..charts.len())
        .filter_map(|g| {
            let c = &charts[g];
            let seams: f64 = c.seams.iter().map(|s| s.1).sum();
            let p = c.border + seams;
            let wedge = c.border < WEDGE * seams;
            (c.border > 0.0 && (wedge || 4.0 * c.area < STRIP * p * p)).then_some((g, wedge))
        })
        .collect();
    order.sort_by(|&(a, _), &(b, _)| charts[a].area.total_cmp(&charts[b].area).then(a.cmp(&b)));
    order.into_iter().find_map(|(g, wedge)| {
        let c = &charts[g];
        let mut beside = c.seams.clone();
        beside.sort_by(|x, y| y.1.total_cmp(&x.1).then(x.0.cmp(&y.0)));
        let h = beside.into_iter().map(|s| s.0).find(|&h| {
            let d = &charts[h as usize];
            let members = [&c.members[..], &d.members[..]];
            let small = c.area < SMALL * d.area;
            let own = if small && wedge {
                WEDGE_ANGLE_DEG.to_radians().cos()
            } else {
                cos_max
            };
            // A small piece hardly moves the taker's mean (see the module doc).
            let taker = if small { -1.0 } else { cos_max };
            let cos = [own, taker];
            union_flattens(mesh, normals, members, [c.mean, d.mean], cos)
        })?;
        Some((g as u32, h))
    })
}

/// Every chart's triangles, area, normal sum, border and seams, indexed by label.
fn measure(mesh: &TriMesh, normals: &[[f64; 3]], across: &[[u32; 3]], group: &[u32]) -> Vec<Chart> {
    let labels = group.iter().map(|&g| g as usize + 1).max().unwrap_or(0);
    let mut charts = vec![Chart::default(); labels];
    for (t, &g) in group.iter().enumerate() {
        let c = &mut charts[g as usize];
        c.members.push(t as u32);
        let a = area(mesh, t);
        c.area += a;
        add(&mut c.mean, &normals[t], a);
        for (k, &u) in across[t].iter().enumerate() {
            let len = edge_length(mesh, t as u32, k);
            if u == NONE {
                c.border += len;
            } else if group[u as usize] != g {
                let h = group[u as usize];
                match c.seams.iter_mut().find(|s| s.0 == h) {
                    Some(s) => s.1 += len,
                    None => c.seams.push((h, len)),
                }
            }
        }
    }
    charts
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A patch 10 m high and `2 * side` wide fanned around a point near its bottom side: chart 0
    /// all around, and one triangle (index 3) reaching the top side along `top` m, in chart 1,
    /// whose normal leans `deg` degrees from the others'.
    fn fan(side: f64, top: f64, deg: f64) -> (TriMesh, Vec<[f64; 3]>, Vec<u32>) {
        let h = top / 2.0;
        let mesh = TriMesh::new(
            vec![
                [5.0 - side, 0.0, 0.0],
                [5.0 + side, 0.0, 0.0],
                [5.0 + side, 10.0, 0.0],
                [5.0 + h, 10.0, 0.0],
                [5.0 - h, 10.0, 0.0],
                [5.0 - side, 10.0, 0.0],
                [5.0, 0.5, 0.0],
            ],
            vec![
                [0, 1, 6],
                [1, 2, 6],
                [2, 3, 6],
                [3, 4, 6],
                [4, 5, 6],
                [5, 0, 6],
            ],
        );
        let (s, c) = deg.to_radians().sin_cos();
        let mut normals = vec![[0.0, 0.0, 1.0]; 6];
        normals[3] = [s, 0.0, c];
        (mesh, normals, vec![0, 0, 0, 1, 0, 0])
    }

    #[test]
    fn a_chart_meeting_the_border_along_a_sliver_joins_the_chart_around_it() {
        let (mesh, normals, mut group) = fan(5.0, 0.1, 30.0);
        assert_eq!(merge_wedges(&mesh, &normals, 60.0, &mut group), 1);
        assert_eq!(group, [0; 6]);
    }

    #[test]
    fn a_small_wedge_joins_though_it_faces_beyond_the_chart_angle() {
        // As on the salt dome cut by the box: one support triangle at 68°.
        let (mesh, normals, mut group) = fan(5.0, 0.1, 68.0);
        assert_eq!(merge_wedges(&mesh, &normals, 60.0, &mut group), 1);
        assert_eq!(group, [0; 6]);
    }

    #[test]
    fn a_wedge_facing_away_beyond_the_wedge_angle_stays() {
        let (mesh, normals, mut group) = fan(5.0, 0.1, 85.0);
        assert_eq!(merge_wedges(&mesh, &normals, 60.0, &mut group), 0);
        assert_eq!(group, [0, 0, 0, 1, 0, 0]);
    }

    #[test]
    fn a_chart_with_a_long_border_keeps_its_seams() {
        // 6 m of border against two seams of 10 m: not a wedge, though the union would flatten.
        let (mesh, normals, mut group) = fan(5.0, 6.0, 0.0);
        assert_eq!(merge_wedges(&mesh, &normals, 60.0, &mut group), 0);
        assert_eq!(group, [0, 0, 0, 1, 0, 0]);
    }

    #[test]
    fn a_wedge_not_small_beside_its_taker_joins_only_within_the_chart_angle() {
        // The patch 0.3 m wide: the wedge is a fifth of the chart around it.
        for (deg, joins) in [(75.0, 0), (30.0, 1)] {
            let (mesh, normals, mut group) = fan(0.15, 0.1, deg);
            assert_eq!(
                merge_wedges(&mesh, &normals, 60.0, &mut group),
                joins,
                "{deg}°"
            );
        }
    }

    /// A patch 100 m long: a strip 0.5 m wide along its bottom side (triangles 0 to 19, chart 1)
    /// below a band 10 m wide (triangles 20 to 39, chart 0), all in the plane z = 0; the strip's
    /// normals lean `deg` degrees towards +x.
    fn strip(deg: f64) -> (TriMesh, Vec<[f64; 3]>, Vec<u32>) {
        let rows = [0.0, 0.5, 10.5];
        let vertices = (rows.iter())
            .flat_map(|&y| (0..11).map(move |i| [10.0 * i as f64, y, 0.0]))
            .collect();
        let mut triangles = Vec::new();
        for row in 0..2u32 {
            let (lo, hi) = (11 * row, 11 * (row + 1));
            for i in 0..10 {
                triangles.push([lo + i, lo + i + 1, hi + i + 1]);
                triangles.push([lo + i, hi + i + 1, hi + i]);
            }
        }
        let (s, c) = deg.to_radians().sin_cos();
        let mut normals = vec![[0.0, 0.0, 1.0]; 40];
        normals[..20].fill([s, 0.0, c]);
        let mut group = vec![0; 40];
        group[..20].fill(1);
        (TriMesh::new(vertices, triangles), normals, group)
    }

    #[test]
    fn a_strip_a_curve_cuts_along_a_seam_joins_the_chart_beside_it() {
        let (mesh, normals, mut group) = strip(11.0);
        assert_eq!(merge_wedges(&mesh, &normals, 60.0, &mut group), 1);
        assert_eq!(group, [0; 40]);
    }

    #[test]
    fn a_strip_facing_past_the_chart_angle_stays_though_a_wedge_as_small_would_join() {
        let (mesh, normals, mut group) = strip(70.0);
        assert_eq!(merge_wedges(&mesh, &normals, 60.0, &mut group), 0);
        assert_eq!(group[..20], [1; 20]);
    }

    #[test]
    fn a_small_strip_joins_a_chart_whose_own_triangles_face_past_the_chart_angle() {
        // The band's last triangle leans 63° the other way: 60.4° from the band's mean, 61.9°
        // from the union's, past the chart angle as on the overhang.
        let (mesh, mut normals, mut group) = strip(30.0);
        let (s, c) = 63f64.to_radians().sin_cos();
        normals[39] = [-s, 0.0, c];
        assert_eq!(merge_wedges(&mesh, &normals, 60.0, &mut group), 1);
        assert_eq!(group, [0; 40]);
    }
}
