//! Trims: which patches of the split model to discard before regions are found.
//!
//! Patches are the pieces of each surface between curves and borders. A patch outside the box
//! (a vertex strictly beyond it, [`inside_box`](crate::patches::inside_box)) is always discarded; then the recipe's
//! `[[trim]]` entries run in recipe order, each looking at the patches still kept whose surface
//! its `surface` selector matches. A patch with free borders inside the box is never discarded
//! for that reason: it dangles (a fault tip), and region finding decides whether it may.
//!
//! What each action decides, and how:
//!
//! * `keep = { below = "S" }` / `{ above = "S" }`: "above" means larger z. Every vertex of the
//!   patch is located against the split mesh of `S` by an exact vertical cast (`side`);
//!   vertices that are vertices of `S` (the curve points where the patch meets `S`, shared bit
//!   for bit by splitting) or lie on it say nothing, nor do vertices whose vertical misses `S` or
//!   crosses a fold of it an even number of times. The remaining vertices must all agree: a
//!   patch found on both sides of `S` is an error (the pair is probably not intersected), and so
//!   is a patch none of whose vertices can be placed (`S` does not cover its xy). A patch all of
//!   whose vertices are on `S` (a sliver between two curves where it meets `S`) is placed by the
//!   centroids of its triangles that `S` does not have; one made only of triangles of `S` (a
//!   face the two surfaces share) is discarded whichever side is kept: `S`'s own patch is there.
//!   Patches of `S` itself are never judged against `S` (a glob may select them).
//! * `keep = { inside = "S" }` / `{ outside = "S" }`: `S` must be closed (every edge of its
//!   split mesh has an even number of triangles, points matched by coordinates), else the trim
//!   fails naming a point of its border. A vertex is inside when the column above it crosses
//!   `S` an odd number of times (the same exact cast); vertices on `S` say nothing, the others
//!   must agree, and a patch all on `S` is placed or discarded as for `above` and `below` (two
//!   bodies modelled sharing a face: two coincident patches would leave a region of no
//!   thickness).
//! * `discard = { containing = p }`: the patch on which `p` lies, exactly (on a triangle, by
//!   `orient3d` and `orient2d`) or within the support tolerance
//!   `Tolerances::support_distance_rel` × the box diagonal (a point typed in a recipe is rarely
//!   exactly on a triangle). A point on no patch, or on several (on the curve between two), is an
//!   error naming the nearest patches.
//! * `discard = { nearest = p }`: the patch at the smallest distance from `p`; ties go to the
//!   first patch name in byte order.
//! * `discard = { area_below = a }`: every patch whose area is below `a`.
//! * `discard = { within = d }`: every patch that hugs another surface (`hug`): each of its
//!   vertices and triangle centroids within `d` of that one surface.
//!
//! A trim that discards nothing is an error naming the trim (its index in recipe order, so the
//! caller can point at its `[[trim]]` header): its selector matches no patch still kept, its
//! point is on no patch, or its condition holds for every patch. A recipe line with no effect is
//! almost always a mistake (a renamed surface, a point in the wrong units).
//!
//! The function is pure; every decision is an exact predicate on input coordinates except the
//! distances and areas, which are measures and say so in the reasons they give.

mod hug;
mod near;
mod side;

pub use near::{on_triangle, triangle_distance};
pub use side::{Column, Enclosure, Verdict, free_border};

use geom::{BBox, Tolerances, TriMesh};
use serde::Serialize;
use std::collections::BTreeMap;

/// Which side of a surface a `keep` trim keeps.
#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
pub enum Side {
    /// Larger z (towards the surface's upward side).
    Above,
    Below,
    /// Enclosed by the surface, which must be closed.
    Inside,
    Outside,
}

impl Side {
    /// The recipe's word for it.
    pub fn word(self) -> &'static str {
        match self {
            Side::Above => "above",
            Side::Below => "below",
            Side::Inside => "inside",
            Side::Outside => "outside",
        }
    }

    /// Whether it is told by enclosure rather than by height.
    fn encloses(self) -> bool {
        matches!(self, Side::Inside | Side::Outside)
    }
}

