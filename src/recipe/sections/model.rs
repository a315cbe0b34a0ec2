//! `[model]` (name and units) and `[tolerances]` (the fields of `crate::geom::Tolerances`).
//! Decides that the model name is a portable file-name stem and that every tolerance is in its
//! documented range.

use toml::de::DeTable;

use crate::geom::Tolerances;
use crate::recipe::reader::{self as rd, Ctx, Value};
use crate::recipe::spec::{ModelSpec, Units};

const MODEL_KEYS: &[&str] = &["name", "units"];

pub(crate) fn read_model(
    ctx: &mut Ctx<'_>,
    root: &DeTable<'_>,
    root_span: std::ops::Range<usize>,
) -> Option<ModelSpec> {
    let v = rd::required(
        ctx,
        root,
        root_span,
        "",
        "model",
        "add `[model]` with `name = \"...\"`",
    )?;
    let t = rd::as_table(ctx, v, "model", None)?;
    rd::check_keys(ctx, t, "model", MODEL_KEYS, &|_| None);
    let name = rd::required(
        ctx,
        t,
        v.span(),
        "model",
        "name",
        "add `name = \"my_model\"`",
    )
    .and_then(|n| {
        let s = rd::string(ctx, n, "model.name")?;
        if s.trim().is_empty() {
            ctx.error(
                n.span(),
                "`model.name` must not be empty".into(),
                Some("e.g. `name = \"didactic\"`".into()),
            );
            return None;
        }
        // The name becomes part of output file names: keep it to a portable character set.
        super::surfaces::check_name(ctx, s, n.span(), "model").then(|| s.to_string())
    });
    let units = match t.get("units") {
        Some(u) => rd::choice(
            ctx,
            u,
            "model.units",
            &[
                ("m", Units::Metre),
                ("km", Units::Kilometre),
                ("ft", Units::Foot),
            ],
        ),
        None => Some(Units::Metre),
    };
    Some(ModelSpec {
        name: name?,
        units: units?,
        span: ctx.span(v.span()),
    })
}

pub(crate) fn read_tolerances(ctx: &mut Ctx<'_>, v: Option<&Value<'_>>) -> Tolerances {
    let mut tol = Tolerances::default();
    let Some(v) = v else { return tol };
    let Some(t) = rd::as_table(ctx, v, "tolerances", None) else {
        return tol;
    };
    // The fields handled below; a field added to `Tolerances` must be added here too.
    rd::check_keys(
        ctx,
        t,
        "tolerances",
        &["kink_angle_deg", "merge_distance", "support_distance_rel"],
        &|_| None,
    );
    if let Some(x) = t.get("kink_angle_deg") {
        let path = "tolerances.kink_angle_deg";
        if let Some(a) = rd::number(ctx, x, path) {
            if a > 0.0 && a < 180.0 {
                tol.kink_angle_deg = a;
            } else {
                let msg = format!(
                    "`{path}` = `{}` must be between 0 and 180 degrees (exclusive)",
                    ctx.text(x.span())
                );
                ctx.error(x.span(), msg, None);
            }
        }
    }
    if let Some(x) = t.get("merge_distance") {
        let path = "tolerances.merge_distance";
        if let Some(d) = rd::number(ctx, x, path) {
            if d >= 0.0 {
                tol.merge_distance = d;
            } else {
                let msg = format!("`{path}` = `{}` must be 0 or more", ctx.text(x.span()));
                ctx.error(x.span(), msg, None);
            }
        }
    }
    if let Some(x) = t.get("support_distance_rel")
        && let Some(d) = rd::size(ctx, x, "tolerances.support_distance_rel")
    {
        tol.support_distance_rel = d;
    }
    tol
}
