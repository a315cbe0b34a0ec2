//! FE assembly along the model's topology: the surface mesher's input for a patch (its loops and
//! constraints made of the curves' FE nodes), the tet mesher's input for a region (its patches'
//! FE triangles, oriented outward, dangling ones embedded) and the final volume mesh (the
//! regions' tets welded into one node set, with every patch triangle tagged by its surface).
//!
//! Nodes are joined by exact coordinates only: every shared node comes bit for bit from the same
//! discretized curve or the same patch mesh, so equal coordinates mean the same node and nothing
//! is ever merged by distance.

use super::{ModelError, PatchBoundary, point_key};
use crate::regions::{FaceUse, Side};
use geom::TriMesh;
use geom::contact::{Contact, Tri, triangle_contact};
use geom::mesh::{FaceSet, RegionGroup, SurfaceGroup, SurfaceKind, VolumeMesh};
use std::collections::HashMap;
use surface_mesh::PatchInput;
use tet_mesh::RegionInput;

/// The surface mesher's input for a patch. `curve_nodes(c)` gives the FE nodes of curve `c` (in
/// the curve's direction; a closed curve repeats its first node at the end).
pub fn patch_input<'a>(
    name: &str,
    support: &TriMesh,
    boundary: &PatchBoundary,
    curve_nodes: &dyn Fn(u32) -> Option<&'a [[f64; 3]]>,
) -> Result<PatchInput, ModelError> {
    let get = |c: u32| {
        curve_nodes(c).ok_or_else(|| {
            ModelError::new(
                format!("patch `{name}`: the nodes of curve {c} are missing"),
                None,
            )
        })
    };
    let mut loops = Vec::with_capacity(boundary.loops.len());
    for lp in &boundary.loops {
        let mut nodes: Vec<[f64; 3]> = Vec::new();
        for u in lp {
            let c = get(u.curve)?;
            let mut seq: Vec<[f64; 3]> = c.to_vec();
            if u.reversed {
                seq.reverse();
            }
            if let Some(last) = nodes.last() {
                if point_key(last) != point_key(&seq[0]) {
                    return Err(ModelError::new(
                        format!("patch `{name}`: its boundary curves do not join"),
                        Some(*last),
                    ));
                }
                nodes.extend_from_slice(&seq[1..]);
            } else {
                nodes.extend(seq);
            }
        }
        match (nodes.first(), nodes.last()) {
            (Some(a), Some(b)) if nodes.len() > 1 && point_key(a) == point_key(b) => {
                nodes.pop();
            }
            (_, last) => {
                return Err(ModelError::new(
                    format!("patch `{name}`: a boundary loop does not close"),
                    last.copied(),
                ));
            }
        }
        loops.push(nodes);
    }
    let constraints = boundary
        .constraints
        .iter()
        .map(|&c| get(c).map(<[[f64; 3]]>::to_vec))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(PatchInput {
        name: name.to_string(),
        support: support.clone(),
        loops,
        constraints,
        points: Vec::new(),
        facets: Vec::new(),
    })
}

/// The face sets, each the triangles of its patches (`ranges[p]` are patch `p`'s), ascending.
fn face_sets(
    sets: &[(String, Vec<usize>)],
    ranges: &[std::ops::Range<u32>],
) -> Result<Vec<FaceSet>, ModelError> {
    let mut out = Vec::with_capacity(sets.len());
    for (name, patches) in sets {
        let mut triangles = Vec::new();
        for &p in patches {
            let range = ranges.get(p).ok_or_else(|| {
                ModelError::new(format!("face set `{name}`: there is no patch {p}"), None)
            })?;
            triangles.extend(range.clone());
        }
        triangles.sort_unstable();
        triangles.dedup();
        out.push(FaceSet {
            name: name.clone(),
            triangles,
        });
    }
    Ok(out)
}

/// Welds points by exact coordinates, in order of first appearance.
#[derive(Default)]
pub(crate) struct Welder {
    ids: HashMap<[u64; 3], u32>,
    points: Vec<[f64; 3]>,
}

impl Welder {
    pub(crate) fn id(&mut self, p: &[f64; 3]) -> u32 {
        let next = self.points.len() as u32;
        let id = *self.ids.entry(point_key(p)).or_insert(next);
        if id == next {
            self.points.push(*p);
        }
        id
    }

