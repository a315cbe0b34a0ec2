//! Where a surface or tet mesh fails at a place where the model's curves come closer than their
//! mesh can resolve (two strands of a fault a metre apart at a kilometre's size), the elements
//! there are flat whatever the mesher does, and the mesher stalls or folds among them. The build
//! then refines that place, as `refine_close_curves` naming one of its curves would, and builds
//! again: only the nodes the refinement reaches run again. What was added is said, with the
//! recipe line that does it from the start.
//!
//! Decisions and why:
//! - The places refined are those on the curves bounding what failed (the region, or the
//!   patch), the one the failure is put down to first, not every place of the model: on the
//!   RINGMesh CloudSpin model, refining all of them gives 9 million tets, and most places mesh
//!   (flat) without it. Refining only the place each failure is put down to took three rounds
//!   there, each region failing at the next place once the last was refined.
//! - The round's places together stay within the budget a refinement may add, estimated as a
//!   tube round the curves where they run close (`tets_near_curves`); the rest are not refined,
//!   and the build says how many.
//! - A failure where two surfaces' meshes cross is left to `crossings`, whose refinement along
//!   the curves where they meet is the remedy: on the corpus's onlap under a degree, refining
//!   the close place as well took 1.5 times the tets for no better smallest dihedral.
//! - `refine_close_curves = false` turns it off, `true` refines every place from the start.
//! - The rounds are the crossings' rounds (`crossings::ROUNDS`): the same recipe gets the same
//!   rounds, so the mesh is as reproducible as any other, and `--locked` checks it.

use crate::plan::ops::{
    AdvisedRefinement, ModelData, REFINEMENT_BUDGET, UnrefinedPlace, refined_size, short_number,
    tets_near_curves, unrefined_places_near,
};
use crate::recipe::{CurveSelector, Recipe};
use engine::{BuildReport, NodeState};

/// A round: the curves whose places to add to `refine_close_curves`, what each adds (for the
/// console), and for each place left out because it would refine too much, why.
#[derive(Debug, Default)]
pub struct CloseRound {
    pub named: Vec<CurveSelector>,
    pub said: Vec<String>,
    pub refused: Vec<String>,
}

/// The places to refine after the failed build `report` of `recipe`: for each surface or tet
/// mesh that failed among close curves of `model` (not where two meshes cross), the places on
/// the curves of what it meshes.
pub fn round(report: &BuildReport, recipe: &Recipe, model: Option<&ModelData>) -> CloseRound {
    let close = &recipe.mesh.refine_close_curves;
    let (Some(model), true, false) = (model, close.on_failure, close.all) else {
        return CloseRound::default();
    };
    let failed: Vec<(&str, [f64; 3])> = (report.nodes.iter())
        .filter(|n| n.state == NodeState::Failed)
        .filter(|n| n.kind == "tet_mesh" || n.kind == "surface_mesh")
        .filter_map(|n| Some((n.name.as_str(), n.error.as_deref()?)))
        .filter(|(_, error)| AdvisedRefinement::of_crossing(error).is_none())
        .filter_map(|(node, error)| Some((node, super::culprit::failure_place(error)?)))
        .collect();
    if failed.is_empty() {
        return CloseRound::default();
    }
    let places = unrefined_places_near(recipe, model, &failed);
    let found = (failed.iter().zip(places))
        .filter(|(_, p)| !p.is_empty())
        .map(|((node, _), p)| (*node, p));
    next_round(found, recipe)
}

/// The round for the places of each failed node (the one its failure is put down to first), as
/// long as their tets together stay within the budget.
fn next_round<'a>(
    failures: impl Iterator<Item = (&'a str, Vec<UnrefinedPlace>)>,
    recipe: &Recipe,
) -> CloseRound {
    let mut round = CloseRound::default();
    let slope = recipe.mesh.growth.min(surface_mesh::MAX_SURFACE_GROWTH) - 1.0;
    let mut total = 0.0;
    for (node, places) in failures {
        let mut over = (0, 0.0);
        for (k, place) in places.into_iter().enumerate() {
            let Ok(selector) = CurveSelector::parse(&place.curve) else {
                continue;
            };
            let size = refined_size(place.gap, recipe.mesh.min_size);
            let tets = tets_near_curves(place.length, size, place.size, slope);
            let pair = place.which();
            if total + tets > REFINEMENT_BUDGET {
                if tets > REFINEMENT_BUDGET {
                    round.refused.push(format!(
                        "not refining where {pair}: they run close for {:.1} km, and refining \
                         there would take about {:.0} million tets, over the {:.0} million a \
                         refinement may add; mend the surfaces there in the data (join or part \
                         them)",
                        place.length / 1000.0,
                        tets / 1e6,
                        REFINEMENT_BUDGET / 1e6,
                    ));
                } else {
                    over = (over.0 + 1, over.1 + tets);
                }
                continue;
            }
            total += tets;
            let [x, y, z] = place.at.map(|v| format!("{v:.1}"));
            let whence = match k {
                0 => format!("at which `{node}` failed"),
                _ => format!("on what `{node}` meshes"),
            };
            round.said.push(format!(
                "where {pair} near ({x}, {y}, {z}), {whence}, to {}, and building again \
                 (`refine_close_curves = [\"{}\"]` in `[mesh]` does it from the start)",
                short_number(size),
                place.curve,
            ));
            round.named.push(selector);
        }
        if over.0 > 0 {
            round.refused.push(format!(
                "not refining {} more places where curves come close on what `{node}` meshes: \
                 they would take about {:.1} million tets more, and with the places above over \
                 the {:.0} million a refinement may add",
                over.0,
                over.1 / 1e6,
                REFINEMENT_BUDGET / 1e6,
            ));
        }
    }
    round
}

