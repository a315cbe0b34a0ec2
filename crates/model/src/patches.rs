//! Patches: the pieces of a split surface between its intersection curves.
//!
//! It decides which triangles of a [`SplitSurface`] form one patch (connected across edges that
//! are neither curve edges nor creases, and that carry exactly two triangles), the canonical
//! order of the patches (so names `S#1`, `S#2`... do not depend on input order or thread count),
//! and whether a patch lies inside the model's box.
//!
//! An edge with three or more triangles (faults given as one surface whose sheets branch or
//! cross along shared edges) bounds each sheet's patch, as the topology stage's patches are
//! bounded: one patch over a branch line is no surface at all (its boundary cannot be chained
//! into loops), while a patch per sheet meets the others along the line like two surfaces along
//! their intersection.
//!
//! A crease is an edge between two triangles of the imported surface that bend by more than
//! `Tolerances::crease_angle_deg` (a box TSurf wrapping around the box's edges in one TFACE, a
//! fold's tight hinge): cutting there gives patches that each flatten without folding, and the
//! crease becomes a curve the meshes share, so the feature is kept. The bend is measured on the
//! original triangles each split triangle lies in (never on the slivers splitting makes), and is
//! a measure, like the kink angle of a border, not an orientation decision.
//! Each patch carries its own compact mesh whose coordinates are copied bit for bit, so patches
//! of different surfaces meeting along a curve share identical vertices there.

use crate::intersect::split::SplitSurface;
use geom::predicates::dot;
use geom::{BBox, TriMesh};
use std::cmp::Ordering;

/// One patch of a surface.
#[derive(Clone, Debug, PartialEq)]
pub struct Patch {
    /// Stable name `surface#k` (1-based, in canonical order).
    pub name: String,
    /// The triangles of the split surface's mesh in this patch, ascending.
    pub triangles: Vec<u32>,
    /// The patch alone: its vertices (in order of first use by `triangles`), coordinates
    /// bit-identical to the split surface's, and its triangles in the same orientation.
    pub mesh: TriMesh,
}

fn lex(a: &[f64; 3], b: &[f64; 3]) -> Ordering {
    (0..3)
        .map(|k| a[k].total_cmp(&b[k]))
        .find(|o| o.is_ne())
        .unwrap_or(Ordering::Equal)
}

/// The patches of `split` (surface `surface`) without cutting at creases: see
/// [`patches_at_creases`].
pub fn patches(surface: &str, split: &SplitSurface) -> Vec<Patch> {
    components(surface, split, |_| false)
}

/// The patches of `split` (surface `surface`, split from an original surface whose triangles'
/// unit normals are `normals`, see `TriMesh::unit_normals`): connected components of its triangles,
/// where two triangles connect through a shared edge that is theirs alone, is not a curve edge,
/// and whose original triangles bend by at most `kink_deg`. Ordered by their smallest vertex
/// (lexicographic, total f64 order), ties broken by the sorted list of their vertices.
pub fn patches_at_creases(
    surface: &str,
    split: &SplitSurface,
    normals: &[[f64; 3]],
    kink_deg: f64,
) -> Vec<Patch> {
    components(surface, split, creased(split, normals, kink_deg))
}

/// Whether two triangles of `split` meet at a crease: their original triangles (unit normals
/// `normals`) bend by more than `kink_deg`. Triangles of one original triangle never do.
pub fn creased<'a>(
    split: &'a SplitSurface,
    normals: &'a [[f64; 3]],
    kink_deg: f64,
) -> impl Fn((u32, u32)) -> bool + 'a {
    let cos_max = kink_deg.to_radians().cos();
    move |(t, u)| {
        let (a, b) = (split.parent[t as usize], split.parent[u as usize]);
        if a == b {
            return false;
        }
        let (Some(n), Some(m)) = (normals.get(a as usize), normals.get(b as usize)) else {
            return false;
        };
        *n != [0.0; 3] && *m != [0.0; 3] && dot(n, m) < cos_max
    }
}

