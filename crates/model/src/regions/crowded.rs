//! Two surfaces that enclose many regions between them alone: noise, not geology.
//!
//! Two surfaces that cross along a closed curve enclose a lens, and a model may hold a few (a
//! channel, a salt body split by a horizon, one piece per body). A horizon jittered by more than
//! the layer it bounds, or picked through its neighbour again and again, crosses that neighbour
//! along hundreds of small loops instead, and each loop encloses a sliver. Meshing them refines
//! every region around them down to `min_size` (millions of elements where the clean model has
//! thousands) and the slivers then fail one by one as too thin to mesh. So the count decides
//! before anything is meshed: more than [`MAX_LENSES`] unnamed regions bounded by the same two
//! surfaces and nothing else fail the model at once, naming the pair, the count and a point of
//! the first, with the likely cause and the trim that resolves a truncation.

use super::{PatchIn, RegionError};
use std::collections::BTreeMap;

/// The most unnamed regions two surfaces may enclose between themselves alone. A salt body of
/// a dozen domes cut by one horizon gives two dozen; noise gives hundreds.
pub const MAX_LENSES: usize = 32;

/// One region as the check sees it: whether the recipe named it, and the sorted, deduplicated
/// names of the surfaces of its outer shell, each with a point of one of its triangles there.
pub(super) struct Enclosed<'a> {
    pub named: bool,
    pub surfaces: Vec<(&'a str, [f64; 3])>,
}

/// Fails when one pair of surfaces (neither a side of the box) alone bounds more than
/// [`MAX_LENSES`] unnamed regions. The error blames the rougher of the two (`roughness` of a
/// surface name, e.g. [`mean_turn`]) at a point of it on the first such region; the regions come
/// in canonical order, so the point is stable.
pub(super) fn check_lenses(
    regions: &[Enclosed],
    roughness: impl Fn(&str) -> f64,
) -> Result<(), RegionError> {
    let mut pairs: BTreeMap<(&str, &str), (usize, &Enclosed)> = BTreeMap::new();
    for r in regions.iter().filter(|r| !r.named) {
        let [(a, _), (b, _)] = r.surfaces[..] else {
            continue;
        };
        if a.starts_with("box.") || b.starts_with("box.") {
            continue;
        }
        pairs.entry((a, b)).or_insert((0, r)).0 += 1;
    }
    let Some((&(a, b), &(count, first))) = pairs.iter().find(|(_, (n, _))| *n > MAX_LENSES) else {
        return Ok(());
    };
    let turn = [roughness(a), roughness(b)];
    let rough = usize::from(turn[1] > turn[0]);
    let (culprit, at) = first.surfaces[rough];
    let other = first.surfaces[1 - rough].0;
    Err(RegionError::new(
        format!(
            "surfaces `{a}` and `{b}` cross each other so often that they alone enclose {count} \
             regions between them (a model holds a few such lenses, at most {MAX_LENSES}): two \
             surfaces that cross again and again are noise in the data, not geology. `{culprit}` \
             is the rougher (its triangles turn by {:.0}° on average from one to the next, \
             `{other}`'s by {:.0}°): likely jittered, re-picked through `{other}` or spiked; \
             smooth or re-pick it where they meet. If instead one truncates the other (an \
             erosion surface), trim the older one to its side of the younger: `[[trim]]` with \
             `surface = \"{b}\"` and `keep = {{ below = \"{a}\" }}` (or `above`). The first \
             region lies on `{culprit}` at ({:.1}, {:.1}, {:.1})",
            turn[rough],
            turn[1 - rough],
            at[0],
            at[1],
            at[2]
        ),
        Some(culprit),
        Some(at),
    ))
}

