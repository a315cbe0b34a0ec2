//! Abaqus `.inp` writer (also read by CalculiX, PyLith's converters and meshio): `*Node`,
//! one `*Element, type=C3D4, elset=<region>` block per region, and for every surface group a
//! node set (`*Nset`, for boundary conditions) and an element-face surface (`*Surface,
//! type=ELEMENT`) built from the tet that owns each triangle (the lowest-numbered one for an
//! interior face such as a horizon or a dangling fault). Abaqus names cannot hold spaces or
//! commas: names are sanitised (and made unique) and the original names, material ids and
//! region properties are listed in `**` comment lines, which every reader skips.

use super::{property_names, split_by};
use geom::mesh::VolumeMesh;
use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write as _;

/// An Abaqus-safe label: letters, digits, `_`; starting with a letter; unique in `taken`.
fn label(name: &str, fallback: &str, taken: &mut BTreeSet<String>) -> String {
    let mut s: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect();
    if !s.chars().next().is_some_and(|c| c.is_ascii_alphabetic()) {
        s = format!("{fallback}_{s}");
    }
    let mut out = s.clone();
    let mut k = 2;
    while !taken.insert(out.to_ascii_uppercase()) {
        out = format!("{s}_{k}");
        k += 1;
    }
    out
}

/// Writes `items` comma-separated, at most 16 per line (the Abaqus data-line limit).
fn list(s: &mut String, items: impl Iterator<Item = usize>) {
    let mut k = 0;
    for it in items {
        if k > 0 {
            s.push_str(if k % 16 == 0 { ",\n" } else { ", " });
        }
        let _ = write!(s, "{it}");
        k += 1;
    }
    if k > 0 {
        s.push('\n');
    }
}

