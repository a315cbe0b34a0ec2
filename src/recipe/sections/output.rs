//! `[output]`: where results go (relative to the recipe file) and in which formats. Decides the
//! defaults (`out`, `["msh", "vtu"]`), that every format is known and listed once, and that the
//! results stay inside the recipe's folder unless the recipe says `allow_outside = true`: a
//! `dir` of `../../x` or `/tmp/x` is more often a slip than a wish, and a build writes and
//! replaces files there. The test is on the path as written (symbolic links are not followed).

use std::path::{Component, Path, PathBuf};

use crate::recipe::reader::{self as rd, Ctx, Value};
use crate::recipe::spec::{Format, OutputSpec};

const KEYS: &[&str] = &["dir", "formats", "allow_outside"];

pub(crate) fn read(
    ctx: &mut Ctx<'_>,
    v: Option<&Value<'_>>,
    base_dir: &Path,
) -> Option<OutputSpec> {
    let default_formats = vec![Format::Msh, Format::Vtu];
    let Some(v) = v else {
        let dir = PathBuf::from("out");
        return Some(OutputSpec {
            path: base_dir.join(&dir),
            dir,
            formats: default_formats,
            span: Default::default(),
        });
    };
    let t = rd::as_table(ctx, v, "output", None)?;
    rd::check_keys(ctx, t, "output", KEYS, &|_| None);
    let dir = match t.get("dir") {
        Some(d) => rd::string(ctx, d, "output.dir").and_then(|s| {
            if s.trim().is_empty() {
                ctx.error(
                    d.span(),
                    "`output.dir` must not be empty".into(),
                    Some("e.g. `dir = \"out\"` (relative to the recipe)".into()),
                );
                None
            } else {
                Some(PathBuf::from(s))
            }
        }),
        None => Some(PathBuf::from("out")),
    };
    let allow_outside = match t.get("allow_outside") {
        Some(x) => rd::boolean(ctx, x, "output.allow_outside"),
        None => Some(false),
    };
    if let (Some(d), Some(dir), Some(false)) = (t.get("dir"), &dir, allow_outside)
        && leaves_folder(dir)
    {
        ctx.error(
            d.span(),
            format!(
                "`output.dir` `{}` is outside the recipe's folder",
                dir.display()
            ),
            Some(
                "write a folder inside it (e.g. `dir = \"out\"`), or add `allow_outside = true` \
                 to `[output]` to write there on purpose"
                    .into(),
            ),
        );
    }
    let formats = match t.get("formats") {
        Some(f) => formats(ctx, f),
        None => Some(default_formats),
    };
    let dir = dir?;
    Some(OutputSpec {
        path: base_dir.join(&dir),
        dir,
        formats: formats?,
        span: ctx.span(v.span()),
    })
}

/// Whether `dir`, relative to the recipe's folder, leads out of it: an absolute path, or more
/// `..` than folders before them.
fn leaves_folder(dir: &Path) -> bool {
    let mut depth = 0i64;
    for c in dir.components() {
        match c {
            Component::Normal(_) => depth += 1,
            Component::ParentDir => depth -= 1,
            Component::CurDir => {}
            Component::RootDir | Component::Prefix(_) => return true,
        }
        if depth < 0 {
            return true;
        }
    }
    false
}

fn formats(ctx: &mut Ctx<'_>, v: &Value<'_>) -> Option<Vec<Format>> {
    let list = rd::array(ctx, v, "output.formats", "an array of format names")?;
    if list.is_empty() {
        ctx.error(
            v.span(),
            "`output.formats` is empty".into(),
            Some(
                "list at least one of `msh`, `msh-binary`, `vtu`, `vtu-binary`, `tetgen`, `medit`, `inp`, `exodus`"
                    .into(),
            ),
        );
        return None;
    }
    let spellings: Vec<(&str, Format)> = Format::ALL.into_iter().chain(Format::ALIASES).collect();
    let mut out = Vec::new();
    let mut ok = true;
    for (i, e) in list.iter().enumerate() {
        match rd::choice(ctx, e, &format!("output.formats[{i}]"), &spellings) {
            Some(f) if out.contains(&f) => {
                ctx.error(
                    e.span(),
                    format!(
                        "format `{}` is listed twice in `output.formats`",
                        f.as_str()
                    ),
                    Some("remove the repeated format".into()),
                );
                ok = false;
            }
            Some(f) => {
                if let Some(&g) = out.iter().find(|&&g| same_file(g, f)) {
                    ctx.error(
                        e.span(),
                        format!(
                            "formats `{}` and `{}` in `output.formats` both write the same file",
                            g.as_str(),
                            f.as_str()
                        ),
                        Some("list one encoding of each format".into()),
                    );
                    ok = false;
                }
                out.push(f);
            }
            None => ok = false,
        }
    }
    ok.then_some(out)
}

/// Whether two formats write a file of the same name (the two encodings of msh or of VTU).
fn same_file(a: Format, b: Format) -> bool {
    a.file_family() == b.file_family()
}
