//! The named points (where a well crosses a surface) in every format that can name a node: read
//! back by our msh reader, by Gmsh (0D physical groups) and by meshio (Exodus node sets) where
//! they are present (an absent reader skips with a note), parsed here for VTU and Abaqus; MEDIT
//! and TetGen leave them out, byte for byte.

use test_support::export_support;

use crate::export_lines::with_wells;
use export::{Format, export};
use export_support::*;
use geom::mesh::{NamedPoint, VolumeMesh};

/// `with_wells()` with three named points on its wells' nodes, in name order.
fn with_points() -> VolumeMesh {
    let mut mesh = with_wells();
    let id = |i: u32, j: u32, k: u32| i + 5 * (j + 5 * k);
    mesh.points = vec![
        NamedPoint {
            name: "W1:H1".into(),
            node: id(2, 2, 4),
        },
        NamedPoint {
            name: "W1:top".into(),
            node: id(2, 2, 6),
        },
        NamedPoint {
            name: "W2 deviated:H2".into(),
            node: id(1, 1, 1),
        },
    ];
    mesh
}

fn written(mesh: &VolumeMesh, format: Format) -> (tempfile::TempDir, Vec<std::path::PathBuf>) {
    let dir = tempfile::tempdir().unwrap();
    let paths = write_all(dir.path(), &export(mesh, "points", format).unwrap());
    (dir, paths)
}

/// `name|x|y|z` per point, coordinates as Python's `repr` prints them.
fn named_coordinates(mesh: &VolumeMesh) -> Vec<String> {
    let py = |x: f64| {
        let s = format!("{x:?}");
        if s.contains(['.', 'e', 'i', 'N']) {
            s
        } else {
            format!("{s}.0")
        }
    };
    (mesh.points.iter())
        .map(|p| {
            let [x, y, z] = mesh.nodes[p.node as usize].map(py);
            format!("{}|{x}|{y}|{z}", p.name)
        })
        .collect()
}

#[test]
fn named_points_come_back_from_both_msh_encodings_through_our_reader() {
    let mesh = with_points();
    for format in [Format::Msh, Format::MshBinary] {
        let files = export(&mesh, "points", format).unwrap();
        let back = geom::mesh::read::read_volume_msh(&files[0].1, "points.msh").unwrap();
        assert_eq!(back.points, mesh.points, "{format:?}");
        assert_eq!(back.nodes, mesh.nodes);
        assert_eq!(back.tets, mesh.tets);
        assert_eq!(back.lines.len(), mesh.lines.len());
    }
}

#[test]
fn msh_points_are_point_entities_with_0d_groups_and_leave_the_other_tags_alone() {
    let mesh = with_points();
    let text =
        String::from_utf8(export(&mesh, "points", Format::Msh).unwrap()[0].1.clone()).unwrap();
    let plain = {
        let mut m = mesh.clone();
        m.points.clear();
        String::from_utf8(export(&m, "points", Format::Msh).unwrap()[0].1.clone()).unwrap()
    };
    let section = |text: &str, name: &str| -> Vec<String> {
        let (_, rest) = text.split_once(&format!("${name}\n")).unwrap();
        let (body, _) = rest.split_once(&format!("$End{name}")).unwrap();
        body.lines().map(str::to_string).collect()
    };
    let names = section(&text, "PhysicalNames");
    assert_eq!(
        names[1..4],
        ["0 1 \"W1:H1\"", "0 2 \"W1:top\"", "0 3 \"W2 deviated:H2\""]
    );
    // The other groups follow with the tags they have without points.
    assert_eq!(names[4..], section(&plain, "PhysicalNames")[1..]);
    let entities = section(&text, "Entities");
    let [x, y, z] = mesh.nodes[mesh.points[0].node as usize];
    assert_eq!(entities[1], format!("1 {x} {y} {z} 1 1"));
    // The named points come first among the point entities, the corners of the curves after
    // them (their tags three further on); the curves are the same records but for the tags of
    // their end points, the surfaces and volumes the same records.
    let plain_entities = section(&plain, "Entities");
    let count =
        |header: &str, k: usize| -> usize { header.split(' ').nth(k).unwrap().parse().unwrap() };
    let (with, without) = (count(&entities[0], 0), count(&plain_entities[0], 0));
    assert_eq!(with, without + 3);
    let curves = count(&entities[0], 1);
    let (ours, theirs) = (&entities[1 + with..], &plain_entities[1 + without..]);
    for (a, b) in ours[..curves].iter().zip(&theirs[..curves]) {
        let (a, b): (Vec<&str>, Vec<&str>) = (a.split(' ').collect(), b.split(' ').collect());
        let n = a.len();
        if b[n - 1] == "0" {
            // A well's curve, bounded by no point.
            assert_eq!(a, b);
            continue;
        }
        assert_eq!(a[..n - 2], b[..n - 2]);
        let tag = |x: &str| -> i64 { x.parse().unwrap() };
        let moved = [tag(b[n - 2]) + 3, tag(b[n - 1]) - 3];
        assert_eq!([tag(a[n - 2]), tag(a[n - 1])], moved);
    }
    assert_eq!(ours[curves..], theirs[curves..]);
    // One point element (type 15) per point, after every other element.
    let elements = section(&text, "Elements");
    let plain_elements = section(&plain, "Elements");
    let total: usize = plain_elements[0]
        .split(' ')
        .nth(1)
        .unwrap()
        .parse()
        .unwrap();
    let first = elements.iter().position(|l| l == "0 1 15 1").unwrap();
    assert_eq!(
        elements[first..],
        [
            "0 1 15 1".to_string(),
            format!("{} {}", total + 1, mesh.points[0].node + 1),
            "0 2 15 1".to_string(),
            format!("{} {}", total + 2, mesh.points[1].node + 1),
            "0 3 15 1".to_string(),
            format!("{} {}", total + 3, mesh.points[2].node + 1),
        ]
    );
}

