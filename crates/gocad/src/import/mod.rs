//! Stage `import`: gOcad ASCII files (TSurf `.ts`, Model3d `.ml`, groups `.gp`, PLine `.pl`,
//! Well `.wl`) to typed surfaces, lines and well paths.
//!
//! It decides which object of a file is the surface, line or well a recipe names (`pick`), how
//! its coordinates map into the recipe's frame (`frame`: unit scaling, `ZPOSITIVE Depth` →
//! z := -z, the same for every object type) and which vertex every triangle, segment, ATOM,
//! BSTONE and BORDER points to. Everything it cannot decide exactly — a missing vertex, a
//! non-numeric or infinite coordinate, a duplicate id, an object of another type, a well whose
//! measured depth decreases — is an [`ImportError`] naming the file and line; no byte sequence
//! makes it panic.
//!
//! The stage is a pure function of bytes: the engine reads the file and passes its label.
//!
//! Orientation note: with `ZPOSITIVE Depth` the z axis is negated but triangles are kept exactly as
//! written (corner order unchanged), so their geometric orientation (right-hand normal) flips.
//! Validation and topology only rely on orientation *consistency*, which a reflection preserves.

mod frame;
mod lexer;
mod model3d;
mod parser;
mod pick;
mod pline;
mod pline_path;
mod records;
mod select;
mod well;
mod well_records;

pub use model3d::{Model3dFace, Model3dInfo, Model3dRecord, Model3dRegion};
pub use parser::{CoordinateSystem, GocadFile, GocadObject, RawPart, parse_gocad};
pub use pline::{LinePart, Polyline, import_line, import_lines};
pub use select::{import_surface, import_surfaces};
pub use well::{Marker, WellPath, import_well, import_wells};
pub use well_records::{RawMarker, RawStation, StationRecord, WellRecords};

use serde::{Deserialize, Serialize};
use std::fmt;

pub use geom::Units;

/// Which object of a file to import.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum ObjectRef {
    /// The object whose HEADER `name` this is; it must be the only object of that name.
    Name(String),
    /// The object at this position in the file, counted from 1 over every GOCAD object in file
    /// order (whatever its type): how a file with two objects of the same name is read.
    Position(u32),
}

impl From<&str> for ObjectRef {
    fn from(name: &str) -> Self {
        ObjectRef::Name(name.to_string())
    }
}

impl From<String> for ObjectRef {
    fn from(name: String) -> Self {
        ObjectRef::Name(name)
    }
}

impl fmt::Display for ObjectRef {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ObjectRef::Name(n) => write!(f, "'{n}'"),
            ObjectRef::Position(k) => write!(f, "#{k}"),
        }
    }
}

/// What the recipe says about one imported surface, line or well.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ImportOptions {
    /// The object to import, by name or position. `None`: the file must hold exactly one object
    /// of the type imported.
    pub object: Option<ObjectRef>,
    /// Skip objects of other types (a PLine when surfaces are imported, VSet, SGrid...) instead
    /// of failing on them.
    pub skip_other_types: bool,
    /// Units of the recipe. `Some(u)`: each axis is scaled from its `AXIS_UNIT` (metres when the
    /// file has no CRS block) into `u`; an unknown unit is an error. `None`: coordinates are kept
    /// as written.
    pub target_units: Option<Units>,
}

impl Default for ImportOptions {
    fn default() -> Self {
        ImportOptions {
            object: None,
            skip_other_types: false,
            target_units: Some(Units::Metre),
        }
    }
}

/// The largest coordinate (or depth) magnitude an import accepts: 10¹² in the file's unit, more
/// than the Earth's circumference in millimetres. A larger value is no position in any unit but
/// a no-data marker or a damaged number, and beyond it products in the exact predicates would
/// lose their range, so it is refused at its line instead of failing far away in a later stage.
pub const MAX_COORDINATE: f64 = 1e12;

