//! `[box]`: the model's bounding box, explicit (`min`, `max`) or around named surfaces plus a
//! margin. Decides that exactly one form is used, that `min < max` on every axis and that the
//! margin is not negative; the box's six sides become the surfaces `box.xmin` .. `box.zmax`.

use toml::de::DeValue;

use crate::recipe::reader::{self as rd, Ctx, Value, name_help};
use crate::recipe::spec::{BoxExtent, BoxSpec};

const KEYS: &[&str] = &["min", "max", "around", "margin"];

pub(crate) fn read(
    ctx: &mut Ctx<'_>,
    v: Option<&Value<'_>>,
    surfaces: &[String],
) -> Option<BoxSpec> {
    let v = v?;
    let t = rd::as_table(
        ctx,
        v,
        "box",
        Some("write `[box]` with `min = [x, y, z]` and `max = [x, y, z]`"),
    )?;
    rd::check_keys(ctx, t, "box", KEYS, &|_| None);
    let span = ctx.span(v.span());
    let explicit = t.get("min").is_some() || t.get("max").is_some();
    let around = t.get("around").is_some() || t.get("margin").is_some();
    if explicit && around {
        ctx.error(
            v.span(),
            "`[box]` mixes `min`/`max` with `around`/`margin`".into(),
            Some("give either explicit corners `min`, `max`, or `around = [surfaces]` with an optional `margin`".into()),
        );
        return None;
    }
    if around {
        let list = rd::required(
            ctx,
            t,
            v.span(),
            "box",
            "around",
            "add `around = [\"top\", \"base\"]`",
        )?;
        let names = rd::strings(ctx, list, "box.around")?;
        if names.is_empty() {
            ctx.error(
                list.span(),
                "`box.around` is empty".into(),
                Some("name at least one surface".into()),
            );
            return None;
        }
        let mut ok = true;
        let mut seen: Vec<&str> = Vec::new();
        for (n, s) in &names {
            if !surfaces.iter().any(|x| x == n) {
                let help = name_help(n, surfaces.iter().map(String::as_str));
                ctx.error(
                    s.clone(),
                    format!("`box.around` names unknown surface `{n}`"),
                    help,
                );
                ok = false;
            } else if seen.contains(&n.as_str()) {
                ctx.error(s.clone(), format!("`box.around` lists `{n}` twice"), None);
                ok = false;
            }
            seen.push(n);
        }
        let margin = match t.get("margin") {
            None => Some([0.0; 3]),
            Some(m) => margin(ctx, m),
        };
        let margin = margin?;
        if !ok {
            return None;
        }
        let surfaces = names.into_iter().map(|(n, _)| n).collect();
        return Some(BoxSpec {
            extent: BoxExtent::Around { surfaces, margin },
            span,
        });
    }
    let min = rd::required(ctx, t, v.span(), "box", "min", "add `min = [x, y, z]`")
        .and_then(|m| rd::vec3(ctx, m, "box.min"));
    let max = rd::required(ctx, t, v.span(), "box", "max", "add `max = [x, y, z]`")
        .and_then(|m| rd::vec3(ctx, m, "box.max"));
    let (min, max) = (min?, max?);
    let mut ok = true;
    for (i, axis) in ["x", "y", "z"].iter().enumerate() {
        if min[i] >= max[i] {
            // Point at the offending coordinate of `max`.
            let at = match t.get("max").map(|m| (m.get_ref(), m.span())) {
                Some((DeValue::Array(a), _)) if a.len() == 3 => {
                    a.get(i).map_or(v.span(), |c| c.span())
                }
                Some((_, s)) => s,
                None => v.span(),
            };
            ctx.error(
                at,
                format!(
                    "box `min` {axis} = {} is not less than `max` {axis} = {}",
                    min[i], max[i]
                ),
                Some("`min` must be the low corner and `max` the high corner on every axis".into()),
            );
            ok = false;
        }
    }
    ok.then_some(BoxSpec {
        extent: BoxExtent::Explicit { min, max },
        span,
    })
}

fn margin(ctx: &mut Ctx<'_>, m: &Value<'_>) -> Option<[f64; 3]> {
    let xyz = match m.get_ref() {
        DeValue::Array(_) => rd::vec3(ctx, m, "box.margin")?,
        _ => {
            let x = rd::number(ctx, m, "box.margin")?;
            [x; 3]
        }
    };
    if xyz.iter().any(|x| *x < 0.0) {
        ctx.error(
            m.span(),
            format!(
                "`box.margin` = `{}` must not be negative",
                ctx.text(m.span())
            ),
            None,
        );
        return None;
    }
    Some(xyz)
}
