//! `report.html`: one self-contained page (inline CSS and SVG; no script, font, image or style
//! fetched from anywhere) in a fixed section order: summary, warnings, pictures, model tables,
//! wells (only when the recipe has any), the seed's Tables 1 and 2, histograms, build steps.
//! Every name goes through `esc`; every number has a fixed precision, so the page is a pure
//! function of its input.

use super::histogram::{self, Histogram};
use super::input::{MarkerKind, ReportInput, StepSummary, WellSummary};
use super::palette::{self, Rgb};
use super::pictures::FACE_CAP;
use super::text::{count, esc, num};
use super::view::Picture;
use export::quality::layout::{self, Cell, Table};
use export::quality::{TetQuality, TriQuality};
use geom::mesh::SurfaceKind;
use model::regions::Side;
use std::fmt::Write as _;

const CSS: &str = "body{font:14px/1.45 system-ui,-apple-system,'Segoe UI',sans-serif;color:#222;margin:0 auto;max-width:1100px;padding:16px 24px}\
h1{font-size:24px;margin:8px 0 2px}h2{font-size:19px;border-bottom:1px solid #ccc;padding-bottom:3px;margin-top:30px}h3{font-size:15px;margin:18px 0 6px}\
.sub{color:#666;margin:0 0 12px}.cards{display:flex;flex-wrap:wrap;gap:8px}.card{border:1px solid #ddd;border-radius:6px;padding:6px 12px;min-width:80px}\
.card b{display:block;font-size:20px}.warn{background:#fff4e5;border:1px solid #f0b060;border-radius:6px;padding:6px 14px}\
table{border-collapse:collapse;margin:6px 0 10px;font-size:13px}th,td{border-bottom:1px solid #e4e4e4;padding:3px 8px;text-align:right;vertical-align:top}\
th{background:#f4f4f4;font-weight:600}td.l,th.l{text-align:left}tr.all td{font-weight:600;border-top:1px solid #999}\
.sw{display:inline-block;width:11px;height:11px;border:1px solid #0003;margin-right:5px;vertical-align:-1px}\
figure{margin:12px 0 22px}figcaption{color:#555;font-size:13px;max-width:960px}svg{max-width:100%;height:auto}\
.legend{display:flex;flex-wrap:wrap;gap:4px 14px;margin:4px 0;font-size:13px}.grid{display:flex;flex-wrap:wrap;gap:10px}\
.small{font-size:12px;color:#444}.st-ran{color:#b35c00}.st-failed{color:#c00;font-weight:600}.st-skipped{color:#888}\
details{margin:6px 0}summary{cursor:pointer}";

/// The page up to its steps section, which alone quotes the steps' durations.
pub fn body(input: &ReportInput, warnings: &[String]) -> String {
    let mut h = String::with_capacity(1 << 16);
    let title = esc(input.model_name);
    let _ = write!(
        h,
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><meta name=\"viewport\" content=\"width=device-width,initial-scale=1\"><title>{title} — georecipe report</title><style>{CSS}</style></head><body>\n"
    );
    let _ = writeln!(
        h,
        "<h1>{title}</h1><p class=\"sub\">Recipe <code>{}</code> · georecipe {}</p>",
        esc(input.recipe_path),
        env!("CARGO_PKG_VERSION")
    );
    summary(&mut h, input);
    if !warnings.is_empty() {
        h.push_str("<div class=\"warn\"><b>Warnings</b><ul>");
        for w in warnings {
            let _ = write!(h, "<li>{}</li>", esc(w));
        }
        h.push_str("</ul></div>\n");
    }
    pictures_section(&mut h, input);
    model_tables(&mut h, input);
    wells_section(&mut h, input);
    ids_section(&mut h, input);
    let q = &input.mesh.quality;
    quality_tables(&mut h, &q.table1, &q.table2);
    histograms(&mut h, input);
    h
}

/// The page: `body` (see [`body`]), the steps section of `steps` and the end.
pub fn finish(mut h: String, steps: &[StepSummary]) -> String {
    steps_section(&mut h, steps);
    h.push_str("</body></html>\n");
    h
}

