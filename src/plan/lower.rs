//! Lowering: recipe → static build graph (plus the expander that adds the per-curve nodes).

use super::ops::*;
use crate::engine::{BuildGraph, GraphError, NodeId};
use crate::recipe::Recipe;
use crate::stages::discretize::{Grading, Subdivision};
use std::collections::BTreeMap;
use std::sync::Arc;

#[derive(Debug)]
pub struct PlanError(pub String);

impl std::fmt::Display for PlanError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl From<GraphError> for PlanError {
    fn from(e: GraphError) -> Self {
        PlanError(e.to_string())
    }
}

/// The six box sides, in the order every listing uses.
pub const BOX_SIDES: [&str; 6] = ["box.xmin", "box.xmax", "box.ymin", "box.ymax", "box.zmin", "box.zmax"];

/// Builds the graph for `recipe`. Paths of imported files are resolved against the recipe's directory.
pub fn lower(recipe: &Recipe) -> Result<BuildGraph, PlanError> {
    let mut g = BuildGraph::new();
    let mut surface_nodes: BTreeMap<String, NodeId> = BTreeMap::new();
    let units_scale = 1.0 / recipe.model.units.metres();
    for (name, spec) in &recipe.surfaces {
        let file = g.add_file(&format!("file:{name}"), recipe.base_dir.join(&spec.file))?;
        let op = ImportOp {
            surface: name.clone(),
            kind: spec.kind,
            file_label: spec.file.display().to_string(),
            object: spec.object.clone(),
            skip_other_types: spec.skip_other_types,
            units_scale,
            on_invalid: if spec.on_invalid_stop() { OnInvalid::Stop } else { OnInvalid::Repair },
            tolerances: recipe.tolerances.clone(),
        };
        let id = g.add_op(&format!("import:{name}"), Arc::new(op), &[file])?;
        surface_nodes.insert(name.clone(), id);
    }
    let import_names: Vec<String> = recipe.surfaces.keys().map(|n| format!("import:{n}")).collect();
    let import_ids: Vec<NodeId> = surface_nodes.values().copied().collect();

    if let Some(b) = &recipe.bbox {
        let (params, inputs) = match b.around() {
            None => (BoxSpecParams::Explicit { min: b.min(), max: b.max() }, vec![]),
            Some((names, margin)) => {
                let ids = names
                    .iter()
                    .map(|n| surface_nodes.get(n).copied().ok_or_else(|| PlanError(format!("box.around names unknown surface `{n}`"))))
                    .collect::<Result<Vec<_>, _>>()?;
                (BoxSpecParams::Around { surfaces: names.to_vec(), margin }, ids)
            }
        };
        let bx = g.add_op("box", Arc::new(BoxOp(params)), &inputs)?;
        for side in BOX_SIDES {
            let id = g.add_op(&format!("surface:{side}"), Arc::new(BoxSideOp { side: side.to_string() }), &[bx])?;
            surface_nodes.insert(side.to_string(), id);
        }
    }

    let mut intersections = Vec::new();
    for (a, b) in &recipe.intersect {
        let (a, b) = if a <= b { (a, b) } else { (b, a) };
        let ia = *surface_nodes.get(a).ok_or_else(|| PlanError(format!("intersect names unknown surface `{a}` (is [box] given?)")))?;
        let ib = *surface_nodes.get(b).ok_or_else(|| PlanError(format!("intersect names unknown surface `{b}` (is [box] given?)")))?;
        let id = g.add_op(&format!("intersect:{a}/{b}"), Arc::new(IntersectOp { a: a.clone(), b: b.clone() }), &[ia, ib])?;
        intersections.push(id);
    }

    let mut curve_inputs = import_ids.clone();
    curve_inputs.extend(intersections);
    let curves = g.add_op(
        "curves",
        Arc::new(CurvesOp { n_surfaces: import_ids.len(), tolerances: recipe.tolerances.clone() }),
        &curve_inputs,
    )?;

    let rules = recipe.curve_rules();
    let default_size = recipe.mesh.size;
    let resolve_rules = rules.clone();
    let resolve: Arc<RuleResolver> = Arc::new(move |name: &str| {
        // The last matching rule in recipe order wins; without one, the global size applies.
        match resolve_rules.iter().rev().find(|r| (r.matches)(name)) {
            Some(r) => (format!("mesh.curves.\"{}\"", r.selector), r.rule.clone()),
            None => ("mesh.size".to_string(), Subdivision::Size { size: default_size, ratio: 1.0, grading: Grading::Geometric }),
        }
    });
    let selectors = rules.iter().map(|r| (r.matches.clone(), r.unmatched_message.clone())).collect();
    let model = recipe.model.name.clone();
    let formats = recipe.output.formats.clone();
    let n_imports = import_names.len();
    let expander = DiscretizeExpander {
        resolve,
        selectors,
        import_nodes: import_names,
        export: Arc::new(move || ExportOp { model: model.clone(), formats: formats.clone(), n_imports }),
    };
    g.set_expander(curves, Arc::new(expander));
    Ok(g)
}
