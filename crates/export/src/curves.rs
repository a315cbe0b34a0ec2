//! Writes named polylines (the model's discretized curves) as a VTK UnstructuredGrid (VTU) of
//! poly-line cells, so users can look at their curve subdivisions in ParaView before any mesh.
//! ASCII, deterministic bytes; point data `curve` (curve index) and field data with the names.

use std::fmt::Write as _;

/// `curves`: (name, nodes) in the order to write; returns the VTU document.
pub fn write_curves_vtu(curves: &[(String, Vec<[f64; 3]>)]) -> Vec<u8> {
    let npts: usize = curves.iter().map(|(_, n)| n.len()).sum();
    let mut s = String::with_capacity(64 * npts + 1024);
    s.push_str("<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n<UnstructuredGrid>\n");
    s.push_str("<FieldData>\n");
    for (i, (name, _)) in curves.iter().enumerate() {
        let _ = writeln!(
            s,
            "<Array type=\"UInt8\" Name=\"curve {i}: {}\" NumberOfTuples=\"1\" format=\"ascii\">0</Array>",
            xml_escape(name)
        );
    }
    s.push_str("</FieldData>\n");
    let _ = writeln!(
        s,
        "<Piece NumberOfPoints=\"{npts}\" NumberOfCells=\"{}\">",
        curves.len()
    );
    s.push_str(
        "<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n",
    );
    for (_, nodes) in curves {
        for p in nodes {
            let _ = writeln!(s, "{} {} {}", p[0], p[1], p[2]);
        }
    }
    s.push_str("</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n");
    let mut k = 0usize;
    for (_, nodes) in curves {
        joined(&mut s, k..k + nodes.len());
        s.push('\n');
        k += nodes.len();
    }
    s.push_str("</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n");
    let mut off = 0usize;
    for (_, nodes) in curves {
        off += nodes.len();
        let _ = write!(s, "{off} ");
    }
    s.push_str("\n</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n");
    joined(&mut s, std::iter::repeat_n(4, curves.len()));
    s.push_str("\n</DataArray>\n</Cells>\n<CellData Scalars=\"curve\">\n<DataArray type=\"Int32\" Name=\"curve\" format=\"ascii\">\n");
    joined(&mut s, 0..curves.len());
    s.push_str("\n</DataArray>\n</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n");
    s.shrink_to_fit();
    s.into_bytes()
}

/// Appends `items` separated by single spaces.
fn joined(s: &mut String, items: impl Iterator<Item = usize>) {
    for (i, v) in items.enumerate() {
        if i > 0 {
            s.push(' ');
        }
        let _ = write!(s, "{v}");
    }
}

fn xml_escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_curve_becomes_one_poly_line_cell_with_its_points() {
        let v = write_curves_vtu(&[
            ("a/b".into(), vec![[0.0; 3], [1.0, 0.0, 0.0]]),
            (
                "c#1".into(),
                vec![[0.0; 3], [0.0, 1.0, 0.0], [0.0, 1.0, 1.0]],
            ),
        ]);
        let s = String::from_utf8(v).unwrap();
        assert!(s.contains("NumberOfPoints=\"5\" NumberOfCells=\"2\""));
        assert!(s.contains("2 5 "));
        assert!(s.contains("curve 1: c#1"));
    }
}