/// What a trim does to the patches of the surfaces it selects.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub enum TrimAction {
    /// Keep the patches on `side` of surface `of`; discard the others.
    Keep { side: Side, of: String },
    /// Discard the patch containing this point (on the support, up to the support tolerance).
    DiscardContaining([f64; 3]),
    /// Discard the patch nearest to this point.
    DiscardNearest([f64; 3]),
    /// Discard every patch whose area is below this value (> 0, model units squared).
    DiscardAreaBelow(f64),
    /// Discard every patch that lies within this distance of one other surface all over (> 0).
    DiscardWithin(f64),
}

/// One trim, applied in order after splitting (outside the box is always discarded).
#[derive(Clone, Debug, PartialEq)]
pub struct TrimSpec {
    /// The surface selector as the recipe writes it (a name or a glob), for messages.
    pub selector: String,
    /// The surfaces it selects, resolved by the caller (the stage knows no glob syntax).
    pub surfaces: Vec<String>,
    pub action: TrimAction,
}

impl TrimSpec {
    fn selects(&self, surface: &str) -> bool {
        self.surfaces.iter().any(|s| s == surface)
    }
}

/// One patch as the trims see it.
#[derive(Copy, Clone, Debug)]
pub struct TrimPatch<'a> {
    /// Stable name `surface#k`.
    pub name: &'a str,
    /// The surface the patch belongs to (matched by the trims' selectors).
    pub surface: &'a str,
    pub mesh: &'a TriMesh,
}

/// One discarded patch.
#[derive(Clone, Debug, PartialEq)]
pub struct Discard {
    /// Index into the patches given to [`apply_trims`].
    pub patch: usize,
    /// The trim that discarded it (index in recipe order); `None` for outside the box.
    pub trim: Option<usize>,
    /// Why, in recipe terms.
    pub reason: String,
}

/// What [`apply_trims`] decided.
#[derive(Clone, Debug, PartialEq)]
pub struct TrimOutcome {
    /// For each patch given, whether it stays in the model.
    pub keep: Vec<bool>,
    /// The discarded patches, in the order they were discarded (box first, then trim by trim,
    /// each in patch order).
    pub discarded: Vec<Discard>,
}

/// Why trimming failed: the trim (index in recipe order), and the patch and point concerned.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{message}")]
pub struct TrimError {
    /// `None` for a malformed patch (found before any trim runs).
    pub trim: Option<usize>,
    pub patch: Option<String>,
    pub at: Option<[f64; 3]>,
    pub message: String,
}

/// A point as a recipe writes it.
fn pt(p: &[f64; 3]) -> String {
    format!("[{}, {}, {}]", p[0], p[1], p[2])
}

/// The trim as written in the recipe: `[[trim]] #k (surface = "F1", keep = { below = "H1" })`.
pub fn describe(index: usize, t: &TrimSpec) -> String {
    let action = match &t.action {
        TrimAction::Keep { side, of } => format!("keep = {{ {} = \"{of}\" }}", side.word()),
        TrimAction::DiscardContaining(p) => format!("discard = {{ containing = {} }}", pt(p)),
        TrimAction::DiscardNearest(p) => format!("discard = {{ nearest = {} }}", pt(p)),
        TrimAction::DiscardAreaBelow(a) => format!("discard = {{ area_below = {a} }}"),
        TrimAction::DiscardWithin(d) => format!("discard = {{ within = {d} }}"),
    };
    format!(
        "[[trim]] #{} (surface = \"{}\", {action})",
        index + 1,
        t.selector
    )
}

