//! The shipped example's msh read by gmsh's API and by meshio: a 3D group per material over the
//! tets of its regions, each fault's front and back groups on the fault's own entities (the
//! front reversed), each region's volume bounded by the surfaces around it with their normals
//! signed outward, and the same model from the binary encoding. Expectations come from our own
//! reader of the same file; a reader that is absent skips with a note.

use crate::common_cli;
use common_cli::*;
use geom::mesh::read::read_volume_msh;
use geom::mesh::{SurfaceKind, VolumeMesh};
use std::collections::{BTreeMap, BTreeSet};
use test_support::export_support::{python, python_has};

/// Prints every physical group (`GROUP|dim|tag|name|entities|elements`), every surface entity's
/// signed group names (`ENTITY|tag|names`) and every volume's boundary (`VOLUME|name|the
/// groups of its bounding surfaces|whether every sign matches the normals`).
const GMSH_MODEL: &str = r#"
import sys, gmsh, numpy as np
gmsh.initialize()
gmsh.option.setNumber("General.Terminal", 0)
gmsh.open(sys.argv[1])
name = gmsh.model.getPhysicalName
def count(dim, ents):
    return sum(len(t) for e in ents for t in gmsh.model.mesh.getElements(dim, e)[1])
for dim, tag in sorted(gmsh.model.getPhysicalGroups()):
    ents = sorted(int(e) for e in gmsh.model.getEntitiesForPhysicalGroup(dim, tag))
    print("GROUP", dim, tag, name(dim, tag), ",".join(map(str, ents)), count(dim, ents), sep="|")
for _, s in gmsh.model.getEntities(2):
    tags = gmsh.model.getPhysicalGroupsForEntity(2, s)
    print("ENTITY", s, ";".join(("-" if p < 0 else "") + name(2, abs(p)) for p in tags), sep="|")
nodes, xyz, _ = gmsh.model.mesh.getNodes()
at = dict(zip(nodes.tolist(), xyz.reshape(-1, 3)))
for _, v in gmsh.model.getEntities(3):
    # The apex of every face of the region's tets: the boundary must be made of such faces.
    apex = {}
    for tet in gmsh.model.mesh.getElements(3, v)[2][0].reshape(-1, 4).tolist():
        for k in range(4):
            apex[tuple(sorted(tet[:k] + tet[k + 1:]))] = tet[k]
    groups, outward = set(), True
    for _, s in gmsh.model.getBoundary([(3, v)], combined=False, oriented=True):
        groups.add(name(2, gmsh.model.getPhysicalGroupsForEntity(2, abs(s))[0]))
        for a, b, c in gmsh.model.mesh.getElements(2, abs(s))[2][0].reshape(-1, 3).tolist():
            d = apex[tuple(sorted((a, b, c)))]
            normal = np.cross(at[b] - at[a], at[c] - at[a])
            outward = outward and s * np.dot(normal, at[d] - at[a]) < 0
    print("VOLUME", name(3, v), ";".join(sorted(groups)), outward, sep="|")
gmsh.finalize()
"#;

/// A physical group as gmsh reads it.
#[derive(Debug, PartialEq)]
struct Group {
    dim: u32,
    tag: usize,
    entities: String,
    elements: usize,
}

/// What [`GMSH_MODEL`] prints about `file`, by kind: groups by name, entities' signed names,
/// volumes' lines.
struct Model {
    groups: BTreeMap<String, Group>,
    entities: Vec<String>,
    volumes: Vec<String>,
}

fn gmsh_model(file: &std::path::Path) -> Model {
    let out = python(GMSH_MODEL, &[file.to_str().unwrap()]);
    let mut m = Model {
        groups: BTreeMap::new(),
        entities: Vec::new(),
        volumes: Vec::new(),
    };
    for line in out.lines() {
        let f: Vec<&str> = line.split('|').collect();
        match f[0] {
            "GROUP" => {
                let group = Group {
                    dim: f[1].parse().unwrap(),
                    tag: f[2].parse().unwrap(),
                    entities: f[4].to_string(),
                    elements: f[5].parse().unwrap(),
                };
                m.groups.insert(f[3].to_string(), group);
            }
            "ENTITY" => m.entities.push(f[2].to_string()),
            "VOLUME" => m.volumes.push(line.to_string()),
            _ => {}
        }
    }
    m
}

