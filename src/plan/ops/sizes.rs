//! Which element size each patch and each curve is meshed at, once the model's topology says which
//! regions a patch bounds and which patches a curve bounds.
//!
//! A size set on a region must reach the surfaces that bound it: without nodes on them at that
//! spacing, the tet mesher cannot refine the region (its boundary triangles are given). So a
//! patch takes the finest of the sizes that apply to it, as Gmsh's per-entity sizes do:
//! - its surface's `[mesh.surfaces]` rule when there is one, and the size of every region on
//!   either side that has one of its own (written, or from `layers`);
//! - without a surface rule, the size of every region on either side, its own or the global
//!   `[mesh] size` (so a coarser region coarsens the
//!   surfaces only it bounds, and never a surface it shares with a region at the global size).
//!
//! A region's own size is the size its entry writes (else the global one), made finer where
//! `layers` (or the global `min_layers`) asks for that many elements across it: its thickness
//! (`model::thickness`, measured on the model) over the count.
//!
//! A curve without a `[mesh.curves]` rule takes the finest size of the patches it bounds (its
//! nodes are their border nodes); a curve rule, written for that curve, wins over sizes, but not
//! over a count across a region it bounds (`layers`: a requirement, not a preference). Sizes a
//! surface or region sets grade out along the curves meeting them, vertex to vertex, so no
//! corner joins segments of very different lengths. Each choice keeps the recipe path of the
//! rule that decided it, which names the parameter in the node's key: a model whose choices are
//! all the global size or curve rules keeps the keys it had without this step.

use super::ModelData;
use super::aspect::{self, aspect_of};
use crate::recipe::{Recipe, Subdivision};
use geom::predicates::polyline_length;
use model::ModelTopology;
use std::cmp::Reverse;
use std::collections::{BTreeMap, BinaryHeap};

/// A size and the recipe path of the rule it comes from (`mesh`, `mesh.surfaces."H1"`,
/// `mesh.regions.reservoir`), without the trailing `.size`.
#[derive(Clone, Debug, PartialEq)]
pub struct SizeChoice {
    pub path: String,
    pub size: f64,
}

impl SizeChoice {
    fn global(recipe: &Recipe) -> SizeChoice {
        SizeChoice {
            path: "mesh".to_string(),
            size: recipe.mesh.size,
        }
    }

    /// Is this the global `[mesh] size`?
    pub fn is_global(&self) -> bool {
        self.path == "mesh"
    }

    /// Does this size come from a count of elements across a region (`layers`, `min_layers`)?
    pub fn is_layers(&self) -> bool {
        self.path.ends_with(".layers") || self.path == "mesh.min_layers"
    }
}

/// The finest of `choices` (the first of equal sizes), or `fallback` when there is none.
fn finest(choices: impl IntoIterator<Item = SizeChoice>, fallback: SizeChoice) -> SizeChoice {
    choices
        .into_iter()
        .reduce(|a, b| if b.size < a.size { b } else { a })
        .unwrap_or(fallback)
}

/// Per region of `model` (in its order), the size inside it: its `[mesh.regions]` size if written,
/// else the global one; and where `layers` (or the global `min_layers`) asks for that many
/// elements across, at most the region's thickness over it (never below its `min_size`).
pub fn region_sizes(recipe: &Recipe, model: &ModelData) -> Vec<SizeChoice> {
    model
        .regions
        .regions
        .iter()
        .enumerate()
        .map(|(i, r)| {
            let thickness = model.thickness.get(i).copied().unwrap_or(0.0);
            region_size(recipe, &r.name, thickness)
        })
        .collect()
}

/// The count of elements across region `name` the recipe asks for (its `layers`, else the
/// global `min_layers`), and the recipe path that asks it.
pub(super) fn layers_of(recipe: &Recipe, name: &str) -> (Option<u32>, String) {
    let m = &recipe.mesh;
    match m.regions.get(name).and_then(|s| s.layers) {
        Some(n) => (Some(n), format!("mesh.regions.{name}.layers")),
        None => (m.min_layers, "mesh.min_layers".to_string()),
    }
}

