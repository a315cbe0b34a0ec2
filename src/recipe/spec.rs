//! The validated, typed recipe: what the planner reads.
//!
//! Every value here has passed validation (finite, in range, names resolved, defaults filled in),
//! so later stages never re-check the recipe; every user-written item keeps the [`Span`] of
//! where it was written so errors found later (a curve rule that matches no curve of the built
//! model) can still point at the recipe. Defaults are documented per field and in the README's recipe reference.
//! The specs are `Serialize` with every span skipped, so a planner can hash a spec as a cache-key
//! parameter without moving a line of the recipe changing any key.

use std::collections::BTreeMap;
use std::path::PathBuf;

use serde::Serialize;

pub use geom::mesh::SurfaceKind;

use super::diagnostic::Span;
use super::selector::{CurveSelector, SurfaceSelector};

/// The six box sides, in this order: the surfaces a `[box]` contributes to the model.
pub const BOX_SIDES: [&str; 6] = [
    "box.xmin", "box.xmax", "box.ymin", "box.ymax", "box.zmin", "box.zmax",
];

pub use geom::Units;

/// `[model]`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ModelSpec {
    /// Required, non-empty: used in output file names.
    pub name: String,
    /// Default `m`.
    pub units: Units,
    /// Default `false`. `true`: the surfaces close every region themselves (e.g. a gOcad
    /// Model3d), so the model is built without a `[box]`; with a `[box]` as well, the box sides
    /// join the model and patches outside the box are trimmed away as usual.
    pub sealed: bool,
    #[serde(skip)]
    pub span: Span,
}

/// The format of an import, from the file extension (case-insensitive).
#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
pub enum ImportFormat {
    /// `.ts`: gOcad TSurf.
    TSurf,
    /// `.ml`: gOcad Model3d.
    Model3d,
    /// `.gp`: gOcad group of objects.
    Group,
}

/// What the importer does with a triangulation that fails validation.
#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
pub enum OnInvalid {
    /// Repair what can be repaired (duplicate vertices, degenerate triangles...) and report it.
    Repair,
    /// Stop the build with the validation report.
    Stop,
}

/// One `[surfaces]` entry.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SurfaceSpec {
    /// The surface name (the key).
    pub name: String,
    /// The file as written in the recipe.
    pub file: PathBuf,
    /// `file` joined to the recipe's directory (absolute paths stay as written).
    pub path: PathBuf,
    pub format: ImportFormat,
    /// Default `Other`; never `Box`.
    pub kind: SurfaceKind,
    /// The TSurf object to take from a multi-object file, by name (`object = "top"`) or by its
    /// position in the file counted from 1 (`object = 2`); `None` = the file's only TSurf object.
    pub object: Option<gocad::import::ObjectRef>,
    /// Re-triangulate the support with this target edge length (> 0); `None` = keep as read.
    pub retriangulate: Option<f64>,
    /// Refine the support with Taubin smoothing before intersection; `None` = keep as read.
    pub smooth: Option<surface_mesh::SupportSmoothing>,
    /// Default `Repair`.
    pub on_invalid: OnInvalid,
    /// Skip objects of other gOcad types in the file instead of failing. Default `false`.
    pub skip_other_types: bool,
    /// Span of the name (the key).
    #[serde(skip)]
    pub span: Span,
    /// Span of the `file` value.
    #[serde(skip)]
    pub file_span: Span,
}

/// The format of a well file, from its extension (case-insensitive).
#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
pub enum WellFormat {
    /// `.wl`: gOcad Well (a path of stations from the well head, with markers).
    Well,
    /// `.pl`: gOcad PLine whose segments form one open path.
    PLine,
}

/// One `[wells]` entry: a well path embedded in the mesh as a chain of edges.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct WellSpec {
    /// The well name (the key).
    pub name: String,
    /// The file as written in the recipe.
    pub file: PathBuf,
    /// `file` joined to the recipe's directory.
    pub path: PathBuf,
    pub format: WellFormat,
    /// The object to take from a file of several, by name or position from 1; `None` = the
    /// file's only Well (or PLine) object.
    pub object: Option<gocad::import::ObjectRef>,
    /// Target length of the well's mesh edges (> 0); `None` = `mesh.size`.
    pub size: Option<f64>,
    /// The regions the well is embedded in (sorted `[regions]` names); `None` = every region it
    /// crosses.
    pub regions: Option<Vec<String>>,
    /// Cross-section area of the well's line elements (model units squared, > 0), written where
    /// a format's line elements need a section (Abaqus); `None` = none written.
    pub area: Option<f64>,
    /// Span of the name (the key).
    #[serde(skip)]
    pub span: Span,
    /// Span of the `file` value.
    #[serde(skip)]
    pub file_span: Span,
}

