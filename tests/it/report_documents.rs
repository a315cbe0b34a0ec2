//! `report.html` and `report.json` on a small hand-made mesh: two unit cubes of six tets each
//! (regions "upper" and "lower"), a third region with no tets, and tagged surface triangles
//! (box sides, a horizon between the cubes, a name with markup characters).

use geom::mesh::{RegionGroup, SurfaceGroup, SurfaceKind, VolumeMesh};
use georecipe::report::{
    CurveSummary, MeshFacts, PatchSide, PatchSummary, RegionSummary, ReportInput, StepSummary,
    SurfaceSummary, render_both, render_html, render_json,
};
use model::regions::Side;

const MARKUP: &str = "F<1>&\"x\"";

/// Nodes of a 2×1×1 grid of unit cubes stacked along z; 6 Kuhn tets per cube.
fn mesh() -> VolumeMesh {
    let mut m = VolumeMesh::default();
    for k in 0..3 {
        for j in 0..2 {
            for i in 0..2 {
                m.nodes
                    .push([i as f64 * 100.0, j as f64 * 100.0, -(k as f64) * 100.0]);
            }
        }
    }
    let id = |i: usize, j: usize, k: usize| (k * 4 + j * 2 + i) as u32;
    for (region, k0) in [(0u32, 0usize), (1, 1)] {
        let c = |b: usize| id(b & 1, (b >> 1) & 1, k0 + ((b >> 2) & 1));
        for p in [[1, 3], [3, 2], [2, 6], [6, 4], [4, 5], [5, 1]] {
            m.tets.push([c(0), c(p[0]), c(p[1]), c(7)]);
            m.tet_region.push(region);
        }
    }
    for (name, material) in [("upper", Some(1)), ("lower", Some(2)), ("empty", None)] {
        m.regions.push(RegionGroup {
            name: name.into(),
            material,
            properties: Default::default(),
        });
    }
    for (name, kind) in [
        ("box.top", SurfaceKind::Box),
        ("H1", SurfaceKind::Horizon),
        (MARKUP, SurfaceKind::Fault),
    ] {
        m.surface_groups.push(SurfaceGroup {
            name: name.into(),
            kind,
        });
    }
    // Top face (z = 0), the horizon between the cubes (z = -100), one vertical fault triangle.
    let quad = |k: usize| {
        [
            [id(0, 0, k), id(1, 0, k), id(1, 1, k)],
            [id(0, 0, k), id(1, 1, k), id(0, 1, k)],
        ]
    };
    for t in quad(0) {
        m.triangles.push(t);
        m.triangle_group.push(0);
    }
    for t in quad(1) {
        m.triangles.push(t);
        m.triangle_group.push(1);
    }
    m.triangles.push([id(0, 0, 0), id(1, 0, 0), id(1, 0, 1)]);
    m.triangle_group.push(2);
    m
}

fn input(m: &VolumeMesh) -> ReportInput<'static> {
    ReportInput {
        model_name: "two <cubes>",
        recipe_path: "recipes/two&cubes.toml",
        surfaces: vec![
            SurfaceSummary {
                name: "H1".into(),
                kind: SurfaceKind::Horizon,
                triangles: 8,
                findings: 0,
            },
            SurfaceSummary {
                name: MARKUP.into(),
                kind: SurfaceKind::Fault,
                triangles: 3,
                findings: 2,
            },
        ],
        curves: vec![CurveSummary {
            name: format!("{MARKUP}/H1"),
            surfaces: vec![MARKUP.into(), "H1".into()],
            length: 100.0,
            nodes: 3,
        }],
        patches: vec![
            PatchSummary {
                name: "H1#0".into(),
                surface: "H1".into(),
                triangles: 2,
                dangling: false,
            },
            PatchSummary {
                name: format!("{MARKUP}#0"),
                surface: MARKUP.into(),
                triangles: 1,
                dangling: true,
            },
        ],
        regions: vec![
            RegionSummary {
                name: "upper".into(),
                material: Some(1),
                patches: vec![PatchSide {
                    patch: "H1#0".into(),
                    side: Side::Front,
                }],
                tets: 6,
                volume: 1e6,
            },
            RegionSummary {
                name: "lower".into(),
                material: Some(2),
                patches: vec![PatchSide {
                    patch: "H1#0".into(),
                    side: Side::Back,
                }],
                tets: 6,
                volume: 1e6,
            },
        ],
        geology: None,
        wells: Vec::new(),
        mesh: MeshFacts::of(m, "two <cubes>"),
        steps: vec![
            StepSummary {
                name: "import:H1".into(),
                state: "cached".into(),
                reason: "up to date".into(),
                duration_ms: 0.0,
            },
            StepSummary {
                name: "tet_mesh:upper".into(),
                state: "ran".into(),
                reason: "parameter mesh.size changed".into(),
                duration_ms: 12.5,
            },
        ],
        warnings: vec!["region `upper` is about 1.00 thick but meshed at 2.00".into()],
    }
}

