//! The warning for a surface of the recipe that has no part in the model: every patch of it was
//! discarded, so it is meshed nowhere and the build would otherwise say nothing about it. The
//! likely cause decides the help: a `[[trim]]` that selects it may have dropped all of it (the
//! recipe's own act, so named first); a surface not cut by the box is discarded whole where it
//! reaches past it; or it lies outside the box.

use super::ModelData;
use crate::recipe::Recipe;

/// One sentence per recipe surface with no patch in `model`, in name order.
pub fn vanished_surface_warnings(recipe: &Recipe, model: &ModelData) -> Vec<String> {
    let boxed = recipe.bbox.is_some();
    (recipe.surfaces.values())
        .filter(|s| !model.patches.iter().any(|p| p.surface == s.name))
        .map(|s| {
            let name = &s.name;
            let cut_by_box = cut_by_box(recipe, name);
            let trimmed = (recipe.trims.iter()).any(|t| t.surface.matches(name));
            let cause = if trimmed {
                "the `[[trim]]` entries that select it discarded all of it; help: check their \
                 sides and points"
                    .to_string()
            } else if boxed && !cut_by_box {
                format!(
                    "it is not cut by the box, and a surface that reaches past the box uncut is \
                     discarded whole; help: list it with the box in `[intersect]` (`all = [\"box\", \
                     \"{name}\", ...]`)"
                )
            } else {
                "none of it lies inside the box; help: widen `[box]`, or remove the surface"
                    .to_string()
            };
            format!(
                "{}: surface `{name}` has no part in the model, so it is meshed nowhere: {cause}",
                recipe.place(s.span)
            )
        })
        .collect()
}

/// Whether `[intersect]` pairs surface `name` with a side of the box (`box` there stands for its
/// six sides, `box.xmin` to `box.zmax`).
fn cut_by_box(recipe: &Recipe, name: &str) -> bool {
    let side = |s: &str| s.starts_with("box.");
    (recipe.intersect.iter()).any(|(a, b)| (a == name && side(b)) || (b == name && side(a)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_surface_listed_with_the_box_is_cut_by_its_sides_and_one_paired_elsewhere_is_not() {
        let text = "[model]\nname = \"m\"\n[surfaces]\nA = { file = \"a.ts\" }\nB = { file = \"b.ts\" }\n\
                    [box]\nmin = [0.0, 0.0, 0.0]\nmax = [1.0, 1.0, 1.0]\n\
                    [intersect]\nall = [\"box\", \"A\"]\npairs = [[\"A\", \"B\"]]\n[mesh]\nsize = 1.0\n[output]\ndir = \"out\"\n";
        let recipe = crate::recipe::parse(std::path::Path::new("r.toml"), text)
            .unwrap_or_else(|d| panic!("{}", crate::recipe::render(&d)));
        assert!(cut_by_box(&recipe, "A"));
        assert!(!cut_by_box(&recipe, "B"));
    }
}