/// Applies the box and then `trims` in order to `patches`.
///
/// `surfaces` are the split surfaces by name (the meshes `split_model` returns, so that curve
/// points are shared bit for bit): `keep` looks its `of` surface up there. `bbox` is the model's
/// box; its diagonal times `tol.support_distance_rel` is the tolerance of `containing`.
pub fn apply_trims(
    patches: &[TrimPatch],
    surfaces: &[(&str, &TriMesh)],
    trims: &[TrimSpec],
    bbox: &BBox,
    tol: &Tolerances,
) -> Result<TrimOutcome, TrimError> {
    for p in patches {
        check_patch(p)?;
    }
    let mut out = TrimOutcome {
        keep: vec![true; patches.len()],
        discarded: Vec::new(),
    };
    for (i, p) in patches.iter().enumerate() {
        if !inside(p.mesh, bbox) {
            out.keep[i] = false;
            out.discarded.push(Discard {
                patch: i,
                trim: None,
                reason: "outside the box".into(),
            });
        }
    }
    let diagonal = {
        let e = bbox.extent();
        (e[0] * e[0] + e[1] * e[1] + e[2] * e[2]).sqrt()
    };
    let support = tol.support_distance_rel * diagonal;
    let mut columns: BTreeMap<&str, Column> = BTreeMap::new();
    for (k, t) in trims.iter().enumerate() {
        let err = |message: String, patch: Option<&str>, at: Option<[f64; 3]>| TrimError {
            trim: Some(k),
            patch: patch.map(str::to_string),
            at,
            message: format!("{}: {message}", describe(k, t)),
        };
        let selected: Vec<usize> = (0..patches.len())
            .filter(|&i| out.keep[i] && t.selects(patches[i].surface))
            .collect();
        if selected.is_empty() {
            return Err(err(
                format!(
                    "no patch of a surface matching `{}` is left to trim",
                    t.selector
                ),
                None,
                None,
            ));
        }
        let found: Vec<(usize, String)> = match &t.action {
            TrimAction::Keep { side, of } => {
                let Some(&(name, mesh)) = surfaces.iter().find(|(n, _)| *n == of.as_str()) else {
                    return Err(err(format!("the model has no surface `{of}`"), None, None));
                };
                if side.encloses()
                    && let Some(at) = free_border(mesh)
                {
                    return Err(err(
                        format!(
                            "`{of}` is not closed (its border runs through {}), so nothing is \
                             inside or outside it; use `above` or `below`, or close it in the data",
                            pt(&at)
                        ),
                        None,
                        Some(at),
                    ));
                }
                let column = columns.entry(name).or_insert_with(|| Column::new(mesh));
                let mut found = Vec::new();
                for &i in selected.iter().filter(|&&i| patches[i].surface != of) {
                    let here = if side.encloses() {
                        enclosed(&patches[i], column, of)
                    } else {
                        place(&patches[i], column, of)
                    };
                    let here = here.map_err(|(m, at)| err(m, Some(patches[i].name), Some(at)))?;
                    let word = here.map_or("a face shared with", Side::word);
                    if here != Some(*side) {
                        found.push((i, format!("{}: {word} {of}", describe(k, t))));
                    }
                }
                found
            }
            TrimAction::DiscardContaining(p) => {
                let i = containing(patches, &selected, p, support)
                    .map_err(|m| err(m, None, Some(*p)))?;
                vec![(i, format!("{}: contains {}", describe(k, t), pt(p)))]
            }
            TrimAction::DiscardNearest(p) => {
                let (i, d) = nearest(patches, &selected, p);
                vec![(
                    i,
                    format!("{}: nearest to {} (distance {d})", describe(k, t), pt(p)),
                )]
            }
            TrimAction::DiscardAreaBelow(a) => selected
                .iter()
                .filter_map(|&i| {
                    let area = patches[i].mesh.area();
                    (area < *a).then(|| (i, format!("{}: area {area}", describe(k, t))))
                })
                .collect(),
            TrimAction::DiscardWithin(d) => hug::hugging(patches, &out.keep, &selected, *d)
                .into_iter()
                .map(|(i, other)| (i, format!("{}: within {d} of {other}", describe(k, t))))
                .collect(),
        };
        if found.is_empty() {
            return Err(err(nothing(patches, &selected, &t.action), None, None));
        }
        for (i, reason) in found {
            out.keep[i] = false;
            out.discarded.push(Discard {
                patch: i,
                trim: Some(k),
                reason,
            });
        }
    }
    Ok(out)
}

