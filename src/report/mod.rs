//! Stage `report`: the build's `report.html` (self-contained: inline CSS and inline SVG, no
//! script, nothing fetched) and `report.json` (for machines), from the model summary, the final
//! tet mesh's figures and the build steps.
//!
//! What the report decides: which figures a user iterating on a recipe sees — the model summary,
//! the seed's Tables 1 and 2 (computed by `export::quality`, not re-derived), quality histograms
//! per region and per surface, what re-ran and why, and two pictures rendered here (surfaces
//! coloured by name; a cut-away of the tets coloured by region). Pure: no filesystem, no clock;
//! the same input gives the same bytes (fixed float precision in HTML, sorted keys and shortest
//! round-trip floats in JSON, index-ordered groups). Every name is HTML-escaped.
//!
//! The mesh enters as its [`MeshFacts`], everything costly computed once from it (`facts`), so
//! that rendering is cheap and a caller may keep the facts of a mesh instead of the mesh.
//!
//! Submodules: `input` (the typed input), `facts` (the mesh's figures and pictures), `model`
//! (patch and region summaries of a region model), `flags` (regions meshed far worse than the
//! rest), `text` (escaping, number formats), `palette` (colours), `view` (projection, painter's
//! algorithm, size bound), `pictures` (the two pictures), `histogram` (bins and bar charts),
//! `html` and `json` (the two documents).

mod facts;
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

pub use facts::{FACTS_VERSION, MeshFacts, Pictures};
pub use histogram::{BINS, Histogram};
pub use input::{
    CurveSummary, PatchSide, PatchSummary, RegionSummary, ReportInput, StepSummary, SurfaceSummary,
    region_tets_and_volumes,
};
pub use model::model_summaries;
pub use pictures::FACE_CAP;
pub use view::Picture;

/// The warnings both documents show, in a fixed order: the build's own, then what the mesh's
/// figures, the surfaces and the steps have to say.
fn warnings(input: &ReportInput) -> Vec<String> {
    let mesh = &input.mesh;
    let mut warnings = input.warnings.clone();
    if let Some(e) = &mesh.inconsistent {
        warnings.push(format!(
            "the mesh is inconsistent ({e}); elements with out-of-range indices are left out"
        ));
    }
    for (r, &n) in mesh.regions.iter().zip(&mesh.region_tets) {
        if n == 0 {
            warnings.push(format!("mesh region '{}' has no tets", r.name));
        }
    }
    for r in &input.regions {
        if mesh.tets > 0 && !mesh.regions.iter().any(|m| m.name == r.name) {
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
    warnings.extend(flags::poor_regions(&mesh.quality.table2));
    warnings
}

/// A report drawn up to its timings: the page before its steps section, which is nearly all of
/// it and does not depend on the steps' durations, is rendered once; the documents are then
/// finished with the durations as measured, or with every duration zero (so that two builds
/// whose reports differ only in their timings have the same timeless documents).
pub struct Draft<'r> {
    input: &'r ReportInput<'r>,
    warnings: Vec<String>,
    body: String,
}

impl<'r> Draft<'r> {
    pub fn new(input: &'r ReportInput<'r>) -> Draft<'r> {
        let warnings = warnings(input);
        let body = html::body(input, &warnings);
        Draft {
            input,
            warnings,
            body,
        }
    }

    fn with_steps(&self, steps: &[StepSummary]) -> (String, String) {
        (
            html::finish(self.body.clone(), steps),
            json::render(self.input, &self.warnings, steps),
        )
    }

    /// Both documents, `(html, json)`.
    pub fn finish(&self) -> (String, String) {
        self.with_steps(&self.input.steps)
    }

    /// Both documents with every step's duration zero.
    pub fn timeless(&self) -> (String, String) {
        let steps: Vec<StepSummary> = self
            .input
            .steps
            .iter()
            .map(|s| StepSummary {
                duration_ms: 0.0,
                ..s.clone()
            })
            .collect();
        self.with_steps(&steps)
    }
}

/// `report.html`: self-contained (inline CSS and SVG, no scripts, no external resources).
pub fn render_html(input: &ReportInput) -> String {
    render_both(input).0
}

/// `report.json`: pretty, sorted keys, deterministic.
pub fn render_json(input: &ReportInput) -> String {
    json::render(input, &warnings(input), &input.steps)
}

/// Both documents: `(html, json)`.
pub fn render_both(input: &ReportInput) -> (String, String) {
    Draft::new(input).finish()
}
