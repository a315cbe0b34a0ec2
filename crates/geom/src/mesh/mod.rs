//! The finite-element mesh types that the meshing stages produce and the export and quality
//! stages consume. Plain data: no geometry decisions here.

use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

pub mod read;

/// What a surface is, geologically. Decides defaults (faults may dangle; box sides bound the model)
/// and how exports group it.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SurfaceKind {
    Horizon,
    Fault,
    Box,
    Other,
}

/// A named group of surface triangles (a surface, a fault, a box side): a 2D physical group.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SurfaceGroup {
    pub name: String,
    pub kind: SurfaceKind,
}

/// A named region: a 3D physical group, with the recipe's attributes.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RegionGroup {
    pub name: String,
    /// Material id from the recipe, if any (exported as a cell tag where the format has one).
    pub material: Option<i64>,
    /// Further numeric attributes from the recipe, in name order.
    pub properties: BTreeMap<String, f64>,
}

/// A named group of line elements: the chain of mesh edges an embedded well became (a 1D
/// physical group).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct LineGroup {
    pub name: String,
    /// Segments between mesh nodes, each an edge of a tet.
    pub lines: Vec<[u32; 2]>,
    /// The cross-section area of its line elements (model units squared), for the formats whose
    /// line elements need a section to run (Abaqus, CalculiX); `None` when the recipe gives none.
    pub area: Option<f64>,
}

/// A named mesh node: where a well crosses a surface (`<well>:<surface>`, `:2`, `:3`, ... for
/// the same well crossing the same surface again, in path order), for a solver to put a source,
/// a monitor or a boundary condition at (a 0D physical group).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct NamedPoint {
    pub name: String,
    /// Index into `nodes`.
    pub node: u32,
}

/// A named set of surface triangles that a recipe's `[groups]` entry selected (patches of one or
/// several surfaces), for a boundary condition to be set on by a stable name. Unlike the surface
/// groups, which partition the triangles, face sets may overlap each other and the surface
/// groups: a triangle of `H1#2` is in the group `H1` and in every face set that selects `H1#2`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct FaceSet {
    pub name: String,
    /// Indices into `triangles`, ascending, without repeats.
    pub triangles: Vec<u32>,
}

/// A tetrahedral FE mesh with tagged surface triangles.
///
/// Invariants (checked by `validate`): every index is in range; every tet has positive signed
/// volume `det[b-a, c-a, d-a] > 0` (the orientation Gmsh, VTK and meshio expect); every triangle
/// is a face of at least one tet (boundary, interface or embedded dangling-fault triangle);
/// `tet_region.len() == tets.len()` and `triangle_group.len() == triangles.len()`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct VolumeMesh {
    pub nodes: Vec<[f64; 3]>,
    pub tets: Vec<[u32; 4]>,
    /// Index into `regions` for each tet.
    pub tet_region: Vec<u32>,
    pub regions: Vec<RegionGroup>,
    pub triangles: Vec<[u32; 3]>,
    /// Index into `surface_groups` for each triangle.
    pub triangle_group: Vec<u32>,
    pub surface_groups: Vec<SurfaceGroup>,
    /// Line elements by group (the wells), in name order; empty without wells.
    pub lines: Vec<LineGroup>,
    /// Named nodes (the wells' crossings of the surfaces), in name order; empty without wells.
    pub points: Vec<NamedPoint>,
    /// The recipe's named groups of surface triangles, in name order; empty without `[groups]`.
    pub face_sets: Vec<FaceSet>,
}

impl VolumeMesh {
    /// Checks the index invariants (cheap; not the geometric ones).
    pub fn check_indices(&self) -> Result<(), String> {
        let n = self.nodes.len() as u32;
        if self.tet_region.len() != self.tets.len() {
            return Err(format!(
                "{} tets but {} region tags",
                self.tets.len(),
                self.tet_region.len()
            ));
        }
        if self.triangle_group.len() != self.triangles.len() {
            return Err(format!(
                "{} triangles but {} group tags",
                self.triangles.len(),
                self.triangle_group.len()
            ));
        }
        if let Some((i, t)) = self
            .tets
            .iter()
            .enumerate()
            .find(|(_, t)| t.iter().any(|&v| v >= n))
        {
            return Err(format!("tet {i} {t:?} references a node beyond {n}"));
        }
        if let Some((i, t)) = self
            .triangles
            .iter()
            .enumerate()
            .find(|(_, t)| t.iter().any(|&v| v >= n))
        {
            return Err(format!("triangle {i} {t:?} references a node beyond {n}"));
        }
        let nr = self.regions.len() as u32;
        if let Some(i) = self.tet_region.iter().position(|&r| r >= nr) {
            return Err(format!("tet {i} has region {} of {nr}", self.tet_region[i]));
        }
        let ng = self.surface_groups.len() as u32;
        if let Some(i) = self.triangle_group.iter().position(|&g| g >= ng) {
            return Err(format!(
                "triangle {i} has group {} of {ng}",
                self.triangle_group[i]
            ));
        }
        if let Some(g) = self
            .lines
            .iter()
            .find(|g| g.lines.iter().flatten().any(|&v| v >= n))
        {
            return Err(format!(
                "line group '{}' references a node beyond {n}",
                g.name
            ));
        }
        if let Some(p) = self.points.iter().find(|p| p.node >= n) {
            return Err(format!("point '{}' is node {}, beyond {n}", p.name, p.node));
        }
        let nt = self.triangles.len() as u32;
        if let Some(s) = (self.face_sets.iter()).find(|s| {
            s.triangles.windows(2).any(|w| w[0] >= w[1]) || s.triangles.last() >= Some(&nt)
        }) {
            return Err(format!(
                "face set '{}' is not an ascending list of triangles below {nt}",
                s.name
            ));
        }
        Ok(())
    }
}
