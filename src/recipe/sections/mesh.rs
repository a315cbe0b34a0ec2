//! `[mesh]`: element sizes. The global size (required) with its bounds and growth, curve
//! subdivisions by curve selector, sizes per surface selector and per named region, and the tet
//! method (global, overridable per region). Decides the defaults (`min_size = size/100`,
//! `max_size = size*10`, `growth = 1.3`, curve `ratio = 1`, `grading = "geometric"`,
//! `tet_method = "delaunay"`), that bounds are ordered, and that every selector side names a
//! known surface and every region key a `[regions]` name. Curves closer than their mesh can
//! resolve are refined everywhere only when `refine_close_curves = true` (that is finer and
//! slower, and where the gap is a wedge of the model's own it buys little), at the places of the
//! curves it lists, and, unless it is `false`, where a mesh fails at such a place. Rules keep
//! their recipe order, which breaks precedence ties (see `MeshSpec::curve_rule`).

use std::collections::BTreeMap;
use std::ops::Range;

use toml::de::DeTable;

use super::Names;
use crate::recipe::reader::{self as rd, Ctx, Value, name_help, path_join};
use crate::recipe::selector::SurfaceSelector;
use crate::recipe::spec::{
    CloseCurves, CurveRule, Grading, MeshSpec, RegionMeshSpec, Subdivision, SurfaceSizeRule,
    TetMethod,
};

const KEYS: &[&str] = &[
    "size",
    "min_size",
    "max_size",
    "growth",
    "tet_method",
    "min_layers",
    "refine",
    "refine_close_curves",
    "curves",
    "surfaces",
    "regions",
];
const CURVE_KEYS: &[&str] = &["count", "size", "ratio", "grading"];
const REGION_KEYS: &[&str] = &[
    "size",
    "min_size",
    "max_size",
    "growth",
    "tet_method",
    "layers",
    "aspect",
];
/// Largest accepted `layers` / `min_layers`: more elements across one layer than this is surely
/// a typo (and would refine a 35 m layer below a metre).
const MAX_LAYERS: i64 = 100;
/// Largest accepted `aspect`: elements fifty times as wide as they are thick are beyond what a
/// solver's elements bear.
const MAX_ASPECT: f64 = 50.0;
/// Largest accepted segment count for one curve: beyond this a recipe is surely a typo.
const MAX_COUNT: i64 = 10_000_000;

struct Sizes {
    size: f64,
    min_size: f64,
    max_size: f64,
    growth: f64,
    tet_method: TetMethod,
}

/// Reads `size`, `min_size`, `max_size`, `growth` and `tet_method` of `t`, defaulting to `dflt`
/// (or, for the global table, to the documented rules), and checks `min_size <= size <=
/// max_size`.
fn sizes(
    ctx: &mut Ctx<'_>,
    t: &DeTable<'_>,
    span: Range<usize>,
    path: &str,
    dflt: Option<&Sizes>,
) -> Option<Sizes> {
    let size = match (t.get("size"), dflt) {
        (Some(v), _) => rd::size(ctx, v, &path_join(path, "size")),
        (None, Some(d)) => Some(d.size),
        (None, None) => {
            rd::required(
                ctx,
                t,
                span.clone(),
                path,
                "size",
                "add `size = 100.0` (the global element size, in model units)",
            );
            None
        }
    };
    let opt = |ctx: &mut Ctx<'_>, key: &str| {
        t.get(key)
            .map(|v| (rd::size(ctx, v, &path_join(path, key)), v.span()))
    };
    let min = opt(ctx, "min_size");
    let max = opt(ctx, "max_size");
    let growth = match t.get("growth") {
        Some(v) => rd::number_above(ctx, v, &path_join(path, "growth"), 1.0, "greater than 1"),
        None => Some(dflt.map_or(1.3, |d| d.growth)),
    };
    let tet_method = match t.get("tet_method") {
        Some(v) => rd::choice(ctx, v, &path_join(path, "tet_method"), &TetMethod::NAMES),
        None => Some(dflt.map_or(TetMethod::Delaunay, |d| d.tet_method)),
    };
    let size = size?;
    let min_size = match &min {
        Some((x, _)) => (*x)?,
        None => dflt.map_or(size / 100.0, |d| d.min_size.min(size)),
    };
    let max_size = match &max {
        Some((x, _)) => (*x)?,
        None => dflt.map_or(size * 10.0, |d| d.max_size.max(size)),
    };
    let mut ok = true;
    if min_size > size {
        let at = min.map_or(span.clone(), |(_, s)| s);
        ctx.error(
            at,
            format!(
                "`{}` = {min_size} is larger than `{}` = {size}",
                path_join(path, "min_size"),
                path_join(path, "size")
            ),
            None,
        );
        ok = false;
    }
    if max_size < size {
        let at = max.map_or(span, |(_, s)| s);
        ctx.error(
            at,
            format!(
                "`{}` = {max_size} is smaller than `{}` = {size}",
                path_join(path, "max_size"),
                path_join(path, "size")
            ),
            None,
        );
        ok = false;
    }
    let growth = growth?;
    let tet_method = tet_method?;
    ok.then_some(Sizes {
        size,
        min_size,
        max_size,
        growth,
        tet_method,
    })
}

