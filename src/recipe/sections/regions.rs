//! `[regions]`: optional names and attributes for regions, each picked by a point inside it.
//! Decides legal names (as for surfaces), that points are finite and distinct, that `material`
//! is an integer and that `properties` are finite numbers with legal names. Which region
//! contains the point is decided later, exactly, once the model exists.

use std::collections::BTreeMap;

use super::surfaces::check_name;
use crate::recipe::reader::{self as rd, Ctx, Value, path_join};
use crate::recipe::spec::RegionSpec;

const KEYS: &[&str] = &["point", "material", "properties"];

pub(crate) fn read(ctx: &mut Ctx<'_>, v: Option<&Value<'_>>) -> BTreeMap<String, RegionSpec> {
    let mut out: BTreeMap<String, RegionSpec> = BTreeMap::new();
    let Some(v) = v else { return out };
    let Some(t) = rd::as_table(ctx, v, "regions", None) else {
        return out;
    };
    let mut entries: Vec<_> = t.iter().collect();
    entries.sort_by_key(|(k, _)| k.span().start);
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
            Some(p) => properties(ctx, p, &path_join(&path, "properties")),
            None => Some(BTreeMap::new()),
        };
        let (true, Some((point, pspan)), Some(material), Some(properties)) =
            (ok, point, material, properties)
        else {
            continue;
        };
        if let Some(other) = out.values().find(|r| r.point == point) {
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

fn properties(ctx: &mut Ctx<'_>, v: &Value<'_>, path: &str) -> Option<BTreeMap<String, f64>> {
    let t = rd::as_table(
        ctx,
        v,
        path,
        Some("write `properties = { porosity = 0.2 }`"),
    )?;
    let mut out = BTreeMap::new();
    let mut ok = true;
    for (k, x) in t.iter() {
        let name: &str = k.get_ref();
        if !check_name(ctx, name, k.span(), "property") {
            ok = false;
            continue;
        }
        match rd::number(ctx, x, &path_join(path, name)) {
            Some(n) => {
                out.insert(name.to_string(), n);
            }
            None => ok = false,
        }
    }
    ok.then_some(out)
}
