//! The operations of the build graph: thin adapters from the engine's `Operation` trait to the
//! pure stage functions, plus the artifact types they exchange. Each operation declares exactly
//! the parameters it reads; its `version` is bumped whenever its output for the same inputs changes.

mod aspect;
mod budget;
mod close_refine;
mod conformity;
mod crossings;
mod curves;
mod expand;
mod export;
mod facts;
mod geology;
mod geometry;
mod import;
mod inputs;
mod model;
mod patch;
mod proximity;
mod refine;
mod region;
mod sizes;
mod support;
mod thin;
mod thin_worst;
mod vanished;
pub use thin::{BUDGET as REFINEMENT_BUDGET, tets_near_curves};
mod wells;
pub use close_refine::refined_size;
pub use conformity::non_conformity_warnings;
pub use crossings::{Crossing, CrossingsOp, unpaired_crossings};
pub use geology::{Counts as GeologyCounts, counts as geology_counts};
pub use proximity::{
    UnrefinedPlace, close_curve_warnings, close_curves_near, unrefined_places_near,
};
pub use refine::KnownRefinementOp;
pub use refine::RefineOp;
pub use sizes::short as short_number;
pub use sizes::{
    THIN_REGIONS_TOLD, ThinRegion, one_across_summary, short_curve_warnings, thin_region_warnings,
};
pub use thin_worst::{DIHEDRAL_BAR, thin_at_worst};
pub use vanished::vanished_surface_warnings;

pub use curves::{
    CurveExtractOp, CurveNodes, CurveSet, CurvesOp, DiscretizeExpander, DiscretizeOp, ModelCurve,
};
pub use expand::ModelExpander;
pub use export::ExportOp;
pub use facts::MeshFactsOp;
pub use geometry::{BoxOp, BoxSideOp, BoxSpecParams, IntersectOp};
pub use import::{FINDINGS_REMAINING, ImportOp, OnInvalid, findings_by_kind};
pub use inputs::{Groups, Wiring};
pub use model::{ModelData, ModelOp, ModelPatch};
pub use patch::{PatchExtractOp, PatchMesh, PatchPiece, SurfaceMeshOp};
pub use region::{AdvisedRefinement, AssembleOp, RegionMesh, TetMeshOp};
pub use support::SupportOp;
pub use wells::{
    CurvePins, CurvePinsOp, RegionWells, RegionWellsOp, WellCutData, WellCutOp, WellData,
    WellImportOp, WellMarker,
};

use geom::TriMesh;
use geom::mesh::SurfaceKind;
use serde::{Deserialize, Serialize};

/// A surface as the geometric stages see it: an imported surface (after validation and repair)
/// or a box side. The output artifact of `import:<name>` and `surface:box.<side>` nodes.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct SurfaceData {
    pub name: String,
    pub kind: SurfaceKind,
    pub mesh: TriMesh,
    /// Part (TFACE) index of each triangle.
    pub triangle_part: Vec<u32>,
    /// Vertices the file marks as corners (BSTONE).
    pub bstones: Vec<u32>,
    /// The validation report (what was found on import) as JSON text (empty for box sides).
    pub report_json: String,
    /// The validation report, readable (empty when clean).
    pub report_text: String,
    /// Number of validation findings before repair.
    pub findings: u64,
}
