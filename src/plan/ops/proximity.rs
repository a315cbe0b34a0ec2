//! Where the model's curves come closer to each other than their mesh can resolve: two strands
//! of one fault whose free edges run a few metres apart, a curve folding back on itself, two
//! curves meeting at a sliver of an angle. The tets between such curves span a gap far thinner
//! than their edges and come out flat, whatever the mesher does; the build says where, so the
//! user can refine there or mend the data (or says that it refined there, when the recipe asks
//! it to: `close_refine`). When a surface or tet mesh then fails within the curves' mesh size of
//! such a place, the build puts the failure down to it, and names the places on what failed for
//! the command line to refine (`cli::close_places`). Several places share one advice, said once.
//!
//! Two points of the curves are *close* when they are nearer than [`FRACTION`] of the finer of
//! the two curves' mesh sizes, and *unexplained* when nothing in the model's layout makes them
//! so: along one curve, the arc between them is long against their distance (a straight run of
//! short segments is not a fold); on two curves meeting at a vertex, the two points are far from
//! it against their distance (they meet at more than [`MIN_ANGLE_DEG`]). Distances are measures,
//! not decisions: nothing in the mesh depends on them.

use super::ModelData;
use super::sizes;
use crate::recipe::Recipe;
use geom::BBox;
use geom::broad_phase::overlapping_pairs;
use geom::predicates::{dist, dot, polyline_length, sub};
use sizes::short;
use std::collections::{BTreeMap, BTreeSet};

/// Curves nearer than this share of their mesh size are warned about (the tets between them
/// have dihedral angles of about this many radians).
pub const FRACTION: f64 = 0.1;
/// Curves meeting at a vertex at less than this angle are close near it.
pub const MIN_ANGLE_DEG: f64 = 10.0;
/// At most this many curves are named per place; the rest are counted.
const NAMES_PER_PLACE: usize = 4;
/// At most this many places are named; the rest are counted.
const MAX_NAMED: usize = 8;

/// One segment of a curve: the curve, the arc length at its start, its ends.
struct Segment {
    curve: usize,
    arc: f64,
    ends: [[f64; 3]; 2],
}

/// An unexplained approach of two curves: how near, the midpoint of the two nearest points,
/// the finer of the two curves' mesh sizes, and the two segments that approach.
#[derive(Clone, Debug)]
pub(super) struct Approach {
    pub distance: f64,
    pub at: [f64; 3],
    pub size: f64,
    pub segments: [[[f64; 3]; 2]; 2],
}

/// One sentence per place where curves come unexplainedly close, closest first, at most
/// eight and a count of the rest.
pub fn close_curve_warnings(recipe: &Recipe, model: &ModelData) -> Vec<String> {
    let found = approaches(recipe, model);
    let refined = super::close_refine::refined_curves(recipe, model, &found);
    let mut closest: BTreeMap<(usize, usize), Approach> = BTreeMap::new();
    for (c, d, a) in found {
        let best = closest.entry((c, d)).or_insert_with(|| a.clone());
        if a.distance < best.distance {
            *best = a;
        }
    }
    let mut pairs: Vec<((usize, usize), Approach)> = closest.into_iter().collect();
    pairs.sort_by(|x, y| x.1.distance.total_cmp(&y.1.distance).then(x.0.cmp(&y.0)));
    let sites = sites(pairs);
    let named = &sites[..sites.len().min(MAX_NAMED)];
    // Several places left as they are share one advice, told once after them.
    let unrefined = named.iter().filter(|s| !refined[s.curves[0]]).count();
    let brief = unrefined > 1;
    let mut out: Vec<String> = (named.iter())
        .map(|site| sentence(recipe, model, site, refined[site.curves[0]], brief))
        .collect();
    if sites.len() > MAX_NAMED {
        out.push(format!(
            "curves come as close at {} more places (the closest are named above)",
            sites.len() - MAX_NAMED
        ));
    }
    if brief {
        out.push(
            "where curves come that close, mend the surfaces in the data (join or part them), or \
             refine there with the line each warning gives, or everywhere with \
             `refine_close_curves = true` in `[mesh]` (finer and slower, the more so the longer \
             the curves run close); a mesh that fails at such a place is refined there without \
             it"
            .to_string(),
        );
    }
    out
}

