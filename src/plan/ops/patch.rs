//! `patch:<p>` and `surface_mesh:<p>`: one patch of the model extracted with its boundary and the
//! wells' crossings of it (so a patch whose support, boundary and crossings did not change cuts
//! its dependents off early), and its FE surface mesh from the discretizations of its curves,
//! with every crossing a node.

use super::aspect::Layer;
use super::wells::{WellCutData, patch_crossings, patch_runs, wells_within_reach};
use super::{CurveNodes, ModelData};
use engine::{Artifact, OpError, Operation, Output, Params, RunContext};
use geom::mesh::SurfaceKind;
use geom::refine::Refinement;
use geom::{Tolerances, TriMesh};
use model::{PatchBoundary, patch_input};
use serde::{Deserialize, Serialize};
use surface_mesh::{SurfaceSize, mesh_patch_stretched, mesh_patch_with_progress};

/// The output of `patch:<p>`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PatchPiece {
    pub name: String,
    pub surface: String,
    pub kind: SurfaceKind,
    pub support: TriMesh,
    /// Curve indices refer to `curves`.
    pub boundary: PatchBoundary,
    /// Names of the curves bounding or constraining the patch, in model order.
    pub curves: Vec<String>,
    /// Where wells cross the patch (nodes its mesh must have), in well order then path order.
    pub crossings: Vec<PatchCrossing>,
    /// Where wells lie on the patch (polylines its mesh must have as edges), in well order then
    /// path order.
    pub runs: Vec<PatchRun>,
    /// Where another surface touches the patch at an isolated point (nodes its mesh must have).
    pub touches: Vec<[f64; 3]>,
    /// The sizes near the wells that come within reach of the patch, in well order.
    pub well_refine: Vec<Refinement>,
    /// The support triangles that stand for another direction than their own, with it
    /// (`ModelPatch::facets`).
    pub facets: Vec<(u32, [f64; 3])>,
}

/// A well's crossing of a patch: a node of its mesh.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PatchCrossing {
    pub point: [f64; 3],
    pub well: String,
}

/// A stretch of a well lying on a patch: constraint edges of its mesh.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PatchRun {
    pub points: Vec<[f64; 3]>,
    pub well: String,
}

/// How far a well's size reaches on a patch: the patch's own size and the slope its mesh grows
/// at (a well finer than the patch refines it up to `(size - well size) / slope` away).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WellReach {
    pub size: f64,
    pub slope: f64,
}

/// `patch:<p>`: extracts patch `p` from the model; inputs `model`, then every `well_cut:<w>`.
pub struct PatchExtractOp {
    pub name: String,
    /// With wells: how far their sizes reach (in the key only then, so recipes without wells
    /// keep their keys).
    pub reach: Option<WellReach>,
}

impl Operation for PatchExtractOp {
    fn kind(&self) -> &'static str {
        "patch"
    }
    /// Read only by its `surface_mesh` when that re-runs.
    fn lazy_output(&self) -> bool {
        true
    }
    fn version(&self) -> u32 {
        // 3: the wells' crossings of the patch and their sizes within reach.
        // 4: the wells' stretches lying on the patch.
        // 5: the points where other surfaces touch the patch.
        // 6: the triangles that stand for another direction (caps and needles).
        6
    }
    fn params(&self) -> Params {
        let mut p = Params::new()
            .with("patch", self.name.as_str())
            .expect("string");
        if let Some(r) = self.reach {
            p.set("size", r.size).expect("validated finite");
            p.set("slope", r.slope).expect("validated finite");
        }
        p
    }
    fn run(&self, _ctx: &dyn RunContext, inputs: &[Artifact]) -> Result<Output, OpError> {
        let (model, cuts) = inputs.split_first().ok_or("patch needs the model")?;
        let model = model.decode_shared::<ModelData>()?;
        let cuts: Vec<WellCutData> = cuts.iter().map(|a| a.decode()).collect::<Result<_, _>>()?;
        let i = model
            .patches
            .iter()
            .position(|p| p.name == self.name)
            .ok_or_else(|| OpError::from(format!("the model has no patch `{}`", self.name)))?;
        let mut boundary = model.topology.patches[i].clone();
        let used = boundary.curves();
        let local = |c: u32| used.binary_search(&c).map_or(u32::MAX, |k| k as u32);
        for u in boundary.loops.iter_mut().flatten() {
            u.curve = local(u.curve);
        }
        for c in &mut boundary.constraints {
            *c = local(*c);
        }
        let p = &model.patches[i];
        let piece = PatchPiece {
            name: p.name.clone(),
            surface: p.surface.clone(),
            kind: p.kind,
            support: p.mesh.clone(),
            boundary,
            curves: used
                .iter()
                .map(|&c| model.topology.curves[c as usize].name.clone())
                .collect(),
            crossings: patch_crossings(&p.name, &cuts),
            runs: patch_runs(&p.name, &cuts),
            touches: (model.touches.iter())
                .filter(|(pi, _)| *pi as usize == i)
                .map(|(_, x)| *x)
                .collect(),
            well_refine: match self.reach {
                Some(r) => wells_within_reach(&cuts, &p.mesh, r.size, r.slope),
                None => Vec::new(),
            },
            facets: p.facets.clone(),
        };
        let n = piece.support.triangles.len() as u64;
        Ok(Output::new(Artifact::encode(&piece)?).count("support_triangles", n))
    }
}

/// The output of `surface_mesh:<p>`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PatchMesh {
    pub name: String,
    pub surface: String,
    pub kind: SurfaceKind,
    /// The FE triangles, oriented like the support.
    pub mesh: TriMesh,
}

