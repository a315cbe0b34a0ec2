//! The six regions of the didactic model whose boundaries Gmsh meshed
//! (`../shared/data/peer-boundaries/region_L1_<name>.off`), with the dangling fault's triangles
//! from `didactic_L1_surface.msh` embedded where `didactic_L1_meta.json` says. The OFF files print
//! coordinates with 6 decimals, so msh nodes are matched to OFF vertices on coordinates rounded to
//! 1e-6 (the OFF coordinates are kept) and the others are added as they are. Shared by the peer
//! tests and the tet mesher's bench.

use geom::mesh::read::{BoundaryMesh, read_by_extension};
use std::collections::BTreeMap;
use tet_mesh::RegionInput;

/// The peer-boundaries folder, or `None` (after printing a note) when ../shared is absent.
pub fn peer_dir() -> Option<String> {
    crate::paths::shared("data/peer-boundaries").map(|p| p.display().to_string())
}

fn read(path: &str) -> Result<BoundaryMesh, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("{path}: {e}"))?;
    read_by_extension(path, &bytes).map_err(|e| e.to_string())
}

/// Region `name` ("overburden_W", ...) of level L1 in `dir`, dangling-fault faces embedded.
pub fn peer_region(dir: &str, name: &str) -> Result<RegionInput, String> {
    let off = read(&format!("{dir}/region_L1_{name}.off"))?;
    let (mut vertices, boundary) = (off.vertices, off.triangles);
    let meta_path = format!("{dir}/didactic_L1_meta.json");
    let meta: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(&meta_path).map_err(|e| format!("{meta_path}: {e}"))?,
    )
    .map_err(|e| format!("{meta_path}: {e}"))?;
    let ents: Vec<i32> = meta["embedded"][name]
        .as_array()
        .ok_or_else(|| format!("{meta_path}: no embedded list for {name}"))?
        .iter()
        .filter_map(|v| v.as_i64())
        .map(|v| v as i32)
        .collect();
    let mut embedded = Vec::new();
    if !ents.is_empty() {
        let msh = read(&format!("{dir}/didactic_L1_surface.msh"))?;
        let key = |p: [f64; 3]| p.map(|c| (c * 1e6).round() as i64);
        let mut index: BTreeMap<[i64; 3], u32> = BTreeMap::new();
        for (i, p) in vertices.iter().enumerate() {
            index.insert(key(*p), i as u32);
        }
        for (t, tag) in msh.triangles.iter().zip(&msh.triangle_tag) {
            if !ents.contains(tag) {
                continue;
            }
            let tri = t.map(|v| {
                let p = msh.vertices[v as usize];
                *index.entry(key(p)).or_insert_with(|| {
                    vertices.push(p);
                    (vertices.len() - 1) as u32
                })
            });
            embedded.push(tri);
        }
    }
    Ok(RegionInput {
        name: name.into(),
        vertices,
        boundary,
        embedded,
        lines: Vec::new(),
    })
}
