//! Stage `export`: writes a finished [`VolumeMesh`] in the formats downstream solvers read, as
//! named byte buffers (the CLI writes them to disk). Every region becomes a 3D group, every
//! surface group (surface, fault, box side) a 2D group and every line group (well) a group of
//! 2-node line elements under the same names and ids in every format: region `r` has id `r + 1`,
//! surface group `g` has id `g + 1`, line group `w` has id `w + 1` (Exodus, whose element block
//! and node set ids must differ from the regions' and the surface groups', numbers the wells'
//! on after those). The recipe's attributes (material id, numeric properties) travel as cell
//! data wherever the format can carry them. A mesh without line groups is written exactly as
//! before line groups existed, in every format, and one without named points (the wells'
//! crossings of the surfaces) as before those existed.
//!
//! Output bytes are a pure function of the mesh, the model name and the [`Provenance`] the caller
//! gives (what built the mesh, which only Exodus records): no timestamps, no hash-order iteration,
//! floats printed with Rust's shortest round-trip formatting.

pub mod curves;
mod exodus;
mod face_sets;
pub mod ids;
mod inp;
mod medit;
mod msh;
mod netcdf;
mod numbering;
pub mod quality;
mod sides;
mod tetgen;
mod vtu;

use geom::mesh::VolumeMesh;
use std::collections::BTreeSet;

/// An output format.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Format {
    /// Gmsh msh 4.1, ASCII.
    Msh,
    /// Gmsh msh 4.1, binary (little-endian, size_t = 8).
    MshBinary,
    /// VTK XML UnstructuredGrid (ASCII), with a copy of each fault's triangles per side.
    Vtu,
    /// VTK XML UnstructuredGrid with raw appended binary data (for large meshes).
    VtuBinary,
    /// TetGen `.node` / `.ele` / `.face` (each face with the tets on its front and back), and
    /// `.edge` for a mesh with line groups.
    TetGen,
    /// MEDIT `.mesh` (INRIA), as read by mmg and meshio.
    Medit,
    /// Abaqus `.inp` (C3D4 elements, a material and a solid section per region, node sets and
    /// element-face surfaces per surface group, a surface per fault side, T3D2 elements per
    /// well).
    Inp,
    /// Exodus II `.exo` (netCDF 64-bit offset): an element block per region, a side set and a
    /// node set per surface group, a front and a back side set per fault, a BAR2 element block
    /// and a node set per well.
    Exodus,
}

impl Format {
    /// Every format, in a fixed order (for help texts and "all").
    pub const ALL: [Format; 6] = [
        Format::Msh,
        Format::MshBinary,
        Format::Vtu,
        Format::TetGen,
        Format::Medit,
        Format::Exodus,
    ];

    /// Every format the writers know, including those a recipe cannot name yet (VTU binary,
    /// Abaqus), in a fixed order.
    pub const EVERY: [Format; 8] = [
        Format::Msh,
        Format::MshBinary,
        Format::Vtu,
        Format::VtuBinary,
        Format::TetGen,
        Format::Medit,
        Format::Inp,
        Format::Exodus,
    ];

    /// Parses a recipe/CLI name (case-insensitive; a few aliases).
    pub fn from_name(s: &str) -> Option<Format> {
        match s.trim().to_ascii_lowercase().as_str() {
            "msh" | "gmsh" | "msh4" | "msh41" => Some(Format::Msh),
            "msh-binary" | "msh_binary" | "mshbinary" | "msh-bin" | "gmsh-binary" => {
                Some(Format::MshBinary)
            }
            "vtu" | "vtk" => Some(Format::Vtu),
            "vtu-binary" | "vtu_binary" | "vtu-bin" => Some(Format::VtuBinary),
            "tetgen" | "node" | "ele" => Some(Format::TetGen),
            "medit" | "mesh" => Some(Format::Medit),
            "inp" | "abaqus" | "calculix" => Some(Format::Inp),
            "exodus" | "exo" | "exodusii" | "e" => Some(Format::Exodus),
            _ => None,
        }
    }

    /// The canonical name (accepted back by [`Format::from_name`]).
    pub fn name(&self) -> &'static str {
        match self {
            Format::Msh => "msh",
            Format::MshBinary => "msh-binary",
            Format::Vtu => "vtu",
            Format::VtuBinary => "vtu-binary",
            Format::TetGen => "tetgen",
            Format::Medit => "medit",
            Format::Inp => "inp",
            Format::Exodus => "exodus",
        }
    }
}

