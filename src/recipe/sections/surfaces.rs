//! `[surfaces]`: surface name -> import. Decides which names are legal (letters, digits, `_ . -`;
//! nothing starting with `box`, which is reserved for the box sides), the import format from the
//! file extension, and the per-import options with their defaults.

use std::collections::BTreeMap;
use std::ops::Range;
use std::path::{Path, PathBuf};

use toml::de::DeValue;

use super::file_table;
use crate::recipe::diagnostic::did_you_mean;
use crate::recipe::reader::{self as rd, Ctx, Value, path_join};
use crate::recipe::selector::valid_name_char;
use crate::recipe::spec::{ImportFormat, OnInvalid, SurfaceSpec};
use geom::mesh::SurfaceKind;
use gocad::import::ObjectRef;
use surface_mesh::{MAX_LEVELS, MAX_PASSES, SupportSmoothing};

const KEYS: &[&str] = &[
    "file",
    "kind",
    "object",
    "retriangulate",
    "smooth",
    "on_invalid",
    "skip_other_types",
];

/// Checks a user-chosen name (surface or region); reports and returns false when illegal.
pub(crate) fn check_name(
    ctx: &mut Ctx<'_>,
    name: &str,
    span: std::ops::Range<usize>,
    what: &str,
) -> bool {
    if name.is_empty() {
        ctx.error(
            span,
            format!("empty {what} name"),
            Some("names use letters, digits, `_`, `.` and `-`".into()),
        );
        return false;
    }
    if let Some(c) = name.chars().find(|c| !valid_name_char(*c)) {
        let fixed: String = name
            .chars()
            .map(|c| if valid_name_char(c) { c } else { '_' })
            .collect();
        ctx.error(
            span,
            format!("{what} name `{name}` contains `{c}`, which is not allowed"),
            Some(format!(
                "names use letters, digits, `_`, `.` and `-`; e.g. `{fixed}`"
            )),
        );
        return false;
    }
    true
}

pub(crate) fn read(
    ctx: &mut Ctx<'_>,
    v: Option<&Value<'_>>,
    base_dir: &Path,
) -> BTreeMap<String, SurfaceSpec> {
    let mut out = BTreeMap::new();
    let Some(v) = v else { return out };
    let Some(t) = rd::as_table(ctx, v, "surfaces", None) else {
        return out;
    };
    for (k, e) in t.iter() {
        let name: &str = k.get_ref();
        let path = path_join("surfaces", name);
        let mut ok = check_name(ctx, name, k.span(), "surface");
        if ok && name.starts_with("box") {
            ctx.error(
                k.span(),
                format!("surface name `{name}` is reserved: names starting with `box` denote the box sides"),
                Some(format!("rename it, e.g. `{}`", name.replacen("box", "bx", 1))),
            );
            ok = false;
        }
        if let DeValue::String(file) = e.get_ref() {
            // Shorthand: `name = "file.ts"`, every option at its default.
            if let (true, Some(format)) = (ok, import_format(ctx, file, e)) {
                let spec = spec(ctx, base_dir, (name, k.span()), (file, e.span()), format);
                out.insert(name.to_string(), spec);
            }
            continue;
        }
        let example =
            format!("write `{name} = {{ file = \"data/{name}.ts\", kind = \"horizon\" }}`");
        let file_help = "add `file = \"path/to/surface.ts\"` (relative to the recipe)";
        let Some((st, file)) =
            file_table(ctx, e, &path, KEYS, (&example, file_help), import_format)
        else {
            continue;
        };
        let kind = match st.get("kind") {
            Some(x) => rd::choice(
                ctx,
                x,
                &path_join(&path, "kind"),
                &[
                    ("horizon", SurfaceKind::Horizon),
                    ("fault", SurfaceKind::Fault),
                    ("other", SurfaceKind::Other),
                ],
            ),
            None => Some(SurfaceKind::Other),
        };
        let object = match st.get("object") {
            Some(x) => object(ctx, x, &path_join(&path, "object")).map(Some),
            None => Some(None),
        };
        let retriangulate = match st.get("retriangulate") {
            Some(x) => rd::size(ctx, x, &path_join(&path, "retriangulate")).map(Some),
            None => Some(None),
        };
        let smooth = match st.get("smooth") {
            Some(x) => smoothing(ctx, x, &path_join(&path, "smooth")),
            None => Some(None),
        };
        let on_invalid = match st.get("on_invalid") {
            Some(x) => rd::choice(
                ctx,
                x,
                &path_join(&path, "on_invalid"),
                &[("repair", OnInvalid::Repair), ("stop", OnInvalid::Stop)],
            ),
            None => Some(OnInvalid::Repair),
        };
        let skip = match st.get("skip_other_types") {
            Some(x) => rd::boolean(ctx, x, &path_join(&path, "skip_other_types")),
            None => Some(false),
        };
        if let (
            true,
            Some((file, format, fspan)),
            Some(kind),
            Some(object),
            Some(retriangulate),
            Some(smooth),
            Some(on_invalid),
            Some(skip_other_types),
        ) = (
            ok,
            file,
            kind,
            object,
            retriangulate,
            smooth,
            on_invalid,
            skip,
        ) {
            let mut spec = spec(ctx, base_dir, (name, k.span()), (&file, fspan), format);
            spec.kind = kind;
            spec.object = object;
            spec.retriangulate = retriangulate;
            spec.smooth = smooth;
            spec.on_invalid = on_invalid;
            spec.skip_other_types = skip_other_types;
            out.insert(name.to_string(), spec);
        }
    }
    out
}

