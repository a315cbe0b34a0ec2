//! The validity check every surface mesh passes before it leaves the mesher (and that anyone can
//! run on a mesh from elsewhere). Exact where it decides:
//! - the given loop and constraint nodes and points come first, bit-identical, in the documented
//!   order (a point is then an interior node: the border edges are the loop edges, below);
//! - every directed edge is used at most once (manifold, consistently oriented), every vertex
//!   has a single fan (a node where the loops touch: one open fan per visit), every node is used;
//! - the border edges are exactly the given loop edges; every constraint edge is an interior edge;
//! - every node lies within `tol_rel` × (its mean incident edge length) of the support;
//! - no fold or overlap: in the support's flattening (an orientation-preserving bijection, see
//!   `param`), every triangle is strictly counter-clockwise (exact `orient2d`) and the loops do not
//!   cross (exact). A consistently oriented triangulation whose border is a set of simple,
//!   non-crossing loops and whose triangles are all positive covers every point of the domain
//!   exactly once (degree argument), so no triangle overlaps another;
//! - in 3D, every triangle's normal is within 90° of the support's normal under its centroid.

use super::SurfaceMeshError;
use super::input::{GivenNodes, given_nodes};
use super::segments::first_crossing;
use super::support::{OnSupport, Support};
use super::{PatchInput, SurfaceMeshOutput};
use geom::predicates::{cross, dot, sub};
use geom::{Orientation, orient2d};
use std::collections::{BTreeMap, BTreeSet};

fn fail(input: &PatchInput, message: String, at: Option<[f64; 3]>) -> SurfaceMeshError {
    SurfaceMeshError {
        patch: input.name.clone(),
        message,
        at,
    }
}

fn centroid(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3]) -> [f64; 3] {
    [
        (a[0] + b[0] + c[0]) / 3.0,
        (a[1] + b[1] + c[1]) / 3.0,
        (a[2] + b[2] + c[2]) / 3.0,
    ]
}

/// See the module doc.
pub fn verify_with(
    input: &PatchInput,
    out: &SurfaceMeshOutput,
    tol_rel: f64,
    support: &Support,
) -> Result<(), SurfaceMeshError> {
    let given: GivenNodes = given_nodes(input)?;
    check_nodes(input, out, &given)?;
    let directed = directed_edges(input, out)?;
    check_border(input, out, &given, &directed)?;
    check_fans(input, out, &given.loop_visits)?;
    let (uv, ntri) = flatten_nodes(input, out, tol_rel, support, &directed)?;
    check_crossings(input, out, &given, &uv)?;
    check_triangles(input, out, support, &uv, &ntri)
}

/// Whether the given nodes come first bit for bit, every node is finite, and there are triangles.
fn check_nodes(
    input: &PatchInput,
    out: &SurfaceMeshOutput,
    given: &GivenNodes,
) -> Result<(), SurfaceMeshError> {
    let nn = out.nodes.len();
    if nn < given.nodes.len() {
        return Err(fail(
            input,
            format!(
                "the mesh has {nn} nodes, fewer than the {} given",
                given.nodes.len()
            ),
            None,
        ));
    }
    for (i, p) in given.nodes.iter().enumerate() {
        let q = &out.nodes[i];
        if p.map(f64::to_bits) != q.map(f64::to_bits) {
            return Err(fail(
                input,
                format!("output node {i} is not the given node bit for bit"),
                Some(*p),
            ));
        }
    }
    for (i, p) in out.nodes.iter().enumerate() {
        if p.iter().any(|c| !c.is_finite()) {
            return Err(fail(input, format!("node {i} is not finite"), None));
        }
    }
    if out.triangles.is_empty() {
        return Err(fail(
            input,
            "the mesh has no triangles".into(),
            given.nodes.first().copied(),
        ));
    }
    Ok(())
}

/// The directed edges (each to its triangle): whether triangles are well formed, no directed
/// edge is used twice, and every node is used.
fn directed_edges(
    input: &PatchInput,
    out: &SurfaceMeshOutput,
) -> Result<BTreeMap<(u32, u32), u32>, SurfaceMeshError> {
    let nn = out.nodes.len();
    let mut directed: BTreeMap<(u32, u32), u32> = BTreeMap::new();
    let mut used = vec![false; nn];
    for (t, tri) in out.triangles.iter().enumerate() {
        if tri.iter().any(|&v| v as usize >= nn) {
            return Err(fail(
                input,
                format!("triangle {t} refers to a missing node"),
                None,
            ));
        }
        if tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2] {
            return Err(fail(
                input,
                format!("triangle {t} repeats a node"),
                Some(out.nodes[tri[0] as usize]),
            ));
        }
        for i in 0..3 {
            used[tri[i] as usize] = true;
            let e = (tri[i], tri[(i + 1) % 3]);
            if directed.insert(e, t as u32).is_some() {
                return Err(fail(
                    input,
                    format!(
                        "edge {}-{} is used twice in the same direction (non-manifold or inconsistent orientation)",
                        e.0, e.1
                    ),
                    Some(out.nodes[e.0 as usize]),
                ));
            }
        }
    }
    if let Some(i) = used.iter().position(|u| !u) {
        return Err(fail(
            input,
            format!("node {i} is not used by any triangle"),
            Some(out.nodes[i]),
        ));
    }
    Ok(directed)
}