/// The components of `split`'s triangles across edges that carry exactly two triangles, are not
/// curve edges, and on which `crease` (given the two triangles) is false.
pub(crate) fn components(
    surface: &str,
    split: &SplitSurface,
    crease: impl Fn((u32, u32)) -> bool,
) -> Vec<Patch> {
    let m = &split.mesh;
    let n = m.triangles.len();
    let nv = m.vertices.len() as u32;
    // Union-find over triangles, with path halving (iterative).
    let mut up: Vec<usize> = (0..n).collect();
    fn root(up: &mut [usize], mut i: usize) -> usize {
        while up[i] != i {
            up[i] = up[up[i]];
            i = up[i];
        }
        i
    }
    // Every (edge, triangle) use, sorted by edge: the triangles around one edge are adjacent.
    let mut uses: Vec<([u32; 2], u32)> = Vec::with_capacity(3 * n);
    for (t, tri) in m.triangles.iter().enumerate() {
        if tri.iter().any(|&v| v >= nv) {
            continue;
        }
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            if a != b {
                uses.push(([a.min(b), a.max(b)], t as u32));
            }
        }
    }
    // A counting sort on the first vertex, then each (small) bucket: the order of a full sort.
    let mut start = vec![0usize; nv as usize + 1];
    for u in &uses {
        start[u.0[0] as usize + 1] += 1;
    }
    for i in 0..nv as usize {
        start[i + 1] += start[i];
    }
    let mut fill = start.clone();
    let mut sorted = vec![([0u32; 2], 0u32); uses.len()];
    for u in &uses {
        sorted[fill[u.0[0] as usize]] = *u;
        fill[u.0[0] as usize] += 1;
    }
    for w in start.windows(2) {
        sorted[w[0]..w[1]].sort_unstable();
    }
    let uses = sorted;
    for run in uses.chunk_by(|x, y| x.0 == y.0) {
        if split.curve_edges.binary_search(&run[0].0).is_ok() {
            continue;
        }
        // Only a manifold edge joins: where three or more sheets meet (a branch line of faults
        // given as one surface), each sheet is a patch of its own and the line is their curve.
        let [x, y] = run else {
            continue;
        };
        if crease((x.1, y.1)) {
            continue;
        }
        let (ra, rb) = (root(&mut up, x.1 as usize), root(&mut up, y.1 as usize));
        if ra != rb {
            up[ra.max(rb)] = ra.min(rb);
        }
    }
    // Components by root, in order of their first (smallest) triangle.
    let mut comp_of: Vec<u32> = vec![u32::MAX; n];
    let mut comps: Vec<Vec<u32>> = Vec::new();
    for t in 0..n {
        if m.triangles[t].iter().any(|&v| v >= nv) {
            continue;
        }
        let r = root(&mut up, t);
        if comp_of[r] == u32::MAX {
            comp_of[r] = comps.len() as u32;
            comps.push(Vec::new());
        }
        comps[comp_of[r] as usize].push(t as u32);
    }
    let mut out = extract(m, comps);
    for (k, p) in out.iter_mut().enumerate() {
        p.name = format!("{surface}#{}", k + 1);
    }
    out
}

/// The patches (unnamed) made of each group of `m`'s triangles, each with its own compact mesh,
/// in canonical order: by their sorted vertex coordinates, then by their triangles.
pub(crate) fn extract(m: &TriMesh, groups: Vec<Vec<u32>>) -> Vec<Patch> {
    // Local vertex numbers, reset after each patch (u32::MAX = not yet used by this patch).
    let mut local: Vec<u32> = vec![u32::MAX; m.vertices.len()];
    let mut out: Vec<(Vec<[f64; 3]>, Patch)> = groups
        .into_iter()
        .map(|triangles| {
            let mut used: Vec<u32> = Vec::new();
            let mut vertices = Vec::new();
            let mut tris = Vec::with_capacity(triangles.len());
            for &t in &triangles {
                let tri = m.triangles[t as usize];
                tris.push(tri.map(|v| {
                    let slot = &mut local[v as usize];
                    if *slot == u32::MAX {
                        *slot = vertices.len() as u32;
                        vertices.push(m.vertices[v as usize]);
                        used.push(v);
                    }
                    *slot
                }));
            }
            for v in used {
                local[v as usize] = u32::MAX;
            }
            let mut key = vertices.clone();
            key.sort_unstable_by(lex);
            let patch = Patch {
                name: String::new(),
                triangles,
                mesh: TriMesh::new(vertices, tris),
            };
            (key, patch)
        })
        .collect();
    out.sort_by(|a, b| {
        a.0.iter()
            .zip(&b.0)
            .map(|(x, y)| lex(x, y))
            .find(|o| o.is_ne())
            .unwrap_or_else(|| a.0.len().cmp(&b.0.len()))
            .then_with(|| a.1.triangles.cmp(&b.1.triangles))
    });
    out.into_iter().map(|(_, p)| p).collect()
}

/// Cuts the patches of one surface into charts where they do not flatten ([`crate::charts`]),
/// labelling the imported surface's triangles once, on the first patch that needs it.
pub struct Charting<'a> {
    original: &'a TriMesh,
    normals: &'a [[f64; 3]],
    labels: Option<Vec<u32>>,
    max_deg: f64,
}