    /// The welded points, in order of first appearance.
    pub(crate) fn into_points(self) -> Vec<[f64; 3]> {
        self.points
    }
}

/// The tet mesher's input for region `name`, bounded by the face-uses `sides` (sorted; a
/// dangling patch appears with both sides). `patch_mesh(p)` gives patch `p`'s FE triangulation,
/// oriented like its support (right-hand normal towards its `Front` side).
pub fn region_input<'a>(
    name: &str,
    sides: &[FaceUse],
    patch_mesh: &dyn Fn(u32) -> Option<&'a TriMesh>,
) -> Result<RegionInput, ModelError> {
    let mut w = Welder::default();
    let mut boundary = Vec::new();
    let mut embedded = Vec::new();
    let mut i = 0;
    while i < sides.len() {
        let p = sides[i].patch;
        let both = sides.get(i + 1).is_some_and(|s| s.patch == p);
        let mesh = patch_mesh(p).ok_or_else(|| {
            ModelError::new(
                format!("region `{name}`: the mesh of patch {p} is missing"),
                None,
            )
        })?;
        for t in &mesh.triangles {
            let tri = t.map(|v| w.id(&mesh.vertices[v as usize]));
            if both {
                embedded.push(tri);
            } else if sides[i].side == Side::Front {
                // The region lies on the front side: the outward normal is the opposite one.
                boundary.push([tri[0], tri[2], tri[1]]);
            } else {
                boundary.push(tri);
            }
        }
        i += if both { 2 } else { 1 };
    }
    Ok(RegionInput {
        name: name.to_string(),
        vertices: w.points,
        boundary,
        embedded,
        lines: Vec::new(),
    })
}

/// Drops the boundary triangles the region holds twice, once each way, and the vertices only
/// they used; returns the centroid of each pair dropped. Such a pair is two patches whose meshes
/// share a triangle with the region on the back of both: a wedge whose two sides close onto each
/// other there (an onlap's tip, where the surfaces come closer than their meshes can part), or
/// two surfaces drawn on each other. The region has no volume there, the triangle is an
/// interface of the regions beyond, and without both copies the boundary stays closed. When the
/// region beyond is this one on both sides (it lies round a thinner region that closes there),
/// the triangle stays in it as an embedded face (`surrounded_pairs`), or its nodes would be in
/// no tet. A triangle held twice the same way, and a boundary that is all such pairs, are left
/// for the mesher's check to refuse.
pub fn drop_pinched_faces(input: &mut RegionInput) -> Vec<[f64; 3]> {
    let canonical = |t: &[u32; 3]| {
        let k = (0..3).min_by_key(|&k| t[k]).unwrap_or(0);
        [t[k], t[(k + 1) % 3], t[(k + 2) % 3]]
    };
    let mut count: HashMap<[u32; 3], u32> = HashMap::new();
    for t in &input.boundary {
        *count.entry(canonical(t)).or_default() += 1;
    }
    let pinched = |t: &[u32; 3]| {
        let [a, b, c] = canonical(t);
        count.get(&[a, b, c]) == Some(&1) && count.get(&[a, c, b]) == Some(&1)
    };
    if input.boundary.iter().all(pinched) {
        // Nothing would be left: the region is all one face, held each way (two surfaces
        // drawn on each other), which the mesher's check refuses.
        return Vec::new();
    }
    let mut places = Vec::new();
    let around = surrounded_pairs(input, &pinched);
    let pts = &input.vertices;
    let mut kept = Vec::new();
    input.boundary.retain(|t| {
        let drop = pinched(t);
        if drop && canonical(t)[1] < canonical(t)[2] {
            if around.binary_search(&sorted(t)).is_ok() {
                kept.push(*t);
            } else {
                let c = t.map(|v| pts[v as usize]);
                places.push([0, 1, 2].map(|k| (c[0][k] + c[1][k] + c[2][k]) / 3.0));
            }
        }
        !drop
    });
    input.embedded.extend(kept);
    if !places.is_empty() {
        keep_used_vertices(input);
    }
    places
}

/// The vertices of `t`, ascending.
fn sorted(t: &[u32; 3]) -> [u32; 3] {
    let mut v = *t;
    v.sort_unstable();
    v
}