/// Per region of `model`, the target size inside it for the tet mesher: its size
/// ([`region_sizes`], `regions`), and in a region with `n ≥ 2` elements across, at most its
/// thickness over [`per_layer`]`(n)` (never below its `min_size`). The surfaces bounding it
/// stay at thickness over `n`. The count across is the fewest tet edges from one side to the
/// other, and a path of `n − 1` edges crosses only if its edges are longer than thickness over
/// `n − 1`: Delaunay refinement leaves tets of circumradius up to 0.9 sizes, so edges of up to
/// 1.8 sizes, and a target of a third of the layer left one path in twenty of two edges (a
/// 35 m reservoir at 11.7 m: 3,026 of 66,209 nodes of its base); at [`EDGE_SPAN`] none.
pub fn interior_sizes(recipe: &Recipe, model: &ModelData, regions: &[SizeChoice]) -> Vec<f64> {
    (model.regions.regions.iter().zip(regions).enumerate())
        .map(|(i, (r, own))| {
            let thickness = model.thickness.get(i).copied().unwrap_or(0.0);
            let (layers, _) = layers_of(recipe, &r.name);
            match layers {
                Some(n) if own.is_layers() && n >= 2 => {
                    let min_size = (recipe.mesh.regions.get(&r.name))
                        .map_or(recipe.mesh.min_size, |s| s.min_size);
                    let across = thickness / per_layer(n);
                    match aspect_of(recipe, &r.name) {
                        Some(s) => (s * across.max(min_size)).min(base_size(recipe, &r.name).size),
                        None => own.size.min(across.max(min_size)),
                    }
                }
                Some(_) if own.is_layers() => match aspect_of(recipe, &r.name) {
                    Some(s) => (s * own.size).min(base_size(recipe, &r.name).size),
                    None => own.size,
                },
                _ => own.size,
            }
        })
        .collect()
}

/// The longest tet edge inside a layered region, in its interior target sizes
/// ([`interior_sizes`]).
pub const EDGE_SPAN: f64 = 2.0;

/// How many interior target sizes a region with `n` layers is across ([`interior_sizes`]):
/// `EDGE_SPAN · (n − 1)`, and at least `n + 1` from two layers on: with `n` for two layers (its
/// surfaces' size) the example's reservoirs kept 393 tet edges straight across them.
pub fn per_layer(n: u32) -> f64 {
    match n {
        0 | 1 => 1.0,
        _ => (EDGE_SPAN * f64::from(n - 1)).max(f64::from(n + 1)),
    }
}

/// The size region `name` writes, else the global one.
fn base_size(recipe: &Recipe, name: &str) -> SizeChoice {
    match recipe.mesh.regions.get(name).filter(|s| s.size_given) {
        Some(s) => SizeChoice {
            path: format!("mesh.regions.{name}"),
            size: s.size,
        },
        None => SizeChoice::global(recipe),
    }
}

fn region_size(recipe: &Recipe, name: &str, thickness: f64) -> SizeChoice {
    let m = &recipe.mesh;
    let spec = m.regions.get(name);
    let base = base_size(recipe, name);
    let (layers, path) = layers_of(recipe, name);
    let min_size = spec.map_or(m.min_size, |s| s.min_size);
    match layers {
        Some(n) if thickness > 0.0 && thickness / f64::from(n) < base.size => SizeChoice {
            path,
            size: (thickness / f64::from(n)).max(min_size),
        },
        _ => base,
    }
}

/// Per patch of `model` (in its order), the size its surface mesh uses; `regions` as
/// [`region_sizes`] gives them.
pub fn patch_sizes(recipe: &Recipe, model: &ModelData, regions: &[SizeChoice]) -> Vec<SizeChoice> {
    model
        .patches
        .iter()
        .zip(&sides_of_patches(recipe, model, regions, true))
        .map(|(p, regions)| patch_size(recipe, &p.surface, regions))
        .collect()
}

/// Per patch of `model`, the sizes of the regions on its sides (`regions` in region order). A
/// region's sides are sorted by patch, so a region with both sides of a patch comes twice in a
/// row and is taken once. With `widen`, a region with an `aspect` (`aspect::layers`) asks its
/// top and base, and the sides meshed in its stretched space (`aspect::side_layers`, where that
/// size is the count's across the layer), for its count's size times the aspect, up to its own
/// size; its other sides keep the count's size.
fn sides_of_patches(
    recipe: &Recipe,
    model: &ModelData,
    regions: &[SizeChoice],
    widen: bool,
) -> Vec<Vec<SizeChoice>> {
    let layers = if widen {
        aspect::layers(recipe, model)
    } else {
        vec![None; regions.len()]
    };
    let sides = aspect::side_layers(model, &layers);
    let mut bounded: Vec<Vec<SizeChoice>> = vec![Vec::new(); model.patches.len()];
    for ((r, choice), layer) in model.regions.regions.iter().zip(regions).zip(&layers) {
        let mut last = None;
        for f in r
            .sides
            .iter()
            .filter(|f| last.replace(f.patch) != Some(f.patch))
        {
            let Some(rs) = bounded.get_mut(f.patch as usize) else {
                continue;
            };
            let wide = |l: &&aspect::Layer| {
                choice.is_layers() && aspect::widened(model, f.patch as usize, l, &sides)
            };
            rs.push(match layer.as_ref().filter(wide) {
                Some(l) => wide_choice(recipe, &r.name, choice, l.aspect),
                None => choice.clone(),
            });
        }
    }
    bounded
}

