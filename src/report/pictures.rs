//! The two pictures of a report, rendered by us as SVG (see `view` for the projection and the
//! size bound):
//!
//! 1. the model: every tagged surface triangle of the mesh, coloured by surface name; a box-side
//!    triangle is drawn only when the model's centre lies between its plane and the viewer (the
//!    far walls make a backdrop, the near ones would hide everything);
//! 2. the mesh: a cut-away of the tets, coloured by region. A tet is kept when its centroid is
//!    not in front of the vertical plane through the centre of the mesh's box that faces the
//!    viewer; the faces drawn are those of kept tets that no other kept tet shares (the outside of
//!    the model and the cut), facing the viewer, so the cut shows the regions' layering.
//!
//! The side of a plane a point lies on is the exact `orient3d`; both are picture choices, not
//! model decisions.
//!
//! The wells (the mesh's line groups) are drawn on the first picture, over the surfaces (see
//! `view`), with the same camera and frame, so they are seen where they cross the surfaces. A
//! group's edges are in no useful order in the mesh (region by region), so they are chained
//! into polylines here; a well's name is written at its head, taken as the highest end of its
//! chains (a well path starts at its head, and the part of it inside the box starts at the box's
//! top or the head below it).

use super::input::{tet_points, tri_points};
use super::palette::{self, Rgb};
use super::view::{self, Camera, Face, Line, Picture, Style};
use geom::BBox;
use geom::mesh::{SurfaceKind, VolumeMesh};
use geom::predicates::{Orientation, orient3d};
use std::collections::BTreeMap;

/// Most faces drawn in one picture: at roughly 55 bytes per face, two pictures stay under 3 MB.
pub const FACE_CAP: usize = 25_000;

/// The box of the nodes used by tets and triangles (finite coordinates only).
pub fn mesh_frame(mesh: &VolumeMesh) -> BBox {
    let mut used = vec![false; mesh.nodes.len()];
    let all = mesh
        .tets
        .iter()
        .flat_map(|t| t.iter())
        .chain(mesh.triangles.iter().flat_map(|t| t.iter()));
    for &v in all {
        if let Some(u) = used.get_mut(v as usize) {
            *u = true;
        }
    }
    BBox::from_points(
        mesh.nodes
            .iter()
            .zip(&used)
            .filter(|(p, u)| **u && p.iter().all(|c| c.is_finite()))
            .map(|(p, _)| p),
    )
}

fn centre(b: &BBox) -> [f64; 3] {
    std::array::from_fn(|k| 0.5 * (b.min[k] + b.max[k]))
}

/// Whether `p` is strictly on the viewer's side of the plane through `o` spanned by `a` and `b`
/// (whose right-hand normal `a × b` points at the viewer).
fn in_front(o: &[f64; 3], a: &[f64; 3], b: &[f64; 3], p: &[f64; 3]) -> bool {
    let pa = std::array::from_fn(|k| o[k] + a[k]);
    let pb = std::array::from_fn(|k| o[k] + b[k]);
    orient3d(o, &pa, &pb, p) == Orientation::Positive
}

/// Picture 1: the model's surfaces. Returns the picture and the colour of every surface group.
pub fn model(mesh: &VolumeMesh, title: &str) -> (Picture, Vec<Rgb>) {
    let frame = mesh_frame(mesh);
    let colours: Vec<Rgb> = mesh
        .surface_groups
        .iter()
        .map(|g| palette::surface(&g.name, g.kind))
        .collect();
    let cam = Camera::oblique();
    let c = centre(&frame);
    // Box sides: a box triangle is drawn when the model's centre lies between it and the viewer
    // (it belongs to a far wall), whatever the grouping of the sides.
    let reach = (0..3)
        .map(|k| frame.max[k] - frame.min[k])
        .fold(0.0f64, f64::max)
        .max(1.0);
    let faces: Vec<Face> = mesh
        .triangles
        .iter()
        .zip(&mesh.triangle_group)
        .filter_map(|(t, &g)| {
            let group = mesh.surface_groups.get(g as usize)?;
            let pts = tri_points(mesh, t)?;
            if group.kind == SurfaceKind::Box && !far_wall(&pts, &c, &cam.toward, reach) {
                return None;
            }
            Some(Face { pts, colour: g })
        })
        .collect();
    let pic = view::draw(
        &faces,
        &frame,
        &Style {
            id: "s",
            colours: &colours,
            cull_back: false,
            edges: None,
            cap: FACE_CAP,
            title,
            lines: &wells(mesh),
        },
    );
    (pic, colours)
}

