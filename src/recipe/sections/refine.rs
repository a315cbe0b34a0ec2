//! `[[mesh.refine]]`: finer elements near a feature of the model — every patch of the surfaces a
//! selector matches, every curve a curve selector matches, or one point — with the size at the
//! feature, the distance over which it grows, and the size it grows to (`far`, by default the
//! global size), in recipe order.

use super::Names;
use crate::recipe::reader::{self as rd, Ctx, Value, path_join};
use crate::recipe::selector::SurfaceSelector;
use crate::recipe::spec::{RefineSpec, RefineTarget};
use toml::de::DeTable;

const KEYS: &[&str] = &["surface", "curve", "point", "size", "distance", "far"];
const TARGETS: [&str; 3] = ["surface", "curve", "point"];

pub(crate) fn read(
    ctx: &mut Ctx<'_>,
    v: &Value<'_>,
    names: &Names,
    global_size: f64,
) -> Vec<RefineSpec> {
    let mut out = Vec::new();
    let Some(list) = rd::array(
        ctx,
        v,
        "mesh.refine",
        "an array of tables, `[[mesh.refine]]`",
    ) else {
        return out;
    };
    for (i, e) in list.iter().enumerate() {
        let path = format!("mesh.refine[{i}]");
        let help = Some("write each as a `[[mesh.refine]]` table".to_string());
        let Some(t) = rd::as_table(ctx, e, &path, help.as_deref()) else {
            continue;
        };
        rd::check_keys(ctx, t, &path, KEYS, &|_| None);
        let near = target(ctx, t, e.span(), &path, names);
        let size = rd::required(ctx, t, e.span(), &path, "size", "add `size = 20.0`")
            .and_then(|s| rd::size(ctx, s, &path_join(&path, "size")));
        let distance = rd::required(
            ctx,
            t,
            e.span(),
            &path,
            "distance",
            "add `distance = 500.0`, how far from the feature the size grows to `far`",
        )
        .and_then(|s| rd::size(ctx, s, &path_join(&path, "distance")));
        let far = match t.get("far") {
            Some(f) => rd::size(ctx, f, &path_join(&path, "far")).map(|x| (x, Some(f))),
            None => Some((global_size, None)),
        };
        let (Some(near), Some(size), Some(distance), Some((far, far_at))) =
            (near, size, distance, far)
        else {
            continue;
        };
        if far <= size {
            let at = far_at.map_or(e.span(), |f| f.span());
            ctx.error(
                at,
                format!("`{path}.far` = {far} is not larger than `{path}.size` = {size}"),
                Some(
                    "`far` is the size the refinement grows back to, away from the feature".into(),
                ),
            );
            continue;
        }
        out.push(RefineSpec {
            near,
            size,
            distance,
            far,
            span: ctx.span(e.span()),
        });
    }
    out
}

/// The one feature an entry names.
fn target(
    ctx: &mut Ctx<'_>,
    t: &DeTable<'_>,
    span: std::ops::Range<usize>,
    path: &str,
    names: &Names,
) -> Option<RefineTarget> {
    let given: Vec<&str> = TARGETS
        .into_iter()
        .filter(|k| t.get(*k).is_some())
        .collect();
    if given.len() != 1 {
        ctx.error(
            span,
            format!(
                "`{path}` must name exactly one feature: `surface`, `curve` or `point` (it has {})",
                if given.is_empty() {
                    "none".to_string()
                } else {
                    given.join(", ")
                }
            ),
            Some("e.g. `surface = \"F1\"`, `curve = \"F1/H1\"` or `point = [x, y, z]`".into()),
        );
        return None;
    }
    let key = given[0];
    let v = t.get(key)?;
    let at = path_join(path, key);
    match key {
        "surface" => {
            let text = rd::string(ctx, v, &at)?;
            names
                .check_pattern(ctx, text, text, v.span(), "refine surface")
                .then(|| RefineTarget::Surface(SurfaceSelector::new(text)))
        }
        "curve" => {
            let text = rd::string(ctx, v, &at)?;
            super::curve_selector(ctx, text, v.span(), names).map(RefineTarget::Curve)
        }
        _ => rd::vec3(ctx, v, &at).map(RefineTarget::Point),
    }
}
