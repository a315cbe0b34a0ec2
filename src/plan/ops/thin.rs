//! Sizes that follow a layer's local thickness. `layers` sizes a region from its median
//! thickness (`sizes`), one size for the whole region; where the layer thins (a pinch-out, a
//! wedge, a slab under a thrust's flat) that size spans it in fewer elements than asked. So
//! where a region with a count across is thinner than its median by more than a fifth, points
//! on its walls there (`model::thickness::thin_places`) ask for the size the local thickness
//! gives, as refinements every mesher takes (the surfaces and curves bounding it, its tets and
//! its neighbours' within their reach), never below the region's `min_size`.
//!
//! The size there is the interior's rule (`sizes::interior_sizes`): thickness over
//! `sizes::per_layer(n)`, so the tets keep `n` edges across; the surfaces there take it
//! too (a refinement is one size for every mesher). Points are grouped by size class (a quarter
//! of an octave, each class at its lower bound), so that a node's feature is one size and an
//! edit far from a thin part re-runs none of the nodes that take it.
//!
//! Isotropic elements across an extensive thin part are many: three layers under a thrust's
//! flat 10 m above a horizon, over 6 km², are tens of millions of tets, and the elements grading
//! out around it as many again. So the thin parts of a region may ask for about [`BUDGET`] tets
//! (their own and the grading's, estimated from the places): past that, they are not refined,
//! the region is meshed from its median thickness as before, and the build warns naming the
//! region, its thinnest place, the count it would have taken and the `min_size` that would fit.
//!
//! The same budget bounds a round of refinement the build adds where two surfaces' meshes cross
//! (`cli::crossings`), estimated round its curves by [`tets_near_curves`]: one measure of what a
//! refinement costs, whichever asks for it.

use super::ModelData;
use super::aspect::aspect_of;
use super::budget::TETS_PER_CUBE;
use super::sizes::{interior_sizes, layers_of, per_layer, region_sizes, short};
use crate::recipe::Recipe;
use geom::TriMesh;
use geom::refine::Refinement;
use model::thickness::thin_places;
use std::collections::BTreeMap;

/// A part thinner than this share of what the region's own size assumes is refined.
pub const FINER: f64 = 0.8;
/// At most about this many points are cast per region.
pub const MAX_POINTS: usize = 400_000;
/// The most tets the thin parts of one region, or one round of refinement where meshes cross,
/// may ask for.
pub const BUDGET: f64 = 4.0e6;
/// Size classes per octave.
const CLASSES: f64 = 4.0;

/// The thin parts of one region.
struct ThinPart {
    region: usize,
    /// Points on its walls, the distance across there and the wall area each stands for.
    places: Vec<([f64; 3], f64, f64)>,
    /// Sizes across the region (the size at a thickness is the thickness over it).
    per: f64,
    min_size: f64,
    /// A floor on the sizes (0: none): what `min_size` would keep the part within the budget.
    floor: f64,
    /// Tets the thin parts would take at their sizes, with the elements grading out round them.
    wanted: f64,
    /// The sizes' growth per unit of length away from the part.
    slope: f64,
}

impl ThinPart {
    fn size_at(&self, t: f64) -> f64 {
        (t / self.per).max(self.min_size).max(self.floor)
    }
}

/// The thin parts of the layered regions of `model`, in region order.
fn thin_parts(recipe: &Recipe, model: &ModelData, interior: &[f64], slope: f64) -> Vec<ThinPart> {
    let meshes: Vec<&TriMesh> = model.patches.iter().map(|p| &p.mesh).collect();
    let mut out = Vec::new();
    for (region, (r, &inside)) in model.regions.regions.iter().zip(interior).enumerate() {
        let (Some(n), _) = layers_of(recipe, &r.name) else {
            continue;
        };
        // A layer meshed flat along it takes its thickness from its sides, not from its walls.
        if aspect_of(recipe, &r.name).is_some() {
            continue;
        }
        let min_size =
            (recipe.mesh.regions.get(&r.name)).map_or(recipe.mesh.min_size, |s| s.min_size);
        if min_size >= FINER * inside {
            continue;
        }
        let per = per_layer(n);
        let spacing = |t: f64| 0.5 * (t / per).max(min_size);
        let thin = FINER * inside * per;
        let places = thin_places(&meshes, &r.sides, thin, &spacing, MAX_POINTS);
        if places.is_empty() {
            continue;
        }
        let mut part = ThinPart {
            region,
            places,
            per,
            min_size,
            floor: 0.0,
            wanted: 0.0,
            slope,
        };
        part.wanted = tets(&part);
        if part.wanted > BUDGET {
            part.floor = floor_within_budget(&mut part);
        }
        out.push(part);
    }
    out
}