/// For meshes that failed at `places`: for each, the unexplained approach of two curves within
/// their mesh size of it, told as the likely cause (the elements between such curves are flat,
/// and a mesher stalls or folds among them); `None` where no curves come close. The model's
/// approaches are found once for all the places.
pub fn close_curves_near(
    recipe: &Recipe,
    model: &ModelData,
    places: &[[f64; 3]],
) -> Vec<Option<String>> {
    let found = approaches(recipe, model);
    let refined = super::close_refine::refined_curves(recipe, model, &found);
    (places.iter())
        .map(|&at| cause_sentence(recipe, model, &found, &refined, at))
        .collect()
}

/// A place where curves come close on what a failed mesh meshed, which the recipe does not
/// refine yet: one of its curves (naming it in `refine_close_curves` refines the place), the
/// other curve of the closest approach, the gap there and where, the curves' mesh size, and how
/// long the place's curves run close.
#[derive(Clone, Debug, PartialEq)]
pub struct UnrefinedPlace {
    pub curve: String,
    pub other: String,
    pub gap: f64,
    pub at: [f64; 3],
    pub size: f64,
    pub length: f64,
}

/// For meshes that failed (each the node's name, `tet_mesh:<region>` or
/// `surface_mesh:<patch>`, and where it failed): the places where curves come close that the
/// recipe does not refine yet among the curves bounding what failed, each place once over all
/// failures. Per failure, the place the failure is put down to ([`close_curves_near`]) first,
/// then the others by their gap, closest first: a mesh that failed at one such place tends to
/// fail at the next once that one is refined.
pub fn unrefined_places_near(
    recipe: &Recipe,
    model: &ModelData,
    failures: &[(&str, [f64; 3])],
) -> Vec<Vec<UnrefinedPlace>> {
    let found = approaches(recipe, model);
    let refined = super::close_refine::refined_curves(recipe, model, &found);
    let curves = &model.topology.curves;
    let place_of = super::close_refine::places(curves.len(), &found);
    // How long each place's curves run close: its approaching segments, one side of each
    // approach, each segment once (a segment approaches several across from it).
    let mut sides: BTreeMap<usize, BTreeSet<[[u64; 3]; 2]>> = BTreeMap::new();
    for (c, _, a) in &found {
        let side = a.segments[0].map(|p| p.map(f64::to_bits));
        sides.entry(place_of[*c]).or_default().insert(side);
    }
    let length = |place: usize| -> f64 {
        (sides.get(&place).into_iter().flatten())
            .map(|s| dist(&s[0].map(f64::from_bits), &s[1].map(f64::from_bits)))
            .sum()
    };
    let mut taken = BTreeSet::new();
    let mut out = Vec::with_capacity(failures.len());
    for &(node, at) in failures {
        let bounding = bounding_curves(model, node);
        let nearest = nearest_within_size(&found, at).map(|(f, _)| (f.0, f.1));
        let mut mine: Vec<&(usize, usize, Approach)> = (found.iter())
            .filter(|(c, d, _)| !refined[*c] && (bounding[*c] || bounding[*d]))
            .collect();
        mine.sort_by(|x, y| {
            let other = |f: &&(usize, usize, Approach)| Some((f.0, f.1)) != nearest;
            (other(x).cmp(&other(y)))
                .then(x.2.distance.total_cmp(&y.2.distance))
                .then((x.0, x.1).cmp(&(y.0, y.1)))
        });
        let mut here = Vec::new();
        for &&(c, d, ref a) in &mine {
            if !taken.insert(place_of[c]) {
                continue;
            }
            here.push(UnrefinedPlace {
                curve: curves[c].name.clone(),
                other: curves[d].name.clone(),
                gap: a.distance,
                at: a.at,
                size: a.size,
                length: length(place_of[c]),
            });
        }
        out.push(here);
    }
    out
}