impl<'a> Charting<'a> {
    /// For the patches split from `original`, whose triangles' unit normals are `normals`
    /// (`TriMesh::unit_normals`), with `Tolerances::chart_angle_deg` = `max_deg`.
    pub fn new(original: &'a TriMesh, normals: &'a [[f64; 3]], max_deg: f64) -> Self {
        Charting {
            original,
            normals,
            labels: None,
            max_deg,
        }
    }

    /// `patch` of `split` cut into charts, named `<patch>.1`, `<patch>.2`... in canonical order,
    /// or the patch itself, unchanged, when it flattens whole. A chart is a connected piece of
    /// the patch whose triangles lie in original triangles of one chart of the surface.
    pub fn cut(&mut self, patch: Patch, split: &SplitSurface) -> Vec<Patch> {
        let parent = |t: u32| split.parent.get(t as usize).copied().unwrap_or(u32::MAX);
        let normals: Vec<[f64; 3]> = patch
            .triangles
            .iter()
            .map(|&t| {
                self.normals
                    .get(parent(t) as usize)
                    .copied()
                    .unwrap_or([0.0; 3])
            })
            .collect();
        if !crate::charts::needs_charts(&patch.mesh, &normals, self.max_deg) {
            return vec![patch];
        }
        let labels = self.labels.get_or_insert_with(|| {
            crate::charts::chart_labels(self.original, self.normals, self.max_deg)
        });
        let label = |t: u32| {
            let p = parent(patch.triangles[t as usize]);
            labels.get(p as usize).copied().unwrap_or(u32::MAX)
        };
        let mut groups = crate::charts::connected_groups(&patch.mesh, label);
        let mut group = vec![0u32; patch.triangles.len()];
        for (g, ts) in groups.iter().enumerate() {
            for &t in ts {
                group[t as usize] = g as u32;
            }
        }
        crate::charts::merge_wedges(&patch.mesh, &normals, self.max_deg, &mut group);
        crate::charts::unpinch(&patch.mesh, &mut group);
        if crate::charts::widen_necks(&patch.mesh, &normals, self.max_deg, &mut group) > 0 {
            crate::charts::unpinch(&patch.mesh, &mut group);
        }
        for _ in 0..crate::charts::UNTWIST_PASSES {
            if crate::charts::untwist(&patch.mesh, &normals, self.max_deg, &mut group) == 0 {
                break;
            }
            crate::charts::unpinch(&patch.mesh, &mut group);
        }
        groups = crate::charts::connected_groups(&patch.mesh, |t| group[t as usize]);
        if groups.len() < 2 {
            return vec![patch];
        }
        let mut out = extract(&patch.mesh, groups);
        for (k, p) in out.iter_mut().enumerate() {
            p.name = format!("{}.{}", patch.name, k + 1);
            for t in &mut p.triangles {
                *t = patch.triangles[*t as usize];
            }
        }
        out
    }
}