/// Whether the border edges are exactly the given loop edges, each used once, and every
/// constraint edge is interior.
fn check_border(
    input: &PatchInput,
    out: &SurfaceMeshOutput,
    given: &GivenNodes,
    directed: &BTreeMap<(u32, u32), u32>,
) -> Result<(), SurfaceMeshError> {
    let loop_edges: BTreeSet<(u32, u32)> = given
        .loop_segments()
        .map(|(a, b)| (a.min(b), a.max(b)))
        .collect();
    for &(a, b) in directed.keys() {
        if !directed.contains_key(&(b, a)) && !loop_edges.contains(&(a.min(b), a.max(b))) {
            return Err(fail(
                input,
                format!(
                    "border edge {a}-{b} is not a given loop edge (a hole or a gap in the mesh)"
                ),
                Some(out.nodes[a as usize]),
            ));
        }
    }
    for &(a, b) in &loop_edges {
        let n = directed.contains_key(&(a, b)) as u32 + directed.contains_key(&(b, a)) as u32;
        if n != 1 {
            return Err(fail(
                input,
                format!("loop edge {a}-{b} is used by {n} triangles, not exactly 1"),
                Some(out.nodes[a as usize]),
            ));
        }
    }
    for (a, b) in given.constraint_segments() {
        if !(directed.contains_key(&(a, b)) && directed.contains_key(&(b, a))) {
            return Err(fail(
                input,
                format!("constraint edge {a}-{b} is not an interior mesh edge"),
                Some(out.nodes[a as usize]),
            ));
        }
    }
    Ok(())
}

/// Vertex fans: whether the link of each vertex is one path or one cycle, or, at a node the
/// loops pass `k >= 2` times (a pinch), `k` paths.
fn check_fans(
    input: &PatchInput,
    out: &SurfaceMeshOutput,
    loop_visits: &[u32],
) -> Result<(), SurfaceMeshError> {
    let mut link: Vec<(u32, u32, u32)> = Vec::with_capacity(out.triangles.len() * 3);
    for tri in &out.triangles {
        for i in 0..3 {
            link.push((tri[i], tri[(i + 1) % 3], tri[(i + 2) % 3]));
        }
    }
    link.sort_unstable();
    let mut k = 0;
    while k < link.len() {
        let v = link[k].0;
        let mut e = k;
        while e < link.len() && link[e].0 == v {
            e += 1;
        }
        let visits = loop_visits.get(v as usize).copied().unwrap_or(0) as usize;
        let ok = match fans(&link[k..e]) {
            Some((paths, cycles)) if visits >= 2 => paths == visits && cycles == 0,
            Some((paths, cycles)) => paths + cycles == 1,
            None => false,
        };
        if !ok {
            return Err(fail(
                input,
                format!("node {v} is not manifold (its triangles form several fans)"),
                Some(out.nodes[v as usize]),
            ));
        }
        k = e;
    }
    Ok(())
}

/// How one vertex's corners `(vertex, next, previous)`, sorted, chain: the number of open fans
/// (paths) and closed ones (cycles); `None` when two corners leave from, or arrive at, the same
/// neighbour.
fn fans(link: &[(u32, u32, u32)]) -> Option<(usize, usize)> {
    let next: BTreeMap<u32, u32> = link.iter().map(|x| (x.1, x.2)).collect();
    let targets: BTreeSet<u32> = link.iter().map(|x| x.2).collect();
    if next.len() != link.len() || targets.len() != link.len() {
        return None;
    }
    let mut seen: BTreeSet<u32> = BTreeSet::new();
    let mut paths = 0;
    for start in next.keys().copied().filter(|s| !targets.contains(s)) {
        paths += 1;
        let mut cur = start;
        while let Some(&n) = next.get(&cur) {
            seen.insert(cur);
            cur = n;
        }
    }
    let mut cycles = 0;
    for &start in next.keys() {
        if seen.contains(&start) {
            continue;
        }
        cycles += 1;
        let mut cur = start;
        while seen.insert(cur) {
            cur = next[&cur];
        }
    }
    Some((paths, cycles))
}

