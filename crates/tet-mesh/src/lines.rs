//! Embedded line segments (well paths): what a valid input segment is, and the exact check that
//! a mesh carries each one as a chain of tet edges.
//!
//! Input (`check_lines`): a segment joins two distinct vertices; it meets a boundary or embedded
//! triangle, or another segment, only in a vertex they share by index (so a segment along a
//! triangle's edge is refused: it would lie in that triangle); and it lies inside the region.
//! Every test is exact (`geom::contact`, `inside`); a segment that fails is named with its end
//! coordinates.
//!
//! Output (`verify_chains`): each segment's chain runs from its first vertex to its second
//! through new nodes used by no other chain, every step is an edge of some tet, and every inner
//! node lies on the segment. A point strictly inside a segment between two float points is in
//! general not a float point (only an axis-parallel or otherwise lucky segment has any), so the
//! mesher places each inner node at the correctly computed point rounded once per coordinate
//! (`point_on`), and the check is exact about that: the segment meets the box of
//! `ROUNDING_ULPS` units in the last place of the segment's coordinates around the node (well
//! over the construction's error), and the nodes advance strictly along the segment's main axis.

use super::inside::{Rays, boundary_vertices, one_per_group};
use super::{RegionInput, TetMeshError, TetMeshOutput};
use geom::BBox;
use geom::broad_phase::overlapping_pairs;
use geom::contact::{Seg, Tri, segment_meets_box, segment_meets_triangle, segments_meet};

type P = [f64; 3];

/// Half-width of the box around an inner chain node that the segment must meet, in units in the
/// last place of the larger end coordinate: `point_on` is off by at most 1.5 such units, and
/// the box's corners, rounded, lose at most one more.
const ROUNDING_ULPS: f64 = 4.0;

/// The point at parameter `t` of the segment `ab`, each coordinate rounded once (fused
/// multiply-add; exact where the segment does not vary in that coordinate).
pub(crate) fn point_on(a: &P, b: &P, t: f64) -> P {
    [0, 1, 2].map(|k| t.mul_add(b[k] - a[k], a[k]))
}

/// The spacing of floats at `x`.
fn ulp(x: f64) -> f64 {
    let x = x.abs();
    x.next_up() - x
}

/// Whether `p` is the rounded image of a point of the segment `ab` (exact, see the module doc).
pub(crate) fn on_segment(a: &P, b: &P, p: &P) -> bool {
    let e = [0, 1, 2].map(|k| ROUNDING_ULPS * ulp(a[k].abs().max(b[k].abs())));
    let lo = [0, 1, 2].map(|k| p[k] - e[k]);
    let hi = [0, 1, 2].map(|k| p[k] + e[k]);
    segment_meets_box(a, b, &lo, &hi)
}

/// The axis along which segment `ab` runs the most (float: any axis along which it varies
/// would do for an exact test of order).
pub(crate) fn main_axis(a: &P, b: &P) -> usize {
    let d = [0, 1, 2].map(|k| (b[k] - a[k]).abs());
    (0..3).fold(0, |m, k| if d[k] > d[m] { k } else { m })
}

fn segment_error(input: &RegionInput, k: usize, what: String) -> TetMeshError {
    let [u, v] = input.lines[k];
    let p = |v: u32| input.vertices.get(v as usize).copied();
    let at = |v: u32| p(v).map_or("?".to_string(), |q| format!("{q:?}"));
    TetMeshError::new(
        &input.name,
        format!(
            "line segment {k} [{u}, {v}] from {} to {} {what}",
            at(u),
            at(v)
        ),
        p(u),
    )
}

/// Checks the input segments (see the module doc); nothing to do without any.
pub(crate) fn check_lines(input: &RegionInput) -> Result<(), TetMeshError> {
    let n = input.vertices.len();
    for (k, &[u, v]) in input.lines.iter().enumerate() {
        if u as usize >= n || v as usize >= n {
            let what = format!("refers to a vertex beyond the {n} vertices");
            return Err(segment_error(input, k, what));
        }
        if input.vertices[u as usize] == input.vertices[v as usize] {
            return Err(segment_error(input, k, "has no length".into()));
        }
    }
    if input.lines.is_empty() {
        return Ok(());
    }
    check_crossings(input)?;
    check_inside(input)
}

