//! The recipe language: TOML text -> a validated, typed [`Recipe`], or every error found.
//!
//! This module decides what a recipe may say and what it means: the schema (every key, its type,
//! default and meaning: see the recipe reference in README.md), the names and selectors that
//! refer to surfaces, curves and regions, and the normalisation of what the planner reads
//! (intersection pairs sorted and deduplicated, defaults filled in). It does no geometry and no
//! I/O: [`parse`] takes the text, [`check_files`] takes an `exists` probe. Every error names
//! `file:line:col`, quotes the offending text and, where it can, suggests the intended name;
//! errors are collected, not stopped at, and returned in source order.
//!
//! How the command line uses it (`recipe check`; `recipe build` continues with the plan):
//!
//! ```
//! use std::path::Path;
//! use georecipe::recipe;
//!
//! let text = "[model]\nname = \"demo\"\n[mesh]\nsize = 10\n[mesh.curves]\n\"top\" = { cuont = 3 }\n";
//! match recipe::check(Path::new("demo.toml"), text, &|p| p.exists()) {
//!     Ok(r) => println!("{}: ok", r.model.name),
//!     Err(diags) => {
//!         eprint!("{}", recipe::render(&diags)); // then exit non-zero
//!         assert!(diags[0].to_string().contains("demo.toml:6:"));
//!     }
//! }
//! ```

mod curves;
mod diagnostic;
mod files;
mod groups;
mod reader;
mod sections;
pub mod selector;
mod spec;
mod syntax;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use toml::de::DeTable;

pub use diagnostic::{Diagnostic, Span};
pub use files::{FileKind, check_files, check_files_with_listing};
pub use groups::GroupPatches;
pub use sections::regions::MAX_PROPERTY_NAMES;
pub use selector::{CurveSelector, PatchSelector, SurfaceSelector, glob_match};
pub use spec::*;

use diagnostic::{SourceText, suggest};
use geom::Tolerances;
use reader::Ctx;
use sections::Names;

/// Top-level keys a recipe may have.
const ROOT_KEYS: &[&str] = &[
    "model",
    "tolerances",
    "surfaces",
    "box",
    "intersect",
    "trim",
    "mesh",
    "regions",
    "wells",
    "groups",
    "output",
];

/// A validated recipe.
#[derive(Clone, Debug)]
pub struct Recipe {
    /// The recipe path as given to [`parse`] (used in every diagnostic).
    pub path: PathBuf,
    /// The directory relative paths in the recipe are resolved against (`path`'s parent).
    pub base_dir: PathBuf,
    pub model: ModelSpec,
    pub tolerances: Tolerances,
    pub surfaces: BTreeMap<String, SurfaceSpec>,
    pub bbox: Option<BoxSpec>,
    /// Normalised pairs: each `(a, b)` with `a < b`, no duplicates, sorted; `box` expanded to
    /// its sides.
    pub intersect: Vec<(String, String)>,
    /// For each pair of `intersect` (same index), where the recipe asked for it.
    pub intersect_spans: Vec<Span>,
    /// In recipe order.
    pub trims: Vec<TrimSpec>,
    pub mesh: MeshSpec,
    pub regions: BTreeMap<String, RegionSpec>,
    /// `[wells]`, by name.
    pub wells: BTreeMap<String, WellSpec>,
    /// `[groups]`, by name.
    pub groups: BTreeMap<String, GroupSpec>,
    pub output: OutputSpec,
    src: SourceText,
}

impl Recipe {
    /// A diagnostic at a recipe location, for errors found after parsing (e.g. a curve rule
    /// whose selector matches no curve of the built model).
    pub fn diagnostic_at(
        &self,
        span: Span,
        message: impl Into<String>,
        help: Option<String>,
    ) -> Diagnostic {
        self.src.diagnostic(span, message.into(), help)
    }

    /// A recipe location as later stages quote it at the start of an error: `file:line:col`.
    /// [`Recipe::located`] reads such an error back.
    pub fn place(&self, span: Span) -> String {
        format!("{}:{}:{}", self.src.label, span.line, span.col)
    }

    /// An error that starts with a location of this recipe ([`Recipe::place`] then `": "`) as a
    /// diagnostic there, quoting the line and underlining the entry; the text after `"; help: "`
    /// becomes its help. `None` for an error that starts with no such location.
    pub fn located(&self, error: &str) -> Option<Diagnostic> {
        let rest = error.strip_prefix(&self.src.label)?.strip_prefix(':')?;
        let (line, rest) = rest.split_once(':')?;
        let (col, message) = rest.split_once(": ")?;
        let span = self.src.token_at(line.parse().ok()?, col.parse().ok()?)?;
        let (message, help) = match message.split_once("; help: ") {
            Some((m, h)) => (m, Some(h.to_string())),
            None => (message, None),
        };
        Some(self.diagnostic_at(span, message, help))
    }

    /// The recipe text as parsed.
    pub fn source(&self) -> &str {
        &self.src.text
    }

    /// Every surface a selector may name: the `[surfaces]` names, then the six box sides when a
    /// `[box]` is given.
    pub fn surface_names(&self) -> Vec<String> {
        let mut v: Vec<String> = self.surfaces.keys().cloned().collect();
        if self.bbox.is_some() {
            v.extend(BOX_SIDES.iter().map(|s| s.to_string()));
        }
        v
    }
}