/// Whether every vertex of `patch` lies within the closed box (exact coordinate comparisons).
/// A patch outside the box has a vertex strictly outside it; NaN coordinates are outside.
pub fn inside_box(patch: &Patch, bbox: &BBox) -> bool {
    patch
        .mesh
        .vertices
        .iter()
        .all(|p| (0..3).all(|k| bbox.min[k] <= p[k] && p[k] <= bbox.max[k]))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::BTreeMap;

    fn square_split(curve: bool) -> SplitSurface {
        // Two triangles sharing edge 0-2; with `curve`, that edge is a curve edge.
        let mesh = TriMesh::new(
            vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [1.0, 1.0, 0.0],
                [0.0, 1.0, 0.0],
            ],
            vec![[0, 1, 2], [0, 2, 3]],
        );
        SplitSurface {
            mesh,
            parent: vec![0, 1],
            vertex_of: BTreeMap::new(),
            vertex_of_each: Vec::new(),
            crossings: Vec::new(),
            curve_edges: if curve { vec![[0, 2]] } else { Vec::new() },
        }
    }

    /// Two triangles sharing edge 0-2, the second bent about it by `deg` degrees out of the
    /// plane, as one unsplit surface (each triangle its own parent), or with the first triangle
    /// split into two slivers along a line through vertex 0 (both children of one parent).
    fn bent(deg: f64, sliver: bool) -> (SplitSurface, TriMesh) {
        let (s, c) = deg.to_radians().sin_cos();
        // Vertex 3 rotates about the diagonal (0,0,0)-(1,1,0) by `deg`.
        let d = [0.5 - 0.5 * c, 0.5 + 0.5 * c, s / std::f64::consts::SQRT_2];
        let vertices = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], d];
        let original = TriMesh::new(vertices.clone(), vec![[0, 1, 2], [0, 2, 3]]);
        let mut split = SplitSurface {
            mesh: original.clone(),
            parent: vec![0, 1],
            vertex_of: BTreeMap::new(),
            vertex_of_each: Vec::new(),
            crossings: Vec::new(),
            curve_edges: Vec::new(),
        };
        if sliver {
            // Triangle 0 cut by the line from vertex 0 to a point on edge 1-2 very close to 2.
            let mut v = vertices;
            v.push([1.0, 1.0 - 1e-9, 0.0]);
            split.mesh = TriMesh::new(v, vec![[0, 1, 4], [0, 4, 2], [0, 2, 3]]);
            split.parent = vec![0, 0, 1];
        }
        (split, original)
    }

    #[test]
    fn a_bend_sharper_than_the_kink_angle_is_a_crease_between_two_patches() {
        for (deg, patches_wanted) in [(10.0, 1), (29.0, 1), (31.0, 2), (90.0, 2), (150.0, 2)] {
            let (split, original) = bent(deg, false);
            let ps = patches_at_creases("s", &split, &original.unit_normals(), 30.0);
            assert_eq!(ps.len(), patches_wanted, "bent by {deg} degrees");
            assert_eq!(patches("s", &split).len(), 1, "without creases");
        }
    }

    #[test]
    fn slivers_that_splitting_makes_inside_one_triangle_never_make_a_crease() {
        // The sliver's own normal is ill-conditioned; its parent's is not.
        let (split, original) = bent(10.0, true);
        assert_eq!(
            patches_at_creases("s", &split, &original.unit_normals(), 30.0).len(),
            1
        );
        let (split, original) = bent(60.0, true);
        let ps = patches_at_creases("s", &split, &original.unit_normals(), 30.0);
        assert_eq!(ps.len(), 2);
        assert_eq!(ps.iter().map(|p| p.triangles.len()).sum::<usize>(), 3);
    }

    #[test]
    fn sheets_meeting_three_and_four_to_an_edge_are_a_patch_each() {
        // Fins on the edge 0-1 (a branch line of faults given as one surface): three sheets, then
        // four (two strands crossing). Each fin has a second triangle beyond it, joined across
        // a manifold edge, so the patches are the sheets, not their triangles.
        for sheets in [3usize, 4] {
            let mut vertices = vec![[0.0, 0.0, 0.0], [0.0, 0.0, 1.0]];
            let mut triangles = Vec::new();
            for k in 0..sheets {
                let a = k as f64 * std::f64::consts::TAU / sheets as f64;
                let (near, far) = (vertices.len() as u32, vertices.len() as u32 + 1);
                vertices.push([a.cos(), a.sin(), 0.0]);
                vertices.push([2.0 * a.cos(), 2.0 * a.sin(), 1.0]);
                triangles.extend([[0, near, 1], [1, near, far]]);
            }
            let n = triangles.len();
            let split = SplitSurface {
                mesh: TriMesh::new(vertices, triangles),
                parent: (0..n as u32).collect(),
                vertex_of: BTreeMap::new(),
                vertex_of_each: Vec::new(),
                crossings: Vec::new(),
                curve_edges: Vec::new(),
            };
            let ps = patches("s", &split);
            assert_eq!(ps.len(), sheets, "{sheets} sheets");
            assert!(ps.iter().all(|p| p.triangles.len() == 2), "{sheets} sheets");
        }
    }

    #[test]
    fn a_curve_edge_separates_two_patches_and_a_plain_edge_does_not() {
        let two = patches("s", &square_split(true));
        assert_eq!(two.len(), 2);
        assert_eq!(two[0].name, "s#1");
        // Both contain vertex 0 (smallest); tie broken by the next vertex: (0,1,0) < (1,0,0).
        assert_eq!(two[0].triangles, vec![1]);
        assert_eq!(two[1].triangles, vec![0]);
        assert_eq!(two[0].mesh.vertices.len(), 3);
        let one = patches("s", &square_split(false));
        assert_eq!(one.len(), 1);
        assert_eq!(one[0].mesh.triangles.len(), 2);
    }

    #[test]
    fn a_patch_with_one_vertex_beyond_the_box_is_outside() {
        let p = &patches("s", &square_split(false))[0];
        let inside = BBox {
            min: [0.0, 0.0, 0.0],
            max: [1.0, 1.0, 0.0],
        };
        assert!(inside_box(p, &inside));
        let smaller = BBox {
            min: [0.0, 0.0, 0.0],
            max: [1.0, 0.999_999_999_999, 0.0],
        };
        assert!(!inside_box(p, &smaller));
    }
}
