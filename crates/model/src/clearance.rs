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
//! - Only curves *apart* from it count: not itself (its chords follow each other along it) and
//!   not the curves it meets at an end. Chords leaving a shared end cross only if they swap sides
//!   there, which distance does not measure; counted, those curves' clearance shrinks to zero at
//!   the end and would split a stair-stepped curve (a chart seam along support edges) into its
//!   support edges at every junction, which cost the salt cases tets of 2° dihedral angle.
//! - A curve on several patches takes the smallest clearance; a point with no other curve in any
//!   of its patches has an infinite clearance.

use crate::regions::PatchIn;
use crate::{Curve, PatchBoundary};
use geom::predicates::{cross, dot, sub};
use rstar::RTree;
use rstar::primitives::{GeomWithData, Line};

/// A projected curve segment tagged with its curve.
type Segment = GeomWithData<Line<[f64; 2]>, u32>;

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
    for (b, p) in bounds.iter().zip(patches) {
        let used = b.curves();
        if used.len() < 2 {
            continue;
        }
        let Some(project) = Projection::of(&p.mesh) else {
            continue;
        };
        let project = &project;
        let segments: Vec<Segment> = used
            .iter()
            .flat_map(|&c| {
                let pts = &curves[c as usize].points;
                pts.windows(2)
                    .map(move |w| Segment::new(Line::new(project.at(&w[0]), project.at(&w[1])), c))
            })
            .collect();
        let tree = RTree::bulk_load(segments);
        for &c in &used {
            let apart = |o: u32| o != c && !share_an_end(&curves[c as usize], &curves[o as usize]);
            for (k, q) in curves[c as usize].points.iter().enumerate() {
                let q = project.at(q);
                let nearest = tree
                    .nearest_neighbor_iter_with_distance_2(q)
                    .find(|(s, _)| apart(s.data))
                    .map_or(f64::INFINITY, |(_, d2)| d2.sqrt());
                let slot = &mut out[c as usize][k];
                *slot = slot.min(nearest);
            }
        }
    }
    out
}

/// Whether two curves meet at an end point (exactly: curves share their end vertices bit for bit).
fn share_an_end(a: &Curve, b: &Curve) -> bool {
    let ends = |c: &Curve| [c.points.first().copied(), c.points.last().copied()];
    let (ea, eb) = (ends(a), ends(b));
    ea.iter().any(|p| p.is_some() && eb.contains(p))
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
mod tests {
    use super::*;
    use crate::CurveUse;
    use geom::TriMesh;

    fn curve(name: &str, points: Vec<[f64; 3]>) -> Curve {
        Curve {
            name: name.into(),
            surfaces: vec!["s".into()],
            patches: vec![0],
            points,
            closed: false,
            clearance: Vec::new(),
        }
    }

    /// A flat 100 x 10 m strip in the plane z = 0, tilted by `tilt` (z grows with y).
    fn strip(tilt: f64) -> (Vec<Curve>, PatchBoundary, PatchIn) {
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
        let mesh = TriMesh::new(
            vec![p(0.0, 0.0), p(100.0, 0.0), p(100.0, 10.0), p(0.0, 10.0)],
            vec![[0, 1, 2], [0, 2, 3]],
        );
        let patch = PatchIn {
            name: "s#1".into(),
            surface: "s".into(),
            mesh,
            chart_of: None,
        };
        (curves, bound, patch)
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
}
