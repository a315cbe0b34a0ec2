//! VTK XML UnstructuredGrid (`.vtu`) writer, for ParaView, PyVista, meshio and OpenGeoSys, with
//! ASCII data arrays or raw appended binary for large meshes.
//!
//! Cells: every tet (VTK type 10) in index order, then every surface triangle (type 5), so
//! faults, horizons and box sides can be shown and selected. Ids follow the crate's one scheme
//! (region `r` is `r + 1`, surface group `g` is `g + 1`); -1 means "none" in every cell array.
//! Cell data ([`cell_data`]): `MaterialIDs` (Int32, the OpenGeoSys convention: the region's
//! material id; -1 for a region without a material and on triangles), `region` (region id, -1 on
//! triangles), `surface` (surface group id, -1 on tets), and one Float64 array per region
//! property (NaN where undefined). The names table is field data: one single-value Int32 array
//! per region, `region:<name>` holding its id, and per surface group, `surface:<name>` (VTU
//! string arrays are not read by meshio; these are, as by VTK). Connectivity and offsets are
//! Int32 whenever they fit and cell types UInt8, so the binary file is smaller than the ASCII.

mod cell_data;
pub(crate) mod writer;

use geom::mesh::VolumeMesh;
use writer::Writer;

/// Fails when a material id does not fit `MaterialIDs`' Int32.
pub(super) fn write(mesh: &VolumeMesh, binary: bool) -> Result<Vec<u8>, String> {
    let materials = cell_data::materials(mesh)?;
    let mut w = Writer::new(binary, raw_capacity(mesh));
    names_table(&mut w, mesh);
    let (nt, nf) = (mesh.tets.len(), mesh.triangles.len());
    w.xml.push_str(&format!(
        "<Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n<Points>\n",
        mesh.nodes.len(),
        nt + nf
    ));
    w.array("Points", 3, mesh.nodes.iter().flatten().copied());
    w.xml.push_str("</Points>\n<Cells>\n");
    cells(&mut w, mesh);
    w.xml
        .push_str("</Cells>\n<CellData Scalars=\"MaterialIDs\">\n");
    cell_data::put(&mut w, mesh, &materials);
    w.xml.push_str("</CellData>\n");
    Ok(w.finish())
}

/// `<FieldData>`: `region:<name>` and `surface:<name>`, each holding its id.
fn names_table(w: &mut Writer, mesh: &VolumeMesh) {
    w.xml.push_str("<FieldData>\n");
    for (r, rg) in mesh.regions.iter().enumerate() {
        w.field_int(&format!("region:{}", rg.name), r as i64 + 1);
    }
    for (g, sg) in mesh.surface_groups.iter().enumerate() {
        w.field_int(&format!("surface:{}", sg.name), g as i64 + 1);
    }
    w.xml.push_str("</FieldData>\n");
}

/// `<Cells>`' arrays: tets, then triangles.
fn cells(w: &mut Writer, mesh: &VolumeMesh) {
    let (nt, nf) = (mesh.tets.len(), mesh.triangles.len());
    let conn = || {
        let tets = mesh.tets.iter().flat_map(|t| t.iter());
        tets.chain(mesh.triangles.iter().flat_map(|t| t.iter()))
            .map(|&v| v as usize)
    };
    w.indices("connectivity", mesh.nodes.len(), conn);
    let offsets = || {
        (1..=nt)
            .map(|i| 4 * i)
            .chain((1..=nf).map(|i| 4 * nt + 3 * i))
    };
    w.indices("offsets", 4 * nt + 3 * nf, offsets);
    let types = std::iter::repeat_n(10u8, nt).chain(std::iter::repeat_n(5u8, nf));
    w.array("types", 1, types);
}

/// About the size of the appended block (a capacity hint; exact for meshes under 2^31 nodes).
fn raw_capacity(mesh: &VolumeMesh) -> usize {
    let (nt, nf) = (mesh.tets.len(), mesh.triangles.len());
    let n_props = crate::property_names(mesh).len();
    let arrays = 7 + n_props;
    let points = 3 * 8 * mesh.nodes.len();
    let cells = (nt + nf) * (4 + 1 + 3 * 4 + 8 * n_props);
    8 * arrays + points + 4 * (4 * nt + 3 * nf) + cells
}
