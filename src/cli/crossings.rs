//! Where the meshes of two surfaces cross inside a region (the surfaces meet at a small angle, an
//! onlap's tip, and each mesh keeps within its tolerance of its own surface, not of the other's),
//! the build refines along the curves where the two surfaces meet and builds again: the finer
//! the meshes there, the closer each follows its own surface, and the two surfaces themselves do
//! not cross. The refinement is the `[[mesh.refine]]` entry the region's error advises (a tenth
//! of the region's size); where the meshes still cross, a quarter of the size before, for at most
//! [`ROUNDS`] rounds, and never below `min_size`. Then the build fails with the place and the
//! advice. What was added is said, with the entry that does it from the start.
//!
//! Building again costs what the refinement reaches: the crossing region fails at its input
//! check, what it does not reach is cached, and what failed out of its reach fails again at once
//! (`engine::build_again`); failed regions within its reach run again. The same recipe gets the
//! same rounds, so the mesh is as reproducible as any other, and `--locked` checks it.

use crate::plan::ops::{AdvisedRefinement, ModelData};
use crate::recipe::{CurveSelector, Recipe, RefineSpec, RefineTarget};
use engine::{BuildReport, NodeState};

/// At most this many rounds of refinement are added.
pub const ROUNDS: usize = 3;
/// Each round after the first refines to this fraction of the size before.
const SHRINK: f64 = 0.25;

/// The `[[mesh.refine]]` entries to add to `recipe` after the failed build `report`: one per
/// pair of surfaces whose meshes cross in a failed region, along curves of `model` where the two
/// meet.
pub fn refinements(
    report: &BuildReport,
    recipe: &Recipe,
    model: Option<&ModelData>,
) -> Vec<RefineSpec> {
    let advised = (report.nodes.iter())
        .filter(|n| n.state == NodeState::Failed && n.kind == "tet_mesh")
        .filter_map(|n| AdvisedRefinement::of_crossing(n.error.as_deref()?));
    next_round(advised, recipe, &|pair| meet_along_a_curve(model, pair))
}

/// The entries to add for the `advised` ones, each once, along curves that exist (`meet`): the
/// size advised, or a quarter of the finest the recipe already has along the same curves; none
/// that would be below `min_size`.
fn next_round(
    advised: impl Iterator<Item = AdvisedRefinement>,
    recipe: &Recipe,
    meet: &dyn Fn(&str) -> bool,
) -> Vec<RefineSpec> {
    let mut added: Vec<RefineSpec> = Vec::new();
    for advised in advised {
        let Ok(selector) = CurveSelector::parse(&advised.curve) else {
            continue;
        };
        if !meet(&advised.curve) || added.iter().any(|r| same(r, &selector)) {
            continue;
        }
        let before = (recipe.mesh.refine.iter())
            .filter(|r| same(r, &selector))
            .map(|r| r.size)
            .fold(f64::INFINITY, f64::min);
        let size = if before.is_finite() {
            SHRINK * before
        } else {
            advised.size
        };
        if size < recipe.mesh.min_size || size >= recipe.mesh.size {
            continue;
        }
        added.push(RefineSpec {
            near: RefineTarget::Curve(selector),
            size,
            distance: advised.distance,
            far: recipe.mesh.size,
            span: Default::default(),
        });
    }
    added
}

/// Whether `r` refines near the curves `selector` selects, written the same way up to order.
fn same(r: &RefineSpec, selector: &CurveSelector) -> bool {
    matches!(&r.near, RefineTarget::Curve(s) if s.sides == selector.sides && s.component == selector.component)
}

/// Whether the model has a curve where the two surfaces of `pair` (`a/b`) meet.
fn meet_along_a_curve(model: Option<&ModelData>, pair: &str) -> bool {
    let Some((a, b)) = pair.split_once('/') else {
        return false;
    };
    let mut want = [a, b];
    want.sort_unstable();
    model.is_some_and(|m| {
        (m.topology.curves.iter()).any(|c| c.surfaces.iter().map(String::as_str).eq(want))
    })
}

/// Says what a round adds, and how to have it from the start.
pub fn said(r: &RefineSpec) -> String {
    let RefineTarget::Curve(s) = &r.near else {
        return String::new();
    };
    format!(
        "`{}` to {} where the meshes of its two surfaces cross, and building again \
         (`[[mesh.refine]]` with `curve = \"{}\"`, `size = {}` and `distance = {}` in the \
         recipe does it from the start)",
        s.text, r.size, s.text, r.size, r.distance
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn recipe(extra: &str) -> Recipe {
        let text = format!(
            "[model]\nname = \"m\"\n\n[surfaces]\nU = {{ file = \"u.ts\", kind = \"horizon\" }}\n\
             H1 = {{ file = \"h1.ts\", kind = \"horizon\" }}\n\n[box]\nmin = [0, 0, -1]\n\
             max = [1, 1, 0]\n\n[intersect]\nall = [\"box\", \"U\", \"H1\"]\n\n[mesh]\n\
             size = 250.0\nmin_size = 2.0\n{extra}"
        );
        crate::recipe::parse(std::path::Path::new("r.toml"), &text).expect("a recipe")
    }

    fn advised(curve: &str) -> AdvisedRefinement {
        AdvisedRefinement {
            curve: curve.into(),
            size: 25.0,
            distance: 500.0,
        }
    }

    #[test]
    fn a_crossing_is_refined_as_advised_then_at_a_quarter_of_the_size_before_down_to_min_size() {
        let meet = |_: &str| true;
        let mut r = recipe("");
        let mut sizes = Vec::new();
        loop {
            // Two regions advise the same pair: one entry.
            let twice = [advised("H1/U"), advised("U/H1")].into_iter();
            let added = next_round(twice, &r, &meet);
            if added.is_empty() {
                break;
            }
            assert_eq!(added.len(), 1);
            assert_eq!((added[0].distance, added[0].far), (500.0, 250.0));
            sizes.push(added[0].size);
            r.mesh.refine.extend(added);
        }
        // 25 / 4 / 4 = 1.5625 is below `min_size`.
        assert_eq!(sizes, [25.0, 6.25]);
    }

    #[test]
    fn a_crossing_of_surfaces_meeting_along_no_curve_is_not_refined() {
        let r = recipe("");
        assert!(next_round([advised("H1/U")].into_iter(), &r, &|_| false).is_empty());
        // Nor is an advice that is no curve selector.
        let odd = advised("H1/U/x");
        assert!(next_round([odd].into_iter(), &r, &|_| true).is_empty());
    }

    #[test]
    fn a_crossing_the_recipe_already_refines_is_refined_finer() {
        let r = recipe("\n[[mesh.refine]]\ncurve = \"U/H1\"\nsize = 100\ndistance = 400\n");
        let added = next_round([advised("H1/U")].into_iter(), &r, &|_| true);
        assert_eq!(added.len(), 1);
        assert_eq!(added[0].size, 25.0);
        assert!(said(&added[0]).starts_with("`H1/U` to 25 where the meshes of its two surfaces"));
    }
}
