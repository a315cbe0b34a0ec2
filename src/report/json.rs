//! `report.json`: the report for machines. Same content as the HTML minus the pictures: model
//! summary, mesh groups, the seed's Tables 1 and 2, the histograms (fixed bins), the steps and the
//! warnings, and the wells. Keys are sorted (serde_json's map is ordered), floats are shortest
//! round-trip, and non-finite numbers (statistics of an empty group, unknown volumes) are `null`.
//!
//! `wells` is there only when the recipe has wells, so that the document of a build without
//! wells is the one it was before wells existed (its report is not written again). A well's
//! `length` is that of its path inside the model, `mesh_edges` its edges in the mesh, `error` why
//! it is known only in part (`null` for whatever is unknown). It lists its `markers` in MD order
//! as the HTML does, each with its `kind` (`crossing`: `name`
//! is the surface, `patch` the patch crossed; `file`: `name` is the file's marker, `nearest` the
//! nearest crossing of a surface other than a box side with `delta_md` = the marker's MD minus
//! the crossing's).

use super::BINS;
use super::input::{ReportInput, StepSummary, WellSummary};
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
    let mut doc = json!({
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
        "geology": input.geology,
        "mesh": {
            "regions": mesh_regions,
            "surface_groups": mesh_groups,
        },
        "ids": super::ids(mesh),
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
    if !input.wells.is_empty()
        && let Some(o) = doc.as_object_mut()
    {
        o.insert(
            "wells".into(),
            Value::Array(input.wells.iter().map(well).collect()),
        );
    }
    let mut s = serde_json::to_string_pretty(&doc).unwrap_or_else(|e| {
        // Serialising plain maps, strings and numbers cannot fail; keep a valid document anyway.
        json!({ "format": FORMAT, "error": e.to_string() }).to_string()
    });
    s.push('\n');
    s
}

fn well(w: &WellSummary) -> Value {
    let markers: Vec<Value> = w
        .markers
        .iter()
        .map(|m| {
            json!({
                "kind": m.kind,
                "name": m.name,
                "patch": m.patch,
                "md": finite(m.md),
                "xyz": m.xyz.map(finite),
                "nearest": m.nearest.as_ref().map(|n| json!({
                    "surface": n.surface,
                    "delta_md": finite(n.delta_md),
                })),
            })
        })
        .collect();
    json!({
        "name": w.name,
        "file": w.file,
        "stations": w.stations,
        "regions": w.regions,
        "length": finite(w.length),
        "mesh_edges": w.edges,
        "markers": markers,
        "error": w.error,
    })
}

/// `null` for NaN and infinities (JSON has no such numbers).
fn finite(v: f64) -> Value {
    if v.is_finite() { json!(v) } else { Value::Null }
}
