//! Exports read back by the real readers (meshio, gmsh) and judged by check_mesh.py.

use test_support::export_support;

use export::{Format, export};
use export_support::*;
use std::collections::{BTreeMap, BTreeSet};

fn counts(mesh: &geom::mesh::VolumeMesh) -> (usize, usize, usize) {
    (mesh.nodes.len(), mesh.tets.len(), mesh.triangles.len())
}

/// The triangles a VTU holds: the surface groups', then a copy per side of each fault triangle
/// (the test mesh's fault has tets on both sides).
fn vtu_triangles(mesh: &geom::mesh::VolumeMesh) -> usize {
    let faults = (mesh.triangle_group.iter())
        .filter(|&&g| mesh.surface_groups[g as usize].kind == geom::mesh::SurfaceKind::Fault);
    mesh.triangles.len() + 2 * faults.count()
}

#[test]
fn the_test_mesh_has_the_expected_groups() {
    let m = layered_box(6, 6);
    let (nn, nt, _) = counts(&m);
    assert_eq!(nn, 7 * 7 * 7);
    assert_eq!(nt, 6 * 6 * 6 * 6);
    for g in 0..m.surface_groups.len() as u32 {
        assert!(
            m.triangle_group.contains(&g),
            "group {} is empty",
            m.surface_groups[g as usize].name
        );
    }
}

const MESHIO_COUNTS: &str = r#"
import sys, meshio, numpy as np
m = meshio.read(sys.argv[1], file_format=sys.argv[2] if len(sys.argv) > 2 else None)
tet = sum(len(b.data) for b in m.cells if b.type == "tetra")
tri = sum(len(b.data) for b in m.cells if b.type == "triangle")
keys = [k for k in ("gmsh:physical", "medit:ref", "region") if k in m.cell_data]
tags = set()
if keys:
    for b, d in zip(m.cells, m.cell_data[keys[0]]):
        if b.type == "tetra":
            tags |= set(int(x) for x in np.unique(d))
print("COUNTS", len(m.points), tet, tri, ",".join(str(t) for t in sorted(tags)))
print("FIELD", ";".join(sorted(m.field_data.keys())))
print("CELLS", ";".join(sorted(m.cell_data.keys())))
"#;

#[test]
fn every_format_reads_back_in_meshio_with_its_counts_and_region_tags() {
    if !python_has("meshio") {
        return;
    }
    let mesh = layered_box(6, 6);
    let (nn, nt, nf) = counts(&mesh);
    let dir = tempfile::tempdir().unwrap();
    for (format, main, region_tags, with_tris) in [
        (Format::Msh, "layered.msh", "1,2,3", true),
        (Format::MshBinary, "layered.msh", "1,2,3", true),
        (Format::Vtu, "layered.vtu", "1,2,3", true),
        (Format::VtuBinary, "layered.vtu", "1,2,3", true),
        (Format::Medit, "layered.mesh", "1,2,3", true),
        (Format::TetGen, "layered.1.node", "", false),
    ] {
        let files = export(&mesh, "layered", format).unwrap();
        write_all(dir.path(), &files);
        let path = dir.path().join(main);
        let out = python(MESHIO_COUNTS, &[path.to_str().unwrap()]);
        let line = |key: &str| {
            out.lines()
                .find_map(|l| l.strip_prefix(key))
                .unwrap_or("")
                .to_string()
        };
        let first = line("COUNTS ");
        let want_tris = match format {
            Format::Vtu | Format::VtuBinary => vtu_triangles(&mesh),
            _ if with_tris => nf,
            _ => 0,
        };
        let want = format!("{nn} {nt} {want_tris} {region_tags}");
        assert_eq!(first.trim_end(), want.trim_end(), "{format:?}: {out}");
        if format == Format::Vtu || format == Format::VtuBinary {
            let field = line("FIELD ");
            assert!(
                field.contains("region:reservoir") && field.contains("surface:F2_dangling"),
                "{field}"
            );
            let cells = line("CELLS ");
            for k in ["MaterialIDs", "density", "porosity", "surface"] {
                assert!(cells.contains(k), "vtu cell data lacks {k}: {cells}");
            }
        }
        if format == Format::Msh || format == Format::MshBinary {
            let field = line("FIELD ");
            assert!(
                field.contains("H1 top") && field.contains("overburden"),
                "{field}"
            );
            let cells = line("CELLS ");
            assert!(
                cells.contains("material") && cells.contains("porosity"),
                "{cells}"
            );
        }
    }
}

