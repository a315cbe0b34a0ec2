//! How narrow the patches are along their seams and creases, as sizes for those curves.
//!
//! A patch narrower than the elements of its border can only be meshed with needles: a strip
//! between two creases along a rough body's tightly bent edge, a chart whose seam runs close
//! beside a contact curve. Their border nodes are their curves' nodes, fixed before the patch is meshed, so the
//! curves must already be as fine as the patch is wide. This module measures that width along
//! the curves and asks for elements no longer than it (the local feature size of a 2D mesher).
//!
//! Decisions and why:
//! - The width at a place of a curve is the distance in the patch's plane to the nearest piece
//!   of its curves that is apart along the curves (`clearance::PlaneCurves::apart`), here by
//!   `WEDGE_DETOUR`: the way between them along the curves is more than 60 times longer. So two
//!   borders of a strip that meet no end of each other narrow it all along, but a wedge (two
//!   curves leaving a corner under about 2° of each other, the three sides of a sliver facet)
//!   does not: its corner holds a thin triangle whatever the size, and refining into it only
//!   costs elements (at the clearance's 20, the corpus's lenses, whose rims are crumpled into
//!   sliver facets, took five to seven times the tets for no better angle).
//! - Only curves inside one surface count (a seam between two charts, a crease between two
//!   patches of one surface). There the region on either side is smooth across the curve, so
//!   elements of the width's size are well shaped and worth their count. Between curves of two
//!   different surfaces a narrow place is a wedge of the model's own (two horizons converging, an
//!   unconformity) whose tets are bound by its angle whatever their size; refining those is the
//!   recipe's choice (`refine_close_curves`).
//! - A polyline segment is sampled, not only its ends: a sliver facet's long side has no point
//!   but its two corners. The samples are spaced by the width at the segment's middle, at most
//!   `MAX_SAMPLES` per segment.
//! - No recipe size enters: the sizes are measures of the model, raised to `min_size` and used
//!   only where they are below the curve's own size when the curve is discretized.

use crate::clearance::{Along, PlaneCurves, arc_lengths};
use crate::regions::PatchIn;
use crate::{Curve, PatchBoundary};

/// Elements across a narrow place are no longer than this many times its width.
const WIDTH_FACTOR: f64 = 1.0;
/// A piece of curve narrows a place when the way between them along the curves is longer than
/// this many times their distance (see the module doc).
const WEDGE_DETOUR: f64 = 60.0;
/// Most samples on one polyline segment.
const MAX_SAMPLES: f64 = 32.0;

/// Whether `c` runs inside one surface, between two of its patches: a seam or a crease.
pub fn inside_one_surface(c: &Curve) -> bool {
    c.surfaces.len() == 1 && c.patches.len() >= 2
}

/// Per curve, the places `[x, y, z, size]` where a patch it bounds is narrow, with the size
/// that width asks for; empty for a curve that is not inside one surface. `bounds` are the
/// patches' boundaries, parallel to `patches`.
pub fn narrow_sizes(
    curves: &[Curve],
    bounds: &[PatchBoundary],
    patches: &[PatchIn],
) -> Vec<Vec<[f64; 4]>> {
    let mut out = vec![Vec::new(); curves.len()];
    if !curves.iter().any(inside_one_surface) {
        return out;
    }
    let arcs = arc_lengths(curves);
    for (b, p) in bounds.iter().zip(patches) {
        let inner = |c: &u32| inside_one_surface(&curves[*c as usize]);
        if !b.curves().iter().any(inner) {
            continue;
        }
        let Some(plane) = PlaneCurves::new(curves, &arcs, b, p) else {
            continue;
        };
        for &c in plane.used.iter().filter(|c| inner(c)) {
            let places = samples(&curves[c as usize], &arcs[c as usize], |at, q| {
                plane.apart(Along { curve: c, arc: at }, q, WEDGE_DETOUR)
            });
            out[c as usize].extend(places);
        }
    }
    out
}