/// The tets `part`'s places ask for at its sizes: each stands for its area times the distance
/// across, halved as the two sides of a layer both stand for it, and for the elements grading
/// out beyond its wall, `∫ dx / (h + g x)³ = 1 / (2 g h²)` per unit of area.
fn tets(part: &ThinPart) -> f64 {
    let g = part.slope.max(0.05);
    (part.places.iter())
        .map(|&(_, t, area)| {
            let h = part.size_at(t);
            area * TETS_PER_CUBE * (0.5 * t / h.powi(3) + 1.0 / (2.0 * g * h * h))
        })
        .sum()
}

/// The tets a refinement of curves `length` long adds: `size` at the curves, growing at `slope`
/// per unit of length (at most) up to `far`. Round the curves the sizes are a tube's, so per
/// unit of length `∫ 2πr dr / (h + g r)³` out to where `far` is reached, less the tets at `far`
/// that were there before.
pub fn tets_near_curves(length: f64, size: f64, far: f64, slope: f64) -> f64 {
    let (a, g) = (size, slope.max(0.05));
    let reach = (far - size).max(0.0) / g;
    let primitive = |r: f64| -(a + 2.0 * g * r) / (2.0 * g * g * (a + g * r).powi(2));
    let refined = 2.0 * std::f64::consts::PI * (primitive(reach) - primitive(0.0));
    let before = std::f64::consts::PI * reach * reach / far.powi(3);
    length * TETS_PER_CUBE * (refined - before).max(0.0)
}

/// The smallest floor (by bisection, to a percent) that keeps `part` within [`BUDGET`].
fn floor_within_budget(part: &mut ThinPart) -> f64 {
    let thickest = (part.places.iter()).map(|p| p.1).fold(0.0, f64::max);
    let (mut lo, mut hi) = (part.min_size, thickest.max(part.min_size));
    while hi > lo * 1.01 {
        part.floor = (lo * hi).sqrt();
        if tets(part) > BUDGET {
            lo = part.floor;
        } else {
            hi = part.floor;
        }
    }
    hi
}

/// The refinements where the layered regions of `model` thin, growing at `slope`: per region in
/// order, per size class from the finest. `interior` as `sizes::interior_sizes` gives it.
pub fn thin_refinements(
    recipe: &Recipe,
    model: &ModelData,
    interior: &[f64],
    slope: f64,
) -> Vec<Refinement> {
    let mut out = Vec::new();
    for part in thin_parts(recipe, model, interior, slope) {
        if part.floor > 0.0 {
            continue;
        }
        let mut by_class: BTreeMap<i64, Vec<[f64; 3]>> = BTreeMap::new();
        for &(p, t, _) in &part.places {
            let class = (CLASSES * part.size_at(t).log2()).floor() as i64;
            by_class.entry(class).or_default().push(p);
        }
        for (class, points) in by_class {
            let size = (class as f64 / CLASSES).exp2();
            out.push(Refinement {
                points,
                size: size.max(part.min_size),
                slope,
            });
        }
    }
    out
}

