//! Refinement where the model's curves come closer than their mesh can resolve. Between two
//! curves a gap `g` apart, elements of edge `h` are flat unless `h` is a few times `g`; left at
//! the curves' own size (ten times the gap or more), the surface meshes there are slivers and the
//! tet mesher stalls or makes tets of a degree. So, where the recipe asks (`[mesh]
//! refine_close_curves = true` for every place, as it can cost millions of tets and does not
//! help where the gap is a wedge of the model's own; or a list of curves, for their places, which
//! the build also adds to where a mesh failed at a place), every unexplained approach
//! (`proximity`) of the places asked becomes a refinement: points along the two curves where
//! they are close, the size there [`GAP_SIZES`] times the local gap, never below the recipe's
//! `min_size` (the budget the user set: it bounds the size ratio, so the element count the
//! refinement adds), growing as the surface meshes may.
//!
//! The places are grouped as the warnings group them (curves joined by close pairs), and each
//! place's points by size class (the gap's power of two), so that a node's feature is one size:
//! an edit far from a place re-runs none of the nodes that take it.

use super::ModelData;
use super::proximity::{Approach, approaches, closest_points};
use crate::recipe::Recipe;
use geom::predicates::dist;
use geom::refine::Refinement;
use model::union_find::UnionFind;
use std::collections::{BTreeMap, BTreeSet};

/// The element size at a close place, in gaps (rounded down to the gap's power of two, so it is
/// between this and half of it).
pub const GAP_SIZES: f64 = 2.0;
/// At most this many points are sampled along one segment of an approach.
const SAMPLES_PER_SEGMENT: usize = 64;

/// The size a gap of `gap` is refined to: `GAP_SIZES` times its power of two, at least
/// `min_size`. The power of two is read from the bits, so the class is the same on every machine.
pub fn refined_size(gap: f64, min_size: f64) -> f64 {
    (GAP_SIZES * power_of_two_below(gap)).max(min_size)
}

/// The largest power of two at most `x` (0 for zero, subnormal or non-finite `x`).
fn power_of_two_below(x: f64) -> f64 {
    if !x.is_normal() || x < 0.0 {
        return 0.0;
    }
    f64::from_bits(x.to_bits() & 0xfff0_0000_0000_0000)
}

/// The refinements that resolve the model's close curves, as the recipe asks (none when it turns
/// them off): per place (closest first), per size (finest first), the points where the curves'
/// gap asks for that size.
pub fn close_refinements(recipe: &Recipe, model: &ModelData, slope: f64) -> Vec<Refinement> {
    let close = &recipe.mesh.refine_close_curves;
    if !close.all && close.named.is_empty() {
        return Vec::new();
    }
    let found = approaches(recipe, model);
    let refined = refined_curves(recipe, model, &found);
    let place_of = places(model.topology.curves.len(), &found);
    let found: Vec<_> = found.into_iter().filter(|(c, ..)| refined[*c]).collect();
    // Per place: its closest gap, and its points by size (the size's bits order as the sizes do).
    type Points = BTreeMap<u64, BTreeSet<[u64; 3]>>;
    let mut by_place: BTreeMap<usize, (f64, Points)> = BTreeMap::new();
    let min_size = recipe.mesh.min_size;
    for (c, _, a) in &found {
        let place = by_place
            .entry(place_of[*c])
            .or_insert((f64::INFINITY, BTreeMap::new()));
        place.0 = place.0.min(a.distance);
        for (gap, p) in samples(a) {
            let size = refined_size(gap, min_size);
            (place.1.entry(size.to_bits()).or_default()).insert(p.map(f64::to_bits));
        }
    }
    let mut order: Vec<(f64, usize)> = by_place.iter().map(|(&k, v)| (v.0, k)).collect();
    order.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
    let mut out = Vec::new();
    for (_, place) in order {
        for (size, points) in std::mem::take(&mut by_place.get_mut(&place).expect("a place").1) {
            out.push(Refinement {
                points: points.iter().map(|p| p.map(f64::from_bits)).collect(),
                size: f64::from_bits(size),
                slope,
            });
        }
    }
    out
}

