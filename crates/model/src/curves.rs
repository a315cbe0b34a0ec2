//! Curves and vertices of the model: curve edges found by their patch signature, chained between
//! topological vertices, named canonically; then every patch's boundary loops and constraints.
//! (The decisions are listed in the module doc of the `model` crate.)

use super::{Curve, CurveUse, ModelError, ModelTopology, PatchBoundary, cmp_points};
use crate::kinks::is_kink;
use crate::regions::PatchIn;
use geom::Tolerances;
use std::collections::BTreeMap;

/// Patches along an edge, each with the number of its triangles there (1: a border of the patch,
/// 2: the patch is on both sides), sorted by patch.
type Signature = Vec<(u32, u8)>;

struct CurveEdge {
    /// Welded vertex ids, `a < b`.
    a: u32,
    b: u32,
    sig: u32,
}

/// Welds the patches' vertices by exact coordinates. Returns the sorted unique points and, per
/// patch, the welded id of every local vertex.
fn weld(patches: &[PatchIn]) -> (Vec<[f64; 3]>, Vec<Vec<u32>>) {
    let fold = |p: &[f64; 3]| p.map(|x| if x == 0.0 { 0.0 } else { x });
    let mut points: Vec<[f64; 3]> = patches
        .iter()
        .flat_map(|p| p.mesh.vertices.iter().map(fold))
        .collect();
    points.sort_by(cmp_points);
    points.dedup();
    let ids = patches
        .iter()
        .map(|p| {
            p.mesh
                .vertices
                .iter()
                .map(|v| {
                    points
                        .binary_search_by(|q| cmp_points(q, &fold(v)))
                        .map_or(u32::MAX, |i| i as u32)
                })
                .collect()
        })
        .collect();
    (points, ids)
}

/// Builds the model's vertices, named curves and patch boundaries from conforming patches.
pub fn build_topology(patches: &[PatchIn], tol: &Tolerances) -> Result<ModelTopology, ModelError> {
    let (points, ids) = weld(patches);
    let edges = triangle_edges(patches, &ids)?;
    let (sig_list, curve_edges, borders) = classify_edges(&edges);
    let seams = seam_signatures(patches, &sig_list);
    let graph = CurveGraph::new(&points, &curve_edges, &seams);
    let nv = points.len();
    let vertex_flags: Vec<bool> = (0..nv as u32).map(|v| graph.is_vertex(v, tol)).collect();
    let chains = graph.chains(&vertex_flags);
    let (curves, curve_sig, chain_to_curve) = name_curves(patches, &points, &sig_list, &chains);

    // Each curve edge's curve, and whether the curve runs it from low to high id.
    let mut edge_curve = vec![(u32::MAX, false); curve_edges.len()];
    for (ci, (vs, es, _, _)) in chains.iter().enumerate() {
        for (k, &e) in es.iter().enumerate() {
            edge_curve[e as usize] = (chain_to_curve[ci], vs[k] < vs[k + 1]);
        }
    }
    let patch_bounds = patch_boundaries(
        patches,
        &curves,
        &borders,
        &edge_curve,
        &curve_sig,
        &sig_list,
    )?;
    let vertices: Vec<[f64; 3]> = (0..nv)
        .filter(|&v| vertex_flags[v])
        .map(|v| points[v])
        .collect();
    let mut curves = curves;
    let room = crate::clearance::clearances(&curves, &patch_bounds, patches);
    for (c, r) in curves.iter_mut().zip(room) {
        c.clearance = r;
    }
    Ok(ModelTopology {
        vertices,
        curves,
        patches: patch_bounds,
    })
}

/// Per signature, whether it is a seam: two or more charts of one patch, each with one triangle
/// along the edge (the charts' own border there).
fn seam_signatures(patches: &[PatchIn], sig_list: &[Signature]) -> Vec<bool> {
    sig_list
        .iter()
        .map(|sig| {
            let of = |p: u32| patches[p as usize].chart_of.as_deref();
            sig.len() >= 2
                && of(sig[0].0).is_some()
                && sig.iter().all(|&(p, n)| n == 1 && of(p) == of(sig[0].0))
        })
        .collect()
}

/// A chain of curve edges: vertex ids, edge ids, signature, closed.
type Chain = (Vec<u32>, Vec<u32>, u32, bool);

/// A triangle edge: low id, high id, patch, whether the triangle runs it from low to high id.
type TriEdge = (u32, u32, u32, bool);

/// A patch's border half-edge: patch, curve edge, whether it runs low→high.
type Border = (u32, u32, bool);