/// `object`: a TSurf name (a non-empty string) or a position in the file (an integer from 1).
pub(crate) fn object(ctx: &mut Ctx<'_>, x: &Value<'_>, path: &str) -> Option<ObjectRef> {
    if let DeValue::Integer(_) = x.get_ref() {
        let k = rd::int(ctx, x, path)?;
        return match u32::try_from(k) {
            Ok(k) if k >= 1 => Some(ObjectRef::Position(k)),
            _ => {
                ctx.error(
                    x.span(),
                    format!("`{path}` = {k} is not a position in the file"),
                    Some(
                        "positions count the file's GOCAD objects from 1: `object = 1` is the \
                         first"
                            .into(),
                    ),
                );
                None
            }
        };
    }
    let s = match x.get_ref() {
        DeValue::String(s) => s,
        _ => {
            let msg = format!(
                "`{path}` must be an object name (a string) or its position in the file (an \
                 integer), found {} `{}`",
                rd::type_name(x.get_ref()),
                ctx.text(x.span())
            );
            ctx.error(x.span(), msg, None);
            return None;
        }
    };
    if s.trim().is_empty() {
        ctx.error(
            x.span(),
            format!("`{path}` must not be empty"),
            Some("remove `object` to take the file's only object of its type".into()),
        );
        return None;
    }
    Some(ObjectRef::Name(s.to_string()))
}

/// `smooth`: `true` (the default levels and passes), `false` (off), or a table
/// `{ levels = 1..=4, passes = 0..=200 }` whose missing keys take the defaults.
fn smoothing(ctx: &mut Ctx<'_>, x: &Value<'_>, path: &str) -> Option<Option<SupportSmoothing>> {
    if let DeValue::Boolean(on) = x.get_ref() {
        return Some(on.then(SupportSmoothing::default));
    }
    let t = rd::as_table(
        ctx,
        x,
        path,
        Some("e.g. `smooth = { levels = 2, passes = 10 }`"),
    )?;
    rd::check_keys(ctx, t, path, &["levels", "passes"], &|_| None);
    let mut how = SupportSmoothing::default();
    let mut ok = true;
    for (key, max, slot, min) in [
        ("levels", MAX_LEVELS, &mut how.levels, 1),
        ("passes", MAX_PASSES, &mut how.passes, 0),
    ] {
        let Some(v) = t.get(key) else { continue };
        let p = path_join(path, key);
        match rd::int(ctx, v, &p) {
            Some(n) if (i64::from(min)..=i64::from(max)).contains(&n) => *slot = n as u32,
            Some(n) => {
                ctx.error(
                    v.span(),
                    format!("`{p}` = {n} is out of range"),
                    Some(format!("use {min} to {max}")),
                );
                ok = false;
            }
            None => ok = false,
        }
    }
    ok.then_some(Some(how))
}

/// A spec with every option at its default.
fn spec(
    ctx: &Ctx<'_>,
    base_dir: &Path,
    (name, name_span): (&str, Range<usize>),
    (file, file_span): (&str, Range<usize>),
    format: ImportFormat,
) -> SurfaceSpec {
    let file = PathBuf::from(file);
    SurfaceSpec {
        name: name.to_string(),
        path: base_dir.join(&file),
        file,
        format,
        kind: SurfaceKind::Other,
        object: None,
        retriangulate: None,
        smooth: None,
        on_invalid: OnInvalid::Repair,
        skip_other_types: false,
        span: ctx.span(name_span),
        file_span: ctx.span(file_span),
    }
}

fn import_format(ctx: &mut Ctx<'_>, file: &str, v: &Value<'_>) -> Option<ImportFormat> {
    if file.trim().is_empty() {
        ctx.error(
            v.span(),
            "empty file name".into(),
            Some("e.g. `file = \"data/top.ts\"`".into()),
        );
        return None;
    }
    let ext = Path::new(file)
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("ts") => Some(ImportFormat::TSurf),
        Some("ml") => Some(ImportFormat::Model3d),
        Some("gp") => Some(ImportFormat::Group),
        other => {
            let msg = match other {
                Some(e) => format!(
                    "file `{file}` has extension `.{e}`, which is not a gOcad format this tool imports"
                ),
                None => format!("file `{file}` has no extension: cannot tell its format"),
            };
            let kinds = "imports are gOcad TSurf `.ts`, Model3d `.ml` or group `.gp` files";
            let help = match other.and_then(|e| did_you_mean(e, ["ts", "ml", "gp"])) {
                Some(c) => format!("did you mean `.{c}`? {kinds}"),
                None => kinds.to_string(),
            };
            ctx.error(v.span(), msg, Some(help));
            None
        }
    }
}
