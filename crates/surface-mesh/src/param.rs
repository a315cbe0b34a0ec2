//! Flattening of a support triangulation to a 2D parameter plane, so that the patch can be
//! meshed in 2D with exact predicates and mapped back onto the support through the support's own
//! triangles (every mesh node then lies on the support by construction).
//!
//! Decisions and why:
//! - First choice: orthogonal projection onto the plane normal to the area-weighted mean normal.
//!   It is accepted only if every support triangle is strictly counter-clockwise in the plane
//!   (exact `orient2d` on the projected coordinates), the projected support border has no
//!   crossing (exact segment tests) and only the outer borders run counter-clockwise (exact, at
//!   each simple cycle's lowest vertex: as many counter-clockwise cycles as the support has
//!   pieces connected across edges): a locally injective, orientation-preserving map of a
//!   disk-with-holes whose border stays simple and whose holes keep their orientation is
//!   injective. (A hole whose image turns the wrong way is a fold the triangles alone do not
//!   show: a sliver standing up in a dome flattens to a hole that overlaps its neighbours, and a
//!   reverse fault's slit whose lips overlap in map view does too. Orientation is judged per
//!   simple cycle, the loops split at their pinches: a slit pinched to another hole is a loop of
//!   two lobes, and the lowest vertex of the loop sees only one of them.) This
//!   keeps the geometry nearly isometric for horizons and steep faults alike (the plane follows
//!   the surface, not z).
//! - The border is traced edge by edge around each vertex's fan, so a support pinched at a
//!   vertex (two faults meeting its border at one point) has that vertex once per fan in its
//!   loops; a projection handles it like any border. A Tutte embedding splits each loop at its
//!   pinches into simple cycles and pins or cones each cycle on its own, so the pinch stays one
//!   point with the support's fans and the cones' holes in turn around it (a hole touching the
//!   outer border, two holes touching, a reverse fault's overlapping lips meeting a border).
//! - Second choice: the exact projection onto the axis plane the mean normal points along most
//!   (`axis_uv`: one coordinate dropped, nothing computed), under the same test. The mean plane's
//!   rotation rounds each coordinate, which can turn a triangle with a sub-nanometre edge (two
//!   curve points a rounding error apart, where a surface's edge passes a box edge) the wrong way
//!   on a plane that a box side is exactly.
//! - Third choice, where the mean plane's projection turns a few triangles over but its border
//!   does not cross itself (a tooth of a chart's border curled round a smoothed body's rim, a
//!   cap left standing): that projection mended (`relax`), under the same test, so the rest of
//!   the support keeps its projected shapes.
//! - Otherwise (recumbent folds, caps down to their equator, overlapping lips): a Tutte
//!   embedding with mean value weights (`tutte`, which says how its border is pinned); the
//!   solution is still checked triangle by triangle with `orient2d`, and a failure is an error.

use super::segments::first_crossing;
use geom::predicates::{cross, dot, sub};
use geom::{Orientation, TriMesh, orient2d};
use std::collections::BTreeMap;

/// A flattening: one 2D point per support vertex (unused vertices get the origin).
pub struct Param {
    pub uv: Vec<[f64; 2]>,
    /// "plane", "relaxed" or "tutte": for reports.
    pub method: &'static str,
}

/// Why a support could not be flattened, with the 3D place.
pub struct ParamError {
    pub message: String,
    pub at: Option<[f64; 3]>,
}

fn err(message: String, at: Option<[f64; 3]>) -> ParamError {
    ParamError { message, at }
}