#[test]
fn tetgen_faces_and_region_attributes_are_what_we_wrote() {
    let mesh = layered_box(4, 3);
    let files = export(&mesh, "m", Format::TetGen).unwrap();
    let names: Vec<&str> = files.iter().map(|f| f.0.as_str()).collect();
    assert_eq!(names, ["m.1.node", "m.1.ele", "m.1.face"]);
    let ele = String::from_utf8(files[1].1.clone()).unwrap();
    let rows: Vec<&str> = ele.lines().filter(|l| !l.starts_with('#')).collect();
    assert_eq!(rows[0], format!("{} 4 1", mesh.tets.len()));
    let last = rows.last().unwrap().split_whitespace().collect::<Vec<_>>();
    assert_eq!(last.len(), 6);
    assert_eq!(
        last[5],
        (mesh.tet_region[mesh.tets.len() - 1] + 1).to_string()
    );
    let face = String::from_utf8(files[2].1.clone()).unwrap();
    let fault = face
        .lines()
        .filter(|l| l.split_whitespace().nth(4) == Some("9"))
        .count();
    assert_eq!(
        fault,
        mesh.triangle_group.iter().filter(|&&g| g == 8).count()
    );
    assert!(fault > 0);
}

const GMSH_GROUPS: &str = r#"
import sys, gmsh
gmsh.initialize()
gmsh.option.setNumber("General.Terminal", 0)
gmsh.open(sys.argv[1])
for dim, tag in sorted(gmsh.model.getPhysicalGroups()):
    ents = gmsh.model.getEntitiesForPhysicalGroup(dim, tag)
    n = 0
    for e in ents:
        types, tags, nodes = gmsh.model.mesh.getElements(dim, e)
        n += sum(len(t) for t in tags)
    print(dim, tag, gmsh.model.getPhysicalName(dim, tag), n, sep="|")
gmsh.finalize()
"#;

#[test]
fn gmsh_opens_both_msh_encodings_with_every_group_fault_side_and_material_and_its_elements() {
    if !python_has("gmsh") {
        return;
    }
    let mut mesh = layered_box(6, 6);
    // The overburden takes the reservoir's material: one material group over two regions.
    mesh.regions[2].material = mesh.regions[1].material;
    let dir = tempfile::tempdir().unwrap();
    let triangles = |g: usize| {
        mesh.triangle_group
            .iter()
            .filter(|&&x| x == g as u32)
            .count()
    };
    let tets = |r: usize| mesh.tet_region.iter().filter(|&&x| x == r as u32).count();
    let n = mesh.surface_groups.len();
    let mut want = Vec::new();
    for (g, s) in mesh.surface_groups.iter().enumerate() {
        want.push(format!("2|{}|{}|{}", g + 1, s.name, triangles(g)));
    }
    let faults = (mesh.surface_groups.iter().enumerate())
        .filter(|(_, s)| s.kind == geom::mesh::SurfaceKind::Fault);
    for (k, (g, s)) in faults.enumerate() {
        want.push(format!(
            "2|{}|{}:front|{}",
            n + 2 * k + 1,
            s.name,
            triangles(g)
        ));
        want.push(format!(
            "2|{}|{}:back|{}",
            n + 2 * k + 2,
            s.name,
            triangles(g)
        ));
    }
    for (r, s) in mesh.regions.iter().enumerate() {
        want.push(format!("3|{}|{}|{}", r + 1, s.name, tets(r)));
    }
    let materials: BTreeSet<i64> = mesh.regions.iter().filter_map(|r| r.material).collect();
    for (k, m) in materials.iter().enumerate() {
        let of_m = (0..mesh.regions.len()).filter(|&r| mesh.regions[r].material == Some(*m));
        let count: usize = of_m.map(tets).sum();
        want.push(format!(
            "3|{}|material:{m}|{count}",
            mesh.regions.len() + k + 1
        ));
    }
    assert_eq!(materials.len(), 2, "3 for one region, 2 for two");
    for format in [Format::Msh, Format::MshBinary] {
        let files = export(&mesh, format.name(), format).unwrap();
        let paths = write_all(dir.path(), &files);
        let out = python(GMSH_GROUPS, &[paths[0].to_str().unwrap()]);
        // The 1D groups are the curves where the surfaces meet or end, named after them.
        let (curves, got): (Vec<&str>, Vec<&str>) = out.lines().partition(|l| l.starts_with("1|"));
        assert_eq!(got, want, "{format:?}");
        assert!(
            curves.iter().any(|l| l.contains("|H1 top/xmax|")),
            "{curves:?}"
        );
        assert!(
            curves.iter().any(|l| l.contains("|F2_dangling:border|")),
            "{curves:?}"
        );
    }
}

