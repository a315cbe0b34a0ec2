//! `[intersect]`: which surface pairs are intersected. Explicit `pairs` plus the `all` shorthand
//! (every pair among the listed names); `box` stands for its six sides. The result is the union,
//! normalised: each pair sorted, duplicates removed, the list sorted. A surface paired with
//! itself, an unknown name, and a pair of two box sides (they meet along the box edges, which
//! the box itself provides) are errors. A top-level `intersect = [["a", "b"], ...]` array is
//! accepted as a shorthand for `[intersect] pairs = ...`.

use std::collections::BTreeMap;
use std::ops::Range;

use toml::de::DeValue;

use super::Names;
use crate::recipe::diagnostic::Span;
use crate::recipe::reader::{self as rd, Ctx, Value, name_help};
use crate::recipe::spec::BOX_SIDES;

const KEYS: &[&str] = &["pairs", "all"];

/// The normalised pairs, each with the span of the first recipe item that asked for it.
pub(crate) fn read(
    ctx: &mut Ctx<'_>,
    v: Option<&Value<'_>>,
    names: &Names,
) -> BTreeMap<(String, String), Span> {
    let mut out = BTreeMap::new();
    let Some(v) = v else { return out };
    match v.get_ref() {
        DeValue::Array(_) => pairs(ctx, v, "intersect", names, &mut out),
        DeValue::Table(t) => {
            rd::check_keys(ctx, t, "intersect", KEYS, &|_| None);
            if let Some(p) = t.get("pairs") {
                pairs(ctx, p, "intersect.pairs", names, &mut out);
            }
            if let Some(a) = t.get("all") {
                all(ctx, a, names, &mut out);
            }
        }
        other => {
            let msg = format!(
                "`intersect` must be a table or an array of pairs, found {} `{}`",
                rd::type_name(other),
                ctx.text(v.span())
            );
            ctx.error(v.span(), msg, Some("write `[intersect]` with `pairs = [[\"top\", \"f1\"]]` and/or `all = [\"top\", \"f1\", \"box\"]`".into()));
        }
    }
    out
}

/// Resolves one name to the surfaces it stands for (`box` -> six sides), or reports it.
fn resolve(
    ctx: &mut Ctx<'_>,
    name: &str,
    span: Range<usize>,
    path: &str,
    names: &Names,
) -> Option<Vec<String>> {
    if name == "box" {
        if names.has_box {
            return Some(BOX_SIDES.iter().map(|s| s.to_string()).collect());
        }
        ctx.error(
            span,
            format!("`{path}` uses `box`, but the recipe has no `[box]`"),
            Some("add a `[box]` with `min` and `max`".into()),
        );
        return None;
    }
    if names.is_known(name) {
        return Some(vec![name.to_string()]);
    }
    let mut cands = names.all();
    if names.has_box {
        cands.push("box");
    }
    let help = if name.starts_with("box.") && !names.has_box {
        Some("the box sides exist only when a `[box]` is given".to_string())
    } else {
        name_help(name, cands.iter().copied())
    };
    ctx.error(
        span,
        format!("`{path}` names unknown surface `{name}`"),
        help,
    );
    None
}

fn add(out: &mut BTreeMap<(String, String), Span>, a: &str, b: &str, span: Span) {
    let key = if a <= b {
        (a.to_string(), b.to_string())
    } else {
        (b.to_string(), a.to_string())
    };
    out.entry(key).or_insert(span);
}

fn both_box(a: &str, b: &str) -> bool {
    BOX_SIDES.contains(&a) && BOX_SIDES.contains(&b)
}

fn pairs(
    ctx: &mut Ctx<'_>,
    v: &Value<'_>,
    path: &str,
    names: &Names,
    out: &mut BTreeMap<(String, String), Span>,
) {
    let Some(list) = rd::array(ctx, v, path, "an array of pairs `[[\"top\", \"f1\"], ...]`") else {
        return;
    };
    for (i, p) in list.iter().enumerate() {
        let ppath = format!("{path}[{i}]");
        let Some(two) = rd::strings(ctx, p, &ppath) else {
            continue;
        };
        let [(a, sa), (b, sb)] = two.as_slice() else {
            let msg = format!(
                "`{ppath}` must be a pair of two surface names, found `{}`",
                ctx.text(p.span())
            );
            ctx.error(p.span(), msg, Some("e.g. `[\"top\", \"f1\"]`".into()));
            continue;
        };
        if a == b {
            ctx.error(
                p.span(),
                format!("`{ppath}` pairs `{a}` with itself"),
                Some(
                    "a surface is not intersected with itself: name two different surfaces".into(),
                ),
            );
            continue;
        }
        let ra = resolve(ctx, a, sa.clone(), &ppath, names);
        let rb = resolve(ctx, b, sb.clone(), &ppath, names);
        let (Some(ra), Some(rb)) = (ra, rb) else {
            continue;
        };
        let span = ctx.span(p.span());
        let mut any = false;
        for x in &ra {
            for y in &rb {
                if x != y && !both_box(x, y) {
                    add(out, x, y, span);
                    any = true;
                }
            }
        }
        if !any {
            ctx.error(
                p.span(),
                format!("`{ppath}` pairs two box sides"),
                Some("box sides meet along the box edges without being listed".into()),
            );
        }
    }
}

fn all(
    ctx: &mut Ctx<'_>,
    v: &Value<'_>,
    names: &Names,
    out: &mut BTreeMap<(String, String), Span>,
) {
    let Some(list) = rd::strings(ctx, v, "intersect.all") else {
        return;
    };
    let span = ctx.span(v.span());
    let mut members: Vec<String> = Vec::new();
    let mut seen: Vec<&str> = Vec::new();
    for (n, s) in &list {
        if seen.contains(&n.as_str()) {
            ctx.error(
                s.clone(),
                format!("`intersect.all` lists `{n}` twice"),
                Some("remove the repeated name".into()),
            );
            continue;
        }
        seen.push(n);
        if let Some(r) = resolve(ctx, n, s.clone(), "intersect.all", names) {
            members.extend(r);
        }
    }
    for (i, a) in members.iter().enumerate() {
        for b in members.iter().skip(i + 1) {
            if a != b && !both_box(a, b) {
                add(out, a, b, span);
            }
        }
    }
}
