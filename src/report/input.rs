//! What a report is made of: the model summary (surfaces, curves, patches, regions), the wells,
//! the final tet mesh's figures and the build steps. Plain data handed over by the caller (the
//! command line); nothing here is computed from files. [`ReportInput::from_mesh`] fills what a
//! bare mesh can say (surface groups, regions, line groups, their element counts and volumes)
//! for callers without a model.
//!
//! A well's markers are one list in measured-depth order: where the model's surfaces cross it and
//! the file's own markers, interleaved ([`well_markers`]), because a geomodeller reads them down
//! the hole. A file marker is compared with the crossing nearest to it in MD among the model's
//! surfaces, box sides aside (a pick is of a geological surface; the box is ours): the
//! difference tells how far the model puts the surface from where the pick says it is.

use super::facts::MeshFacts;
use geom::mesh::{SurfaceKind, VolumeMesh};
use geom::predicates::signed_volume;
use model::regions::Side;
use serde::Serialize;

/// One imported surface (or box side) of the model.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SurfaceSummary {
    pub name: String,
    pub kind: SurfaceKind,
    /// Triangles as imported (before splitting).
    pub triangles: usize,
    /// Validation findings (the seed's black-list) on this surface.
    pub findings: usize,
}

/// One curve of the model (an intersection, a box edge, a free border).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CurveSummary {
    /// Stable curve name, e.g. `F1/H1` or `F1/H1#2`.
    pub name: String,
    /// Surfaces the curve lies on, in name order.
    pub surfaces: Vec<String>,
    /// Polyline length in model units.
    pub length: f64,
    /// FE nodes of its discretization (ends included); 0 when not discretized yet.
    pub nodes: usize,
}

/// One patch of the model (a piece of a surface between curves).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PatchSummary {
    /// Stable patch name `surface#k`.
    pub name: String,
    pub surface: String,
    /// FE triangles of its surface mesh; 0 when not meshed yet.
    pub triangles: usize,
    /// Both sides bound the same region (a fault tip inside a region).
    pub dangling: bool,
}

/// One side of one patch bounding a region.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PatchSide {
    pub patch: String,
    pub side: Side,
}

/// One region of the model.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RegionSummary {
    pub name: String,
    /// Material id from the recipe (as in [`geom::mesh::RegionGroup::material`]).
    pub material: Option<i64>,
    /// The patch sides bounding it (a dangling patch appears with both sides).
    pub patches: Vec<PatchSide>,
    /// Tets of its mesh; 0 when not meshed yet.
    pub tets: usize,
    /// Enclosed volume of the model region (model units cubed; NaN when unknown).
    pub volume: f64,
}

/// One node of the build: what ran and why.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct StepSummary {
    /// Build node name, e.g. `discretize:F1/H1`.
    pub name: String,
    /// `ran`, `cached`, `cut off`, `failed` or `skipped` (the engine's `NodeState::as_str`).
    pub state: String,
    /// Why it ran (the engine's rebuild reason, in words).
    pub reason: String,
    pub duration_ms: f64,
}

/// Whether a row of a well's markers is a crossing of the model or a marker of the file.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum MarkerKind {
    /// Where the path crosses a patch of the model (a node of that patch's mesh).
    Crossing,
    /// A marker of the well's file (a gOcad Well's `MRKR` record).
    File,
}

/// The crossing a file marker is compared with.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct NearestCrossing {
    pub surface: String,
    /// The marker's MD minus the crossing's: positive when the marker lies deeper along the path.
    pub delta_md: f64,
}

/// One row of a well's markers.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct WellMarkerRow {
    pub kind: MarkerKind,
    /// The surface crossed, or the file marker's name.
    pub name: String,
    /// The patch crossed (crossings only).
    pub patch: Option<String>,
    /// Measured depth, in model units.
    pub md: f64,
    /// Position, in the recipe's frame.
    pub xyz: [f64; 3],
    /// A file marker's nearest crossing by MD of a surface other than a box side; `None` for a
    /// crossing, or when the well crosses no such surface.
    pub nearest: Option<NearestCrossing>,
}

impl WellMarkerRow {
    /// The crossing of `patch` (of `surface`) at `md`, `xyz`.
    pub fn crossing(surface: &str, patch: &str, md: f64, xyz: [f64; 3]) -> Self {
        WellMarkerRow {
            kind: MarkerKind::Crossing,
            name: surface.to_string(),
            patch: Some(patch.to_string()),
            md,
            xyz,
            nearest: None,
        }
    }

    /// The file's marker `name` at `md`, `xyz` (its nearest crossing is left to
    /// [`well_markers`]).
    pub fn file(name: &str, md: f64, xyz: [f64; 3]) -> Self {
        WellMarkerRow {
            kind: MarkerKind::File,
            name: name.to_string(),
            patch: None,
            md,
            xyz,
            nearest: None,
        }
    }
}

