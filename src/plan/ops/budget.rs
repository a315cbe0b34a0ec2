//! What the recipe's sizes may ask of one build, checked when the model is known and before any
//! mesher runs. A size in the wrong unit or a digit too few (`size = 0.05` for 50) asks a 5 km
//! box for about 10¹⁵ tets: without this check the build meshed its first surfaces for many
//! minutes and never answered. With it, the build fails at once naming the region or surface,
//! its extent, the size and the recipe entry it comes from.
//!
//! The estimates are each region's volume at its interior size and each patch's area at its
//! own size (a regular tet of edge h fills h³/8.49, an equilateral triangle √3/4·h²). Sizes get
//! finer towards curves, features and refinements, and the refinement leaves elements somewhat
//! larger than the size, so an estimate is right to within a small factor: the 10.8 million tets
//! of `benches/large` are estimated at 12.4 million. A billion tets is seven times what a 24 GB
//! machine holds (about 140 million at 170 bytes a tet), so only sizes off by far are refused.

use super::ModelData;
use super::sizes::SizeChoice;

/// The most tets the regions' sizes may ask for: a billion, about 170 GB at the 170 bytes a tet
/// a build takes.
pub const MAX_TETS: f64 = 1.0e9;
/// The most triangles the surfaces' sizes may ask for.
pub const MAX_TRIANGLES: f64 = 1.0e8;
/// Tets in a cube of the size's edge, for a regular mesh (a regular tet's volume is h³/8.49).
pub const TETS_PER_CUBE: f64 = 8.49;
/// Equilateral triangles of the size's edge in a unit of area.
const TRIANGLES_PER_SQUARE: f64 = 4.0 / 1.732_050_807_568_877_2;

/// An error when the regions at their `interior` sizes (chosen by `regions`, in model order) ask
/// for more than [`MAX_TETS`], or the patches at their `patches` sizes for more than
/// [`MAX_TRIANGLES`]; it names the one that asks most.
pub fn check(
    model: &ModelData,
    regions: &[SizeChoice],
    interior: &[f64],
    patches: &[SizeChoice],
) -> Result<(), String> {
    let tets =
        (model.regions.regions.iter().zip(regions).zip(interior)).map(|((r, choice), &h)| {
            let volume =
                r.outer.signed_volume + r.cavities.iter().map(|c| c.signed_volume).sum::<f64>();
            let wanted = volume.max(0.0) * TETS_PER_CUBE / h.powi(3);
            (
                wanted,
                format!("region `{}`", r.name),
                volume,
                "m³",
                choice,
                h,
            )
        });
    over(tets.collect(), MAX_TETS, "tets")?;
    let triangles = (model.patches.iter().zip(patches)).map(|(p, choice)| {
        let area = p.mesh.area();
        let wanted = area * TRIANGLES_PER_SQUARE / choice.size.powi(2);
        (
            wanted,
            format!("surface `{}` (patch `{}`)", p.surface, p.name),
            area,
            "m²",
            choice,
            choice.size,
        )
    });
    over(triangles.collect(), MAX_TRIANGLES, "triangles")
}

/// One part's ask: elements, what it is, its extent and unit, the size rule and the size.
type Ask<'a> = (f64, String, f64, &'static str, &'a SizeChoice, f64);

/// An error when the asks together exceed `budget` elements of kind `what`.
fn over(asks: Vec<Ask<'_>>, budget: f64, what: &str) -> Result<(), String> {
    let total: f64 = asks.iter().map(|a| a.0).sum();
    // A sum that is no number (a size of 0 is refused earlier) asks for nothing.
    if total.is_nan() || total <= budget {
        return Ok(());
    }
    let Some((wanted, name, extent, unit, choice, h)) = asks
        .into_iter()
        .reduce(|a, b| if b.0 > a.0 { b } else { a })
    else {
        return Ok(());
    };
    Err(format!(
        "the mesh sizes ask for about {total:.1e} {what}, over the {budget:.0e} a build may make: \
         {name} alone, {extent:.3e} {unit} at size {h}, asks for {wanted:.1e}; its size comes \
         from {}: raise it (a size in the wrong unit, or a digit too few?)",
        entry(&choice.path)
    ))
}

/// A size rule's recipe path as the recipe writes it: `mesh` is `size` in `[mesh]`,
/// `mesh.regions.r` is `size` in `[mesh.regions]`'s entry `r`.
fn entry(path: &str) -> String {
    match path.rsplit_once('.') {
        None => format!("`size` in `[{path}]`"),
        Some((_, "layers" | "min_layers")) => format!("`{path}`"),
        Some((table, key)) => format!("`size` in `[{table}]`'s entry {key}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_size_rule_is_named_as_the_recipe_writes_it() {
        assert_eq!(entry("mesh"), "`size` in `[mesh]`");
        assert_eq!(
            entry("mesh.regions.reservoir"),
            "`size` in `[mesh.regions]`'s entry reservoir"
        );
        assert_eq!(entry("mesh.min_layers"), "`mesh.min_layers`");
    }

    fn choice(size: f64) -> SizeChoice {
        SizeChoice {
            path: "mesh".into(),
            size,
        }
    }

    #[test]
    fn asks_within_the_budget_pass_and_the_largest_ask_over_it_is_named() {
        let c = choice(0.05);
        let ask = |n: f64, name: &str| (n, name.to_string(), 1.0e10, "m³", &c, 0.05);
        assert!(over(vec![ask(4.0e8, "a"), ask(5.0e8, "b")], MAX_TETS, "tets").is_ok());
        let e = over(vec![ask(4.0e8, "a"), ask(7.0e8, "b")], MAX_TETS, "tets").unwrap_err();
        assert!(
            e.starts_with("the mesh sizes ask for about 1.1e9 tets, over the 1e9"),
            "{e}"
        );
        assert!(
            e.contains("b alone, 1.000e10 m³ at size 0.05, asks for 7.0e8"),
            "{e}"
        );
        assert!(e.contains("from `size` in `[mesh]`: raise it"), "{e}");
        // No ask, or asks that are not numbers, are no error.
        assert!(over(vec![], MAX_TETS, "tets").is_ok());
        assert!(over(vec![ask(f64::NAN, "a")], MAX_TETS, "tets").is_ok());
    }
}