/// A patch whose triangles point at missing vertices, or that has none, is malformed.
fn check_patch(p: &TrimPatch) -> Result<(), TrimError> {
    let nv = p.mesh.vertices.len();
    let bad = |message: String| TrimError {
        trim: None,
        patch: Some(p.name.to_string()),
        at: None,
        message,
    };
    if p.mesh.triangles.is_empty() {
        return Err(bad(format!("patch `{}` has no triangles", p.name)));
    }
    for (t, tri) in p.mesh.triangles.iter().enumerate() {
        if let Some(v) = tri.iter().find(|&&v| v as usize >= nv) {
            return Err(bad(format!(
                "patch `{}`: triangle {t} refers to vertex {v}, but the patch has {nv} vertices",
                p.name
            )));
        }
    }
    Ok(())
}

/// The rule of [`inside_box`](crate::patches::inside_box) on a bare mesh: every vertex within the closed box
/// (exact coordinate comparisons; NaN is outside).
fn inside(mesh: &TriMesh, bbox: &BBox) -> bool {
    mesh.vertices
        .iter()
        .all(|p| (0..3).all(|k| bbox.min[k] <= p[k] && p[k] <= bbox.max[k]))
}

/// The side of `of` the patch lies on, or why it cannot be told (message and a point).
fn place(p: &TrimPatch, column: &Column, of: &str) -> Result<Option<Side>, (String, [f64; 3])> {
    let mut judged: Vec<([f64; 3], Verdict)> = (p.mesh.vertices.iter())
        .map(|v| (*v, column.locate(v)))
        .collect();
    if judged.iter().all(|(_, j)| *j == Verdict::On) {
        let Some(own) = own_centroids(p, column) else {
            return Ok(None);
        };
        judged = own.into_iter().map(|c| (c, column.locate(&c))).collect();
    }
    let (mut above, mut below) = (None, None);
    let (mut uncovered, mut folded) = (None, None);
    for (v, verdict) in &judged {
        match *verdict {
            Verdict::Above => {
                above.get_or_insert(*v);
            }
            Verdict::Below => {
                below.get_or_insert(*v);
            }
            Verdict::On => {}
            Verdict::Uncovered => {
                uncovered.get_or_insert(*v);
            }
            Verdict::Folded(n) => {
                folded.get_or_insert((*v, n));
            }
        }
    }
    match (above, below) {
        (Some(a), Some(b)) => Err(both_sides(
            p,
            of,
            "on both sides of",
            [("above", a), ("below", b)],
        )),
        (Some(_), None) => Ok(Some(Side::Above)),
        (None, Some(_)) => Ok(Some(Side::Below)),
        (None, None) => Err(match (folded, uncovered) {
            (Some((v, n)), _) => (
                format!(
                    "cannot tell which side of `{of}` patch `{}` lies on: the vertical through {} \
                     crosses `{of}` {n} times (a fold), so above and below are undefined there",
                    p.name,
                    pt(&v)
                ),
                v,
            ),
            (None, Some(v)) => (
                format!(
                    "cannot tell which side of `{of}` patch `{}` lies on: `{of}` does not extend \
                     over (x, y) = ({}, {}) of its vertex {}",
                    p.name,
                    v[0],
                    v[1],
                    pt(&v)
                ),
                v,
            ),
            (None, None) => {
                let v = p.mesh.vertices.first().copied().unwrap_or([0.0; 3]);
                (
                    format!(
                        "cannot tell which side of `{of}` patch `{}` lies on: every vertex of it \
                         is on `{of}` (e.g. {})",
                        p.name,
                        pt(&v)
                    ),
                    v,
                )
            }
        }),
    }
}

/// The centroid of a triangle given by its corners.
fn centroid(c: [&[f64; 3]; 3]) -> [f64; 3] {
    [0, 1, 2].map(|k| (c[0][k] + c[1][k] + c[2][k]) / 3.0)
}

