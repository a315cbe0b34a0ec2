//! The one place tolerances live. Exact predicates decide every orientation and inside/outside
//! question; these values only steer *constructions* and *reports* where no exact answer exists
//! (how far a mesh node may sit from its support, what kink angle makes a corner...). Every field
//! is part of the cache key of every operation that receives a `Tolerances`, so changing one
//! re-runs exactly the operations that depend on it.

use serde::{Deserialize, Serialize};

/// Tolerances, with units. Defaults are documented per field and in the README's recipe reference.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Tolerances {
    /// Boundary vertices where the polyline turns by more than this angle (degrees) become
    /// topological vertices (corners) that split boundary loops into curves, when it also turns
    /// by more than half of it over the longer edge's length there (`model::kinks`: a jog that
    /// turns back within its edges is no corner). Default 30°.
    pub kink_angle_deg: f64,
    /// Edges inside a surface where its triangles bend by more than this angle (degrees) are
    /// creases: the surface is cut into patches there (a box TSurf folded around the box's
    /// edges, a fold's tight hinge). Default 30°, as the folded box TSurfs of RINGMesh's models
    /// need; a coarsely faceted curved body (a lens, a dome) bends by 30-45° between facets, and
    /// cutting there leaves needle patches of one facet each, which 45° avoids.
    pub crease_angle_deg: f64,
    /// A patch whose triangles face more than this angle (degrees) away from their mean
    /// direction (a tube, a closed body, a cup, a salt wall) is cut into charts, each facing
    /// within this angle of one axis direction, so that every piece flattens onto a plane
    /// without folding. Default 60°.
    pub chart_angle_deg: f64,
    /// Vertices of one surface closer than this distance (model units) are reported as
    /// coincident duplicates by validation and merged by repair. 0.0 (the default) means
    /// bit-identical coordinates only.
    pub merge_distance: f64,
    /// Largest distance (model units, relative to the local element size) a generated mesh node
    /// may lie from its support surface, as a fraction of the local element size. Default 1e-6.
    pub support_distance_rel: f64,
    /// Vertices of two different surfaces closer than this fraction of the model's bounding
    /// box diagonal, but not at the same coordinates, are reported as a non-conformal contact
    /// (surfaces meant to meet there, as a sealed model's must, share their vertices bit for
    /// bit). Default 1e-7 (2 mm across a 20 km model). A report only: nothing is moved.
    pub conformity_rel: f64,
}

impl Default for Tolerances {
    fn default() -> Self {
        Tolerances {
            kink_angle_deg: 30.0,
            crease_angle_deg: 30.0,
            chart_angle_deg: 60.0,
            merge_distance: 0.0,
            support_distance_rel: 1e-6,
            conformity_rel: 1e-7,
        }
    }
}

impl Tolerances {
    /// The fields as (name, value) pairs in a fixed order, for cache keys and reports.
    pub fn fields(&self) -> [(&'static str, f64); 6] {
        [
            ("kink_angle_deg", self.kink_angle_deg),
            ("crease_angle_deg", self.crease_angle_deg),
            ("chart_angle_deg", self.chart_angle_deg),
            ("merge_distance", self.merge_distance),
            ("support_distance_rel", self.support_distance_rel),
            ("conformity_rel", self.conformity_rel),
        ]
    }
}
