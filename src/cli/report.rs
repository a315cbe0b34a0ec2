//! `report.html` and `report.json`: gathered after each build from the build report (what ran
//! and why), the artifacts of `model`, the imports, the wells (`well:<w>`, `well_cut:<w>`) and
//! the per-entity nodes, and the figures of the final mesh, rendered by `crate::report`, and
//! written atomically beside the outputs. They are not build outputs in the lock file: they say
//! what re-ran, which differs from build to build by design.
//!
//! The mesh's figures are a derivation of the `mesh` node's output (`plan::ops::MeshFactsOp`,
//! cached by the mesh's hash), so a build whose mesh did not change neither reads the mesh nor
//! measures it again; and a report that would differ from the one on disk only in its timings is
//! not written again (`report_state`).
//!
//! A well is reported from the recipe's list, so one whose file was not read or that was not
//! cut is still there, with what is known of it (the file; its stations and markers once read)
//! and why the rest is missing, as a failed import is reported in `validation.json`.
//!
//! `validation.json` is written here too, after every build and so also after one that failed
//! past the imports, when it is needed most: for each surface, what validation found on import,
//! what repair removed and what remains (from the import nodes' artifacts and counts), or why the
//! surface was not imported. It is not in the lock file either; the import nodes it is made from
//! are.

use super::Failure;
use super::build::write_atomic;
use super::report_state::{self, ReportState};
use crate::plan::ops::{
    MeshFactsOp, ModelData, SurfaceData, WellCutData, WellData, findings_by_kind,
};
use crate::recipe::Recipe;
use crate::report::{
    CurveSummary, Draft, MeshFacts, ReportInput, StepSummary, SurfaceSummary, WellMarkerRow,
    WellSummary, model_summaries, well_markers,
};
use engine::{BuildReport, Derivations, NodeReport, NodeState};
use geom::mesh::SurfaceKind;
use geom::mesh::VolumeMesh;
use geom::predicates::polyline_length;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// The build's nodes by name: looked up once per curve, patch and region, where a scan of the
/// list each time made the report quadratic (a surface of thousands of patches has tens of
/// thousands of nodes).
struct ByName<'r>(HashMap<&'r str, &'r NodeReport>);

impl<'r> ByName<'r> {
    fn new(report: &'r BuildReport) -> Self {
        ByName(report.nodes.iter().map(|n| (n.name.as_str(), n)).collect())
    }

