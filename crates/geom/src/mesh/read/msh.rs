//! Gmsh msh reader: format 4.1 (ASCII and binary, little-endian, `size_t` = 8) and 2.2 (ASCII),
//! per the Gmsh reference manual. Reads `$MeshFormat`, `$PhysicalNames`, `$Entities`, `$Nodes`,
//! `$Elements` and scalar `$ElementData`; skips other sections. Node tags may be sparse; vertices
//! are returned in node-tag order.
//!
//! [`read_msh`] returns the triangles (type 2) as a [`BoundaryMesh`] tagged by their elementary
//! entity, each entity named after its first 2D physical group; [`read_msh_lines`] the line
//! elements (type 1) as segments. [`read_volume_msh`] reads a whole
//! tet mesh back into a [`VolumeMesh`] (3D physical groups become regions, 2D ones surface
//! groups, 1D ones line groups, named 0D ones on point elements named points, the "material"
//! element data and other scalar element data become region attributes),
//! which is how exports are round-trip tested.

use super::cursor::Cursor;
use super::msh_sections::{Elem, Msh, parse};
use super::{BoundaryMesh, LineMesh, ReadError};
use crate::mesh::{LineGroup, NamedPoint, RegionGroup, SurfaceGroup, SurfaceKind, VolumeMesh};
use std::collections::BTreeMap;

/// Maps node tags to indices and checks every element's nodes.
fn resolve(m: &Msh, c: &Cursor) -> Result<Vec<[u32; 4]>, ReadError> {
    // Dense lookup when the tags are not too sparse (the usual 1..n), a map otherwise.
    let max = m.node_tags.iter().copied().max().unwrap_or(0);
    let dense = max <= 2 * m.node_tags.len() as u64 + 1024;
    let mut table: Vec<u32> = Vec::new();
    let mut map: BTreeMap<u64, u32> = BTreeMap::new();
    if dense {
        table = vec![u32::MAX; max as usize + 1];
    }
    for (i, &t) in m.node_tags.iter().enumerate() {
        let old = if dense {
            std::mem::replace(&mut table[t as usize], i as u32) != u32::MAX
        } else {
            map.insert(t, i as u32).is_some()
        };
        if old {
            return Err(c.err(format!("node tag {t} is defined twice")));
        }
    }
    let lookup = |t: u64| -> Option<u32> {
        if dense {
            table
                .get(usize::try_from(t).ok()?)
                .copied()
                .filter(|&i| i != u32::MAX)
        } else {
            map.get(&t).copied()
        }
    };
    m.elems
        .iter()
        .map(|e| {
            let mut out = [0u32; 4];
            for (k, slot) in out.iter_mut().enumerate().take(e.n) {
                *slot = lookup(e.nodes[k]).ok_or_else(|| {
                    c.err_at(
                        e.at,
                        format!(
                            "element {} refers to node {}, which is not defined",
                            e.tag, e.nodes[k]
                        ),
                    )
                })?;
            }
            Ok(out)
        })
        .collect()
}

/// The physical group of an element of dimension `dim`, if any.
fn phys_of(m: &Msh, e: &Elem) -> Option<i32> {
    e.phys.filter(|&p| p != 0).or_else(|| {
        m.entity_phys
            .get(&(e.dim, e.entity))
            .and_then(|v| v.first().copied())
    })
}

/// Whether a line element lies on one of the model's curves, as our `$GeorecipeSurfaceKinds`
/// section marks their 1D physical groups.
fn is_curve(m: &Msh, e: &Elem) -> bool {
    phys_of(m, e).is_some_and(|p| m.curves.contains(&p))
}

/// Reads the triangles of a Gmsh msh file (4.1 ASCII/binary, 2.2 ASCII).
pub fn read_msh(bytes: &[u8], label: &str) -> Result<BoundaryMesh, ReadError> {
    let m = parse(bytes, label)?;
    let c = Cursor::new(bytes, label);
    let idx = resolve(&m, &c)?;
    let mut out = BoundaryMesh {
        vertices: m.nodes.clone(),
        ..Default::default()
    };
    for (e, ix) in m.elems.iter().zip(&idx) {
        if e.n != 3 {
            continue;
        }
        out.triangles.push([ix[0], ix[1], ix[2]]);
        out.triangle_tag.push(e.entity);
        if let Some(name) = phys_of(&m, e).and_then(|p| m.names.get(&(2, p))) {
            out.tag_names
                .entry(e.entity)
                .or_insert_with(|| name.clone());
        }
    }
    if out.triangles.is_empty() {
        return Err(c.err_at(bytes.len(), "the file holds no triangles (element type 2)"));
    }
    Ok(out)
}

