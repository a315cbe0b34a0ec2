//! The wells in the build graph: `well:<w>` reads a well path from its file (`import`),
//! `well_cut:<w>` cuts it by the model's patches (`cut`: its crossings become nodes of those
//! patches' surface meshes and its stretches lying on a patch edges of it, which `patch:<p>`
//! gathers with the sizes of the wells within reach),
//! and `wells_in:<r>` hands each region its pieces of every well for its tet mesh (`region`). A
//! well is its own chain of nodes: moving one re-runs its cut, the cheap extractions (only the
//! patches whose crossings or sizes changed mesh again) and the regions whose pieces changed.

mod cut;
mod import;
mod region;

pub use cut::{WellCutData, WellCutOp, WellMarker};
pub use import::{WellData, WellImportOp};
pub use region::{CurvePins, CurvePinsOp, RegionWells, RegionWellsOp};

use super::patch::{PatchCrossing, PatchRun};
use geom::TriMesh;
use geom::refine::{Refinement, boxes_meet};

/// Points along the pieces at most half of `size` apart.
pub(super) fn samples(pieces: &[Vec<[f64; 3]>], size: f64) -> Vec<[f64; 3]> {
    let mut out = Vec::new();
    for p in pieces {
        for w in p.windows(2) {
            let len = geom::predicates::dist(&w[0], &w[1]);
            let n = (2.0 * len / size).ceil().max(1.0) as usize;
            out.extend((0..n).map(|i| {
                let t = i as f64 / n as f64;
                [0, 1, 2].map(|k| w[0][k] + t * (w[1][k] - w[0][k]))
            }));
        }
        out.extend(p.last());
    }
    out
}

/// The crossings of the patch `patch` by the wells `cuts`, in well order then path order.
pub fn patch_crossings(patch: &str, cuts: &[WellCutData]) -> Vec<PatchCrossing> {
    cuts.iter()
        .flat_map(|c| c.markers.iter().map(move |m| (m, c)))
        .filter(|(m, _)| m.patch == patch)
        .map(|(m, c)| PatchCrossing {
            point: m.point,
            well: c.name.clone(),
        })
        .collect()
}

/// The stretches of the wells `cuts` lying on the patch `patch`, in well order then path order.
pub fn patch_runs(patch: &str, cuts: &[WellCutData]) -> Vec<PatchRun> {
    cuts.iter()
        .flat_map(|c| c.runs.iter().map(move |r| (r, c)))
        .filter(|((p, _), _)| p == patch)
        .map(|((_, points), c)| PatchRun {
            points: points.clone(),
            well: c.name.clone(),
        })
        .collect()
}

/// The sizes near the wells `cuts` that reach the support `support` of a patch meshed at `size`
/// growing at `slope`: one refinement per well finer than the patch with a piece within
/// `(size - well size) / slope` of the support's box.
pub fn wells_within_reach(
    cuts: &[WellCutData],
    support: &TriMesh,
    size: f64,
    slope: f64,
) -> Vec<Refinement> {
    let Some(near) = Refinement {
        points: support.vertices.clone(),
        ..Refinement::default()
    }
    .bounds(0.0) else {
        return Vec::new();
    };
    let mut out = Vec::new();
    for c in cuts.iter().filter(|c| c.size < size && slope > 0.0) {
        let pieces: Vec<Vec<[f64; 3]>> = (c.pieces.iter().chain(&c.runs))
            .map(|(_, p)| p.clone())
            .collect();
        let r = Refinement {
            points: samples(&pieces, c.size),
            size: c.size,
            slope,
        };
        let reach = r.reach(size);
        if r.bounds(reach).is_some_and(|b| boxes_meet(b, near)) {
            out.push(r);
        }
    }
    out
}
