//! The model the msh file describes: its discrete entities, how they bound each other, and the
//! physical groups attached to them (see the module doc of [`super`] for why).

use super::tag;
use crate::numbering::Numbering;
use crate::sides::{face_uses, fault_sides, on_side, side_name};
use geom::mesh::VolumeMesh;
use std::collections::{BTreeMap, BTreeSet};

/// A surface entity: the triangles of one surface group with the same region on their front
/// and the same behind (`None`: outside the model, or no tet at all), in the same face sets.
struct Piece {
    group: usize,
    front: Option<usize>,
    back: Option<usize>,
    sets: Vec<usize>,
}

/// The entities and physical groups of a mesh. Surface entity `k` (0-based) is piece `k`, volume
/// entity `r` is region `r`; their tags are the index + 1.
pub(super) struct Topology {
    /// Per piece: its triangle indices, ascending.
    pub(super) tris: Vec<Vec<usize>>,
    /// Per piece: its physical tags, its group's first (signed: a negative tag holds the piece
    /// reversed).
    pub(super) surface_physicals: Vec<Vec<i32>>,
    /// Per region: its physical tags, its own first, then its material's.
    pub(super) volume_physicals: Vec<Vec<i32>>,
    /// Per region: its bounding surface entities, signed (+ where their normals point out of it).
    pub(super) volume_bounds: Vec<Vec<i32>>,
    /// Every physical group as (dimension, tag, name), by dimension, then tag.
    pub(super) names: Vec<(i32, i32, String)>,
}

impl Topology {
    /// The entities and groups of `mesh` (whose indices are in range).
    pub(super) fn new(mesh: &VolumeMesh) -> Topology {
        let (pieces, tris) = pieces(mesh);
        let n = mesh.surface_groups.len();
        let regions = mesh.regions.len();
        let mut names = Vec::new();
        for (g, sg) in mesh.surface_groups.iter().enumerate() {
            names.push((2, tag(g), sg.name.clone()));
        }
        // Per group, the physical tags its pieces carry after the group's own.
        let mut extra: Vec<Vec<i32>> = vec![Vec::new(); n];
        for fault in fault_sides(mesh) {
            let name = &mesh.surface_groups[fault.group].name;
            for front in [true, false] {
                let id = tag(fault.id(front) - 1);
                names.push((2, id, side_name(name, front)));
                // The sign the pieces have in the boundary of the volume on that side.
                extra[fault.group].push(if front { -id } else { id });
            }
        }
        let first_set = crate::face_sets::first_id(&mesh.surface_groups);
        for (k, set) in mesh.face_sets.iter().enumerate() {
            names.push((2, tag(first_set + k - 1), set.name.clone()));
        }
        let surface_physicals = pieces
            .iter()
            .map(|p| {
                let sets = p.sets.iter().map(|&k| tag(first_set + k - 1));
                std::iter::once(tag(p.group))
                    .chain(extra[p.group].iter().copied())
                    .chain(sets)
            })
            .map(Iterator::collect)
            .collect();
        let material_tag: BTreeMap<i64, i32> = (crate::ids::materials(&mesh.regions))
            .into_iter()
            .enumerate()
            .map(|(k, m)| (m, tag(regions + k)))
            .collect();
        for (r, rg) in mesh.regions.iter().enumerate() {
            names.push((3, tag(r), rg.name.clone()));
        }
        for (&m, &t) in &material_tag {
            names.push((3, t, format!("material:{m}")));
        }
        let volume_physicals = (mesh.regions.iter().enumerate())
            .map(|(r, rg)| {
                let material = rg.material.map(|m| material_tag[&m]);
                std::iter::once(tag(r)).chain(material).collect()
            })
            .collect();
        let mut volume_bounds = vec![Vec::new(); regions];
        for (k, p) in pieces.iter().enumerate() {
            if p.front == p.back {
                continue;
            }
            if let Some(r) = p.back {
                volume_bounds[r].push(tag(k));
            }
            if let Some(r) = p.front {
                volume_bounds[r].push(-tag(k));
            }
        }
        Topology {
            tris,
            surface_physicals,
            volume_physicals,
            volume_bounds,
            names,
        }
    }
}

/// What tells pieces apart: group, region in front, region behind, face sets.
type PieceKey = (usize, Option<usize>, Option<usize>, Vec<usize>);

