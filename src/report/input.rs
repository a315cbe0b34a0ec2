//! What a report is made of: the model summary (surfaces, curves, patches, regions), the final
//! tet mesh's figures and the build steps. Plain data handed over by the caller (the command
//! line); nothing here is computed from files. [`ReportInput::from_mesh`] fills what a bare mesh
//! can say (surface groups, regions, their element counts and volumes) for callers without a
//! model.

use super::facts::MeshFacts;
use geom::mesh::{SurfaceKind, VolumeMesh};
use geom::predicates::signed_volume;
use model::regions::Side;
use serde::Serialize;

/// One imported surface (or box side) of the model.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SurfaceSummary {
    pub name: String,
    pub kind: SurfaceKind,
    /// Triangles as imported (before splitting).
    pub triangles: usize,
    /// Validation findings (the seed's black-list) on this surface.
    pub findings: usize,
}

/// One curve of the model (an intersection, a box edge, a free border).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CurveSummary {
    /// Stable curve name, e.g. `F1/H1` or `F1/H1#2`.
    pub name: String,
    /// Surfaces the curve lies on, in name order.
    pub surfaces: Vec<String>,
    /// Polyline length in model units.
    pub length: f64,
    /// FE nodes of its discretization (ends included); 0 when not discretized yet.
    pub nodes: usize,
}

/// One patch of the model (a piece of a surface between curves).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PatchSummary {
    /// Stable patch name `surface#k`.
    pub name: String,
    pub surface: String,
    /// FE triangles of its surface mesh; 0 when not meshed yet.
    pub triangles: usize,
    /// Both sides bound the same region (a fault tip inside a region).
    pub dangling: bool,
}

/// One side of one patch bounding a region.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PatchSide {
    pub patch: String,
    pub side: Side,
}

/// One region of the model.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RegionSummary {
    pub name: String,
    /// Material id from the recipe (as in [`geom::mesh::RegionGroup::material`]).
    pub material: Option<i64>,
    /// The patch sides bounding it (a dangling patch appears with both sides).
    pub patches: Vec<PatchSide>,
    /// Tets of its mesh; 0 when not meshed yet.
    pub tets: usize,
    /// Enclosed volume of the model region (model units cubed; NaN when unknown).
    pub volume: f64,
}

/// One node of the build: what ran and why.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct StepSummary {
    /// Build node name, e.g. `discretize:F1/H1`.
    pub name: String,
    /// `ran`, `cached`, `cut off`, `failed` or `skipped` (the engine's `NodeState::as_str`).
    pub state: String,
    /// Why it ran (the engine's rebuild reason, in words).
    pub reason: String,
    pub duration_ms: f64,
}

/// Everything a report shows.
#[derive(Clone, Debug)]
pub struct ReportInput<'a> {
    pub model_name: &'a str,
    pub recipe_path: &'a str,
    pub surfaces: Vec<SurfaceSummary>,
    pub curves: Vec<CurveSummary>,
    pub patches: Vec<PatchSummary>,
    pub regions: Vec<RegionSummary>,
    /// The figures of the final tet mesh (with its tagged triangles and groups).
    pub mesh: MeshFacts,
    pub steps: Vec<StepSummary>,
    /// What the build has to say about the recipe's effect (thin regions meshed one element
    /// across), shown first among the report's warnings.
    pub warnings: Vec<String>,
}

/// Nothing: empty names and lists and the figures of an empty mesh, so a caller can write
/// `ReportInput { model_name, mesh: MeshFacts::of(&mesh, model_name), ..Default::default() }` and
/// fields added later do not break it.
impl Default for ReportInput<'_> {
    fn default() -> Self {
        ReportInput {
            model_name: "",
            recipe_path: "",
            surfaces: Vec::new(),
            curves: Vec::new(),
            patches: Vec::new(),
            regions: Vec::new(),
            mesh: MeshFacts::of(&VolumeMesh::default(), ""),
            steps: Vec::new(),
            warnings: Vec::new(),
        }
    }
}

impl<'a> ReportInput<'a> {
    /// A report of a bare mesh: one surface per surface group (its FE triangles as the imported
    /// count, no findings), one region per region group (tets, summed tet volume), no curves,
    /// patches or steps. Elements whose tags or nodes are out of range are not counted.
    pub fn from_mesh(model_name: &'a str, recipe_path: &'a str, mesh: &VolumeMesh) -> Self {
        let facts = MeshFacts::of(mesh, model_name);
        let (tris, tets, volume) = (
            &facts.group_triangles,
            &facts.region_tets,
            &facts.region_volume,
        );
        ReportInput {
            model_name,
            recipe_path,
            surfaces: mesh
                .surface_groups
                .iter()
                .zip(tris)
                .map(|(g, &n)| SurfaceSummary {
                    name: g.name.clone(),
                    kind: g.kind,
                    triangles: n,
                    findings: 0,
                })
                .collect(),
            curves: Vec::new(),
            patches: Vec::new(),
            regions: mesh
                .regions
                .iter()
                .enumerate()
                .map(|(i, r)| RegionSummary {
                    name: r.name.clone(),
                    material: r.material,
                    patches: Vec::new(),
                    tets: tets.get(i).copied().unwrap_or(0),
                    volume: volume.get(i).copied().unwrap_or(f64::NAN),
                })
                .collect(),
            mesh: facts,
            steps: Vec::new(),
            warnings: Vec::new(),
        }
    }
}

/// Tets per mesh region and the sum of their absolute volumes (a measure), in region index
/// order. Tets with an out-of-range region tag or node are skipped.
pub fn region_tets_and_volumes(mesh: &VolumeMesh) -> (Vec<usize>, Vec<f64>) {
    let n = mesh.regions.len();
    let (mut count, mut vol) = (vec![0usize; n], vec![0.0f64; n]);
    for (t, &r) in mesh.tets.iter().zip(&mesh.tet_region) {
        let r = r as usize;
        let (Some(c), Some(v)) = (count.get_mut(r), vol.get_mut(r)) else {
            continue;
        };
        let Some([a, b, p, d]) = tet_points(mesh, t) else {
            continue;
        };
        *c += 1;
        *v += signed_volume(&a, &b, &p, &d).abs();
    }
    (count, vol)
}

/// The four corners of a tet, or `None` if a node index is out of range.
pub(crate) fn tet_points(mesh: &VolumeMesh, t: &[u32; 4]) -> Option<[[f64; 3]; 4]> {
    Some([
        *mesh.nodes.get(t[0] as usize)?,
        *mesh.nodes.get(t[1] as usize)?,
        *mesh.nodes.get(t[2] as usize)?,
        *mesh.nodes.get(t[3] as usize)?,
    ])
}

/// The three corners of a triangle, or `None` if a node index is out of range.
pub(crate) fn tri_points(mesh: &VolumeMesh, t: &[u32; 3]) -> Option<[[f64; 3]; 3]> {
    Some([
        *mesh.nodes.get(t[0] as usize)?,
        *mesh.nodes.get(t[1] as usize)?,
        *mesh.nodes.get(t[2] as usize)?,
    ])
}
