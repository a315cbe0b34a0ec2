//! `[groups]`: group name -> a patch selector or a list of them (`seafloor = "box.zmax"`,
//! `reservoir_top = ["H1#2", "H1#3"]`). Decides which names are legal (not a surface's, a box
//! side's, a region's or a well's, so every output group has one meaning) and which selectors
//! are well formed, each surface part matching a known surface. Whether a `#k` names a patch the
//! model has is known only once the model is built ([`crate::recipe::Recipe::group_patches`]).

use std::collections::BTreeMap;

use toml::de::DeValue;

use super::Names;
use super::surfaces::check_name;
use crate::recipe::reader::{self as rd, Ctx, Value, path_join};
use crate::recipe::selector::PatchSelector;
use crate::recipe::spec::GroupSpec;

/// Reads `[groups]`; `taken` are the other names a group may not take, each with what it is
/// (`region`, `well`).
pub(crate) fn read(
    ctx: &mut Ctx<'_>,
    v: Option<&Value<'_>>,
    names: &Names,
    taken: &[(&str, &str)],
) -> BTreeMap<String, GroupSpec> {
    let mut out = BTreeMap::new();
    let Some(v) = v else { return out };
    let Some(t) = rd::as_table(ctx, v, "groups", None) else {
        return out;
    };
    for (k, e) in t.iter() {
        let name: &str = k.get_ref();
        let path = path_join("groups", name);
        let mut ok = check_name(ctx, name, k.span(), "group");
        let clash = if names.is_known(name) {
            Some("surface")
        } else {
            taken
                .iter()
                .find(|(n, _)| *n == name)
                .map(|(_, what)| *what)
        };
        if let (true, Some(what)) = (ok, clash) {
            ctx.error(
                k.span(),
                format!("group name `{name}` is also a {what} name"),
                Some(format!(
                    "outputs name groups and {what}s alike: rename the group, e.g. `{name}_bc`"
                )),
            );
            ok = false;
        }
        let written: Vec<(String, std::ops::Range<usize>)> = match e.get_ref() {
            DeValue::String(s) => vec![(s.to_string(), e.span())],
            _ => match rd::strings(ctx, e, &path) {
                Some(list) => list,
                None => continue,
            },
        };
        if written.is_empty() {
            ctx.error(
                e.span(),
                format!("`{path}` is empty: the group would hold no face"),
                Some("name surfaces or patches, e.g. `[\"H1#2\", \"box.zmax\"]`".into()),
            );
            continue;
        }
        let mut selectors = Vec::with_capacity(written.len());
        let mut selector_spans = Vec::with_capacity(written.len());
        for (text, span) in written {
            if let Some(s) = selector(ctx, &text, span.clone(), names) {
                selectors.push(s);
                selector_spans.push(ctx.span(span));
            } else {
                ok = false;
            }
        }
        if ok {
            let spec = GroupSpec {
                name: name.to_string(),
                selectors,
                selector_spans,
                span: ctx.span(k.span()),
            };
            out.insert(name.to_string(), spec);
        }
    }
    out
}

/// The patch selector `text` (written at `span`), its surface part checked against the known
/// surfaces; `None` after reporting what is wrong.
fn selector(
    ctx: &mut Ctx<'_>,
    text: &str,
    span: std::ops::Range<usize>,
    names: &Names,
) -> Option<PatchSelector> {
    match PatchSelector::parse(text) {
        Ok(s) => names
            .check_pattern(ctx, &s.surface.pattern, text, span, "group selector")
            .then_some(s),
        Err(err) => {
            ctx.error(
                span,
                format!("bad group selector `{text}`: {err}"),
                Some("e.g. `\"box.zmax\"`, `\"H1\"`, `\"H1#2\"` or `\"F*\"`".into()),
            );
            None
        }
    }
}
