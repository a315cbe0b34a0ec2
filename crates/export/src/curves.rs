//! Writes named polylines (the model's discretized curves) as a VTK UnstructuredGrid (VTU), so
//! users can look at their curve subdivisions in ParaView before any mesh. Each segment is one
//! line cell (VTK type 3) rather than each curve one poly-line: meshio reads lines and not
//! poly-lines, and ParaView shows both alike. Cell data `curve` holds the curve's id (its index
//! plus one, the crate's one scheme); the names table is field data, `curve:<name>` holding the
//! id, as the volume VTU names its regions. ASCII, deterministic bytes.

use crate::vtu::writer::Writer;

/// `curves`: (name, nodes) in the order to write; returns the VTU document.
pub fn write_curves_vtu(curves: &[(String, Vec<[f64; 3]>)]) -> Vec<u8> {
    let npts: usize = curves.iter().map(|(_, n)| n.len()).sum();
    let segments = || {
        let mut first = 0;
        curves.iter().enumerate().flat_map(move |(c, (_, nodes))| {
            let start = first;
            first += nodes.len();
            (1..nodes.len()).map(move |k| (c, start + k - 1))
        })
    };
    let ncells = segments().count();
    let mut w = Writer::new(false, 0);
    w.xml.push_str("<FieldData>\n");
    for (c, (name, _)) in curves.iter().enumerate() {
        w.field_int(&format!("curve:{name}"), c as i64 + 1);
    }
    w.xml.push_str(&format!(
        "</FieldData>\n<Piece NumberOfPoints=\"{npts}\" NumberOfCells=\"{ncells}\">\n<Points>\n"
    ));
    w.array(
        "Points",
        3,
        curves.iter().flat_map(|(_, n)| n.iter().flatten().copied()),
    );
    w.xml.push_str("</Points>\n<Cells>\n");
    w.indices("connectivity", npts, || {
        segments().flat_map(|(_, a)| [a, a + 1])
    });
    w.indices("offsets", 2 * ncells, || (1..=ncells).map(|i| 2 * i));
    w.array("types", 1, std::iter::repeat_n(3u8, ncells));
    w.xml.push_str("</Cells>\n<CellData Scalars=\"curve\">\n");
    w.array("curve", 1, segments().map(|(c, _)| c as i32 + 1));
    w.xml.push_str("</CellData>\n");
    w.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_segment_becomes_one_line_cell_of_its_curve() {
        let v = write_curves_vtu(&[
            ("a/b".into(), vec![[0.0; 3], [1.0, 0.0, 0.0]]),
            (
                "c#1".into(),
                vec![[0.0; 3], [0.0, 1.0, 0.0], [0.0, 1.0, 1.0]],
            ),
        ]);
        let s = String::from_utf8(v).unwrap();
        assert!(
            s.contains("NumberOfPoints=\"5\" NumberOfCells=\"3\""),
            "{s}"
        );
        assert!(s.contains("0 1 2 3 3 4\n"), "{s}");
        assert!(
            s.contains("Name=\"types\" format=\"ascii\">\n3 3 3\n"),
            "{s}"
        );
        assert!(
            s.contains("Name=\"curve\" format=\"ascii\">\n1 2 2\n"),
            "{s}"
        );
        assert!(s.contains("Name=\"curve:c#1\" NumberOfTuples=\"1\" format=\"ascii\">2<"));
    }
}
