//! Recipe values into stage inputs: each recipe enum has its stage's counterpart, and the match
//! here is exhaustive, so a value added on one side fails to compile until the other knows it.

use crate::recipe;
use model::discretize::{Grading, Subdivision};
use model::trims;

/// The discretization stage's subdivision for a `[mesh.curves]` rule.
pub fn subdivision(s: &recipe::Subdivision) -> Subdivision {
    match *s {
        recipe::Subdivision::Count(n) => Subdivision::Count(n),
        recipe::Subdivision::Size {
            size,
            ratio,
            grading,
        } => Subdivision::Size {
            size,
            ratio,
            grading: match grading {
                recipe::Grading::Geometric => Grading::Geometric,
                recipe::Grading::Bump => Grading::Bump,
            },
        },
    }
}

/// The tet mesher's method for a recipe's `tet_method`.
pub fn tet_method(m: recipe::TetMethod) -> tet_mesh::Method {
    match m {
        recipe::TetMethod::Delaunay => tet_mesh::Method::Delaunay,
        recipe::TetMethod::Front => tet_mesh::Method::Front,
    }
}

/// The trims stage's action for a `[[trim]]`.
pub fn trim_action(a: &recipe::TrimAction) -> trims::TrimAction {
    let side = |s: recipe::Side| match s {
        recipe::Side::Above => trims::Side::Above,
        recipe::Side::Below => trims::Side::Below,
        recipe::Side::Inside => trims::Side::Inside,
        recipe::Side::Outside => trims::Side::Outside,
    };
    match a {
        recipe::TrimAction::Keep { side: s, of } => trims::TrimAction::Keep {
            side: side(*s),
            of: of.clone(),
        },
        recipe::TrimAction::DiscardContaining(p) => trims::TrimAction::DiscardContaining(*p),
        recipe::TrimAction::DiscardNearest(p) => trims::TrimAction::DiscardNearest(*p),
        recipe::TrimAction::DiscardAreaBelow(a) => trims::TrimAction::DiscardAreaBelow(*a),
        recipe::TrimAction::DiscardWithin(d) => trims::TrimAction::DiscardWithin(*d),
    }
}

/// The export stage's format for a recipe's `output.formats` entry.
pub fn output_format(f: recipe::Format) -> export::Format {
    match f {
        recipe::Format::Msh => export::Format::Msh,
        recipe::Format::MshBinary => export::Format::MshBinary,
        recipe::Format::Vtu => export::Format::Vtu,
        recipe::Format::VtuBinary => export::Format::VtuBinary,
        recipe::Format::Tetgen => export::Format::TetGen,
        recipe::Format::Medit => export::Format::Medit,
        recipe::Format::Inp => export::Format::Inp,
        recipe::Format::Exodus => export::Format::Exodus,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_recipe_format_keeps_its_spelling_as_the_export_stages_name() {
        for (spelling, f) in recipe::Format::ALL {
            assert_eq!(output_format(f).name(), spelling);
        }
    }

    #[test]
    fn every_recipe_alias_names_the_same_format_in_the_export_stage() {
        for (alias, f) in recipe::Format::ALIASES {
            assert_eq!(export::Format::from_name(alias), Some(output_format(f)));
        }
    }

    #[test]
    fn every_recipe_tet_method_keeps_its_spelling_as_the_meshers_name() {
        for (spelling, m) in recipe::TetMethod::NAMES {
            assert_eq!(tet_method(m).name(), spelling);
        }
        assert_eq!(
            tet_method(recipe::TetMethod::default()),
            tet_mesh::Method::default()
        );
    }

    #[test]
    fn formats_of_one_file_family_are_exactly_those_the_export_gives_a_common_file() {
        for (_, a) in recipe::Format::ALL {
            for (_, b) in recipe::Format::ALL {
                let files = |f| {
                    export::file_names("m", output_format(f), &geom::mesh::VolumeMesh::default())
                };
                let common = files(a).iter().any(|n| files(b).contains(n));
                assert_eq!(a.file_family() == b.file_family(), common, "{a:?} {b:?}");
            }
        }
    }
}
