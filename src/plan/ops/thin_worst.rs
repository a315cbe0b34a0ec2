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
use export::quality::TetQuality;
use geom::TriMesh;

/// The seed's bar on the smallest dihedral angle (degrees).
pub const DIHEDRAL_BAR: f64 = 10.0;

/// A region thinner than this share of its size is under one element across.
const THIN_SHARE: f64 = 0.5;

/// The warning for the worst tet of Table 2's regions (`table2`, the whole mesh's row `all`
/// left out) when it is under [`DIHEDRAL_BAR`], its region's surfaces allow more, and the
/// region of `model` is thinner there than half its size, with what to write in `recipe`.
pub fn thin_at_worst(recipe: &Recipe, model: &ModelData, table2: &[TetQuality]) -> Option<String> {
    let row = (table2.iter())
        .filter(|r| r.name != "all")
        .min_by(|a, b| a.min_dihedral_deg.total_cmp(&b.min_dihedral_deg))?;
    // Under the bar (an empty region's angle is not a number), and not where the surfaces meet.
    let under = row.min_dihedral_deg < DIHEDRAL_BAR;
    let explained = row.min_dihedral_bound_deg.is_some_and(|b| b < DIHEDRAL_BAR);
    if !under || explained {
        return None;
    }
    let at = row.min_dihedral_at?;
    let regions = &model.regions.regions;
    let k = regions.iter().position(|r| r.name == row.name)?;
    let r = &regions[k];
    // A layered region is sized from its thickness where it thins, and its thin parts' own
    // warnings say where that was held back; one thin all over is told by the thin regions'.
    let own = region_sizes(recipe, model).into_iter().nth(k)?;
    let median = model.thickness.get(k).copied().unwrap_or(0.0);
    if layers_of(recipe, &r.name).0.is_some() || (median > 0.0 && median < own.size) {
        return None;
    }
    let meshes: Vec<&TriMesh> = model.patches.iter().map(|p| &p.mesh).collect();
    let t = model::thickness::thickness_near(&meshes, &r.sides, at)?;
    if t >= THIN_SHARE * own.size {
        return None;
    }
    let [x, y, z] = at.map(|c| format!("{c:.1}"));
    Some(format!(
        "region `{}`'s worst tet ({:.2}°) is where the region is only {} thick, near ({x}, {y}, \
         {z}), but it is meshed at {} (`{}.size`): its tets there are flat whatever the mesher \
         does; a count across sizes it from its thickness where it thins: {}",
        r.name,
        row.min_dihedral_deg,
        short(t),
        short(own.size),
        own.path,
        three_layers(recipe, r)
    ))
}