/// The size a layer's count asks of its top and base when its elements are `aspect` times as
/// wide as thick: the count's size times the aspect, up to the region's own size.
fn wide_choice(recipe: &Recipe, name: &str, choice: &SizeChoice, aspect: f64) -> SizeChoice {
    let base = base_size(recipe, name);
    let wide = choice.size * aspect;
    if wide >= base.size {
        base
    } else {
        SizeChoice {
            path: format!("mesh.regions.{name}.aspect"),
            size: wide,
        }
    }
}

/// Per curve of `model`, the finest size a count of elements across (`layers`, `min_layers`)
/// gives the regions its patches bound, if any does. A `[mesh.curves]` rule for the curve
/// yields to it: the curves along a layer's edges (where it meets a fault or the box) are the
/// borders of the strips across it, and segments longer than the layer's size would leave those
/// strips one element across whatever the layer's own size. Sizes without a count stay below a
/// curve's rule, which names the curve.
pub fn curve_caps(
    recipe: &Recipe,
    model: &ModelData,
    regions: &[SizeChoice],
) -> Vec<Option<SizeChoice>> {
    let topo = &model.topology;
    let per_patch: Vec<Option<SizeChoice>> = sides_of_patches(recipe, model, regions, false)
        .into_iter()
        .map(|rs| {
            let layered = rs.into_iter().filter(|c| c.is_layers());
            layered.reduce(|a, b| if b.size < a.size { b } else { a })
        })
        .collect();
    let mut caps: Vec<Option<SizeChoice>> = vec![None; topo.curves.len()];
    for (boundary, cap) in topo.patches.iter().zip(&per_patch) {
        let Some(cap) = cap else { continue };
        for c in boundary.curves() {
            if let Some(slot) = caps.get_mut(c as usize)
                && slot.as_ref().is_none_or(|s| cap.size < s.size)
            {
                *slot = Some(cap.clone());
            }
        }
    }
    caps
}

fn patch_size(recipe: &Recipe, surface: &str, regions: &[SizeChoice]) -> SizeChoice {
    let m = &recipe.mesh;
    let each = regions.iter().cloned();
    if m.surfaces.iter().any(|r| r.selector.matches(surface)) {
        let own = SizeChoice {
            path: format!("mesh.surfaces.\"{surface}\""),
            size: m.surface_size(surface),
        };
        let set = each.filter(|c| !c.is_global());
        finest(std::iter::once(own).chain(set), SizeChoice::global(recipe))
    } else {
        finest(each, SizeChoice::global(recipe))
    }
}

/// `sizes` (per curve) lowered to `caps` where finer: a curve bounding the sides of a layer with
/// an `aspect` takes the count's size across it although its patches are meshed coarser.
pub fn within_caps(sizes: Vec<SizeChoice>, caps: &[Option<SizeChoice>]) -> Vec<SizeChoice> {
    (sizes.into_iter().zip(caps))
        .map(|(s, cap)| match cap {
            Some(c) if c.size < s.size => c.clone(),
            _ => s,
        })
        .collect()
}

/// Per curve of `topo`, the size a curve without a `[mesh.curves]` rule uses: the finest of the
/// patches it bounds (`patches`, in the topology's patch order), the global size for a curve
/// that bounds none.
pub fn curve_sizes(
    recipe: &Recipe,
    topo: &ModelTopology,
    patches: &[SizeChoice],
) -> Vec<SizeChoice> {
    let mut per_curve: Vec<Vec<SizeChoice>> = vec![Vec::new(); topo.curves.len()];
    for (p, boundary) in topo.patches.iter().enumerate() {
        let Some(choice) = patches.get(p) else {
            continue;
        };
        for c in boundary.curves() {
            if let Some(v) = per_curve.get_mut(c as usize) {
                v.push(choice.clone());
            }
        }
    }
    per_curve
        .into_iter()
        .map(|v| finest(v, SizeChoice::global(recipe)))
        .collect()
}