/// The line groups of `mesh` as polylines, each named at its head (the highest end of its
/// chains, the first on a tie). Edges with a node out of range are left out.
pub fn wells(mesh: &VolumeMesh) -> Vec<Line> {
    mesh.lines
        .iter()
        .map(|g| {
            let parts: Vec<Vec<[f64; 3]>> = chains(&g.lines, mesh.nodes.len())
                .iter()
                .map(|c| c.iter().map(|&v| mesh.nodes[v as usize]).collect())
                .collect();
            let head = parts
                .iter()
                .flat_map(|p| [p.first(), p.last()])
                .flatten()
                .filter(|p| p.iter().all(|c| c.is_finite()))
                .fold(None, |best: Option<[f64; 3]>, &p| match best {
                    Some(b) if b[2] >= p[2] => Some(b),
                    _ => Some(p),
                });
            Line {
                name: g.name.clone(),
                parts,
                head,
            }
        })
        .collect()
}

/// `edges` (between nodes below `n`) chained into walks that use every edge once: first from
/// every node that does not have two edges (the ends of open chains, branch points), in node
/// order, then around the loops left, from their smallest node. One open chain gives one walk.
fn chains(edges: &[[u32; 2]], n: usize) -> Vec<Vec<u32>> {
    let mut e: Vec<[u32; 2]> = edges
        .iter()
        .filter(|&&[a, b]| a != b && (a as usize) < n && (b as usize) < n)
        .map(|&[a, b]| [a.min(b), a.max(b)])
        .collect();
    e.sort_unstable();
    e.dedup();
    let mut adj: BTreeMap<u32, Vec<(u32, usize)>> = BTreeMap::new();
    for (i, &[a, b]) in e.iter().enumerate() {
        adj.entry(a).or_default().push((b, i));
        adj.entry(b).or_default().push((a, i));
    }
    let starts: Vec<u32> = (adj.iter().filter(|(_, a)| a.len() != 2).map(|(&v, _)| v))
        .chain(adj.keys().copied())
        .collect();
    let mut used = vec![false; e.len()];
    let mut out = Vec::new();
    for s in starts {
        loop {
            let mut walk = vec![s];
            let mut v = s;
            while let Some(&(w, i)) = adj[&v].iter().find(|(_, i)| !used[*i]) {
                used[i] = true;
                walk.push(w);
                v = w;
            }
            if walk.len() < 2 {
                break;
            }
            out.push(walk);
        }
    }
    out
}

/// Whether the plane of triangle `p` has `centre` strictly on the viewer's side (the viewer is
/// `reach` away along `toward`): both exact `orient3d` signs agree and are not zero.
fn far_wall(p: &[[f64; 3]; 3], centre: &[f64; 3], toward: &[f64; 3], reach: f64) -> bool {
    let eye: [f64; 3] = std::array::from_fn(|k| p[0][k] + reach * toward[k]);
    let s = orient3d(&p[0], &p[1], &p[2], centre);
    s != Orientation::Zero && s == orient3d(&p[0], &p[1], &p[2], &eye)
}

/// Outward faces of a positively oriented tet `abcd` (opposite d, c, b, a).
const OUTWARD: [[usize; 3]; 4] = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];