/// The message for a value beyond [`MAX_COORDINATE`]: `what` names it.
pub(crate) fn beyond_earth(what: &str, value: f64) -> String {
    format!(
        "{what} {value:e} is beyond ±{MAX_COORDINATE:e}, no position in any unit: it is probably \
         a no-data value or a damaged number; remove the vertex or write its real value"
    )
}

/// An import failure: `file:line: message`, or `file: message` when the whole file is concerned
/// (`line` 0).
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct ImportError {
    pub file: String,
    pub line: usize,
    pub message: String,
}

impl fmt::Display for ImportError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.line {
            0 => write!(f, "{}: {}", self.file, self.message),
            line => write!(f, "{}:{line}: {}", self.file, self.message),
        }
    }
}

impl std::error::Error for ImportError {}

impl ImportError {
    pub fn new(file: &str, line: usize, message: impl Into<String>) -> Self {
        ImportError {
            file: file.to_string(),
            line,
            message: message.into(),
        }
    }
}

/// One TFACE of an imported surface.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PartInfo {
    /// `TFACE <k>` (1-based in file order), or the Model3d TFACE id when the file is a Model3d.
    pub name: String,
    /// Line of the TFACE keyword (the object's first line when the object has no TFACE).
    pub line: usize,
    /// Name of the gOcad object the part comes from.
    pub object: String,
    /// Model3d TFACE record matched to this part: its id and type (`boundary`, `normal_fault`...).
    pub model_tface: Option<(u64, String)>,
    pub triangle_count: usize,
}

/// Where each vertex and triangle came from, for messages of later stages.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct SourceMap {
    pub file: String,
    /// gOcad id of each vertex (VRTX/PVRTX id).
    pub vertex_ids: Vec<u64>,
    /// 1-based line of each vertex's VRTX/PVRTX record.
    pub vertex_lines: Vec<u32>,
    /// 1-based line of each triangle's TRGL record.
    pub triangle_lines: Vec<u32>,
}

impl SourceMap {
    pub fn vertex_line(&self, v: u32) -> usize {
        self.vertex_lines.get(v as usize).map_or(0, |&l| l as usize)
    }
    pub fn triangle_line(&self, t: u32) -> usize {
        self.triangle_lines
            .get(t as usize)
            .map_or(0, |&l| l as usize)
    }
    pub fn vertex_id(&self, v: u32) -> Option<u64> {
        self.vertex_ids.get(v as usize).copied()
    }
}

/// A surface ready for validation: coordinates in the recipe's frame, one part per TFACE.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ImportedSurface {
    pub name: String,
    /// Vertices (z flipped for `ZPOSITIVE Depth`, scaled to the target units) and triangles
    /// (corner order as written). ATOM/PATOM aliases are resolved to the vertex they repeat.
    pub mesh: geom::TriMesh,
    /// Part (index into `parts`) of each triangle.
    pub triangle_part: Vec<u32>,
    pub parts: Vec<PartInfo>,
    /// Vertex indices named by BSTONE records.
    pub bstones: Vec<u32>,
    /// BORDER records as pairs of vertex indices.
    pub borders: Vec<[u32; 2]>,
    /// One name per property column (`U[0]`, `U[1]`, `U[2]` for an ESIZES 3 property `U`).
    pub property_names: Vec<String>,
    /// `properties[k][v]`: value of column `k` at vertex `v` (NO_DATA values kept as written).
    pub properties: Vec<Vec<f64>>,
    pub source: SourceMap,
}

impl ImportedSurface {
    /// Heap bytes held (capacities), for memory budgets.
    pub fn heap_bytes(&self) -> usize {
        use std::mem::size_of;
        self.mesh.vertices.capacity() * size_of::<[f64; 3]>()
            + self.mesh.triangles.capacity() * size_of::<[u32; 3]>()
            + self.triangle_part.capacity() * 4
            + self.bstones.capacity() * 4
            + self.borders.capacity() * 8
            + self
                .properties
                .iter()
                .map(|c| c.capacity() * 8)
                .sum::<usize>()
            + self.source.vertex_ids.capacity() * 8
            + self.source.vertex_lines.capacity() * 4
            + self.source.triangle_lines.capacity() * 4
    }
}