/// Per curve of `topo`, the length of its mesh segments before any grading: its
/// `[mesh.curves]` rule's (a count's as the curve's length over it), at most its cap
/// ([`curve_caps`]); without a rule, the finest of its patches' sizes ([`curve_sizes`]).
pub fn nominal_curve_sizes(
    recipe: &Recipe,
    topo: &ModelTopology,
    fallbacks: &[SizeChoice],
    caps: &[Option<SizeChoice>],
) -> Vec<f64> {
    (topo.curves.iter().zip(fallbacks).zip(caps))
        .map(|((c, fallback), cap)| {
            let own = match recipe.mesh.curve_rule(&c.name).map(|r| &r.subdivision) {
                Some(Subdivision::Size { size, .. }) => *size,
                Some(Subdivision::Count(n)) => polyline_length(&c.points) / f64::from((*n).max(1)),
                None => fallback.size,
            };
            cap.as_ref().map_or(own, |cap| own.min(cap.size))
        })
        .collect()
}

/// Per curve of `topo` (`fallbacks` and `caps` as [`curve_sizes`] and [`curve_caps`] give
/// them), the segment length its two ends (first point, last point) must start from, where that is finer than the curve's own size: a size that a surface or region sets
/// (a curve's fallback or cap that is not the global size) grades out along the curves meeting
/// it, growing by `slope` per unit of length from vertex to vertex (a shortest path over the
/// curves), the way the surface meshes grade from their borders. Without it a fault's border
/// at its rule's 100 meets a layer's curves at 12 in one corner triangle, and the embedded
/// fault's large triangles beside the layer's fine surface are more than the tet mesher's
/// recovery can take. A curve rule, written for its curve, is not graded out (the seed's
/// refinements refine the reservoir's curves alone). `None` at an end that is not finer than
/// the curve's own size by more than [`GRADED_JUMP`].
pub fn curve_end_sizes(
    recipe: &Recipe,
    topo: &ModelTopology,
    fallbacks: &[SizeChoice],
    caps: &[Option<SizeChoice>],
    slope: f64,
) -> Vec<[Option<f64>; 2]> {
    let nominal = nominal_curve_sizes(recipe, topo, fallbacks, caps);
    let key = |p: &[f64; 3]| p.map(|x| (x + 0.0).to_bits());
    let mut vertices: BTreeMap<[u64; 3], usize> = BTreeMap::new();
    let mut ends: Vec<Option<[usize; 2]>> = Vec::with_capacity(topo.curves.len());
    for c in &topo.curves {
        ends.push(match (c.points.first(), c.points.last()) {
            (Some(a), Some(b)) if !c.closed => {
                let n = vertices.len();
                let i = *vertices.entry(key(a)).or_insert(n);
                let n = vertices.len();
                Some([i, *vertices.entry(key(b)).or_insert(n)])
            }
            _ => None,
        });
    }
    // Seeds: each vertex takes the finest size a surface or region sets on a curve ending there.
    let mut at = vec![f64::INFINITY; vertices.len()];
    for (i, c) in topo.curves.iter().enumerate() {
        let ruled = recipe.mesh.curve_rule(&c.name).is_some();
        let set = caps[i].is_some() || (!ruled && !fallbacks[i].is_global());
        if let (true, Some(e)) = (set, ends[i]) {
            for v in e {
                at[v] = at[v].min(nominal[i]);
            }
        }
    }
    // Dijkstra over the curves, each as long as its polyline (sizes are finite and positive).
    let mut links: Vec<Vec<(usize, f64)>> = vec![Vec::new(); vertices.len()];
    for (c, e) in topo.curves.iter().zip(&ends) {
        if let Some([a, b]) = *e {
            let len = polyline_length(&c.points);
            links[a].push((b, len));
            links[b].push((a, len));
        }
    }
    let mut heap: BinaryHeap<Reverse<(u64, usize)>> = (at.iter().enumerate())
        .filter(|(_, s)| s.is_finite())
        .map(|(v, s)| Reverse((s.to_bits(), v)))
        .collect();
    while let Some(Reverse((bits, v))) = heap.pop() {
        if f64::from_bits(bits) > at[v] {
            continue;
        }
        for &(w, len) in &links[v] {
            let s = at[v] + slope * len;
            if s < at[w] {
                at[w] = s;
                heap.push(Reverse((s.to_bits(), w)));
            }
        }
    }
    (ends.iter().zip(&nominal))
        .map(|(e, &own)| match e {
            Some(e) => e.map(|v| (at[v] * GRADED_JUMP < own).then_some(at[v])),
            None => [None, None],
        })
        .collect()
}

