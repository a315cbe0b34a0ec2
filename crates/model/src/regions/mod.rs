//! Stage `regions`: volume recognition at the patch level (the seed paper's §3).
//!
//! It decides which closed volumes (regions) the conforming patches of a model bound, which
//! patches and which of their sides bound each region, which shells are the outside of the model,
//! which patches dangle inside a region (faults ending inside it, both sides in the region), and
//! which closed bodies sit inside another region as cavities (lenses). Every orientation and
//! inside/outside decision is an exact predicate from `geom`: the radial order of the
//! triangles around a curve edge, the exterior shell of each connected component, the host of a
//! nested body and the region that holds a recipe's naming point. Floating-point values are only
//! used for measures (`Shell::signed_volume`) and to construct candidate points whose position is
//! then verified exactly.
//!
//! Method: vertices are welded by exact coordinates; every triangle has two face-uses; at every
//! edge the incident triangles are sorted radially and each wedge between two consecutive
//! half-planes links the two face-uses facing it; the linked face-uses form shells. A surface
//! that stops short leaves a free border, which links both sides of its patch: unless the surface
//! may dangle (a fault, see [`RegionOptions`]) this is reported by name with the gap's ends.

mod assemble;
mod crowded;
mod exact;
mod locate;
mod names;
mod radial;
mod shells;
mod weld;

pub use locate::Locator;
use serde::{Deserialize, Serialize};
use std::collections::BTreeSet;

/// One conforming patch: a connected, consistently oriented piece of a surface between curves.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PatchIn {
    /// Unique, stable patch name, e.g. `h1#2`.
    pub name: String,
    /// Name of the surface the patch belongs to (used in messages and generated region names).
    pub surface: String,
    pub mesh: geom::TriMesh,
    /// For a chart (a piece of a patch cut so that it flattens), the name of that patch: the
    /// curves between charts of one patch are seams, not features.
    #[serde(default)]
    pub chart_of: Option<String>,
}

/// A side of a patch.
#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
pub enum Side {
    /// The side the triangles' right-hand normal `(b-a)×(c-a)` points to.
    Front,
    Back,
}

impl Side {
    pub fn opposite(self) -> Side {
        match self {
            Side::Front => Side::Back,
            Side::Back => Side::Front,
        }
    }
}

/// One side of one patch (index into the `patches` slice given to [`find_regions`]).
#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
pub struct FaceUse {
    pub patch: u32,
    pub side: Side,
}

/// A closed set of linked face-uses.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Shell {
    /// Sorted by (patch, side).
    pub face_uses: Vec<FaceUse>,
    /// Volume enclosed on the side the face-uses face (positive for a region's outer shell,
    /// negative for the outside of a body; a measure, never used for decisions).
    pub signed_volume: f64,
}

/// A closed volume of the model.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Region {
    pub name: String,
    pub outer: Shell,
    /// Outer shells of the bodies nested inside this region (lenses), facing into this region.
    pub cavities: Vec<Shell>,
    /// Every (patch, side) bounding the region; a dangling patch appears with both sides. Sorted.
    pub sides: Vec<FaceUse>,
    /// A point strictly inside the region (off every patch), for naming and picking.
    pub interior_point: [f64; 3],
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RegionModel {
    /// Canonical order: by the lexicographically smallest vertex of the outer shell, then by the
    /// sorted names of its patches — never by input or creation order.
    pub regions: Vec<Region>,
    /// The shells facing the unbounded outside (one per top-level connected body).
    pub exterior: Vec<Shell>,
    /// Patches whose two sides bound the same region (sorted).
    pub dangling: Vec<u32>,
}

/// Why regions could not be found: a message naming the surface and a point where it happens.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, thiserror::Error)]
#[error("{message}")]
pub struct RegionError {
    pub message: String,
    pub surface: Option<String>,
    pub at: Option<[f64; 3]>,
}

impl RegionError {
    pub(crate) fn new(
        message: impl Into<String>,
        surface: Option<&str>,
        at: Option<[f64; 3]>,
    ) -> Self {
        RegionError {
            message: message.into(),
            surface: surface.map(str::to_string),
            at,
        }
    }
}

/// Which surfaces may end inside the model (have free borders) without closing a region.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub enum Dangling {
    /// No surface may: every free border is reported (the safe default).
    #[default]
    Forbidden,
    /// These surfaces (by name: typically the faults) may; the others are reported.
    Surfaces(BTreeSet<String>),
    /// Every surface may (a model like RINGMesh's `non_split_cube`, whose horizon stops short).
    Allowed,
}

/// Options of [`find_regions_with`].
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct RegionOptions {
    pub dangling: Dangling,
}

impl RegionOptions {
    /// Options letting the named surfaces (the faults) dangle.
    pub fn with_faults<I: IntoIterator<Item = S>, S: Into<String>>(faults: I) -> Self {
        RegionOptions {
            dangling: Dangling::Surfaces(faults.into_iter().map(Into::into).collect()),
        }
    }
    pub(crate) fn may_dangle(&self, surface: &str) -> bool {
        match &self.dangling {
            Dangling::Forbidden => false,
            Dangling::Surfaces(s) => s.contains(surface),
            Dangling::Allowed => true,
        }
    }
}

/// Finds the regions with the default options: no surface may stop short (every free border is
/// an error). Use [`find_regions_with`] to let faults dangle.
pub fn find_regions(
    patches: &[PatchIn],
    names: &[(String, [f64; 3])],
) -> Result<RegionModel, RegionError> {
    find_regions_with(patches, names, &RegionOptions::default())
}

/// Finds the regions bounded by conforming `patches`; `names` gives recipe names by point.
pub fn find_regions_with(
    patches: &[PatchIn],
    names: &[(String, [f64; 3])],
    opts: &RegionOptions,
) -> Result<RegionModel, RegionError> {
    let soup = weld::Soup::build(patches)?;
    let links = radial::link(&soup, patches)?;
    shells::check_free_borders(&soup, patches, &links.free_edges, opts)?;
    let shells = shells::Shells::build(&soup, patches, links)?;
    let built = assemble::assemble(&soup, patches, &shells)?;
    names::name_regions(built, patches, names)
}

/// The index of the region strictly containing `p` (exact), `None` outside every region or on a
/// patch bounding or dangling in the region.
pub fn locate(model: &RegionModel, patches: &[PatchIn], p: [f64; 3]) -> Option<usize> {
    Locator::new(model, patches).locate(p)
}