/// For a patch all of whose vertices lie on the surface of `column`: the centroids of its
/// triangles that the surface does not have, which tell its side; `None` when it has none (a
/// face the two surfaces share).
fn own_centroids(p: &TrimPatch, column: &Column) -> Option<Vec<[f64; 3]>> {
    let own: Vec<[f64; 3]> = (0..p.mesh.triangles.len())
        .map(|t| p.mesh.corners(t))
        .filter(|&c| !column.has_triangle(c))
        .map(centroid)
        .collect();
    (!own.is_empty()).then_some(own)
}

/// The error of a patch found on two sides of `of`: `how` it lies, and a vertex on each side.
fn both_sides(
    p: &TrimPatch,
    of: &str,
    how: &str,
    [(one, a), (other, b)]: [(&str, [f64; 3]); 2],
) -> (String, [f64; 3]) {
    (
        format!(
            "patch `{}` lies {how} `{of}`: {} is {one} it and {} {other}; intersect `{}` with \
             `{of}` in `[intersect]` so that it is split there",
            p.name,
            pt(&a),
            pt(&b),
            p.surface
        ),
        a,
    )
}

/// Whether the closed surface `of` encloses the patch (`None`: the patch is a face it shares
/// with `of`), or why it cannot be told (message and a point): its vertices on `of` say nothing,
/// the others must agree; a patch all of whose vertices are on `of` is judged by the centroids
/// of its triangles that are not triangles of `of`.
fn enclosed(p: &TrimPatch, column: &Column, of: &str) -> Result<Option<Side>, (String, [f64; 3])> {
    let judge = |points: &mut dyn Iterator<Item = [f64; 3]>| {
        let (mut inside, mut outside) = (None, None);
        for v in points {
            match column.enclosure(&v) {
                Enclosure::Inside => inside = inside.or(Some(v)),
                Enclosure::Outside => outside = outside.or(Some(v)),
                Enclosure::On => {}
            }
        }
        (inside, outside)
    };
    let (mut inside, mut outside) = judge(&mut p.mesh.vertices.iter().copied());
    if inside.is_none() && outside.is_none() {
        let Some(own) = own_centroids(p, column) else {
            return Ok(None);
        };
        (inside, outside) = judge(&mut own.into_iter());
    }
    match (inside, outside) {
        (Some(a), Some(b)) => Err(both_sides(
            p,
            of,
            "both inside and outside",
            [("inside", a), ("outside", b)],
        )),
        (Some(_), None) => Ok(Some(Side::Inside)),
        (None, Some(_)) => Ok(Some(Side::Outside)),
        (None, None) => {
            let v = p.mesh.vertices.first().copied().unwrap_or([0.0; 3]);
            Err((
                format!(
                    "cannot tell whether `{of}` encloses patch `{}`: every vertex of it is on \
                     `{of}` (e.g. {})",
                    p.name,
                    pt(&v)
                ),
                v,
            ))
        }
    }
}

/// Selected patches by increasing distance to `p` (exact hits first at distance 0), ties by name.
fn by_distance(
    patches: &[TrimPatch],
    selected: &[usize],
    p: &[f64; 3],
) -> Vec<(usize, near::Nearness)> {
    let mut v: Vec<(usize, near::Nearness)> = selected
        .iter()
        .map(|&i| (i, near::nearness(p, patches[i].mesh)))
        .collect();
    v.sort_by(|a, b| {
        b.1.exact
            .cmp(&a.1.exact)
            .then(a.1.distance.total_cmp(&b.1.distance))
            .then_with(|| patches[a.0].name.cmp(patches[b.0].name))
    });
    v
}