/// A curve starts from the size at its end only where its own is more than this many times
/// that: a corner joining segments of twice the length is one the surface mesher grades across
/// well (the shipped example's fault curves at 100 meet the box's at 200), and a size set on a
/// region or surface then re-runs the curves along it and nothing further.
pub const GRADED_JUMP: f64 = 2.0;

/// A warning about one thin region: its name, the sentence, and for a region about one element
/// across with no `layers` asked, its thickness and size (so that many can be told at once).
pub struct ThinRegion {
    pub region: String,
    pub message: String,
    pub one_across: Option<(f64, f64)>,
}

/// What the sizes did to thin regions, one sentence each: the regions whose thin parts the
/// element budget held back (`thin`), then in region order a region thinner than its size with
/// no `layers` asked (its mesh is about one element across), and a `layers` count that
/// `min_size` kept from being met.
pub fn thin_region_warnings(recipe: &Recipe, model: &ModelData) -> Vec<ThinRegion> {
    let m = &recipe.mesh;
    let slope = recipe.mesh.growth.min(surface_mesh::MAX_SURFACE_GROWTH) - 1.0;
    let mut out: Vec<ThinRegion> = (super::thin::budget_warnings(recipe, model, slope))
        .into_iter()
        .map(|(region, message)| ThinRegion {
            region,
            message,
            one_across: None,
        })
        .collect();
    for ((r, own), &t) in model
        .regions
        .regions
        .iter()
        .zip(region_sizes(recipe, model))
        .zip(&model.thickness)
    {
        let asked = m
            .regions
            .get(&r.name)
            .and_then(|s| s.layers)
            .or(m.min_layers);
        let name = &r.name;
        match asked {
            None if t > 0.0 && t < own.size => out.push(ThinRegion {
                region: name.clone(),
                message: format!(
                    "region `{name}` is about {} thick but meshed at {} (`{}.size`): about one \
                     element across; {}",
                    short(t),
                    short(own.size),
                    own.path,
                    three_layers(recipe, r)
                ),
                one_across: Some((t, own.size)),
            }),
            Some(n) if t > 0.0 && t / f64::from(n) < own.size => out.push(ThinRegion {
                region: name.clone(),
                message: format!(
                    "region `{name}` is about {} thick: {n} layers need {} but `min_size` keeps \
                     it at {}; lower `min_size` to get them",
                    short(t),
                    short(t / f64::from(n)),
                    short(own.size)
                ),
                one_across: None,
            }),
            _ => {}
        }
    }
    out
}

/// Thin regions told one by one on the console; more are told in one sentence
/// ([`one_across_summary`]), and the report still lists each.
pub const THIN_REGIONS_TOLD: usize = 4;

/// One sentence for many regions about one element across (`thin`, each with `one_across`):
/// the first few named, how many more, the range of thicknesses and sizes, and the one setting
/// that gives them all three elements across. (A model whose surfaces cross each other over and
/// over, a horizon jittered through the next one, has hundreds of such slivers.)
pub fn one_across_summary(thin: &[&ThinRegion]) -> String {
    let across: Vec<(f64, f64)> = thin.iter().filter_map(|t| t.one_across).collect();
    let range = |v: &mut dyn Iterator<Item = f64>| {
        let (lo, hi) = v.fold((f64::INFINITY, 0.0f64), |(lo, hi), x| {
            (lo.min(x), hi.max(x))
        });
        if short(lo) == short(hi) {
            short(lo)
        } else {
            format!("{} to {}", short(lo), short(hi))
        }
    };
    let named: Vec<String> = (thin.iter().take(THIN_REGIONS_TOLD))
        .map(|t| format!("`{}`", t.region))
        .collect();
    format!(
        "regions {} and {} more are about {} thick but meshed at {}: about one element across \
         each (the report lists them); `min_layers = 3` in `[mesh]` gives them three",
        named.join(", "),
        thin.len() - named.len(),
        range(&mut across.iter().map(|a| a.0)),
        range(&mut across.iter().map(|a| a.1)),
    )
}

