//! Stage `export`: writes a finished [`VolumeMesh`] in the formats downstream solvers read, as
//! named byte buffers (the CLI writes them to disk). Every region becomes a 3D group and every
//! surface group (surface, fault, box side) a 2D group under the same names and ids in every
//! format: region `r` has id `r + 1`, surface group `g` has id `g + 1`. The recipe's attributes
//! (material id, numeric properties) travel as cell data wherever the format can carry them.
//!
//! Output bytes are a pure function of the mesh and the model name: no timestamps, no hash-order
//! iteration, floats printed with Rust's shortest round-trip formatting.

pub mod curves;
mod exodus;
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
    /// VTK XML UnstructuredGrid (ASCII).
    Vtu,
    /// VTK XML UnstructuredGrid with raw appended binary data (for large meshes).
    VtuBinary,
    /// TetGen `.node` / `.ele` / `.face`.
    TetGen,
    /// MEDIT `.mesh` (INRIA), as read by mmg and meshio.
    Medit,
    /// Abaqus `.inp` (C3D4 elements, a material and a solid section per region, node sets and
    /// element-face surfaces per surface group, a surface per fault side).
    Inp,
    /// Exodus II `.exo` (netCDF 64-bit offset): an element block per region, a side set and a
    /// node set per surface group, a front and a back side set per fault.
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

/// Writes `mesh` in `format`. Returns `(file name, bytes)` pairs: file names are `model_name`
/// plus the format's extension (`didactic.msh`, `didactic.1.node`, ...). Fails with a message on
/// a mesh whose indices are out of range or a model name that cannot be a file name. The mesh's
/// line groups (wells): msh writes each as a curve entity of line elements (type 1) with a 1D
/// physical group of the group's name; the other formats take no lines (an error if some are
/// given).
pub fn export(
    mesh: &VolumeMesh,
    model_name: &str,
    format: Format,
) -> Result<Vec<(String, Vec<u8>)>, String> {
    mesh.check_indices()
        .map_err(|e| format!("cannot export model '{model_name}': {e}"))?;
    if mesh.lines.iter().any(|g| !g.lines.is_empty())
        && !matches!(format, Format::Msh | Format::MshBinary)
    {
        return Err(format!(
            "cannot export model '{model_name}' with line elements as {format:?}: only msh takes them"
        ));
    }
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
        Format::TetGen => Vec::from(tetgen::write(mesh, model_name)),
        Format::Medit => vec![medit::write(mesh)],
        Format::Inp => vec![inp::write(mesh, model_name)?],
        Format::Exodus => vec![exodus::write(mesh, model_name)?],
    };
    Ok(file_names(model_name, format)
        .into_iter()
        .zip(contents)
        .collect())
}

/// The names of the files [`export`] writes for `format`, in the order it returns them
/// (known before any is written, so a caller can produce them in its own order).
pub fn file_names(model_name: &str, format: Format) -> Vec<String> {
    let exts: &[&str] = match format {
        Format::Msh | Format::MshBinary => &["msh"],
        Format::Vtu | Format::VtuBinary => &["vtu"],
        Format::TetGen => &["1.node", "1.ele", "1.face"],
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
        for f in all {
            let files = export(&VolumeMesh::default(), "m", f).unwrap();
            let names: Vec<String> = files.into_iter().map(|(n, _)| n).collect();
            assert_eq!(names, file_names("m", f), "{f:?}");
        }
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