fn containing(
    patches: &[TrimPatch],
    selected: &[usize],
    p: &[f64; 3],
    support: f64,
) -> Result<usize, String> {
    let near = by_distance(patches, selected, p);
    let exact: Vec<usize> = near.iter().filter(|n| n.1.exact).map(|n| n.0).collect();
    let hits: Vec<usize> = if exact.is_empty() {
        near.iter()
            .filter(|n| n.1.distance <= support)
            .map(|n| n.0)
            .collect()
    } else {
        exact
    };
    let names = |v: &[usize]| {
        v.iter()
            .map(|&i| format!("`{}`", patches[i].name))
            .collect::<Vec<_>>()
            .join(", ")
    };
    match hits.as_slice() {
        [i] => Ok(*i),
        [] => {
            let (i, n) = near[0];
            Err(format!(
                "{} is on no patch (within {support} of one); the nearest is `{}` at distance {}",
                pt(p),
                patches[i].name,
                n.distance
            ))
        }
        many => Err(format!(
            "{} is on {} patches ({}): it lies on the curve between them; move it inside the \
             one to discard",
            pt(p),
            many.len(),
            names(many)
        )),
    }
}

fn nearest(patches: &[TrimPatch], selected: &[usize], p: &[f64; 3]) -> (usize, f64) {
    let near = by_distance(patches, selected, p);
    let (i, n) = near[0];
    (i, n.distance)
}