/// Checks that every element opened is closed in order (void and self-closing ones aside).
fn assert_balanced(html: &str) {
    let mut stack: Vec<String> = Vec::new();
    let mut rest = html;
    while let Some(start) = rest.find('<') {
        let end = rest[start..].find('>').expect("an unclosed tag") + start;
        let tag = &rest[start + 1..end];
        rest = &rest[end + 1..];
        if tag.starts_with('!') || tag.ends_with('/') {
            continue;
        }
        let name: String = tag
            .trim_start_matches('/')
            .chars()
            .take_while(|c| c.is_ascii_alphanumeric())
            .collect();
        if name == "meta" {
            continue;
        }
        if tag.starts_with('/') {
            let open = stack
                .pop()
                .unwrap_or_else(|| panic!("</{name}> closes nothing"));
            assert_eq!(open, name, "</{name}> closes <{open}>");
        } else {
            stack.push(name);
        }
    }
    assert!(stack.is_empty(), "unclosed: {stack:?}");
}

#[test]
fn the_html_names_every_region_and_surface_and_has_both_seed_tables() {
    let m = mesh();
    let html = render_html(&input(&m));
    for name in ["upper", "lower", "empty", "box.top", "H1", "H1#0"] {
        assert!(html.contains(name), "{name} missing");
    }
    assert!(html.contains("Table 1: surface triangles"));
    assert!(html.contains("Table 2: tetrahedra"));
    for col in ["% &gt; 1.15", "% &lt; 0.1", "min dihedral", "SD"] {
        assert!(html.contains(col), "column {col} missing");
    }
    // Figures, legends, histograms (2 pictures + 3 region + 3 surface charts).
    assert_eq!(html.matches("<svg").count(), 8);
    assert_eq!(html.matches("</svg>").count(), 8);
    assert!(html.contains("Figure 1.") && html.contains("Figure 2."));
    assert!(html.contains("<path class=\"r"), "the cut-away draws faces");
    assert!(
        html.contains("<path class=\"s"),
        "the model picture draws triangles"
    );
    assert!(html.contains("What re-ran and why"));
    assert!(html.contains("parameter mesh.size changed"));
    assert!(html.contains("2 steps: 1 ran, 1 cached."));
    assert!(html.contains("<details><summary>1 cached steps</summary>"));
    assert_balanced(&html);
}

#[test]
fn the_html_is_self_contained() {
    let m = mesh();
    let html = render_html(&input(&m));
    assert!(html.starts_with("<!DOCTYPE html>"));
    assert!(!html.contains("<script"));
    assert!(!html.contains(" src="));
    assert!(!html.contains("<link"));
    assert!(!html.contains("@import"));
    let links = html.matches("http").count();
    let svg_ns = html.matches("xmlns=\"http://www.w3.org/2000/svg\"").count();
    assert_eq!(links, svg_ns, "the only URLs are SVG namespaces");
}

#[test]
fn names_with_markup_characters_are_escaped() {
    let m = mesh();
    let html = render_html(&input(&m));
    assert!(!html.contains(MARKUP));
    assert!(!html.contains("two <cubes>"));
    assert!(html.contains("F&lt;1&gt;&amp;&quot;x&quot;"));
    assert!(html.contains("two &lt;cubes&gt;"));
    assert!(html.contains("recipes/two&amp;cubes.toml"));
}

#[test]
fn the_json_parses_and_counts_what_the_input_has() {
    let m = mesh();
    let json = render_json(&input(&m));
    let v: serde_json::Value = serde_json::from_str(&json).expect("valid JSON");
    assert_eq!(v["model"], "two <cubes>");
    assert_eq!(v["counts"]["tets"], 12);
    assert_eq!(v["counts"]["nodes"], 12);
    assert_eq!(v["counts"]["triangles"], 5);
    assert_eq!(v["surfaces"].as_array().unwrap().len(), 2);
    assert_eq!(v["curves"][0]["surfaces"][0], MARKUP);
    assert_eq!(v["patches"][1]["dangling"], true);
    assert_eq!(v["regions"][1]["patches"][0]["side"], "Back");
    // Table 2: three regions and "all"; the empty region keeps its row with null statistics.
    let t2 = v["quality"]["table2"].as_array().unwrap();
    assert_eq!(t2.len(), 4);
    assert_eq!(t2[0]["elements"], 6);
    assert_eq!(t2[2]["elements"], 0);
    assert!(t2[2]["avg"].is_null());
    assert_eq!(t2[3]["name"], "all");
    assert_eq!(v["quality"]["table1"].as_array().unwrap().len(), 4);
    // Histograms: every tet of a region is in its bins.
    let mr = v["histograms"]["mean_ratio"].as_array().unwrap();
    let total: u64 = mr[0]["counts"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c.as_u64().unwrap())
        .sum();
    assert_eq!(total, 6);
    assert_eq!(v["mesh"]["regions"][0]["tets"], 6);
    let vol = v["mesh"]["regions"][0]["volume"].as_f64().unwrap();
    assert!(
        (vol - 1e6).abs() < 1e-6,
        "six Kuhn tets fill the cube: {vol}"
    );
    assert_eq!(v["steps_by_state"]["ran"], 1);
    let warnings: Vec<&str> = v["warnings"]
        .as_array()
        .unwrap()
        .iter()
        .map(|w| w.as_str().unwrap())
        .collect();
    assert!(warnings.iter().any(|w| w.contains("'empty' has no tets")));
    assert!(warnings.iter().any(|w| w.contains("2 validation findings")));
    assert!(
        warnings[0].contains("region `upper` is about 1.00 thick"),
        "the build's own warnings come first: {warnings:?}"
    );
}

