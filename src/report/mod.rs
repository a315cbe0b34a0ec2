//! Stage `report`: the build's `report.html` (self-contained: inline CSS and inline SVG, no
//! script, nothing fetched) and `report.json` (for machines), from the model summary, the final
//! tet mesh and the build steps.
//!
//! What the report decides: which figures a user iterating on a recipe sees — the model summary,
//! the seed's Tables 1 and 2 (computed by `export::quality`, not re-derived), quality histograms
//! per region and per surface, what re-ran and why, and two pictures rendered here (surfaces
//! coloured by name; a cut-away of the tets coloured by region). Pure: no filesystem, no clock;
//! the same input gives the same bytes (fixed float precision in HTML, sorted keys and shortest
//! round-trip floats in JSON, index-ordered groups). Every name is HTML-escaped.
//!
//! Submodules: `input` (the typed input), `model` (patch and region summaries of a region
//! model), `flags` (regions meshed far worse than the rest), `text` (escaping, number formats),
//! `palette` (colours), `view` (projection, painter's algorithm, size bound), `pictures` (the two
//! pictures), `histogram` (bins and bar charts), `html` and `json` (the two documents).

mod flags;
mod histogram;
mod html;
mod input;
mod json;
mod model;
mod palette;
mod pictures;
mod text;
mod view;

pub use histogram::{BINS, Histogram};
pub use input::{
    CurveSummary, PatchSide, PatchSummary, RegionSummary, ReportInput, StepSummary, SurfaceSummary,
    region_tets_and_volumes,
};
pub use model::model_summaries;
pub use pictures::FACE_CAP;

use export::quality::{self, QualityReport};

/// Everything computed from the mesh that both documents show, computed once.
#[derive(Clone, Debug, PartialEq)]
pub struct Facts {
    /// The seed's Tables 1 and 2 (`export::quality::report`).
    pub quality: QualityReport,
    /// Mean ratio per mesh region (index order).
    pub mean_ratio: Vec<Histogram>,
    /// `c/c*` per mesh surface group (index order).
    pub c_ratio: Vec<Histogram>,
    /// Tets and summed tet volume per mesh region (index order).
    pub region_tets: Vec<usize>,
    pub region_volume: Vec<f64>,
    /// Triangles per mesh surface group (index order).
    pub group_triangles: Vec<usize>,
    /// Things the reader should know (the build's own warnings, invalid indices, empty regions,
    /// failed steps), in a fixed order.
    pub warnings: Vec<String>,
}

/// Computes the mesh figures of a report.
pub fn facts(input: &ReportInput) -> Facts {
    let mesh = input.mesh;
    let (region_tets, region_volume) = region_tets_and_volumes(mesh);
    let mut group_triangles = vec![0usize; mesh.surface_groups.len()];
    for &g in &mesh.triangle_group {
        if let Some(c) = group_triangles.get_mut(g as usize) {
            *c += 1;
        }
    }
    let mut warnings = input.warnings.clone();
    if let Err(e) = mesh.check_indices() {
        warnings.push(format!(
            "the mesh is inconsistent ({e}); elements with out-of-range indices are left out"
        ));
    }
    for (r, &n) in mesh.regions.iter().zip(&region_tets) {
        if n == 0 {
            warnings.push(format!("mesh region '{}' has no tets", r.name));
        }
    }
    for r in &input.regions {
        if !mesh.tets.is_empty() && !mesh.regions.iter().any(|m| m.name == r.name) {
            warnings.push(format!("model region '{}' is not in the mesh", r.name));
        }
    }
    for s in &input.surfaces {
        if s.findings > 0 {
            warnings.push(format!(
                "surface '{}' has {} validation finding{}",
                s.name,
                s.findings,
                if s.findings == 1 { "" } else { "s" }
            ));
        }
    }
    for s in &input.steps {
        if s.state == "failed" {
            warnings.push(format!("step '{}' failed: {}", s.name, s.reason));
        }
    }
    let quality = quality::report(mesh);
    warnings.extend(flags::poor_regions(&quality.table2));
    Facts {
        quality,
        mean_ratio: histogram::mean_ratio(mesh),
        c_ratio: histogram::c_ratio(mesh),
        region_tets,
        region_volume,
        group_triangles,
        warnings,
    }
}

/// `report.html`: self-contained (inline CSS and SVG, no scripts, no external resources).
pub fn render_html(input: &ReportInput) -> String {
    html::render(input, &facts(input))
}

/// `report.json`: pretty, sorted keys, deterministic.
pub fn render_json(input: &ReportInput) -> String {
    json::render(input, &facts(input))
}

/// Both documents, computing the mesh figures once: `(html, json)`.
pub fn render_both(input: &ReportInput) -> (String, String) {
    let f = facts(input);
    (html::render(input, &f), json::render(input, &f))
}
