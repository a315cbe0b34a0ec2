//! The expander attached to `model`: once the model is known it adds, for every curve,
//! `curve:<c>` → `discretize:<c>`; for every well, `well_cut:<w>`; for every patch, `patch:<p>`
//! (inputs: the model and the well cuts) → `surface_mesh:<p>` (inputs: the discretizations of its
//! curves); for every region, `wells_in:<r>` when there are wells and `tet_mesh:<r>` (inputs: the
//! surface meshes of its patches and its wells); then `mesh` (all regions and patches, and the
//! well cuts when there are wells, for the named points where they cross the surfaces) and
//! `export`. Sizes come from `sizes`
//! (a patch at the finest of its surface's and its regions' sizes, a curve at its patches'), and
//! each `refine:<k>` feature, and each `close_curves:<k>` refinement where the model's curves
//! come closer than their mesh can resolve, is an extra input of exactly the curves, patches and
//! regions within its reach. Editing one curve's subdivision therefore re-runs that curve, the patches it
//! bounds, the regions those bound, `mesh` and `export`, and nothing else.

use super::aspect;
use super::budget;
use super::close_refine;
use super::curves::{CurveSizing, add_curve_nodes, graph_error};
use super::patch::WellReach;
use super::refine;
use super::refine::KnownRefinementOp;
use super::sizes::{self, SizeChoice};
use super::thin;
use super::wells::{CurvePinsOp, RegionWellsOp, WellCutOp};
use super::{AssembleOp, ExportOp, ModelData, PatchExtractOp, SurfaceMeshOp, TetMeshOp, Wiring};
use crate::recipe::{self, Recipe};
use engine::{Artifact, Expander, Expansion, NodeId, OpError};
use geom::mesh::RegionGroup;
use model::regions::FaceUse;
use std::sync::Arc;
use surface_mesh::{MAX_SURFACE_GROWTH, SurfaceSize};
use tet_mesh::{Method, SizeField};

pub struct ModelExpander {
    pub recipe: Arc<Recipe>,
}

impl ModelExpander {
    fn surface_size(&self, choice: &SizeChoice) -> (String, SurfaceSize) {
        let m = &self.recipe.mesh;
        (
            format!("{}.size", choice.path),
            SurfaceSize {
                size: choice.size,
                min_size: m.min_size,
                max_size: m.max_size,
                growth: m.growth,
            },
        )
    }

    /// Whether the surface of the patch named `patch` (`<surface>#<k>`) is smoothed.
    fn smoothed(&self, patch: &str) -> bool {
        let surface = patch.rsplit_once('#').map_or(patch, |(s, _)| s);
        (self.recipe.surfaces.get(surface)).is_some_and(|s| s.smooth.is_some())
    }

    /// The recipe path of the region's mesh settings, its size field and its tet method.
    fn region_settings(&self, region: &str) -> (String, SizeField, Method) {
        let m = &self.recipe.mesh;
        match m.regions.get(region) {
            Some(r) => (
                format!("mesh.regions.{region}"),
                SizeField {
                    size: r.size,
                    min_size: r.min_size,
                    max_size: r.max_size,
                    growth: r.growth,
                    refine: Vec::new(),
                },
                crate::plan::tet_method(r.tet_method),
            ),
            None => (
                "mesh".to_string(),
                SizeField {
                    size: m.size,
                    min_size: m.min_size,
                    max_size: m.max_size,
                    growth: m.growth,
                    refine: Vec::new(),
                },
                crate::plan::tet_method(m.tet_method),
            ),
        }
    }
}

impl ModelExpander {
    /// `well_cut:<w>` for every well (inputs `model` and `well:<w>`), in name order.
    fn add_well_cuts(&self, x: &mut Expansion, model: NodeId) -> Result<Vec<NodeId>, OpError> {
        let mut cuts = Vec::with_capacity(self.recipe.wells.len());
        for (name, w) in &self.recipe.wells {
            let well = x
                .node(&format!("well:{name}"))
                .ok_or_else(|| format!("no `well:{name}` node"))?;
            let (size_path, size) = match w.size {
                Some(s) => (format!("wells.{name}.size"), s),
                None => ("mesh.size".to_string(), self.recipe.mesh.size),
            };
            let op = WellCutOp {
                name: name.clone(),
                size_path,
                size,
                regions: w.regions.clone(),
            };
            let id = x
                .add_op(&format!("well_cut:{name}"), Arc::new(op), &[model, well])
                .map_err(graph_error)?;
            cuts.push(id);
        }
        Ok(cuts)
    }
}

