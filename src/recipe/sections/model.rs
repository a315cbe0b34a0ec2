//! `[model]` (name, units and whether the surfaces are sealed) and `[tolerances]` (the fields of `geom::Tolerances`).
//! Decides that the model name is a portable file-name stem and that every tolerance is in its
//! documented range.

use toml::de::DeTable;

use crate::recipe::reader::{self as rd, Ctx, Value};
use crate::recipe::spec::{ModelSpec, Units};
use geom::Tolerances;

const MODEL_KEYS: &[&str] = &["name", "units", "sealed"];

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
        // The name becomes part of output file names: keep it to a portable character set, and
        // let it make no hidden file (`.x.msh`, `..msh`).
        if !super::surfaces::check_name(ctx, s, n.span(), "model") {
            return None;
        }
        if s.starts_with('.') {
            ctx.error(
                n.span(),
                format!("`model.name` `{s}` starts with `.`, which makes hidden output files (`{s}.msh`)"),
                Some(format!("e.g. `name = \"{}\"`", portable(s.trim_start_matches('.')))),
            );
            return None;
        }
        Some(s.to_string())
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
    let sealed = match t.get("sealed") {
        Some(x) => rd::boolean(ctx, x, "model.sealed"),
        None => Some(false),
    };
    Some(ModelSpec {
        name: name?,
        units: units?,
        sealed: sealed?,
        span: ctx.span(v.span()),
    })
}

/// The range each known tolerance must lie in (lower bound, inclusive?, upper bound), checked
/// here so the message can name the field; a field added to `Tolerances` later is accepted as
/// any finite number until a range is added here.
fn range(field: &str) -> Option<(f64, bool, f64)> {
    match field {
        "kink_angle_deg" => Some((0.0, false, 180.0)),
        "crease_angle_deg" => Some((0.0, false, 180.0)),
        "chart_angle_deg" => Some((0.0, false, 90.0)),
        "merge_distance" => Some((0.0, true, f64::INFINITY)),
        "support_distance_rel" => Some((0.0, false, f64::INFINITY)),
        "conformity_rel" => Some((0.0, true, 1.0)),
        _ => None,
    }
}

/// `[tolerances]`: every field of `Tolerances` (as listed by `Tolerances::fields`) may be given;
/// values are set through `Tolerances`' own deserializer, so fields added to the struct are
/// picked up without touching the recipe code.
pub(crate) fn read_tolerances(ctx: &mut Ctx<'_>, v: Option<&Value<'_>>) -> Tolerances {
    let tol = Tolerances::default();
    let Some(v) = v else { return tol };
    let Some(t) = rd::as_table(ctx, v, "tolerances", None) else {
        return tol;
    };
    let fields = tol.fields();
    let names: Vec<&str> = fields.iter().map(|(n, _)| *n).collect();
    rd::check_keys(ctx, t, "tolerances", &names, &|_| None);
    let mut given = toml::Table::new();
    for name in &names {
        let Some(x) = t.get(*name) else { continue };
        let path = format!("tolerances.{name}");
        let Some(value) = rd::number(ctx, x, &path) else {
            continue;
        };
        if let Some((lo, lo_incl, hi)) = range(name) {
            let above = if lo_incl { value >= lo } else { value > lo };
            if !above || value >= hi {
                let bound = match (lo_incl, hi.is_finite()) {
                    (_, true) => format!("between {lo} and {hi} (exclusive)"),
                    (true, false) => format!("{lo} or more"),
                    (false, false) => format!("greater than {lo}"),
                };
                let msg = format!("`{path}` = `{}` must be {bound}", ctx.text(x.span()));
                ctx.error(x.span(), msg, None);
                continue;
            }
        }
        given.insert(name.to_string(), toml::Value::Float(value));
    }
    match toml::Value::Table(given).try_into::<Tolerances>() {
        Ok(tol) => tol,
        Err(e) => {
            let msg = format!("`tolerances` could not be applied: {}", e.message());
            ctx.error(v.span(), msg, None);
            tol
        }
    }
}

/// `name` made a name the recipe accepts, for a suggestion.
fn portable(name: &str) -> String {
    let s: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' {
                c
            } else {
                '_'
            }
        })
        .collect();
    if s.is_empty() { "model".to_string() } else { s }
}