/// A build of the example (its msh in `encoding`, "msh" or "msh-binary"), the file's path and
/// the mesh our reader makes of it.
fn built(encoding: &str) -> (Scratch, std::path::PathBuf, VolumeMesh) {
    let s = Scratch::didactic_built();
    if encoding != "msh" {
        let formats = format!("formats = [\"{encoding}\", \"vtu\"]");
        s.edit("formats = [\"msh\", \"vtu\"]", &formats);
        let (ok, _, err) = s.build(&[]);
        assert!(ok, "{err}");
    }
    let path = s.path("out/didactic/didactic.msh");
    let bytes = std::fs::read(&path).expect("the msh is written");
    let mesh = read_volume_msh(&bytes, "didactic.msh").expect("reads");
    (s, path, mesh)
}

fn triangles_of(mesh: &VolumeMesh, group: &str) -> usize {
    let g = mesh.surface_groups.iter().position(|s| s.name == group);
    let g = g.unwrap_or_else(|| panic!("no group {group}")) as u32;
    mesh.triangle_group.iter().filter(|&&x| x == g).count()
}

#[test]
fn gmsh_reads_a_material_group_over_the_tets_of_every_region_of_that_material() {
    if !python_has("gmsh, numpy") {
        return;
    }
    let (_s, path, mesh) = built("msh");
    let model = gmsh_model(&path);
    let materials: BTreeSet<i64> = mesh.regions.iter().filter_map(|r| r.material).collect();
    assert_eq!(
        materials,
        BTreeSet::from([1, 2, 3]),
        "the example's materials"
    );
    for (k, &m) in materials.iter().enumerate() {
        let regions: Vec<usize> = (0..mesh.regions.len())
            .filter(|&r| mesh.regions[r].material == Some(m))
            .collect();
        let tets = (mesh.tet_region.iter())
            .filter(|&&r| regions.contains(&(r as usize)))
            .count();
        let volumes: Vec<String> = regions.iter().map(|r| (r + 1).to_string()).collect();
        let want = Group {
            dim: 3,
            tag: mesh.regions.len() + k + 1,
            entities: volumes.join(","),
            elements: tets,
        };
        assert_eq!(model.groups[&format!("material:{m}")], want, "material {m}");
        assert_eq!(
            regions.len(),
            2,
            "material {m} spans the example's two sides"
        );
    }
    // The regions' own groups are still there, one volume each.
    for (r, region) in mesh.regions.iter().enumerate() {
        assert_eq!(model.groups[&region.name].entities, (r + 1).to_string());
    }
}

#[test]
fn gmsh_reads_each_faults_front_and_back_groups_as_its_own_entities_with_the_front_reversed() {
    if !python_has("gmsh, numpy") {
        return;
    }
    let (_s, path, mesh) = built("msh");
    let model = gmsh_model(&path);
    let n = mesh.surface_groups.len();
    let faults = (mesh.surface_groups.iter()).filter(|g| g.kind == SurfaceKind::Fault);
    let mut seen = 0;
    for (k, fault) in faults.enumerate() {
        let name = &fault.name;
        let whole = &model.groups[name];
        assert_eq!(whole.elements, triangles_of(&mesh, name), "{name}");
        for (side, tag) in [("front", n + 2 * k + 1), ("back", n + 2 * k + 2)] {
            let want = Group {
                dim: 2,
                tag,
                entities: whole.entities.clone(),
                elements: whole.elements,
            };
            assert_eq!(
                model.groups[&format!("{name}:{side}")],
                want,
                "{name}:{side}"
            );
        }
        // Every entity of the fault is in its group, its front reversed and its back as is.
        let signed = format!("{name};-{name}:front;{name}:back");
        let of_fault = (model.entities.iter()).filter(|e| e.split(';').next() == Some(name));
        assert!(of_fault.clone().count() > 0, "{name} has entities");
        for e in of_fault {
            assert_eq!(e, &signed);
        }
        seen += 1;
    }
    assert_eq!(seen, 2, "F1 and F2");
}