/// The directed border half-edges of the support, chained into loops, and manifold checks.
pub fn border_loops(s: &TriMesh) -> Result<Vec<Vec<u32>>, ParamError> {
    let nv = s.vertices.len();
    let mut directed: BTreeMap<(u32, u32), u32> = BTreeMap::new();
    for (t, tri) in s.triangles.iter().enumerate() {
        for &v in tri {
            if v as usize >= nv {
                return Err(err(
                    format!("support triangle {t} refers to missing vertex {v}"),
                    None,
                ));
            }
        }
        if tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2] {
            return Err(err(
                format!("support triangle {t} repeats a vertex"),
                Some(s.vertices[tri[0] as usize]),
            ));
        }
        for i in 0..3 {
            let e = (tri[i], tri[(i + 1) % 3]);
            if directed.insert(e, t as u32).is_some() {
                return Err(err(
                    format!(
                        "support edge {}-{} is used twice in the same direction (non-manifold or inconsistently oriented support)",
                        e.0, e.1
                    ),
                    Some(s.vertices[e.0 as usize]),
                ));
            }
        }
    }
    // Border half-edges, each chained to the next one around its end vertex's fan, so that a
    // vertex where the border touches itself (a pinch) is passed once per fan.
    let border: Vec<(u32, u32)> = directed
        .keys()
        .copied()
        .filter(|&(a, b)| !directed.contains_key(&(b, a)))
        .collect();
    let mut used: BTreeMap<(u32, u32), bool> = BTreeMap::new();
    let mut loops = Vec::new();
    for &first in &border {
        if used.contains_key(&first) {
            continue;
        }
        let mut lp = Vec::new();
        let mut e = first;
        loop {
            used.insert(e, true);
            lp.push(e.0);
            let next = next_border_edge(s, &directed, e)?;
            if next == first {
                break;
            }
            if used.contains_key(&next) {
                return Err(err(
                    "support border does not close into loops".into(),
                    Some(s.vertices[next.0 as usize]),
                ));
            }
            e = next;
        }
        loops.push(lp);
    }
    Ok(loops)
}

/// The border half-edge that follows `(a, b)`: the first edge out of `b` without a twin, turning
/// around `b` through the triangles of `(a, b)`'s fan.
fn next_border_edge(
    s: &TriMesh,
    directed: &BTreeMap<(u32, u32), u32>,
    (a, b): (u32, u32),
) -> Result<(u32, u32), ParamError> {
    let mut t = directed[&(a, b)];
    for _ in 0..=s.triangles.len() {
        let tri = s.triangles[t as usize];
        let k = tri.iter().position(|&v| v == b).unwrap_or(0);
        let c = tri[(k + 1) % 3];
        match directed.get(&(c, b)) {
            Some(&u) => t = u,
            None => return Ok((b, c)),
        }
    }
    Err(err(
        "support border does not close into loops".into(),
        Some(s.vertices[b as usize]),
    ))
}

/// Flattens the support (see the module doc for the choice).
pub fn flatten(s: &TriMesh) -> Result<Param, ParamError> {
    if s.triangles.is_empty() {
        return Err(err("the support has no triangles".into(), None));
    }
    for (i, v) in s.vertices.iter().enumerate() {
        if v.iter().any(|c| !c.is_finite()) {
            return Err(err(format!("support vertex {i} is not finite"), None));
        }
    }
    let loops = border_loops(s)?;
    if loops.is_empty() {
        return Err(err(
            "the support is closed (no border): it must come split into disk-like patches".into(),
            s.vertices.first().copied(),
        ));
    }
    check_connected(s)?;
    if let Some(uv) = plane_projection(s, &loops) {
        return Ok(Param {
            uv,
            method: "plane",
        });
    }
    if let Some(uv) = mean_plane_uv(s).and_then(|uv| super::relax::mended(s, &loops, &uv)) {
        return Ok(Param {
            uv,
            method: "relaxed",
        });
    }
    let uv = super::tutte::embed(s, &loops)?;
    Ok(Param {
        uv,
        method: "tutte",
    })
}

fn check_connected(s: &TriMesh) -> Result<(), ParamError> {
    let nv = s.vertices.len();
    let mut parent: Vec<u32> = (0..nv as u32).collect();
    for t in &s.triangles {
        for i in 0..3 {
            let a = find(&mut parent, t[i]);
            let b = find(&mut parent, t[(i + 1) % 3]);
            if a != b {
                parent[a.max(b) as usize] = a.min(b);
            }
        }
    }
    let r0 = find(&mut parent, s.triangles[0][0]);
    for t in &s.triangles {
        if find(&mut parent, t[0]) != r0 {
            return Err(err(
                "the support has several disconnected pieces".into(),
                Some(s.vertices[t[0] as usize]),
            ));
        }
    }
    Ok(())
}

