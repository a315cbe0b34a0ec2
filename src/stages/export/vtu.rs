//! VTK XML UnstructuredGrid (`.vtu`) writer, ASCII data arrays.
//!
//! Cells: every tet (VTK type 10) in index order, then every surface triangle (type 5), so
//! faults, horizons and box sides can be shown and selected. Cell data: "region" (region index,
//! -1 on triangles), "material" (material id, -1 where none and on triangles), "surface"
//! (surface group index, -1 on tets), and one Float64 array per region property (NaN where
//! undefined). Names travel as field data: one single-value Int32 array per region, named
//! `region:<name>` holding the region index, and one per surface group, `surface:<name>` holding
//! the group index (string arrays are not read by every VTU reader; this is).

use super::property_names;
use crate::mesh::VolumeMesh;
use std::fmt::Write as _;

fn xml_escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            c if c.is_control() => out.push(' '),
            c => out.push(c),
        }
    }
    out
}

/// Writes a data array, `per_line` values per line.
fn array<T: std::fmt::Display>(
    s: &mut String,
    ty: &str,
    name: &str,
    comps: usize,
    vals: impl Iterator<Item = T>,
) {
    let comp = if comps > 1 {
        format!(" NumberOfComponents=\"{comps}\"")
    } else {
        String::new()
    };
    let _ = writeln!(
        s,
        "<DataArray type=\"{ty}\" Name=\"{}\"{comp} format=\"ascii\">",
        xml_escape(name)
    );
    let per_line = if comps > 1 { comps } else { 12 };
    let mut k = 0;
    for v in vals {
        if k > 0 {
            s.push(if k % per_line == 0 { '\n' } else { ' ' });
        }
        let _ = write!(s, "{v}");
        k += 1;
    }
    if k > 0 {
        s.push('\n');
    }
    s.push_str("</DataArray>\n");
}

pub(super) fn write(mesh: &VolumeMesh) -> Vec<u8> {
    let nt = mesh.tets.len();
    let nf = mesh.triangles.len();
    let mut s = String::new();
    s.push_str("<?xml version=\"1.0\"?>\n");
    s.push_str("<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n");
    s.push_str("<UnstructuredGrid>\n");
    s.push_str("<FieldData>\n");
    for (r, rg) in mesh.regions.iter().enumerate() {
        let _ = writeln!(
            s,
            "<DataArray type=\"Int32\" Name=\"region:{}\" NumberOfTuples=\"1\" format=\"ascii\">{r}</DataArray>",
            xml_escape(&rg.name)
        );
    }
    for (g, sg) in mesh.surface_groups.iter().enumerate() {
        let _ = writeln!(
            s,
            "<DataArray type=\"Int32\" Name=\"surface:{}\" NumberOfTuples=\"1\" format=\"ascii\">{g}</DataArray>",
            xml_escape(&sg.name)
        );
    }
    s.push_str("</FieldData>\n");
    let _ = writeln!(
        s,
        "<Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">",
        mesh.nodes.len(),
        nt + nf
    );
    s.push_str("<Points>\n");
    array(&mut s, "Float64", "Points", 3, mesh.nodes.iter().flatten());
    s.push_str("</Points>\n<Cells>\n");
    let conn = mesh
        .tets
        .iter()
        .flat_map(|t| t.iter())
        .chain(mesh.triangles.iter().flat_map(|t| t.iter()));
    array(&mut s, "Int64", "connectivity", 1, conn);
    let offsets = (1..=nt)
        .map(|i| 4 * i)
        .chain((1..=nf).map(|i| 4 * nt + 3 * i));
    array(&mut s, "Int64", "offsets", 1, offsets);
    let types = std::iter::repeat_n(10u8, nt).chain(std::iter::repeat_n(5u8, nf));
    array(&mut s, "UInt8", "types", 1, types);
    s.push_str("</Cells>\n<CellData Scalars=\"region\">\n");
    let region = mesh
        .tet_region
        .iter()
        .map(|&r| r as i64)
        .chain(std::iter::repeat_n(-1, nf));
    array(&mut s, "Int32", "region", 1, region);
    let material = mesh
        .tet_region
        .iter()
        .map(|&r| {
            mesh.regions
                .get(r as usize)
                .and_then(|g| g.material)
                .unwrap_or(-1)
        })
        .chain(std::iter::repeat_n(-1, nf));
    array(&mut s, "Int64", "material", 1, material);
    let surface =
        std::iter::repeat_n(-1i64, nt).chain(mesh.triangle_group.iter().map(|&g| g as i64));
    array(&mut s, "Int32", "surface", 1, surface);
    for name in property_names(mesh) {
        let vals = mesh
            .tet_region
            .iter()
            .map(|&r| {
                mesh.regions
                    .get(r as usize)
                    .and_then(|g| g.properties.get(&name).copied())
                    .unwrap_or(f64::NAN)
            })
            .chain(std::iter::repeat_n(f64::NAN, nf))
            .map(|v| {
                if v.is_nan() {
                    "nan".to_string()
                } else {
                    v.to_string()
                }
            });
        array(&mut s, "Float64", &name, 1, vals);
    }
    s.push_str("</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n");
    s.into_bytes()
}
