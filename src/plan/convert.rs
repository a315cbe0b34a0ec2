//! Recipe values into stage inputs: each recipe enum has its stage's counterpart, and the match
//! here is exhaustive, so a value added on one side fails to compile until the other knows it.

use crate::recipe;

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
    fn formats_of_one_file_family_are_exactly_those_the_export_gives_a_common_file() {
        for (_, a) in recipe::Format::ALL {
            for (_, b) in recipe::Format::ALL {
                let files = |f| export::file_names("m", output_format(f));
                let common = files(a).iter().any(|n| files(b).contains(n));
                assert_eq!(a.file_family() == b.file_family(), common, "{a:?} {b:?}");
            }
        }
    }
}