/// One `[groups]` entry: a named set of patches, written as a boundary group by every format
/// that can carry overlapping groups.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct GroupSpec {
    /// The group name (the key).
    pub name: String,
    /// What it gathers, as written (one or more); a patch is in the group when any matches.
    pub selectors: Vec<crate::recipe::selector::PatchSelector>,
    /// Span of each selector, as `selectors`.
    #[serde(skip)]
    pub selector_spans: Vec<Span>,
    /// Span of the name (the key).
    #[serde(skip)]
    pub span: Span,
}

/// How the bounding box is given.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub enum BoxExtent {
    /// Explicit corners, `min < max` on every axis.
    Explicit { min: [f64; 3], max: [f64; 3] },
    /// The extent of the named surfaces, grown by `margin` (>= 0) on each axis, both sides.
    Around {
        surfaces: Vec<String>,
        margin: [f64; 3],
    },
}

/// `[box]`: its six sides are the surfaces [`BOX_SIDES`].
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BoxSpec {
    pub extent: BoxExtent,
    #[serde(skip)]
    pub span: Span,
}

/// Which side of a surface a `keep` trim keeps.
#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
pub enum Side {
    /// Larger z (towards the surface's upward side).
    Above,
    Below,
    /// Enclosed by the surface, which must be closed (a salt body, an intrusion).
    Inside,
    Outside,
}

/// What a `[[trim]]` does to the patches of the selected surfaces.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub enum TrimAction {
    /// `keep = { above|below|inside|outside = of }`: keep the patches on `side` of surface `of`.
    Keep { side: Side, of: String },
    /// `discard = { containing = p }`.
    DiscardContaining([f64; 3]),
    /// `discard = { nearest = p }`.
    DiscardNearest([f64; 3]),
    /// `discard = { area_below = a }` (> 0, model units squared).
    DiscardAreaBelow(f64),
    /// `discard = { within = d }` (> 0): patches lying within `d` of another surface all over.
    DiscardWithin(f64),
}

/// One `[[trim]]`, applied in recipe order after splitting (outside the box is always discarded).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TrimSpec {
    pub surface: SurfaceSelector,
    pub action: TrimAction,
    /// Span of the `[[trim]]` header.
    #[serde(skip)]
    pub span: Span,
}

/// How a `[mesh.curves]` rule subdivides a curve.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub enum Subdivision {
    /// `count`: this many equal segments (at least 1).
    Count(u32),
    /// `size` (first segment), `ratio` between consecutive segments, `grading`.
    Size {
        size: f64,
        ratio: f64,
        grading: Grading,
    },
}

/// `grading` of a `[mesh.curves]` rule.
#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
pub enum Grading {
    /// Sizes grow from the curve's start to its end.
    Geometric,
    /// Sizes grow from both ends towards the middle.
    Bump,
}

/// `tet_method`: how regions are filled.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum TetMethod {
    /// Delaunay with local boundary recovery (the default).
    #[default]
    Delaunay,
    /// The advancing front.
    Front,
}

impl TetMethod {
    /// Every method with its recipe spelling.
    pub const NAMES: [(&'static str, TetMethod); 2] = [
        ("delaunay", TetMethod::Delaunay),
        ("front", TetMethod::Front),
    ];
}

/// One `[mesh.curves]` entry.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CurveRule {
    pub selector: CurveSelector,
    pub subdivision: Subdivision,
    /// Span of the selector key.
    #[serde(skip)]
    pub span: Span,
}

/// One `[[mesh.refine]]` entry: elements of `size` at a feature, growing to `far` over
/// `distance` (never faster than the mesh's growth allows).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RefineSpec {
    pub near: RefineTarget,
    pub size: f64,
    pub distance: f64,
    pub far: f64,
    #[serde(skip)]
    pub span: Span,
}

