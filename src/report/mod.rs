//! Stage `report`: the build's `report.html` (self-contained: inline CSS and inline SVG, no
//! script, nothing fetched) and `report.json` (for machines), from the model summary, the final
//! tet mesh's figures and the build steps.
//!
//! What the report decides: which figures a user iterating on a recipe sees — the model summary,
//! the wells (the regions each passes through, its mesh edges, its crossings of the model's
//! surfaces interleaved with its file's markers), the seed's Tables 1 and 2 (computed by
//! `export::quality`, not re-derived), quality histograms per region and per surface, what
//! re-ran and why, the ids every region, surface, fault side, material and well has in each
//! output format (`export::ids`), and two pictures rendered here (surfaces coloured by name, with the wells
//! drawn over them; a cut-away of the tets coloured by region). A build without wells gets the
//! report it got before wells existed: no wells section, no `wells` key. Pure: no filesystem, no clock;
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

pub use facts::{FACTS_VERSION, LineFacts, MeshFacts, Pictures};
pub use histogram::{BINS, Histogram};
pub use input::{
    CurveSummary, MarkerKind, NearestCrossing, PatchSide, PatchSummary, RegionSummary, ReportInput,
    StepSummary, SurfaceSummary, WellMarkerRow, WellSummary, region_tets_and_volumes, well_markers,
};
pub use model::model_summaries;
pub use pictures::FACE_CAP;
pub use view::Picture;

/// The id table of the mesh (`export::ids`), shown by both documents: what each region, surface
/// group, fault side, material, well, named point and face set is called and numbered in every
/// format.
fn ids(mesh: &MeshFacts) -> Vec<export::ids::IdRow> {
    let wells: Vec<String> = mesh.lines.iter().map(|l| l.name.clone()).collect();
    let named = export::ids::Named {
        wells: &wells,
        points: &mesh.points,
        face_sets: &mesh.face_sets,
    };
    export::ids::table(&mesh.regions, &mesh.surface_groups, named)
}

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

#[cfg(test)]
mod tests {
    use super::*;

    fn at(z: f64) -> [f64; 3] {
        [500.0, 700.0, z]
    }

    /// A well cut by the model with a file marker near its H1 crossing, and one whose cut
    /// failed (its name and error with markup characters).
    fn wells() -> Vec<WellSummary> {
        vec![
            WellSummary {
                name: "W1".into(),
                file: "data/W1.wl".into(),
                stations: Some(68),
                regions: vec!["upper".into(), "lower".into()],
                length: 1985.0,
                edges: Some(11),
                markers: well_markers(
                    vec![
                        WellMarkerRow::crossing("box.top", "box.top#0", 25.0, at(0.0)),
                        WellMarkerRow::crossing("H1", "H1#0", 1226.4, at(-1201.4)),
                    ],
                    vec![WellMarkerRow::file("H1_pick", 1226.31, at(-1201.31))],
                    |s| s.starts_with("box."),
                ),
                error: None,
            },
            WellSummary {
                name: "W<2>".into(),
                file: "data/W&2.wl".into(),
                stations: Some(5),
                regions: Vec::new(),
                length: f64::NAN,
                edges: None,
                markers: well_markers(
                    Vec::new(),
                    vec![WellMarkerRow::file("top", 3.0, at(22.0))],
                    |_| false,
                ),
                error: Some("well `W<2>` runs along F1".into()),
            },
        ]
    }