fn card(h: &mut String, n: usize, what: &str) {
    let _ = write!(h, "<div class=\"card\"><b>{}</b>{what}</div>", count(n));
}

fn summary(h: &mut String, input: &ReportInput) {
    let m = &input.mesh;
    h.push_str("<section><div class=\"cards\">");
    card(h, input.surfaces.len(), "surfaces");
    card(h, input.curves.len(), "curves");
    card(h, input.patches.len(), "patches");
    card(h, input.regions.len(), "regions");
    if !input.wells.is_empty() {
        card(h, input.wells.len(), "wells");
    }
    card(h, m.nodes, "mesh nodes");
    card(h, m.triangles, "surface triangles");
    card(h, m.tets, "tetrahedra");
    let ran = input
        .steps
        .iter()
        .filter(|s| s.state == "ran" || s.state == "failed")
        .count();
    if !input.steps.is_empty() {
        card(h, ran, &format!("of {} steps re-ran", input.steps.len()));
    }
    h.push_str("</div></section>\n");
}

fn legend(h: &mut String, items: impl Iterator<Item = (String, Rgb)>) {
    h.push_str("<div class=\"legend\">");
    for (name, c) in items {
        let _ = write!(
            h,
            "<span><span class=\"sw\" style=\"background:{}\"></span>{}</span>",
            c.hex(),
            esc(&name)
        );
    }
    h.push_str("</div>");
}

fn bound_note(p: &Picture) -> String {
    if p.cell > 0.0 {
        format!(
            " Size bound: {} of {} visible faces drawn — at most {} faces per picture, so the corners are snapped to a grid of {}-unit squares: faces that collapse, and faces with the same snapped corners as a nearer one, are left out (the others cover them without gaps).",
            count(p.drawn),
            count(p.visible),
            count(FACE_CAP),
            num(p.cell, 1)
        )
    } else {
        format!(
            " All {} faces drawn (the bound, {} faces per picture, was not reached).",
            count(p.drawn),
            count(FACE_CAP)
        )
    }
}

fn pictures_section(h: &mut String, input: &ReportInput) {
    let m = &input.mesh;
    h.push_str("<section><h2>Pictures</h2>");
    let p1 = &m.pictures.model;
    h.push_str("<figure>");
    h.push_str(&p1.svg);
    legend(
        h,
        m.surface_groups
            .iter()
            .map(|g| (g.name.clone(), palette::surface(&g.name, g.kind))),
    );
    let wells = if m.lines.is_empty() {
        ""
    } else {
        " The wells (the mesh's line groups) are the dark lines, named at their heads, drawn over the surfaces whatever lies in front of them."
    };
    let _ = writeln!(
        h,
        "<figcaption>Figure 1. The model's surface triangles seen from the south-west, 30° above the horizon (parallel projection, far triangles painted first), coloured by surface name; box sides in grey, only where the model's centre lies between them and the viewer.{wells}{}</figcaption></figure>",
        bound_note(p1)
    );
    let (p2, kept) = (&m.pictures.cutaway, m.pictures.kept);
    h.push_str("<figure>");
    h.push_str(&p2.svg);
    legend(
        h,
        m.regions
            .iter()
            .enumerate()
            .map(|(i, r)| (r.name.clone(), palette::region(i))),
    );
    let _ = writeln!(
        h,
        "<figcaption>Figure 2. The tetrahedra coloured by region, same view, cut by the vertical plane through the centre of the mesh's box facing the viewer: the {} of {} tets whose centroid lies behind it are kept, and their faces that no other kept tet shares and that face the viewer are drawn.{}</figcaption></figure>",
        count(kept),
        count(m.tets),
        bound_note(p2)
    );
    h.push_str("</section>\n");
}

fn side(s: Side) -> &'static str {
    match s {
        Side::Front => "front",
        Side::Back => "back",
    }
}

fn kind(k: SurfaceKind) -> &'static str {
    match k {
        SurfaceKind::Horizon => "horizon",
        SurfaceKind::Fault => "fault",
        SurfaceKind::Box => "box",
        SurfaceKind::Other => "other",
    }
}