/// A well's markers in MD order: `crossings` (in path order) and the file's `markers`
/// interleaved, each file marker given its nearest crossing by MD of a surface for which
/// `box_side` is false (the first in path order on a tie). Rows of equal MD keep their order, the
/// crossings first; rows whose MD is NaN come last.
pub fn well_markers(
    crossings: Vec<WellMarkerRow>,
    markers: Vec<WellMarkerRow>,
    box_side: impl Fn(&str) -> bool,
) -> Vec<WellMarkerRow> {
    let markers: Vec<WellMarkerRow> = markers
        .into_iter()
        .map(|mut m| {
            m.nearest = crossings
                .iter()
                .filter(|c| m.md.is_finite() && c.md.is_finite() && !box_side(&c.name))
                .min_by(|a, b| (m.md - a.md).abs().total_cmp(&(m.md - b.md).abs()))
                .map(|c| NearestCrossing {
                    surface: c.name.clone(),
                    delta_md: m.md - c.md,
                });
            m
        })
        .collect();
    let mut rows = crossings;
    rows.extend(markers);
    // Stable: equal MDs keep the crossings first, each list in its own order.
    rows.sort_by(|a, b| match (a.md.is_nan(), b.md.is_nan()) {
        (false, false) => a.md.total_cmp(&b.md),
        (x, y) => x.cmp(&y),
    });
    rows
}

/// One well of the recipe: what its file, its cut by the model and the mesh say of it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct WellSummary {
    pub name: String,
    /// The file as the recipe names it (empty when unknown, e.g. a bare mesh's line group).
    pub file: String,
    /// Stations read from the file; `None` when it was not read.
    pub stations: Option<usize>,
    /// The regions the path passes through inside the model, in path order; a region the path
    /// leaves and enters again is named again, but not one it stays in (past the tip of a
    /// dangling fault). Empty when the well was not cut.
    pub regions: Vec<String>,
    /// Length of the path inside the model (model units); NaN when the well was not cut.
    pub length: f64,
    /// Edges of the well's line group in the mesh; `None` when the mesh has no group of its name.
    pub edges: Option<usize>,
    /// Crossings and file markers in MD order (see [`well_markers`]).
    pub markers: Vec<WellMarkerRow>,
    /// Why the well is known only in part: its file was not read, or it was not cut.
    pub error: Option<String>,
}

/// Everything a report shows.
#[derive(Clone, Debug)]
pub struct ReportInput<'a> {
    pub model_name: &'a str,
    pub recipe_path: &'a str,
    pub surfaces: Vec<SurfaceSummary>,
    pub curves: Vec<CurveSummary>,
    pub patches: Vec<PatchSummary>,
    pub regions: Vec<RegionSummary>,
    /// The model's corners, lines, surfaces and regions as its source files draw them, without
    /// the mesher's cuts (`plan::ops::geology_counts`); none without a model.
    pub geology: Option<crate::plan::ops::GeologyCounts>,
    /// The recipe's wells, in name order (none: the report has no wells section).
    pub wells: Vec<WellSummary>,
    /// The figures of the final tet mesh (with its tagged triangles and groups).
    pub mesh: MeshFacts,
    pub steps: Vec<StepSummary>,
    /// What the build has to say about the recipe's effect (thin regions meshed one element
    /// across), shown first among the report's warnings.
    pub warnings: Vec<String>,
}

/// Nothing: empty names and lists and the figures of an empty mesh, so a caller can write
/// `ReportInput { model_name, mesh: MeshFacts::of(&mesh, model_name), ..Default::default() }` and
/// fields added later do not break it.
impl Default for ReportInput<'_> {
    fn default() -> Self {
        ReportInput {
            model_name: "",
            recipe_path: "",
            surfaces: Vec::new(),
            curves: Vec::new(),
            patches: Vec::new(),
            regions: Vec::new(),
            geology: None,
            wells: Vec::new(),
            mesh: MeshFacts::of(&VolumeMesh::default(), ""),
            steps: Vec::new(),
            warnings: Vec::new(),
        }
    }
}

impl<'a> ReportInput<'a> {
    /// A report of a bare mesh: one surface per surface group (its FE triangles as the imported
    /// count, no findings), one region per region group (tets, summed tet volume), one well per
    /// line group (its edges and their length; no file, stations, regions or markers), no
    /// curves, patches or steps. Elements whose tags or nodes are out of range are not counted.
    pub fn from_mesh(model_name: &'a str, recipe_path: &'a str, mesh: &VolumeMesh) -> Self {
        let facts = MeshFacts::of(mesh, model_name);
        let (tris, tets, volume) = (
            &facts.group_triangles,
            &facts.region_tets,
            &facts.region_volume,
        );
        ReportInput {
            model_name,
            recipe_path,
            surfaces: mesh
                .surface_groups
                .iter()
                .zip(tris)
                .map(|(g, &n)| SurfaceSummary {
                    name: g.name.clone(),
                    kind: g.kind,
                    triangles: n,
                    findings: 0,
                })
                .collect(),
            curves: Vec::new(),
            patches: Vec::new(),
            regions: mesh
                .regions
                .iter()
                .enumerate()
                .map(|(i, r)| RegionSummary {
                    name: r.name.clone(),
                    material: r.material,
                    patches: Vec::new(),
                    tets: tets.get(i).copied().unwrap_or(0),
                    volume: volume.get(i).copied().unwrap_or(f64::NAN),
                })
                .collect(),
            geology: None,
            wells: facts
                .lines
                .iter()
                .map(|l| WellSummary {
                    name: l.name.clone(),
                    file: String::new(),
                    stations: None,
                    regions: Vec::new(),
                    length: l.length,
                    edges: Some(l.edges),
                    markers: Vec::new(),
                    error: None,
                })
                .collect(),
            mesh: facts,
            steps: Vec::new(),
            warnings: Vec::new(),
        }
    }
}