/// Why a trim that found patches discarded none of them.
fn nothing(patches: &[TrimPatch], selected: &[usize], action: &TrimAction) -> String {
    match action {
        TrimAction::Keep { side, of } => {
            let judged = selected
                .iter()
                .filter(|&&i| patches[i].surface != of.as_str())
                .count();
            let s = side.word();
            if judged == 0 {
                format!("it selects only patches of `{of}` itself")
            } else {
                format!(
                    "all {judged} patches it selects are already {s} `{of}`: it discards nothing"
                )
            }
        }
        TrimAction::DiscardAreaBelow(a) => {
            let smallest = selected
                .iter()
                .map(|&i| (patches[i].mesh.area(), patches[i].name))
                .min_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(y.1)));
            match smallest {
                Some((area, name)) => {
                    format!("no patch has an area below {a}: the smallest is `{name}` with {area}")
                }
                None => format!("no patch has an area below {a}"),
            }
        }
        TrimAction::DiscardWithin(d) => {
            format!("no patch it selects lies within {d} of another surface all over")
        }
        // `containing` and `nearest` either find a patch or fail with their own message.
        _ => "it discards nothing".into(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_box() -> BBox {
        BBox {
            min: [-10.0; 3],
            max: [10.0; 3],
        }
    }

    /// A unit right triangle at height `z`, shifted by `dx` in x.
    fn tri(dx: f64, z: f64) -> TriMesh {
        TriMesh::new(
            vec![[dx, 0.0, z], [dx + 1.0, 0.0, z], [dx, 1.0, z]],
            vec![[0, 1, 2]],
        )
    }

    fn nearest(p: [f64; 3]) -> TrimSpec {
        TrimSpec {
            selector: "*".into(),
            surfaces: vec!["a".into(), "b".into(), "c".into()],
            action: TrimAction::DiscardNearest(p),
        }
    }

    fn keep(side: Side) -> TrimSpec {
        TrimSpec {
            selector: "p".into(),
            surfaces: vec!["p".into()],
            action: TrimAction::Keep {
                side,
                of: "s".into(),
            },
        }
    }

    /// Trims the patches `p#k` (the meshes given) against `s` with `keep(side)`.
    fn trim_against(s: &TriMesh, meshes: &[TriMesh], side: Side) -> Result<TrimOutcome, TrimError> {
        let names: Vec<String> = (1..=meshes.len()).map(|k| format!("p#{k}")).collect();
        let patches: Vec<TrimPatch> = (meshes.iter().zip(&names))
            .map(|(mesh, name)| TrimPatch {
                name,
                surface: "p",
                mesh,
            })
            .collect();
        let box_ = unit_box();
        apply_trims(
            &patches,
            &[("s", s)],
            &[keep(side)],
            &box_,
            &Tolerances::default(),
        )
    }

    #[test]
    fn keeping_outside_or_inside_a_closed_surface_discards_the_other_side_and_its_own_faces() {
        let (v, t) = test_support::shapes::cuboid([0.0; 3], [2.0; 3]);
        let s = TriMesh::new(v, t);
        let inside = TriMesh::new(
            vec![[0.5, 0.5, 1.0], [1.5, 0.5, 1.2], [0.5, 1.5, 0.8]],
            vec![[0, 1, 2]],
        );
        // Outside, with a vertex on `s` (a corner of it), which says nothing.
        let outside = TriMesh::new(
            vec![[2.0, 2.0, 2.0], [3.0, 2.0, 2.0], [3.0, 3.0, 1.0]],
            vec![[0, 1, 2]],
        );
        let shared = TriMesh::new(s.vertices.clone(), vec![s.triangles[0]]);
        let out = trim_against(
            &s,
            &[inside.clone(), outside.clone(), shared.clone()],
            Side::Outside,
        )
        .expect("trims");
        assert_eq!(out.keep, [false, true, false]);
        assert!(
            out.discarded[0].reason.ends_with(": inside s"),
            "{:?}",
            out.discarded
        );
        assert!(out.discarded[1].reason.ends_with(": a face shared with s"));
        let out = trim_against(&s, &[inside, outside, shared], Side::Inside).expect("trims");
        assert_eq!(out.keep, [true, false, false]);
    }

    #[test]
    fn a_patch_with_every_vertex_on_the_surface_is_placed_by_its_own_triangles() {
        // `s` is a low pyramid over [0, 2]²; the patch is a flat triangle on three of its base
        // corners, every vertex on `s`, its inside under it.
        let s = TriMesh::new(
            vec![
                [0.0, 0.0, 0.0],
                [2.0, 0.0, 0.0],
                [2.0, 2.0, 0.0],
                [0.0, 2.0, 0.0],
                [1.0, 1.0, 1.0],
            ],
            vec![[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]],
        );
        let under = TriMesh::new(s.vertices[..3].to_vec(), vec![[0, 1, 2]]);
        let shared = TriMesh::new(s.vertices.clone(), vec![s.triangles[1]]);
        let out = trim_against(&s, &[under.clone(), shared.clone()], Side::Above).expect("trims");
        assert_eq!(out.keep, [false, false]);
        assert!(
            out.discarded[0].reason.ends_with(": below s"),
            "{:?}",
            out.discarded
        );
        assert!(out.discarded[1].reason.ends_with(": a face shared with s"));
        let out = trim_against(&s, &[under, shared], Side::Below).expect("trims");
        assert_eq!(out.keep, [true, false]);
    }

    #[test]
    fn a_patch_hugging_another_surface_is_discarded_only_where_that_surface_closes_its_border() {
        // `s`: a square of four triangles round its centre, at z = 0.
        let corners = [
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [2.0, 2.0, 0.0],
            [0.0, 2.0, 0.0],
        ];
        let fan = |centre: [f64; 3]| {
            let mut v = corners.to_vec();
            v.push(centre);
            TriMesh::new(v, vec![[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]])
        };
        let s = fan([1.0, 1.0, 0.0]);
        // A copy of it 5 cm off at the centre, one 50 cm off, and a sliver 5 cm beside its edge
        // whose border leaves `s`.
        let near = fan([1.0, 1.0, 0.05]);
        let far = fan([1.0, 1.0, 0.5]);
        let beside = TriMesh::new(
            vec![[0.2, 0.0, 0.0], [1.8, 0.0, 0.0], [1.0, -0.05, 0.0]],
            vec![[0, 2, 1]],
        );
        let names = ["p#1", "p#2", "p#3", "s#1"];
        let patches: Vec<TrimPatch> = [&near, &far, &beside, &s]
            .iter()
            .zip(names)
            .map(|(mesh, name)| TrimPatch {
                name,
                surface: &name[..1],
                mesh,
            })
            .collect();
        let within = TrimSpec {
            selector: "p".into(),
            surfaces: vec!["p".into()],
            action: TrimAction::DiscardWithin(0.1),
        };
        let (box_, tol) = (unit_box(), Tolerances::default());
        let out = apply_trims(
            &patches,
            &[("s", &s)],
            std::slice::from_ref(&within),
            &box_,
            &tol,
        )
        .expect("trims");
        assert_eq!(out.keep, [false, true, true, true]);
        assert!(
            out.discarded[0].reason.ends_with(": within 0.1 of s"),
            "{:?}",
            out.discarded
        );
        // A surface already trimmed away closes nothing: with `s` gone first, nothing hugs.
        let gone = TrimSpec {
            selector: "s".into(),
            surfaces: vec!["s".into()],
            action: TrimAction::DiscardAreaBelow(100.0),
        };
        let trims = [gone, within.clone()];
        let e = apply_trims(&patches, &[("s", &s)], &trims, &box_, &tol).unwrap_err();
        assert_eq!(e.trim, Some(1), "{}", e.message);
        // Nothing hugs at 1 mm: the trim is an error saying so.
        let tight = TrimSpec {
            action: TrimAction::DiscardWithin(0.001),
            ..within
        };
        let e = apply_trims(&patches, &[("s", &s)], &[tight], &box_, &tol).unwrap_err();
        assert!(
            e.message.contains("within 0.001 of another surface"),
            "{}",
            e.message
        );
    }

    #[test]
    fn inside_a_surface_that_is_not_closed_or_across_it_is_an_error_with_a_point() {
        let (v, mut t) = test_support::shapes::cuboid([0.0; 3], [2.0; 3]);
        t.pop();
        let open = TriMesh::new(v.clone(), t);
        let p = tri(0.5, 1.0);
        let e = trim_against(&open, &[p], Side::Outside).unwrap_err();
        assert!(e.message.contains("`s` is not closed"), "{}", e.message);
        assert!(e.at.is_some());
        let (_, t) = test_support::shapes::cuboid([0.0; 3], [2.0; 3]);
        let closed = TriMesh::new(v, t);
        let across = tri(1.5, 1.0);
        let e = trim_against(&closed, &[across], Side::Inside).unwrap_err();
        assert!(
            e.message.contains("lies both inside and outside `s`"),
            "{}",
            e.message
        );
        assert_eq!(e.patch.as_deref(), Some("p#1"));
    }

    #[test]
    fn a_patch_pointing_at_a_missing_vertex_is_an_error_naming_it_not_a_panic() {
        let bad = TriMesh::new(vec![[0.0; 3]], vec![[0, 1, 2]]);
        let p = [TrimPatch {
            name: "s#1",
            surface: "s",
            mesh: &bad,
        }];
        let e = apply_trims(
            &p,
            &[],
            &[nearest([0.0; 3])],
            &unit_box(),
            &Tolerances::default(),
        )
        .unwrap_err();
        assert_eq!(e.trim, None);
        assert_eq!(e.patch.as_deref(), Some("s#1"));
        assert!(e.message.contains("refers to vertex 1"), "{}", e.message);
    }

    #[test]
    fn two_patches_at_the_same_distance_go_by_name_and_one_outside_the_box_is_not_a_candidate() {
        let (a, b, far) = (tri(-2.0, 0.0), tri(1.0, 0.0), tri(0.0, 20.0));
        // The origin is exactly 1 from the corner (1, 0, 0) of `b#1` and (-1, 0, 0) of `a#1`.
        let p = [
            TrimPatch {
                name: "b#1",
                surface: "b",
                mesh: &b,
            },
            TrimPatch {
                name: "a#1",
                surface: "a",
                mesh: &a,
            },
            TrimPatch {
                name: "c#1",
                surface: "c",
                mesh: &far,
            },
        ];
        let out = apply_trims(
            &p,
            &[],
            &[nearest([0.0, 0.0, 0.0])],
            &unit_box(),
            &Tolerances::default(),
        )
        .expect("trims");
        assert_eq!(out.keep, vec![true, false, false]);
        assert_eq!(out.discarded[0].reason, "outside the box");
        assert_eq!(
            out.discarded[1].patch, 1,
            "a#1 before b#1 at equal distance 1"
        );
    }
}