/// The root of `x` in the union-find forest `p`, halving the path on the way.
fn find(p: &mut [u32], mut x: u32) -> u32 {
    while p[x as usize] != x {
        let g = p[p[x as usize] as usize];
        p[x as usize] = g;
        x = g;
    }
    x
}

/// An orthonormal basis (e1, e2) of the plane normal to `n`, with e1 × e2 = n / |n|.
pub fn plane_basis(n: [f64; 3]) -> ([f64; 3], [f64; 3]) {
    let l = dot(&n, &n).sqrt();
    let n = [n[0] / l, n[1] / l, n[2] / l];
    let a = if n[0].abs() < 0.6 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let e1 = cross(&a, &n);
    let l1 = dot(&e1, &e1).sqrt();
    let e1 = [e1[0] / l1, e1[1] / l1, e1[2] / l1];
    let e2 = cross(&n, &e1);
    (e1, e2)
}

/// The sum of the support triangles' normals, each as long as twice its area.
fn area_normal(s: &TriMesh) -> [f64; 3] {
    let mut n = [0.0; 3];
    for t in 0..s.triangles.len() {
        let [a, b, c] = s.corners(t);
        let c = cross(&sub(b, a), &sub(c, a));
        n = [n[0] + c[0], n[1] + c[1], n[2] + c[2]];
    }
    n
}

/// Every support vertex projected onto the plane normal to the area-weighted mean normal (about
/// the bounding box's centre); `None` when the normals cancel out.
pub fn mean_plane_uv(s: &TriMesh) -> Option<Vec<[f64; 2]>> {
    let n = area_normal(s);
    if !(dot(&n, &n) > 0.0) {
        return None;
    }
    let (e1, e2) = plane_basis(n);
    let o = centre(s);
    Some(
        s.vertices
            .iter()
            .map(|p| {
                let d = sub(p, &o);
                [dot(&d, &e1), dot(&d, &e2)]
            })
            .collect(),
    )
}

fn plane_projection(s: &TriMesh, loops: &[Vec<u32>]) -> Option<Vec<[f64; 2]>> {
    (mean_plane_uv(s).filter(|uv| injective(s, loops, uv)))
        .or_else(|| axis_uv(s).filter(|uv| injective(s, loops, uv)))
}

/// Every support vertex with the coordinate along the mean normal's largest component dropped,
/// the other two ordered so that the support keeps its orientation: an exact projection (no
/// coordinate is computed), so a support lying in an axis plane, as a box side does, projects
/// with every triangle's orientation as the exact predicates see it in 3D, even beside a curve
/// point a rounding error away from another. `None` when the normals cancel out.
pub fn axis_uv(s: &TriMesh) -> Option<Vec<[f64; 2]>> {
    let n = area_normal(s);
    let k = (0..3).max_by(|&i, &j| n[i].abs().total_cmp(&n[j].abs()))?;
    if !(n[k].abs() > 0.0) {
        return None;
    }
    // (k + 1, k + 2) is right-handed about axis k; swapped when the normal points down it.
    let (u, v) = ((k + 1) % 3, (k + 2) % 3);
    let (u, v) = if n[k] > 0.0 { (u, v) } else { (v, u) };
    Some(s.vertices.iter().map(|p| [p[u], p[v]]).collect())
}

/// The first two border edges of the support (each as its directed vertex pair) that conflict on
/// the plane of its mean normal, when neither projection that the flattening tries first is one to
/// one: `None` when a projection is accepted, when the border projects without a crossing (the
/// projection fails for another reason), or when there is no border to project (no mean normal,
/// a non-manifold support). Lets whoever cuts a surface into pieces keep each piece flat on its
/// own plane, as the plane keeps the support's shapes and a Tutte embedding distorts them.
pub fn projected_border_conflict(s: &TriMesh) -> Option<[[u32; 2]; 2]> {
    let loops = border_loops(s).ok()?;
    if plane_projection(s, &loops).is_some() {
        return None;
    }
    let uv = mean_plane_uv(s)?;
    let edges: Vec<[u32; 2]> = loops
        .iter()
        .flat_map(|l| (0..l.len()).map(move |i| [l[i], l[(i + 1) % l.len()]]))
        .collect();
    let segs: Vec<([f64; 2], [f64; 2])> = edges
        .iter()
        .map(|&[a, b]| (uv[a as usize], uv[b as usize]))
        .collect();
    first_crossing(&segs).map(|(i, j)| [edges[i], edges[j]])
}