/// What a file records about the build that made it, so a file met later can be traced to the
/// recipe and the lock file entry it came from. Only Exodus has a place for it (its QA and info
/// records); an empty provenance records nothing, as [`export`] writes.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Provenance {
    /// The recipe's file name (no directory, so the bytes do not depend on where it lies).
    pub recipe: String,
    /// A hash that identifies the build inputs, in hex: the export node's key as the lock file
    /// records it.
    pub key: String,
}

/// Writes `mesh` in `format`, with an empty [`Provenance`]: see [`export_with`].
pub fn export(
    mesh: &VolumeMesh,
    model_name: &str,
    format: Format,
) -> Result<Vec<(String, Vec<u8>)>, String> {
    export_with(mesh, model_name, format, &Provenance::default())
}

/// Writes `mesh` in `format`, recording `provenance` where the format can. Returns `(file name, bytes)` pairs: file names are `model_name`
/// plus the format's extension (`didactic.msh`, `didactic.1.node`, ...), as [`file_names`]
/// lists them. Fails with a message on a mesh whose indices are out of range or a model name
/// that cannot be a file name.
///
/// The mesh's line groups (wells) go into every format, each in its own way, under the group's
/// name where the format has names and its id (`w + 1`) where it has tags:
/// - msh: a curve entity of line elements (type 1) per group, with a 1D physical group of the
///   group's name;
/// - VTU: line cells (VTK type 3) after the triangles, an Int32 `well` cell array (the group's
///   id on lines, -1 elsewhere; -1 and NaN on lines in the other arrays) and `well:<name>`
///   field data;
/// - Exodus II: a `BAR2` element block per group with lines, after the regions' blocks and
///   named after it, and a node set of its nodes under its name (meshio names no block);
/// - MEDIT: an `Edges` section, the reference being the group's id;
/// - TetGen: a `<model>.1.edge` file, the boundary marker being the group's id (written only
///   when the mesh has line groups);
/// - Abaqus: a `*Element, type=T3D2, elset=<name>` block per group with lines, numbered after
///   the tets (without a section, which needs the well's cross-section area).
///
/// The mesh's named points (where a well crosses a surface, `<well>:<surface>`) go where the
/// format can name a node:
/// - msh: a point entity, a point element (type 15) and a 0D physical group of the point's name
///   each (tags `i + 1`);
/// - Exodus II: a one-node node set each, named after it, ids after the wells' node sets;
/// - VTU: `point:<name>` field data holding the node's 0-based index;
/// - Abaqus: a one-node `*Nset` each (the name made Abaqus-safe);
/// - MEDIT and TetGen: not written (they have no named node sets; see their modules).
///
/// A mesh without named points is written exactly as before they existed.
pub fn export_with(
    mesh: &VolumeMesh,
    model_name: &str,
    format: Format,
    provenance: &Provenance,
) -> Result<Vec<(String, Vec<u8>)>, String> {
    mesh.check_indices()
        .map_err(|e| format!("cannot export model '{model_name}': {e}"))?;
    if model_name.is_empty()
        || model_name.contains(['/', '\\'])
        || model_name.chars().any(char::is_control)
    {
        return Err(format!(
            "model name '{model_name}' cannot be used as a file name"
        ));
    }
    let lines = &mesh.lines;
    let contents = match format {
        Format::Msh => vec![msh::write(mesh, lines, false)],
        Format::MshBinary => vec![msh::write(mesh, lines, true)],
        Format::Vtu => vec![vtu::write(mesh, false)?],
        Format::VtuBinary => vec![vtu::write(mesh, true)?],
        Format::TetGen => tetgen::write(mesh, model_name),
        Format::Medit => vec![medit::write(mesh)],
        Format::Inp => vec![inp::write(mesh, model_name)?],
        Format::Exodus => vec![exodus::write(mesh, model_name, provenance)?],
    };
    Ok(file_names(model_name, format, mesh)
        .into_iter()
        .zip(contents)
        .collect())
}