/// What a `[[mesh.refine]]` entry refines near.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub enum RefineTarget {
    /// Every patch of the surfaces the selector matches.
    Surface(SurfaceSelector),
    /// Every curve the selector matches.
    Curve(CurveSelector),
    Point([f64; 3]),
}

/// One `[mesh.surfaces]` entry.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SurfaceSizeRule {
    pub selector: SurfaceSelector,
    pub size: f64,
    #[serde(skip)]
    pub span: Span,
}

/// Sizes for one region (`[mesh.regions]`), each defaulting to the global `[mesh]` value.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RegionMeshSpec {
    pub size: f64,
    /// Whether the entry writes `size` (else `size` is the global one): only a written size
    /// reaches the surfaces and curves bounding the region.
    #[serde(skip)]
    pub size_given: bool,
    /// Elements across the region's thickness (`layers`), as written: the region (and the
    /// surfaces and curves bounding it) is meshed at most at its thickness over this.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub layers: Option<u32>,
    /// `aspect`: the region is meshed stretched across its layer by this factor, so its elements
    /// are about this many times as wide along the layer as across it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub aspect: Option<f64>,
    pub min_size: f64,
    pub max_size: f64,
    pub growth: f64,
    /// How the region is filled; default the global `[mesh] tet_method`.
    pub tet_method: TetMethod,
    #[serde(skip)]
    pub span: Span,
}

/// `[mesh]`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MeshSpec {
    /// Global element size, required, > 0.
    pub size: f64,
    /// Default `size / 100`; `0 < min_size <= size`.
    pub min_size: f64,
    /// Default `size * 10`; `max_size >= size`.
    pub max_size: f64,
    /// Size growth ratio between neighbouring elements in volumes, > 1, default 1.3.
    pub growth: f64,
    /// How regions are filled with tets: `"delaunay"` (default) or `"front"` (the seed's
    /// advancing front).
    pub tet_method: TetMethod,
    /// `min_layers`: elements across every region's thickness, where its own `layers` says
    /// nothing.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_layers: Option<u32>,
    /// In recipe order; see [`MeshSpec::curve_rule`] for precedence.
    pub curves: Vec<CurveRule>,
    /// In recipe order; see [`MeshSpec::surface_size`] for precedence.
    pub surfaces: Vec<SurfaceSizeRule>,
    /// Keyed by region name (every key is a `[regions]` name).
    pub regions: BTreeMap<String, RegionMeshSpec>,
    /// `[[mesh.refine]]`, in recipe order.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub refine: Vec<RefineSpec>,
    /// `refine_close_curves`: where the model's curves come closer than their mesh can resolve,
    /// which of those places are refined rather than only warned about.
    #[serde(skip_serializing_if = "CloseCurves::is_default")]
    pub refine_close_curves: CloseCurves,
    #[serde(skip)]
    pub span: Span,
}

/// `[mesh] refine_close_curves`: `true` refines every place where curves come closer than their
/// mesh can resolve; a list of curve names, the places those curves are in; `false`, none. Unless
/// it is `false`, a build whose surface or tet mesh fails at such a place adds the place's curves
/// and builds again (as where two surfaces' meshes cross).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CloseCurves {
    /// `true`: every place.
    pub all: bool,
    /// The curves whose places are refined from the start.
    pub named: Vec<CurveSelector>,
    /// Whether a failure at a place adds it (all but `false`).
    pub on_failure: bool,
}

impl Default for CloseCurves {
    fn default() -> Self {
        CloseCurves {
            all: false,
            named: Vec::new(),
            on_failure: true,
        }
    }
}

impl CloseCurves {
    /// `true` in the recipe.
    pub fn every() -> Self {
        CloseCurves {
            all: true,
            ..Self::default()
        }
    }

    /// `false` in the recipe.
    pub fn none() -> Self {
        CloseCurves {
            on_failure: false,
            ..Self::default()
        }
    }

    /// Not written in the recipe.
    pub fn is_default(&self) -> bool {
        *self == Self::default()
    }

    /// Whether the place holding the curves `names` is refined.
    pub fn refines<'a>(&self, mut names: impl Iterator<Item = &'a str>) -> bool {
        self.all || names.any(|n| self.named.iter().any(|m| m.matches(n)))
    }
}