/// Picture 2: the cut-away of the tets. Returns the picture, the number of tets kept by the cut
/// and the colour of every region.
pub fn cutaway(mesh: &VolumeMesh, title: &str) -> (Picture, usize, Vec<Rgb>) {
    let frame = mesh_frame(mesh);
    let colours: Vec<Rgb> = (0..mesh.regions.len()).map(palette::region).collect();
    let cam = Camera::oblique();
    let c = centre(&frame);
    // The vertical plane through the centre facing the viewer: spanned by `right` (horizontal)
    // and z, its normal right × z is the horizontal direction towards the viewer.
    let z = [0.0, 0.0, 1.0];
    // (sorted face key, tet, local face) of every face of a kept tet.
    let mut faces: Vec<([u32; 3], u32, u8)> = Vec::new();
    let mut kept = 0usize;
    for (i, (t, &r)) in mesh.tets.iter().zip(&mesh.tet_region).enumerate() {
        if r as usize >= mesh.regions.len() {
            continue;
        }
        let Some(p) = tet_points(mesh, t) else {
            continue;
        };
        if p.iter().any(|q| q.iter().any(|v| !v.is_finite())) {
            continue;
        }
        let g: [f64; 3] = std::array::from_fn(|k| 0.25 * (p[0][k] + p[1][k] + p[2][k] + p[3][k]));
        if in_front(&c, &cam.right, &z, &g) {
            continue;
        }
        kept += 1;
        for (l, f) in OUTWARD.iter().enumerate() {
            let mut key = f.map(|j| t[j]);
            key.sort_unstable();
            faces.push((key, i as u32, l as u8));
        }
    }
    faces.sort_unstable();
    let mut out = Vec::new();
    let mut i = 0;
    while i < faces.len() {
        let mut j = i + 1;
        while j < faces.len() && faces[j].0 == faces[i].0 {
            j += 1;
        }
        if j - i == 1 {
            let (_, t, l) = faces[i];
            if let Some(f) = outward_face(mesh, t as usize, l as usize) {
                out.push(f);
            }
        }
        i = j;
    }
    let pic = view::draw(
        &out,
        &frame,
        &Style {
            id: "r",
            colours: &colours,
            cull_back: true,
            edges: Some("#00000059"),
            cap: FACE_CAP,
            title,
            lines: &[],
        },
    );
    (pic, kept, colours)
}