const GMSH_POINTS: &str = r#"
import sys, gmsh
gmsh.initialize()
gmsh.option.setNumber("General.Terminal", 0)
gmsh.open(sys.argv[1])
for dim, tag in sorted(gmsh.model.getPhysicalGroups(0)):
    for e in gmsh.model.getEntitiesForPhysicalGroup(dim, tag):
        types, tags, nodes = gmsh.model.mesh.getElements(0, e)
        for n in nodes[0]:
            c, _, _, _ = gmsh.model.mesh.getNode(n)
            print(gmsh.model.getPhysicalName(dim, tag), *[repr(float(x)) for x in c], sep="|")
# The wells' 1D groups; the others are the model's curves, named `A/B` or `A:border`.
wells = [t for d, t in gmsh.model.getPhysicalGroups(1)
         if "/" not in gmsh.model.getPhysicalName(d, t)
         and not gmsh.model.getPhysicalName(d, t).endswith(":border")]
print("VOLUMES", len(gmsh.model.getPhysicalGroups(3)), "WELLS", len(wells))
gmsh.finalize()
"#;

#[test]
fn gmsh_reads_each_named_point_as_a_0d_physical_group_at_its_node() {
    if !python_has("gmsh") {
        return;
    }
    let mesh = with_points();
    for format in [Format::Msh, Format::MshBinary] {
        let (_dir, paths) = written(&mesh, format);
        let out = python(GMSH_POINTS, &[paths[0].to_str().unwrap()]);
        let mut want = named_coordinates(&mesh);
        let regions = mesh.regions.len() + 2; // and the materials
        want.push(format!("VOLUMES {regions} WELLS 2"));
        assert_eq!(out.lines().collect::<Vec<_>>(), want, "{format:?}: {out}");
    }
}

const MESHIO_EXODUS_POINTS: &str = r#"
import sys, meshio
m = meshio.read(sys.argv[1], file_format="exodus")
for k in sorted(m.point_sets):
    if ":" in k:
        print(k, *m.point_sets[k].tolist(), sep="|")
"#;

#[test]
fn meshio_reads_each_named_point_as_an_exodus_node_set_of_its_node() {
    if !python_has("meshio") {
        return;
    }
    let mesh = with_points();
    let (_dir, paths) = written(&mesh, Format::Exodus);
    let out = python(MESHIO_EXODUS_POINTS, &[paths[0].to_str().unwrap()]);
    let want: Vec<String> = (mesh.points.iter())
        .map(|p| format!("{}|{}", p.name, p.node))
        .collect();
    assert_eq!(out.lines().collect::<Vec<_>>(), want, "{out}");
}

#[test]
fn vtu_field_data_and_abaqus_node_sets_name_each_point() {
    let mesh = with_points();
    let vtu =
        String::from_utf8(export(&mesh, "points", Format::Vtu).unwrap()[0].1.clone()).unwrap();
    for p in &mesh.points {
        let want = format!(
            "<DataArray type=\"Int32\" Name=\"point:{}\" NumberOfTuples=\"1\" format=\"ascii\">{}</DataArray>",
            p.name, p.node
        );
        assert!(vtu.contains(&want), "{want}");
    }
    let inp =
        String::from_utf8(export(&mesh, "points", Format::Inp).unwrap()[0].1.clone()).unwrap();
    for (p, label) in mesh
        .points
        .iter()
        .zip(["W1_H1", "W1_top", "W2_deviated_H2"])
    {
        assert!(
            inp.contains(&format!("*Nset, nset={label}\n{}\n", p.node + 1)),
            "{label}"
        );
        assert!(
            inp.contains(&format!("\"{}\" nset={label}", p.name)),
            "{label}"
        );
    }
}

#[test]
fn medit_and_tetgen_leave_the_points_out_and_a_mesh_without_points_has_none_anywhere() {
    let mesh = with_points();
    let mut plain = mesh.clone();
    plain.points.clear();
    for format in [Format::Medit, Format::TetGen] {
        assert_eq!(
            export(&mesh, "points", format).unwrap(),
            export(&plain, "points", format).unwrap(),
            "{format:?}"
        );
    }
    let msh = export(&plain, "points", Format::Msh).unwrap();
    assert!(msh[0].1.starts_with(b"$MeshFormat"));
    let text = String::from_utf8(msh[0].1.clone()).unwrap();
    assert!(!text.contains(" 15 1\n") && !text.contains("\n0 1 \""));
    let vtu =
        String::from_utf8(export(&plain, "points", Format::Vtu).unwrap()[0].1.clone()).unwrap();
    assert!(!vtu.contains("point:"));
}
