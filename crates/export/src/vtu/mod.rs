//! VTK XML UnstructuredGrid (`.vtu`) writer, for ParaView, PyVista, meshio and OpenGeoSys, with
//! ASCII data arrays or raw appended binary for large meshes.
//!
//! Cells: every tet (VTK type 10) in index order, then every surface triangle (type 5), so
//! faults, horizons and box sides can be shown and selected, then the line elements of the line
//! groups (wells) as line cells (type 3), group after group, as the curves VTU writes its
//! segments. Ids follow the crate's one scheme (region `r` is `r + 1`, surface group `g` is
//! `g + 1`, line group `w` is `w + 1`); -1 means "none" in every cell array.
//! Cell data ([`cell_data`]): `MaterialIDs` (Int32, the OpenGeoSys convention: the region's
//! material id; -1 for a region without a material and on triangles and lines), `region`
//! (region id, -1 on triangles and lines), `surface` (surface group id, -1 on tets and lines),
//! one Float64 array per region property (NaN where undefined), and, only when the mesh has line
//! groups, `well` (Int32, the line group's id on lines, -1 on tets and triangles). The names
//! table is field data: one single-value Int32 array per region, `region:<name>` holding its id,
//! per surface group, `surface:<name>`, and per line group, `well:<name>` (VTU string arrays are
//! not read by meshio; these are, as by VTK). Each named point (a well's crossing of a surface)
//! is field data too, `point:<name>` holding its node's 0-based index (the VTK point id): VTK
//! has no named vertex set, and a vertex cell per point would change every cell array's length
//! for the sake of a name. A mesh without line groups or points is written as before they
//! existed. Each fault side is a copy of the fault's triangles after every other cell, marked
//! by a `fault_side` array and named by `side:<fault>:front` / `side:<fault>:back` field data
//! ([`sides`]); a mesh without faults is written as before they existed. The recipe's face
//! sets (`[groups]`) overlap the surface groups and each other, so each is its own cell array,
//! `group:<name>`, holding the set's id on its triangles and -1 elsewhere, named by
//! `group:<name>` field data; a mesh without them is written as before. Connectivity and offsets are Int32 whenever they fit and cell types UInt8, so
//! the binary file is smaller than the ASCII.

mod cell_data;
mod sides;
pub(crate) mod writer;

use geom::mesh::VolumeMesh;
use sides::SideCells;
use writer::Writer;

/// The cells after the tets: the counts of triangles, lines and side cells, and the side cells.
struct Extra {
    triangles: usize,
    lines: usize,
    sides: SideCells,
}

impl Extra {
    fn new(mesh: &VolumeMesh) -> Extra {
        Extra {
            triangles: mesh.triangles.len(),
            lines: line_count(mesh),
            sides: SideCells::new(mesh),
        }
    }

    /// The number of cells after the tets.
    fn len(&self) -> usize {
        self.triangles + self.lines + self.sides.len()
    }
}

/// Fails when a material id does not fit `MaterialIDs`' Int32.
pub(super) fn write(mesh: &VolumeMesh, binary: bool) -> Result<Vec<u8>, String> {
    let materials = cell_data::materials(mesh)?;
    let extra = Extra::new(mesh);
    let mut w = Writer::new(binary, raw_capacity(mesh, &extra));
    names_table(&mut w, mesh, &extra.sides);
    w.xml.push_str(&format!(
        "<Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n<Points>\n",
        mesh.nodes.len(),
        mesh.tets.len() + extra.len()
    ));
    w.array("Points", 3, mesh.nodes.iter().flatten().copied());
    w.xml.push_str("</Points>\n<Cells>\n");
    cells(&mut w, mesh, &extra);
    w.xml
        .push_str("</Cells>\n<CellData Scalars=\"MaterialIDs\">\n");
    cell_data::put(&mut w, mesh, &materials, &extra);
    w.xml.push_str("</CellData>\n");
    Ok(w.finish())
}