/// Of the triangles the region holds once each way (`pinched`), as sorted vertex triples, those
/// where the region lies round the pinch rather than in it: a thinner region between the two
/// patches closes to nothing there and drops them, so this one must keep the triangle, as a
/// face inside it, or its nodes would be in no tet. Decided where an edge of such a triangle
/// has exactly two other boundary triangles, one of each patch: the region lies round the pinch
/// when the one's far corner is outside the other (exact `orient3d`), since the patches part
/// there with the thinner region between them. A component of such triangles (connected through
/// edges) goes one way, by its first decided edge; undecided, it is dropped as before.
fn surrounded_pairs(input: &RegionInput, pinched: &dyn Fn(&[u32; 3]) -> bool) -> Vec<[u32; 3]> {
    let edge = |a: u32, b: u32| [a.min(b), a.max(b)];
    let mut by_edge: HashMap<[u32; 2], Vec<usize>> = HashMap::new();
    for (i, t) in input.boundary.iter().enumerate() {
        for k in 0..3 {
            by_edge
                .entry(edge(t[k], t[(k + 1) % 3]))
                .or_default()
                .push(i);
        }
    }
    let mut faces: Vec<[u32; 3]> = (input.boundary.iter())
        .filter(|t| pinched(t))
        .map(sorted)
        .collect();
    faces.sort_unstable();
    faces.dedup();
    let p = |v: u32| &input.vertices[v as usize];
    // Whether the region lies round the pinch at edge `e`, when the edge decides it.
    let decide = |e: [u32; 2]| -> Option<bool> {
        let others: Vec<&[u32; 3]> = (by_edge.get(&e)?.iter())
            .map(|&i| &input.boundary[i])
            .filter(|t| !pinched(t))
            .collect();
        let [t1, t2] = others[..] else { return None };
        let far = *t2.iter().find(|&&v| v != e[0] && v != e[1])?;
        let side = geom::predicates::orient3d(p(t1[0]), p(t1[1]), p(t1[2]), p(far));
        match side {
            geom::Orientation::Positive => Some(true),
            geom::Orientation::Negative => Some(false),
            geom::Orientation::Zero => None,
        }
    };
    let mut out = Vec::new();
    let mut seen = vec![false; faces.len()];
    for start in 0..faces.len() {
        if seen[start] {
            continue;
        }
        seen[start] = true;
        let mut component = vec![start];
        let mut k = 0;
        let mut verdict = None;
        while k < component.len() {
            let f = faces[component[k]];
            k += 1;
            for e in [edge(f[0], f[1]), edge(f[1], f[2]), edge(f[0], f[2])] {
                let near = (by_edge.get(&e).into_iter().flatten())
                    .map(|&i| &input.boundary[i])
                    .filter(|t| pinched(t))
                    .filter_map(|t| faces.binary_search(&sorted(t)).ok());
                for j in near {
                    if !seen[j] {
                        seen[j] = true;
                        component.push(j);
                    }
                }
                if verdict.is_none() {
                    verdict = decide(e);
                }
            }
        }
        if verdict == Some(true) {
            out.extend(component.iter().map(|&j| faces[j]));
        }
    }
    out.sort_unstable();
    out
}

/// Renumbers the region's triangles onto the vertices they use, in their order.
fn keep_used_vertices(input: &mut RegionInput) {
    let mut map = vec![u32::MAX; input.vertices.len()];
    let triangles = input.boundary.iter().chain(&input.embedded);
    for &v in triangles.flatten().chain(input.lines.iter().flatten()) {
        map[v as usize] = 0;
    }
    let mut kept = Vec::with_capacity(input.vertices.len());
    for (v, p) in input.vertices.iter().enumerate() {
        if map[v] == 0 {
            map[v] = kept.len() as u32;
            kept.push(*p);
        }
    }
    input.vertices = kept;
    for t in input.boundary.iter_mut().chain(input.embedded.iter_mut()) {
        *t = t.map(|v| map[v as usize]);
    }
    for l in input.lines.iter_mut() {
        *l = l.map(|v| map[v as usize]);
    }
}

/// Two patches of a region whose meshes hold the same triangle (`at`: its centroid): the
/// region has no thickness there, the two surfaces lie on each other.
#[derive(Clone, Debug, PartialEq)]
pub struct FaceToFace {
    pub patches: [u32; 2],
    pub at: [f64; 3],
}

/// One triangle of a region's patch meshes: the patch, its corners as the region orients them
/// (outward), and whether the patch is dangling (embedded).
struct RegionTriangle {
    patch: u32,
    corners: [[f64; 3]; 3],
    dangling: bool,
}