/// Every triangle edge, with its patch and whether the triangle runs it from low to high id;
/// sorted. Rejects triangles that index past their patch's vertices.
fn triangle_edges(patches: &[PatchIn], ids: &[Vec<u32>]) -> Result<Vec<TriEdge>, ModelError> {
    let mut edges: Vec<TriEdge> = Vec::new();
    for (p, patch) in patches.iter().enumerate() {
        for t in &patch.mesh.triangles {
            let g = t.map(|v| ids[p].get(v as usize).copied().unwrap_or(u32::MAX));
            if g.contains(&u32::MAX) {
                return Err(ModelError::new(
                    format!("patch `{}` has a triangle {t:?} out of range", patch.name),
                    None,
                ));
            }
            for k in 0..3 {
                let (u, v) = (g[k], g[(k + 1) % 3]);
                if u != v {
                    edges.push((u.min(v), u.max(v), p as u32, u < v));
                }
            }
        }
    }
    edges.sort_unstable();
    Ok(edges)
}

/// Which edges are curve edges (patch borders or shared by several patches), their signatures
/// (indexed by first appearance), and each patch's border half-edges as
/// (patch, curve edge, runs low→high).
fn classify_edges(edges: &[TriEdge]) -> (Vec<Signature>, Vec<CurveEdge>, Vec<Border>) {
    let mut sigs: BTreeMap<Signature, u32> = BTreeMap::new();
    let mut curve_edges: Vec<CurveEdge> = Vec::new();
    let mut borders: Vec<Border> = Vec::new();
    let mut i = 0;
    while i < edges.len() {
        let (a, b) = (edges[i].0, edges[i].1);
        let mut j = i;
        while j < edges.len() && edges[j].0 == a && edges[j].1 == b {
            j += 1;
        }
        let group = &edges[i..j];
        let mut sig: Signature = Vec::new();
        for e in group {
            match sig.last_mut() {
                Some((p, n)) if *p == e.2 => *n = n.saturating_add(1),
                _ => sig.push((e.2, 1)),
            }
        }
        if sig.len() >= 2 || sig[0].1 == 1 {
            let next = sigs.len() as u32;
            let s = *sigs.entry(sig.clone()).or_insert(next);
            let ce = curve_edges.len() as u32;
            curve_edges.push(CurveEdge { a, b, sig: s });
            for &(p, n) in &sig {
                if n == 1 {
                    let fwd = group.iter().find(|e| e.2 == p).is_some_and(|e| e.3);
                    borders.push((p, ce, fwd));
                }
            }
        }
        i = j;
    }
    let mut sig_list = vec![Vec::new(); sigs.len()];
    for (s, i) in sigs {
        sig_list[i as usize] = s;
    }
    (sig_list, curve_edges, borders)
}

/// The curve edges around each welded vertex (compressed rows).
struct CurveGraph<'a> {
    points: &'a [[f64; 3]],
    curve_edges: &'a [CurveEdge],
    /// Per signature, whether its curves are seams (never cut at kinks).
    seams: &'a [bool],
    start: Vec<u32>,
    inc: Vec<u32>,
}

impl<'a> CurveGraph<'a> {
    /// Lists every vertex's incident curve edges, in edge order.
    fn new(points: &'a [[f64; 3]], curve_edges: &'a [CurveEdge], seams: &'a [bool]) -> Self {
        let nv = points.len();
        let mut start = vec![0u32; nv + 1];
        for e in curve_edges {
            start[e.a as usize + 1] += 1;
            start[e.b as usize + 1] += 1;
        }
        for k in 0..nv {
            start[k + 1] += start[k];
        }
        let mut fill = start.clone();
        let mut inc = vec![0u32; start[nv] as usize];
        for (k, e) in curve_edges.iter().enumerate() {
            for v in [e.a, e.b] {
                inc[fill[v as usize] as usize] = k as u32;
                fill[v as usize] += 1;
            }
        }
        CurveGraph {
            points,
            curve_edges,
            seams,
            start,
            inc,
        }
    }

    fn incident(&self, v: u32) -> &[u32] {
        &self.inc[self.start[v as usize] as usize..self.start[v as usize + 1] as usize]
    }

    fn other(&self, e: u32, v: u32) -> u32 {
        let ce = &self.curve_edges[e as usize];
        if ce.a == v { ce.b } else { ce.a }
    }

    /// Whether `v` is a topological vertex: a curve end, a junction, a change of signature, or a
    /// kink sharper than the kink angle (except on a seam between charts).
    fn is_vertex(&self, v: u32, tol: &Tolerances) -> bool {
        let es = self.incident(v);
        if es.len() != 2 {
            return !es.is_empty();
        }
        let sig = self.curve_edges[es[0] as usize].sig;
        if self.curve_edges[es[1] as usize].sig != sig {
            return true;
        }
        if self.seams[sig as usize] {
            return false;
        }
        is_kink(
            &self.points[v as usize],
            self.run(v, es[0]),
            self.run(v, es[1]),
            tol.kink_angle_deg,
        )
    }

