//! How far each curve point is from the other curves of the patches it bounds, measured where
//! the surface mesher draws them: in each patch's plane.
//!
//! A curve's FE segments are chords of its polyline. Two chords of one patch that cross in the
//! patch's plane leave no surface mesh possible, and shared curve nodes cannot be moved once
//! discretized; so the discretization keeps every chord within half this clearance of its curve
//! (`discretize`). A chord within `d` of its sub-polyline is within `d` of it both ways (the
//! polyline joins the chord's ends inside the chord's `d`-tube), so two chords that each keep
//! within half the distance between their curves cannot meet.
//!
//! Decisions and why:
//! - The plane is the one normal to the patch's area-weighted mean normal, the plane the surface
//!   mesher projects onto; an orthogonal projection never lengthens a distance, so a chord that
//!   keeps within half the plane clearance in 3D keeps within it in the plane too.
//! - Only the parts of curves *apart* from the point count: a piece of curve farther from the
//!   point along the curves (along its own curve, or through an end the two curves share) than
//!   `DETOUR` (20) times its distance in the plane. Its own neighbours and the curves leaving a
//!   shared end at an open angle are not apart (their chords follow each other, or cross only if
//!   they swap sides at the end, which distance does not measure); counted, their clearance would
//!   shrink to zero at every junction and split a stair-stepped curve (a chart seam along support
//!   edges) into its support edges there, which cost the salt cases tets of 2° dihedral angle.
//!   But the two lips of a sliver between faults, which leave their common end at a fraction of a
//!   degree and run side by side for kilometres, and a curve that comes back along itself, are
//!   apart: their chords would cross.
//! - A curve on several patches takes the smallest clearance; a point with no other curve in any
//!   of its patches has an infinite clearance.
//! - Work is bounded: a point looks at `MAX_CANDIDATES` nearest pieces of curve at most, and a
//!   point with none apart among them keeps an infinite clearance from that patch.

use crate::regions::PatchIn;
use crate::{Curve, PatchBoundary};
use geom::predicates::{cross, dot, sub};
use rstar::RTree;
use rstar::primitives::{GeomWithData, Line};

/// A projected curve segment tagged with its curve and its index along it.
type Segment = GeomWithData<Line<[f64; 2]>, (u32, u32)>;

/// Per curve, per polyline point, the clearance (see the module doc); `bounds` are the patches'
/// boundaries, parallel to `patches`.
pub fn clearances(
    curves: &[Curve],
    bounds: &[PatchBoundary],
    patches: &[PatchIn],
) -> Vec<Vec<f64>> {
    let mut out: Vec<Vec<f64>> = curves
        .iter()
        .map(|c| vec![f64::INFINITY; c.points.len()])
        .collect();
    let arcs = arc_lengths(curves);
    for (b, p) in bounds.iter().zip(patches) {
        let Some(plane) = PlaneCurves::new(curves, &arcs, b, p) else {
            continue;
        };
        for &c in &plane.used {
            for (k, q) in curves[c as usize].points.iter().enumerate() {
                let at = Along {
                    curve: c,
                    arc: arcs[c as usize][k],
                };
                let slot = &mut out[c as usize][k];
                *slot = slot.min(plane.apart(at, q, DETOUR));
            }
        }
    }
    out
}

/// One patch's curves drawn in its plane, searchable for the nearest piece apart from a place
/// on one of them.
pub(crate) struct PlaneCurves<'a> {
    curves: &'a [Curve],
    arcs: &'a [Vec<f64>],
    project: Projection,
    tree: RTree<Segment>,
    /// The curves the patch's loops and constraints use, ascending.
    pub used: Vec<u32>,
}

impl<'a> PlaneCurves<'a> {
    /// `None` for a patch with no curve or no plane to draw in.
    pub fn new(
        curves: &'a [Curve],
        arcs: &'a [Vec<f64>],
        bound: &PatchBoundary,
        patch: &PatchIn,
    ) -> Option<Self> {
        let used = bound.curves();
        if used.is_empty() {
            return None;
        }
        let project = Projection::of(&patch.mesh)?;
        let segments: Vec<Segment> = used
            .iter()
            .flat_map(|&c| {
                let pts = &curves[c as usize].points;
                let project = &project;
                pts.windows(2).enumerate().map(move |(t, w)| {
                    let line = Line::new(project.at(&w[0]), project.at(&w[1]));
                    Segment::new(line, (c, t as u32))
                })
            })
            .collect();
        Some(PlaneCurves {
            curves,
            arcs,
            project,
            tree: RTree::bulk_load(segments),
            used,
        })
    }