/// The region's patch triangles in `sides` order, oriented as [`region_input`] orients them,
/// without those it holds once each way unless that is all of them, as [`drop_pinched_faces`]
/// drops them from its input.
fn region_triangles<'a>(
    sides: &[FaceUse],
    patch_mesh: &dyn Fn(u32) -> Option<&'a TriMesh>,
) -> Vec<RegionTriangle> {
    let mut all = Vec::new();
    let mut i = 0;
    while i < sides.len() {
        let p = sides[i].patch;
        let dangling = sides.get(i + 1).is_some_and(|s| s.patch == p);
        let front = sides[i].side == Side::Front;
        i += if dangling { 2 } else { 1 };
        let Some(mesh) = patch_mesh(p) else { continue };
        for t in &mesh.triangles {
            let mut corners = t.map(|v| mesh.vertices[v as usize]);
            if front && !dangling {
                corners.swap(1, 2);
            }
            all.push(RegionTriangle {
                patch: p,
                corners,
                dangling,
            });
        }
    }
    // Rotated to start at the least corner: a triangle and its reverse differ in the last two.
    let oriented = |t: &RegionTriangle| {
        let keys = t.corners.map(|c| point_key(&c));
        let first = (0..3).min_by_key(|&k| keys[k]).unwrap_or(0);
        [0, 1, 2].map(|k| keys[(first + k) % 3])
    };
    let mut count: HashMap<[[u64; 3]; 3], u32> = HashMap::new();
    for t in all.iter().filter(|t| !t.dangling) {
        *count.entry(oriented(t)).or_default() += 1;
    }
    let kept = |t: &RegionTriangle| {
        let [a, b, c] = oriented(t);
        t.dangling || count.get(&[a, b, c]) != Some(&1) || count.get(&[a, c, b]) != Some(&1)
    };
    if all.iter().any(|t| !t.dangling && kept(t)) {
        all.retain(kept);
    }
    all
}

/// The first triangle (in `sides` order) that the meshes of two of the region's patches both
/// hold, if any; compared by exact coordinates, as [`region_input`] welds them. A triangle held
/// once each way is no fault: the region closes to nothing there ([`drop_pinched_faces`]).
pub fn face_to_face<'a>(
    sides: &[FaceUse],
    patch_mesh: &dyn Fn(u32) -> Option<&'a TriMesh>,
) -> Option<FaceToFace> {
    let mut owner: HashMap<[[u64; 3]; 3], u32> = HashMap::new();
    for t in region_triangles(sides, patch_mesh) {
        let mut key = t.corners.map(|c| point_key(&c));
        key.sort_unstable();
        match owner.get(&key) {
            Some(&q) if q != t.patch => {
                let c = t.corners;
                return Some(FaceToFace {
                    patches: [q, t.patch],
                    at: [0, 1, 2].map(|k| (c[0][k] + c[1][k] + c[2][k]) / 3.0),
                });
            }
            _ => {
                owner.insert(key, t.patch);
            }
        }
    }
    None
}

/// The first edge (in `sides` order) that the boundary meshes of two of the region's patches run
/// the same way, oriented as [`region_input`] orients them (`at`: its midpoint): both bound the
/// region from the same side there, so the region touches itself along that edge (two surfaces
/// that cross or meet along a line, a wedge closed to nothing). Compared by exact coordinates.
pub fn edge_clash<'a>(
    sides: &[FaceUse],
    patch_mesh: &dyn Fn(u32) -> Option<&'a TriMesh>,
) -> Option<FaceToFace> {
    let mut owner: HashMap<[[u64; 3]; 2], u32> = HashMap::new();
    // A dangling patch is embedded, not boundary.
    for t in region_triangles(sides, patch_mesh)
        .iter()
        .filter(|t| !t.dangling)
    {
        let c = t.corners;
        for k in 0..3 {
            let (a, b) = (c[k], c[(k + 1) % 3]);
            match owner.insert([point_key(&a), point_key(&b)], t.patch) {
                Some(q) if q != t.patch => {
                    return Some(FaceToFace {
                        patches: [q, t.patch],
                        at: [0, 1, 2].map(|j| 0.5 * (a[j] + b[j])),
                    });
                }
                _ => {}
            }
        }
    }
    None
}

