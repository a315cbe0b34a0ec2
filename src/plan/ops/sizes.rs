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
//! nodes are their border nodes); a curve rule, written for that curve, always wins. Each choice
//! keeps the recipe path of the rule that decided it, which names the parameter in the node's
//! key: a model whose choices are all the global size keeps the keys it had without this step.

use super::ModelData;
use crate::recipe::{Recipe, Subdivision};
use geom::predicates::polyline_length;
use model::ModelTopology;

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

fn region_size(recipe: &Recipe, name: &str, thickness: f64) -> SizeChoice {
    let m = &recipe.mesh;
    let spec = m.regions.get(name);
    let base = match spec.filter(|s| s.size_given) {
        Some(s) => SizeChoice {
            path: format!("mesh.regions.{name}"),
            size: s.size,
        },
        None => SizeChoice::global(recipe),
    };
    let (layers, path) = match spec.and_then(|s| s.layers) {
        Some(n) => (Some(n), format!("mesh.regions.{name}.layers")),
        None => (m.min_layers, "mesh.min_layers".to_string()),
    };
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
    // Per patch, the regions on its sides (a region's sides are sorted by patch, so a region
    // with both sides of a patch comes twice in a row).
    let mut bounded: Vec<Vec<&SizeChoice>> = vec![Vec::new(); model.patches.len()];
    for (r, choice) in model.regions.regions.iter().zip(regions) {
        let mut last = None;
        for f in r
            .sides
            .iter()
            .filter(|f| last.replace(f.patch) != Some(f.patch))
        {
            if let Some(rs) = bounded.get_mut(f.patch as usize) {
                rs.push(choice);
            }
        }
    }
    model
        .patches
        .iter()
        .zip(&bounded)
        .map(|(p, regions)| patch_size(recipe, &p.surface, regions))
        .collect()
}

fn patch_size(recipe: &Recipe, surface: &str, regions: &[&SizeChoice]) -> SizeChoice {
    let m = &recipe.mesh;
    let each = regions.iter().map(|c| (*c).clone());
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

/// What the sizes did to thin regions, one sentence each, in region order: a region thinner than
/// its size with no `layers` asked (its mesh is about one element across), and a `layers` count
/// that `min_size` kept from being met. `(region, message)`.
pub fn thin_region_warnings(recipe: &Recipe, model: &ModelData) -> Vec<(String, String)> {
    let m = &recipe.mesh;
    let mut out = Vec::new();
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
            None if t > 0.0 && t < own.size => out.push((
                name.clone(),
                format!(
                    "region `{name}` is about {} thick but meshed at {} (`{}.size`): about one \
                     element across; {}",
                    short(t),
                    short(own.size),
                    own.path,
                    three_layers(recipe, r)
                ),
            )),
            Some(n) if t > 0.0 && t / f64::from(n) < own.size => out.push((
                name.clone(),
                format!(
                    "region `{name}` is about {} thick: {n} layers need {} but `min_size` keeps \
                     it at {}; lower `min_size` to get them",
                    short(t),
                    short(t / f64::from(n)),
                    short(own.size)
                ),
            )),
            _ => {}
        }
    }
    out
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
fn three_layers(recipe: &Recipe, r: &model::regions::Region) -> String {
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
pub(super) fn short(x: f64) -> String {
    let digits = (2 - x.abs().log10().floor() as i32).clamp(0, 6) as usize;
    format!("{x:.digits$}")
}