/// Whether one of the projections that the flattening tries first maps the support one to one:
/// then its surface mesh is made on a plane, with the support's shapes kept.
pub fn projects_one_to_one(s: &TriMesh) -> bool {
    border_loops(s).is_ok_and(|loops| !loops.is_empty() && plane_projection(s, &loops).is_some())
}

/// Whether two edges of the border `loops` cross in `uv` (exact).
pub fn border_crosses(loops: &[Vec<u32>], uv: &[[f64; 2]]) -> bool {
    let segs: Vec<([f64; 2], [f64; 2])> = loops
        .iter()
        .flat_map(|l| (0..l.len()).map(move |i| (l[i], l[(i + 1) % l.len()])))
        .map(|(a, b)| (uv[a as usize], uv[b as usize]))
        .collect();
    first_crossing(&segs).is_some()
}

/// Whether `uv` maps the support one to one (exact): every triangle counter-clockwise, the border
/// `loops` free of crossings and, of their simple cycles, only the outer borders (one per piece
/// connected across edges) counter-clockwise.
pub fn injective(s: &TriMesh, loops: &[Vec<u32>], uv: &[[f64; 2]]) -> bool {
    if !all_positive(s, uv) || border_crosses(loops, uv) {
        return false;
    }
    let outer = loops
        .iter()
        .flat_map(|l| simple_cycles(l))
        .filter(|c| counter_clockwise(c, uv) == Some(true));
    outer.count() == edge_connected_pieces(s)
}

/// A closed walk split into simple cycles at its repeated vertices, in the order they close (the
/// remainder last): `a b c b d` gives `b c` and `a b d`.
pub fn simple_cycles(walk: &[u32]) -> Vec<Vec<u32>> {
    let mut cycles = Vec::new();
    let mut path: Vec<u32> = Vec::with_capacity(walk.len());
    for &v in walk {
        if let Some(k) = path.iter().rposition(|&u| u == v) {
            cycles.push(path.split_off(k));
        }
        path.push(v);
    }
    cycles.push(path);
    cycles
}

/// The number of pieces of the support whose triangles connect across edges (pieces touching
/// at a vertex only, a pinch, count apart: each has its own outer border).
fn edge_connected_pieces(s: &TriMesh) -> usize {
    let mut parent: Vec<u32> = (0..s.triangles.len() as u32).collect();
    let mut by_edge: BTreeMap<(u32, u32), u32> = BTreeMap::new();
    for (t, tri) in s.triangles.iter().enumerate() {
        for i in 0..3 {
            let (a, b) = (tri[i], tri[(i + 1) % 3]);
            if let Some(&u) = by_edge.get(&(b, a)) {
                let (x, y) = (find(&mut parent, u), find(&mut parent, t as u32));
                parent[x.max(y) as usize] = x.min(y);
            }
            by_edge.insert((a, b), t as u32);
        }
    }
    (0..s.triangles.len() as u32)
        .filter(|&t| find(&mut parent, t) == t)
        .count()
}

/// The orientation of a simple polygon (exact): at its lowest-leftmost vertex the polygon turns
/// the way it runs. `None` when the turn there is degenerate.
pub fn counter_clockwise(polygon: &[u32], uv: &[[f64; 2]]) -> Option<bool> {
    let n = polygon.len();
    let at = |i: usize| uv[polygon[i % n] as usize];
    let low = (0..n).min_by(|&i, &j| {
        let (p, q) = (at(i), at(j));
        p[1].total_cmp(&q[1]).then(p[0].total_cmp(&q[0]))
    })?;
    match orient2d(&at(low + n - 1), &at(low), &at(low + 1)) {
        Orientation::Positive => Some(true),
        Orientation::Negative => Some(false),
        _ => None,
    }
}

pub fn centre(s: &TriMesh) -> [f64; 3] {
    let b = s.bbox();
    [
        0.5 * (b.min[0] + b.max[0]),
        0.5 * (b.min[1] + b.max[1]),
        0.5 * (b.min[2] + b.max[2]),
    ]
}