#[cfg(test)]
mod tests {
    use super::*;

    fn recipe() -> Recipe {
        let text = "[model]\nname = \"m\"\n\n[surfaces]\nF = { file = \"f.ts\", kind = \"fault\" }\n\
             H = { file = \"h.ts\", kind = \"horizon\" }\n\n[box]\nmin = [0, 0, -1]\n\
             max = [1, 1, 0]\n\n[intersect]\nall = [\"box\", \"F\", \"H\"]\n\n[mesh]\n\
             size = 1000.0\nmin_size = 10.0\n";
        crate::recipe::parse(std::path::Path::new("r.toml"), text).expect("a recipe")
    }

    fn place(curve: &str, other: &str, gap: f64, length: f64) -> UnrefinedPlace {
        UnrefinedPlace {
            curve: curve.into(),
            other: other.into(),
            gap,
            at: [1.0, 2.0, 3.0],
            size: 1000.0,
            length,
        }
    }

    #[test]
    fn the_places_of_what_failed_are_named_once_with_the_line_that_does_it() {
        // Two regions failed; the second at a place the first's places hold already.
        let failures = [
            (
                "tet_mesh:a",
                vec![
                    place("F/H#1", "F/H#2", 0.14, 300.0),
                    place("F#3", "F#3", 25.0, 80.0),
                ],
            ),
            ("tet_mesh:b", vec![]),
        ];
        let round = next_round(failures.into_iter(), &recipe());
        let named: Vec<&str> = round.named.iter().map(|s| s.text.as_str()).collect();
        assert_eq!(named, ["F/H#1", "F#3"]);
        assert!(round.refused.is_empty());
        // Refined to twice the gap's power of two, never below `min_size`.
        assert_eq!(
            round.said[0],
            "where curves `F/H#1` and `F/H#2` come within 0.140 of each other near (1.0, 2.0, \
             3.0), at which `tet_mesh:a` failed, to 10.0, and building again \
             (`refine_close_curves = [\"F/H#1\"]` in `[mesh]` does it from the start)"
        );
        assert!(
            round.said[1].starts_with(
                "where curve `F#3` comes within 25.0 of itself near (1.0, 2.0, 3.0), on what \
                 `tet_mesh:a` meshes, to 32.0"
            ),
            "{}",
            round.said[1]
        );
    }

    #[test]
    fn a_place_whose_curves_run_close_too_long_is_not_refined_and_the_build_is_told_why() {
        // Two sheets 0.5 m apart for 200 km: refined to 10 m, tens of millions of tets.
        let sheets = [("tet_mesh:a", vec![place("F/H#1", "F/H#2", 0.5, 2.0e5)])];
        let round = next_round(sheets.into_iter(), &recipe());
        assert!(round.named.is_empty() && round.said.is_empty());
        let why = &round.refused[0];
        assert!(
            why.starts_with(
                "not refining where curves `F/H#1` and `F/H#2` come within 0.500 of each other: \
                 they run close for 200.0 km"
            ),
            "{why}"
        );
        assert!(
            why.contains("over the 4 million a refinement may add"),
            "{why}"
        );
    }

    #[test]
    fn the_places_of_a_round_stay_within_the_budget_together() {
        // Each place alone is within the budget, five together are not: the first ones are
        // refined and the rest are counted.
        let place_of = |k: usize| place(&format!("F/H#{k}"), "F#1", 0.5, 1.6e4);
        let alone = next_round([("tet_mesh:a", vec![place_of(1)])].into_iter(), &recipe());
        assert_eq!(alone.named.len(), 1);
        let five = [("tet_mesh:a", (1..=5).map(place_of).collect())];
        let round = next_round(five.into_iter(), &recipe());
        assert!(
            !round.named.is_empty() && round.named.len() < 5,
            "{round:?}"
        );
        let why = &round.refused[0];
        assert!(
            why.starts_with(&format!(
                "not refining {} more places where curves come close on what `tet_mesh:a` meshes",
                5 - round.named.len()
            )),
            "{why}"
        );
    }
}
