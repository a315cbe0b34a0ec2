//! One reader per recipe section, each turning its part of the spanned TOML tree into typed
//! specs and reporting every problem it finds. Sections that refer to names (selectors,
//! intersections, trims, region sizes) resolve them against [`Names`], built from `[surfaces]`
//! and `[box]` first.

pub(crate) mod bbox;
pub(crate) mod groups;
pub(crate) mod intersect;
pub(crate) mod mesh;
pub(crate) mod model;
pub(crate) mod output;
pub(crate) mod refine;
pub(crate) mod regions;
pub(crate) mod surfaces;
pub(crate) mod trim;
pub(crate) mod wells;

use std::ops::Range;

use super::reader::{self as rd, Ctx, Value, name_help, path_join};
use super::selector::{SurfaceSelector, is_glob};
use super::spec::BOX_SIDES;
use toml::de::DeTable;

/// The surface names a selector or a reference may use: the `[surfaces]` keys, plus the six
/// box sides when a `[box]` is given.
pub(crate) struct Names {
    pub surfaces: Vec<String>,
    pub has_box: bool,
}

impl Names {
    /// Every known name, sorted: surfaces then box sides.
    pub fn all(&self) -> Vec<&str> {
        let mut v: Vec<&str> = self.surfaces.iter().map(String::as_str).collect();
        if self.has_box {
            v.extend(BOX_SIDES);
        }
        v
    }

    pub fn is_known(&self, name: &str) -> bool {
        self.surfaces.iter().any(|s| s == name) || (self.has_box && BOX_SIDES.contains(&name))
    }

    /// Checks that a name or glob matches at least one known surface; reports it otherwise.
    /// `whole` is the full text the pattern came from (for the message), `span` its location.
    pub fn check_pattern(
        &self,
        ctx: &mut Ctx<'_>,
        pattern: &str,
        whole: &str,
        span: Range<usize>,
        what: &str,
    ) -> bool {
        let sel = SurfaceSelector::new(pattern);
        let all = self.all();
        if all.iter().any(|n| sel.matches(n)) {
            return true;
        }
        let mut candidates: Vec<&str> = all.clone();
        if self.has_box {
            candidates.push("box.*");
        }
        let help = if pattern.starts_with("box") && !self.has_box {
            Some(
                "the box sides `box.xmin` .. `box.zmax` exist only when a `[box]` is given"
                    .to_string(),
            )
        } else {
            name_help(pattern, candidates.iter().copied()).or_else(|| {
                Some(format!(
                    "known surfaces: {}",
                    all.iter()
                        .map(|n| format!("`{n}`"))
                        .collect::<Vec<_>>()
                        .join(", ")
                ))
            })
        };
        let kind = if is_glob(pattern) { "pattern" } else { "name" };
        let msg = if pattern == whole {
            format!("{what} `{pattern}` matches no surface")
        } else {
            format!("{kind} `{pattern}` in {what} `{whole}` matches no surface")
        };
        // Underline just the offending side when it can be found in the written key.
        let span = if pattern == whole {
            span
        } else {
            side_span(ctx, span, pattern)
        };
        ctx.error(span, msg, help);
        false
    }
}

/// The span of the side `pattern` inside a written curve selector key (`"top/f1#2"`), or the
/// whole key when the side cannot be located (e.g. written with escapes).
fn side_span(ctx: &Ctx<'_>, key: Range<usize>, pattern: &str) -> Range<usize> {
    let written = ctx.src.slice(ctx.span(key.clone()));
    let mut offset = 0;
    for (i, part) in written.split('/').enumerate() {
        let mut core = part;
        let mut lead = 0;
        if i == 0 {
            let t = core.trim_start_matches(['"', '\'']);
            lead = core.len() - t.len();
            core = t;
        }
        let core = core.trim_end_matches(['"', '\'']);
        let core = core.split('#').next().unwrap_or(core);
        if core == pattern {
            let start = key.start + offset + lead;
            return start..start + pattern.len();
        }
        offset += part.len() + 1;
    }
    key
}

/// The curve selector `text` (written at `span`), each side checked against the surfaces;
/// `None` after reporting what is wrong.
pub(crate) fn curve_selector(
    ctx: &mut Ctx<'_>,
    text: &str,
    span: Range<usize>,
    names: &Names,
) -> Option<super::selector::CurveSelector> {
    match super::selector::CurveSelector::parse(text) {
        Ok(s) => {
            let mut ok = true;
            for side in &s.sides {
                ok &= names.check_pattern(ctx, &side.pattern, text, span.clone(), "curve selector");
            }
            ok.then_some(s)
        }
        Err(err) => {
            ctx.error(
                span,
                format!("bad curve selector `{text}`: {err}"),
                Some("e.g. `\"top/f1\"`, `\"f1/box.*\"`, `\"top\"` or `\"top/f1#2\"`".into()),
            );
            None
        }
    }
}

/// The file of a `{ file = "...", … }` entry, with its format (read by `format`) and span.
pub(crate) type FileOf<T> = Option<(String, T, Range<usize>)>;

/// A `name = { file = "...", … }` entry at `path`: the table, its keys checked against `keys`,
/// and its `file` (`None` when missing or bad, reported with `file_help`). `None` when the entry
/// is not a table, reported with `example` as the help.
pub(crate) fn file_table<'a, 'i, T>(
    ctx: &mut Ctx<'_>,
    e: &'a Value<'i>,
    path: &str,
    keys: &[&str],
    (example, file_help): (&str, &str),
    format: impl Fn(&mut Ctx<'_>, &str, &Value<'_>) -> Option<T>,
) -> Option<(&'a DeTable<'i>, FileOf<T>)> {
    let st = rd::as_table(ctx, e, path, Some(example))?;
    rd::check_keys(ctx, st, path, keys, &|_| None);
    let file = rd::required(ctx, st, e.span(), path, "file", file_help).and_then(|f| {
        let s = rd::string(ctx, f, &path_join(path, "file"))?;
        let fmt = format(ctx, s, f)?;
        Some((s.to_string(), fmt, f.span()))
    });
    Some((st, file))
}