/// The first pair of triangles (in `sides` order) of two different patches of the region that
/// cross or overlap beyond the vertices and edges they share (`at`: the midpoint of their
/// centroids): two surfaces meeting at a small angle whose meshes, each within its tolerance of
/// its own support, pass through each other near where they meet. Decided by the exact contact
/// test the tet mesher's input check uses, on the region's welded nodes.
pub fn patch_crossing<'a>(
    sides: &[FaceUse],
    patch_mesh: &dyn Fn(u32) -> Option<&'a TriMesh>,
) -> Option<FaceToFace> {
    let mut w = Welder::default();
    let mut tris: Vec<([u32; 3], u32)> = Vec::new();
    let mut patches: Vec<u32> = sides.iter().map(|s| s.patch).collect();
    patches.dedup();
    for p in patches {
        let Some(mesh) = patch_mesh(p) else { continue };
        for t in &mesh.triangles {
            tris.push((t.map(|v| w.id(&mesh.vertices[v as usize])), p));
        }
    }
    let pts = &w.points;
    let boxes: Vec<geom::BBox> = (tris.iter())
        .map(|(t, _)| geom::BBox::from_points(t.map(|v| &pts[v as usize])))
        .collect();
    let tri = |k: u32| {
        let t = tris[k as usize].0;
        Tri {
            ids: t,
            pts: t.map(|v| &pts[v as usize]),
        }
    };
    let hits = geom::broad_phase::overlapping_pairs(&boxes, |k, j| {
        let (pk, pj) = (tris[k as usize].1, tris[j as usize].1);
        (pk != pj && triangle_contact(&tri(k), &tri(j)) != Contact::None).then_some(())
    });
    let &(k, j, ()) = hits.first()?;
    let centroid = |k: u32| {
        let c = tri(k).pts;
        [0, 1, 2].map(|i| (c[0][i] + c[1][i] + c[2][i]) / 3.0)
    };
    let (a, b) = (centroid(k), centroid(j));
    Some(FaceToFace {
        patches: [tris[k as usize].1, tris[j as usize].1],
        at: [0, 1, 2].map(|i| 0.5 * (a[i] + b[i])),
    })
}

/// Adds polylines (well pieces inside the region) to a region's input as embedded segments. A
/// polyline node bit-identical to a boundary node (a well's crossing, a node of the patch mesh)
/// is that node; the others are new vertices. Returns, per polyline, the range of its segments
/// in `input.lines`.
pub fn embed_polylines(
    input: &mut RegionInput,
    polylines: &[Vec<[f64; 3]>],
) -> Vec<std::ops::Range<usize>> {
    let mut w = Welder::default();
    for p in &input.vertices {
        w.id(p);
    }
    let mut ranges = Vec::with_capacity(polylines.len());
    for line in polylines {
        let start = input.lines.len();
        let ids: Vec<u32> = line.iter().map(|p| w.id(p)).collect();
        input.lines.extend(
            ids.windows(2)
                .filter(|s| s[0] != s[1])
                .map(|s| [s[0], s[1]]),
        );
        ranges.push(start..input.lines.len());
    }
    input.vertices = w.points;
    ranges
}

/// One region's part of the final mesh: its group (name and attributes), nodes and positive tets.
pub type RegionPart<'a> = (RegionGroup, &'a [[f64; 3]], &'a [[u32; 4]]);

/// The pieces of the final mesh, in model order.
pub struct VolumeAssembly<'a> {
    pub regions: Vec<RegionPart<'a>>,
    /// Per patch: the surface it belongs to, that surface's kind, and its FE triangles.
    pub patches: Vec<(&'a str, SurfaceKind, &'a TriMesh)>,
    /// Named face sets, in name order: each a name and the indices into `patches` it gathers.
    pub face_sets: Vec<(String, Vec<usize>)>,
}