    fn with_wells() -> ReportInput<'static> {
        ReportInput {
            model_name: "wells",
            wells: wells(),
            ..Default::default()
        }
    }

    #[test]
    fn the_model_is_counted_as_its_files_draw_it_in_both_documents() {
        let input = ReportInput {
            model_name: "drawn",
            geology: Some(crate::plan::ops::GeologyCounts {
                corners: 52,
                lines: 98,
                surfaces: 55,
                regions: 8,
            }),
            ..Default::default()
        };
        let (html, json) = render_both(&input);
        assert!(
            html.contains("As its files draw it: 52 corners, 98 lines, 55 surfaces, 8 regions."),
            "{html}"
        );
        let doc: serde_json::Value = serde_json::from_str(&json).unwrap();
        assert_eq!(doc["geology"]["lines"], 98);
        let (html, json) = render_both(&ReportInput::default());
        assert!(!html.contains("As its files draw it"));
        assert!(json.contains("\"geology\": null") || json.contains("\"geology\":null"));
    }

    #[test]
    fn the_wells_section_has_a_row_per_well_and_its_markers_in_md_order() {
        let (html, _) = render_both(&with_wells());
        assert!(html.contains("<b>2</b>wells</div>"), "a summary card");
        let section = &html[html.find("<h2>Wells (2)</h2>").expect("the section")..];
        let section = &section[..section.find("</section>").unwrap()];
        assert!(section.contains(
            "<tr><td class=\"l\">W1</td><td class=\"l\"><code>data/W1.wl</code></td><td>68</td><td class=\"l small\">upper → lower</td><td>11</td><td>1985.00</td></tr>"
        ));
        // The failed cut: what is known, why the rest is not, every name escaped.
        assert!(section.contains(
            "<tr><td class=\"l\">W&lt;2&gt;</td><td class=\"l\"><code>data/W&amp;2.wl</code></td><td>5</td><td class=\"l small\"><span class=\"st-failed\">well `W&lt;2&gt;` runs along F1</span></td><td>-</td><td>-</td></tr>"
        ));
        let w1 = &section[section.find("<h3>W1 (3 markers)</h3>").unwrap()..];
        let rows: Vec<&str> = w1.split("<tr>").skip(2).take(3).collect();
        assert!(rows[0].starts_with("<td>25.00</td><td class=\"l\">crossing</td><td class=\"l\">box.top</td><td class=\"l\">box.top#0</td><td>500.00</td><td>700.00</td><td>0.00</td><td></td>"), "{}", rows[0]);
        assert!(rows[1].starts_with("<td>1226.31</td><td class=\"l\">file</td><td class=\"l\"><b>H1_pick</b></td><td class=\"l\"></td><td>500.00</td><td>700.00</td><td>-1201.31</td><td>-0.09 (H1)</td>"), "{}", rows[1]);
        assert!(
            rows[2].starts_with(
                "<td>1226.40</td><td class=\"l\">crossing</td><td class=\"l\">H1</td>"
            )
        );
        let w2 = &section[section.find("<h3>W&lt;2&gt; (1 marker)</h3>").unwrap()..];
        assert!(w2.contains("<td class=\"l\"><b>top</b></td><td class=\"l\"></td><td>500.00</td><td>700.00</td><td>22.00</td><td>-</td>"));
    }

    #[test]
    fn a_bare_meshs_line_groups_are_its_wells() {
        let m = geom::mesh::VolumeMesh {
            nodes: vec![[0.0, 0.0, 0.0], [0.0, 0.0, -3.0], [0.0, 4.0, -3.0]],
            lines: vec![geom::mesh::LineGroup {
                area: None,
                name: "W1".into(),
                lines: vec![[0, 1], [1, 2], [2, 7]],
            }],
            ..Default::default()
        };
        let i = ReportInput::from_mesh("bare", "bare.msh", &m);
        assert_eq!(i.wells.len(), 1);
        assert_eq!((i.wells[0].edges, i.wells[0].length), (Some(2), 7.0));
        let html = render_html(&i);
        assert!(html.contains(
            "<tr><td class=\"l\">W1</td><td class=\"l\">-</td><td>-</td><td class=\"l small\">-</td><td>2</td><td>7.00</td></tr>"
        ));
    }

    #[test]
    fn a_report_without_wells_has_no_wells_section_card_or_key() {
        let (html, json) = render_both(&ReportInput::default());
        assert!(!html.contains("Wells") && !html.contains("wells</div>"));
        assert!(
            !html.contains("The wells"),
            "nor a word of them in Figure 1"
        );
        let v: serde_json::Value = serde_json::from_str(&json).unwrap();
        assert!(v.get("wells").is_none());
    }

    #[test]
    fn report_json_lists_the_wells_with_their_markers_in_md_order() {
        let (_, json) = render_both(&with_wells());
        let v: serde_json::Value = serde_json::from_str(&json).unwrap();
        let w = v["wells"].as_array().expect("wells");
        assert_eq!(w.len(), 2);
        assert_eq!(w[0]["name"], "W1");
        assert_eq!(w[0]["file"], "data/W1.wl");
        assert_eq!(w[0]["stations"], 68);
        assert_eq!(w[0]["regions"], serde_json::json!(["upper", "lower"]));
        assert_eq!(w[0]["length"], 1985.0);
        assert_eq!(w[0]["mesh_edges"], 11);
        assert_eq!(w[0]["error"], serde_json::Value::Null);
        let kinds: Vec<&str> = (w[0]["markers"].as_array().unwrap().iter())
            .map(|m| m["kind"].as_str().unwrap())
            .collect();
        assert_eq!(kinds, ["crossing", "file", "crossing"]);
        let pick = &w[0]["markers"][1];
        assert_eq!(pick["name"], "H1_pick");
        assert_eq!(pick["patch"], serde_json::Value::Null);
        assert_eq!(pick["nearest"]["surface"], "H1");
        assert!((pick["nearest"]["delta_md"].as_f64().unwrap() + 0.09).abs() < 1e-9);
        assert_eq!(w[0]["markers"][2]["patch"], "H1#0");
        assert_eq!(
            w[0]["markers"][2]["xyz"],
            serde_json::json!([500.0, 700.0, -1201.4])
        );
        // What is known of a well that was not cut; unknowns are null.
        assert_eq!(w[1]["length"], serde_json::Value::Null);
        assert_eq!(w[1]["mesh_edges"], serde_json::Value::Null);
        assert_eq!(w[1]["error"], "well `W<2>` runs along F1");
        assert_eq!(w[1]["markers"][0]["nearest"], serde_json::Value::Null);
        assert_eq!(json, render_both(&with_wells()).1, "deterministic");
    }
}
