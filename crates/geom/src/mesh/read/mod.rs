//! Readers for closed boundary meshes given to the standalone mesher as a file: OFF, Wavefront
//! OBJ and Gmsh msh (4.1 ASCII and binary, 2.2 ASCII). They take bytes (the CLI reads the file)
//! and a label for messages, and return triangles with an integer tag per triangle (OBJ group,
//! msh entity) plus the tag names the file gives. Polygons are fan-triangulated; everything else
//! (normals, texture coordinates, lines, points) is skipped. The line readers
//! ([`read_lines_by_extension`]) take the lines of an OBJ (`l` polylines) or msh (line elements,
//! type 1) file instead: the segments the mesher embeds (well paths).
//!
//! Bad input never panics: every error names the file (label) and the line where it was found.
//! Non-finite coordinates and out-of-range indices are errors, not silently kept.

mod cursor;
mod msh;
mod msh_sections;
mod obj;
mod off;

pub use msh::{read_msh, read_msh_lines, read_volume_msh};
pub use obj::{read_obj, read_obj_lines};
pub use off::read_off;

use serde::Serialize;
use std::collections::BTreeMap;

/// A triangulated surface with tagged triangles (the input of the standalone mesher).
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct BoundaryMesh {
    pub vertices: Vec<[f64; 3]>,
    pub triangles: Vec<[u32; 3]>,
    /// One tag per triangle: OBJ group number (1.. in order of first use, 0 before any group),
    /// msh elementary entity tag, 0 for OFF.
    pub triangle_tag: Vec<i32>,
    /// Names of tags, where the file names them (OBJ group names, msh physical names).
    pub tag_names: BTreeMap<i32, String>,
}

/// Segments between vertices (the embedded lines of the standalone mesher).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LineMesh {
    pub vertices: Vec<[f64; 3]>,
    pub lines: Vec<[u32; 2]>,
}

/// A read error at `file:line`.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{file}:{line}: {message}")]
pub struct ReadError {
    pub file: String,
    pub line: usize,
    pub message: String,
}

/// Reads by the extension of `path_label` (`.off`, `.obj`, `.msh`; case-insensitive).
pub fn read_by_extension(path_label: &str, bytes: &[u8]) -> Result<BoundaryMesh, ReadError> {
    let ext = path_label
        .rsplit_once('.')
        .map(|(_, e)| e.to_ascii_lowercase())
        .unwrap_or_default();
    match ext.as_str() {
        "off" => read_off(bytes, path_label),
        "obj" => read_obj(bytes, path_label),
        "msh" => read_msh(bytes, path_label),
        _ => Err(ReadError {
            file: path_label.to_string(),
            line: 0,
            message: format!("unknown mesh file extension '.{ext}': expected .off, .obj or .msh"),
        }),
    }
}

/// Reads the lines of an `.obj` or `.msh` file, by the extension of `path_label`.
pub fn read_lines_by_extension(path_label: &str, bytes: &[u8]) -> Result<LineMesh, ReadError> {
    let ext = path_label
        .rsplit_once('.')
        .map(|(_, e)| e.to_ascii_lowercase())
        .unwrap_or_default();
    match ext.as_str() {
        "obj" => read_obj_lines(bytes, path_label),
        "msh" => read_msh_lines(bytes, path_label),
        _ => Err(ReadError {
            file: path_label.to_string(),
            line: 0,
            message: format!("unknown line file extension '.{ext}': expected .obj or .msh"),
        }),
    }
}

/// Fan-triangulates polygon `poly` (already 0-based indices) into `out`.
pub(crate) fn fan(poly: &[u32], tag: i32, out: &mut BoundaryMesh) {
    for k in 1..poly.len().saturating_sub(1) {
        out.triangles.push([poly[0], poly[k], poly[k + 1]]);
        out.triangle_tag.push(tag);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_unknown_extension_is_an_error_naming_the_file() {
        let e = read_by_extension("model.stl", b"solid").unwrap_err();
        assert_eq!(e.file, "model.stl");
        assert!(
            e.to_string()
                .starts_with("model.stl:0: unknown mesh file extension '.stl'"),
            "{e}"
        );
    }

    #[test]
    fn the_extension_picks_the_reader_whatever_its_case() {
        let m =
            read_by_extension("a/b.OFF", b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n").unwrap();
        assert_eq!(m.triangles, vec![[0, 1, 2]]);
    }
}