/// Parses and validates a recipe. `path_label` names the file in diagnostics and anchors
/// relative paths; nothing is read from disk. Returns every error found, in source order.
pub fn parse(path_label: &Path, text: &str) -> Result<Recipe, Vec<Diagnostic>> {
    let src = SourceText::new(path_label.display().to_string(), text);
    let (doc, errors) = DeTable::parse_recoverable(text);
    if !errors.is_empty() {
        return Err(syntax::diagnostics(&src, &errors));
    }
    let base_dir = path_label
        .parent()
        .map(Path::to_path_buf)
        .unwrap_or_default();
    let root = doc.get_ref();
    let root_span = 0..0;
    let mut ctx = Ctx::new(&src);
    reader::check_keys(&mut ctx, root, "", ROOT_KEYS, &|k| {
        ["size", "min_size", "max_size", "growth", "tet_method"]
            .contains(&k)
            .then(|| format!("`{k}` belongs in `[mesh]`"))
            .or_else(|| suggest(k, ROOT_KEYS, "valid top-level tables are"))
    });
    let model = sections::model::read_model(&mut ctx, root, root_span.clone());
    let tolerances = sections::model::read_tolerances(&mut ctx, root.get("tolerances"));
    let surfaces = sections::surfaces::read(&mut ctx, root.get("surfaces"), &base_dir);
    // Names declared under [surfaces] but rejected still count as known, so one bad entry does
    // not cascade into "unknown surface" errors everywhere it is used.
    let mut declared: Vec<String> = match root.get("surfaces").map(|v| v.get_ref()) {
        Some(toml::de::DeValue::Table(t)) => {
            t.iter().map(|(k, _)| k.get_ref().to_string()).collect()
        }
        _ => Vec::new(),
    };
    declared.sort();
    let has_box_table = root.get("box").is_some();
    let bbox = sections::bbox::read(&mut ctx, root.get("box"), &declared);
    let names = Names {
        surfaces: declared,
        has_box: has_box_table,
    };
    let pairs = sections::intersect::read(&mut ctx, root.get("intersect"), &names);
    let trims = sections::trim::read(&mut ctx, root.get("trim"), &names);
    let regions = sections::regions::read(&mut ctx, root.get("regions"), bbox.as_ref());
    let mut region_names: Vec<String> = match root.get("regions").map(|v| v.get_ref()) {
        Some(toml::de::DeValue::Table(t)) => {
            t.iter().map(|(k, _)| k.get_ref().to_string()).collect()
        }
        _ => Vec::new(),
    };
    region_names.sort();
    let mesh = sections::mesh::read(&mut ctx, root, root_span, &names, &region_names);
    let output = sections::output::read(&mut ctx, root.get("output"), &base_dir);
    let wells = sections::wells::read(
        &mut ctx,
        root.get("wells"),
        &base_dir,
        &names.surfaces,
        &region_names,
    );
    let taken: Vec<(&str, &str)> = (region_names.iter().map(|r| (r.as_str(), "region")))
        .chain(wells.keys().map(|w| (w.as_str(), "well")))
        .collect();
    let groups = sections::groups::read(&mut ctx, root.get("groups"), &names, &taken);

    let mut diags = ctx.diags;
    if let (true, Some(model), Some(mesh), Some(output)) =
        (diags.is_empty(), model.clone(), mesh, output)
    {
        let (intersect, intersect_spans) = pairs.into_iter().unzip();
        return Ok(Recipe {
            path: path_label.to_path_buf(),
            base_dir,
            model,
            tolerances,
            surfaces,
            bbox,
            intersect,
            intersect_spans,
            trims,
            mesh,
            regions,
            wells,
            groups,
            output,
            src,
        });
    }
    diags.sort_by(|a, b| (a.line, a.col, &a.message).cmp(&(b.line, b.col, &b.message)));
    diags.dedup();
    if diags.is_empty() {
        // Unreachable in practice (every `None` above reports why), but never return Err(empty).
        diags.push(src.diagnostic(src.span(0..0), "the recipe is incomplete".into(), None));
    }
    Err(diags)
}

/// What `recipe check` does: [`parse`], then [`check_files`]; every diagnostic in source order.
pub fn check(
    path_label: &Path,
    text: &str,
    exists: &dyn Fn(&Path) -> bool,
) -> Result<Recipe, Vec<Diagnostic>> {
    let recipe = parse(path_label, text)?;
    let missing = check_files(&recipe, exists);
    if missing.is_empty() {
        Ok(recipe)
    } else {
        let mut d = missing;
        d.sort_by_key(|d| (d.line, d.col));
        Err(d)
    }
}

/// All diagnostics rendered for a terminal, separated by blank lines, with a closing count:
/// "error: could not use `FILE`: N errors".
pub fn render(diags: &[Diagnostic]) -> String {
    let mut out = String::new();
    for d in diags {
        out.push_str(&d.to_string());
        out.push_str("\n\n");
    }
    if let Some(first) = diags.first() {
        let n = diags.len();
        let s = if n == 1 { "" } else { "s" };
        out.push_str(&format!(
            "error: could not use `{}`: {n} error{s}\n",
            first.file
        ));
    }
    out
}