impl MeshSpec {
    /// The rule for the curve `curve_name`: among matching rules, the most specific (see
    /// [`CurveSelector::specificity`]); among equally specific ones, the one written last.
    pub fn curve_rule(&self, curve_name: &str) -> Option<&CurveRule> {
        self.curve_rule_index(curve_name).map(|i| &self.curves[i])
    }

    /// The position in `curves` of [`Self::curve_rule`]'s rule.
    pub fn curve_rule_index(&self, curve_name: &str) -> Option<usize> {
        let mut best: Option<usize> = None;
        for (i, r) in
            (self.curves.iter().enumerate()).filter(|(_, r)| r.selector.matches(curve_name))
        {
            let beats =
                |b: usize| r.selector.specificity() >= self.curves[b].selector.specificity();
            if best.is_none_or(beats) {
                best = Some(i);
            }
        }
        best
    }

    /// The size for surface `name`: the most specific matching rule (exact name before glob,
    /// then more literal characters; the last written wins a tie), else the global size.
    pub fn surface_size(&self, name: &str) -> f64 {
        let key = |r: &SurfaceSizeRule| (r.selector.is_exact(), r.selector.literal_len());
        let mut best: Option<&SurfaceSizeRule> = None;
        for r in self.surfaces.iter().filter(|r| r.selector.matches(name)) {
            if best.is_none_or(|b| key(r) >= key(b)) {
                best = Some(r);
            }
        }
        best.map_or(self.size, |r| r.size)
    }
}

/// One `[regions]` entry: a name and attributes for the region containing `point`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RegionSpec {
    pub name: String,
    pub point: [f64; 3],
    pub material: Option<i64>,
    /// Numeric attributes, by name.
    pub properties: BTreeMap<String, f64>,
    #[serde(skip)]
    pub span: Span,
}

/// An output format.
#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
pub enum Format {
    /// Gmsh msh 4.1 ASCII.
    Msh,
    /// Gmsh msh 4.1 binary.
    MshBinary,
    /// VTK unstructured grid XML.
    Vtu,
    /// VTK unstructured grid XML with raw appended binary data (large meshes).
    VtuBinary,
    /// TetGen `.node`/`.ele`/`.face` (and `.edge` for the wells).
    Tetgen,
    /// MEDIT `.mesh`.
    Medit,
    /// Abaqus `.inp` (C3D4 elements, region element sets, surface node sets and surfaces, T3D2
    /// well element sets).
    Inp,
    /// Exodus II `.exo` (element blocks, the wells' BAR2 ones too, side sets, node sets).
    Exodus,
}

impl Format {
    /// Every format with its recipe spelling.
    pub const ALL: [(&'static str, Format); 8] = [
        ("msh", Format::Msh),
        ("msh-binary", Format::MshBinary),
        ("vtu", Format::Vtu),
        ("vtu-binary", Format::VtuBinary),
        ("tetgen", Format::Tetgen),
        ("medit", Format::Medit),
        ("inp", Format::Inp),
        ("exodus", Format::Exodus),
    ];

    /// Further spellings a recipe may use (the usual names and extensions of Exodus II).
    pub const ALIASES: [(&'static str, Format); 3] = [
        ("exo", Format::Exodus),
        ("exodusii", Format::Exodus),
        ("e", Format::Exodus),
    ];

    pub fn as_str(self) -> &'static str {
        Format::ALL
            .iter()
            .find(|(_, f)| *f == self)
            .map_or("msh", |(s, _)| s)
    }

    /// The file a format writes, up to the model name: the two encodings of msh, and of VTU,
    /// write the same file, so a recipe can ask for only one of each (the plan's tests check
    /// this against the file names the export stage gives).
    pub fn file_family(self) -> &'static str {
        match self {
            Format::Msh | Format::MshBinary => "msh",
            Format::Vtu | Format::VtuBinary => "vtu",
            Format::Tetgen => "tetgen",
            Format::Medit => "medit",
            Format::Inp => "inp",
            Format::Exodus => "exodus",
        }
    }
}

/// `[output]`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct OutputSpec {
    /// As written; default `out`.
    pub dir: PathBuf,
    /// `dir` joined to the recipe's directory.
    pub path: PathBuf,
    /// Without duplicates, in recipe order; default `["msh", "vtu"]`.
    pub formats: Vec<Format>,
    #[serde(skip)]
    pub span: Span,
}
