//! Lowering: recipe → static build graph (plus the expander that adds the per-curve nodes).

use super::ops::*;
use crate::recipe::{self, Recipe};
use engine::{BuildGraph, GraphError, NodeId};
use model::discretize::{Grading, Subdivision};
use std::collections::BTreeMap;
use std::sync::Arc;

/// Why a recipe cannot be lowered to a graph.
#[derive(Debug, thiserror::Error)]
pub enum PlanError {
    #[error(transparent)]
    Graph(#[from] GraphError),
    /// A section (`box.around`, `intersect`) names a surface the recipe does not import.
    #[error("{section} names unknown surface `{name}`")]
    UnknownSurface { section: &'static str, name: String },
}

/// The node of surface `name`, which `section` names.
fn surface_node(
    nodes: &BTreeMap<String, NodeId>,
    section: &'static str,
    name: &str,
) -> Result<NodeId, PlanError> {
    nodes
        .get(name)
        .copied()
        .ok_or_else(|| PlanError::UnknownSurface {
            section,
            name: name.to_string(),
        })
}

/// Builds the graph for `recipe`. Paths of imported files are resolved against the recipe's directory.
pub fn lower(recipe: &Recipe) -> Result<BuildGraph, PlanError> {
    let mut g = BuildGraph::new();
    let mut surface_nodes: BTreeMap<String, NodeId> = BTreeMap::new();
    for (name, spec) in &recipe.surfaces {
        let file = g.add_file(&format!("file:{name}"), spec.path.clone())?;
        let op = ImportOp {
            surface: name.clone(),
            kind: spec.kind,
            file_label: spec.file.display().to_string(),
            object: spec.object.clone(),
            skip_other_types: spec.skip_other_types,
            target_units: recipe.model.units,
            on_invalid: match spec.on_invalid {
                recipe::OnInvalid::Stop => OnInvalid::Stop,
                recipe::OnInvalid::Repair => OnInvalid::Repair,
            },
            tolerances: recipe.tolerances.clone(),
        };
        let mut id = g.add_op(&format!("import:{name}"), Arc::new(op), &[file])?;
        if spec.retriangulate.is_some() || spec.smooth.is_some() {
            let op = SupportOp {
                surface: name.clone(),
                retriangulate: spec.retriangulate,
                smooth: spec.smooth,
                tolerances: recipe.tolerances.clone(),
            };
            id = g.add_op(&format!("support:{name}"), Arc::new(op), &[id])?;
        }
        surface_nodes.insert(name.clone(), id);
    }
    let import_ids: Vec<NodeId> = surface_nodes.values().copied().collect();
    for (name, w) in &recipe.wells {
        let file = g.add_file(&format!("file:{name}"), w.path.clone())?;
        let op = WellImportOp {
            name: name.clone(),
            file_label: w.file.display().to_string(),
            format: w.format,
            object: w.object.clone(),
            target_units: recipe.model.units,
        };
        g.add_op(&format!("well:{name}"), Arc::new(op), &[file])?;
    }

    let mut box_node = None;
    if let Some(b) = &recipe.bbox {
        let (params, inputs) = match &b.extent {
            recipe::BoxExtent::Explicit { min, max } => (
                BoxSpecParams::Explicit {
                    min: *min,
                    max: *max,
                },
                vec![],
            ),
            recipe::BoxExtent::Around { surfaces, margin } => {
                let ids = surfaces
                    .iter()
                    .map(|n| surface_node(&surface_nodes, "box.around", n))
                    .collect::<Result<Vec<_>, _>>()?;
                (
                    BoxSpecParams::Around {
                        surfaces: surfaces.clone(),
                        margin: *margin,
                    },
                    ids,
                )
            }
        };
        let bx = g.add_op("box", Arc::new(BoxOp(params)), &inputs)?;
        box_node = Some(bx);
        for side in recipe::BOX_SIDES {
            let id = g.add_op(
                &format!("surface:{side}"),
                Arc::new(BoxSideOp {
                    side: side.to_string(),
                }),
                &[bx],
            )?;
            surface_nodes.insert(side.to_string(), id);
        }
    }

    let mut intersections = Vec::new();
    for (a, b) in &recipe.intersect {
        let (a, b) = if a <= b { (a, b) } else { (b, a) };
        let ia = surface_node(&surface_nodes, "intersect", a)?;
        let ib = surface_node(&surface_nodes, "intersect", b)?;
        let id = g.add_op(
            &format!("intersect:{a}/{b}"),
            Arc::new(IntersectOp {
                a: a.clone(),
                b: b.clone(),
            }),
            &[ia, ib],
        )?;
        intersections.push(id);
    }

    // The topological model needs something that closes the regions: the box, or surfaces that
    // are sealed already (`[model] sealed = true`, e.g. a gOcad Model3d).
    if box_node.is_some() || recipe.model.sealed {
        let mut paired: Vec<(String, String)> = recipe
            .intersect
            .iter()
            .map(|(a, b)| {
                if a <= b {
                    (a.clone(), b.clone())
                } else {
                    (b.clone(), a.clone())
                }
            })
            .collect();
        paired.sort();
        paired.dedup();
        let (check_inputs, check_groups) = Wiring::new()
            .group("box", box_node)
            .group("surfaces", surface_nodes.values().copied())
            .finish();
        g.add_op(
            "crossings",
            Arc::new(super::ops::CrossingsOp {
                inputs: check_groups,
                paired,
            }),
            &check_inputs,
        )?;
        let (inputs, groups) = Wiring::new()
            .group("box", box_node)
            .group("surfaces", surface_nodes.values().copied())
            .group("intersections", intersections.iter().copied())
            .finish();
        let op = ModelOp {
            inputs: groups,
            faults: recipe
                .surfaces
                .values()
                .filter(|s| s.kind == recipe::SurfaceKind::Fault)
                .map(|s| s.name.clone())
                .collect(),
            smoothed: recipe
                .surfaces
                .values()
                .filter(|s| s.smooth.is_some())
                .map(|s| s.name.clone())
                .collect(),
            names: recipe
                .regions
                .iter()
                .map(|(n, r)| (n.clone(), r.point))
                .collect(),
            names_at: recipe
                .regions
                .values()
                .map(|r| recipe.place(r.span))
                .collect(),
            tolerances: recipe.tolerances.clone(),
            min_size: recipe.mesh.min_size,
            trims: trims(recipe),
            box_at: recipe.bbox.as_ref().map(|b| recipe.place(b.span)),
        };
        let model = g.add_op("model", Arc::new(op), &inputs)?;
        for k in 0..recipe.mesh.refine.len() {
            if let Some(op) = super::ops::RefineOp::new(recipe, k) {
                g.add_op(&format!("refine:{}", k + 1), Arc::new(op), &[model])?;
            }
        }
        g.set_expander(
            model,
            Arc::new(ModelExpander {
                recipe: Arc::new(recipe.clone()),
            }),
        );
        return Ok(g);
    }

    // Without a box or sealed surfaces there is no closed model: the curves of the imports and intersections are
    // discretized and exported, nothing is meshed.
    let (curve_inputs, groups) = Wiring::new()
        .group("surfaces", import_ids)
        .group("intersections", intersections)
        .finish();
    let curves = g.add_op(
        "curves",
        Arc::new(CurvesOp {
            inputs: groups,
            tolerances: recipe.tolerances.clone(),
        }),
        &curve_inputs,
    )?;
    let expander = DiscretizeExpander {
        recipe: Arc::new(recipe.clone()),
    };
    g.set_expander(curves, Arc::new(expander));
    Ok(g)
}

/// The subdivision of the curve `name`: the recipe rule that applies (see
/// `MeshSpec::curve_rule` for precedence), else the global size. Returns the rule's recipe path.
pub fn curve_subdivision(recipe: &Recipe, name: &str) -> (String, Subdivision) {
    match recipe.mesh.curve_rule(name) {
        Some(r) => {
            let sub = super::subdivision(&r.subdivision);
            (format!("mesh.curves.\"{}\"", r.selector.text), sub)
        }
        None => (
            "mesh.size".to_string(),
            Subdivision::Size {
                size: recipe.mesh.size,
                ratio: 1.0,
                grading: Grading::Geometric,
            },
        ),
    }
}

/// The recipe's `[[trim]]`s as the trims stage takes them (each selector resolved to the surfaces
/// it selects), each with its recipe location `file:line:col`.
fn trims(recipe: &Recipe) -> Vec<(model::trims::TrimSpec, String)> {
    let names = recipe.surface_names();
    recipe
        .trims
        .iter()
        .map(|t| {
            let spec = model::trims::TrimSpec {
                selector: t.surface.pattern.clone(),
                surfaces: names
                    .iter()
                    .filter(|n| t.surface.matches(n))
                    .cloned()
                    .collect(),
                action: super::trim_action(&t.action),
            };
            let at = recipe.place(t.span);
            (spec, at)
        })
        .collect()
}
