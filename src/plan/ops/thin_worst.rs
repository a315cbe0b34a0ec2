//! Why a region's worst tet is flat when its surfaces do not force it: the region is thinner
//! there than its elements. A partly thin region (a detachment's slab under a fault's flat, a
//! layer pinching between two horizons that never meet) is not thin by its median thickness,
//! so the thin-region warning is silent, and Table 2's bound is high, as its surfaces meet at
//! wide angles; its tets there are nevertheless flat whatever the mesher does.
//!
//! Decisions and why:
//! - Looked at only for the region the summary names, and only when its smallest dihedral is
//!   under the bar while the bound is not: the cost (the region's walls indexed, a few rays) is
//!   paid where a bad result needs a reason, never on a good build.
//! - Thin means under half the region's size where its worst tet is: then its tets there are
//!   under one element across. It measures the model (the walls the region is meshed from),
//!   not the mesh, so the thickness is the geology's.
//! - The remedy is the recipe's: a count across (`layers`), which sizes a region from its local
//!   thickness where it thins and says when that would take too many tets. Refining every
//!   thin part by default would cost millions of tets where the user may accept flat ones.
//! - Not told for a region with a count across (its thin parts are sized already, or their
//!   budget's warning says why not), nor for one thin all over (the thin regions' warning says
//!   so): one warning per cause.

use super::ModelData;
use super::sizes::{layers_of, region_sizes, short, three_layers};
use crate::recipe::Recipe;
use geom::TriMesh;

/// A region's worst tet: the region, its smallest dihedral angle (degrees) and where.
pub struct WorstTet<'a> {
    pub region: &'a str,
    pub dihedral: f64,
    pub at: [f64; 3],
}

/// A region thinner than this share of its size is under one element across.
const THIN_SHARE: f64 = 0.5;

/// The warning for `worst` when its region of `model` is thinner there than half its size, with
/// what to write in `recipe`; `None` when it is not (or the place is not in a region of it).
pub fn thin_at_worst(recipe: &Recipe, model: &ModelData, worst: &WorstTet) -> Option<String> {
    let regions = &model.regions.regions;
    let k = regions.iter().position(|r| r.name == worst.region)?;
    let r = &regions[k];
    // A layered region is sized from its thickness where it thins, and its thin parts' own
    // warnings say where that was held back; one thin all over is told by the thin regions'.
    let own = region_sizes(recipe, model).into_iter().nth(k)?;
    let median = model.thickness.get(k).copied().unwrap_or(0.0);
    if layers_of(recipe, &r.name).0.is_some() || (median > 0.0 && median < own.size) {
        return None;
    }
    let meshes: Vec<&TriMesh> = model.patches.iter().map(|p| &p.mesh).collect();
    let t = model::thickness::thickness_near(&meshes, &r.sides, worst.at)?;
    if t >= THIN_SHARE * own.size {
        return None;
    }
    let [x, y, z] = worst.at.map(|c| format!("{c:.1}"));
    Some(format!(
        "region `{}`'s worst tet ({:.2}°) is where the region is only {} thick, near ({x}, {y}, \
         {z}), but it is meshed at {} (`{}.size`): its tets there are flat whatever the mesher \
         does; a count across sizes it from its thickness where it thins: {}",
        r.name,
        worst.dihedral,
        short(t),
        short(own.size),
        own.path,
        three_layers(recipe, r)
    ))
}
