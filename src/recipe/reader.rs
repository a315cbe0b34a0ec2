//! Typed reading of the spanned TOML tree, collecting every error instead of stopping at the first.
//!
//! The recipe is parsed by `toml` into a tree in which every key and value keeps its byte span.
//! This module decides what counts as a number, a size, a point, a name, a choice among words; it
//! reports each violation at the offending value's span, with a did-you-mean where one exists, and
//! keeps going so a user sees all their mistakes at once. Unknown keys are checked per table
//! against the keys that table accepts.

use std::ops::Range;

use toml::Spanned;
use toml::de::{DeTable, DeValue};

use super::diagnostic::{Diagnostic, SourceText, Span, did_you_mean, suggest};

pub(crate) type Value<'i> = Spanned<DeValue<'i>>;

/// Collects diagnostics while the recipe is read.
pub(crate) struct Ctx<'s> {
    pub src: &'s SourceText,
    pub diags: Vec<Diagnostic>,
    /// Tables (by address, as identity only) that had an unknown key: a missing required key
    /// there is most likely the misspelled one, already reported with its did-you-mean.
    misspelled_in: Vec<*const ()>,
}

impl<'s> Ctx<'s> {
    pub fn new(src: &'s SourceText) -> Ctx<'s> {
        Ctx {
            src,
            diags: Vec::new(),
            misspelled_in: Vec::new(),
        }
    }

    /// True when `table` had an unknown key (see `check_keys`).
    pub fn had_unknown_key(&self, table: &DeTable<'_>) -> bool {
        self.misspelled_in
            .contains(&(table as *const DeTable<'_> as *const ()))
    }

    pub fn span(&self, r: Range<usize>) -> Span {
        self.src.span(r)
    }

    pub fn error(&mut self, r: Range<usize>, message: String, help: Option<String>) {
        let span = self.src.span(r);
        self.diags.push(self.src.diagnostic(span, message, help));
    }

    /// The source text of a value, shortened for messages.
    pub fn text(&self, r: Range<usize>) -> String {
        let s = self.src.slice(self.src.span(r));
        let first = s.lines().next().unwrap_or("");
        if first.chars().count() > 40 || first.len() < s.len() {
            format!("{}...", first.chars().take(40).collect::<String>())
        } else {
            first.to_string()
        }
    }
}

/// A key path such as `mesh.curves."top/f1"`, quoting keys that are not bare TOML keys.
pub(crate) fn path_join(parent: &str, key: &str) -> String {
    let bare = !key.is_empty()
        && key
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
    let k = if bare {
        key.to_string()
    } else {
        format!("{key:?}")
    };
    if parent.is_empty() {
        k
    } else {
        format!("{parent}.{k}")
    }
}

/// Describes a TOML value's type for "expected X, found Y" messages.
pub(crate) fn type_name(v: &DeValue<'_>) -> &'static str {
    match v {
        DeValue::String(_) => "a string",
        DeValue::Integer(_) => "an integer",
        DeValue::Float(_) => "a float",
        DeValue::Boolean(_) => "a boolean",
        DeValue::Datetime(_) => "a date-time",
        DeValue::Array(_) => "an array",
        DeValue::Table(_) => "a table",
    }
}

/// Reports every key of `table` not in `valid` as unknown, with a did-you-mean.
/// `extra_help` may give a more specific hint for a key (returning `None` falls back).
pub(crate) fn check_keys(
    ctx: &mut Ctx<'_>,
    table: &DeTable<'_>,
    path: &str,
    valid: &[&str],
    extra_help: &dyn Fn(&str) -> Option<String>,
) {
    for (k, _) in table.iter() {
        let key: &str = k.get_ref();
        if valid.contains(&key) {
            continue;
        }
        let place = if path.is_empty() {
            "the recipe".to_string()
        } else {
            format!("`{path}`")
        };
        let help = extra_help(key)
            .or_else(|| misplaced(key, path))
            .or_else(|| suggest(key, valid, "valid keys are"));
        ctx.error(k.span(), format!("unknown key `{key}` in {place}"), help);
        let id = table as *const DeTable<'_> as *const ();
        if !ctx.misspelled_in.contains(&id) {
            ctx.misspelled_in.push(id);
        }
    }
}

/// A top-level table's name written inside a table: TOML puts every `key = value` after a
/// `[table]` header into that table, a classic trap.
fn misplaced(key: &str, path: &str) -> Option<String> {
    let top = [
        "model",
        "tolerances",
        "surfaces",
        "box",
        "intersect",
        "trim",
        "mesh",
        "regions",
        "output",
    ];
    let header = path.split('.').next().unwrap_or(path);
    (!path.is_empty() && top.contains(&key)).then(|| {
        format!("`{key}` belongs to the top level, but TOML puts it in `[{header}]` because it follows that header: move it above `[{header}]`, or write it as its own `[{key}]` table")
    })
}

/// The value as a table, or an error at its span.
pub(crate) fn as_table<'a, 'i>(
    ctx: &mut Ctx<'_>,
    v: &'a Value<'i>,
    path: &str,
    help: Option<&str>,
) -> Option<&'a DeTable<'i>> {
    match v.get_ref() {
        DeValue::Table(t) => Some(t),
        other => {
            let msg = format!(
                "`{path}` must be a table, found {} `{}`",
                type_name(other),
                ctx.text(v.span())
            );
            ctx.error(v.span(), msg, help.map(str::to_string));
            None
        }
    }
}

/// A required key, or an error at the table's span naming the key.
pub(crate) fn required<'a, 'i>(
    ctx: &mut Ctx<'_>,
    table: &'a DeTable<'i>,
    table_span: Range<usize>,
    path: &str,
    key: &str,
    help: &str,
) -> Option<&'a Value<'i>> {
    let v = table.get(key);
    if v.is_none() && !ctx.had_unknown_key(table) {
        let place = if path.is_empty() {
            "the recipe".to_string()
        } else {
            format!("`{path}`")
        };
        ctx.error(
            table_span,
            format!("missing key `{key}` in {place}"),
            Some(help.to_string()),
        );
    }
    v
}

fn parse_float_text(s: &str) -> Option<f64> {
    let t = s.replace('_', "");
    let (neg, body) = match t.as_bytes().first() {
        Some(b'-') => (true, &t[1..]),
        Some(b'+') => (false, &t[1..]),
        _ => (false, t.as_str()),
    };
    let x = match body {
        "nan" => f64::NAN,
        "inf" => f64::INFINITY,
        _ => body.parse::<f64>().ok()?,
    };
    Some(if neg { -x } else { x })
}

/// An integer, exactly as written (any radix), or an error.
pub(crate) fn int(ctx: &mut Ctx<'_>, v: &Value<'_>, path: &str) -> Option<i64> {
    match v.get_ref() {
        DeValue::Integer(i) => {
            let digits = i.as_str().replace('_', "");
            match i64::from_str_radix(&digits, i.radix()) {
                Ok(x) => Some(x),
                Err(_) => {
                    let msg = format!(
                        "`{path}` = `{}` does not fit in a 64-bit integer",
                        ctx.text(v.span())
                    );
                    ctx.error(v.span(), msg, None);
                    None
                }
            }
        }
        other => {
            let msg = format!(
                "`{path}` must be an integer, found {} `{}`",
                type_name(other),
                ctx.text(v.span())
            );
            let help = match other {
                DeValue::Float(_) => {
                    Some("write a whole number without a decimal point".to_string())
                }
                DeValue::String(_) => Some("write the number without quotes".to_string()),
                _ => None,
            };
            ctx.error(v.span(), msg, help);
            None
        }
    }
}

/// A finite number (integer or float), or an error. NaN and infinities are rejected here, so no
/// later stage and no cache key ever sees one.
pub(crate) fn number(ctx: &mut Ctx<'_>, v: &Value<'_>, path: &str) -> Option<f64> {
    let x = match v.get_ref() {
        DeValue::Float(f) => parse_float_text(f.as_str()),
        DeValue::Integer(_) => return int(ctx, v, path).map(|i| i as f64),
        other => {
            let msg = format!(
                "`{path}` must be a number, found {} `{}`",
                type_name(other),
                ctx.text(v.span())
            );
            let help = match other {
                DeValue::String(s) if parse_float_text(s.trim()).is_some() => {
                    Some(format!("write the number without quotes: `{}`", s.trim()))
                }
                _ => None,
            };
            ctx.error(v.span(), msg, help);
            return None;
        }
    };
    match x {
        Some(x) if x.is_finite() => Some(if x == 0.0 { 0.0 } else { x }),
        _ => {
            let msg = format!("`{path}` = `{}` is not a finite number", ctx.text(v.span()));
            ctx.error(
                v.span(),
                msg,
                Some("use a finite value such as `100.0`".to_string()),
            );
            None
        }
    }
}

/// A finite number strictly greater than `min` (`min` = 0 for sizes).
pub(crate) fn number_above(
    ctx: &mut Ctx<'_>,
    v: &Value<'_>,
    path: &str,
    min: f64,
    what: &str,
) -> Option<f64> {
    let x = number(ctx, v, path)?;
    if x > min {
        Some(x)
    } else {
        let msg = format!("`{path}` = `{}` must be {what}", ctx.text(v.span()));
        ctx.error(v.span(), msg, None);
        None
    }
}

/// A size: a finite number > 0.
pub(crate) fn size(ctx: &mut Ctx<'_>, v: &Value<'_>, path: &str) -> Option<f64> {
    number_above(ctx, v, path, 0.0, "greater than 0")
}

/// A string, or an error.
pub(crate) fn string<'a>(ctx: &mut Ctx<'_>, v: &'a Value<'_>, path: &str) -> Option<&'a str> {
    match v.get_ref() {
        DeValue::String(s) => Some(s),
        other => {
            let msg = format!(
                "`{path}` must be a string, found {} `{}`",
                type_name(other),
                ctx.text(v.span())
            );
            ctx.error(
                v.span(),
                msg,
                Some("put the text in double quotes".to_string()),
            );
            None
        }
    }
}

/// A boolean, or an error.
pub(crate) fn boolean(ctx: &mut Ctx<'_>, v: &Value<'_>, path: &str) -> Option<bool> {
    match v.get_ref() {
        DeValue::Boolean(b) => Some(*b),
        other => {
            let msg = format!(
                "`{path}` must be `true` or `false`, found {} `{}`",
                type_name(other),
                ctx.text(v.span())
            );
            ctx.error(v.span(), msg, None);
            None
        }
    }
}

/// An array, or an error.
pub(crate) fn array<'a, 'i>(
    ctx: &mut Ctx<'_>,
    v: &'a Value<'i>,
    path: &str,
    what: &str,
) -> Option<&'a [Value<'i>]> {
    match v.get_ref() {
        DeValue::Array(a) => Some(a),
        other => {
            let msg = format!(
                "`{path}` must be {what}, found {} `{}`",
                type_name(other),
                ctx.text(v.span())
            );
            ctx.error(v.span(), msg, None);
            None
        }
    }
}

/// Three finite numbers `[x, y, z]`.
pub(crate) fn vec3(ctx: &mut Ctx<'_>, v: &Value<'_>, path: &str) -> Option<[f64; 3]> {
    let a = array(ctx, v, path, "a point `[x, y, z]`")?;
    if a.len() != 3 {
        let msg = format!(
            "`{path}` must have 3 coordinates `[x, y, z]`, found {}: `{}`",
            a.len(),
            ctx.text(v.span())
        );
        ctx.error(v.span(), msg, None);
        return None;
    }
    let mut out = [0.0; 3];
    let mut ok = true;
    for (i, e) in a.iter().enumerate() {
        match number(ctx, e, &format!("{path}[{i}]")) {
            Some(x) => out[i] = x,
            None => ok = false,
        }
    }
    ok.then_some(out)
}

/// An array of strings, each with its span.
pub(crate) fn strings(
    ctx: &mut Ctx<'_>,
    v: &Value<'_>,
    path: &str,
) -> Option<Vec<(String, Range<usize>)>> {
    let a = array(ctx, v, path, "an array of strings")?;
    let mut out = Vec::with_capacity(a.len());
    let mut ok = true;
    for (i, e) in a.iter().enumerate() {
        match string(ctx, e, &format!("{path}[{i}]")) {
            Some(s) => out.push((s.to_string(), e.span())),
            None => ok = false,
        }
    }
    ok.then_some(out)
}

/// One word among `choices`, with a did-you-mean on a miss.
pub(crate) fn choice<T: Copy>(
    ctx: &mut Ctx<'_>,
    v: &Value<'_>,
    path: &str,
    choices: &[(&str, T)],
) -> Option<T> {
    let s = string(ctx, v, path)?;
    if let Some((_, t)) = choices.iter().find(|(name, _)| *name == s) {
        return Some(*t);
    }
    let names: Vec<&str> = choices.iter().map(|(n, _)| *n).collect();
    let help = suggest(s, &names, "valid values are");
    ctx.error(
        v.span(),
        format!(
            "`{path}` = `{}` is not one of the valid values",
            ctx.text(v.span())
        ),
        help,
    );
    None
}

/// The closest of `names` to `word` as a "did you mean" help text.
pub(crate) fn name_help<'a, I: IntoIterator<Item = &'a str>>(
    word: &str,
    names: I,
) -> Option<String> {
    did_you_mean(word, names).map(|c| format!("did you mean `{c}`?"))
}
