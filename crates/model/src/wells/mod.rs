//! Wells in the model: where a well path crosses the model's patches, and which region holds
//! each piece of the path between crossings.
//!
//! It decides:
//! * the **crossings** (the markers of the well): every place a path segment meets a patch's
//!   support triangle, found with `orient3d` only (`cross`). A crossing strictly inside a support
//!   triangle is the segment's intersection with the triangle's plane; one through a support edge
//!   or vertex is met by every triangle there and kept once; one through a support vertex is that
//!   vertex, bit for bit; a station lying on a patch is the crossing itself. Each crossing
//!   becomes a node of that patch's surface mesh, so the well is cut there and its pieces end on
//!   the surfaces exactly.
//! * the **runs**: a path segment in the plane of a patch's support triangles lies on the patch
//!   when those triangles cover it from end to end (exact tests decide which triangles it meets
//!   and crosses the edges of; the parameters where it enters and leaves each are computed from
//!   the shared edge or corner alone, so neighbours' spans meet bit for bit). Consecutive such
//!   segments are a run: it becomes constraint edges of the patch's surface mesh, and its ends
//!   are crossings (where the well reaches and leaves the surface) or path ends.
//! * crossings **on a curve** (through a support edge that is a curve segment, or a support
//!   vertex that is a curve point: where surfaces meet, a fault ends or a chart seam runs): the
//!   point is computed from the curve segment alone (`curves`), so every patch meeting there
//!   gets the same bits, and it is kept as a pin of that curve (`CurvePin`): the curve's
//!   discretization holds it, so all those patches and the regions between them share the node.
//! * what is refused, with the well, the place and the surface: a path that runs along a patch
//!   for part of a segment only (it must have a station where it leaves the surface), or onto
//!   the patch's border, and a crossing of another surface where the path runs along a patch.
//! * the **pieces** (`pieces`): the path cut at every crossing, each piece not lying on a patch
//!   located exactly in the region that strictly contains it (`regions::Locator` on a point of its longest segment);
//!   pieces outside every region (above the box, say) are left out.
//! * the **resampling** of a piece to a target segment length (`resample`): the tet mesher makes
//!   every well segment a chain of tet edges, so a path surveyed every metre would force
//!   metre-sized elements; the resampled piece keeps its two ends bit for bit.

mod cross;
mod curves;
mod pieces;

pub(crate) use cross::inside_patch;
pub use curves::CurveIndex;
pub use pieces::{lengths_along, resample};

use crate::regions::{Locator, PatchIn};
use serde::{Deserialize, Serialize};

/// Where a well meets one patch.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct WellCrossing {
    /// Index of the patch in the slice given to [`cut_well`].
    pub patch: u32,
    pub point: [f64; 3],
    /// Length along the path from its first station.
    pub along: f64,
    /// The model curve the crossing lies on, if any: the point must be a node of that curve's
    /// discretization (a pin), which every patch and region meeting there then shares.
    pub curve: Option<CurvePin>,
}

/// A place on a model curve: on segment `segment` of the polyline of curve `curve` (the index
/// given to [`CurveIndex::new`]), its ends included, so possibly a curve end (a model vertex,
/// a node already).
#[derive(Copy, Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct CurvePin {
    pub curve: u32,
    pub segment: u32,
}

/// A piece of a well inside one region, between two crossings or a crossing and a path end.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct WellPiece {
    /// Index of the region in the `RegionModel` the locator was built from.
    pub region: u32,
    /// The path's stations between the ends, the ends being crossings or path ends (bit for bit).
    pub points: Vec<[f64; 3]>,
}

/// A stretch of a well lying on one patch: its segments are in the patch's support, so they
/// become edges of that patch's surface mesh, not of a region's tet mesh.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct WellRun {
    /// Index of the patch in the slice given to [`cut_well`].
    pub patch: u32,
    /// The path's stations from the end where it reaches the patch to the end where it leaves
    /// it (each a crossing or a path end), bit for bit.
    pub points: Vec<[f64; 3]>,
}

/// A well cut by the model.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct WellCut {
    /// In order along the path.
    pub crossings: Vec<WellCrossing>,
    /// In order along the path.
    pub pieces: Vec<WellPiece>,
    /// The stretches lying on a patch, in order along the path.
    pub runs: Vec<WellRun>,
}

/// Why a well cannot be cut: what happened, at which path segment (index of its first station)
/// and where.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, thiserror::Error)]
#[error("{message}{}", geom::at_suffix(.at))]
pub struct WellError {
    pub message: String,
    pub segment: Option<usize>,
    pub at: Option<[f64; 3]>,
}

/// Cuts the well path `stations` (at least two, no two consecutive equal) by `patches`, whose
/// borders and inner curves are `curves`, and locates its pieces with `locator` (built from the
/// same patches).
pub fn cut_well(
    stations: &[[f64; 3]],
    patches: &[PatchIn],
    curves: &CurveIndex,
    locator: &Locator,
) -> Result<WellCut, WellError> {
    pieces::check_path(stations)?;
    let (crossings, on) = cross::crossings(stations, patches, curves)?;
    let (pieces, runs) = pieces::split(stations, &crossings, &on, locator);
    Ok(WellCut {
        crossings: crossings.into_iter().map(|c| c.crossing).collect(),
        pieces,
        runs,
    })
}
