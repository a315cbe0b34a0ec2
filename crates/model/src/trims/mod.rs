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
//!   is a patch none of whose vertices can be placed (it lies on `S`, or `S` does not cover its
//!   xy). Patches of `S` itself are never judged against `S` (a glob may select them).
//! * `discard = { containing = p }`: the patch on which `p` lies, exactly (on a triangle, by
//!   `orient3d` and `orient2d`) or within the support tolerance
//!   `Tolerances::support_distance_rel` × the box diagonal (a point typed in a recipe is rarely
//!   exactly on a triangle). A point on no patch, or on several (on the curve between two), is an
//!   error naming the nearest patches.
//! * `discard = { nearest = p }`: the patch at the smallest distance from `p`; ties go to the
//!   first patch name in byte order.
//! * `discard = { area_below = a }`: every patch whose area is below `a`.
//!
//! A trim that discards nothing is an error naming the trim (its index in recipe order, so the
//! caller can point at its `[[trim]]` header): its selector matches no patch still kept, its
//! point is on no patch, or its condition holds for every patch. A recipe line with no effect is
//! almost always a mistake (a renamed surface, a point in the wrong units).
//!
//! The function is pure; every decision is an exact predicate on input coordinates except the
//! distances and areas, which are measures and say so in the reasons they give.

mod near;
mod side;

pub use near::{on_triangle, triangle_distance};
pub use side::{Column, Verdict};

use geom::{BBox, Tolerances, TriMesh};
use serde::Serialize;
use std::collections::BTreeMap;

/// Which side of a surface a `keep` trim keeps.
#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
pub enum Side {
    /// Larger z (towards the surface's upward side).
    Above,
    Below,
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
        TrimAction::Keep { side, of } => {
            let s = if *side == Side::Above {
                "above"
            } else {
                "below"
            };
            format!("keep = {{ {s} = \"{of}\" }}")
        }
        TrimAction::DiscardContaining(p) => format!("discard = {{ containing = {} }}", pt(p)),
        TrimAction::DiscardNearest(p) => format!("discard = {{ nearest = {} }}", pt(p)),
        TrimAction::DiscardAreaBelow(a) => format!("discard = {{ area_below = {a} }}"),
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
                let column = columns.entry(name).or_insert_with(|| Column::new(mesh));
                let mut found = Vec::new();
                for &i in selected.iter().filter(|&&i| patches[i].surface != of) {
                    let here = place(&patches[i], column, of)
                        .map_err(|(m, at)| err(m, Some(patches[i].name), Some(at)))?;
                    if here != *side {
                        let word = if here == Side::Above {
                            "above"
                        } else {
                            "below"
                        };
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
fn place(p: &TrimPatch, column: &Column, of: &str) -> Result<Side, (String, [f64; 3])> {
    let (mut above, mut below) = (None, None);
    let (mut uncovered, mut folded) = (None, None);
    for v in &p.mesh.vertices {
        match column.locate(v) {
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
        (Some(a), Some(b)) => Err((
            format!(
                "patch `{}` lies on both sides of `{of}`: {} is above it and {} below; \
                 intersect `{}` with `{of}` in `[intersect]` so that it is split there",
                p.name,
                pt(&a),
                pt(&b),
                p.surface
            ),
            a,
        )),
        (Some(_), None) => Ok(Side::Above),
        (None, Some(_)) => Ok(Side::Below),
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
            let s = if *side == Side::Above {
                "above"
            } else {
                "below"
            };
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