/// The mean angle in degrees between the normals of neighbouring triangles of the patches of
/// `surface`: a few degrees on a smooth surface, tens on a jittered one.
pub(super) fn mean_turn(patches: &[PatchIn], surface: &str) -> f64 {
    let (mut sum, mut edges) = (0.0, 0usize);
    for p in patches.iter().filter(|p| p.surface == surface) {
        let normals = p.mesh.unit_normals();
        let mut first: BTreeMap<(u32, u32), usize> = BTreeMap::new();
        for (t, tri) in p.mesh.triangles.iter().enumerate() {
            for k in 0..3 {
                let (u, v) = (tri[k], tri[(k + 1) % 3]);
                match first.remove(&(u.min(v), u.max(v))) {
                    Some(o) => {
                        let dot: f64 = (0..3).map(|i| normals[o][i] * normals[t][i]).sum();
                        sum += dot.clamp(-1.0, 1.0).acos().to_degrees();
                        edges += 1;
                    }
                    None => {
                        first.insert((u.min(v), u.max(v)), t);
                    }
                }
            }
        }
    }
    if edges == 0 { 0.0 } else { sum / edges as f64 }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lens<'a>(a: &'a str, b: &'a str, named: bool, x: f64) -> Enclosed<'a> {
        Enclosed {
            named,
            surfaces: vec![(a, [x, 0.0, 0.0]), (b, [x, 1.0, 0.0])],
        }
    }

    fn rough_h2(s: &str) -> f64 {
        if s == "h2" { 30.0 } else { 2.0 }
    }

    #[test]
    fn a_few_lenses_between_two_surfaces_pass() {
        let r: Vec<Enclosed> = (0..MAX_LENSES)
            .map(|i| lens("h1", "h2", false, i as f64))
            .collect();
        assert!(check_lenses(&r, rough_h2).is_ok());
    }

    #[test]
    fn more_lenses_than_the_limit_fail_blaming_the_rougher_surface_on_the_first() {
        let r: Vec<Enclosed> = (0..=MAX_LENSES)
            .map(|i| lens("h1", "h2", false, 10.0 + i as f64))
            .collect();
        let e = check_lenses(&r, rough_h2).unwrap_err();
        assert!(e.message.contains("`h1` and `h2`"), "{}", e.message);
        assert!(e.message.contains(&format!("{} regions", MAX_LENSES + 1)));
        assert!(e.message.contains("`h2` is the rougher"), "{}", e.message);
        assert_eq!(e.surface.as_deref(), Some("h2"));
        assert_eq!(e.at, Some([10.0, 1.0, 0.0]));
        assert!(e.message.contains("[[trim]]"), "{}", e.message);
        let e = check_lenses(&r, |s| if s == "h1" { 9.0 } else { 1.0 }).unwrap_err();
        assert_eq!(
            (e.surface.as_deref(), e.at),
            (Some("h1"), Some([10.0, 0.0, 0.0]))
        );
    }

    #[test]
    fn named_regions_regions_with_the_box_and_regions_of_three_surfaces_do_not_count() {
        let mut r: Vec<Enclosed> = (0..=MAX_LENSES)
            .map(|i| lens("h1", "h2", true, i as f64))
            .collect();
        r.extend((0..=MAX_LENSES).map(|i| lens("box.xmin", "h2", false, i as f64)));
        r.extend((0..=MAX_LENSES).map(|_| Enclosed {
            named: false,
            surfaces: vec![("f1", [0.0; 3]), ("h1", [0.0; 3]), ("h2", [0.0; 3])],
        }));
        assert!(check_lenses(&r, rough_h2).is_ok());
    }

    #[test]
    fn the_mean_turn_of_a_flat_sheet_is_zero_and_of_a_folded_one_its_angle() {
        // The unit square in two triangles, its corner (1, 1) raised by `z`.
        let sheet = |z: f64| {
            let v = vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [1.0, 1.0, z],
                [0.0, 1.0, 0.0],
            ];
            geom::TriMesh::new(v, vec![[0, 1, 2], [0, 2, 3]])
        };
        let (flat, folded) = (sheet(0.0), sheet(1.0));
        let patch = |surface: &str, mesh: geom::TriMesh| PatchIn {
            name: format!("{surface}#1"),
            surface: surface.to_string(),
            mesh,
            chart_of: None,
        };
        let patches = [patch("a", flat), patch("b", folded)];
        assert!(mean_turn(&patches, "a").abs() < 1e-9);
        let b = mean_turn(&patches, "b");
        assert!(b > 30.0 && b < 90.0, "{b}");
        assert_eq!(mean_turn(&patches, "c"), 0.0);
    }
}