/// Per curve of `model`, whether it bounds what the failed node `node` meshed: a region's
/// patches' curves for `tet_mesh:<region>`, a patch's for `surface_mesh:<patch>` (a chart
/// `<patch>.<k>` counts as its patch); none for another node.
fn bounding_curves(model: &ModelData, node: &str) -> Vec<bool> {
    let topology = &model.topology;
    let mut out = vec![false; topology.curves.len()];
    let patches: Vec<usize> = match node.split_once(':') {
        Some(("tet_mesh", region)) => (model.regions.regions.iter())
            .filter(|r| r.name == region)
            .flat_map(|r| r.sides.iter().map(|s| s.patch as usize))
            .collect(),
        Some(("surface_mesh", patch)) => {
            let whole = patch.rsplit_once('.').map_or(patch, |(p, _)| p);
            (model.patches.iter().enumerate())
                .filter(|(_, p)| p.name == patch || p.name == whole)
                .map(|(k, _)| k)
                .collect()
        }
        _ => Vec::new(),
    };
    for p in patches {
        for c in topology
            .patches
            .get(p)
            .map(|b| b.curves())
            .unwrap_or_default()
        {
            if let Some(b) = out.get_mut(c as usize) {
                *b = true;
            }
        }
    }
    out
}

impl UnrefinedPlace {
    /// "curves `a` and `b` come within g of each other", or of itself for one curve.
    pub fn which(&self) -> String {
        come_within(&self.curve, &self.other, self.gap)
    }
}

/// "curves `a` and `b` come within `gap` of each other", or of itself when `a` is `b`.
fn come_within(a: &str, b: &str, gap: f64) -> String {
    let gap = short(gap);
    if a == b {
        format!("curve `{a}` comes within {gap} of itself")
    } else {
        format!("curves `{a}` and `{b}` come within {gap} of each other")
    }
}

/// The sentence for a failure at `at`, from the model's approaches `found`.
fn cause_sentence(
    recipe: &Recipe,
    model: &ModelData,
    found: &[(usize, usize, Approach)],
    refined: &[bool],
    at: [f64; 3],
) -> Option<String> {
    let (&(c, d, ref a), from) = nearest_within_size(found, at)?;
    let curves = &model.topology.curves;
    let which = come_within(&curves[c].name, &curves[d].name, a.distance);
    let [x, y, z] = a.at.map(|v| format!("{v:.1}"));
    Some(format!(
        "{} from ({x}, {y}, {z}), where {which}, under a tenth of their mesh size {}: the \
         likely cause; {}",
        short(from),
        short(a.size),
        remedy(recipe, &curves[c].name, a.distance, refined[c], false),
    ))
}

/// What the user can do about curves `gap` apart, one of them `curve`: what the build did when
/// it refines there (`refined`), else how to make it (`brief`: the line that refines there
/// alone, the rest being told once for several places).
fn remedy(recipe: &Recipe, curve: &str, gap: f64, refined: bool, brief: bool) -> String {
    let min_size = recipe.mesh.min_size;
    let wanted = super::close_refine::refined_size(gap, 0.0);
    if !refined && brief {
        format!(
            "`refine_close_curves = [\"{curve}\"]` in `[mesh]` refines there (elements of {} \
             where the gap is smallest)",
            short(wanted.max(min_size))
        )
    } else if !refined {
        format!(
            "mend the surfaces there in the data (join or part them), or refine there: \
             `refine_close_curves = [\"{curve}\"]` in `[mesh]` (elements of {} where the gap is \
             smallest), or `refine_close_curves = true` for every such place (finer and slower, \
             the more so the longer the curves run close)",
            short(wanted.max(min_size))
        )
    } else if wanted < min_size {
        format!(
            "refined there to `min_size` {}, coarser than the {} the gap asks for: lower \
             `min_size` in `[mesh]` to resolve it, or mend the surfaces there in the data",
            short(min_size),
            short(wanted)
        )
    } else {
        format!(
            "refined there to {} (`refine_close_curves`); if the gap is a mistake, mend the \
             surfaces there in the data (join or part them)",
            short(wanted)
        )
    }
}

