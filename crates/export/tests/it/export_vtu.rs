//! The volume VTU read by meshio and by VTK (through PyVista), in both encodings: the
//! OpenGeoSys `MaterialIDs` array, 1-based region and surface ids, the names table, and the
//! sizes of the two encodings. A reader that is absent skips with a note.

use test_support::export_support;

use export::{Format, export};
use export_support::*;
use geom::mesh::VolumeMesh;

/// `MaterialIDs` per region, then `region` and `surface` ids, as meshio reads them.
const MESHIO: &str = r#"
import sys, meshio, numpy as np
m = meshio.read(sys.argv[1])
for k in ("MaterialIDs", "region", "surface"):
    for b, d in zip(m.cells, m.cell_data[k]):
        print(k, b.type, d.dtype, ",".join(str(x) for x in sorted(set(d.tolist()))))
for k, v in sorted(m.field_data.items()):
    print("FIELD", k, int(v[0]))
"#;

/// The expected id lists, `[region, material]` per region in region order.
fn ids(mesh: &VolumeMesh) -> (String, String, String) {
    let join = |v: Vec<i64>| {
        let mut v = v;
        v.sort_unstable();
        v.dedup();
        v.iter().map(i64::to_string).collect::<Vec<_>>().join(",")
    };
    let materials = mesh.regions.iter().map(|r| r.material.unwrap_or(-1));
    let regions = (1..=mesh.regions.len() as i64).collect();
    let groups = (1..=mesh.surface_groups.len() as i64).collect();
    (join(materials.collect()), join(regions), join(groups))
}

#[test]
fn meshio_reads_int32_material_ids_and_one_based_ids_from_both_vtu_encodings() {
    if !python_has("meshio") {
        return;
    }
    let mesh = layered_box(4, 3);
    let (materials, regions, groups) = ids(&mesh);
    let dir = tempfile::tempdir().unwrap();
    for format in [Format::Vtu, Format::VtuBinary] {
        let paths = write_all(dir.path(), &export(&mesh, "m", format).unwrap());
        let out = python(MESHIO, &[paths[0].to_str().unwrap()]);
        for want in [
            format!("MaterialIDs tetra int32 {materials}"),
            "MaterialIDs triangle int32 -1".to_string(),
            format!("region tetra int32 {regions}"),
            "region triangle int32 -1".to_string(),
            "surface tetra int32 -1".to_string(),
            // The fault's side cells (after the groups' triangles) have no surface.
            format!("surface triangle int32 -1,{groups}"),
            "FIELD region:reservoir 2".to_string(),
            "FIELD surface:F2_dangling 9".to_string(),
        ] {
            assert!(
                out.lines().any(|l| l == want),
                "{format:?}: {want} not in\n{out}"
            );
        }
    }
}

/// What VTK reads: the cell arrays' types and the material of the first tet of each region.
const PYVISTA: &str = r#"
import sys, pyvista
m = pyvista.read(sys.argv[1])
print("TYPE", m.cell_data["MaterialIDs"].dtype, m.cell_data["region"].dtype)
seen = {}
for r, mat in zip(m.cell_data["region"], m.cell_data["MaterialIDs"]):
    seen.setdefault(int(r), int(mat))
print("PAIRS", ";".join(f"{r}:{mat}" for r, mat in sorted(seen.items())))
print("NAMES", ";".join(f"{k}={int(m.field_data[k][0])}" for k in sorted(m.field_data.keys())))
"#;

#[test]
fn vtk_reads_each_regions_material_and_the_names_table_from_the_vtu() {
    if !python_has("pyvista") {
        return;
    }
    let mesh = layered_box(4, 3);
    let dir = tempfile::tempdir().unwrap();
    let paths = write_all(dir.path(), &export(&mesh, "m", Format::VtuBinary).unwrap());
    let out = python(PYVISTA, &[paths[0].to_str().unwrap()]);
    assert!(out.contains("TYPE int32 int32\n"), "{out}");
    let mut pairs = vec!["-1:-1".to_string()];
    for (r, g) in mesh.regions.iter().enumerate() {
        pairs.push(format!("{}:{}", r + 1, g.material.unwrap_or(-1)));
    }
    assert!(
        out.contains(&format!("PAIRS {}\n", pairs.join(";"))),
        "{out}"
    );
    let mut names: Vec<String> = mesh
        .regions
        .iter()
        .enumerate()
        .map(|(r, g)| format!("region:{}={}", g.name, r + 1))
        .chain(
            (mesh.surface_groups.iter().enumerate())
                .map(|(i, g)| format!("surface:{}={}", g.name, i + 1)),
        )
        .chain([
            "side:F2_dangling:front=10".into(),
            "side:F2_dangling:back=11".into(),
        ])
        .collect();
    names.sort();
    assert!(
        out.contains(&format!("NAMES {}\n", names.join(";"))),
        "{out}"
    );
}