/// The pieces of every surface group, in order of group, region in front, region behind
/// (`None` first) and face sets; a group without triangles keeps one empty piece, so that its
/// physical groups have an entity.
fn pieces(mesh: &VolumeMesh) -> (Vec<Piece>, Vec<Vec<usize>>) {
    let numbering = Numbering::new(mesh);
    let uses = face_uses(mesh, &numbering.number);
    let region = |front: bool, t: usize| {
        on_side(&uses[t], front).map(|u| mesh.tet_region[u.tet as usize] as usize)
    };
    let mut sets = crate::face_sets::memberships(mesh);
    let mut by_key: BTreeMap<PieceKey, Vec<usize>> = (0..mesh.surface_groups.len())
        .map(|g| ((g, None, None, Vec::new()), Vec::new()))
        .collect();
    for (t, &g) in mesh.triangle_group.iter().enumerate() {
        let key = (
            g as usize,
            region(true, t),
            region(false, t),
            std::mem::take(&mut sets[t]),
        );
        by_key.entry(key).or_default().push(t);
    }
    // The placeholder of a group that has triangles elsewhere goes.
    let groups_with_triangles: BTreeSet<usize> = (by_key.iter())
        .filter(|(_, tris)| !tris.is_empty())
        .map(|((g, ..), _)| *g)
        .collect();
    by_key
        .into_iter()
        .filter(|((g, ..), tris)| !tris.is_empty() || !groups_with_triangles.contains(g))
        .map(|((group, front, back, sets), tris)| {
            (
                Piece {
                    group,
                    front,
                    back,
                    sets,
                },
                tris,
            )
        })
        .unzip()
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use geom::mesh::{RegionGroup, SurfaceGroup, SurfaceKind};

    /// Tet A (region `a`) between tet B (region `b`, below the horizon `H`) and tet C (region
    /// `a` again, beyond the fault `F`), two outer faces in `box`, a fault `G` without triangles,
    /// and a region `c` without tets. `a` and `b` share material 7, `c` has 3.
    pub(crate) fn three_tets() -> VolumeMesh {
        let group = |name: &str, kind| SurfaceGroup {
            name: name.into(),
            kind,
        };
        let region = |name: &str, material| RegionGroup {
            name: name.into(),
            material: Some(material),
            properties: Default::default(),
        };
        VolumeMesh {
            nodes: vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [0.0, 0.0, 1.0],
                [0.0, 0.0, -1.0],
                [1.0, 1.0, 1.0],
            ],
            tets: vec![[0, 1, 2, 3], [0, 2, 1, 4], [1, 2, 3, 5]],
            tet_region: vec![0, 1, 0],
            regions: vec![region("a", 7), region("b", 7), region("c", 3)],
            // H's normal points to A, F's to C, each box face's into its tet.
            triangles: vec![[0, 1, 2], [1, 2, 3], [0, 3, 1], [0, 1, 4]],
            triangle_group: vec![1, 2, 0, 0],
            surface_groups: vec![
                group("box", SurfaceKind::Box),
                group("H", SurfaceKind::Horizon),
                group("F", SurfaceKind::Fault),
                group("G", SurfaceKind::Fault),
            ],
            lines: Vec::new(),
            points: Vec::new(),
            face_sets: Vec::new(),
        }
    }

    #[test]
    fn a_group_splits_into_pieces_by_the_regions_on_its_two_sides() {
        let t = Topology::new(&three_tets());
        // box in front of a, box in front of b, H, F, and G's empty placeholder.
        assert_eq!(t.tris, vec![vec![2], vec![3], vec![0], vec![1], vec![]]);
    }

    #[test]
    fn a_volume_lists_its_pieces_positive_where_their_normals_point_out_and_not_a_fault_inside_it()
    {
        let t = Topology::new(&three_tets());
        // a: the box face and H point into it; F lies inside it. b: its box face points into it,
        // H out of it. c has no tets.
        assert_eq!(t.volume_bounds, vec![vec![-1, -3], vec![-2, 3], vec![]]);
    }

    #[test]
    fn regions_of_one_material_share_its_group_numbered_after_the_regions() {
        let t = Topology::new(&three_tets());
        assert_eq!(t.volume_physicals, vec![vec![1, 5], vec![2, 5], vec![3, 4]]);
        let volumes: Vec<_> = t.names.iter().filter(|n| n.0 == 3).cloned().collect();
        let named = |tag: i32, name: &str| (3, tag, name.to_string());
        assert_eq!(
            volumes,
            [
                named(1, "a"),
                named(2, "b"),
                named(3, "c"),
                named(4, "material:3"),
                named(5, "material:7")
            ]
        );
    }

    #[test]
    fn a_faults_sides_hold_its_pieces_front_negated_with_the_exodus_side_set_ids() {
        let t = Topology::new(&three_tets());
        let surfaces: Vec<_> = t.names.iter().filter(|n| n.0 == 2).cloned().collect();
        let named = |tag: i32, name: &str| (2, tag, name.to_string());
        assert_eq!(
            surfaces,
            [
                named(1, "box"),
                named(2, "H"),
                named(3, "F"),
                named(4, "G"),
                named(5, "F:front"),
                named(6, "F:back"),
                named(7, "G:front"),
                named(8, "G:back")
            ]
        );
        // The group's own tag first; a fault without triangles keeps an entity for its groups.
        let want: Vec<Vec<i32>> = vec![vec![1], vec![1], vec![2], vec![3, -5, 6], vec![4, -7, 8]];
        assert_eq!(t.surface_physicals, want);
    }

    #[test]
    fn face_sets_split_pieces_by_membership_and_tag_them_after_the_fault_sides() {
        let mut mesh = three_tets();
        // One box face in `walls`, the other and H in `both`: three sets over two groups.
        let set = |name: &str, triangles: Vec<u32>| geom::mesh::FaceSet {
            name: name.into(),
            triangles,
        };
        mesh.face_sets = vec![set("both", vec![0, 3]), set("walls", vec![2])];
        let t = Topology::new(&mesh);
        assert_eq!(t.tris, vec![vec![2], vec![3], vec![0], vec![1], vec![]]);
        let want: Vec<Vec<i32>> = vec![
            vec![1, 10],
            vec![1, 9],
            vec![2, 9],
            vec![3, -5, 6],
            vec![4, -7, 8],
        ];
        assert_eq!(t.surface_physicals, want);
        let named: Vec<_> = t.names.iter().filter(|n| n.1 >= 9).cloned().collect();
        assert_eq!(
            named,
            [(2, 9, "both".to_string()), (2, 10, "walls".to_string())]
        );
        // The two box faces, in front of different regions, stay apart; a face set joining two
        // faces of one group with the same regions would not split them.
        mesh.face_sets = vec![set("all_box", vec![2, 3])];
        assert_eq!(Topology::new(&mesh).tris.len(), 5);
    }
}
