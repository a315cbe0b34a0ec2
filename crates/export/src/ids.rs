//! The one id scheme every writer follows, as a table a report can show: per region, surface
//! group, fault side, material, well, named point and face set, what it is called and numbered
//! in each format. The numbers come from the same functions the writers use (`sides::fault_sides_of`,
//! [`materials`]), so the table cannot drift from the files; it depends only on the mesh's
//! groups (names, kinds, materials), not on its elements.
//!
//! Abaqus is not a column: its labels are the names made Abaqus-safe, and the `.inp`'s `**`
//! comments pair each label with its name and id.

use crate::sides::{fault_sides_of, side_name};
use geom::mesh::{RegionGroup, SurfaceGroup};
use serde::Serialize;
use std::collections::BTreeSet;

/// One thing a format names or numbers, and how each format does it.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct IdRow {
    /// `region`, `surface`, `fault side`, `material`, `well`, `point` or `group`.
    pub kind: &'static str,
    /// Its name (`material:<id>` for a material).
    pub name: String,
    /// Its Gmsh physical group.
    pub msh: String,
    /// Its Exodus II element block or sets.
    pub exodus: String,
    /// Its VTU cell data value.
    pub vtu: String,
    /// Its MEDIT reference.
    pub medit: String,
    /// Its TetGen attribute, marker or column.
    pub tetgen: String,
}

/// Every distinct material id of `regions`, ascending: the `k`-th is the msh's 3D physical
/// group `regions.len() + k + 1`.
pub fn materials(regions: &[RegionGroup]) -> Vec<i64> {
    let set: BTreeSet<i64> = regions.iter().filter_map(|r| r.material).collect();
    set.into_iter().collect()
}

/// The names of a mesh's line groups (wells), named points and face sets.
#[derive(Clone, Copy, Debug, Default)]
pub struct Named<'a> {
    pub wells: &'a [String],
    pub points: &'a [String],
    pub face_sets: &'a [String],
}

/// The id table of a mesh with these regions, surface groups, and `named` wells, points and
/// face sets.
pub fn table(regions: &[RegionGroup], groups: &[SurfaceGroup], named: Named) -> Vec<IdRow> {
    let Named {
        wells,
        points,
        face_sets,
    } = named;
    let mut rows: Vec<IdRow> = (regions.iter().enumerate())
        .map(|(r, g)| region(r + 1, g))
        .collect();
    rows.extend((groups.iter().enumerate()).map(|(g, s)| surface(g + 1, &s.name)));
    for fault in fault_sides_of(groups) {
        let name = &groups[fault.group].name;
        rows.extend([true, false].map(|front| side(fault.id(front), name, front)));
    }
    let first = regions.len() + 1;
    rows.extend((materials(regions).into_iter().enumerate()).map(|(k, m)| material(first + k, m)));
    let (n, r) = (groups.len(), regions.len());
    rows.extend((wells.iter().enumerate()).map(|(w, name)| well(w + 1, name, r, n)));
    let first_set = n + wells.len() + 1;
    rows.extend((points.iter().enumerate()).map(|(i, name)| point(i + 1, name, first_set + i)));
    let first = crate::face_sets::first_id(groups);
    let first_node_set = crate::face_sets::first_node_set(n, wells.len(), points.len());
    rows.extend(
        (face_sets.iter().enumerate())
            .map(|(k, name)| face_set(first + k, first_node_set + k, name)),
    );
    rows
}

fn row(kind: &'static str, name: String, cells: [String; 5]) -> IdRow {
    let [msh, exodus, vtu, medit, tetgen] = cells;
    IdRow {
        kind,
        name,
        msh,
        exodus,
        vtu,
        medit,
        tetgen,
    }
}

fn region(id: usize, g: &RegionGroup) -> IdRow {
    let cells = [
        format!("3D group {id}"),
        format!("element block {id}"),
        format!("region {id}"),
        format!("tetrahedron {id}"),
        format!("attribute {id}"),
    ];
    row("region", g.name.clone(), cells)
}

fn surface(id: usize, name: &str) -> IdRow {
    let cells = [
        format!("2D group {id}"),
        format!("side set, node set {id}"),
        format!("surface {id}"),
        format!("triangle {id}"),
        format!("face marker {id}"),
    ];
    row("surface", name.to_string(), cells)
}