fn model_tables(h: &mut String, input: &ReportInput) {
    let m = &input.mesh;
    h.push_str("<section><h2>Model</h2>");
    if let Some(g) = &input.geology {
        let _ = write!(
            h,
            "<p>As its files draw it: {} corners, {} lines, {} surfaces, {} regions. The mesher cuts surfaces at creases and chart seams, and curves where those end and at kinks: its {} curves and {} patches are listed below.</p>",
            count(g.corners),
            count(g.lines),
            count(g.surfaces),
            count(g.regions),
            count(input.curves.len()),
            count(input.patches.len())
        );
    }
    // Surfaces, with their FE triangles when the mesh has a group of that name.
    let _ = write!(h, "<h3>Surfaces ({})</h3>", input.surfaces.len());
    h.push_str("<table><tr><th class=\"l\">surface</th><th class=\"l\">kind</th><th>imported triangles</th><th>findings</th><th>FE triangles</th></tr>");
    for s in &input.surfaces {
        let fe = m
            .surface_groups
            .iter()
            .position(|g| g.name == s.name)
            .and_then(|i| m.group_triangles.get(i))
            .map_or("-".to_string(), |&n| count(n));
        let _ = write!(
            h,
            "<tr><td class=\"l\"><span class=\"sw\" style=\"background:{}\"></span>{}</td><td class=\"l\">{}</td><td>{}</td><td>{}</td><td>{fe}</td></tr>",
            palette::surface(&s.name, s.kind).hex(),
            esc(&s.name),
            kind(s.kind),
            count(s.triangles),
            count(s.findings)
        );
    }
    h.push_str("</table>");
    let _ = write!(h, "<h3>Curves ({})</h3>", input.curves.len());
    if !input.curves.is_empty() {
        h.push_str("<table><tr><th class=\"l\">curve</th><th class=\"l\">surfaces</th><th>length</th><th>FE nodes</th></tr>");
        for c in &input.curves {
            let surfaces: Vec<String> = c.surfaces.iter().map(|s| esc(s)).collect();
            let _ = write!(
                h,
                "<tr><td class=\"l\">{}</td><td class=\"l\">{}</td><td>{}</td><td>{}</td></tr>",
                esc(&c.name),
                surfaces.join(", "),
                num(c.length, 2),
                count(c.nodes)
            );
        }
        h.push_str("</table>");
    }
    let _ = write!(h, "<h3>Patches ({})</h3>", input.patches.len());
    if !input.patches.is_empty() {
        h.push_str("<table><tr><th class=\"l\">patch</th><th class=\"l\">surface</th><th>FE triangles</th><th class=\"l\">dangling</th></tr>");
        for p in &input.patches {
            let _ = write!(
                h,
                "<tr><td class=\"l\">{}</td><td class=\"l\">{}</td><td>{}</td><td class=\"l\">{}</td></tr>",
                esc(&p.name),
                esc(&p.surface),
                count(p.triangles),
                if p.dangling { "yes" } else { "" }
            );
        }
        h.push_str("</table>");
    }
    let _ = write!(h, "<h3>Regions ({})</h3>", input.regions.len());
    h.push_str("<table><tr><th class=\"l\">region</th><th>material</th><th>tets</th><th>volume (model)</th><th>volume (mesh)</th><th class=\"l\">bounded by (patch side)</th></tr>");
    for r in &input.regions {
        let at = m.regions.iter().position(|g| g.name == r.name);
        let colour = at.map_or(Rgb(255, 255, 255), palette::region);
        let mesh_vol = at
            .and_then(|i| m.region_volume.get(i))
            .copied()
            .unwrap_or(f64::NAN);
        // The mesh's count when the mesh has the region, else the summary's.
        let tets = at
            .and_then(|i| m.region_tets.get(i))
            .copied()
            .unwrap_or(r.tets);
        let sides: Vec<String> = r
            .patches
            .iter()
            .map(|p| format!("{} ({})", esc(&p.patch), side(p.side)))
            .collect();
        let _ = write!(
            h,
            "<tr><td class=\"l\"><span class=\"sw\" style=\"background:{}\"></span>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td class=\"l small\">{}</td></tr>",
            colour.hex(),
            esc(&r.name),
            r.material.map_or("-".to_string(), |v| v.to_string()),
            count(tets),
            num(r.volume, 0),
            num(mesh_vol, 0),
            sides.join(", ")
        );
    }
    h.push_str("</table></section>\n");
}

