//! `[regions]`: optional names and attributes for regions, each picked by a point inside it.
//! Decides legal names (as for surfaces), that points are finite and distinct, that `material`
//! is an integer and that `properties` are finite numbers with legal names, and that each point
//! lies strictly inside an explicit `[box]` (a point outside it, or on one of its sides, is in no
//! region). Which region contains the point is decided later, exactly, once the model exists.
//! At most [`MAX_PROPERTY_NAMES`] distinct property names: each is a field on every element of
//! every output, so a generated recipe with millions of them would ask for outputs (and
//! allocations) of terabytes; it is refused here, at the first name over the budget.

use std::collections::{BTreeMap, BTreeSet};

use super::surfaces::check_name;
use crate::recipe::reader::{self as rd, Ctx, Value, path_join};
use crate::recipe::spec::{BoxExtent, BoxSpec, RegionSpec};
use toml::de::DeValue;

const KEYS: &[&str] = &["point", "material", "properties"];

/// The most distinct property names a recipe may give its regions (all regions together).
pub const MAX_PROPERTY_NAMES: usize = 1024;

/// The property names seen so far, and whether going over the budget was reported (once).
#[derive(Default)]
struct PropertyNames {
    seen: BTreeSet<String>,
    refused: bool,
}

pub(crate) fn read(
    ctx: &mut Ctx<'_>,
    v: Option<&Value<'_>>,
    bbox: Option<&BoxSpec>,
) -> BTreeMap<String, RegionSpec> {
    let mut out: BTreeMap<String, RegionSpec> = BTreeMap::new();
    let Some(v) = v else { return out };
    let Some(t) = rd::as_table(ctx, v, "regions", None) else {
        return out;
    };
    let mut entries: Vec<_> = t.iter().collect();
    entries.sort_by_key(|(k, _)| k.span().start);
    // Each accepted point -> its region's name: one lookup per region, however many regions.
    let mut taken: BTreeMap<[u64; 3], String> = BTreeMap::new();
    let mut property_names = PropertyNames::default();
    for (k, e) in entries {
        let name: &str = k.get_ref();
        let path = path_join("regions", name);
        let ok = check_name(ctx, name, k.span(), "region");
        let help = format!("write `{name} = {{ point = [x, y, z], material = 1 }}`");
        let Some(rt) = rd::as_table(ctx, e, &path, Some(&help)) else {
            continue;
        };
        rd::check_keys(ctx, rt, &path, KEYS, &|_| None);
        let point = rd::required(
            ctx,
            rt,
            e.span(),
            &path,
            "point",
            "add `point = [x, y, z]`, a point inside the region",
        )
        .and_then(|p| rd::vec3(ctx, p, &path_join(&path, "point")).map(|x| (x, p.span())));
        let material = match rt.get("material") {
            Some(m) => rd::int(ctx, m, &path_join(&path, "material")).map(Some),
            None => Some(None),
        };
        let properties = match rt.get("properties") {
            Some(p) => properties(ctx, p, &path_join(&path, "properties"), &mut property_names),
            None => Some(BTreeMap::new()),
        };
        let (true, Some((point, pspan)), Some(material), Some(properties)) =
            (ok, point, material, properties)
        else {
            continue;
        };
        if let Some(b) = bbox
            && !inside_box(ctx, name, point, rt.get("point"), b)
        {
            continue;
        }
        // `+ 0.0` makes -0.0 and 0.0, equal as numbers, one key.
        let key = point.map(|c| (c + 0.0).to_bits());
        if let Some(other) = taken.get(&key).map(|n| &out[n]) {
            let msg = format!(
                "region `{name}` has the same point as region `{}` (line {})",
                other.name, other.span.line
            );
            ctx.error(
                pspan,
                msg,
                Some("each region is picked by its own point: two names cannot share one".into()),
            );
            continue;
        }
        taken.insert(key, name.to_string());
        out.insert(
            name.to_string(),
            RegionSpec {
                name: name.to_string(),
                point,
                material,
                properties,
                span: ctx.span(k.span()),
            },
        );
    }
    out
}

/// Whether `point` lies strictly inside the box when the box is explicit (an `around` box is
/// known only once the surfaces are read: the `model` step checks it then); reports it if not,
/// at the offending coordinate.
fn inside_box(
    ctx: &mut Ctx<'_>,
    name: &str,
    point: [f64; 3],
    written: Option<&Value<'_>>,
    b: &BoxSpec,
) -> bool {
    let BoxExtent::Explicit { min, max } = &b.extent else {
        return true;
    };
    let Some(i) = (0..3).find(|&i| !(min[i] < point[i] && point[i] < max[i])) else {
        return true;
    };
    let axis = ["x", "y", "z"][i];
    let at = match written.map(|w| (w.get_ref(), w.span())) {
        Some((DeValue::Array(a), s)) => a.get(i).map_or(s, |c| c.span()),
        Some((_, s)) => s,
        None => 0..0,
    };
    let fmt = |p: &[f64; 3]| format!("[{}, {}, {}]", p[0], p[1], p[2]);
    let (min_s, max_s) = (fmt(min), fmt(max));
    let c = point[i];
    let what = if c < min[i] {
        format!("{axis} = {c} is below the box's `min` {axis} = {}", min[i])
    } else if c > max[i] {
        format!("{axis} = {c} is above the box's `max` {axis} = {}", max[i])
    } else {
        let side = if c == min[i] { "min" } else { "max" };
        format!(
            "{axis} = {c} is on the box side `box.{axis}{side}`, and a point on a surface is in no region"
        )
    };
    let msg = format!(
        "region `{name}`: the point {} is outside the box {min_s}..{max_s}: {what}",
        fmt(&point)
    );
    let help = format!(
        "a region's point must be strictly inside `[box]` (line {}), {axis} between {} and {}: \
         check the coordinate for a typo or other units, then move the point into its region or \
         widen the box",
        b.span.line, min[i], max[i]
    );
    ctx.error(at, msg, Some(help));
    false
}

fn properties(
    ctx: &mut Ctx<'_>,
    v: &Value<'_>,
    path: &str,
    names: &mut PropertyNames,
) -> Option<BTreeMap<String, f64>> {
    let t = rd::as_table(
        ctx,
        v,
        path,
        Some("write `properties = { porosity = 0.2 }`"),
    )?;
    let mut out = BTreeMap::new();
    let mut ok = true;
    let mut entries: Vec<_> = t.iter().collect();
    entries.sort_by_key(|(k, _)| k.span().start);
    for (k, x) in entries {
        let name: &str = k.get_ref();
        if !check_name(ctx, name, k.span(), "property") {
            ok = false;
            continue;
        }
        if !names.seen.contains(name) && names.seen.len() == MAX_PROPERTY_NAMES {
            if !names.refused {
                ctx.error(
                    k.span(),
                    format!(
                        "property `{name}` is one name more than the {MAX_PROPERTY_NAMES} \
                         distinct property names the regions may have"
                    ),
                    Some(
                        "each property name becomes a field on every element of every output: \
                         keep the ones the simulation reads"
                            .into(),
                    ),
                );
                names.refused = true;
            }
            ok = false;
            continue;
        }
        names.seen.insert(name.to_string());
        match rd::number(ctx, x, &path_join(path, name)) {
            Some(n) => {
                out.insert(name.to_string(), n);
            }
            None => ok = false,
        }
    }
    ok.then_some(out)
}