/// Per region, the names of the groups whose triangles separate it from another region or from
/// the outside (a face of one of its tets and of no other tet of its own region).
fn boundary_groups(mesh: &VolumeMesh) -> Vec<BTreeSet<&str>> {
    let mut faces: BTreeMap<[u32; 3], Vec<usize>> = BTreeMap::new();
    for (tet, &r) in mesh.tets.iter().zip(&mesh.tet_region) {
        for k in 0..4 {
            let mut f = [0u32; 3];
            let others = (0..4).filter(|&j| j != k).map(|j| tet[j]);
            for (slot, v) in f.iter_mut().zip(others) {
                *slot = v;
            }
            f.sort_unstable();
            faces.entry(f).or_default().push(r as usize);
        }
    }
    let mut out = vec![BTreeSet::new(); mesh.regions.len()];
    for (tri, &g) in mesh.triangles.iter().zip(&mesh.triangle_group) {
        let mut key = *tri;
        key.sort_unstable();
        let name = mesh.surface_groups[g as usize].name.as_str();
        match faces[&key][..] {
            [r] => {
                out[r].insert(name);
            }
            [a, b] if a != b => {
                out[a].insert(name);
                out[b].insert(name);
            }
            _ => {}
        }
    }
    out
}

#[test]
fn gmsh_returns_the_surfaces_around_each_region_as_its_boundary_signed_outward() {
    if !python_has("gmsh, numpy") {
        return;
    }
    let (_s, path, mesh) = built("msh");
    let model = gmsh_model(&path);
    let around = boundary_groups(&mesh);
    let want: Vec<String> = (mesh.regions.iter().zip(&around))
        .map(|(r, groups)| {
            let groups: Vec<&str> = groups.iter().copied().collect();
            format!("VOLUME|{}|{}|True", r.name, groups.join(";"))
        })
        .collect();
    assert_eq!(model.volumes, want);
    // The through-going fault bounds regions; the dangling one lies inside them.
    assert!(around.iter().any(|g| g.contains("F1")));
    assert!(around.iter().all(|g| !g.contains("F2")));
}

#[test]
fn gmsh_reads_the_same_groups_and_boundaries_from_the_binary_msh_as_from_the_ascii_one() {
    if !python_has("gmsh, numpy") {
        return;
    }
    let (_a, ascii, _) = built("msh");
    let (_b, binary, _) = built("msh-binary");
    let (a, b) = (gmsh_model(&ascii), gmsh_model(&binary));
    assert_eq!(a.groups, b.groups);
    assert_eq!(a.entities, b.entities);
    assert_eq!(a.volumes, b.volumes);
}

const MESHIO_SETS: &str = r#"
import sys, meshio
m = meshio.read(sys.argv[1])
count = lambda t: sum(len(b.data) for b in m.cells if b.type == t)
print("COUNTS", len(m.points), count("tetra"), count("triangle"))
for k, v in m.cell_sets.items():
    print("SET", k, sum(len(x) for x in v if x is not None), sep="|")
"#;