/// The samples of one curve (points `curve.points`, arc lengths `arc`) with a finite width,
/// as `[x, y, z, size]`: each segment's start and points spaced by the width at its middle, and
/// the curve's last point.
fn samples(curve: &Curve, arc: &[f64], width: impl Fn(f64, &[f64; 3]) -> f64) -> Vec<[f64; 4]> {
    let mut out = Vec::new();
    let mut push = |s: f64, q: [f64; 3]| {
        let w = width(s, &q);
        if w.is_finite() {
            out.push([q[0], q[1], q[2], WIDTH_FACTOR * w]);
        }
    };
    let pts = &curve.points;
    for k in 0..pts.len().saturating_sub(1) {
        let (a, b) = (pts[k], pts[k + 1]);
        let len = arc[k + 1] - arc[k];
        let at = |f: f64| {
            let q = [0, 1, 2].map(|i| a[i] + f * (b[i] - a[i]));
            (arc[k] + f * len, q)
        };
        let (s, mid) = at(0.5);
        let w = width(s, &mid);
        let m = if w > 0.0 && w.is_finite() {
            (len / w).ceil().clamp(1.0, MAX_SAMPLES) as usize
        } else {
            1
        };
        for j in 0..m {
            let (s, q) = at(j as f64 / m as f64);
            push(s, q);
        }
    }
    if let (Some(last), Some(&s)) = (pts.last(), arc.last()) {
        push(s, *last);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::CurveUse;
    use crate::clearance::tests::{curve, strip};
    use geom::TriMesh;

    /// The strip's long borders as creases: inside surface `s`, between its patch and another.
    fn creased(mut curves: Vec<Curve>) -> Vec<Curve> {
        for k in [0, 2] {
            curves[k].patches = vec![0, 1];
        }
        curves
    }

    #[test]
    fn a_strip_between_two_creases_asks_its_width_all_along_both() {
        // 100 x 10 m.
        let (curves, bound, patch) = strip(0.0);
        let curves = creased(curves);
        let n = narrow_sizes(&curves, &[bound], &[patch]);
        for k in [0, 2] {
            assert!(n[k].len() >= 10, "{}: {:?}", curves[k].name, n[k]);
            for s in &n[k] {
                assert!((s[3] - 10.0).abs() < 1e-9, "{s:?}");
            }
        }
        assert!(
            n[1].is_empty() && n[3].is_empty(),
            "the ends are borders of one patch"
        );
    }

    #[test]
    fn a_strip_between_curves_of_two_surfaces_asks_nothing() {
        // A wedge or sheet of the model's own: refining it is the recipe's choice.
        let (mut curves, bound, patch) = strip(0.0);
        for c in &mut curves {
            c.surfaces = vec!["s".into(), "t".into()];
            c.patches = vec![0, 1];
        }
        let n = narrow_sizes(&curves, &[bound], &[patch]);
        assert!(n.iter().all(Vec::is_empty), "{n:?}");
    }

    #[test]
    fn a_sliver_facet_cut_out_by_creases_asks_nothing() {
        // One facet 300 m long and 10 m wide, with corners of 4° at both ends, cut out by
        // creases on all three sides: two wedges back to back. Its corners hold a triangle of 4°
        // whatever the size, so refining it would only cost elements.
        let p = |x: f64, y: f64| [x, y, 0.0];
        let (a, b, c) = (p(0.0, 0.0), p(150.0, 10.0), p(300.0, 0.0));
        let mut curves = vec![
            curve("ab", vec![a, b]),
            curve("bc", vec![b, c]),
            curve("ca", vec![c, a]),
        ];
        for c in &mut curves {
            c.patches = vec![0, 1];
        }
        let bound = PatchBoundary {
            loops: vec![
                (0..3)
                    .map(|curve| CurveUse {
                        curve,
                        reversed: false,
                    })
                    .collect(),
            ],
            constraints: Vec::new(),
        };
        let patch = PatchIn {
            name: "s#1".into(),
            surface: "s".into(),
            mesh: TriMesh::new(vec![a, b, c], vec![[0, 2, 1]]),
            chart_of: None,
        };
        let n = narrow_sizes(&curves, &[bound], &[patch]);
        assert!(n.iter().all(Vec::is_empty), "{n:?}");
    }
}