/// Fails when a surface triangle is not a face of any tet (Abaqus surfaces are element faces).
pub(super) fn write(mesh: &VolumeMesh, model: &str) -> Result<Vec<u8>, String> {
    let mut s = String::new();
    let _ = writeln!(s, "*Heading\n georecipe model {model}");
    let mut taken = BTreeSet::new();
    let region_labels: Vec<String> = mesh
        .regions
        .iter()
        .enumerate()
        .map(|(r, g)| label(&g.name, &format!("R{}", r + 1), &mut taken))
        .collect();
    let group_labels: Vec<String> = mesh
        .surface_groups
        .iter()
        .enumerate()
        .map(|(i, g)| label(&g.name, &format!("S{}", i + 1), &mut taken))
        .collect();
    let props = property_names(mesh);
    for (r, g) in mesh.regions.iter().enumerate() {
        let mat = g.material.map_or("none".to_string(), |m| m.to_string());
        let _ = write!(
            s,
            "** region {} \"{}\" elset={} material={}",
            r + 1,
            g.name,
            region_labels[r],
            mat
        );
        for p in &props {
            if let Some(v) = g.properties.get(p) {
                let _ = write!(s, " {p}={v}");
            }
        }
        s.push('\n');
    }
    for (i, g) in mesh.surface_groups.iter().enumerate() {
        let _ = writeln!(
            s,
            "** surface {} \"{}\" nset/surface={}",
            i + 1,
            g.name,
            group_labels[i]
        );
    }
    s.push_str("*Node\n");
    for (i, p) in mesh.nodes.iter().enumerate() {
        let _ = writeln!(s, "{}, {}, {}, {}", i + 1, p[0], p[1], p[2]);
    }
    // Element numbers: tets in region order, 1-based; remember each tet's number.
    let by_region = split_by(&mesh.tet_region, mesh.regions.len());
    let mut number = vec![0usize; mesh.tets.len()];
    let mut next = 1;
    for (r, sel) in by_region.iter().enumerate() {
        if sel.is_empty() {
            continue;
        }
        let _ = writeln!(s, "*Element, type=C3D4, elset={}", region_labels[r]);
        for &t in sel {
            let [a, b, c, d] = mesh.tets[t];
            let _ = writeln!(s, "{next}, {}, {}, {}, {}", a + 1, b + 1, c + 1, d + 1);
            number[t] = next;
            next += 1;
        }
    }
    // Faces of C3D4 in Abaqus order: S1 = 1-2-3, S2 = 1-4-2, S3 = 2-4-3, S4 = 3-4-1.
    const FACES: [[usize; 3]; 4] = [[0, 1, 2], [0, 3, 1], [1, 3, 2], [2, 3, 0]];
    let mut owner: BTreeMap<[u32; 3], (usize, usize)> = BTreeMap::new();
    for (t, tet) in mesh.tets.iter().enumerate() {
        for (f, loc) in FACES.iter().enumerate() {
            let mut key = loc.map(|k| tet[k]);
            key.sort_unstable();
            let e = owner.entry(key).or_insert((number[t], f + 1));
            if number[t] < e.0 {
                *e = (number[t], f + 1);
            }
        }
    }
    let by_group = split_by(&mesh.triangle_group, mesh.surface_groups.len());
    for (g, sel) in by_group.iter().enumerate() {
        let nodes: BTreeSet<u32> = sel.iter().flat_map(|&t| mesh.triangles[t]).collect();
        let _ = writeln!(s, "*Nset, nset={}", group_labels[g]);
        list(&mut s, nodes.iter().map(|&v| v as usize + 1));
        // Element faces grouped by face number (one element set per face side).
        let mut sides: BTreeMap<usize, BTreeSet<usize>> = BTreeMap::new();
        for &t in sel {
            let mut key = mesh.triangles[t];
            key.sort_unstable();
            let Some(&(e, f)) = owner.get(&key) else {
                let [a, b, c] = mesh.triangles[t];
                return Err(format!(
                    "surface '{}' triangle {t} ({:?}, {:?}, {:?}) is not a face of any tet: Abaqus cannot name it",
                    mesh.surface_groups[g].name,
                    mesh.nodes[a as usize],
                    mesh.nodes[b as usize],
                    mesh.nodes[c as usize]
                ));
            };
            sides.entry(f).or_default().insert(e);
        }
        for (f, elems) in &sides {
            let _ = writeln!(s, "*Elset, elset={}_S{f}", group_labels[g]);
            list(&mut s, elems.iter().copied());
        }
        if !sides.is_empty() {
            let _ = writeln!(s, "*Surface, type=ELEMENT, name={}", group_labels[g]);
            for f in sides.keys() {
                let _ = writeln!(s, "{}_S{f}, S{f}", group_labels[g]);
            }
        }
    }
    s.shrink_to_fit();
    Ok(s.into_bytes())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_triangle_that_is_no_tet_face_is_refused_with_its_coordinates() {
        let mesh = VolumeMesh {
            nodes: vec![
                [0.0; 3],
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [0.0, 0.0, 1.0],
                [5.0, 5.0, 5.0],
            ],
            tets: vec![[0, 1, 2, 3]],
            tet_region: vec![0],
            regions: vec![geom::mesh::RegionGroup {
                name: "r".into(),
                material: None,
                properties: Default::default(),
            }],
            triangles: vec![[0, 1, 2], [0, 1, 4]],
            triangle_group: vec![0, 0],
            surface_groups: vec![geom::mesh::SurfaceGroup {
                name: "fault".into(),
                kind: geom::mesh::SurfaceKind::Fault,
            }],
        };
        let e = write(&mesh, "m").unwrap_err();
        assert!(
            e.contains("'fault' triangle 1") && e.contains("[5.0, 5.0, 5.0]"),
            "{e}"
        );
    }

    #[test]
    fn labels_are_abaqus_safe_and_unique() {
        let mut taken = BTreeSet::new();
        assert_eq!(label("H1 top", "S1", &mut taken), "H1_top");
        assert_eq!(label("h1,top", "S2", &mut taken), "h1_top_2");
        assert_eq!(label("2nd", "R3", &mut taken), "R3_2nd");
    }
}