/// Distance to the support and parameters: whether every node lies within `tol_rel` × its mean
/// edge length of the support; returns each node's flattening and support triangle.
fn flatten_nodes(
    input: &PatchInput,
    out: &SurfaceMeshOutput,
    tol_rel: f64,
    support: &Support,
    directed: &BTreeMap<(u32, u32), u32>,
) -> Result<(Vec<[f64; 2]>, Vec<u32>), SurfaceMeshError> {
    let nn = out.nodes.len();
    let mut lsum = vec![0.0f64; nn];
    let mut lcnt = vec![0u32; nn];
    for &(a, b) in directed.keys() {
        let d = sub(&out.nodes[a as usize], &out.nodes[b as usize]);
        let l = dot(&d, &d).sqrt();
        lsum[a as usize] += l;
        lcnt[a as usize] += 1;
        lsum[b as usize] += l;
        lcnt[b as usize] += 1;
    }
    let mut uv = Vec::with_capacity(nn);
    let mut ntri = Vec::with_capacity(nn);
    let on_support = node_facets(support, &out.nodes);
    for (i, (p, on)) in out.nodes.iter().zip(on_support).enumerate() {
        let Some(on) = on else {
            return Err(fail(input, "the support is empty".into(), Some(*p)));
        };
        let local = lsum[i] / lcnt[i].max(1) as f64;
        if on.dist > tol_rel * local {
            return Err(fail(
                input,
                format!(
                    "node {i} is {:.3e} from the support, more than {tol_rel:e} × its edge length {local:.3e}",
                    on.dist
                ),
                Some(*p),
            ));
        }
        uv.push(on.uv);
        ntri.push(on.tri);
    }
    Ok((uv, ntri))
}

/// Where each of `nodes` lies on the support, each search starting from the facet of the node
/// before it. The fold repair finds the facets the same way, so that it sees what
/// [`check_triangles`] refuses: on a crumpled support, searches from different facets can land
/// on different ones.
pub(crate) fn node_facets(support: &Support, nodes: &[[f64; 3]]) -> Vec<Option<OnSupport>> {
    let mut hint = u32::MAX;
    (nodes.iter())
        .map(|p| {
            let on = support.project_hinted(hint, p);
            if let Some(on) = &on {
                hint = on.tri;
            }
            on
        })
        .collect()
}

/// Whether the flat triangle `[a, b, c]` faces away from the support (its normal 90° or more
/// from the support's) under its centroid, as found from support facet `from`; `None` where
/// nothing is found or the facet there has no normal (zero area).
pub(crate) fn faces_away(
    support: &Support,
    [a, b, c]: [&[f64; 3]; 3],
    from: u32,
) -> Option<(bool, u32)> {
    let g = centroid(a, b, c);
    let n = cross(&sub(b, a), &sub(c, a));
    let on = support.project_from(from, &g)?;
    let ns = support.normals[on.tri as usize];
    (ns != [0.0; 3]).then(|| (!(dot(&n, &ns) > 0.0), on.tri))
}

/// Whether the loops and constraints stay apart in the flattening (exact).
fn check_crossings(
    input: &PatchInput,
    out: &SurfaceMeshOutput,
    given: &GivenNodes,
    uv: &[[f64; 2]],
) -> Result<(), SurfaceMeshError> {
    let segs: Vec<([f64; 2], [f64; 2])> = given
        .loop_segments()
        .chain(given.constraint_segments())
        .map(|(a, b)| (uv[a as usize], uv[b as usize]))
        .collect();
    if let Some((i, _)) = first_crossing(&segs) {
        let (a, _) = given
            .loop_segments()
            .chain(given.constraint_segments())
            .nth(i)
            .unwrap_or((0, 0));
        return Err(fail(
            input,
            "the loops or constraints cross each other".into(),
            Some(out.nodes[a as usize]),
        ));
    }
    Ok(())
}

/// Whether every triangle is strictly counter-clockwise in the flattening and, in 3D, within 90°
/// of the support's normal under its centroid.
fn check_triangles(
    input: &PatchInput,
    out: &SurfaceMeshOutput,
    support: &Support,
    uv: &[[f64; 2]],
    ntri: &[u32],
) -> Result<(), SurfaceMeshError> {
    for (t, tri) in out.triangles.iter().enumerate() {
        let [a, b, c] = tri.map(|v| v as usize);
        let g = centroid(&out.nodes[a], &out.nodes[b], &out.nodes[c]);
        if orient2d(&uv[a], &uv[b], &uv[c]) != Orientation::Positive {
            return Err(fail(
                input,
                format!("triangle {t} is inverted or overlaps its neighbours on the support"),
                Some(g),
            ));
        }
        let corners = [&out.nodes[a], &out.nodes[b], &out.nodes[c]];
        if let Some((true, under)) = faces_away(support, corners, ntri[a]) {
            // How far the support turns between the facets under the triangle's corners and
            // centroid: a bend sharper than one element can follow is the usual cause.
            let under = [ntri[a], ntri[b], ntri[c], under].map(|f| support.normals[f as usize]);
            let bend = (under.iter())
                .flat_map(|m| under.iter().map(move |k| dot(m, k).clamp(-1.0, 1.0).acos()))
                .fold(0.0, f64::max)
                .to_degrees();
            return Err(fail(
                input,
                format!(
                    "triangle {t} folds: its normal is more than 90° from the support's (the \
                     support turns by {bend:.0}° under it)"
                ),
                Some(g),
            ));
        }
    }
    Ok(())
}