/// `surface_mesh:<p>`: inputs are `patch:<p>` then `discretize:<c>` for each of its curves, in
/// the order of `PatchPiece::curves`.
pub struct SurfaceMeshOp {
    pub name: String,
    /// Recipe path of the size rule (`mesh.surfaces."H1"` or `mesh.size`).
    pub size_path: String,
    pub size: SurfaceSize,
    pub tolerances: Tolerances,
    /// How many `refine:<k>` inputs follow the curves (features within reach of the patch).
    pub refinements: usize,
    /// For a side of a region with an `aspect`, the layer it is meshed stretched across (in the
    /// key only then).
    pub layer: Option<Layer>,
}

impl Operation for SurfaceMeshOp {
    fn kind(&self) -> &'static str {
        "surface_mesh"
    }
    /// A patch mesh is read only by the tet meshes that re-run and by `mesh`.
    fn lazy_output(&self) -> bool {
        true
    }
    fn version(&self) -> u32 {
        // 4: triangles that fold on the support (a fan turning more than 360°) are split.
        // 5: supports no plane projects one to one get mean value Tutte embeddings, pinched
        //    ones too.
        // 6: a projection is refused when any simple cycle of a pinched border loop turns the
        //    wrong way (a reverse fault's slit pinched to another hole).
        // 7: a support the mean plane does not project one to one tries the exact axis-plane
        //    projection before a Tutte embedding.
        // 8: a folded triangle is judged from every corner's facet, and unfolded by an edge
        //    flip where one does.
        // 9: and as the verification judges it, from the facets it finds.
        // 10: only as the verification judges it (no global search per triangle).
        // 11: the support's curvature is measured on the directions its caps stand for.
        // 12: a projection that turns a few triangles over is mended (teeth folded back, the
        //     vertices round the rest relaxed) before a Tutte embedding is tried.
        // 13: the given nodes enter the triangulation in a biased randomized order, not along
        //     the borders.
        // 14: that order is the tet mesher's (rounds by a hash of the index, 3D Hilbert keys).
        14
    }
    fn params(&self) -> Params {
        let mut p = Params::new();
        p.set("patch", self.name.as_str()).expect("string");
        p.set(&self.size_path, self.size.size)
            .expect("validated finite");
        p.set("mesh.min_size", self.size.min_size)
            .expect("validated finite");
        p.set("mesh.max_size", self.size.max_size)
            .expect("validated finite");
        p.set("mesh.growth", self.size.growth)
            .expect("validated finite");
        p.set(
            "tolerances.support_distance_rel",
            self.tolerances.support_distance_rel,
        )
        .expect("validated finite");
        if let Some(l) = &self.layer {
            p.set("stretch.factor", l.aspect).expect("validated finite");
            p.set("stretch.axis", l.normal.to_vec()).expect("finite");
        }
        p
    }
    fn run(&self, ctx: &dyn RunContext, inputs: &[Artifact]) -> Result<Output, OpError> {
        let (inputs, refine) = super::refine::split_refinements(inputs, self.refinements)?;
        let (piece, rest) = inputs.split_first().ok_or("surface_mesh needs its patch")?;
        let piece: PatchPiece = piece.decode()?;
        let curves: Vec<CurveNodes> = rest.iter().map(|a| a.decode()).collect::<Result<_, _>>()?;
        if curves.len() != piece.curves.len()
            || curves.iter().zip(&piece.curves).any(|(c, n)| &c.name != n)
        {
            return Err(format!(
                "surface_mesh:{}: its curves do not match the patch",
                self.name
            )
            .into());
        }
        let nodes = |c: u32| curves.get(c as usize).map(|c| c.nodes.as_slice());
        let mut input = patch_input(&piece.name, &piece.support, &piece.boundary, &nodes)
            .map_err(|e| OpError::from(e.to_string()))?;
        input.points = (piece.crossings.iter().map(|c| c.point))
            .chain(piece.touches.iter().copied())
            .collect();
        (input.constraints).extend(piece.runs.iter().map(|r| r.points.clone()));
        input.facets = piece.facets.clone();
        let refine: Vec<Refinement> = (refine.into_iter())
            .chain(piece.well_refine.iter().cloned())
            .collect();
        let progress = |done, total| ctx.progress(done, total);
        let (size, tol) = (&self.size, &self.tolerances);
        let out = match (&self.layer, input.support.vertices.first()) {
            (Some(l), Some(&origin)) => {
                mesh_patch_stretched(&input, size, tol, &refine, &l.stretch(origin), &progress)
            }
            _ => mesh_patch_with_progress(&input, size, tol, &refine, &progress),
        }
        .map_err(|e| OpError::from(well_context(e, &piece)))?;
        let mesh = TriMesh::new(out.nodes, out.triangles);
        let (nn, nt) = (mesh.vertices.len() as u64, mesh.triangles.len() as u64);
        Ok(Output::new(Artifact::encode(&PatchMesh {
            name: piece.name,
            surface: piece.surface,
            kind: piece.kind,
            mesh,
        })?)
        .count("nodes", nn)
        .count("triangles", nt))
    }
}

/// A surface-mesh error, naming the well whose crossing or stretch on the patch it is at, if
/// any.
fn well_context(e: surface_mesh::SurfaceMeshError, piece: &PatchPiece) -> String {
    if let Some(c) = piece.crossings.iter().find(|c| Some(c.point) == e.at) {
        return format!(
            "{e} (where well `{}` crosses the patch; move the well path a little if the crossing is too close to a curve)",
            c.well
        );
    }
    match (piece.runs.iter()).find(|r| e.at.is_some_and(|a| r.points.contains(&a))) {
        Some(r) => format!(
            "{e} (where well `{}` runs along the patch; move that stretch of its path away from the patch's curves)",
            r.well
        ),
        None => e.to_string(),
    }
}
