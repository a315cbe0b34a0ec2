//! VTK XML UnstructuredGrid (`.vtu`) writer, with ASCII data arrays or raw appended binary
//! (little-endian, `UInt64` headers) for large meshes.
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

/// A typed data array.
enum Data {
    F64(Vec<f64>),
    I64(Vec<i64>),
    I32(Vec<i32>),
    U8(Vec<u8>),
}

impl Data {
    fn vtk_type(&self) -> &'static str {
        match self {
            Data::F64(_) => "Float64",
            Data::I64(_) => "Int64",
            Data::I32(_) => "Int32",
            Data::U8(_) => "UInt8",
        }
    }
    fn len(&self) -> usize {
        match self {
            Data::F64(v) => v.len(),
            Data::I64(v) => v.len(),
            Data::I32(v) => v.len(),
            Data::U8(v) => v.len(),
        }
    }
    fn ascii(&self, i: usize) -> String {
        match self {
            Data::F64(v) if v[i].is_nan() => "nan".to_string(),
            Data::F64(v) => v[i].to_string(),
            Data::I64(v) => v[i].to_string(),
            Data::I32(v) => v[i].to_string(),
            Data::U8(v) => v[i].to_string(),
        }
    }
    fn raw(&self, out: &mut Vec<u8>) {
        match self {
            Data::F64(v) => v
                .iter()
                .for_each(|x| out.extend_from_slice(&x.to_le_bytes())),
            Data::I64(v) => v
                .iter()
                .for_each(|x| out.extend_from_slice(&x.to_le_bytes())),
            Data::I32(v) => v
                .iter()
                .for_each(|x| out.extend_from_slice(&x.to_le_bytes())),
            Data::U8(v) => out.extend_from_slice(v),
        }
    }
}

/// Collects the XML and, in binary mode, the appended raw block.
struct Writer {
    xml: String,
    appended: Option<Vec<u8>>,
}

impl Writer {
    fn array(&mut self, name: &str, comps: usize, data: Data) {
        let comp = if comps > 1 {
            format!(" NumberOfComponents=\"{comps}\"")
        } else {
            String::new()
        };
        let head = format!(
            "<DataArray type=\"{}\" Name=\"{}\"{comp}",
            data.vtk_type(),
            xml_escape(name)
        );
        match &mut self.appended {
            Some(raw) => {
                let _ = writeln!(
                    self.xml,
                    "{head} format=\"appended\" offset=\"{}\"/>",
                    raw.len()
                );
                let mut body = Vec::new();
                data.raw(&mut body);
                raw.extend_from_slice(&(body.len() as u64).to_le_bytes());
                raw.extend_from_slice(&body);
            }
            None => {
                let _ = writeln!(self.xml, "{head} format=\"ascii\">");
                let per_line = if comps > 1 { comps } else { 12 };
                for i in 0..data.len() {
                    if i > 0 {
                        self.xml.push(if i % per_line == 0 { '\n' } else { ' ' });
                    }
                    self.xml.push_str(&data.ascii(i));
                }
                if data.len() > 0 {
                    self.xml.push('\n');
                }
                self.xml.push_str("</DataArray>\n");
            }
        }
    }
}

pub(super) fn write(mesh: &VolumeMesh, binary: bool) -> Vec<u8> {
    let nt = mesh.tets.len();
    let nf = mesh.triangles.len();
    let mut w = Writer {
        xml: String::new(),
        appended: binary.then(Vec::new),
    };
    let s = &mut w.xml;
    s.push_str("<?xml version=\"1.0\"?>\n");
    s.push_str("<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n");
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
    w.array(
        "Points",
        3,
        Data::F64(mesh.nodes.iter().flatten().copied().collect()),
    );
    w.xml.push_str("</Points>\n<Cells>\n");
    let conn = mesh
        .tets
        .iter()
        .flat_map(|t| t.iter())
        .chain(mesh.triangles.iter().flat_map(|t| t.iter()));
    w.array(
        "connectivity",
        1,
        Data::I64(conn.map(|&v| v as i64).collect()),
    );
    let offsets = (1..=nt)
        .map(|i| 4 * i)
        .chain((1..=nf).map(|i| 4 * nt + 3 * i));
    w.array("offsets", 1, Data::I64(offsets.map(|v| v as i64).collect()));
    let types = std::iter::repeat_n(10u8, nt).chain(std::iter::repeat_n(5u8, nf));
    w.array("types", 1, Data::U8(types.collect()));
    w.xml.push_str("</Cells>\n<CellData Scalars=\"region\">\n");
    let region = mesh
        .tet_region
        .iter()
        .map(|&r| r as i32)
        .chain(std::iter::repeat_n(-1, nf));
    w.array("region", 1, Data::I32(region.collect()));
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
    w.array("material", 1, Data::I64(material.collect()));
    let surface =
        std::iter::repeat_n(-1i32, nt).chain(mesh.triangle_group.iter().map(|&g| g as i32));
    w.array("surface", 1, Data::I32(surface.collect()));
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
            .chain(std::iter::repeat_n(f64::NAN, nf));
        w.array(&name, 1, Data::F64(vals.collect()));
    }
    w.xml
        .push_str("</CellData>\n</Piece>\n</UnstructuredGrid>\n");
    let mut out = w.xml.into_bytes();
    if let Some(raw) = w.appended {
        out.extend_from_slice(b"<AppendedData encoding=\"raw\">\n_");
        out.extend_from_slice(&raw);
        out.extend_from_slice(b"\n</AppendedData>\n");
    }
    out.extend_from_slice(b"</VTKFile>\n");
    out
}