pub(crate) fn read(
    ctx: &mut Ctx<'_>,
    root: &DeTable<'_>,
    root_span: Range<usize>,
    names: &Names,
    regions: &[String],
) -> Option<MeshSpec> {
    let v = rd::required(
        ctx,
        root,
        root_span,
        "",
        "mesh",
        "add `[mesh]` with `size = 100.0`",
    )?;
    let t = rd::as_table(ctx, v, "mesh", None)?;
    rd::check_keys(ctx, t, "mesh", KEYS, &|_| None);
    let global = sizes(ctx, t, v.span(), "mesh", None);
    let curves = t
        .get("curves")
        .map(|c| curve_rules(ctx, c, names))
        .unwrap_or_default();
    let surfaces = t
        .get("surfaces")
        .map(|s| surface_rules(ctx, s, names))
        .unwrap_or_default();
    let min_layers = layers(ctx, t, "mesh", "min_layers");
    let refine_close_curves = match t.get("refine_close_curves") {
        Some(v) => close_curves(ctx, v, names),
        None => Some(CloseCurves::default()),
    };
    let global = global?;
    let refine = t
        .get("refine")
        .map(|r| super::refine::read(ctx, r, names, global.size))
        .unwrap_or_default();
    let region_sizes = t
        .get("regions")
        .map(|r| region_rules(ctx, r, regions, &global))
        .unwrap_or_default();
    Some(MeshSpec {
        size: global.size,
        min_size: global.min_size,
        max_size: global.max_size,
        growth: global.growth,
        tet_method: global.tet_method,
        min_layers,
        curves,
        surfaces,
        regions: region_sizes,
        refine,
        refine_close_curves: refine_close_curves?,
        span: ctx.span(v.span()),
    })
}

/// `refine_close_curves`: `true`, `false` or a list of curve selectors.
fn close_curves(ctx: &mut Ctx<'_>, v: &Value<'_>, names: &Names) -> Option<CloseCurves> {
    const PATH: &str = "mesh.refine_close_curves";
    match v.get_ref() {
        toml::de::DeValue::Boolean(true) => return Some(CloseCurves::every()),
        toml::de::DeValue::Boolean(false) => return Some(CloseCurves::none()),
        toml::de::DeValue::Array(_) => {}
        other => {
            let msg = format!(
                "`{PATH}` must be `true`, `false` or a list of curve names, found {} `{}`",
                rd::type_name(other),
                ctx.text(v.span())
            );
            let help = "`true` refines every place where curves come closer than their mesh can \
                        resolve, `[\"top/f1#2\"]` the places of the curves listed";
            ctx.error(v.span(), msg, Some(help.into()));
            return None;
        }
    }
    let mut named = Vec::new();
    let mut ok = true;
    for (text, span) in rd::strings(ctx, v, PATH)? {
        match super::curve_selector(ctx, &text, span, names) {
            Some(s) => named.push(s),
            None => ok = false,
        }
    }
    ok.then(|| CloseCurves {
        named,
        ..CloseCurves::default()
    })
}