/// A difference of measured depths with its sign (`+2.50`, `-0.75`, `0.00`).
fn signed(v: f64, digits: usize) -> String {
    let s = num(v, digits);
    if v > 0.0 && s.bytes().any(|b| (b'1'..=b'9').contains(&b)) {
        format!("+{s}")
    } else {
        s
    }
}

/// The wells: one row per well (its file, stations, the regions it passes through, its mesh
/// edges and its length inside the model), then each well's crossings and file markers in MD
/// order. Left out when the recipe has no wells.
fn wells_section(h: &mut String, input: &ReportInput) {
    if input.wells.is_empty() {
        return;
    }
    let _ = write!(h, "<section><h2>Wells ({})</h2>", input.wells.len());
    h.push_str("<table><tr><th class=\"l\">well</th><th class=\"l\">file</th><th>stations</th><th class=\"l\">regions (path order)</th><th>mesh edges</th><th>length in model</th></tr>");
    for w in &input.wells {
        let regions = match &w.error {
            Some(e) if w.regions.is_empty() => {
                format!("<span class=\"st-failed\">{}</span>", esc(e))
            }
            _ => {
                let r: Vec<String> = w.regions.iter().map(|r| region_name(input, r)).collect();
                if r.is_empty() {
                    "-".to_string()
                } else {
                    r.join(" → ")
                }
            }
        };
        let _ = write!(
            h,
            "<tr><td class=\"l\">{}</td><td class=\"l\">{}</td><td>{}</td><td class=\"l small\">{regions}</td><td>{}</td><td>{}</td></tr>",
            esc(&w.name),
            if w.file.is_empty() {
                "-".to_string()
            } else {
                format!("<code>{}</code>", esc(&w.file))
            },
            w.stations.map_or("-".to_string(), count),
            w.edges.map_or("-".to_string(), count),
            num(w.length, 2)
        );
    }
    h.push_str("</table>");
    if input.wells.iter().all(|w| w.markers.is_empty()) {
        h.push_str("</section>\n");
        return;
    }
    h.push_str("<p class=\"small\">Markers down each well in measured depth (MD, model units along the path from its head): where the well crosses a patch of the model (a node of that patch's mesh), and the file's own markers. ΔMD is a file marker's MD minus that of the nearest crossing of a surface other than a box side: positive when the marker lies deeper along the path than the model's surface.</p>");
    for w in input.wells.iter().filter(|w| !w.markers.is_empty()) {
        well_markers_table(h, input, w);
    }
    h.push_str("</section>\n");
}

/// A region's name with the swatch of its colour in the mesh (none when the mesh lacks it).
fn region_name(input: &ReportInput, name: &str) -> String {
    match input.mesh.regions.iter().position(|g| g.name == name) {
        Some(i) => format!(
            "<span class=\"sw\" style=\"background:{}\"></span>{}",
            palette::region(i).hex(),
            esc(name)
        ),
        None => esc(name),
    }
}

