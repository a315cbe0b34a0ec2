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
//! - Curves inside one surface count (a seam between two charts, a crease between two patches
//!   of one surface). There the region on either side is smooth across the curve, so elements
//!   of the width's size are well shaped and worth their count.
//! - Curves of two surfaces count only on a juxtaposition strip ([`juxtaposition_strips`]): a
//!   patch every region beside which goes on along the patch's surface past one of its curves,
//!   as on each side of a fault whose throw is far below the size, where the strip between a
//!   horizon's two cutoffs lies between two thick blocks (a 5 m throw at 250 m left needles
//!   there and tets of 2.2°; refined, 14°). Elsewhere a narrow place between two surfaces is a
//!   region closing between them (a thin layer, a wedge of two converging horizons, an
//!   unconformity) whose tets are bound by its own thickness or angle whatever the size there;
//!   refining those is the recipe's choice (`refine_close_curves`, `layers`).
//! - A strip narrower than `min_size` asks for `min_size² / width` ([`faded`]), not for
//!   `min_size` as a seam does. No element goes under `min_size`, so such a strip holds needles
//!   whatever its curves' size, and refining it all along to `min_size` only costs: RINGMesh's
//!   modelA5, whose horizons turn round a fault tip with cutoffs millimetres apart, took 1.01
//!   million tets and reached 0.33° so; with the fade, 383,000 tets and 1.15°. The fade is
//!   continuous at `min_size`, so the size does not jump where a strip narrows past it.
//! - A polyline segment is sampled, not only its ends: a sliver facet's long side has no point
//!   but its two corners. The samples are spaced by the width at the segment's middle, at most
//!   `MAX_SAMPLES` per segment.
//! - No recipe size enters but the strips' `min_size`: the sizes are measures of the model,
//!   raised to `min_size` and used only where they are below the curve's own size when the
//!   curve is discretized.

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
    widths(curves, bounds, patches, |_, c| inside_one_surface(c))
}

/// Per curve of two surfaces, the places `[x, y, z, size]` where a patch it bounds that
/// `strips` marks (see [`juxtaposition_strips`]) is narrow, with the size that width asks for;
/// where the strip is narrower than `min_size`, the ask fades ([`faded`]).
pub fn strip_sizes(
    curves: &[Curve],
    bounds: &[PatchBoundary],
    patches: &[PatchIn],
    strips: &[bool],
    min_size: f64,
) -> Vec<Vec<[f64; 4]>> {
    let mut out = widths(curves, bounds, patches, |p, c| {
        strips.get(p).copied().unwrap_or(false) && c.surfaces.len() >= 2
    });
    for place in out.iter_mut().flatten() {
        place[3] = faded(place[3], min_size);
    }
    out
}

/// The size a strip of width `w` asks for: `w`, or where `w` is below `min_size` (which no
/// element goes under, so the strip holds needles whatever its curves' size),
/// `min_size² / w`: the narrower the strip, the larger, so that a strip closing to nothing (a
/// throw falling to zero at a fault's tip) asks for nothing near its end. At
/// `min_size` the two agree, so the size does not jump as the strip narrows.
pub fn faded(w: f64, min_size: f64) -> f64 {
    if w >= min_size || w <= 0.0 {
        w
    } else {
        min_size * (min_size / w)
    }
}