    /// The points of the curve from `v` outwards along `e`: through vertices with two curve
    /// edges of one signature, ending at the first other vertex (or back at `v`).
    fn run(&self, v: u32, e: u32) -> impl Iterator<Item = [f64; 3]> + '_ {
        let sig = self.curve_edges[e as usize].sig;
        let mut step = Some((v, e));
        std::iter::from_fn(move || {
            let (from, e) = step?;
            let w = self.other(e, from);
            let es = self.incident(w);
            step = (w != v && es.len() == 2)
                .then(|| es.iter().copied().find(|&f| f != e))
                .flatten()
                .filter(|&f| self.curve_edges[f as usize].sig == sig)
                .map(|f| (w, f));
            Some(self.points[w as usize])
        })
    }

    /// Follows curve edges from `v0` along `e0` until a topological vertex, back to `v0`, or an
    /// already visited edge.
    fn walk(
        &self,
        vertex_flags: &[bool],
        v0: u32,
        e0: u32,
        visited: &mut [bool],
    ) -> (Vec<u32>, Vec<u32>) {
        let mut vs = vec![v0];
        let mut es = Vec::new();
        let (mut v, mut e) = (v0, e0);
        loop {
            visited[e as usize] = true;
            es.push(e);
            let w = self.other(e, v);
            vs.push(w);
            if vertex_flags[w as usize] || w == v0 {
                break;
            }
            match self.incident(w).iter().copied().find(|&f| f != e) {
                Some(f) if !visited[f as usize] => {
                    v = w;
                    e = f;
                }
                _ => break,
            }
        }
        (vs, es)
    }

    /// Cuts the curve edges into chains between topological vertices, then closed loops through
    /// none, each in canonical direction.
    fn chains(&self, vertex_flags: &[bool]) -> Vec<Chain> {
        let mut visited = vec![false; self.curve_edges.len()];
        let mut chains: Vec<Chain> = Vec::new();
        for v in 0..self.points.len() as u32 {
            if !vertex_flags[v as usize] {
                continue;
            }
            for &e in self.incident(v) {
                if !visited[e as usize] {
                    let (vs, es) = self.walk(vertex_flags, v, e, &mut visited);
                    let sig = self.curve_edges[e as usize].sig;
                    chains.push((vs, es, sig, false));
                }
            }
        }
        // What is left are closed loops through no topological vertex.
        for e in 0..self.curve_edges.len() as u32 {
            if visited[e as usize] {
                continue;
            }
            let v0 = self.curve_edges[e as usize].a;
            let (vs, es) = self.walk(vertex_flags, v0, e, &mut visited);
            let sig = self.curve_edges[e as usize].sig;
            chains.push((vs, es, sig, true));
        }
        for (vs, es, _, closed) in &mut chains {
            canonical_direction(vs, es, *closed);
        }
        chains
    }
}

/// Names the chains: by surface set, then rank by the canonical polyline (ids are in coordinate
/// order). Returns the curves, each curve's signature, and each chain's curve.
fn name_curves(
    patches: &[PatchIn],
    points: &[[f64; 3]],
    sig_list: &[Signature],
    chains: &[Chain],
) -> (Vec<Curve>, Vec<u32>, Vec<u32>) {
    let surfaces_of = |sig: u32| {
        let mut s: Vec<String> = sig_list[sig as usize]
            .iter()
            .map(|&(p, _)| patches[p as usize].surface.clone())
            .collect();
        s.sort();
        s.dedup();
        s
    };
    let mut keyed: Vec<(Vec<String>, usize)> = chains
        .iter()
        .enumerate()
        .map(|(i, c)| (surfaces_of(c.2), i))
        .collect();
    keyed.sort_by(|x, y| {
        x.0.cmp(&y.0)
            .then_with(|| chains[x.1].0.cmp(&chains[y.1].0))
    });
    let mut curves: Vec<Curve> = Vec::with_capacity(chains.len());
    let mut curve_sig: Vec<u32> = Vec::with_capacity(chains.len());
    let mut chain_to_curve = vec![0u32; chains.len()];
    let mut g = 0;
    while g < keyed.len() {
        let mut h = g;
        while h < keyed.len() && keyed[h].0 == keyed[g].0 {
            h += 1;
        }
        let base = keyed[g].0.join("/");
        let numbered = h - g > 1 || keyed[g].0.len() == 1;
        for (k, (surfaces, ci)) in keyed[g..h].iter().enumerate() {
            let (vs, _, sig, closed) = &chains[*ci];
            chain_to_curve[*ci] = curves.len() as u32;
            curve_sig.push(*sig);
            curves.push(Curve {
                name: if numbered {
                    format!("{base}#{}", k + 1)
                } else {
                    base.clone()
                },
                surfaces: surfaces.clone(),
                patches: sig_list[*sig as usize].iter().map(|&(p, _)| p).collect(),
                points: vs.iter().map(|&v| points[v as usize]).collect(),
                closed: *closed,
                clearance: Vec::new(),
                curvature_size: Vec::new(),
                narrow_size: Vec::new(),
            });
        }
        g = h;
    }
    (curves, curve_sig, chain_to_curve)
}