    /// The distance in the plane from `q` (at place `at` of one of the curves) to the nearest
    /// piece of the patch's curves apart from it; infinite when none is among the nearest
    /// `MAX_CANDIDATES`.
    pub fn apart(&self, at: Along, q: &[f64; 3], ratio: f64) -> f64 {
        let q = self.project.at(q);
        self.tree
            .nearest_neighbor_iter_with_distance_2(q)
            .take(MAX_CANDIDATES)
            .find(|(s, d2)| {
                let (j, t) = s.data;
                let arc = arc_at(&self.arcs[j as usize], t, s.geom(), &q);
                let there = Along { curve: j, arc };
                // The place's own piece of curve, a rounding away, is never apart from it.
                let own = ARC_EPS * self.arcs[at.curve as usize].last().copied().unwrap_or(0.0);
                detour(self.curves, self.arcs, at, there) > ratio * d2.sqrt() + own
            })
            .map_or(f64::INFINITY, |(_, d2)| d2.sqrt())
    }
}

/// A piece of curve is apart from a point when the way between them along the curves is longer
/// than this many times their distance in the plane: two curves leaving a shared end less than
/// about 6° apart (2 / `DETOUR` radians), a curve doubling back on itself. Curves meeting at an
/// open angle (a chart seam leaving a salt body's rim at 10°) stay out, so their stair-steps near
/// the junction are not split into support edges.
const DETOUR: f64 = 20.0;
/// Relative to its curve's length, the arc length by which a place may miss its own piece of
/// curve by rounding.
const ARC_EPS: f64 = 1e-9;
/// Nearest pieces of curve a point looks at for one apart from it.
const MAX_CANDIDATES: usize = 4096;

/// A place on a curve: the curve and the arc length from its first point.
#[derive(Clone, Copy)]
pub(crate) struct Along {
    pub curve: u32,
    pub arc: f64,
}

/// Cumulative arc length at each point of each curve.
pub(crate) fn arc_lengths(curves: &[Curve]) -> Vec<Vec<f64>> {
    curves
        .iter()
        .map(|c| {
            let mut total = 0.0;
            let mut out = Vec::with_capacity(c.points.len());
            for (k, p) in c.points.iter().enumerate() {
                if k > 0 {
                    let d = sub(p, &c.points[k - 1]);
                    total += dot(&d, &d).sqrt();
                }
                out.push(total);
            }
            out
        })
        .collect()
}