/// The element count across a region that `key` of `t` asks for, if written and valid.
fn layers(ctx: &mut Ctx<'_>, t: &DeTable<'_>, path: &str, key: &str) -> Option<u32> {
    let v = t.get(key)?;
    let at = path_join(path, key);
    let n = rd::int(ctx, v, &at)?;
    if !(1..=MAX_LAYERS).contains(&n) {
        ctx.error(
            v.span(),
            format!("`{at}` = {n} must be between 1 and {MAX_LAYERS}"),
            Some("the number of elements across the region's thickness, e.g. `3`".into()),
        );
        return None;
    }
    u32::try_from(n).ok()
}

/// The aspect of a region's elements that `aspect` of `t` asks for, if written and valid.
fn aspect(ctx: &mut Ctx<'_>, t: &DeTable<'_>, path: &str) -> Option<f64> {
    let v = t.get("aspect")?;
    let at = path_join(path, "aspect");
    let a = rd::number(ctx, v, &at)?;
    if !(1.0..=MAX_ASPECT).contains(&a) {
        ctx.error(
            v.span(),
            format!("`{at}` = {a} must be between 1 and {MAX_ASPECT}"),
            Some("how many times as wide along the layer as across it, e.g. `4`".into()),
        );
        return None;
    }
    Some(a)
}

fn curve_rules(ctx: &mut Ctx<'_>, v: &Value<'_>, names: &Names) -> Vec<CurveRule> {
    let mut out: Vec<CurveRule> = Vec::new();
    let Some(t) = rd::as_table(ctx, v, "mesh.curves", None) else {
        return out;
    };
    let mut entries: Vec<_> = t.iter().collect();
    entries.sort_by_key(|(k, _)| k.span().start);
    // Canonical selector -> its rule in `out`: one lookup per rule, however many rules.
    let mut seen: BTreeMap<String, usize> = Default::default();
    for (k, e) in entries {
        let text: &str = k.get_ref();
        let path = path_join("mesh.curves", text);
        let selector = super::curve_selector(ctx, text, k.span(), names);
        let sub = subdivision(ctx, e, &path);
        let (Some(selector), Some(subdivision)) = (selector, sub) else {
            continue;
        };
        if let Some(prev) = seen.get(&selector.canonical()).map(|&i| &out[i]) {
            let msg = format!(
                "curve selector `{text}` repeats `{}` (line {})",
                prev.selector.text, prev.span.line
            );
            ctx.error(
                k.span(),
                msg,
                Some("`a/b` and `b/a` select the same curves: keep one rule".into()),
            );
            continue;
        }
        seen.insert(selector.canonical(), out.len());
        out.push(CurveRule {
            selector,
            subdivision,
            span: ctx.span(k.span()),
        });
    }
    out
}