#[test]
fn meshio_still_reads_the_msh_with_its_material_sets_and_the_faults_back_sides() {
    if !python_has("meshio") {
        return;
    }
    let (_s, path, mesh) = built("msh");
    let out = python(MESHIO_SETS, &[path.to_str().unwrap()]);
    let counts = format!(
        "COUNTS {} {} {}",
        mesh.nodes.len(),
        mesh.tets.len(),
        mesh.triangles.len()
    );
    assert!(out.lines().any(|l| l == counts), "{counts} not in\n{out}");
    let sets: BTreeMap<&str, usize> = (out.lines())
        .filter_map(|l| l.strip_prefix("SET|")?.split_once('|'))
        .map(|(k, v)| (k, v.parse().unwrap()))
        .collect();
    for m in 1..=3 {
        let tets = (mesh.tet_region.iter())
            .filter(|&&r| mesh.regions[r as usize].material == Some(m))
            .count();
        assert_eq!(sets[format!("material:{m}").as_str()], tets, "material {m}");
    }
    for fault in ["F1", "F2"] {
        let n = triangles_of(&mesh, fault);
        assert_eq!(sets[fault], n, "{fault}");
        assert_eq!(sets[format!("{fault}:back").as_str()], n, "{fault}:back");
        // meshio matches positive tags only: the reversed front reads as an empty set.
        assert_eq!(sets[format!("{fault}:front").as_str()], 0, "{fault}:front");
    }
}

/// Every physical group as `dim|tag|name`, and the VTU's field data as `FIELD|name|id`.
const GROUPS_AND_FIELDS: &str = r#"
import sys, gmsh, meshio
gmsh.initialize()
gmsh.option.setNumber("General.Terminal", 0)
gmsh.open(sys.argv[1])
for dim, tag in sorted(gmsh.model.getPhysicalGroups()):
    print(dim, tag, gmsh.model.getPhysicalName(dim, tag), sep="|")
for k, v in meshio.read(sys.argv[2]).field_data.items():
    print("FIELD", k, int(v[0]), sep="|")
"#;

#[test]
fn report_json_ids_are_the_msh_groups_gmsh_reads_and_the_vtu_field_data_meshio_reads() {
    if !python_has("gmsh, meshio") {
        return;
    }
    let s = Scratch::didactic_built();
    let out = python(
        GROUPS_AND_FIELDS,
        &[
            s.path("out/didactic/didactic.msh").to_str().unwrap(),
            s.path("out/didactic/didactic.vtu").to_str().unwrap(),
        ],
    );
    let got: BTreeSet<&str> = out.lines().collect();
    let report = std::fs::read_to_string(s.path("out/didactic/report.json")).unwrap();
    let report: serde_json::Value = serde_json::from_str(&report).unwrap();
    let rows = report["ids"].as_array().expect("an ids table");
    let mut kinds = BTreeSet::new();
    for row in rows {
        let (kind, name) = (row["kind"].as_str().unwrap(), row["name"].as_str().unwrap());
        kinds.insert(kind);
        let msh = row["msh"].as_str().unwrap();
        let (dim, tag) = msh.split_once("D group ").expect("a msh group");
        let want = format!("{dim}|{tag}|{name}");
        assert!(got.contains(want.as_str()), "{want} not in\n{out}");
        let vtu = row["vtu"].as_str().unwrap();
        let (array, id) = vtu.rsplit_once(' ').unwrap();
        let field = match array {
            "region" | "surface" => format!("FIELD|{array}:{name}|{id}"),
            "fault_side" => format!("FIELD|side:{name}|{id}"),
            _ => continue,
        };
        assert!(got.contains(field.as_str()), "{field} not in\n{out}");
    }
    let all = ["fault side", "material", "region", "surface"];
    assert_eq!(kinds, BTreeSet::from(all));
}

/// Walks the model down from each surface: per surface entity (`SURFACE|tag|curves|whether
/// every curve's nodes are the surface's|whether every sign follows the surface's triangles`),
/// per curve (`CURVE|tag|group|points|whether its points are its end nodes|surfaces around`),
/// then how many volumes Gmsh meshes again from the file's geometry (`REMESHED n`).
const GMSH_TOPOLOGY: &str = r#"
import sys, gmsh
gmsh.initialize()
gmsh.option.setNumber("General.Terminal", 0)
gmsh.open(sys.argv[1])
def segments(c):
    return gmsh.model.mesh.getElements(1, c)[2][0].reshape(-1, 2).tolist()