    /// Count `key` of node `node`, 0 when either is missing.
    fn count(&self, node: &str, key: &str) -> usize {
        (self.0.get(node))
            .and_then(|n| n.counts.get(key))
            .map_or(0, |&c| c as usize)
    }
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

/// Why node `node` has no output, in words: its error, or that it was skipped and why.
fn why_not(node: Option<&NodeReport>, what: &str) -> String {
    match node {
        None => format!("not {what}: the build has no such step"),
        Some(n) => match (&n.error, n.state) {
            (Some(e), _) => e.clone(),
            (None, NodeState::Skipped) => format!("not {what}: {}", n.reason),
            (None, state) => format!("not {what} ({state})"),
        },
    }
}

/// The recipe's wells, in name order, from their `well:<w>` and `well_cut:<w>` nodes and the
/// mesh's line groups; `surfaces` says which crossings are of box sides.
fn well_summaries(
    recipe: &Recipe,
    report: &BuildReport,
    surfaces: &[SurfaceSummary],
    mesh: &MeshFacts,
) -> Result<Vec<WellSummary>, Failure> {
    let box_side = |name: &str| {
        surfaces
            .iter()
            .any(|s| s.name == name && s.kind == SurfaceKind::Box)
    };
    let mut wells = Vec::new();
    for (name, spec) in &recipe.wells {
        let (read, cut) = (format!("well:{name}"), format!("well_cut:{name}"));
        let data: Option<WellData> = decoded(report, &read)?;
        let cut_data: Option<WellCutData> = decoded(report, &cut)?;
        let error = match (&data, &cut_data) {
            (None, _) => Some(why_not(report.node(&read), "read")),
            (Some(_), None) => Some(why_not(report.node(&cut), "cut")),
            _ => None,
        };
        let file_markers = data.as_ref().map_or(Vec::new(), |d| {
            d.markers
                .iter()
                .map(|m| WellMarkerRow::file(&m.name, m.md, m.xyz))
                .collect()
        });
        let crossings = cut_data.as_ref().map_or(Vec::new(), |c| {
            c.markers
                .iter()
                .map(|m| WellMarkerRow::crossing(&m.surface, &m.patch, m.md, m.point))
                .collect()
        });
        let mut regions: Vec<String> = Vec::new();
        if let Some(c) = &cut_data {
            for (r, _) in &c.pieces {
                if regions.last() != Some(r) {
                    regions.push(r.clone());
                }
            }
        }
        wells.push(WellSummary {
            name: name.clone(),
            file: data
                .as_ref()
                .map_or_else(|| spec.file.display().to_string(), |d| d.file.clone()),
            stations: data.as_ref().map(|d| d.stations.len()),
            regions,
            length: cut_data.as_ref().map_or(f64::NAN, |c| {
                (c.pieces.iter().chain(&c.runs))
                    .map(|(_, p)| polyline_length(p))
                    .sum()
            }),
            edges: mesh.lines.iter().find(|l| l.name == *name).map(|l| l.edges),
            markers: well_markers(crossings, file_markers, box_side),
            error,
        });
    }
    Ok(wells)
}

/// The figures of the build's final mesh (of an empty mesh when it has none), derived from the
/// `mesh` node's output.
fn mesh_facts(
    recipe: &Recipe,
    report: &BuildReport,
    derivations: &Derivations,
) -> Result<MeshFacts, Failure> {
    let model = &recipe.model.name;
    let Some(mesh) = report.artifact("mesh") else {
        return Ok(MeshFacts::of(&VolumeMesh::default(), model));
    };
    let op = MeshFactsOp {
        model: model.clone(),
    };
    derivations
        .derive("mesh_facts", &op, std::slice::from_ref(mesh))
        .and_then(|a| a.decode())
        .map_err(|e| Failure(format!("error: report: the figures of node `mesh`: {e}")))
}

/// Where a build's report goes.
pub struct ReportPlace<'a> {
    /// Where the build writes its files: the output directory, or its staging directory.
    pub write_dir: &'a Path,
    /// Where the report ends up, which the record's state describes.
    pub output_dir: &'a Path,
    /// The recipe's record.
    pub record_dir: &'a Path,
}

/// Writes `report.html` and `report.json` into `place.write_dir`, unless the output directory
/// holds them already, timings aside (see `report_state`). Returns the report's state for the
/// record once its files are in the output directory, `None` when they were left alone.
pub fn write_report(
    recipe: &Recipe,
    recipe_path: &Path,
    report: &BuildReport,
    derivations: &Derivations,
    place: &ReportPlace,
) -> Result<Option<ReportState>, Failure> {
    let label = recipe_path.display().to_string();
    let input = report_input(recipe, &label, report, derivations)?;
    let draft = Draft::new(&input);
    let fingerprint = report_state::fingerprint(&draft);
    let recorded = ReportState::load(place.record_dir);
    if recorded.is_some_and(|s| s.fingerprint == fingerprint && s.on_disk(place.output_dir)) {
        return Ok(None);
    }
    let (html, json) = draft.finish();
    for (name, text) in report_state::FILES.iter().zip([&html, &json]) {
        write_atomic(&place.write_dir.join(name), text.as_bytes())?;
    }
    Ok(Some(ReportState::of(fingerprint, &html, &json)))
}