/// Per region whose thin parts the budget held back, `(region, warning)`: the thinnest place,
/// the count asked there, the tets it would have taken and the `min_size` that would fit.
/// `slope` as the sizes grow on the surfaces.
pub fn budget_warnings(recipe: &Recipe, model: &ModelData, slope: f64) -> Vec<(String, String)> {
    let regions = region_sizes(recipe, model);
    let interior = interior_sizes(recipe, model, &regions);
    let mut out = Vec::new();
    let parts = thin_parts(recipe, model, &interior, slope);
    for part in parts.iter().filter(|p| p.floor > 0.0) {
        let r = &model.regions.regions[part.region];
        let (n, path) = layers_of(recipe, &r.name);
        let Some((p, t, _)) = (part.places.iter()).min_by(|a, b| a.1.total_cmp(&b.1)) else {
            continue;
        };
        let [x, y, z] = p.map(|c| format!("{c:.1}"));
        out.push((
            r.name.clone(),
            format!(
                "region `{}` thins to {} at ({x}, {y}, {z}): `{path} = {}` there would take \
                 about {:.0} million tets with the elements grading out round it, over the {:.0} \
                 million a region's thin parts may ask; it is meshed from its median thickness \
                 instead; `min_size = {}` for it would fit, or refine a part of it with \
                 `[[mesh.refine]]`",
                r.name,
                short(*t),
                n.unwrap_or(0),
                part.wanted / 1e6,
                BUDGET / 1e6,
                short(part.floor)
            ),
        ));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_layer_is_as_many_sizes_across_as_its_tets_need_for_its_count() {
        assert_eq!(per_layer(1), 1.0);
        assert_eq!(per_layer(2), 3.0);
        assert_eq!(per_layer(3), 4.0);
        assert_eq!(per_layer(5), 8.0);
    }

    #[test]
    fn a_refinement_round_curves_counts_the_tube_it_fills_and_nothing_at_its_far_size() {
        // A kilometre of curve at 20 m, growing at 0.3 to 200 m: the tube holds
        // 2π · (1/(2g²a) − (a + 2gR)/(2g²(a + gR)²)) per cube, R = 600 m.
        let (a, g, r): (f64, f64, f64) = (20.0, 0.3, 600.0);
        let per_m = 2.0
            * std::f64::consts::PI
            * (1.0 / (2.0 * g * g * a) - (a + 2.0 * g * r) / (2.0 * g * g * (a + g * r).powi(2)));
        let before = std::f64::consts::PI * r * r / 200f64.powi(3);
        let want = 1000.0 * TETS_PER_CUBE * (per_m - before);
        let got = tets_near_curves(1000.0, 20.0, 200.0, 0.3);
        assert!((got - want).abs() < 1e-6 * want, "{got} {want}");
        // Twice the length, twice the tets; a quarter of the size, many times more.
        assert!((tets_near_curves(2000.0, 20.0, 200.0, 0.3) - 2.0 * got).abs() < 1e-6 * got);
        assert!(tets_near_curves(1000.0, 5.0, 200.0, 0.3) > 3.0 * got);
        // At the far size already, nothing.
        assert_eq!(tets_near_curves(1000.0, 200.0, 200.0, 0.3), 0.0);
    }

    #[test]
    fn the_floor_keeps_a_thin_parts_tets_within_the_budget_and_no_higher() {
        // 6 km² of wall on each side of a 10 m slab, three layers at 2.5 m: inside, 6e7 m³ at
        // 2.5 m, 33 million tets; grading out at 0.15, 1.2e7 m² · 8.49 / (0.3 · 2.5²), 54 million.
        let places = (0..12_000)
            .map(|k| ([k as f64, 0.0, 0.0], 10.0, 1000.0))
            .collect();
        let mut part = ThinPart {
            region: 0,
            places,
            per: 4.0,
            min_size: 2.5,
            floor: 0.0,
            wanted: 0.0,
            slope: 0.15,
        };
        part.wanted = tets(&part);
        assert!((85.0e6..89.0e6).contains(&part.wanted), "{}", part.wanted);
        part.floor = floor_within_budget(&mut part);
        let within = tets(&part);
        assert!(within <= BUDGET && within > 0.95 * BUDGET, "{within}");
        // 5.1e8 / h³ + 3.4e8 / h² = 4e6 near h = 9.9 m: one element across the slab.
        assert!((9.5..10.5).contains(&part.floor), "{}", part.floor);
    }
}