/// Local face `l` of tet `t`, oriented outward whatever the tet's orientation (exact
/// `orient3d`); `None` for a flat tet, which has no outside.
fn outward_face(mesh: &VolumeMesh, t: usize, l: usize) -> Option<Face> {
    let tet = mesh.tets.get(t)?;
    let p = tet_points(mesh, tet)?;
    let f = OUTWARD.get(l)?;
    let pts = match orient3d(&p[0], &p[1], &p[2], &p[3]) {
        Orientation::Positive => f.map(|j| p[j]),
        Orientation::Negative => [p[f[0]], p[f[2]], p[f[1]]],
        Orientation::Zero => return None,
    };
    Some(Face {
        pts,
        colour: *mesh.tet_region.get(t)?,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use geom::mesh::{LineGroup, RegionGroup, SurfaceGroup};

    /// Two unit cubes side by side along x, each as 6 Kuhn tets, regions 0 and 1.
    fn two_cubes() -> VolumeMesh {
        let mut m = VolumeMesh::default();
        for i in 0..3 {
            for j in 0..2 {
                for k in 0..2 {
                    m.nodes.push([i as f64, j as f64, k as f64]);
                }
            }
        }
        let id = |i: usize, j: usize, k: usize| (i * 4 + j * 2 + k) as u32;
        for (cube, x) in [0usize, 1].into_iter().enumerate() {
            let c = |b: usize| id(x + (b & 1), (b >> 1) & 1, (b >> 2) & 1);
            // The 6 tets around the diagonal 0-7 of a cube.
            for p in [[1, 3], [3, 2], [2, 6], [6, 4], [4, 5], [5, 1]] {
                m.tets.push([c(0), c(p[0]), c(p[1]), c(7)]);
                m.tet_region.push(cube as u32);
            }
        }
        for r in ["left", "right"] {
            m.regions.push(RegionGroup {
                name: r.into(),
                material: None,
                properties: Default::default(),
            });
        }
        m
    }

    #[test]
    fn the_cut_keeps_the_tets_behind_the_centre_plane_and_draws_their_hull() {
        let m = two_cubes();
        let (pic, kept, colours) = cutaway(&m, "cut");
        assert_eq!(colours.len(), 2);
        // The centre plane faces the south-west viewer: some tets are cut away, not all.
        assert!(kept > 0 && kept < 12, "kept {kept}");
        assert!(pic.visible > 0);
        assert_eq!(pic.svg.matches("<path").count(), pic.drawn);
    }

    #[test]
    fn only_the_far_walls_of_the_box_are_drawn() {
        let c = [0.5, 0.5, 0.5];
        let cam = Camera::oblique();
        let top = [[0.0, 0.0, 1.0], [1.0, 0.0, 1.0], [0.0, 1.0, 1.0]];
        let bottom = [[0.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]];
        // The viewer is above, south-west: the floor and the north and east walls are far.
        let north = [[0.0, 1.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 1.0]];
        let south = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]];
        assert!(!far_wall(&top, &c, &cam.toward, 1.0));
        assert!(far_wall(&bottom, &c, &cam.toward, 1.0));
        assert!(far_wall(&north, &c, &cam.toward, 1.0));
        assert!(!far_wall(&south, &c, &cam.toward, 1.0));
    }

    #[test]
    fn edges_in_any_order_chain_into_one_walk_per_open_chain() {
        // 0-1-2-3 shuffled and repeated, a loop 5-6-7, an edge out of range and a degenerate one.
        let edges = [
            [2, 3],
            [1, 0],
            [6, 7],
            [2, 1],
            [7, 5],
            [3, 2],
            [5, 6],
            [4, 99],
            [8, 8],
        ];
        let walks = chains(&edges, 10);
        assert_eq!(walks, [vec![0, 1, 2, 3], vec![5, 6, 7, 5]]);
        // A branch: every edge once, a walk from each node without two edges.
        let walks = chains(&[[0, 1], [1, 2], [1, 3]], 4);
        assert_eq!(walks.iter().map(|w| w.len() - 1).sum::<usize>(), 3);
    }

    #[test]
    fn the_model_picture_draws_a_polyline_per_well_named_at_its_head() {
        let mut m = two_cubes();
        // The top of the first cube as a horizon (nodes i * 4 + j * 2 + k at (i, j, k)).
        m.surface_groups.push(SurfaceGroup {
            name: "H".into(),
            kind: SurfaceKind::Horizon,
        });
        m.triangles.extend([[1, 5, 7], [1, 7, 3]]);
        m.triangle_group.extend([0, 0]);
        let bare = model(&m, "m").0;
        assert!(bare.drawn > 0);
        assert!(!bare.svg.contains("<polyline") && !bare.svg.contains("-wells"));
        // W<1>: 4 (1, 0, 0) up to 5 (1, 0, 1), on to 9 (2, 0, 1) and 11 (2, 1, 1), its edges out
        // of order; W2: 0 (0, 0, 0) to 2 (0, 1, 0) up to 3 (0, 1, 1).
        m.lines.push(LineGroup {
            area: None,
            name: "W<1>".into(),
            lines: vec![[9, 11], [5, 4], [9, 5]],
        });
        m.lines.push(LineGroup {
            area: None,
            name: "W2".into(),
            lines: vec![[2, 0], [3, 2]],
        });
        let pic = model(&m, "m").0;
        assert_eq!(pic.svg.matches("<polyline").count(), 2, "{}", pic.svg);
        assert!(pic.svg.contains("<title>W&lt;1&gt;</title></polyline>"));
        assert!(pic.svg.contains("<title>W2</title></polyline>"));
        assert_eq!(
            pic.svg.matches("<text x").count(),
            2 + 3,
            "two names, three axes"
        );
        // The lines come after every face, the names after the lines.
        let last_face = pic.svg.rfind("<path").unwrap();
        let first_line = pic.svg.find("<polyline").unwrap();
        let name = pic.svg.find(">W&lt;1&gt;</text>").unwrap();
        assert!(last_face < first_line && first_line < name);
        // Each well is one chain, named at its highest end.
        let w = wells(&m);
        assert_eq!(w[0].parts, [[4, 5, 9, 11].map(|v| m.nodes[v])]);
        assert_eq!(w[0].head, Some(m.nodes[11]));
        assert_eq!(w[1].parts, [[0, 2, 3].map(|v| m.nodes[v])]);
        assert_eq!(w[1].head, Some(m.nodes[3]));
        // The faces are drawn as without wells.
        assert_eq!((pic.visible, pic.drawn), (bare.visible, bare.drawn));
    }

    #[test]
    fn a_tet_with_a_missing_node_or_region_is_ignored() {
        let mut m = two_cubes();
        m.tets.push([0, 1, 2, 999]);
        m.tet_region.push(0);
        m.tets.push([0, 1, 2, 3]);
        m.tet_region.push(7);
        let (_, kept, _) = cutaway(&m, "cut");
        let (_, kept0, _) = cutaway(&two_cubes(), "cut");
        assert_eq!(kept, kept0);
    }
}
