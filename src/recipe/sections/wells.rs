//! `[wells]`: well name -> path file. Decides which names are legal (those of surfaces, and not
//! a surface's own name, so every output group has one meaning), the format from the extension
//! (`.wl` Well, `.pl` PLine), and the options: `object`, the target edge length `size`, the
//! `regions` it is embedded in (names from `[regions]`; by default every region it crosses), and
//! the cross-section `area` of its line elements (for the formats that need a section).

use std::collections::BTreeMap;
use std::ops::Range;
use std::path::{Path, PathBuf};

use toml::de::DeValue;

use super::file_table;
use super::surfaces::{check_name, object};
use crate::recipe::diagnostic::did_you_mean;
use crate::recipe::reader::{self as rd, Ctx, Value, name_help, path_join};
use crate::recipe::spec::{WellFormat, WellSpec};

const KEYS: &[&str] = &["file", "object", "size", "regions", "area"];

pub(crate) fn read(
    ctx: &mut Ctx<'_>,
    v: Option<&Value<'_>>,
    base_dir: &Path,
    surfaces: &[String],
    regions: &[String],
) -> BTreeMap<String, WellSpec> {
    let mut out = BTreeMap::new();
    let Some(v) = v else { return out };
    let Some(t) = rd::as_table(ctx, v, "wells", None) else {
        return out;
    };
    for (k, e) in t.iter() {
        let name: &str = k.get_ref();
        let path = path_join("wells", name);
        let mut ok = check_name(ctx, name, k.span(), "well");
        if ok && surfaces.iter().any(|s| s == name) {
            ctx.error(
                k.span(),
                format!("well name `{name}` is also a surface name"),
                Some(format!(
                    "outputs group elements by name: rename the well, e.g. `well_{name}`"
                )),
            );
            ok = false;
        }
        if let DeValue::String(file) = e.get_ref() {
            if let (true, Some(format)) = (ok, well_format(ctx, file, e)) {
                let spec = spec(ctx, base_dir, (name, k.span()), (file, e.span()), format);
                out.insert(name.to_string(), spec);
            }
            continue;
        }
        let example = format!("write `{name} = {{ file = \"data/{name}.wl\", size = 50.0 }}`");
        let file_help = "add `file = \"path/to/well.wl\"` (relative to the recipe)";
        let Some((st, file)) = file_table(ctx, e, &path, KEYS, (&example, file_help), well_format)
        else {
            continue;
        };
        let object = match st.get("object") {
            Some(x) => object(ctx, x, &path_join(&path, "object")).map(Some),
            None => Some(None),
        };
        let size = match st.get("size") {
            Some(x) => rd::size(ctx, x, &path_join(&path, "size")).map(Some),
            None => Some(None),
        };
        let within = match st.get("regions") {
            Some(x) => region_list(ctx, x, &path_join(&path, "regions"), regions).map(Some),
            None => Some(None),
        };
        let area = match st.get("area") {
            Some(x) => rd::number_above(
                ctx,
                x,
                &path_join(&path, "area"),
                0.0,
                "a cross-section area greater than 0 (model units squared)",
            )
            .map(Some),
            None => Some(None),
        };
        if let (
            true,
            Some((file, format, fspan)),
            Some(object),
            Some(size),
            Some(within),
            Some(area),
        ) = (ok, file, object, size, within, area)
        {
            let mut spec = spec(ctx, base_dir, (name, k.span()), (&file, fspan), format);
            spec.object = object;
            spec.size = size;
            spec.regions = within;
            spec.area = area;
            out.insert(name.to_string(), spec);
        }
    }
    out
}

/// A spec with every option at its default.
fn spec(
    ctx: &Ctx<'_>,
    base_dir: &Path,
    (name, name_span): (&str, Range<usize>),
    (file, file_span): (&str, Range<usize>),
    format: WellFormat,
) -> WellSpec {
    let file = PathBuf::from(file);
    WellSpec {
        name: name.to_string(),
        path: base_dir.join(&file),
        file,
        format,
        object: None,
        size: None,
        regions: None,
        area: None,
        span: ctx.span(name_span),
        file_span: ctx.span(file_span),
    }
}

/// `regions = ["a", "b"]`: non-empty, each a `[regions]` name, no repeats; sorted.
fn region_list(
    ctx: &mut Ctx<'_>,
    v: &Value<'_>,
    path: &str,
    regions: &[String],
) -> Option<Vec<String>> {
    let names = rd::strings(ctx, v, path)?;
    if names.is_empty() {
        ctx.error(
            v.span(),
            format!("`{path}` is empty: the well would be embedded nowhere"),
            Some("name the regions it is embedded in, or leave `regions` out for all".into()),
        );
        return None;
    }
    let mut ok = true;
    for (n, span) in &names {
        if !regions.iter().any(|r| r == n) {
            let help = name_help(n, regions.iter().map(String::as_str)).or_else(|| {
                Some("name the region in `[regions]` with a point inside it first".into())
            });
            ctx.error(
                span.clone(),
                format!("`{path}` names unknown region `{n}`"),
                help,
            );
            ok = false;
        }
    }
    let mut out: Vec<String> = names.into_iter().map(|(n, _)| n).collect();
    out.sort();
    let n = out.len();
    out.dedup();
    if out.len() != n {
        ctx.error(v.span(), format!("`{path}` names a region twice"), None);
        ok = false;
    }
    ok.then_some(out)
}

fn well_format(ctx: &mut Ctx<'_>, file: &str, v: &Value<'_>) -> Option<WellFormat> {
    let ext = Path::new(file)
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("wl") => Some(WellFormat::Well),
        Some("pl") => Some(WellFormat::PLine),
        other => {
            let msg = match other {
                Some(e) => format!(
                    "well file `{file}` has extension `.{e}`, which is not a gOcad well or line"
                ),
                None => format!("well file `{file}` has no extension: cannot tell its format"),
            };
            let kinds = "wells are gOcad Well `.wl` or PLine `.pl` files";
            let help = match other.and_then(|e| did_you_mean(e, ["wl", "pl"])) {
                Some(c) => format!("did you mean `.{c}`? {kinds}"),
                None => kinds.to_string(),
            };
            ctx.error(v.span(), msg, Some(help));
            None
        }
    }
}