/// Everything the report shows of `report`'s build.
fn report_input<'a>(
    recipe: &'a Recipe,
    label: &'a str,
    report: &BuildReport,
    derivations: &Derivations,
) -> Result<ReportInput<'a>, Failure> {
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
    let mut warnings: Vec<String> = crate::plan::ops::unpaired_crossings(report)
        .iter()
        .map(|c| c.message())
        .collect();
    if let Some(m) = &model {
        let nodes = ByName::new(report);
        curves = m
            .topology
            .curves
            .iter()
            .map(|c| CurveSummary {
                name: c.name.clone(),
                surfaces: c.surfaces.clone(),
                length: polyline_length(&c.points),
                nodes: nodes.count(&format!("discretize:{}", c.name), "nodes"),
            })
            .collect();
        let named: Vec<(&str, &str)> = m
            .patches
            .iter()
            .map(|p| (p.name.as_str(), p.surface.as_str()))
            .collect();
        (patches, regions) = model_summaries(&named, &m.regions);
        warnings.extend(
            crate::plan::ops::thin_region_warnings(recipe, m)
                .into_iter()
                .map(|t| t.message),
        );
        warnings.extend(crate::plan::ops::non_conformity_warnings(m));
        warnings.extend(crate::plan::ops::vanished_surface_warnings(recipe, m));
        warnings.extend(
            crate::plan::ops::short_curve_warnings(recipe, m)
                .into_iter()
                .map(|(_, w)| w),
        );
        warnings.extend(crate::plan::ops::close_curve_warnings(recipe, m));
        for p in &mut patches {
            p.triangles = nodes.count(&format!("surface_mesh:{}", p.name), "triangles");
        }
        for r in &mut regions {
            r.tets = nodes.count(&format!("tet_mesh:{}", r.name), "tets");
            r.material = recipe.regions.get(&r.name).and_then(|s| s.material);
        }
    }
    let mesh = mesh_facts(recipe, report, derivations)?;
    if let Some(m) = &model {
        warnings.extend(crate::plan::ops::thin_at_worst(
            recipe,
            m,
            &mesh.quality.table2,
        ));
    }
    let wells = well_summaries(recipe, report, &surfaces, &mesh)?;
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
    Ok(ReportInput {
        model_name: &recipe.model.name,
        recipe_path: label,
        surfaces,
        curves,
        patches,
        regions,
        geology: model.as_ref().map(crate::plan::ops::geology_counts),
        wells,
        mesh,
        steps,
        warnings,
    })
}

/// The validation of every imported surface, by surface name: the report of what was found on
/// import (`findings`, `counts`), what repair removed (`repaired`) and what remains on the surface
/// the model gets (`remaining`), all counts by kind, and the same in one line (`summary`); for a
/// surface whose import failed or was skipped, `error` says why.
pub fn validation_json(report: &BuildReport) -> Result<String, Failure> {
    let mut surfaces = std::collections::BTreeMap::new();
    for n in report.nodes.iter().filter(|n| n.kind == "import") {
        let name = n
            .name
            .strip_prefix("import:")
            .unwrap_or(&n.name)
            .to_string();
        let Some(s) = decoded::<SurfaceData>(report, &n.name)? else {
            let why = why_not(Some(n), "imported");
            surfaces.insert(name, serde_json::json!({ "error": why }));
            continue;
        };
        let (found, remaining) = findings_by_kind(&s.report_json, &n.counts);
        let mut v: serde_json::Value =
            serde_json::from_str(&s.report_json).unwrap_or_else(|_| serde_json::json!({}));
        let all = |m: &std::collections::BTreeMap<String, u64>| {
            gocad::validate::FindingKind::ALL
                .iter()
                .map(|k| (k.name().to_string(), m.get(k.name()).copied().unwrap_or(0)))
                .collect::<std::collections::BTreeMap<_, _>>()
        };
        if let Some(o) = v.as_object_mut() {
            o.insert(
                "summary".into(),
                gocad::validate::repair_summary(&found, &remaining).into(),
            );
            o.insert(
                "repaired".into(),
                serde_json::json!(gocad::validate::repaired_counts(&found, &remaining)),
            );
            o.insert("remaining".into(), serde_json::json!(all(&remaining)));
        }
        surfaces.insert(s.name, v);
    }
    serde_json::to_string_pretty(&surfaces)
        .map_err(|e| Failure(format!("error: validation.json: {e}")))
}

/// Writes `validation.json` into `output_dir` (left alone when it already holds the same bytes);
/// returns its path.
pub fn write_validation(report: &BuildReport, output_dir: &Path) -> Result<PathBuf, Failure> {
    let path = output_dir.join("validation.json");
    let text = validation_json(report)?;
    if std::fs::read(&path).ok().as_deref() != Some(text.as_bytes()) {
        write_atomic(&path, text.as_bytes())?;
    }
    Ok(path)
}