/// A mesh's nodes at full-precision coordinates, as a mesher's are (the box's are round).
fn at_full_precision(mut mesh: VolumeMesh) -> VolumeMesh {
    for (i, p) in mesh.nodes.iter_mut().enumerate() {
        p[0] += 1.0 / (3.0 + i as f64);
        p[1] += (i as f64).sqrt();
        p[2] -= 1.0 / 7.0;
    }
    mesh
}

/// At a meshed model's size (five-digit node ids); a tiny mesh with round coordinates and short
/// ids is shorter in ASCII.
#[test]
fn the_binary_vtu_of_a_meshed_model_is_smaller_than_the_ascii_with_32_bit_indices() {
    let mesh = at_full_precision(layered_box(24, 24));
    let size = |f| export(&mesh, "m", f).unwrap()[0].1.len();
    let (ascii, binary) = (size(Format::Vtu), size(Format::VtuBinary));
    assert!(binary < ascii, "binary {binary} >= ascii {ascii}");
    let bytes = &export(&mesh, "m", Format::VtuBinary).unwrap()[0].1;
    let head = String::from_utf8_lossy(&bytes[..2000]);
    for array in ["connectivity", "offsets", "MaterialIDs"] {
        let want = format!("<DataArray type=\"Int32\" Name=\"{array}\"");
        assert!(head.contains(&want), "{want} not in\n{head}");
    }
    assert!(
        head.contains("<DataArray type=\"UInt8\" Name=\"types\""),
        "{head}"
    );
}

#[test]
fn a_material_id_beyond_32_bits_is_refused_naming_the_region() {
    let mut mesh = layered_box(4, 3);
    mesh.regions[0].material = Some(1 << 40);
    let err = export(&mesh, "m", Format::Vtu).unwrap_err();
    assert!(
        err.contains("'underburden'") && err.contains("32-bit"),
        "{err}"
    );
}

/// Per fault side id (VTK): the side cells, how many have exactly one tet behind them (the tet
/// their normal points away from), and how many point against the fault triangle they copy.
const PYVISTA_SIDES: &str = r#"
import sys, pyvista, numpy as np
m = pyvista.read(sys.argv[1])
side, surface, types = m.cell_data["fault_side"], m.cell_data["surface"], m.celltypes
P = m.points
conn = [m.get_cell(i).point_ids for i in range(m.n_cells)]
faces = {}
for i in np.flatnonzero(types == 10):
    t = conn[i]
    for k in range(4):
        f = [t[j] for j in range(4) if j != k]
        faces.setdefault(tuple(sorted(f)), []).append(t[k])
normal = lambda f: np.cross(P[f[1]] - P[f[0]], P[f[2]] - P[f[0]])
fault = {tuple(sorted(conn[i])): normal(conn[i]) for i in np.flatnonzero(surface == 9)}
for s in sorted(set(side[side > 0].tolist())):
    ids = np.flatnonzero(side == s)
    behind = against = 0
    for i in ids:
        f = conn[i]
        n = normal(f)
        apexes = faces.get(tuple(sorted(f)), [])
        behind += sum(1 for a in apexes if np.dot(P[a] - P[f[0]], n) < 0) == 1
        against += np.dot(n, fault[tuple(sorted(f))]) < 0
    print("SIDE", s, len(ids), behind, against, int(types[ids[0]]))
print("NAMES", ";".join(f"{k}={int(m.field_data[k][0])}" for k in sorted(m.field_data.keys())
                        if k.startswith("side:")))
"#;

#[test]
fn vtk_reads_each_fault_side_as_triangles_oriented_out_of_the_tets_on_that_side() {
    if !python_has("pyvista") {
        return;
    }
    let mesh = layered_box(4, 3);
    let fault = mesh.triangle_group.iter().filter(|&&g| g == 8).count();
    let dir = tempfile::tempdir().unwrap();
    for format in [Format::Vtu, Format::VtuBinary] {
        let paths = write_all(dir.path(), &export(&mesh, "m", format).unwrap());
        let out = python(PYVISTA_SIDES, &[paths[0].to_str().unwrap()]);
        let got: Vec<&str> = out.lines().collect();
        let want = [
            // front: every copy reversed against the fault's normal; back: as the fault.
            format!("SIDE 10 {fault} {fault} {fault} 5"),
            format!("SIDE 11 {fault} {fault} 0 5"),
            "NAMES side:F2_dangling:back=11;side:F2_dangling:front=10".to_string(),
        ];
        assert_eq!(got, want, "{format:?}");
    }
}

#[test]
fn a_vtu_without_faults_has_no_side_cells_and_no_fault_side_array() {
    let mut mesh = layered_box(4, 3);
    mesh.surface_groups[8].kind = geom::mesh::SurfaceKind::Horizon;
    let text = String::from_utf8(export(&mesh, "m", Format::Vtu).unwrap().remove(0).1).unwrap();
    assert!(!text.contains("fault_side") && !text.contains("side:"));
    let cells = mesh.tets.len() + mesh.triangles.len();
    assert!(text.contains(&format!("NumberOfCells=\"{cells}\"")));
}
