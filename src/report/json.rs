//! `report.json`: the report for machines. Same content as the HTML minus the pictures: model
//! summary, mesh groups, the seed's Tables 1 and 2, the histograms (fixed bins), the steps and the
//! warnings. Keys are sorted (serde_json's map is ordered), floats are shortest round-trip, and
//! non-finite numbers (statistics of an empty group, unknown volumes) are `null`.

use super::BINS;
use super::input::{ReportInput, StepSummary};
use serde_json::{Value, json};
use std::collections::BTreeMap;

/// Version of the document's layout; bumped when a key changes meaning.
pub const FORMAT: &str = "georecipe-report/1";

/// The document of `input` with `steps` (the input's, or the same with other durations).
pub fn render(input: &ReportInput, warnings: &[String], steps: &[StepSummary]) -> String {
    let mesh = &input.mesh;
    let mut states: BTreeMap<&str, usize> = BTreeMap::new();
    for s in steps {
        *states.entry(s.state.as_str()).or_default() += 1;
    }
    let mesh_regions: Vec<Value> = mesh
        .regions
        .iter()
        .enumerate()
        .map(|(i, r)| {
            json!({
                "name": r.name,
                "material": r.material,
                "properties": r.properties,
                "tets": mesh.region_tets.get(i).copied().unwrap_or(0),
                "volume": finite(mesh.region_volume.get(i).copied().unwrap_or(f64::NAN)),
            })
        })
        .collect();
    let mesh_groups: Vec<Value> = mesh
        .surface_groups
        .iter()
        .enumerate()
        .map(|(i, g)| {
            json!({
                "name": g.name,
                "kind": g.kind,
                "triangles": mesh.group_triangles.get(i).copied().unwrap_or(0),
            })
        })
        .collect();
    let regions: Vec<Value> = input
        .regions
        .iter()
        .map(|r| {
            json!({
                "name": r.name,
                "material": r.material,
                "patches": r.patches,
                "tets": r.tets,
                "volume": finite(r.volume),
            })
        })
        .collect();
    let curves: Vec<Value> = input
        .curves
        .iter()
        .map(|c| {
            json!({
                "name": c.name,
                "surfaces": c.surfaces,
                "length": finite(c.length),
                "nodes": c.nodes,
            })
        })
        .collect();
    let steps: Vec<Value> = steps
        .iter()
        .map(|s| {
            json!({
                "name": s.name,
                "state": s.state,
                "reason": s.reason,
                "duration_ms": finite(s.duration_ms),
            })
        })
        .collect();
    let doc = json!({
        "format": FORMAT,
        "model": input.model_name,
        "recipe": input.recipe_path,
        "counts": {
            "surfaces": input.surfaces.len(),
            "curves": input.curves.len(),
            "patches": input.patches.len(),
            "regions": input.regions.len(),
            "nodes": mesh.nodes,
            "tets": mesh.tets,
            "triangles": mesh.triangles,
        },
        "surfaces": input.surfaces,
        "curves": curves,
        "patches": input.patches,
        "regions": regions,
        "mesh": {
            "regions": mesh_regions,
            "surface_groups": mesh_groups,
        },
        "quality": {
            "table1": mesh.quality.table1,
            "table2": mesh.quality.table2,
            "mean_ratio_scale_of_the_seed": export::quality::PAPER_MEAN_RATIO_SCALE,
        },
        "histograms": {
            "bins": BINS,
            "mean_ratio": mesh.mean_ratio,
            "c_ratio": mesh.c_ratio,
        },
        "steps": steps,
        "steps_by_state": states,
        "warnings": warnings,
    });
    let mut s = serde_json::to_string_pretty(&doc).unwrap_or_else(|e| {
        // Serialising plain maps, strings and numbers cannot fail; keep a valid document anyway.
        json!({ "format": FORMAT, "error": e.to_string() }).to_string()
    });
    s.push('\n');
    s
}

/// `null` for NaN and infinities (JSON has no such numbers).
fn finite(v: f64) -> Value {
    if v.is_finite() { json!(v) } else { Value::Null }
}
