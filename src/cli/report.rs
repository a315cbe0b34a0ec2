//! `report.html` and `report.json`: gathered after each build from the build report (what ran
//! and why) and the artifacts of `model`, the imports, the per-entity nodes and `mesh`, rendered
//! by `crate::report`, and written atomically beside the outputs. They are not build outputs in
//! the lock file: they say what re-ran, which differs from build to build by design.

use super::Failure;
use super::build::write_atomic;
use crate::plan::ops::{ModelData, SurfaceData};
use crate::recipe::Recipe;
use crate::report::{
    CurveSummary, ReportInput, StepSummary, SurfaceSummary, model_summaries, render_both,
};
use engine::BuildReport;
use geom::mesh::VolumeMesh;
use std::path::{Path, PathBuf};

fn count(report: &BuildReport, node: &str, key: &str) -> usize {
    report
        .node(node)
        .and_then(|n| n.counts.get(key))
        .map_or(0, |&c| c as usize)
}

fn polyline_length(p: &[[f64; 3]]) -> f64 {
    p.windows(2)
        .map(|w| {
            let d = [w[1][0] - w[0][0], w[1][1] - w[0][1], w[1][2] - w[0][2]];
            (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt()
        })
        .sum()
}

/// The artifact of node `name` decoded as `T`: `None` when the build has none (the node failed or
/// the recipe has no such node), an error naming the node when it does not decode (the report
/// would otherwise quietly leave a section out).
fn decoded<T: serde::de::DeserializeOwned>(
    report: &BuildReport,
    name: &str,
) -> Result<Option<T>, Failure> {
    report
        .artifact(name)
        .map(|a| a.decode::<T>())
        .transpose()
        .map_err(|e| Failure(format!("error: report: the output of node `{name}`: {e}")))
}

/// Writes `report.html` and `report.json` into `output_dir`; returns their paths.
pub fn write_report(
    recipe: &Recipe,
    recipe_path: &Path,
    report: &BuildReport,
    output_dir: &Path,
) -> Result<Vec<PathBuf>, Failure> {
    let mesh: VolumeMesh = decoded(report, "mesh")?.unwrap_or_default();
    let model: Option<ModelData> = decoded(report, "model")?;
    let mut imported = Vec::new();
    for n in &report.nodes {
        if n.kind == "import" || n.kind == "box_side" {
            imported.extend(decoded::<SurfaceData>(report, &n.name)?);
        }
    }
    let mut surfaces: Vec<SurfaceSummary> = imported
        .into_iter()
        .map(|s| SurfaceSummary {
            name: s.name,
            kind: s.kind,
            triangles: s.mesh.triangles.len(),
            findings: s.findings as usize,
        })
        .collect();
    surfaces.sort_by(|a, b| a.name.cmp(&b.name));
    let (mut curves, mut patches, mut regions) = (Vec::new(), Vec::new(), Vec::new());
    if let Some(m) = &model {
        curves = m
            .topology
            .curves
            .iter()
            .map(|c| CurveSummary {
                name: c.name.clone(),
                surfaces: c.surfaces.clone(),
                length: polyline_length(&c.points),
                nodes: count(report, &format!("discretize:{}", c.name), "nodes"),
            })
            .collect();
        let named: Vec<(&str, &str)> = m
            .patches
            .iter()
            .map(|p| (p.name.as_str(), p.surface.as_str()))
            .collect();
        (patches, regions) = model_summaries(&named, &m.regions);
        for p in &mut patches {
            p.triangles = count(report, &format!("surface_mesh:{}", p.name), "triangles");
        }
        for r in &mut regions {
            r.tets = count(report, &format!("tet_mesh:{}", r.name), "tets");
            r.material = recipe.regions.get(&r.name).and_then(|s| s.material);
        }
    }
    let steps = report
        .nodes
        .iter()
        .map(|n| StepSummary {
            name: n.name.clone(),
            state: n.state.as_str().to_string(),
            reason: n.reason.to_string(),
            duration_ms: n.duration_ms,
        })
        .collect();
    let label = recipe_path.display().to_string();
    let input = ReportInput {
        model_name: &recipe.model.name,
        recipe_path: &label,
        surfaces,
        curves,
        patches,
        regions,
        mesh: &mesh,
        steps,
    };
    let (html, json) = render_both(&input);
    let h = output_dir.join("report.html");
    let j = output_dir.join("report.json");
    write_atomic(&h, html.as_bytes())?;
    write_atomic(&j, json.as_bytes())?;
    Ok(vec![h, j])
}