fn subdivision(ctx: &mut Ctx<'_>, e: &Value<'_>, path: &str) -> Option<Subdivision> {
    let t = rd::as_table(
        ctx,
        e,
        path,
        Some("write `{ count = 40 }` or `{ size = 25.0, ratio = 1.2 }`"),
    )?;
    rd::check_keys(ctx, t, path, CURVE_KEYS, &|_| None);
    match (t.get("count"), t.get("size")) {
        (Some(c), None) => {
            for key in ["ratio", "grading"] {
                if let Some(x) = t.get(key) {
                    ctx.error(
                        x.span(),
                        format!(
                            "`{}` applies to a sized subdivision, not to `count`",
                            path_join(path, key)
                        ),
                        Some("use `{ size = ..., ratio = ... }`, or drop it".into()),
                    );
                    return None;
                }
            }
            let n = rd::int(ctx, c, &path_join(path, "count"))?;
            if !(1..=MAX_COUNT).contains(&n) {
                ctx.error(
                    c.span(),
                    format!(
                        "`{}` = {n} must be between 1 and {MAX_COUNT}",
                        path_join(path, "count")
                    ),
                    None,
                );
                return None;
            }
            u32::try_from(n).ok().map(Subdivision::Count)
        }
        (None, Some(s)) => {
            let size = rd::size(ctx, s, &path_join(path, "size"));
            let ratio = match t.get("ratio") {
                Some(r) => rd::size(ctx, r, &path_join(path, "ratio")),
                None => Some(1.0),
            };
            let grading = match t.get("grading") {
                Some(g) => rd::choice(
                    ctx,
                    g,
                    &path_join(path, "grading"),
                    &[("geometric", Grading::Geometric), ("bump", Grading::Bump)],
                ),
                None => Some(Grading::Geometric),
            };
            Some(Subdivision::Size {
                size: size?,
                ratio: ratio?,
                grading: grading?,
            })
        }
        (Some(_), Some(s)) => {
            ctx.error(
                s.span(),
                format!("`{path}` gives both `count` and `size`"),
                Some("give one: a segment count, or a size with an optional ratio".into()),
            );
            None
        }
        (None, None) if ctx.had_unknown_key(t) => None,
        (None, None) => {
            ctx.error(
                e.span(),
                format!("`{path}` gives neither `count` nor `size`"),
                Some("e.g. `{ count = 40 }` or `{ size = 25.0 }`".into()),
            );
            None
        }
    }
}

fn surface_rules(ctx: &mut Ctx<'_>, v: &Value<'_>, names: &Names) -> Vec<SurfaceSizeRule> {
    let mut out = Vec::new();
    let Some(t) = rd::as_table(ctx, v, "mesh.surfaces", None) else {
        return out;
    };
    let mut entries: Vec<_> = t.iter().collect();
    entries.sort_by_key(|(k, _)| k.span().start);
    for (k, e) in entries {
        let text: &str = k.get_ref();
        let path = path_join("mesh.surfaces", text);
        let known = names.check_pattern(ctx, text, text, k.span(), "surface selector");
        let Some(st) = rd::as_table(ctx, e, &path, Some("write `{ size = 50.0 }`")) else {
            continue;
        };
        rd::check_keys(ctx, st, &path, &["size"], &|_| None);
        let size = rd::required(ctx, st, e.span(), &path, "size", "add `size = 50.0`")
            .and_then(|s| rd::size(ctx, s, &path_join(&path, "size")));
        if let (true, Some(size)) = (known, size) {
            out.push(SurfaceSizeRule {
                selector: SurfaceSelector::new(text),
                size,
                span: ctx.span(k.span()),
            });
        }
    }
    out
}

fn region_rules(
    ctx: &mut Ctx<'_>,
    v: &Value<'_>,
    regions: &[String],
    global: &Sizes,
) -> BTreeMap<String, RegionMeshSpec> {
    let mut out = BTreeMap::new();
    let Some(t) = rd::as_table(ctx, v, "mesh.regions", None) else {
        return out;
    };
    for (k, e) in t.iter() {
        let name: &str = k.get_ref();
        let path = path_join("mesh.regions", name);
        let known = regions.iter().any(|r| r == name);
        if !known {
            let help = name_help(name, regions.iter().map(String::as_str)).or_else(|| {
                Some("name the region in `[regions]` with a point inside it first".into())
            });
            ctx.error(
                k.span(),
                format!("`mesh.regions` names unknown region `{name}`"),
                help,
            );
        }
        let Some(rt) = rd::as_table(ctx, e, &path, Some("write `{ size = 50.0 }`")) else {
            continue;
        };
        rd::check_keys(ctx, rt, &path, REGION_KEYS, &|_| None);
        if let (true, Some(s)) = (known, sizes(ctx, rt, e.span(), &path, Some(global))) {
            out.insert(
                name.to_string(),
                RegionMeshSpec {
                    size: s.size,
                    size_given: rt.get("size").is_some(),
                    layers: layers(ctx, rt, &path, "layers"),
                    aspect: aspect(ctx, rt, &path),
                    min_size: s.min_size,
                    max_size: s.max_size,
                    growth: s.growth,
                    tet_method: s.tet_method,
                    span: ctx.span(k.span()),
                },
            );
        }
    }
    out
}