/// No segment meets a triangle or another segment improperly (exact, after a box filter).
fn check_crossings(input: &RegionInput) -> Result<(), TetMeshError> {
    let pts = &input.vertices;
    let tris: Vec<([u32; 3], &str, usize)> = (input.boundary.iter().enumerate())
        .map(|(i, &t)| (t, "boundary", i))
        .chain((input.embedded.iter().enumerate()).map(|(i, &t)| (t, "embedded", i)))
        .collect();
    let segs = &input.lines;
    let box_of = |vs: &[u32]| BBox::from_points(vs.iter().map(|&v| &pts[v as usize]));
    // Boxes: the segments first, then the triangles near them.
    let reach = box_of(segs.as_flattened());
    let near: Vec<usize> = (0..tris.len())
        .filter(|&i| box_of(&tris[i].0).overlaps(&reach))
        .collect();
    let mut boxes: Vec<BBox> = segs.iter().map(|s| box_of(s)).collect();
    boxes.extend(near.iter().map(|&i| box_of(&tris[i].0)));
    // The first failing pair in (segment, other) order is reported.
    let bad = overlapping_pairs(&boxes, |x, y| {
        let (x, y) = (x as usize, y as usize);
        let e = Seg::of(*segs.get(x)?, pts);
        let meet = match segs.get(y) {
            Some(&f) => segments_meet(&e, &Seg::of(f, pts)),
            None => segment_meets_triangle(&e, &Tri::of(tris[near[y - segs.len()]].0, pts)),
        };
        meet.then_some(())
    });
    let Some(&(k, y, ())) = bad.first() else {
        return Ok(());
    };
    let (k, y) = (k as usize, y as usize);
    let what = if y < segs.len() {
        let [a, b] = segs[y];
        format!(
            "meets line segment {y} [{a}, {b}] ({:?} to {:?}) other than at a shared end",
            pts[a as usize], pts[b as usize]
        )
    } else {
        let (t, kind, i) = tris[near[y - segs.len()]];
        format!(
            "meets {kind} triangle {i} {t:?} ({:?}, {:?}, {:?}) other than at a shared vertex",
            pts[t[0] as usize], pts[t[1] as usize], pts[t[2] as usize]
        )
    };
    Err(segment_error(input, k, what))
}

/// Every segment lies inside the region. Segments joined through a vertex off the boundary lie
/// on one side together (none crosses the boundary), so one of each such group is tested.
fn check_inside(input: &RegionInput) -> Result<(), TetMeshError> {
    let pts = &input.vertices;
    let on_boundary = boundary_vertices(pts.len(), &input.boundary);
    let rays = Rays::new(pts, &input.boundary);
    for k in one_per_group(&input.lines, &on_boundary) {
        let [u, v] = input.lines[k].map(|v| &pts[v as usize]);
        match rays.segment_inside(u, v) {
            Some(true) => {}
            Some(false) => {
                return Err(segment_error(input, k, "lies outside the region".into()));
            }
            None => {
                return Err(segment_error(input, k, "lies on the boundary".into()));
            }
        }
    }
    Ok(())
}

/// Checks that `out.lines` holds, for each input segment, a chain of tet edges along it (see the
/// module doc).
pub(crate) fn verify_chains(input: &RegionInput, out: &TetMeshOutput) -> Result<(), TetMeshError> {
    let name = &input.name;
    if out.lines.len() != input.lines.len() {
        let msg = format!(
            "the mesh gives {} chains for the {} line segments",
            out.lines.len(),
            input.lines.len()
        );
        return Err(TetMeshError::new(name, msg, None));
    }
    let n_in = input.vertices.len();
    let mut used = vec![false; out.nodes.len()];
    let mut steps: Vec<([u32; 2], usize)> = Vec::new();
    for (k, chain) in out.lines.iter().enumerate() {
        let [u, v] = input.lines[k];
        let fail = |what: String| Err(segment_error(input, k, what));
        if chain.len() < 2 || chain[0] != u || chain[chain.len() - 1] != v {
            return fail(format!(
                "became the chain {chain:?}, not one from {u} to {v}"
            ));
        }
        let (a, b) = (input.vertices[u as usize], input.vertices[v as usize]);
        for &x in &chain[1..chain.len() - 1] {
            let i = x as usize;
            if i < n_in || i >= out.nodes.len() || used[i] {
                return fail(format!(
                    "has node {x} in its chain: not a new node of its own"
                ));
            }
            used[i] = true;
            if !on_segment(&a, &b, &out.nodes[i]) {
                let msg = format!("has chain node {x} at {:?} off the segment", out.nodes[i]);
                return fail(msg);
            }
        }
        let axis = main_axis(&a, &b);
        let rising = b[axis] > a[axis];
        for w in chain.windows(2) {
            let (p, q) = (out.nodes[w[0] as usize], out.nodes[w[1] as usize]);
            if q[axis] == p[axis] || (q[axis] > p[axis]) != rising {
                return fail(format!("has chain nodes {w:?} out of order"));
            }
            steps.push(([w[0].min(w[1]), w[0].max(w[1])], k));
        }
    }
    steps.sort_unstable();
    let mut found = vec![false; steps.len()];
    for t in &out.tets {
        for (i, j) in [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)] {
            let e = [t[i].min(t[j]), t[i].max(t[j])];
            let first = steps.partition_point(|s| s.0 < e);
            for f in found[first..].iter_mut().zip(&steps[first..]) {
                if f.1.0 != e {
                    break;
                }
                *f.0 = true;
            }
        }
    }
    if let Some(k) = found.iter().position(|f| !f) {
        let (e, s) = steps[k];
        return Err(segment_error(
            input,
            s,
            format!("has chain step {e:?} that is not an edge of the mesh"),
        ));
    }
    Ok(())
}