#[test]
fn two_renderings_of_the_same_input_are_byte_identical() {
    let m = mesh();
    let (h1, j1) = render_both(&input(&m));
    let m2 = mesh();
    assert_eq!(h1, render_html(&input(&m2)));
    assert_eq!(j1, render_json(&input(&m2)));
}

#[test]
fn the_json_keys_are_sorted() {
    let m = mesh();
    let json = render_json(&input(&m));
    let top: Vec<&str> = json
        .lines()
        .filter(|l| l.starts_with("  \""))
        .map(|l| l.trim().split('"').nth(1).unwrap())
        .collect();
    let mut sorted = top.clone();
    sorted.sort();
    assert_eq!(top, sorted);
}

#[test]
fn an_inconsistent_or_empty_mesh_renders_with_a_warning_instead_of_panicking() {
    let mut m = mesh();
    m.tets.push([0, 1, 2, 4000]);
    m.tet_region.push(0);
    m.tets.push([0, 1, 2, 3]);
    m.tet_region.push(9);
    m.triangles.push([0, 1, 9999]);
    m.triangle_group.push(0);
    m.triangles.push([0, 1, 2]);
    m.triangle_group.push(42);
    m.nodes[5] = [f64::NAN, 0.0, 0.0];
    let (html, json) = render_both(&input(&m));
    assert!(html.contains("the mesh is inconsistent"));
    assert_balanced(&html);
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    assert_eq!(v["counts"]["tets"], 14);

    let empty = VolumeMesh::default();
    let i = ReportInput::from_mesh("nothing", "none.toml", &empty);
    let (html, json) = render_both(&i);
    assert_balanced(&html);
    assert!(html.contains("No build steps were recorded."));
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    assert_eq!(v["counts"]["tets"], 0);
}

#[test]
fn a_report_of_a_bare_mesh_lists_its_groups_as_surfaces_and_regions() {
    let m = mesh();
    let i = ReportInput::from_mesh("bare", "bare.toml", &m);
    assert_eq!(i.surfaces.len(), 3);
    assert_eq!(i.surfaces[1].triangles, 2);
    assert_eq!(i.regions.len(), 3);
    assert_eq!((i.regions[0].tets, i.regions[2].tets), (6, 0));
    assert!((i.regions[1].volume - 1e6).abs() < 1e-6);
    let html = render_html(&i);
    assert!(html.contains("empty"));
}

#[test]
fn a_default_input_with_only_a_mesh_renders() {
    let m = mesh();
    let i = ReportInput {
        model_name: "partial",
        mesh: MeshFacts::of(&m, "partial"),
        ..Default::default()
    };
    let (html, json) = render_both(&i);
    assert_balanced(&html);
    assert!(html.contains("upper") && html.contains("Table 2:"));
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    assert_eq!(v["counts"]["tets"], 12);
    assert_eq!(
        v["counts"]["regions"], 0,
        "model regions come from the summaries"
    );
    assert_eq!(v["mesh"]["regions"].as_array().unwrap().len(), 3);
}

#[test]
fn the_html_ids_table_numbers_every_region_and_surface_group_as_the_outputs_do() {
    let m = mesh();
    let html = render_html(&input(&m));
    let table = html
        .split("<h2>Ids in the output files</h2>")
        .nth(1)
        .expect("an ids section");
    let table = &table[..table.find("</table>").unwrap()];
    for (r, g) in m.regions.iter().enumerate() {
        let row = format!(
            "<td class=\"l\">{}</td><td class=\"l\">3D group {}</td>",
            g.name,
            r + 1
        );
        assert!(table.contains(&row), "{row} not in {table}");
    }
    for (i, g) in m.surface_groups.iter().enumerate() {
        let name = georecipe_esc(&g.name);
        let row = format!(
            "<td class=\"l\">{name}</td><td class=\"l\">2D group {}</td>",
            i + 1
        );
        assert!(table.contains(&row), "{row} not in {table}");
    }
}

/// `s` HTML-escaped as the report escapes names.
fn georecipe_esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}