/// Per curve (of `curves` in all), the place it is in among the approaches `found`: the curves
/// joined by approaches share a place, named by one of them.
pub(super) fn places(curves: usize, found: &[(usize, usize, Approach)]) -> Vec<usize> {
    let mut places = UnionFind::new(curves);
    for (c, d, _) in found {
        places.union(*c, *d);
    }
    (0..curves).map(|k| places.find(k)).collect()
}

/// Per curve of `model`, whether the recipe refines the place it is in among the approaches
/// `found`: a place is the curves joined by approaches, and it is refined when the recipe's
/// `refine_close_curves` is `true` or selects one of its curves.
pub(super) fn refined_curves(
    recipe: &Recipe,
    model: &ModelData,
    found: &[(usize, usize, Approach)],
) -> Vec<bool> {
    let curves = &model.topology.curves;
    let place_of = places(curves.len(), found);
    let mut members: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
    for (c, d, _) in found {
        for k in [*c, *d] {
            members.entry(place_of[k]).or_default().push(k);
        }
    }
    let close = &recipe.mesh.refine_close_curves;
    let mut out = vec![false; curves.len()];
    for place in members.values() {
        if close.refines(place.iter().map(|&k| curves[k].name.as_str())) {
            for &k in place {
                out[k] = true;
            }
        }
    }
    out
}

/// Points along both segments of `a` where the other is nearer than the curves' warning
/// distance, each with its gap there: the two nearest points, and samples about a gap apart
/// (at most [`SAMPLES_PER_SEGMENT`] per segment).
fn samples(a: &Approach) -> Vec<(f64, [f64; 3])> {
    let limit = super::proximity::FRACTION * a.size;
    let mut out = Vec::new();
    for (own, other) in [(0, 1), (1, 0)] {
        let [p, q] = a.segments[own];
        let len = dist(&p, &q);
        let n = ((len / a.distance.max(len / SAMPLES_PER_SEGMENT as f64)).ceil() as usize)
            .clamp(1, SAMPLES_PER_SEGMENT);
        for k in 0..=n {
            let w = k as f64 / n as f64;
            let x = [0, 1, 2].map(|i| p[i] + w * (q[i] - p[i]));
            let (_, y, ..) = closest_points(&[x, x], &a.segments[other]);
            let gap = dist(&x, &y);
            if gap < limit {
                out.push((gap.max(a.distance), x));
            }
        }
        let (x, y, ..) = closest_points(&a.segments[own], &a.segments[other]);
        out.push((a.distance, x));
        out.push((a.distance, y));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_gap_is_refined_to_twice_its_power_of_two_and_never_below_min_size() {
        assert_eq!(refined_size(0.488, 0.01), 0.5);
        assert_eq!(refined_size(0.5, 0.01), 1.0);
        assert_eq!(refined_size(0.999, 0.01), 1.0);
        assert_eq!(refined_size(3.0, 0.01), 4.0);
        assert_eq!(refined_size(0.488, 2.5), 2.5);
        assert_eq!(refined_size(0.0, 2.5), 2.5);
    }

    #[test]
    fn samples_cover_the_close_run_of_two_segments_and_no_more() {
        // Two segments 100 m long, 1 m apart at x = 0 and opening to 21 m at x = 100.
        let a = Approach {
            distance: 1.0,
            at: [0.0, 0.5, 0.0],
            size: 100.0,
            segments: [
                [[0.0, 0.0, 0.0], [100.0, 0.0, 0.0]],
                [[0.0, 1.0, 0.0], [100.0, 21.0, 0.0]],
            ],
        };
        let s = samples(&a);
        // Close means under a tenth of 100 m: the first 45 m of the run, on both segments.
        assert!(s.iter().all(|(g, _)| *g >= 1.0 && *g < 10.0), "{s:?}");
        let reach = s.iter().map(|(_, p)| p[0]).fold(0.0, f64::max);
        assert!((40.0..50.0).contains(&reach), "{reach}");
        assert!(s.iter().any(|(_, p)| p[1] > 0.5) && s.iter().any(|(_, p)| p[1] == 0.0));
        // About a gap apart near the closest point: 64 samples over 100 m.
        assert!(s.len() > 40, "{}", s.len());
    }
}