/// The `[mesh.curves]` size rules that cannot be honoured anywhere: a rule asking for segments
/// of `size` (any ratio) whose curves are all shorter than that, so each is one segment as long
/// as the curve and the rule changes nothing. (A rule for a whole surface that some short
/// pieces of it cannot follow is honoured elsewhere, and not warned about.) One sentence per
/// rule, in recipe order, naming the rule by its place and at most four curves with their
/// lengths, with the curves' names. Counts are always honoured.
pub fn short_curve_warnings(recipe: &Recipe, model: &ModelData) -> Vec<(Vec<String>, String)> {
    // Each curve's rule found once: per rule, the curves it governs and their lengths.
    let mut by_rule: Vec<Vec<(&str, f64)>> = vec![Vec::new(); recipe.mesh.curves.len()];
    for c in &model.topology.curves {
        if let Some(i) = recipe.mesh.curve_rule_index(&c.name) {
            by_rule[i].push((c.name.as_str(), polyline_length(&c.points)));
        }
    }
    let mut out = Vec::new();
    for (rule, short_ones) in recipe.mesh.curves.iter().zip(by_rule) {
        let Subdivision::Size { size, .. } = rule.subdivision else {
            continue;
        };
        if short_ones.is_empty() || short_ones.iter().any(|&(_, len)| len >= size) {
            continue;
        }
        let named: Vec<String> = (short_ones.iter().take(4))
            .map(|(n, len)| format!("`{n}` ({})", short(*len)))
            .collect();
        let more = match short_ones.len() {
            n if n > 4 => format!(" and {} more", n - 4),
            _ => String::new(),
        };
        let curves = short_ones.iter().map(|(n, _)| n.to_string()).collect();
        let which = match short_ones.len() {
            1 => "curve is".to_string(),
            n => format!("{n} curves are all"),
        };
        let warning = format!(
            "{}: `[mesh.curves]` rule `{}` asks for segments of {}, but its {which} shorter: \
             {}{more}; each is one segment as long as the curve, so the rule changes nothing: \
             give a smaller size or a `count`",
            recipe.place(rule.span),
            rule.selector.text,
            short(size),
            named.join(", ")
        );
        out.push((curves, warning));
    }
    out
}

/// How to ask for three layers in `r`: its `[mesh.regions]` entry when the recipe names it, else
/// naming it first (a point of its own, which the model gives), or `min_layers` for all.
pub(super) fn three_layers(recipe: &Recipe, r: &model::regions::Region) -> String {
    let name = &r.name;
    if recipe.regions.contains_key(name) {
        return "write `layers = 3` in its `[mesh.regions]` entry (or `min_layers = 3` in `[mesh]`) \
                for three"
            .to_string();
    }
    // Written in full: a rounded point could fall outside a region thinner than the rounding.
    let [x, y, z] = r.interior_point.map(|c| format!("{c:?}"));
    format!(
        "for three, write `min_layers = 3` in `[mesh]`, or name it in `[regions]` (for example \
         `{name} = {{ point = [{x}, {y}, {z}] }}`, a point inside it) and write `layers = 3` in \
         its `[mesh.regions]` entry"
    )
}

/// A length for a message, in model units: three significant digits.
pub fn short(x: f64) -> String {
    let digits = (2 - x.abs().log10().floor() as i32).clamp(0, 6) as usize;
    format!("{x:.digits$}")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sliver(k: usize, thickness: f64) -> ThinRegion {
        ThinRegion {
            region: format!("H1+H2#{k}"),
            message: String::new(),
            one_across: Some((thickness, 200.0)),
        }
    }

    #[test]
    fn many_regions_one_element_across_are_told_in_one_sentence_with_their_range() {
        let thin: Vec<ThinRegion> = [2.28, 3.94, 0.378, 8.37, 2.93, 3.05]
            .iter()
            .enumerate()
            .map(|(k, &t)| sliver(k + 1, t))
            .collect();
        let told = one_across_summary(&thin.iter().collect::<Vec<_>>());
        assert!(
            told.starts_with(
                "regions `H1+H2#1`, `H1+H2#2`, `H1+H2#3`, `H1+H2#4` and 2 more are about 0.378 \
                 to 8.37 thick but meshed at 200:"
            ),
            "{told}"
        );
        assert!(told.contains("`min_layers = 3` in `[mesh]`"), "{told}");
    }
}
