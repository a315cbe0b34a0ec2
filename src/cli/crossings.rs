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
//!
//! A round is for surfaces that meet at a small angle along a line or two. Two surfaces that
//! cross each other all over (a horizon jittered through the next) meet along hundreds of
//! curves, and refining them all is refining the whole layer: a round whose tets, estimated
//! round the curves (`tets_near_curves`), would pass the budget a region's thin parts have is
//! not built, and the build fails with the crossing and says why it did not refine.

use crate::plan::ops::{AdvisedRefinement, ModelData, REFINEMENT_BUDGET, tets_near_curves};
use crate::recipe::{CurveSelector, Recipe, RefineSpec, RefineTarget};
use engine::{BuildReport, NodeState};

/// At most this many rounds of refinement are added.
pub const ROUNDS: usize = 3;
/// Each round after the first refines to this fraction of the size before.
const SHRINK: f64 = 0.25;

/// A round of refinement: the `[[mesh.refine]]` entries to add, and for each advised one left
/// out because it would refine too much, why.
#[derive(Debug, Default)]
pub struct Round {
    pub added: Vec<RefineSpec>,
    pub refused: Vec<String>,
}

/// The `[[mesh.refine]]` entries to add to `recipe` after the failed build `report`: one per
/// pair of surfaces whose meshes cross in a failed region, along curves of `model` where the two
/// meet.
pub fn refinements(report: &BuildReport, recipe: &Recipe, model: Option<&ModelData>) -> Round {
    let advised = (report.nodes.iter())
        .filter(|n| n.state == NodeState::Failed && n.kind == "tet_mesh")
        .filter_map(|n| AdvisedRefinement::of_crossing(n.error.as_deref()?));
    next_round(advised, recipe, &|pair| meet_along_curves(model, pair))
}

/// The entries to add for the `advised` ones, each once, along curves that exist (`meet` gives
/// their length): the size advised, or a quarter of the finest the recipe already has along the
/// same curves; none that would be below `min_size`, nor one whose tets would pass the budget.
fn next_round(
    advised: impl Iterator<Item = AdvisedRefinement>,
    recipe: &Recipe,
    meet: &dyn Fn(&str) -> Option<f64>,
) -> Round {
    let mut round = Round::default();
    // The sizes grow away from the curves as the surfaces' meshes along them let them.
    let slope = recipe.mesh.growth.min(surface_mesh::MAX_SURFACE_GROWTH) - 1.0;
    for advised in advised {
        let Ok(selector) = CurveSelector::parse(&advised.curve) else {
            continue;
        };
        let Some(length) = meet(&advised.curve) else {
            continue;
        };
        if round.added.iter().any(|r| same(r, &selector)) {
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
        let tets = tets_near_curves(length, size, recipe.mesh.size, slope);
        if tets > REFINEMENT_BUDGET {
            round.refused.push(format!(
                "not refining `{}` to {size} where the meshes of its two surfaces cross: its \
                 curves run {:.1} km, and refining them would take about {:.0} million tets, over \
                 the {:.0} million a refinement may add; surfaces that meet along so much cross \
                 each other all over, not just where they meet at a small angle: part them in \
                 the data",
                selector.text,
                length / 1000.0,
                tets / 1e6,
                REFINEMENT_BUDGET / 1e6,
            ));
            continue;
        }
        round.added.push(RefineSpec {
            near: RefineTarget::Curve(selector),
            size,
            distance: advised.distance,
            far: recipe.mesh.size,
            span: Default::default(),
        });
    }
    round
}

/// Whether `r` refines near the curves `selector` selects, written the same way up to order.
fn same(r: &RefineSpec, selector: &CurveSelector) -> bool {
    matches!(&r.near, RefineTarget::Curve(s) if s.sides == selector.sides && s.component == selector.component)
}

/// The length of the model's curves where the two surfaces of `pair` (`a/b`) meet, if any.
fn meet_along_curves(model: Option<&ModelData>, pair: &str) -> Option<f64> {
    let (a, b) = pair.split_once('/')?;
    let mut want = [a, b];
    want.sort_unstable();
    let lengths: Vec<f64> = (model?.topology.curves.iter())
        .filter(|c| c.surfaces.iter().map(String::as_str).eq(want))
        .map(|c| geom::predicates::polyline_length(&c.points))
        .collect();
    (!lengths.is_empty()).then(|| lengths.iter().sum())
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
        let meet = |_: &str| Some(1000.0);
        let mut r = recipe("");
        let mut sizes = Vec::new();
        loop {
            // Two regions advise the same pair: one entry.
            let twice = [advised("H1/U"), advised("U/H1")].into_iter();
            let added = next_round(twice, &r, &meet).added;
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
        let none = next_round([advised("H1/U")].into_iter(), &r, &|_| None);
        assert!(none.added.is_empty() && none.refused.is_empty());
        // Nor is an advice that is no curve selector.
        let odd = advised("H1/U/x");
        assert!(
            next_round([odd].into_iter(), &r, &|_| Some(1000.0))
                .added
                .is_empty()
        );
    }

    #[test]
    fn a_crossing_the_recipe_already_refines_is_refined_finer() {
        let r = recipe("\n[[mesh.refine]]\ncurve = \"U/H1\"\nsize = 100\ndistance = 400\n");
        let added = next_round([advised("H1/U")].into_iter(), &r, &|_| Some(1000.0)).added;
        assert_eq!(added.len(), 1);
        assert_eq!(added[0].size, 25.0);
        assert!(said(&added[0]).starts_with("`H1/U` to 25 where the meshes of its two surfaces"));
    }

    #[test]
    fn curves_crossing_all_over_are_not_refined_and_the_build_is_told_why() {
        // A horizon jittered 50 m through the next meets it along 49 km of curves: refined once
        // to 20 (about 2 million tets), not again to a quarter of that.
        let r = recipe("\n[[mesh.refine]]\ncurve = \"U/H1\"\nsize = 20\ndistance = 400\n");
        let all_over = next_round([advised("H1/U")].into_iter(), &r, &|_| Some(4.9e4));
        assert!(all_over.added.is_empty());
        let why = &all_over.refused[0];
        assert!(
            why.starts_with(
                "not refining `H1/U` to 5 where the meshes of its two surfaces cross: its \
                 curves run 49.0 km, and refining them would take about 11 million tets, over \
                 the 4 million a refinement may add"
            ),
            "{why}"
        );
        // An onlap's tip of 4 km is refined as finely.
        let tip = next_round([advised("H1/U")].into_iter(), &r, &|_| Some(4000.0));
        assert_eq!((tip.added.len(), tip.refused.len()), (1, 0));
    }
}