/// The approach nearest to `at` among those within their mesh size of it, and how far it is
/// (ties to the lower pair of curves, then the closer approach).
fn nearest_within_size(
    found: &[(usize, usize, Approach)],
    at: [f64; 3],
) -> Option<(&(usize, usize, Approach), f64)> {
    found
        .iter()
        .map(|f| (f, dist(&f.2.at, &at)))
        .filter(|(f, d)| *d <= f.2.size)
        .min_by(|(f, d), (g, e)| {
            d.total_cmp(e)
                .then((f.0, f.1).cmp(&(g.0, g.1)))
                .then(f.2.distance.total_cmp(&g.2.distance))
        })
}

/// Every unexplained approach of two segments, with its two curves (lower first).
pub(super) fn approaches(recipe: &Recipe, model: &ModelData) -> Vec<(usize, usize, Approach)> {
    let regions = sizes::region_sizes(recipe, model);
    let patches = sizes::patch_sizes(recipe, model, &regions);
    let caps = sizes::curve_caps(recipe, model, &regions);
    let fallbacks = sizes::curve_sizes(recipe, &model.topology, &patches);
    let fallbacks = sizes::within_caps(fallbacks, &caps);
    let size = sizes::nominal_curve_sizes(recipe, &model.topology, &fallbacks, &caps);
    let segments = segments(model);
    let boxes: Vec<BBox> = (segments.iter())
        .map(|s| BBox::from_points(&s.ends).inflate(FRACTION * size[s.curve] / 2.0))
        .collect();
    let found = overlapping_pairs(&boxes, |i, j| {
        approach(model, &size, &segments[i as usize], &segments[j as usize])
    });
    (found.into_iter())
        .map(|(i, j, a)| {
            let (c, d) = (segments[i as usize].curve, segments[j as usize].curve);
            (c.min(d), c.max(d), a)
        })
        .collect()
}

/// Curves that come close, joined by their close pairs: the closest approach, the curves
/// involved, and the approaches far apart from each other (the closest first).
struct Site {
    first: Approach,
    curves: Vec<usize>,
    places: Vec<Approach>,
}

/// Approaches of one site nearer than this many mesh sizes to a closer one are not told apart.
const PLACE_SPACING: f64 = 10.0;
/// At most this many places are told per site.
const PLACES_PER_SITE: usize = 3;

/// `pairs` (closest first) gathered into places: the curves joined by close pairs (two sheets
/// running side by side for kilometres are one place, told at its closest point), in order of
/// their closest approach.
fn sites(pairs: Vec<((usize, usize), Approach)>) -> Vec<Site> {
    let mut root: BTreeMap<usize, usize> = BTreeMap::new();
    fn find(root: &mut BTreeMap<usize, usize>, c: usize) -> usize {
        let up = *root.entry(c).or_insert(c);
        if up == c {
            return c;
        }
        let top = find(root, up);
        root.insert(c, top);
        top
    }
    for &((c, d), _) in &pairs {
        let (a, b) = (find(&mut root, c), find(&mut root, d));
        root.insert(a.max(b), a.min(b));
    }
    let mut out: Vec<Site> = Vec::new();
    let mut site_of: BTreeMap<usize, usize> = BTreeMap::new();
    for ((c, d), a) in pairs {
        let r = find(&mut root, c);
        let k = *site_of.entry(r).or_insert_with(|| {
            out.push(Site {
                first: a.clone(),
                curves: Vec::new(),
                places: Vec::new(),
            });
            out.len() - 1
        });
        let site = &mut out[k];
        let apart = |p: &Approach| dist(&p.at, &a.at) > PLACE_SPACING * p.size;
        if site.places.len() < PLACES_PER_SITE && site.places.iter().all(apart) {
            site.places.push(a);
        }
        for c in [c, d] {
            if !out[k].curves.contains(&c) {
                out[k].curves.push(c);
            }
        }
    }
    out
}