/// Whether every support triangle is strictly counter-clockwise in `uv` (exact).
pub fn all_positive(s: &TriMesh, uv: &[[f64; 2]]) -> bool {
    first_non_positive(s, uv).is_none()
}

pub fn first_non_positive(s: &TriMesh, uv: &[[f64; 2]]) -> Option<usize> {
    s.triangles.iter().position(|t| {
        orient2d(&uv[t[0] as usize], &uv[t[1] as usize], &uv[t[2] as usize])
            != Orientation::Positive
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn flat(vertices: &[[f64; 2]], triangles: Vec<[u32; 3]>) -> TriMesh {
        TriMesh::new(
            vertices.iter().map(|p| [p[0], p[1], 0.0]).collect(),
            triangles,
        )
    }

    #[test]
    fn the_axis_projection_keeps_the_orientation_whichever_way_the_normal_points() {
        for k in 0..3 {
            for sign in [1.0, -1.0] {
                // A triangle in the plane normal to axis k, turning about +k or -k.
                let mut p = [[0.0; 3]; 3];
                p[1][(k + 1) % 3] = 1.0;
                p[2][(k + 2) % 3] = sign;
                let s = TriMesh::new(p.to_vec(), vec![[0, 1, 2]]);
                let uv = axis_uv(&s).expect("a plane");
                assert!(all_positive(&s, &uv), "axis {k}, sign {sign}");
                assert!(
                    uv.iter()
                        .zip(&p)
                        .all(|(q, x)| q.iter().all(|c| x.contains(c)))
                );
            }
        }
    }

    #[test]
    fn two_pieces_touching_at_a_vertex_each_have_their_outer_border() {
        // A bowtie: two triangles sharing vertex 0, one border loop through it twice.
        let s = flat(
            &[
                [0.0, 0.0],
                [1.0, -1.0],
                [1.0, 1.0],
                [-1.0, 1.0],
                [-1.0, -1.0],
            ],
            vec![[0, 1, 2], [0, 3, 4]],
        );
        let loops = border_loops(&s).unwrap_or_else(|e| panic!("{}", e.message));
        assert_eq!(edge_connected_pieces(&s), 2);
        assert!(injective(&s, &loops, &mean_plane_uv(&s).expect("a plane")));
    }

    #[test]
    fn a_pinched_loop_with_a_lobe_turning_the_wrong_way_is_not_one_to_one() {
        // One piece (a square fan round its centre 5) and a border walk through its corner 0
        // twice, with a lobe 0 6 7 inside that runs counter-clockwise like the outer border and
        // crosses nothing: the walk's lowest vertex, 0, sees only the outer turn.
        let s = flat(
            &[
                [0.0, 0.0],
                [2.0, 0.0],
                [2.0, 2.0],
                [0.0, 2.0],
                [-1.0, -1.0],
                [1.0, 1.0],
                [1.0, 0.3],
                [0.3, 1.0],
            ],
            vec![[0, 1, 5], [1, 2, 5], [2, 3, 5], [3, 0, 5]],
        );
        let uv = mean_plane_uv(&s).expect("a plane");
        assert!(!injective(&s, &[vec![0, 1, 2, 3, 0, 6, 7]], &uv));
        assert!(injective(&s, &[vec![0, 1, 2, 3]], &uv));
    }

    fn ramp(turn_deg: f64) -> TriMesh {
        let (v, t) = test_support::shapes::ramp(turn_deg, 5.0);
        TriMesh::new(v, t)
    }

    #[test]
    fn a_ramp_winding_past_a_full_turn_conflicts_on_its_plane_and_one_short_of_it_projects() {
        let over = ramp(400.0);
        assert!(!projects_one_to_one(&over));
        let [a, b] = projected_border_conflict(&over).expect("a crossing");
        // Both edges are border edges of the ribbon, as its triangles run them.
        for [p, q] in [a, b] {
            assert!(
                over.triangles
                    .iter()
                    .any(|t| (0..3).any(|k| t[k] == p && t[(k + 1) % 3] == q))
            );
        }
        let short = ramp(300.0);
        assert!(projects_one_to_one(&short));
        assert_eq!(projected_border_conflict(&short), None);
    }
}