fn well_markers_table(h: &mut String, input: &ReportInput, w: &WellSummary) {
    let _ = write!(
        h,
        "<h3>{} ({} marker{})</h3><table><tr><th>MD</th><th class=\"l\">marker</th><th class=\"l\">surface / name</th><th class=\"l\">patch</th><th>x</th><th>y</th><th>z</th><th>ΔMD to nearest surface</th></tr>",
        esc(&w.name),
        count(w.markers.len()),
        if w.markers.len() == 1 { "" } else { "s" }
    );
    for m in &w.markers {
        let (what, name, nearest) = match m.kind {
            MarkerKind::Crossing => {
                let colour = input
                    .surfaces
                    .iter()
                    .find(|s| s.name == m.name)
                    .map(|s| palette::surface(&s.name, s.kind));
                let name = match colour {
                    Some(c) => format!(
                        "<span class=\"sw\" style=\"background:{}\"></span>{}",
                        c.hex(),
                        esc(&m.name)
                    ),
                    None => esc(&m.name),
                };
                ("crossing", name, String::new())
            }
            MarkerKind::File => {
                let nearest = m.nearest.as_ref().map_or("-".to_string(), |n| {
                    format!("{} ({})", signed(n.delta_md, 2), esc(&n.surface))
                });
                ("file", format!("<b>{}</b>", esc(&m.name)), nearest)
            }
        };
        let _ = write!(
            h,
            "<tr><td>{}</td><td class=\"l\">{what}</td><td class=\"l\">{name}</td><td class=\"l\">{}</td><td>{}</td><td>{}</td><td>{}</td><td>{nearest}</td></tr>",
            num(m.md, 2),
            m.patch.as_deref().map_or(String::new(), esc),
            num(m.xyz[0], 2),
            num(m.xyz[1], 2),
            num(m.xyz[2], 2)
        );
    }
    h.push_str("</table>");
}

/// The id table: how every region, surface group, fault side, material, well, named point and
/// face set is numbered in each output format (the README's table, filled in for this mesh).
fn ids_section(h: &mut String, input: &ReportInput) {
    let rows = super::ids(&input.mesh);
    if rows.is_empty() {
        return;
    }
    h.push_str("<h2>Ids in the output files</h2><table><tr><th class=\"l\">what</th><th class=\"l\">name</th><th class=\"l\">msh</th><th class=\"l\">Exodus</th><th class=\"l\">VTU</th><th class=\"l\">MEDIT</th><th class=\"l\">TetGen</th></tr>");
    for r in &rows {
        h.push_str("<tr>");
        for c in [
            r.kind, &r.name, &r.msh, &r.exodus, &r.vtu, &r.medit, &r.tetgen,
        ] {
            let _ = write!(h, "<td class=\"l\">{}</td>", esc(c));
        }
        h.push_str("</tr>");
    }
    h.push_str("</table><p class=\"small\">Abaqus labels are these names made Abaqus-safe; the <code>.inp</code>'s <code>**</code> comments pair each with its name and id.</p>\n");
}

/// One quality table from its shared layout; the last ("all") row is set apart.
fn quality_table(h: &mut String, table: &Table) {
    let _ = write!(h, "<h3>{}</h3><table><tr>", esc(table.title));
    for (i, c) in table.columns.iter().enumerate() {
        let class = if i == 0 { " class=\"l\"" } else { "" };
        let _ = write!(h, "<th{class}>{}</th>", esc(c));
    }
    h.push_str("</tr>");
    for (i, row) in table.rows.iter().enumerate() {
        h.push_str(if i + 1 == table.rows.len() {
            "<tr class=\"all\">"
        } else {
            "<tr>"
        });
        for c in row {
            match c {
                Cell::Name(s) => {
                    let _ = write!(h, "<td class=\"l\">{}</td>", esc(s));
                }
                Cell::Count(n) => {
                    let _ = write!(h, "<td>{}</td>", count(*n));
                }
                Cell::Number { value, digits } => {
                    let _ = write!(h, "<td>{}</td>", num(*value, *digits));
                }
            }
        }
        h.push_str("</tr>");
    }
    h.push_str("</table>");
}

fn quality_tables(h: &mut String, t1: &[TriQuality], t2: &[TetQuality]) {
    h.push_str("<section><h2>Quality (the seed's Tables 1 and 2)</h2>");
    quality_table(h, &layout::table1(t1));
    quality_table(h, &layout::table2(t2));
    h.push_str("<p class=\"small\">Thresholds and statistics as in the seed (population SD; strict comparisons), computed like <code>tools/check_mesh.py</code>. The percentages of Table 2 are of the normalised mean ratio. Its bound is the sharpest angle a region's surfaces leave its tets round an edge: no tet there, so no mesh of that boundary, has a larger smallest dihedral angle.</p></section>\n");
}