fn sentence(recipe: &Recipe, model: &ModelData, site: &Site, refined: bool, brief: bool) -> String {
    let curves = &model.topology.curves;
    let mut names: Vec<String> = (site.curves.iter().take(NAMES_PER_PLACE))
        .map(|&c| format!("`{}`", curves[c].name))
        .collect();
    if site.curves.len() > NAMES_PER_PLACE {
        names.push(format!("{} more", site.curves.len() - NAMES_PER_PLACE));
    }
    let gap = short(site.first.distance);
    let which = match names.as_slice() {
        [one] => format!("curve {one} comes within {gap} of itself"),
        [rest @ .., last] => {
            format!(
                "curves {} and {last} come within {gap} of each other",
                rest.join(", ")
            )
        }
        [] => String::new(),
    };
    let places: Vec<String> = (site.places.iter())
        .map(|p| {
            let [x, y, z] = p.at.map(|v| format!("{v:.1}"));
            format!("({x}, {y}, {z}) ({})", short(p.distance))
        })
        .collect();
    let first = &curves[site.curves[0]].name;
    let flat = if refined {
        ""
    } else {
        " the elements between them will be flat;"
    };
    format!(
        "{which} near {}, under a tenth of their mesh size {}:{flat} {}",
        places.join(", "),
        short(site.first.size),
        remedy(recipe, first, site.first.distance, refined, brief),
    )
}

/// Every segment of every curve, with its arc length.
fn segments(model: &ModelData) -> Vec<Segment> {
    let mut out = Vec::new();
    for (c, curve) in model.topology.curves.iter().enumerate() {
        let mut arc = 0.0;
        for w in curve.points.windows(2) {
            out.push(Segment {
                curve: c,
                arc,
                ends: [w[0], w[1]],
            });
            arc += dist(&w[0], &w[1]);
        }
    }
    out
}

/// The approach of two segments when it is close and unexplained.
fn approach(model: &ModelData, size: &[f64], s: &Segment, t: &Segment) -> Option<Approach> {
    let shared = |p: &[f64; 3]| t.ends.iter().any(|q| q == p);
    if s.ends.iter().any(shared) {
        return None;
    }
    let limit = FRACTION * size[s.curve].min(size[t.curve]);
    let (p, q, u, v) = closest_points(&s.ends, &t.ends);
    let d = dist(&p, &q);
    if d >= limit {
        return None;
    }
    let sin_min = MIN_ANGLE_DEG.to_radians().sin();
    let explained = if s.curve == t.curve {
        let curve = &model.topology.curves[s.curve];
        let (a, b) = (s.arc + u * seg_len(s), t.arc + v * seg_len(t));
        let mut between = (a - b).abs();
        if curve.closed {
            let total = polyline_length(&curve.points);
            between = between.min(total - between);
        }
        d >= sin_min * between
    } else {
        let ends = |c: usize| {
            let pts = &model.topology.curves[c].points;
            [pts[0], pts[pts.len() - 1]]
        };
        let (es, et) = (ends(s.curve), ends(t.curve));
        (es.iter())
            .filter(|e| et.contains(e))
            .any(|e| d >= sin_min * dist(&p, e).max(dist(&q, e)))
    };
    (!explained).then(|| Approach {
        distance: d,
        at: [0, 1, 2].map(|k| (p[k] + q[k]) / 2.0),
        size: size[s.curve].min(size[t.curve]),
        segments: [s.ends, t.ends],
    })
}