#[test]
fn check_mesh_passes_on_msh_binary_msh_vtu_and_medit_with_utm_offsets() {
    if !python_has("meshio, numpy") {
        return;
    }
    let Some(tool) = checker() else { return };
    let mesh = layered_box(6, 6);
    let dir = tempfile::tempdir().unwrap();
    for format in [
        Format::Msh,
        Format::MshBinary,
        Format::Vtu,
        Format::VtuBinary,
        Format::Medit,
    ] {
        let files = export(&mesh, "checked", format).unwrap();
        let paths = write_all(dir.path(), &files);
        let (ok, out) = run_checker(&tool, &paths[0], 3, None);
        assert!(ok, "{format:?} failed check_mesh.py:\n{out}");
        let triangles = match format {
            Format::Vtu | Format::VtuBinary => vtu_triangles(&mesh),
            _ => mesh.triangles.len(),
        };
        assert!(
            out.contains(&format!("\"surface_triangles\": {triangles}")),
            "{format:?}: {out}"
        );
    }
}

#[test]
fn check_mesh_fails_when_a_fault_triangle_is_not_a_tet_face() {
    if !python_has("meshio, numpy") {
        return;
    }
    let Some(tool) = checker() else { return };
    let mut mesh = layered_box(4, 3);
    // Break one fault triangle: it no longer matches a tet face (the checker must notice).
    let i = mesh.triangle_group.iter().position(|&g| g == 8).unwrap();
    mesh.triangles[i][2] = 0; // the corner (xmin, ymin, zmin), far from the fault
    let dir = tempfile::tempdir().unwrap();
    let paths = write_all(dir.path(), &export(&mesh, "broken", Format::Msh).unwrap());
    let (ok, out) = run_checker(&tool, &paths[0], 3, None);
    assert!(!ok, "the checker accepted a broken fault:\n{out}");
}

#[test]
fn the_same_mesh_gives_the_same_bytes_every_time() {
    let a = layered_box(4, 3);
    let b = layered_box(4, 3);
    for f in export::Format::ALL {
        assert_eq!(
            export(&a, "d", f).unwrap(),
            export(&b, "d", f).unwrap(),
            "{f:?}"
        );
    }
    let msh = export(&a, "d", Format::Msh).unwrap();
    let text = String::from_utf8(msh[0].1.clone()).unwrap();
    assert!(
        text.starts_with("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n"),
        "{}",
        &text[..80]
    );
    assert!(text.contains("3 2 \"reservoir\"\n") && text.contains("2 9 \"F2_dangling\"\n"));
}

const MESHIO_INP: &str = r#"
import sys, meshio
m = meshio.read(sys.argv[1])
tet = sum(len(b.data) for b in m.cells if b.type == "tetra")
print("COUNTS", len(m.points), tet)
print("SETS", ";".join(sorted(m.cell_sets.keys())))
print("NSETS", ";".join(sorted(m.point_sets.keys())))
"#;

#[test]
fn abaqus_inp_reads_in_meshio_with_region_sets_and_surface_node_sets() {
    if !python_has("meshio") {
        return;
    }
    let mesh = layered_box(6, 6);
    let dir = tempfile::tempdir().unwrap();
    let paths = write_all(dir.path(), &export(&mesh, "abq", Format::Inp).unwrap());
    let out = python(MESHIO_INP, &[paths[0].to_str().unwrap()]);
    let line = |key: &str| {
        out.lines()
            .find_map(|l| l.strip_prefix(key))
            .unwrap_or("")
            .to_string()
    };
    assert_eq!(
        line("COUNTS "),
        format!("{} {}", mesh.nodes.len(), mesh.tets.len()),
        "{out}"
    );
    let sets = line("SETS ").to_ascii_lowercase();
    let fault_sides = ["f2_dangling_front_s", "f2_dangling_back_s"];
    for r in ["underburden", "reservoir", "overburden", "f2_dangling_s"]
        .into_iter()
        .chain(fault_sides)
    {
        assert!(sets.contains(r), "no element set {r}: {out}");
    }
    assert!(
        line("NSETS ").to_ascii_lowercase().contains("h1_top"),
        "{out}"
    );
}