/// `<FieldData>`: `region:<name>`, `surface:<name>`, `well:<name>` and `side:<fault side>`,
/// each holding its id, then `point:<name>` holding the point's 0-based node index, then
/// `group:<name>` holding each face set's id.
fn names_table(w: &mut Writer, mesh: &VolumeMesh, sides: &SideCells) {
    w.xml.push_str("<FieldData>\n");
    for (r, rg) in mesh.regions.iter().enumerate() {
        w.field_int(&format!("region:{}", rg.name), r as i64 + 1);
    }
    for (g, sg) in mesh.surface_groups.iter().enumerate() {
        w.field_int(&format!("surface:{}", sg.name), g as i64 + 1);
    }
    for (g, lg) in mesh.lines.iter().enumerate() {
        w.field_int(&format!("well:{}", lg.name), g as i64 + 1);
    }
    for (name, id) in &sides.names {
        w.field_int(&format!("side:{name}"), i64::from(*id));
    }
    for p in &mesh.points {
        w.field_int(&format!("point:{}", p.name), p.node as i64);
    }
    let first = crate::face_sets::first_id(&mesh.surface_groups);
    for (k, set) in mesh.face_sets.iter().enumerate() {
        w.field_int(&format!("group:{}", set.name), (first + k) as i64);
    }
    w.xml.push_str("</FieldData>\n");
}

/// The number of line elements of `mesh`.
pub(super) fn line_count(mesh: &VolumeMesh) -> usize {
    mesh.lines.iter().map(|g| g.lines.len()).sum()
}

/// `<Cells>`' arrays: tets, then triangles, then lines, then side cells.
fn cells(w: &mut Writer, mesh: &VolumeMesh, extra: &Extra) {
    let (nt, nf, nl, ns) = (
        mesh.tets.len(),
        extra.triangles,
        extra.lines,
        extra.sides.len(),
    );
    let conn = || {
        let tets = mesh.tets.iter().flat_map(|t| t.iter());
        let lines = mesh.lines.iter().flat_map(|g| g.lines.iter().flatten());
        let sides = extra.sides.cells.iter().flat_map(|(t, _)| t.iter());
        tets.chain(mesh.triangles.iter().flat_map(|t| t.iter()))
            .chain(lines)
            .chain(sides)
            .map(|&v| v as usize)
    };
    w.indices("connectivity", mesh.nodes.len(), conn);
    let ends = 4 * nt + 3 * nf + 2 * nl;
    let offsets = || {
        (1..=nt)
            .map(|i| 4 * i)
            .chain((1..=nf).map(|i| 4 * nt + 3 * i))
            .chain((1..=nl).map(|i| 4 * nt + 3 * nf + 2 * i))
            .chain((1..=ns).map(|i| ends + 3 * i))
    };
    w.indices("offsets", ends + 3 * ns, offsets);
    let types = std::iter::repeat_n(10u8, nt)
        .chain(std::iter::repeat_n(5u8, nf))
        .chain(std::iter::repeat_n(3u8, nl))
        .chain(std::iter::repeat_n(5u8, ns));
    w.array("types", 1, types);
}

/// About the size of the appended block (a capacity hint; exact for meshes under 2^31 nodes).
fn raw_capacity(mesh: &VolumeMesh, extra: &Extra) -> usize {
    let (nt, nf, nl, ns) = (
        mesh.tets.len(),
        extra.triangles,
        extra.lines,
        extra.sides.len(),
    );
    let n_props = crate::property_names(mesh).len();
    let wells = usize::from(!mesh.lines.is_empty());
    let sides = usize::from(!extra.sides.names.is_empty());
    let sets = mesh.face_sets.len();
    let arrays = 7 + n_props + wells + sides + 2 * sets;
    let points = 3 * 8 * mesh.nodes.len();
    let cells = (nt + nf + nl + ns) * (4 + 1 + 3 * 4 + 8 * n_props + 4 * (wells + sides + sets));
    8 * arrays + points + 4 * (4 * nt + 3 * (nf + ns) + 2 * nl) + cells
}