/// The names of the files [`export`] writes for `mesh` in `format`, in the order it returns
/// them (known before any is written, so a caller can produce them in its own order). They
/// depend on the mesh only through its line groups: TetGen's `.edge` file is written only for a
/// mesh that has some.
pub fn file_names(model_name: &str, format: Format, mesh: &VolumeMesh) -> Vec<String> {
    let exts: &[&str] = match format {
        Format::Msh | Format::MshBinary => &["msh"],
        Format::Vtu | Format::VtuBinary => &["vtu"],
        Format::TetGen if mesh.lines.is_empty() => &["1.node", "1.ele", "1.face"],
        Format::TetGen => &["1.node", "1.ele", "1.face", "1.edge"],
        Format::Medit => &["mesh"],
        Format::Inp => &["inp"],
        Format::Exodus => &["exo"],
    };
    exts.iter().map(|e| format!("{model_name}.{e}")).collect()
}

/// The union of the regions' property names, sorted.
pub(crate) fn property_names(mesh: &VolumeMesh) -> Vec<String> {
    let set: BTreeSet<&String> = mesh
        .regions
        .iter()
        .flat_map(|r| r.properties.keys())
        .collect();
    set.into_iter().cloned().collect()
}

/// Bounding box `[min, max]` of the nodes used by `elems` (zeros when none).
pub(crate) fn bbox_of<'a>(
    mesh: &VolumeMesh,
    elems: impl Iterator<Item = &'a [u32]>,
) -> [[f64; 3]; 2] {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for e in elems {
        for &v in e {
            if let Some(p) = mesh.nodes.get(v as usize) {
                for k in 0..3 {
                    lo[k] = lo[k].min(p[k]);
                    hi[k] = hi[k].max(p[k]);
                }
            }
        }
    }
    if lo[0] > hi[0] {
        [[0.0; 3]; 2]
    } else {
        [lo, hi]
    }
}

/// Element indices per group tag, in index order (tags are checked in range by `export`).
pub(crate) fn split_by(tags: &[u32], n: usize) -> Vec<Vec<usize>> {
    let mut out = vec![Vec::new(); n];
    for (i, &g) in tags.iter().enumerate() {
        if let Some(v) = out.get_mut(g as usize) {
            v.push(i);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_format_name_parses_back_to_itself() {
        for f in Format::ALL {
            assert_eq!(Format::from_name(f.name()), Some(f));
        }
        assert_eq!(Format::from_name("GMSH"), Some(Format::Msh));
        assert_eq!(Format::from_name("stl"), None);
    }

    #[test]
    fn file_names_are_the_names_export_returns_in_order() {
        let all = [Format::VtuBinary, Format::Inp]
            .into_iter()
            .chain(Format::ALL);
        let well = VolumeMesh {
            nodes: vec![[0.0; 3], [0.0, 0.0, -1.0]],
            lines: vec![geom::mesh::LineGroup {
                area: None,
                name: "W".into(),
                lines: vec![[0, 1]],
            }],
            ..Default::default()
        };
        for f in all {
            for mesh in [&VolumeMesh::default(), &well] {
                let files = export(mesh, "m", f).unwrap();
                let names: Vec<String> = files.into_iter().map(|(n, _)| n).collect();
                assert_eq!(names, file_names("m", f, mesh), "{f:?}");
            }
        }
        assert_eq!(file_names("m", Format::TetGen, &well)[3], "m.1.edge");
    }

    #[test]
    fn an_empty_mesh_exports_in_every_format_without_panicking() {
        for f in Format::ALL {
            let files = export(&VolumeMesh::default(), "empty", f).unwrap();
            assert!(
                files.iter().all(|(name, _)| name.starts_with("empty.")),
                "{f:?}"
            );
        }
        assert!(export(&VolumeMesh::default(), "a/b", Format::Msh).is_err());
        assert!(export(&VolumeMesh::default(), "a\nb", Format::Inp).is_err());
    }

    #[test]
    fn an_out_of_range_region_tag_is_refused_with_the_model_name() {
        let mesh = VolumeMesh {
            nodes: vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            tets: vec![[0, 1, 2, 3]],
            tet_region: vec![3],
            ..Default::default()
        };
        let err = export(&mesh, "m", Format::Msh).unwrap_err();
        assert!(err.contains("'m'") && err.contains("region 3"), "{err}");
    }
}