fn histogram_grid(h: &mut String, hs: &[Histogram], colours: &[Rgb], measure: &str, marks: &[f64]) {
    h.push_str("<div class=\"grid\">");
    for (i, hist) in hs.iter().enumerate() {
        let c = colours.get(i).copied().unwrap_or(Rgb(90, 90, 90));
        h.push_str(&histogram::svg(hist, c, measure, marks));
    }
    h.push_str("</div>");
}

fn histograms(h: &mut String, input: &ReportInput) {
    let m = &input.mesh;
    h.push_str("<section><h2>Histograms</h2>");
    h.push_str("<h3>Mean ratio per region</h3><p class=\"small\">20 bins on [0, 1]; bar height is the share of the region's tets; dashed lines at the seed's thresholds 0.1, 0.2, 0.3.</p>");
    let rc: Vec<Rgb> = (0..m.regions.len()).map(palette::region).collect();
    histogram_grid(h, &m.mean_ratio, &rc, "mean ratio", &[0.1, 0.2, 0.3]);
    h.push_str("<h3>c/c* per surface</h3><p class=\"small\">20 bins on [1, 2], a grey bar for c/c* ≥ 2; dashed lines at the seed's thresholds 1.15 and 1.5.</p>");
    let sc: Vec<Rgb> = m
        .surface_groups
        .iter()
        .map(|g| palette::surface(&g.name, g.kind))
        .collect();
    histogram_grid(h, &m.c_ratio, &sc, "c/c*", &[1.15, 1.5]);
    h.push_str("</section>\n");
}

fn step_row(h: &mut String, s: &StepSummary) {
    let class = s.state.replace(|c: char| !c.is_ascii_alphanumeric(), "-");
    let _ = write!(
        h,
        "<tr><td class=\"l\">{}</td><td class=\"l st-{}\">{}</td><td class=\"l\">{}</td><td>{}</td></tr>",
        esc(&s.name),
        esc(&class),
        esc(&s.state),
        esc(&s.reason),
        num(s.duration_ms, 1)
    );
}

fn steps_section(h: &mut String, steps: &[StepSummary]) {
    h.push_str("<section><h2>What re-ran and why</h2>");
    if steps.is_empty() {
        h.push_str("<p>No build steps were recorded.</p></section>\n");
        return;
    }
    let (cached, other): (Vec<_>, Vec<_>) = steps.iter().partition(|s| s.state == "cached");
    let total: f64 = steps
        .iter()
        .map(|s| s.duration_ms)
        .filter(|d| d.is_finite())
        .sum();
    // Counts per state, the engine's states in a fixed order, then any other state by name.
    let mut by_state: std::collections::BTreeMap<&str, usize> = Default::default();
    for s in steps {
        *by_state.entry(s.state.as_str()).or_default() += 1;
    }
    let order = ["ran", "failed", "skipped", "cut off", "cached"];
    let mut parts: Vec<String> = order
        .iter()
        .filter_map(|st| {
            by_state
                .get(st)
                .map(|n| format!("{} {}", count(*n), esc(st)))
        })
        .collect();
    parts.extend(
        by_state
            .iter()
            .filter(|(st, _)| !order.contains(st))
            .map(|(st, n)| format!("{} {}", count(*n), esc(st))),
    );
    let _ = write!(
        h,
        "<p>{} steps: {}. A step is cut off when an input re-ran but gave the same output, so it did not re-run. Time in steps: {} ms.</p>",
        count(steps.len()),
        parts.join(", "),
        num(total, 1)
    );
    let head = "<table><tr><th class=\"l\">step</th><th class=\"l\">state</th><th class=\"l\">reason</th><th>ms</th></tr>";
    if !other.is_empty() {
        h.push_str(head);
        for s in &other {
            step_row(h, s);
        }
        h.push_str("</table>");
    }
    if !cached.is_empty() {
        let _ = write!(
            h,
            "<details><summary>{} cached steps</summary>{head}",
            count(cached.len())
        );
        for s in &cached {
            step_row(h, s);
        }
        h.push_str("</table></details>");
    }
    h.push_str("</section>\n");
}