/// Per curve, the places where a patch it bounds is narrow, for the curves `counts(patch, c)`
/// accepts on that patch.
fn widths(
    curves: &[Curve],
    bounds: &[PatchBoundary],
    patches: &[PatchIn],
    counts: impl Fn(usize, &Curve) -> bool,
) -> Vec<Vec<[f64; 4]>> {
    let mut out = vec![Vec::new(); curves.len()];
    let counted: Vec<bool> = (bounds.iter().enumerate())
        .map(|(k, b)| (b.curves().into_iter()).any(|c| counts(k, &curves[c as usize])))
        .collect();
    if !counted.contains(&true) {
        return out;
    }
    let arcs = arc_lengths(curves);
    for (k, (b, p)) in bounds.iter().zip(patches).enumerate() {
        let inner = |c: &u32| counts(k, &curves[*c as usize]);
        if !counted[k] {
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

/// Per patch, whether it is a juxtaposition strip: it bounds a region, and every region it
/// bounds goes on along the patch's surface past one of the patch's curves of two surfaces (a
/// patch of that surface beside it across the curve bounds the region too). A region that turns
/// off the surface at every such curve closes between the surfaces there (a layer, a wedge).
/// `region_patches` lists each region's patches, ascending.
pub fn juxtaposition_strips(
    curves: &[Curve],
    bounds: &[PatchBoundary],
    patches: &[PatchIn],
    region_patches: &[Vec<u32>],
) -> Vec<bool> {
    let mut regions_of: Vec<Vec<usize>> = vec![Vec::new(); patches.len()];
    for (r, ps) in region_patches.iter().enumerate() {
        for &p in ps {
            if let Some(rs) = regions_of.get_mut(p as usize) {
                rs.push(r);
            }
        }
    }
    let goes_on = |p: usize, r: usize, c: &Curve| {
        c.patches.iter().any(|&q| {
            q as usize != p
                && patches.get(q as usize).map(|x| &x.surface) == Some(&patches[p].surface)
                && region_patches[r].binary_search(&q).is_ok()
        })
    };
    (bounds.iter().enumerate())
        .map(|(p, b)| {
            let across: Vec<&Curve> = (b.curves().iter())
                .map(|&c| &curves[c as usize])
                .filter(|c| c.surfaces.len() >= 2)
                .collect();
            !regions_of[p].is_empty()
                && (regions_of[p].iter()).all(|&r| across.iter().any(|c| goes_on(p, r, c)))
        })
        .collect()
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

    /// The 100 x 10 m strip as patch 0 of a fault `s` between two horizons' cutoffs: `low`
    /// meets `t` (patch 4) and `high` meets `u` (patch 2); patches 1 and 3 go on along `s`
    /// past `low` and `high`. Returns the curves, boundaries and patches of the five.
    fn cutoffs() -> (Vec<Curve>, Vec<PatchBoundary>, Vec<PatchIn>) {
        let (mut curves, bound, patch) = strip(0.0);
        (curves[0].surfaces, curves[0].patches) = (vec!["s".into(), "t".into()], vec![0, 1, 4]);
        (curves[2].surfaces, curves[2].patches) = (vec!["s".into(), "u".into()], vec![0, 2, 3]);
        let mut bounds = vec![bound];
        let mut patches = vec![patch.clone()];
        for surface in ["s", "u", "s", "t"] {
            bounds.push(PatchBoundary {
                loops: Vec::new(),
                constraints: Vec::new(),
            });
            patches.push(PatchIn {
                surface: surface.into(),
                ..patch.clone()
            });
        }
        (curves, bounds, patches)
    }

    #[test]
    fn a_strip_of_a_fault_between_two_blocks_asks_its_width_of_the_cutoffs() {
        // Each block goes on along the fault past one cutoff: the footwall's (0, 1, 2) past
        // `low`, the hanging wall's (0, 3, 4) past `high`.
        let (curves, bounds, patches) = cutoffs();
        let blocks = [vec![0, 1, 2], vec![0, 3, 4]];
        let strips = juxtaposition_strips(&curves, &bounds, &patches, &blocks);
        assert_eq!(strips, [true, false, false, false, false]);
        let n = strip_sizes(&curves, &bounds, &patches, &strips, 0.0);
        for k in [0, 2] {
            assert!(n[k].len() >= 10, "{}: {:?}", curves[k].name, n[k]);
            assert!(
                n[k].iter().all(|s| (s[3] - 10.0).abs() < 1e-9),
                "{:?}",
                n[k]
            );
        }
        // Curves of two surfaces count on strips only.
        assert!(
            narrow_sizes(&curves, &bounds, &patches)
                .iter()
                .all(Vec::is_empty)
        );
    }

    #[test]
    fn a_strip_narrower_than_min_size_asks_less_the_narrower_it_is() {
        // The 10 m strip under a `min_size` of 20: its needles stay whatever the size, so it
        // asks for 40, not for 20 along its whole length.
        let (curves, bounds, patches) = cutoffs();
        let strips = [true, false, false, false, false];
        let n = strip_sizes(&curves, &bounds, &patches, &strips, 20.0);
        for k in [0, 2] {
            assert!(!n[k].is_empty());
            assert!(
                n[k].iter().all(|s| (s[3] - 40.0).abs() < 1e-9),
                "{:?}",
                n[k]
            );
        }
        // At `min_size` the ask meets the width; above it, it is the width; and it grows
        // without end as a strip closes to nothing.
        assert_eq!(faded(20.0, 20.0), 20.0);
        assert_eq!(faded(30.0, 20.0), 30.0);
        assert!(faded(19.9, 20.0) > 20.0 && faded(19.9, 20.0) < 20.2);
        assert!(faded(0.002, 20.0) > 1e5);
        let mut last = f64::INFINITY;
        for w in [0.01, 0.1, 1.0, 5.0, 10.0, 19.0] {
            assert!(faded(w, 20.0) < last, "{w}");
            last = faded(w, 20.0);
        }
    }

    #[test]
    fn a_strip_closing_a_region_between_two_surfaces_is_no_juxtaposition() {
        // A thin layer (or a wedge) between `t` and `u`, ending on `s`: it turns off `s` at both
        // curves, so its thickness, not the strip, bounds its tets.
        let (curves, bounds, patches) = cutoffs();
        let layer = [vec![0, 2, 4], vec![0, 3, 4]];
        assert!(!juxtaposition_strips(&curves, &bounds, &patches, &layer)[0]);
        // Nor is a patch that bounds no region.
        assert!(!juxtaposition_strips(&curves, &bounds, &patches, &[])[0]);
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
