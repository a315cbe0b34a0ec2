//! A realistic multi-region mesh for report tests and the `report_peers` example: regions of the
//! didactic model whose boundaries Gmsh meshed (`../shared/data/peer-boundaries`), each filled by
//! our tet mesher, merged on shared nodes (coordinates rounded to 1e-6, as the OFF files print
//! them), with every boundary triangle tagged by the surface the Gmsh surface mesh says it lies
//! on (box, H1_top_reservoir, H2_base_reservoir, F1_through, F2_dangling).

use geom::mesh::read::{BoundaryMesh, read_by_extension};
use geom::mesh::{RegionGroup, SurfaceGroup, SurfaceKind, VolumeMesh};
use std::collections::{BTreeMap, BTreeSet};
use tet_mesh::{RegionInput, SizeField, TetMeshOptions, mesh_region};

pub fn shared_dir() -> Option<String> {
    crate::paths::shared("data/peer-boundaries").map(|p| p.display().to_string())
}

fn read(path: &str) -> Result<BoundaryMesh, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("{path}: {e}"))?;
    read_by_extension(path, &bytes).map_err(|e| e.to_string())
}

type Key = [i64; 3];

fn key(p: &[f64; 3]) -> Key {
    p.map(|c| (c * 1e6).round() as i64)
}

fn tri_key(t: [Key; 3]) -> [Key; 3] {
    let mut t = t;
    t.sort();
    t
}

fn kind_of(surface: &str) -> SurfaceKind {
    if surface.starts_with("box") {
        SurfaceKind::Box
    } else if surface.starts_with('F') {
        SurfaceKind::Fault
    } else if surface.starts_with('H') {
        SurfaceKind::Horizon
    } else {
        SurfaceKind::Other
    }
}

/// The merged mesh of `regions` (names as in the meta file, e.g. "overburden_W"), and the
/// enclosed volume of each region according to the meta file.
pub fn peer_mesh(dir: &str, regions: &[&str]) -> Result<(VolumeMesh, Vec<f64>), String> {
    let meta: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(format!("{dir}/didactic_L1_meta.json"))
            .map_err(|e| e.to_string())?,
    )
    .map_err(|e| e.to_string())?;
    let msh = read(&format!("{dir}/didactic_L1_surface.msh"))?;
    let surface_of_entity = |tag: i32| -> String {
        meta["surfaces"][tag.to_string()]
            .as_str()
            .unwrap_or("unknown")
            .to_string()
    };
    // Surface of every Gmsh triangle, by its corners' keys.
    let mut surface_of: BTreeMap<[Key; 3], String> = BTreeMap::new();
    for (t, &tag) in msh.triangles.iter().zip(&msh.triangle_tag) {
        let k = tri_key(t.map(|v| key(&msh.vertices[v as usize])));
        surface_of.insert(k, surface_of_entity(tag));
    }
    let names: BTreeSet<String> = surface_of.values().cloned().collect();
    let mut mesh = VolumeMesh::default();
    for n in &names {
        mesh.surface_groups.push(SurfaceGroup {
            name: n.clone(),
            kind: kind_of(n),
        });
    }
    let group: BTreeMap<String, u32> = names
        .iter()
        .enumerate()
        .map(|(i, n)| (n.clone(), i as u32))
        .collect();
    let mut pool: BTreeMap<Key, u32> = BTreeMap::new();
    let mut seen: BTreeSet<[u32; 3]> = BTreeSet::new();
    let mut volumes = Vec::new();
    for (ri, name) in regions.iter().enumerate() {
        let off = read(&format!("{dir}/region_L1_{name}.off"))?;
        let mut vertices = off.vertices.clone();
        let mut index: BTreeMap<Key, u32> = BTreeMap::new();
        for (i, p) in vertices.iter().enumerate() {
            index.insert(key(p), i as u32);
        }
        let ents: Vec<i64> = meta["embedded"][*name]
            .as_array()
            .map(|a| a.iter().filter_map(|v| v.as_i64()).collect())
            .unwrap_or_default();
        let mut embedded = Vec::new();
        for (t, &tag) in msh.triangles.iter().zip(&msh.triangle_tag) {
            if !ents.contains(&(tag as i64)) {
                continue;
            }
            embedded.push(t.map(|v| {
                let p = msh.vertices[v as usize];
                *index.entry(key(&p)).or_insert_with(|| {
                    vertices.push(p);
                    (vertices.len() - 1) as u32
                })
            }));
        }
        let input = RegionInput {
            name: name.to_string(),
            vertices,
            boundary: off.triangles.clone(),
            embedded,
            lines: Vec::new(),
        };
        let out = mesh_region(&input, &SizeField::default(), &TetMeshOptions::default())
            .map_err(|e| e.to_string())?;
        let map: Vec<u32> = out
            .nodes
            .iter()
            .map(|p| {
                *pool.entry(key(p)).or_insert_with(|| {
                    mesh.nodes.push(*p);
                    (mesh.nodes.len() - 1) as u32
                })
            })
            .collect();
        for t in &out.tets {
            mesh.tets.push(t.map(|v| map[v as usize]));
            mesh.tet_region.push(ri as u32);
        }
        for t in input.boundary.iter().chain(&input.embedded) {
            let g = t.map(|v| map[v as usize]);
            let mut s = g;
            s.sort();
            if !seen.insert(s) {
                continue;
            }
            let k = tri_key(t.map(|v| key(&input.vertices[v as usize])));
            let surface = surface_of
                .get(&k)
                .ok_or_else(|| format!("{name}: a boundary triangle is on no Gmsh surface"))?;
            mesh.triangles.push(g);
            mesh.triangle_group.push(group[surface]);
        }
        mesh.regions.push(RegionGroup {
            name: name.to_string(),
            material: Some(ri as i64 + 1),
            properties: Default::default(),
        });
        volumes.push(
            meta["region_checks"][*name]["enclosed_volume_m3"]
                .as_f64()
                .unwrap_or(f64::NAN),
        );
    }
    Ok((mesh, volumes))
}