/// Reads the line elements (type 1: two nodes each) of a Gmsh msh file as segments, but for the
/// model's curves bounding the surfaces of one of our volume meshes.
pub fn read_msh_lines(bytes: &[u8], label: &str) -> Result<LineMesh, ReadError> {
    let m = parse(bytes, label)?;
    let c = Cursor::new(bytes, label);
    let idx = resolve(&m, &c)?;
    let lines: Vec<[u32; 2]> = (m.elems.iter().zip(&idx))
        .filter(|(e, _)| e.n == 2 && !is_curve(&m, e))
        .map(|(_, ix)| [ix[0], ix[1]])
        .collect();
    if lines.is_empty() {
        return Err(c.err_at(bytes.len(), "the file holds no lines (element type 1)"));
    }
    Ok(LineMesh {
        vertices: m.nodes,
        lines,
    })
}

/// Reads a tet mesh (tets type 4, triangles type 2, lines type 1, points type 15) back into a
/// [`VolumeMesh`]: regions are the 3D physical groups in tag order (an element without one goes
/// to a group named after its entity), line groups the 1D ones (but the model's curves, which
/// our writer marks), named points the point elements
/// of named 0D ones (sorted by name; unnamed or group-less points, such as the geometry points
/// Gmsh saves, are skipped), surface groups the 2D ones (kinds from our `$GeorecipeSurfaceKinds` section, else `Other`). Region attributes come from
/// scalar `$ElementData`: "material" (negative or NaN = none) and every other view as a property,
/// taken from the region's first tet that has a finite value.
pub fn read_volume_msh(bytes: &[u8], label: &str) -> Result<VolumeMesh, ReadError> {
    let m = parse(bytes, label)?;
    let c = Cursor::new(bytes, label);
    let idx = resolve(&m, &c)?;
    let mut out = VolumeMesh {
        nodes: m.nodes.clone(),
        ..Default::default()
    };
    // Group keys: Ok(physical tag) or Err(entity tag) when the element has no physical group.
    let key = |e: &Elem| phys_of(&m, e).ok_or(e.entity);
    let mut reg_keys: BTreeMap<Result<i32, i32>, u32> = BTreeMap::new();
    let mut grp_keys: BTreeMap<Result<i32, i32>, u32> = BTreeMap::new();
    let mut line_keys: BTreeMap<Result<i32, i32>, u32> = BTreeMap::new();
    // Line elements of the model's curves are not line groups.
    let grouped_line = |e: &Elem| e.n == 2 && !is_curve(&m, e);
    for e in &m.elems {
        match e.n {
            4 => reg_keys.insert(key(e), 0),
            3 => grp_keys.insert(key(e), 0),
            2 if grouped_line(e) => line_keys.insert(key(e), 0),
            _ => None,
        };
    }
    let name = |dim: i32, k: &Result<i32, i32>| match k {
        Ok(p) => m
            .names
            .get(&(dim, *p))
            .cloned()
            .unwrap_or_else(|| format!("physical_{p}")),
        Err(ent) => format!("entity_{ent}"),
    };
    for (i, (k, v)) in reg_keys.iter_mut().enumerate() {
        *v = i as u32;
        out.regions.push(RegionGroup {
            name: name(3, k),
            material: None,
            properties: BTreeMap::new(),
        });
    }
    for (i, (k, v)) in grp_keys.iter_mut().enumerate() {
        *v = i as u32;
        let kind = k
            .ok()
            .and_then(|p| m.kinds.get(&p).copied())
            .unwrap_or(SurfaceKind::Other);
        out.surface_groups.push(SurfaceGroup {
            name: name(2, k),
            kind,
        });
    }
    for (i, (k, v)) in line_keys.iter_mut().enumerate() {
        *v = i as u32;
        out.lines.push(LineGroup {
            area: None,
            name: name(1, k),
            lines: Vec::new(),
        });
    }
    for (e, ix) in m.elems.iter().zip(&idx) {
        if e.n == 1 {
            let named = phys_of(&m, e).and_then(|p| m.names.get(&(0, p)));
            if let Some(name) = named {
                out.points.push(NamedPoint {
                    name: name.clone(),
                    node: ix[0],
                });
            }
        } else if grouped_line(e) {
            out.lines[line_keys[&key(e)] as usize]
                .lines
                .push([ix[0], ix[1]]);
        } else if e.n == 4 {
            let r = reg_keys[&key(e)];
            out.tets.push(*ix);
            out.tet_region.push(r);
            let region = &mut out.regions[r as usize];
            for (view, vals) in &m.data {
                let Some(&v) = vals.get(&e.tag) else { continue };
                if !v.is_finite() {
                    continue;
                }
                if view == "material" {
                    if region.material.is_none() && v >= 0.0 && v.fract() == 0.0 {
                        region.material = Some(v as i64);
                    }
                } else {
                    region.properties.entry(view.clone()).or_insert(v);
                }
            }
        } else if e.n == 3 {
            out.triangles.push([ix[0], ix[1], ix[2]]);
            out.triangle_group.push(grp_keys[&key(e)]);
        }
    }
    if out.tets.is_empty() {
        return Err(c.err_at(bytes.len(), "the file holds no tetrahedra (element type 4)"));
    }
    out.points.sort_by(|a, b| a.name.cmp(&b.name));
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    const V22: &str = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n1\n2 7 \"top face\"\n$EndPhysicalNames\n\
$Nodes\n4\n10 0 0 0\n20 1 0 0\n30 0 1 0\n40 0 0 1\n$EndNodes\n$Elements\n2\n1 2 2 7 3 10 20 30\n2 15 2 1 1 40\n$EndElements\n";

    #[test]
    fn a_version_2_2_file_gives_triangles_tagged_by_elementary_entity_with_physical_names() {
        let m = read_msh(V22.as_bytes(), "v22.msh").unwrap();
        assert_eq!(m.triangles, vec![[0, 1, 2]]);
        assert_eq!(m.triangle_tag, vec![3]);
        assert_eq!(m.tag_names.get(&3).map(String::as_str), Some("top face"));
    }

    #[test]
    fn a_triangle_pointing_at_a_missing_node_names_the_line() {
        let bad = V22.replace("1 2 2 7 3 10 20 30", "1 2 2 7 3 10 20 99");
        let e = read_msh(bad.as_bytes(), "bad.msh").unwrap_err();
        assert_eq!(e.line, 17, "{e}");
        assert!(e.message.contains("node 99"), "{e}");
    }

    #[test]
    fn very_sparse_node_tags_are_looked_up_through_a_map() {
        let sparse = V22
            .replace("\n10 0 0 0", "\n1000000000000 0 0 0")
            .replace(" 10 20 30", " 1000000000000 20 30");
        let m = read_msh(sparse.as_bytes(), "s.msh").unwrap();
        // Vertices come in tag order: the huge tag is last.
        assert_eq!(m.triangles, vec![[3, 0, 1]]);
        assert_eq!(m.vertices[3], [0.0; 3]);
        let dup = V22.replace("\n20 1 0 0", "\n10 1 0 0");
        assert!(
            read_msh(dup.as_bytes(), "d.msh")
                .unwrap_err()
                .message
                .contains("node tag 10 is defined twice")
        );
    }

    #[test]
    fn line_elements_are_read_as_segments_and_a_file_without_any_is_refused() {
        let with = V22.replace("$Elements\n2\n", "$Elements\n3\n3 1 2 5 9 10 40\n");
        let m = read_msh_lines(with.as_bytes(), "w.msh").unwrap();
        assert_eq!(m.lines, vec![[0, 3]]);
        assert_eq!(m.vertices[3], [0.0, 0.0, 1.0]);
        // The triangles are read as before.
        assert_eq!(
            read_msh(with.as_bytes(), "w.msh").unwrap().triangles.len(),
            1
        );
        let e = read_msh_lines(V22.as_bytes(), "v22.msh").unwrap_err();
        assert!(e.message.contains("no lines (element type 1)"), "{e}");
    }

    #[test]
    fn a_truncated_file_is_an_error_not_a_panic() {
        for cut in [10, 40, 90, 130, 160, V22.len() - 14] {
            let e = read_msh(&V22.as_bytes()[..cut], "cut.msh");
            assert!(e.is_err(), "cut at {cut} was accepted");
        }
    }

    #[test]
    fn an_unsupported_version_is_named() {
        let e = read_msh(b"$MeshFormat\n3.0 0 8\n$EndMeshFormat\n", "v3.msh").unwrap_err();
        assert_eq!(
            e.to_string(),
            "v3.msh:2: msh format version 3.0 is not supported (4.1 and 2.2 are)"
        );
    }
}