/// Welds the regions' tets into one [`VolumeMesh`]; every patch triangle joins the 2D group of
/// its surface (groups in name order) and the face sets that gather its patch.
pub fn assemble_volume(parts: &VolumeAssembly) -> Result<VolumeMesh, ModelError> {
    let mut w = Welder::default();
    let mut out = VolumeMesh::default();
    for (r, (group, nodes, tets)) in parts.regions.iter().enumerate() {
        let map: Vec<u32> = nodes.iter().map(|p| w.id(p)).collect();
        for t in tets.iter() {
            out.tets.push(t.map(|v| map[v as usize]));
            out.tet_region.push(r as u32);
        }
        out.regions.push(group.clone());
    }
    let mut names: Vec<(&str, SurfaceKind)> =
        parts.patches.iter().map(|(s, k, _)| (*s, *k)).collect();
    names.sort();
    names.dedup_by(|a, b| a.0 == b.0);
    out.surface_groups = names
        .iter()
        .map(|(s, k)| SurfaceGroup {
            name: s.to_string(),
            kind: *k,
        })
        .collect();
    let n_volume_nodes = w.points.len();
    let mut ranges = Vec::with_capacity(parts.patches.len());
    for (surface, _, mesh) in &parts.patches {
        let g = names.partition_point(|(s, _)| s < surface) as u32;
        let first = out.triangles.len() as u32;
        ranges.push(first..first + mesh.triangles.len() as u32);
        for t in &mesh.triangles {
            let tri = t.map(|v| w.id(&mesh.vertices[v as usize]));
            out.triangles.push(tri);
            out.triangle_group.push(g);
        }
    }
    if w.points.len() != n_volume_nodes {
        let at = w.points[n_volume_nodes];
        return Err(ModelError::new(
            "a surface node is not a node of any tetrahedron (a patch bounds no meshed region)",
            Some(at),
        ));
    }
    out.nodes = w.points;
    out.face_sets = face_sets(&parts.face_sets, &ranges)?;
    out.check_indices().map_err(|e| ModelError::new(e, None))?;
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn face(patch: u32, side: Side) -> FaceUse {
        FaceUse { patch, side }
    }

    #[test]
    fn two_patches_holding_the_same_triangle_either_way_round_lie_face_to_face() {
        let v = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
        ];
        let lower = TriMesh::new(v.clone(), vec![[0, 1, 2], [0, 1, 3]]);
        // The same triangle with its corners in another order and numbering.
        let upper = TriMesh::new(vec![v[2], v[0], v[1]], vec![[0, 2, 1]]);
        let apart = TriMesh::new(v, vec![[1, 2, 3]]);
        let meshes = [lower, upper, apart];
        let get = |p: u32| meshes.get(p as usize);
        for (sides, patches) in [
            (vec![face(0, Side::Back), face(1, Side::Front)], [0, 1]),
            (vec![face(1, Side::Back), face(0, Side::Front)], [1, 0]),
        ] {
            let f = face_to_face(&sides, &get).expect("they share a triangle");
            assert_eq!(f.patches, patches);
            assert_eq!(f.at, [1.0 / 3.0, 1.0 / 3.0, 0.0]);
        }
        let sides = [face(0, Side::Back), face(2, Side::Front)];
        assert_eq!(face_to_face(&sides, &get), None);
        // Held once each way, the region on the back of both: it closes to nothing there.
        let sides = [face(0, Side::Back), face(1, Side::Back)];
        assert_eq!(face_to_face(&sides, &get), None);
        // A dangling patch's two sides are one patch, not two.
        let sides = [face(0, Side::Back), face(0, Side::Front)];
        assert_eq!(face_to_face(&sides, &get), None);
    }

    /// A region on a unit tetrahedron's corners and a fifth vertex (3, 3, 0), bounded by
    /// `boundary`.
    fn tet_and_fin(boundary: Vec<[u32; 3]>) -> RegionInput {
        RegionInput {
            name: "r".into(),
            vertices: vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [0.0, 0.0, 1.0],
                [3.0, 3.0, 0.0],
            ],
            boundary,
            embedded: Vec::new(),
            lines: Vec::new(),
        }
    }

    #[test]
    fn a_triangle_held_once_each_way_is_dropped_with_the_vertices_only_it_used() {
        // A tetrahedron's four outward faces, and a flat triangle on a fifth vertex held twice,
        // once each way (two patches closing onto each other there).
        let input = tet_and_fin;
        let shell = vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]];
        let mut pinched = input([shell.clone(), vec![[1, 4, 2], [4, 1, 2]]].concat());
        let places = drop_pinched_faces(&mut pinched);
        assert_eq!(places, vec![[4.0 / 3.0, 4.0 / 3.0, 0.0]]);
        assert_eq!(pinched.boundary, shell);
        assert_eq!(pinched.vertices.len(), 4);
        // Held twice the same way, it stays for the mesher's check to refuse.
        let mut twice = input([shell.clone(), vec![[1, 4, 2], [4, 2, 1]]].concat());
        assert!(drop_pinched_faces(&mut twice).is_empty());
        assert_eq!(twice.boundary.len(), 6);
        let mut plain = input(shell.clone());
        assert!(drop_pinched_faces(&mut plain).is_empty());
        assert_eq!(plain.vertices.len(), 5);
    }

    #[test]
    fn a_triangle_held_once_each_way_by_the_region_round_it_stays_as_a_face_inside() {
        // The tetrahedron as a cavity (its faces turned inward: the region lies outside it), and
        // the same fin on its edge 1-2: the region is on both sides of the fin, which a thinner
        // region closing there would drop, so this one keeps it, embedded.
        let shell = vec![[0, 1, 2], [0, 3, 1], [1, 3, 2], [0, 2, 3]];
        let mut input = tet_and_fin([shell.clone(), vec![[1, 4, 2], [4, 1, 2]]].concat());
        assert!(drop_pinched_faces(&mut input).is_empty());
        assert_eq!(input.boundary, shell);
        assert_eq!(input.embedded, vec![[4, 1, 2]]);
        assert_eq!(input.vertices.len(), 5);
    }

    #[test]
    fn the_meshes_of_two_patches_passing_through_each_other_cross_where_they_do() {
        // A unit square in z = 0, and a triangle through it on the y axis's far side; a third
        // patch shares the square's edge along the x axis and meets it only there.
        let v = |x: f64, y: f64, z: f64| [x, y, z];
        let square = TriMesh::new(
            vec![
                v(0.0, 0.0, 0.0),
                v(1.0, 0.0, 0.0),
                v(1.0, 1.0, 0.0),
                v(0.0, 1.0, 0.0),
            ],
            vec![[0, 1, 2], [0, 2, 3]],
        );
        let through = TriMesh::new(
            vec![v(0.5, 0.5, -1.0), v(0.6, 0.5, 1.0), v(0.5, 0.6, 1.0)],
            vec![[0, 1, 2]],
        );
        let beside = TriMesh::new(
            vec![v(0.0, 0.0, 0.0), v(1.0, 0.0, 0.0), v(0.5, -1.0, 0.3)],
            vec![[0, 2, 1]],
        );
        let meshes = [square, through, beside];
        let get = |p: u32| meshes.get(p as usize);
        let sides = [face(0, Side::Back), face(2, Side::Back)];
        assert_eq!(patch_crossing(&sides, &get), None);
        for sides in [
            [face(0, Side::Back), face(1, Side::Back)],
            [face(1, Side::Back), face(0, Side::Back)],
        ] {
            let c = patch_crossing(&sides, &get).expect("they cross");
            assert_eq!(c.patches, [sides[0].patch, sides[1].patch]);
        }
    }

    #[test]
    fn two_patches_bounding_a_region_from_one_side_of_an_edge_clash_there() {
        // Two unit squares meeting along the x axis, as two patches: as the two halves of one
        // flat face of the region they run the shared edge opposite ways; folded onto one side
        // (one patch's sides swapped) they both run it one way, and the region touches itself.
        let v = |x: f64, y: f64| [x, y, 0.0];
        let south = TriMesh::new(
            vec![v(0.0, 0.0), v(1.0, 0.0), v(1.0, -1.0), v(0.0, -1.0)],
            vec![[0, 3, 2], [0, 2, 1]],
        );
        let north = TriMesh::new(
            vec![v(0.0, 0.0), v(1.0, 0.0), v(1.0, 1.0), v(0.0, 1.0)],
            vec![[0, 1, 2], [0, 2, 3]],
        );
        let meshes = [south, north];
        let get = |p: u32| meshes.get(p as usize);
        let flat = [face(0, Side::Back), face(1, Side::Back)];
        assert_eq!(edge_clash(&flat, &get), None);
        let folded = [face(0, Side::Back), face(1, Side::Front)];
        let c = edge_clash(&folded, &get).expect("they run the edge one way");
        assert_eq!(c.patches, [0, 1]);
        assert_eq!(c.at, [0.5, 0.0, 0.0]);
        // A dangling patch's two sides are embedded, not boundary.
        let dangling = [
            face(0, Side::Back),
            face(1, Side::Back),
            face(1, Side::Front),
        ];
        assert_eq!(edge_clash(&dangling, &get), None);
    }
}