fn side(id: usize, fault: &str, front: bool) -> IdRow {
    let (winding, column) = if front {
        ("its normal's side", "front tet")
    } else {
        ("behind its normal", "back tet")
    };
    let cells = [
        format!("2D group {id}"),
        format!("side set {id}"),
        format!("fault_side {id}"),
        format!("fault triangles, {winding}"),
        format!("face {column}"),
    ];
    row("fault side", side_name(fault, front), cells)
}

fn material(tag: usize, m: i64) -> IdRow {
    let cells = [
        format!("3D group {tag}"),
        format!("MATERIAL_ID {m}"),
        format!("MaterialIDs {m}"),
        "—".into(),
        "—".into(),
    ];
    row("material", format!("material:{m}"), cells)
}

fn well(id: usize, name: &str, regions: usize, groups: usize) -> IdRow {
    let cells = [
        format!("1D group {id}"),
        format!("element block {}, node set {}", regions + id, groups + id),
        format!("well {id}"),
        format!("edge {id}"),
        format!("edge marker {id}"),
    ];
    row("well", name.to_string(), cells)
}

/// Named point `id` (1-based, the msh's 0D group), Exodus node set `set` (after the wells'):
/// VTU names it in field data by its node's index, Abaqus by a one-node `*Nset`; MEDIT and TetGen
/// do not write it.
fn point(id: usize, name: &str, set: usize) -> IdRow {
    let cells = [
        format!("0D group {id}"),
        format!("node set {set}"),
        format!("point:{name} (node index)"),
        "—".into(),
        "—".into(),
    ];
    row("point", name.to_string(), cells)
}

/// Face set `id` (2D group, side set and VTU value), Exodus node set `node_set`: MEDIT and
/// TetGen give each triangle one tag and cannot carry overlapping sets.
fn face_set(id: usize, node_set: usize, name: &str) -> IdRow {
    let cells = [
        format!("2D group {id}"),
        format!("side set {id}, node set {node_set}"),
        format!("group:{name} {id}"),
        "—".into(),
        "—".into(),
    ];
    row("group", name.to_string(), cells)
}

#[cfg(test)]
mod tests {
    use super::*;
    use geom::mesh::SurfaceKind;

    #[test]
    fn the_table_numbers_regions_groups_fault_sides_materials_and_wells_as_the_writers_do() {
        let region = |name: &str, material| RegionGroup {
            name: name.into(),
            material,
            properties: Default::default(),
        };
        let group = |name: &str, kind| SurfaceGroup {
            name: name.into(),
            kind,
        };
        let regions = [
            region("a", Some(7)),
            region("b", None),
            region("c", Some(2)),
        ];
        let groups = [
            group("H1", SurfaceKind::Horizon),
            group("F1", SurfaceKind::Fault),
        ];
        let named = Named {
            wells: &["W".to_string()],
            points: &["W:H1".to_string()],
            face_sets: &["seafloor".to_string()],
        };
        let rows = table(&regions, &groups, named);
        let got: Vec<(&str, &str, &str)> = (rows.iter())
            .map(|r| (r.name.as_str(), r.msh.as_str(), r.exodus.as_str()))
            .collect();
        assert_eq!(
            got,
            [
                ("a", "3D group 1", "element block 1"),
                ("b", "3D group 2", "element block 2"),
                ("c", "3D group 3", "element block 3"),
                ("H1", "2D group 1", "side set, node set 1"),
                ("F1", "2D group 2", "side set, node set 2"),
                ("F1:front", "2D group 3", "side set 3"),
                ("F1:back", "2D group 4", "side set 4"),
                ("material:2", "3D group 4", "MATERIAL_ID 2"),
                ("material:7", "3D group 5", "MATERIAL_ID 7"),
                ("W", "1D group 1", "element block 4, node set 3"),
                ("W:H1", "0D group 1", "node set 4"),
                ("seafloor", "2D group 5", "side set 5, node set 5"),
            ]
        );
        assert_eq!(rows[5].vtu, "fault_side 3");
    }
}