/// The arc length of the point of segment `t` (of a curve with arc lengths `arcs`) nearest `q`
/// in the plane.
fn arc_at(arcs: &[f64], t: u32, seg: &Line<[f64; 2]>, q: &[f64; 2]) -> f64 {
    let (a, b) = (seg.from, seg.to);
    let ab = [b[0] - a[0], b[1] - a[1]];
    let l2 = ab[0] * ab[0] + ab[1] * ab[1];
    let f = if l2 > 0.0 {
        (((q[0] - a[0]) * ab[0] + (q[1] - a[1]) * ab[1]) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let (s0, s1) = (arcs[t as usize], arcs[t as usize + 1]);
    s0 + f * (s1 - s0)
}

/// The length of the way along the curves between two places: along the curve itself (either
/// way round a closed one), or through an end the two curves share; infinite when the curves
/// share no end.
fn detour(curves: &[Curve], arcs: &[Vec<f64>], a: Along, b: Along) -> f64 {
    let len = |c: u32| arcs[c as usize].last().copied().unwrap_or(0.0);
    if a.curve == b.curve {
        let d = (a.arc - b.arc).abs();
        return if curves[a.curve as usize].closed {
            d.min(len(a.curve) - d)
        } else {
            d
        };
    }
    let ends = |c: u32| {
        let pts = &curves[c as usize].points;
        [(pts.first().copied(), 0.0), (pts.last().copied(), len(c))]
    };
    let mut best = f64::INFINITY;
    for (pa, sa) in ends(a.curve) {
        for (pb, sb) in ends(b.curve) {
            if pa.is_some() && pa == pb {
                best = best.min((a.arc - sa).abs() + (b.arc - sb).abs());
            }
        }
    }
    best
}

/// Orthogonal projection onto the plane normal to a mesh's area-weighted mean normal.
struct Projection {
    e1: [f64; 3],
    e2: [f64; 3],
}

impl Projection {
    /// `None` when the triangles' normals cancel out (no plane to draw in).
    fn of(mesh: &geom::TriMesh) -> Option<Self> {
        let mut n = [0.0; 3];
        for t in 0..mesh.triangles.len() {
            let [a, b, c] = mesh.corners(t);
            let m = cross(&sub(b, a), &sub(c, a));
            n = [n[0] + m[0], n[1] + m[1], n[2] + m[2]];
        }
        let len = dot(&n, &n).sqrt();
        if !(len > 0.0 && len.is_finite()) {
            return None;
        }
        let n = [n[0] / len, n[1] / len, n[2] / len];
        // Any unit vector across `n`: the axis `n` leans on least.
        let k = (0..3)
            .min_by(|&i, &j| n[i].abs().total_cmp(&n[j].abs()))
            .unwrap_or(0);
        let mut axis = [0.0; 3];
        axis[k] = 1.0;
        let e1 = cross(&n, &axis);
        let l1 = dot(&e1, &e1).sqrt();
        let e1 = [e1[0] / l1, e1[1] / l1, e1[2] / l1];
        Some(Projection {
            e1,
            e2: cross(&n, &e1),
        })
    }

    fn at(&self, p: &[f64; 3]) -> [f64; 2] {
        [dot(p, &self.e1), dot(p, &self.e2)]
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::CurveUse;
    use geom::TriMesh;

    pub(crate) fn curve(name: &str, points: Vec<[f64; 3]>) -> Curve {
        Curve {
            name: name.into(),
            surfaces: vec!["s".into()],
            patches: vec![0],
            points,
            closed: false,
            clearance: Vec::new(),
            curvature_size: Vec::new(),
            narrow_size: Vec::new(),
        }
    }

    /// A flat 100 x 10 m strip in the plane z = 0, tilted by `tilt` (z grows with y).
    pub(crate) fn strip(tilt: f64) -> (Vec<Curve>, PatchBoundary, PatchIn) {
        let p = |x: f64, y: f64| [x, y, tilt * y];
        let curves = vec![
            curve("low", vec![p(0.0, 0.0), p(50.0, 0.0), p(100.0, 0.0)]),
            curve("right", vec![p(100.0, 0.0), p(100.0, 10.0)]),
            curve("high", vec![p(0.0, 10.0), p(100.0, 10.0)]),
            curve("left", vec![p(0.0, 0.0), p(0.0, 10.0)]),
        ];
        let use_ = |curve, reversed| CurveUse { curve, reversed };
        let bound = PatchBoundary {
            loops: vec![vec![
                use_(0, false),
                use_(1, false),
                use_(2, true),
                use_(3, true),
            ]],
            constraints: Vec::new(),
        };
        let patch = quad([p(0.0, 0.0), p(100.0, 0.0), p(100.0, 10.0), p(0.0, 10.0)]);
        (curves, bound, patch)
    }

    /// A patch on a support of two triangles over the quad `corners`.
    fn quad(corners: [[f64; 3]; 4]) -> PatchIn {
        PatchIn {
            name: "s#1".into(),
            surface: "s".into(),
            mesh: TriMesh::new(corners.to_vec(), vec![[0, 1, 2], [0, 2, 3]]),
            chart_of: None,
        }
    }

    #[test]
    fn a_point_midway_along_a_strip_is_as_far_from_the_other_curves_as_the_strip_is_wide() {
        let (curves, bound, patch) = strip(0.0);
        let c = clearances(&curves, &[bound], &[patch]);
        assert_eq!(c[0][1], 10.0, "the middle of `low` is 10 m from `high`");
        assert_eq!(
            c[0][0], 10.0,
            "`left`, met at its end, does not count; `high` does"
        );
    }

    #[test]
    fn the_clearance_is_measured_in_the_patch_plane_whatever_its_tilt() {
        let (curves, bound, patch) = strip(3.0);
        let c = clearances(&curves, &[bound], &[patch]);
        let width = (10.0f64 * 10.0 + 30.0 * 30.0).sqrt();
        assert!(
            (c[0][1] - width).abs() < 1e-9,
            "{} against {width}",
            c[0][1]
        );
    }

    #[test]
    fn a_curve_alone_in_its_patch_has_no_clearance_bound() {
        let (curves, mut bound, patch) = strip(0.0);
        bound.loops = vec![vec![CurveUse {
            curve: 0,
            reversed: false,
        }]];
        let c = clearances(&curves, &[bound], &[patch]);
        assert!(c[0].iter().all(|d| d.is_infinite()));
        assert!(
            c[2].iter().all(|d| d.is_infinite()),
            "`high` is on no patch"
        );
    }

    /// A flat patch bounded by `curves` (used in order, none reversed) over a 2 km square.
    fn patch_of(curves: &[Curve]) -> (PatchBoundary, PatchIn) {
        let bound = PatchBoundary {
            loops: vec![
                (0..curves.len() as u32)
                    .map(|curve| CurveUse {
                        curve,
                        reversed: false,
                    })
                    .collect(),
            ],
            constraints: Vec::new(),
        };
        let p = |x: f64, y: f64| [x, y, 0.0];
        (
            bound,
            quad([p(-1e3, -1e3), p(2e3, -1e3), p(2e3, 1e3), p(-1e3, 1e3)]),
        )
    }

    #[test]
    fn the_lips_of_a_sliver_that_meet_at_its_tip_bound_each_others_chords() {
        // A horizon sliver between two faults: its lips leave the tip 0.6° apart and run 1 km
        // side by side; their chords would cross unless each keeps within half the gap.
        let p = |x: f64, y: f64| [x, y, 0.0];
        let lip = |name: &str, y: f64| {
            curve(
                name,
                (0..=10)
                    .map(|k| p(100.0 * f64::from(k), y * f64::from(k) / 10.0))
                    .collect(),
            )
        };
        let curves = vec![
            lip("upper", 5.0),
            curve("end", vec![p(1000.0, 5.0), p(1000.0, -5.0)]),
            lip("lower", -5.0),
        ];
        let (bound, patch) = patch_of(&curves);
        let c = clearances(&curves, &[bound], &[patch]);
        let gap = c[0][5];
        assert!(
            (gap - 5.0).abs() < 0.01,
            "midway the lips are 5 m apart: {gap}"
        );
        assert!(c[2][8] < 8.0 + 1e-9 && c[2][8] > 7.9, "{}", c[2][8]);
        assert!(c[0][0] > 0.0, "at the tip itself the lips do not count");
    }

    #[test]
    fn a_curve_that_comes_back_along_itself_bounds_its_own_chords() {
        let p = |x: f64, y: f64| [x, y, 0.0];
        let curves = vec![
            curve(
                "hairpin",
                vec![
                    p(0.0, 0.0),
                    p(500.0, 0.0),
                    p(1000.0, 0.0),
                    p(1000.0, 10.0),
                    p(500.0, 10.0),
                    p(0.0, 10.0),
                ],
            ),
            curve("mouth", vec![p(0.0, 10.0), p(0.0, 0.0)]),
        ];
        let (bound, patch) = patch_of(&curves);
        let c = clearances(&curves, &[bound], &[patch]);
        assert_eq!(c[0][1], 10.0, "the way back runs 10 m away");
        assert_eq!(c[0][4], 10.0);
    }

    #[test]
    fn curves_meeting_at_an_open_angle_do_not_bound_each_other_near_their_junction() {
        // The strip's corner: `low` and `left` meet at a right angle; the way between points
        // near the corner is under three times their distance.
        let (curves, bound, patch) = strip(0.0);
        let c = clearances(&curves, &[bound], &[patch]);
        assert_eq!(
            c[3][0], 100.0,
            "`left` at the corner: `low` and `high`, met at its ends, do not count; `right` does"
        );
    }
}
