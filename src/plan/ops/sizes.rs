//! Which element size each patch and each curve is meshed at, once the model's topology says which
//! regions a patch bounds and which patches a curve bounds.
//!
//! A size set on a region must reach the surfaces that bound it: without nodes on them at that
//! spacing, the tet mesher cannot refine the region (its boundary triangles are given). So a
//! patch takes the finest of the sizes that apply to it, as Gmsh's per-entity sizes do:
//! - its surface's `[mesh.surfaces]` rule when there is one, and the `[mesh.regions]` size of
//!   every region on either side whose entry writes one;
//! - without a surface rule, the size of every region on either side: the size its
//!   `[mesh.regions]` entry writes, or the global `[mesh] size` (so a coarser region coarsens the
//!   surfaces only it bounds, and never a surface it shares with a region at the global size).
//!
//! A curve without a `[mesh.curves]` rule takes the finest size of the patches it bounds (its
//! nodes are their border nodes); a curve rule, written for that curve, always wins. Each choice
//! keeps the recipe path of the rule that decided it, which names the parameter in the node's
//! key: a model whose choices are all the global size keeps the keys it had without this step.

use super::ModelData;
use crate::recipe::Recipe;
use model::ModelTopology;

/// A size and the recipe path of the rule it comes from (`mesh`, `mesh.surfaces."H1"`,
/// `mesh.regions.reservoir`), without the trailing `.size`.
#[derive(Clone, Debug, PartialEq)]
pub struct SizeChoice {
    pub path: String,
    pub size: f64,
}

impl SizeChoice {
    fn global(recipe: &Recipe) -> SizeChoice {
        SizeChoice {
            path: "mesh".to_string(),
            size: recipe.mesh.size,
        }
    }

    /// Is this the global `[mesh] size`?
    pub fn is_global(&self) -> bool {
        self.path == "mesh"
    }
}

/// The finest of `choices` (the first of equal sizes), or `fallback` when there is none.
fn finest(choices: impl IntoIterator<Item = SizeChoice>, fallback: SizeChoice) -> SizeChoice {
    choices
        .into_iter()
        .reduce(|a, b| if b.size < a.size { b } else { a })
        .unwrap_or(fallback)
}

/// Per patch of `model` (in its order), the size its surface mesh uses.
pub fn patch_sizes(recipe: &Recipe, model: &ModelData) -> Vec<SizeChoice> {
    let mut bounded: Vec<Vec<&str>> = vec![Vec::new(); model.patches.len()];
    for r in &model.regions.regions {
        for f in &r.sides {
            if let Some(rs) = bounded.get_mut(f.patch as usize)
                && rs.last() != Some(&r.name.as_str())
            {
                rs.push(&r.name);
            }
        }
    }
    model
        .patches
        .iter()
        .zip(&bounded)
        .map(|(p, regions)| patch_size(recipe, &p.surface, regions))
        .collect()
}

fn patch_size(recipe: &Recipe, surface: &str, regions: &[&str]) -> SizeChoice {
    let m = &recipe.mesh;
    let region = |r: &str| -> Option<SizeChoice> {
        m.regions
            .get(r)
            .filter(|spec| spec.size_given)
            .map(|spec| SizeChoice {
                path: format!("mesh.regions.{r}"),
                size: spec.size,
            })
    };
    let ruled = m.surfaces.iter().any(|r| r.selector.matches(surface));
    if ruled {
        let own = SizeChoice {
            path: format!("mesh.surfaces.\"{surface}\""),
            size: m.surface_size(surface),
        };
        let explicit = regions.iter().filter_map(|r| region(r));
        finest(
            std::iter::once(own).chain(explicit),
            SizeChoice::global(recipe),
        )
    } else {
        let each = regions
            .iter()
            .map(|r| region(r).unwrap_or_else(|| SizeChoice::global(recipe)));
        finest(each, SizeChoice::global(recipe))
    }
}

/// Per curve of `topo`, the size a curve without a `[mesh.curves]` rule uses: the finest of the
/// patches it bounds (`patches`, in the topology's patch order), the global size for a curve
/// that bounds none.
pub fn curve_sizes(
    recipe: &Recipe,
    topo: &ModelTopology,
    patches: &[SizeChoice],
) -> Vec<SizeChoice> {
    let mut per_curve: Vec<Vec<SizeChoice>> = vec![Vec::new(); topo.curves.len()];
    for (p, boundary) in topo.patches.iter().enumerate() {
        let Some(choice) = patches.get(p) else {
            continue;
        };
        for c in boundary.curves() {
            if let Some(v) = per_curve.get_mut(c as usize) {
                v.push(choice.clone());
            }
        }
    }
    per_curve
        .into_iter()
        .map(|v| finest(v, SizeChoice::global(recipe)))
        .collect()
}
