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
use geom::mesh::VolumeMesh;
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

/// A value type of a data array: its VTK name and its two spellings.
trait Value: Copy {
    const VTK: &'static str;
    /// Appends the ASCII text (Rust's shortest round-trip `Display`; `nan` for NaN).
    fn ascii(self, out: &mut String);
    /// Appends the little-endian bytes.
    fn raw(self, out: &mut Vec<u8>);
}

impl Value for f64 {
    const VTK: &'static str = "Float64";
    fn ascii(self, out: &mut String) {
        if self.is_nan() {
            out.push_str("nan");
        } else {
            let _ = write!(out, "{self}");
        }
    }
    fn raw(self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.to_le_bytes());
    }
}

macro_rules! int_value {
    ($t:ty, $name:literal) => {
        impl Value for $t {
            const VTK: &'static str = $name;
            fn ascii(self, out: &mut String) {
                let _ = write!(out, "{self}");
            }
            fn raw(self, out: &mut Vec<u8>) {
                out.extend_from_slice(&self.to_le_bytes());
            }
        }
    };
}
int_value!(i64, "Int64");
int_value!(i32, "Int32");
int_value!(u8, "UInt8");

/// Collects the XML and, in binary mode, the appended raw block. Values are written straight
/// from the mesh into these buffers: no array is materialized and no value gets a `String`.
struct Writer {
    xml: String,
    appended: Option<Vec<u8>>,
}

impl Writer {
    fn array<T: Value>(&mut self, name: &str, comps: usize, values: impl Iterator<Item = T>) {
        let _ = write!(
            self.xml,
            "<DataArray type=\"{}\" Name=\"{}\"",
            T::VTK,
            xml_escape(name)
        );
        if comps > 1 {
            let _ = write!(self.xml, " NumberOfComponents=\"{comps}\"");
        }
        match &mut self.appended {
            Some(raw) => {
                let _ = writeln!(self.xml, " format=\"appended\" offset=\"{}\"/>", raw.len());
                // The block's byte count, patched once the values are written.
                let at = raw.len();
                raw.extend_from_slice(&0u64.to_le_bytes());
                values.for_each(|v| v.raw(raw));
                let len = (raw.len() - at - 8) as u64;
                raw[at..at + 8].copy_from_slice(&len.to_le_bytes());
            }
            None => {
                self.xml.push_str(" format=\"ascii\">\n");
                let per_line = if comps > 1 { comps } else { 12 };
                let mut n = 0usize;
                for v in values {
                    if n > 0 {
                        self.xml.push(if n.is_multiple_of(per_line) {
                            '\n'
                        } else {
                            ' '
                        });
                    }
                    v.ascii(&mut self.xml);
                    n += 1;
                }
                if n > 0 {
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
    let props = property_names(mesh);
    let mut w = Writer {
        xml: String::new(),
        appended: binary.then(|| Vec::with_capacity(raw_len(mesh, props.len()))),
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
    w.array("Points", 3, mesh.nodes.iter().flatten().copied());
    w.xml.push_str("</Points>\n<Cells>\n");
    let conn = mesh
        .tets
        .iter()
        .flat_map(|t| t.iter())
        .chain(mesh.triangles.iter().flat_map(|t| t.iter()));
    w.array("connectivity", 1, conn.map(|&v| i64::from(v)));
    let offsets = (1..=nt)
        .map(|i| 4 * i)
        .chain((1..=nf).map(|i| 4 * nt + 3 * i));
    w.array("offsets", 1, offsets.map(|v| v as i64));
    let types = std::iter::repeat_n(10u8, nt).chain(std::iter::repeat_n(5u8, nf));
    w.array("types", 1, types);
    w.xml.push_str("</Cells>\n<CellData Scalars=\"region\">\n");
    let region = mesh
        .tet_region
        .iter()
        .map(|&r| r as i32)
        .chain(std::iter::repeat_n(-1, nf));
    w.array("region", 1, region);
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
    w.array("material", 1, material);
    let surface =
        std::iter::repeat_n(-1i32, nt).chain(mesh.triangle_group.iter().map(|&g| g as i32));
    w.array("surface", 1, surface);
    for name in &props {
        let vals = mesh
            .tet_region
            .iter()
            .map(|&r| {
                mesh.regions
                    .get(r as usize)
                    .and_then(|g| g.properties.get(name).copied())
                    .unwrap_or(f64::NAN)
            })
            .chain(std::iter::repeat_n(f64::NAN, nf));
        w.array(name, 1, vals);
    }
    w.xml
        .push_str("</CellData>\n</Piece>\n</UnstructuredGrid>\n");
    match w.appended {
        None => {
            w.xml.push_str("</VTKFile>\n");
            w.xml.shrink_to_fit();
            w.xml.into_bytes()
        }
        Some(mut raw) => {
            // The (small) XML goes in front of the raw block in place: one move, no copy of
            // the block into a second buffer.
            w.xml.push_str("<AppendedData encoding=\"raw\">\n_");
            let head = w.xml.as_bytes();
            let tail = b"\n</AppendedData>\n</VTKFile>\n";
            let body = raw.len();
            raw.reserve_exact(head.len() + tail.len());
            raw.resize(body + head.len(), 0);
            raw.copy_within(..body, head.len());
            raw[..head.len()].copy_from_slice(head);
            raw.extend_from_slice(tail);
            raw.shrink_to_fit();
            raw
        }
    }
}

/// The exact size of the appended block: each array's 8-byte count and its values.
fn raw_len(mesh: &VolumeMesh, n_props: usize) -> usize {
    let (nt, nf) = (mesh.tets.len(), mesh.triangles.len());
    let cells = nt + nf;
    let header = 8 * (7 + n_props);
    let points = 3 * 8 * mesh.nodes.len();
    let cells_part = 8 * (4 * nt + 3 * nf) + cells * (8 + 1 + 4 + 8 + 4 + 8 * n_props);
    header + points + cells_part
}