/// Tets per mesh region and the sum of their absolute volumes (a measure), in region index
/// order. Tets with an out-of-range region tag or node are skipped.
pub fn region_tets_and_volumes(mesh: &VolumeMesh) -> (Vec<usize>, Vec<f64>) {
    let n = mesh.regions.len();
    let (mut count, mut vol) = (vec![0usize; n], vec![0.0f64; n]);
    for (t, &r) in mesh.tets.iter().zip(&mesh.tet_region) {
        let r = r as usize;
        let (Some(c), Some(v)) = (count.get_mut(r), vol.get_mut(r)) else {
            continue;
        };
        let Some([a, b, p, d]) = tet_points(mesh, t) else {
            continue;
        };
        *c += 1;
        *v += signed_volume(&a, &b, &p, &d).abs();
    }
    (count, vol)
}

/// The four corners of a tet, or `None` if a node index is out of range.
pub(crate) fn tet_points(mesh: &VolumeMesh, t: &[u32; 4]) -> Option<[[f64; 3]; 4]> {
    Some([
        *mesh.nodes.get(t[0] as usize)?,
        *mesh.nodes.get(t[1] as usize)?,
        *mesh.nodes.get(t[2] as usize)?,
        *mesh.nodes.get(t[3] as usize)?,
    ])
}

/// The three corners of a triangle, or `None` if a node index is out of range.
pub(crate) fn tri_points(mesh: &VolumeMesh, t: &[u32; 3]) -> Option<[[f64; 3]; 3]> {
    Some([
        *mesh.nodes.get(t[0] as usize)?,
        *mesh.nodes.get(t[1] as usize)?,
        *mesh.nodes.get(t[2] as usize)?,
    ])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn file_markers_interleave_with_the_crossings_by_md_and_face_the_nearest_surface() {
        let crossings = vec![
            WellMarkerRow::crossing("box.zmax", "box.zmax#0", 10.0, [0.0, 0.0, 0.0]),
            WellMarkerRow::crossing("H1", "H1#0", 500.0, [0.0, 0.0, -490.0]),
            WellMarkerRow::crossing("H2", "H2#1", 600.0, [0.0, 0.0, -590.0]),
        ];
        let file = vec![
            WellMarkerRow::file("H2_pick", 596.5, [0.0, 0.0, -586.5]),
            WellMarkerRow::file("seabed", 12.0, [0.0, 0.0, -2.0]),
            WellMarkerRow::file("H1_pick", 502.0, [0.0, 0.0, -492.0]),
            WellMarkerRow::file("lost", f64::NAN, [0.0; 3]),
            WellMarkerRow::file("at_H1", 500.0, [0.0, 0.0, -490.0]),
        ];
        let rows = well_markers(crossings, file, |s| s.starts_with("box."));
        let names: Vec<&str> = rows.iter().map(|r| r.name.as_str()).collect();
        assert_eq!(
            names,
            [
                "box.zmax", "seabed", "H1", "at_H1", "H1_pick", "H2_pick", "H2", "lost"
            ]
        );
        let nearest = |name: &str| {
            let r = rows.iter().find(|r| r.name == name).unwrap();
            r.nearest.as_ref().map(|n| (n.surface.as_str(), n.delta_md))
        };
        // A box side is not a surface a pick is of: the seabed marker faces H1.
        assert_eq!(nearest("seabed"), Some(("H1", -488.0)));
        assert_eq!(nearest("H1_pick"), Some(("H1", 2.0)));
        assert_eq!(nearest("H2_pick"), Some(("H2", -3.5)));
        assert_eq!(nearest("at_H1"), Some(("H1", 0.0)));
        assert_eq!(nearest("lost"), None);
        assert_eq!(nearest("H1"), None, "crossings have no nearest");
        assert_eq!(rows[2].patch.as_deref(), Some("H1#0"));
        assert_eq!(rows[3].kind, MarkerKind::File);
    }

    #[test]
    fn a_file_marker_of_a_well_crossing_only_box_sides_has_no_nearest_surface() {
        let rows = well_markers(
            vec![WellMarkerRow::crossing(
                "box.zmax",
                "box.zmax#0",
                0.0,
                [0.0; 3],
            )],
            vec![WellMarkerRow::file("top", 1.0, [0.0; 3])],
            |s| s == "box.zmax",
        );
        assert_eq!(rows.len(), 2);
        assert!(rows.iter().all(|r| r.nearest.is_none()));
    }
}
