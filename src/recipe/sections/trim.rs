//! `[[trim]]`: which patches to discard after splitting, in recipe order (patches outside the box
//! are always discarded and need no entry). Each entry selects surfaces and gives exactly one
//! action: keep one side of a named surface (above or below it, or inside or outside a closed
//! one), or discard the patch containing / nearest a point,
//! or every patch below an area, or every patch lying within a distance of another surface.

use super::Names;
use crate::recipe::reader::{self as rd, Ctx, Value, name_help};
use crate::recipe::selector::SurfaceSelector;
use crate::recipe::spec::{Side, TrimAction, TrimSpec};

const KEYS: &[&str] = &["surface", "keep", "discard"];
const KEEP_KEYS: &[&str] = &["above", "below", "inside", "outside"];
const DISCARD_KEYS: &[&str] = &["containing", "nearest", "area_below", "within"];

pub(crate) fn read(ctx: &mut Ctx<'_>, v: Option<&Value<'_>>, names: &Names) -> Vec<TrimSpec> {
    let mut out = Vec::new();
    let Some(v) = v else { return out };
    let Some(list) = rd::array(ctx, v, "trim", "an array of tables, written `[[trim]]`") else {
        return out;
    };
    for (i, e) in list.iter().enumerate() {
        let path = format!("trim[{i}]");
        let Some(t) = rd::as_table(ctx, e, &path, Some("write each trim as a `[[trim]]` table"))
        else {
            continue;
        };
        rd::check_keys(ctx, t, &path, KEYS, &|_| None);
        let surface = rd::required(
            ctx,
            t,
            e.span(),
            &path,
            "surface",
            "add `surface = \"f2\"` (a name or glob)",
        )
        .and_then(|s| {
            let text = rd::string(ctx, s, &format!("{path}.surface"))?;
            names
                .check_pattern(ctx, text, text, s.span(), "trim surface")
                .then(|| SurfaceSelector::new(text))
        });
        let action = match (t.get("keep"), t.get("discard")) {
            (Some(_), Some(d)) => {
                ctx.error(
                    d.span(),
                    format!("`{path}` has both `keep` and `discard`"),
                    Some(
                        "give one action per `[[trim]]`; add another `[[trim]]` for the second"
                            .into(),
                    ),
                );
                None
            }
            (None, None) if ctx.had_unknown_key(t) => None,
            (None, None) => {
                ctx.error(e.span(), format!("`{path}` has no action"), Some("add `keep = { below = \"top\" }` or `discard = { containing = [x, y, z] }`".into()));
                None
            }
            (Some(k), None) => keep(ctx, k, &format!("{path}.keep"), names, surface.as_ref()),
            (None, Some(d)) => discard(ctx, d, &format!("{path}.discard")),
        };
        if let (Some(surface), Some(action)) = (surface, action) {
            out.push(TrimSpec {
                surface,
                action,
                span: ctx.span(e.span()),
            });
        }
    }
    out
}

/// The one key of an action table, or an error.
fn single<'a, 'i>(
    ctx: &mut Ctx<'_>,
    v: &'a Value<'i>,
    path: &str,
    valid: &[&str],
    example: &str,
) -> Option<(&'a str, &'a Value<'i>)> {
    let t = rd::as_table(ctx, v, path, Some(example))?;
    rd::check_keys(ctx, t, path, valid, &|_| None);
    let known: Vec<_> = t
        .iter()
        .filter(|(k, _)| valid.contains(&k.get_ref().as_ref()))
        .collect();
    match known.as_slice() {
        [(k, x)] => Some((k.get_ref().as_ref(), *x)),
        [] => {
            if !ctx.had_unknown_key(t) {
                ctx.error(
                    v.span(),
                    format!("`{path}` is empty"),
                    Some(example.to_string()),
                );
            }
            None
        }
        _ => {
            ctx.error(
                v.span(),
                format!(
                    "`{path}` gives {} conditions; give exactly one",
                    known.len()
                ),
                Some("use one `[[trim]]` per condition".into()),
            );
            None
        }
    }
}

fn keep(
    ctx: &mut Ctx<'_>,
    v: &Value<'_>,
    path: &str,
    names: &Names,
    trimmed: Option<&SurfaceSelector>,
) -> Option<TrimAction> {
    let (k, x) = single(ctx, v, path, KEEP_KEYS, "e.g. `keep = { below = \"top\" }`")?;
    let side = match k {
        "above" => Side::Above,
        "below" => Side::Below,
        "inside" => Side::Inside,
        _ => Side::Outside,
    };
    let of = rd::string(ctx, x, &format!("{path}.{k}"))?;
    if !names.is_known(of) {
        let help = name_help(of, names.all());
        ctx.error(
            x.span(),
            format!("`{path}.{k}` names unknown surface `{of}`"),
            help,
        );
        return None;
    }
    if trimmed.is_some_and(|s| s.is_exact() && s.pattern == of) {
        ctx.error(
            x.span(),
            format!("`{path}.{k}` refers to the trimmed surface `{of}` itself"),
            Some("name another surface that cuts it".into()),
        );
        return None;
    }
    Some(TrimAction::Keep {
        side,
        of: of.to_string(),
    })
}

fn discard(ctx: &mut Ctx<'_>, v: &Value<'_>, path: &str) -> Option<TrimAction> {
    let (k, x) = single(
        ctx,
        v,
        path,
        DISCARD_KEYS,
        "e.g. `discard = { containing = [x, y, z] }`",
    )?;
    let p = format!("{path}.{k}");
    match k {
        "containing" => rd::vec3(ctx, x, &p).map(TrimAction::DiscardContaining),
        "nearest" => rd::vec3(ctx, x, &p).map(TrimAction::DiscardNearest),
        "area_below" => rd::size(ctx, x, &p).map(TrimAction::DiscardAreaBelow),
        _ => rd::size(ctx, x, &p).map(TrimAction::DiscardWithin),
    }
}