/// Element number → its nodes (0-based).
type Elements = BTreeMap<usize, [u32; 4]>;
/// Surface name → its (element, face) pairs.
type Surfaces = BTreeMap<String, Vec<(usize, String)>>;

/// The elements of an `.inp` and the (element, face) pairs of each of its element-face surfaces
/// (from the `<surface>_S<n>` element sets).
fn inp_surfaces(text: &str) -> (Elements, Surfaces) {
    let mut elems = BTreeMap::new();
    let mut surfaces = Surfaces::new();
    let mut mode = String::new();
    for l in text.lines().filter(|l| !l.starts_with("**")) {
        if l.starts_with('*') {
            mode = l.to_string();
            continue;
        }
        let v: Vec<&str> = l
            .split(',')
            .map(str::trim)
            .filter(|t| !t.is_empty())
            .collect();
        if mode.starts_with("*Element,") {
            let n: Vec<u32> = v[1..]
                .iter()
                .map(|t| t.parse::<u32>().unwrap() - 1)
                .collect();
            elems.insert(v[0].parse().unwrap(), [n[0], n[1], n[2], n[3]]);
        } else if let Some((surface, face)) = mode
            .strip_prefix("*Elset, elset=")
            .and_then(|name| name.rsplit_once('_'))
            .filter(|(_, f)| f.starts_with('S') && f[1..].parse::<u8>().is_ok())
        {
            let faces = surfaces.entry(surface.to_string()).or_default();
            faces.extend(v.iter().map(|t| (t.parse().unwrap(), face.to_string())));
        }
    }
    (elems, surfaces)
}

#[test]
fn abaqus_surfaces_name_the_tet_faces_of_a_group_and_of_each_fault_side() {
    let mesh = layered_box(4, 3);
    let text = String::from_utf8(export(&mesh, "abq", Format::Inp).unwrap().remove(0).1).unwrap();
    let (elems, surfaces) = inp_surfaces(&text);
    let local = |s: &str| match s {
        "S1" => [0, 1, 2],
        "S2" => [0, 3, 1],
        "S3" => [1, 3, 2],
        _ => [2, 3, 0],
    };
    let faces_of = |name: &str| {
        let mut faces: Vec<[u32; 3]> = (surfaces[name].iter())
            .map(|(e, side)| {
                let mut f = local(side).map(|k| elems[e][k]);
                f.sort();
                f
            })
            .collect();
        faces.sort();
        faces
    };
    let mut want: Vec<[u32; 3]> = mesh
        .triangles
        .iter()
        .zip(&mesh.triangle_group)
        .filter(|(_, g)| **g == 8)
        .map(|(t, _)| {
            let mut t = *t;
            t.sort();
            t
        })
        .collect();
    want.sort();
    assert!(!want.is_empty());
    for name in ["F2_dangling", "F2_dangling_front", "F2_dangling_back"] {
        assert_eq!(faces_of(name), want, "{name}");
    }
    let tets = |name: &str| {
        surfaces[name]
            .iter()
            .map(|(e, _)| *e)
            .collect::<BTreeSet<_>>()
    };
    assert!(tets("F2_dangling_front").is_disjoint(&tets("F2_dangling_back")));
}

#[test]
fn every_abaqus_region_has_a_solid_section_of_its_own_material_with_its_density() {
    let mesh = layered_box(4, 3);
    let text = String::from_utf8(export(&mesh, "abq", Format::Inp).unwrap().remove(0).1).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let mut sections = BTreeMap::new();
    let mut densities = BTreeMap::new();
    for (i, l) in lines.iter().enumerate() {
        if let Some(rest) = l.strip_prefix("*Solid Section, elset=") {
            let (elset, material) = rest.split_once(", material=").unwrap();
            sections.insert(elset.to_string(), material.to_string());
        } else if let Some(name) = l.strip_prefix("*Material, name=") {
            assert_eq!(lines[i + 1], "*Density", "{name}");
            densities.insert(name.to_string(), lines[i + 2].to_string());
        }
    }
    let want_sections = BTreeMap::from([
        ("underburden".to_string(), "M3_underburden".to_string()),
        ("reservoir".to_string(), "M2_reservoir".to_string()),
        ("overburden".to_string(), "NOMAT_overburden".to_string()),
    ]);
    assert_eq!(sections, want_sections);
    let want_densities = BTreeMap::from([
        ("M3_underburden".to_string(), "2600,".to_string()),
        ("M2_reservoir".to_string(), "2300,".to_string()),
        ("NOMAT_overburden".to_string(), "2200,".to_string()),
    ]);
    assert_eq!(densities, want_densities);
    assert!(
        text.contains(
            "*Material, name=M2_reservoir\n*Density\n2300,\n** property porosity = 0.21\n"
        )
    );
}