for _, s in gmsh.model.getEntities(2):
    tris = gmsh.model.mesh.getElements(2, s)[2][0].reshape(-1, 3).tolist()
    nodes = {n for t in tris for n in t}
    turns = {(t[k], t[(k + 1) % 3]) for t in tris for k in range(3)}
    on, signed = True, True
    curves = gmsh.model.getBoundary([(2, s)], combined=False, oriented=True)
    for _, c in curves:
        seg = segments(abs(c))
        on = on and all(a in nodes and b in nodes for a, b in seg)
        a, b = seg[0]
        signed = signed and ((a, b) in turns if c > 0 else (b, a) in turns)
    print("SURFACE", s, len(curves), on, signed, sep="|")
for _, c in gmsh.model.getEntities(1):
    groups = gmsh.model.getPhysicalGroupsForEntity(1, c)
    name = gmsh.model.getPhysicalName(1, groups[0]) if len(groups) else ""
    seg = segments(c)
    ends = {seg[0][0], seg[-1][1]}
    points = gmsh.model.getBoundary([(1, c)], combined=False, oriented=False)
    at = {int(gmsh.model.mesh.getNodes(0, p)[0][0]) for _, p in points}
    up, _ = gmsh.model.getAdjacencies(1, c)
    print("CURVE", c, name, len(points), at == ends, len(up), sep="|")
# Gmsh re-meshes the model from the file alone: its geometry from the discrete entities.
gmsh.model.mesh.createGeometry()
gmsh.model.mesh.clear()
gmsh.option.setNumber("Mesh.MeshSizeMax", 400)
gmsh.model.mesh.generate(3)
meshed = [v for _, v in gmsh.model.getEntities(3) if len(gmsh.model.mesh.getElements(3, v)[1])]
print("REMESHED", len(meshed))
gmsh.finalize()
"#;

#[test]
fn gmsh_walks_each_surface_to_its_curves_and_points_and_meshes_the_model_again_from_the_file() {
    if !python_has("gmsh, numpy") {
        return;
    }
    let (_s, msh, mesh) = built("msh");
    let out = python(GMSH_TOPOLOGY, &[msh.to_str().expect("utf-8 path")]);
    let surfaces: Vec<&str> = out.lines().filter(|l| l.starts_with("SURFACE|")).collect();
    assert!(surfaces.len() >= mesh.surface_groups.len(), "{out}");
    for line in &surfaces {
        let f: Vec<&str> = line.split('|').collect();
        // Every piece of the example ends somewhere (no closed surface), along its own nodes,
        // each curve signed the way the piece's triangles turn.
        assert!(f[2].parse::<usize>().unwrap() >= 1, "{line}");
        assert_eq!(f[3..], ["True", "True"], "{line}");
    }
    let curves: Vec<Vec<&str>> = (out.lines())
        .filter(|l| l.starts_with("CURVE|"))
        .map(|l| l.split('|').collect())
        .collect();
    let names: BTreeSet<&str> = curves.iter().map(|f| f[2]).collect();
    for want in ["F1/H1", "F1/H2", "F2/H1", "F2:border", "box.xmin/box.zmax"] {
        assert!(names.contains(want), "no curve group `{want}` in {names:?}");
    }
    for f in &curves {
        // An open curve's two points, or a closed one's one, are the ends of its segments; a
        // curve of two surfaces lies between at least two surface entities.
        assert!(f[3] == "2" || f[3] == "1", "{f:?}");
        assert_eq!(f[4], "True", "{f:?}");
        let meeting = if f[2].contains('/') { 2 } else { 1 };
        assert!(f[5].parse::<usize>().unwrap() >= meeting, "{f:?}");
    }
    let remeshed = format!("REMESHED {}", mesh.regions.len());
    assert!(out.lines().any(|l| l == remeshed), "{out}");
}
