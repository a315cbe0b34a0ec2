//! What a report shows of the final mesh, computed from the mesh once: its counts and groups,
//! the seed's Tables 1 and 2, the histograms, the element counts and volumes per group, the
//! edges and length of every line group (well), the named points' and face sets' names, and
//! the two pictures.
//!
//! These are the report's only costly parts (a measure per element, a sort of every tet face,
//! the painter's algorithm), and they depend on the mesh and the model's name alone (the
//! pictures carry it in their titles), so they are a plain serialisable value: the command line
//! keeps it in the cache by the mesh's content hash (see `cli::report`), and a build whose mesh
//! did not change renders its report without reading the mesh. [`FACTS_VERSION`] enters that
//! cache key: bump it whenever what [`MeshFacts::of`] computes changes.

use super::histogram::{self, Histogram};
use super::input::region_tets_and_volumes;
use super::pictures;
use super::view::Picture;
use export::quality::{self, QualityReport};
use geom::mesh::{LineGroup, RegionGroup, SurfaceGroup, VolumeMesh};
use serde::{Deserialize, Serialize};

/// The version of what [`MeshFacts::of`] computes, for caches of it.
pub const FACTS_VERSION: u32 = 5;

/// Everything a report shows of a mesh.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MeshFacts {
    pub nodes: usize,
    pub triangles: usize,
    pub tets: usize,
    /// The mesh's regions and surface groups (index order).
    pub regions: Vec<RegionGroup>,
    pub surface_groups: Vec<SurfaceGroup>,
    /// Why the mesh's indices are inconsistent, when they are.
    pub inconsistent: Option<String>,
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
    /// The mesh's line groups (the wells), index order.
    pub lines: Vec<LineFacts>,
    /// The names of the mesh's named points (the wells' crossings of the surfaces), index order.
    pub points: Vec<String>,
    /// The names of the mesh's face sets (the recipe's `[groups]`), index order.
    pub face_sets: Vec<String>,
    pub pictures: Pictures,
}

/// One line group of a mesh (a well).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct LineFacts {
    pub name: String,
    /// Its edges whose nodes are in range.
    pub edges: usize,
    /// Their summed length (model units).
    pub length: f64,
}

impl LineFacts {
    fn of(mesh: &VolumeMesh, g: &LineGroup) -> LineFacts {
        let (mut edges, mut length) = (0, 0.0);
        for &[a, b] in &g.lines {
            let (Some(p), Some(q)) = (mesh.nodes.get(a as usize), mesh.nodes.get(b as usize))
            else {
                continue;
            };
            edges += 1;
            length += (0..3).map(|k| (q[k] - p[k]).powi(2)).sum::<f64>().sqrt();
        }
        LineFacts {
            name: g.name.clone(),
            edges,
            length,
        }
    }
}

/// The report's two pictures (see `pictures`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Pictures {
    /// The surfaces, coloured by name.
    pub model: Picture,
    /// The cut-away of the tets, coloured by region.
    pub cutaway: Picture,
    /// Tets kept by the cut.
    pub kept: usize,
}

impl MeshFacts {
    /// The figures of `mesh`, whose pictures are titled after `model_name`.
    pub fn of(mesh: &VolumeMesh, model_name: &str) -> MeshFacts {
        let (region_tets, region_volume) = region_tets_and_volumes(mesh);
        let mut group_triangles = vec![0usize; mesh.surface_groups.len()];
        for &g in &mesh.triangle_group {
            if let Some(c) = group_triangles.get_mut(g as usize) {
                *c += 1;
            }
        }
        // The pictures and the measures are independent: drawn and measured side by side.
        let (((model, _), (cutaway, kept, _)), (quality, mean_ratio)) = rayon::join(
            || {
                rayon::join(
                    || pictures::model(mesh, &format!("{model_name} surfaces")),
                    || pictures::cutaway(mesh, &format!("{model_name} tetrahedra, cut away")),
                )
            },
            || {
                let (quality, measures) = quality::report_and_measures(mesh);
                (quality, histogram::mean_ratio_from(mesh, &measures))
            },
        );
        MeshFacts {
            nodes: mesh.nodes.len(),
            triangles: mesh.triangles.len(),
            tets: mesh.tets.len(),
            regions: mesh.regions.clone(),
            surface_groups: mesh.surface_groups.clone(),
            inconsistent: mesh.check_indices().err(),
            quality,
            mean_ratio,
            c_ratio: histogram::c_ratio(mesh),
            region_tets,
            region_volume,
            group_triangles,
            lines: mesh.lines.iter().map(|g| LineFacts::of(mesh, g)).collect(),
            points: mesh.points.iter().map(|p| p.name.clone()).collect(),
            face_sets: mesh.face_sets.iter().map(|s| s.name.clone()).collect(),
            pictures: Pictures {
                model,
                cutaway,
                kept,
            },
        }
    }
}