/// The rows of a TetGen file, comments and the header left out, as whitespace-split numbers.
fn tetgen_rows(bytes: &[u8]) -> Vec<Vec<f64>> {
    let text = String::from_utf8(bytes.to_vec()).unwrap();
    let rows = text.lines().filter(|l| !l.starts_with('#')).skip(1);
    rows.map(|l| l.split_whitespace().map(|x| x.parse().unwrap()).collect())
        .collect()
}

#[test]
fn tetgen_faces_name_the_tet_on_their_front_then_the_tet_behind_them() {
    let mesh = layered_box(4, 3);
    let files = export(&mesh, "m", Format::TetGen).unwrap();
    let (node, ele, face) = (
        tetgen_rows(&files[0].1),
        tetgen_rows(&files[1].1),
        tetgen_rows(&files[2].1),
    );
    let p = |v: f64| [1, 2, 3].map(|k| node[v as usize - 1][k]);
    // The sign of the apex's side of the face (positive: where its right-hand normal points).
    let side = |f: &[f64], apex: [f64; 3]| {
        let [a, b, c] = [p(f[1]), p(f[2]), p(f[3])];
        let d = |u: [f64; 3], v: [f64; 3]| [0, 1, 2].map(|k| u[k] - v[k]);
        let (u, v, w) = (d(b, a), d(c, a), d(apex, a));
        let n = [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ];
        n[0] * w[0] + n[1] * w[1] + n[2] * w[2]
    };
    let mut sided = [0usize; 2];
    for f in &face {
        assert_eq!(f.len(), 7, "index, 3 nodes, marker, front tet, back tet");
        let boundary = f[4] <= 6.0;
        assert_eq!(f[5] < 0.0 || f[6] < 0.0, boundary, "{f:?}");
        for (col, sign) in [(5, 1.0), (6, -1.0)] {
            if f[col] < 0.0 {
                continue;
            }
            let tet = &ele[f[col] as usize - 1][1..5];
            let apex = tet
                .iter()
                .find(|v| !f[1..4].contains(v))
                .expect("a face of it");
            assert_eq!(tet.iter().filter(|v| f[1..4].contains(v)).count(), 3);
            assert!(side(f, p(*apex)) * sign > 0.0, "{f:?}");
            sided[col - 5] += usize::from(f[4] == 9.0);
        }
    }
    let fault = mesh.triangle_group.iter().filter(|&&g| g == 8).count();
    assert_eq!(sided, [fault, fault], "both sides of every fault face");
}

/// The fault's triangles (reference 9) as meshio reads them from the MEDIT file, in order.
const MESHIO_MEDIT_FAULT: &str = r#"
import sys, meshio
m = meshio.read(sys.argv[1])
for b, ref in zip(m.cells, m.cell_data["medit:ref"]):
    if b.type == "triangle":
        for t, r in zip(b.data, ref):
            if r == 9:
                print(*t)
"#;

#[test]
fn meshio_reads_medit_fault_triangles_wound_so_their_normal_points_to_the_front() {
    if !python_has("meshio") {
        return;
    }
    let mesh = layered_box(4, 3);
    let dir = tempfile::tempdir().unwrap();
    let paths = write_all(dir.path(), &export(&mesh, "m", Format::Medit).unwrap());
    let out = python(MESHIO_MEDIT_FAULT, &[paths[0].to_str().unwrap()]);
    let want: Vec<String> = (mesh.triangles.iter().zip(&mesh.triangle_group))
        .filter(|(_, g)| **g == 8)
        .map(|(t, _)| format!("{} {} {}", t[0], t[1], t[2]))
        .collect();
    assert!(!want.is_empty());
    assert_eq!(out.lines().collect::<Vec<_>>(), want);
}