impl Expander for ModelExpander {
    fn expand(&self, output: &Artifact, x: &mut Expansion) -> Result<(), OpError> {
        let model: ModelData = output.decode()?;
        let topo = &model.topology;
        let names: Vec<String> = topo.curves.iter().map(|c| c.name.clone()).collect();
        let unmatched = self.recipe.check_curve_rules(&names);
        if !unmatched.is_empty() {
            return Err(recipe::render(&unmatched).into());
        }
        let patch_names: Vec<String> = model.patches.iter().map(|p| p.name.clone()).collect();
        let face_sets = self
            .recipe
            .group_patches(&patch_names)
            .map_err(|d| recipe::render(&d))?;
        let model_node = x.node("model").ok_or("no `model` node")?;
        let min_segments = topo.min_segments();
        let region_sizes = sizes::region_sizes(&self.recipe, &model);
        let patch_sizes = sizes::patch_sizes(&self.recipe, &model, &region_sizes);
        let curve_caps = sizes::curve_caps(&self.recipe, &model, &region_sizes);
        let curve_sizes = sizes::curve_sizes(&self.recipe, topo, &patch_sizes);
        let curve_sizes = sizes::within_caps(curve_sizes, &curve_caps);
        let surface_slope = self.recipe.mesh.growth.min(MAX_SURFACE_GROWTH) - 1.0;
        let end_sizes =
            sizes::curve_end_sizes(&self.recipe, topo, &curve_sizes, &curve_caps, surface_slope);
        let interior = sizes::interior_sizes(&self.recipe, &model, &region_sizes);
        budget::check(&model, &region_sizes, &interior, &patch_sizes)?;
        let mut placed = refine::place(&self.recipe, &model, x);
        placed.extend(add_close_curves(x, &self.recipe, &model, surface_slope)?);
        let thin = thin::thin_refinements(&self.recipe, &model, &interior, surface_slope);
        placed.extend(add_known(x, "thin", thin)?);
        let cuts = self.add_well_cuts(x, model_node)?;
        let pins = if cuts.is_empty() {
            None
        } else {
            let id = x.add_op("curve_pins", Arc::new(CurvePinsOp), &cuts);
            Some(id.map_err(graph_error)?)
        };
        let mut discretized = Vec::with_capacity(topo.curves.len());
        let sized = curve_sizes.iter().zip(&curve_caps).zip(&end_sizes);
        let each = topo.curves.iter().enumerate().zip(&min_segments).zip(sized);
        for (((at, c), &min), ((size, cap), &ends)) in each {
            let near = refine::bounds_of(&c.points);
            let sizing = CurveSizing {
                fallback: Some(size),
                cap: cap.as_ref(),
                ends,
                refine: refine::within_reach(&placed, near, size.size, surface_slope),
                max_slope: surface_slope,
            };
            discretized.push(add_curve_nodes(
                x,
                &self.recipe,
                (&c.name, at),
                (model_node, true),
                min,
                sizing,
                pins,
            )?);
        }

        let mut piece_inputs = vec![model_node];
        piece_inputs.extend(&cuts);
        let layers = aspect::layers(&self.recipe, &model);
        let sides = aspect::side_layers(&model, &layers);
        let mut meshed = Vec::with_capacity(model.patches.len());
        let each = (model.patches.iter().zip(&topo.patches)).zip(patch_sizes.iter().zip(&sides));
        for ((p, boundary), (choice, side)) in each {
            let reach = (!cuts.is_empty()).then_some(WellReach {
                size: choice.size,
                slope: surface_slope,
            });
            let piece = x
                .add_op(
                    &format!("patch:{}", p.name),
                    Arc::new(PatchExtractOp {
                        name: p.name.clone(),
                        reach,
                    }),
                    &piece_inputs,
                )
                .map_err(graph_error)?;
            let mut inputs = vec![piece];
            inputs.extend(boundary.curves().iter().map(|&c| discretized[c as usize]));
            let near = refine::bounds_of(&p.mesh.vertices);
            let features = refine::within_reach(&placed, near, choice.size, surface_slope);
            inputs.extend(&features);
            let (size_path, size) = self.surface_size(choice);
            let m = x
                .add_op(
                    &format!("surface_mesh:{}", p.name),
                    Arc::new(SurfaceMeshOp {
                        name: p.name.clone(),
                        size_path,
                        size,
                        tolerances: self.recipe.tolerances.clone(),
                        refinements: features.len(),
                        layer: side.clone(),
                    }),
                    &inputs,
                )
                .map_err(graph_error)?;
            meshed.push(m);
        }

        let mut region_nodes = Vec::new();
        let mut groups = Vec::new();
        let each =
            (model.regions.regions.iter().zip(&region_sizes)).zip(interior.iter().zip(&layers));
        for ((r, own), (&inside, layer)) in each {
            let mut patches: Vec<u32> = r.sides.iter().map(|f| f.patch).collect();
            patches.dedup();
            let sides: Vec<FaceUse> = r
                .sides
                .iter()
                .map(|f| FaceUse {
                    patch: patches.binary_search(&f.patch).unwrap_or(0) as u32,
                    side: f.side,
                })
                .collect();
            let mut inputs: Vec<NodeId> = patches.iter().map(|&p| meshed[p as usize]).collect();
            if !cuts.is_empty() {
                let wells = x
                    .add_op(
                        &format!("wells_in:{}", r.name),
                        Arc::new(RegionWellsOp {
                            region: r.name.clone(),
                        }),
                        &cuts,
                    )
                    .map_err(graph_error)?;
                inputs.push(wells);
            }
            let (size_path, mut size, method) = self.region_settings(&r.name);
            size.size = inside;
            let near = refine::bounds_of(
                patches
                    .iter()
                    .flat_map(|&p| &model.patches[p as usize].mesh.vertices),
            );
            let features =
                refine::within_reach(&placed, near, own.size, (size.growth - 1.0).clamp(0.0, 1.0));
            inputs.extend(&features);
            let id = x
                .add_op(
                    &format!("tet_mesh:{}", r.name),
                    Arc::new(TetMeshOp {
                        name: r.name.clone(),
                        patches: patches
                            .iter()
                            .map(|&p| model.patches[p as usize].name.clone())
                            .collect(),
                        smoothed: patches
                            .iter()
                            .map(|&p| self.smoothed(&model.patches[p as usize].name))
                            .collect(),
                        sides,
                        size_path,
                        size,
                        method,
                        refinements: features.len(),
                        wells: !cuts.is_empty(),
                        layer: layer.clone(),
                    }),
                    &inputs,
                )
                .map_err(graph_error)?;
            region_nodes.push(id);
            let spec = self.recipe.regions.get(&r.name);
            groups.push(RegionGroup {
                name: r.name.clone(),
                material: spec.and_then(|s| s.material),
                properties: spec.map(|s| s.properties.clone()).unwrap_or_default(),
            });
        }
        let mut wiring = Wiring::new()
            .group("regions", region_nodes)
            .group("patches", meshed);
        if !cuts.is_empty() {
            // Only with wells, so that a recipe without keeps its graph.
            wiring = wiring.group("wells", cuts);
        }
        let (mesh_inputs, inputs) = wiring.finish();
        let well_areas = (self.recipe.wells.iter())
            .filter_map(|(name, w)| w.area.map(|a| (name.clone(), a)))
            .collect();
        let assemble = AssembleOp {
            regions: groups,
            face_sets,
            well_areas,
            inputs,
        };
        let mesh = x
            .add_op("mesh", Arc::new(assemble), &mesh_inputs)
            .map_err(graph_error)?;
        let (export_inputs, inputs) = Wiring::new()
            .group("curves", discretized)
            .group("mesh", [mesh])
            .finish();

        let export = ExportOp::new(&self.recipe, inputs);
        x.add_op("export", Arc::new(export), &export_inputs)
            .map_err(graph_error)?;
        Ok(())
    }
}

/// A `close_curves:<k>` node for each refinement where the model's curves come close.
fn add_close_curves(
    x: &mut Expansion,
    recipe: &Recipe,
    model: &ModelData,
    slope: f64,
) -> Result<Vec<refine::Placed>, OpError> {
    let found = close_refine::close_refinements(recipe, model, slope);
    add_known(x, "close_curves", found)
}

/// One `<kind>:<k>` node per refinement, in order, placed for the nodes within their reach.
fn add_known(
    x: &mut Expansion,
    kind: &'static str,
    refinements: Vec<geom::refine::Refinement>,
) -> Result<Vec<refine::Placed>, OpError> {
    let mut out = Vec::new();
    for (k, refinement) in refinements.into_iter().enumerate() {
        let name = format!("{kind}:{}", k + 1);
        let node = (x.add_op(
            &name,
            Arc::new(KnownRefinementOp {
                kind,
                refinement: refinement.clone(),
            }),
            &[],
        ))
        .map_err(graph_error)?;
        out.extend(refine::Placed::known(node, &refinement));
    }
    Ok(out)
}