/// Open chains run from their smaller end (ties: smaller second point); closed loops start at
/// their smallest vertex and go towards its smaller neighbour.
fn canonical_direction(vs: &mut [u32], es: &mut [u32], closed: bool) {
    if closed {
        // vs repeats its first vertex at the end; rotate so the smallest comes first.
        let n = vs.len() - 1;
        let m = (0..n).min_by_key(|&i| vs[i]).unwrap_or(0);
        vs[..n].rotate_left(m);
        vs[n] = vs[0];
        es.rotate_left(m);
    }
    let n = vs.len();
    let reverse = if vs[0] != vs[n - 1] {
        vs[n - 1] < vs[0]
    } else {
        n > 2 && vs[n - 2] < vs[1]
    };
    if reverse {
        vs.reverse();
        es.reverse();
    }
}

fn patch_boundaries(
    patches: &[PatchIn],
    curves: &[Curve],
    borders: &[(u32, u32, bool)],
    edge_curve: &[(u32, bool)],
    curve_sig: &[u32],
    sig_list: &[Signature],
) -> Result<Vec<PatchBoundary>, ModelError> {
    let mut out = vec![PatchBoundary::default(); patches.len()];
    // (patch, curve) -> reversed
    let mut uses: BTreeMap<(u32, u32), bool> = BTreeMap::new();
    for &(p, e, fwd) in borders {
        let (c, curve_fwd) = edge_curve[e as usize];
        let reversed = fwd != curve_fwd;
        if let Some(&r) = uses.get(&(p, c)) {
            if r != reversed {
                let at = curves[c as usize].points[0];
                return Err(ModelError::new(
                    format!(
                        "patch `{}` is not consistently oriented along curve `{}`",
                        patches[p as usize].name, curves[c as usize].name
                    ),
                    Some(at),
                ));
            }
        } else {
            uses.insert((p, c), reversed);
        }
    }
    for (c, &sig) in curve_sig.iter().enumerate() {
        for &(p, n) in &sig_list[sig as usize] {
            if n >= 2 {
                out[p as usize].constraints.push(c as u32);
            }
        }
    }
    let mut by_patch: BTreeMap<u32, Vec<CurveUse>> = BTreeMap::new();
    for (&(p, c), &reversed) in &uses {
        by_patch
            .entry(p)
            .or_default()
            .push(CurveUse { curve: c, reversed });
    }
    for (p, list) in by_patch {
        out[p as usize].loops = chain_loops(&patches[p as usize].name, curves, &list)?;
    }
    Ok(out)
}

/// The end points of a curve use, in loop direction.
fn ends(curves: &[Curve], u: &CurveUse) -> ([f64; 3], [f64; 3]) {
    let pts = &curves[u.curve as usize].points;
    let (a, b) = (pts[0], pts[pts.len() - 1]);
    if u.reversed { (b, a) } else { (a, b) }
}

/// Chains a patch's curve uses into closed loops (deterministically: smallest curve index first).
fn chain_loops(
    patch: &str,
    curves: &[Curve],
    list: &[CurveUse],
) -> Result<Vec<Vec<CurveUse>>, ModelError> {
    let mut used = vec![false; list.len()];
    let mut loops = Vec::new();
    while let Some(first) = used.iter().position(|u| !u) {
        used[first] = true;
        let (start, mut end) = ends(curves, &list[first]);
        let mut lp = vec![list[first]];
        while end != start {
            let next = (0..list.len()).find(|&k| !used[k] && ends(curves, &list[k]).0 == end);
            let Some(k) = next else {
                return Err(ModelError::new(
                    format!("the boundary of patch `{patch}` is open"),
                    Some(end),
                ));
            };
            used[k] = true;
            lp.push(list[k]);
            end = ends(curves, &list[k]).1;
        }
        loops.push(lp);
    }
    Ok(loops)
}