/// The closest points of segments `ab` and `cd`, and their parameters along each.
pub(super) fn closest_points(
    s: &[[f64; 3]; 2],
    t: &[[f64; 3]; 2],
) -> ([f64; 3], [f64; 3], f64, f64) {
    let (a, b, c, d) = (s[0], s[1], t[0], t[1]);
    let d1 = sub(&b, &a);
    let d2 = sub(&d, &c);
    let r = sub(&a, &c);
    let (aa, ee, f) = (dot(&d1, &d1), dot(&d2, &d2), dot(&d2, &r));
    let (mut u, mut v);
    if aa <= 0.0 && ee <= 0.0 {
        (u, v) = (0.0, 0.0);
    } else if aa <= 0.0 {
        u = 0.0;
        v = (f / ee).clamp(0.0, 1.0);
    } else {
        let cc = dot(&d1, &r);
        if ee <= 0.0 {
            v = 0.0;
            u = (-cc / aa).clamp(0.0, 1.0);
        } else {
            let bb = dot(&d1, &d2);
            let denom = aa * ee - bb * bb;
            u = if denom > 0.0 {
                ((bb * f - cc * ee) / denom).clamp(0.0, 1.0)
            } else {
                0.0
            };
            v = (bb * u + f) / ee;
            if v < 0.0 {
                v = 0.0;
                u = (-cc / aa).clamp(0.0, 1.0);
            } else if v > 1.0 {
                v = 1.0;
                u = ((bb - cc) / aa).clamp(0.0, 1.0);
            }
        }
    }
    let at = |o: &[f64; 3], dir: &[f64; 3], w: f64| [0, 1, 2].map(|k| o[k] + w * dir[k]);
    (at(&a, &d1, u), at(&c, &d2, v), u, v)
}

fn seg_len(s: &Segment) -> f64 {
    dist(&s.ends[0], &s.ends[1])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_failure_is_put_down_to_the_nearest_approach_within_its_mesh_size() {
        let near = |distance: f64, at: [f64; 3], size: f64| Approach {
            distance,
            at,
            size,
            segments: [[at; 2]; 2],
        };
        let found = vec![
            (0, 1, near(0.1, [0.0, 0.0, 0.0], 100.0)),
            (2, 3, near(0.5, [50.0, 0.0, 0.0], 100.0)),
            (2, 3, near(0.2, [60.0, 0.0, 0.0], 100.0)),
            (4, 5, near(1.0, [500.0, 0.0, 0.0], 20.0)),
        ];
        let at = |x: f64| [x, 0.0, 0.0];
        let pick = |x: f64| nearest_within_size(&found, at(x)).map(|(f, d)| (f.0, f.2.at[0], d));
        // Nearest first, whichever gap is the smallest.
        assert_eq!(pick(40.0), Some((2, 50.0, 10.0)));
        assert_eq!(pick(5.0), Some((0, 0.0, 5.0)));
        // Only within the curves' own mesh size: 30 from a 20 m curve pair is too far.
        assert_eq!(pick(470.0), None);
        assert_eq!(pick(485.0), Some((4, 500.0, 15.0)));
        assert_eq!(pick(-150.0), None);
        assert_eq!(nearest_within_size(&[], at(0.0)).map(|(_, d)| d), None);
    }

    #[test]
    fn the_closest_points_of_crossing_parallel_and_skew_segments() {
        let (p, q, u, v) = closest_points(
            &[[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]],
            &[[1.0, -1.0, 3.0], [1.0, 1.0, 3.0]],
        );
        assert_eq!((p, q, u, v), ([1.0, 0.0, 0.0], [1.0, 0.0, 3.0], 0.5, 0.5));
        // Parallel: the start of the first against the second.
        let (p, q, ..) = closest_points(
            &[[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]],
            &[[1.0, 0.5, 0.0], [3.0, 0.5, 0.0]],
        );
        assert!((dist(&p, &q) - 0.5).abs() < 1e-12, "{p:?} {q:?}");
        // Apart along their line: end to start.
        let (p, q, ..) = closest_points(
            &[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]],
            &[[3.0, 0.0, 0.0], [5.0, 0.0, 0.0]],
        );
        assert_eq!((p, q), ([1.0, 0.0, 0.0], [3.0, 0.0, 0.0]));
    }
}
