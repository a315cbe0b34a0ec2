//! Cargo-style status lines and progress bars for build events.
//!
//! What a build says, by verbosity: by default one line per node that ran (with its notes) and
//! every failure in full (at its recipe entry when it names one), cached nodes only counted (the command line prints the count); `-v`
//! also a line per cached, cut-off or skipped node and each expansion; `--quiet` only failures.
//!
//! Progress bars (from the nodes' `Event::Progress`): drawn only when standard error, where
//! they go, is a terminal and the build is not `--quiet`, so a log, a pipe or a script never
//! gets a bar's escape sequences. A node gets its bar once it has run for [`BAR_DELAY`] (or
//! `RECIPE_BAR_DELAY_MS` milliseconds, for tests): most nodes take milliseconds, and a bar that
//! appears and vanishes at once is only flicker.

use crate::recipe::Recipe;
use engine::{Event, NodeReport, NodeState};
use indicatif::{MultiProgress, ProgressBar, ProgressStyle};
use std::collections::BTreeMap;
use std::io::IsTerminal;
use std::sync::Mutex;
use std::time::{Duration, Instant};

/// How long a node runs before its progress bar is shown.
const BAR_DELAY: Duration = Duration::from_millis(300);

/// How much a build prints (`--quiet`, default, `-v`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Verbosity {
    /// Errors and the final line.
    Quiet,
    /// What ran, failures, a short summary and the final line.
    Normal,
    /// Every node, the expansions and the full quality tables too.
    Verbose,
}

/// Renders events on stderr.
pub struct Renderer {
    /// The recipe built, to show failures located in it as recipe errors are shown.
    recipe: Recipe,
    verbosity: Verbosity,
    explain: bool,
    bars: Option<MultiProgress>,
    delay: Duration,
    active: Mutex<BTreeMap<String, Running>>,
    /// The recipe's surfaces, imported when a meshing failure first needs them (`culprit`).
    surfaces: std::sync::OnceLock<Vec<super::culprit::Indexed>>,
    /// Failures of a build that may be tried again, held until it is known whether it will be
    /// (`hold_failures`).
    held: Mutex<Option<Vec<String>>>,
}

/// A node that runs, when bars are drawn: since when, and its bar once it has one.
struct Running {
    since: Instant,
    bar: Option<ProgressBar>,
}

/// Whether a build draws progress bars.
fn draws_bars(verbosity: Verbosity, stderr_is_terminal: bool) -> bool {
    verbosity > Verbosity::Quiet && stderr_is_terminal
}

impl Renderer {
    pub fn new(recipe: &Recipe, verbosity: Verbosity, explain: bool) -> Self {
        let bars = draws_bars(verbosity, std::io::stderr().is_terminal()).then(MultiProgress::new);
        let delay = std::env::var("RECIPE_BAR_DELAY_MS")
            .ok()
            .and_then(|ms| ms.parse().ok())
            .map_or(BAR_DELAY, Duration::from_millis);
        Renderer {
            recipe: recipe.clone(),
            verbosity,
            explain,
            bars,
            delay,
            active: Mutex::new(BTreeMap::new()),
            surfaces: std::sync::OnceLock::new(),
            held: Mutex::new(None),
        }
    }

    fn line(&self, s: String) {
        match &self.bars {
            Some(m) => {
                let _ = m.println(s);
            }
            None => errln!("{s}"),
        }
    }

    pub fn event(&self, e: &Event) {
        let normal = self.verbosity >= Verbosity::Normal;
        match e {
            Event::WaitingForLock { path } if normal => self.line(format!(
                "    Blocking waiting for another build holding the cache lock at {}",
                path.display()
            )),
            Event::CacheCorrupt { name, detail } if normal => self.line(format!(
                "     Warning cache entry of `{name}` is corrupt ({detail}): rebuilding it"
            )),
            Event::Expanded { by, added } if self.verbosity == Verbosity::Verbose => {
                self.line(format!("    Expanded {by}: {added} nodes"))
            }
            Event::Started { name, .. } if self.bars.is_some() => {
                let mut active = self.active.lock().unwrap_or_else(|p| p.into_inner());
                active.insert(
                    name.clone(),
                    Running {
                        since: Instant::now(),
                        bar: None,
                    },
                );
            }
            Event::Progress { name, done, total } => self.progress(name, *done, *total),
            Event::Finished(r) => self.finished(r),
            _ => {}
        }
    }

    fn progress(&self, name: &str, done: u64, total: u64) {
        let Some(m) = &self.bars else { return };
        let mut active = self.active.lock().unwrap_or_else(|p| p.into_inner());
        let running = active.entry(name.to_string()).or_insert_with(|| Running {
            since: Instant::now(),
            bar: None,
        });
        if running.bar.is_none() && running.since.elapsed() < self.delay {
            return;
        }
        let bar = running.bar.get_or_insert_with(|| {
            let b = m.add(ProgressBar::new(total));
            b.set_style(
                ProgressStyle::with_template("{prefix:>12.cyan.bold} [{bar:30}] {pos}/{len} {msg}")
                    .unwrap_or_else(|_| ProgressStyle::default_bar()),
            );
            b.set_prefix("Building");
            b.set_message(name.to_string());
            b
        });
        bar.set_length(total);
        bar.set_position(done);
    }

    fn finished(&self, r: &NodeReport) {
        if let Some(b) = self
            .active
            .lock()
            .unwrap_or_else(|p| p.into_inner())
            .remove(&r.name)
            .and_then(|running| running.bar)
        {
            b.finish_and_clear();
        }
        let why = if self.explain {
            format!(" [{}]", r.reason)
        } else {
            String::new()
        };
        match r.state {
            NodeState::Failed => {
                let line = self.failure(&r.name, r.error.as_deref().unwrap_or("unknown error"));
                match self.held.lock().unwrap_or_else(|p| p.into_inner()).as_mut() {
                    Some(held) => held.push(line),
                    None => self.line(line),
                }
            }
            NodeState::Ran if self.verbosity >= Verbosity::Normal => {
                self.line(format!(
                    "{:>12} {}{} in {:.2}s{why}",
                    verb(&r.kind),
                    r.name,
                    counts(r),
                    r.duration_ms / 1000.0,
                ));
                for n in &r.notes {
                    self.line(format!("{:>12} {n}", "note"));
                }
            }
            NodeState::Cached | NodeState::CutOff if self.verbosity == Verbosity::Verbose => {
                let cut = if r.state == NodeState::CutOff {
                    " (cut off: its inputs re-ran to the same outputs)"
                } else {
                    ""
                };
                self.line(format!(
                    "{:>12} {}{}{cut}{why}",
                    "Cached",
                    r.name,
                    counts(r)
                ));
            }
            NodeState::Skipped if self.verbosity == Verbosity::Verbose => {
                self.line(format!("{:>12} {} ({})", "Skipped", r.name, r.reason));
            }
            _ => {}
        }
    }
}

impl Renderer {
    /// Holds the failures of the build about to run instead of printing them.
    pub fn hold_failures(&self) {
        *self.held.lock().unwrap_or_else(|p| p.into_inner()) = Some(Vec::new());
    }

    /// Prints the failures held, if `print`, else drops them (the build is tried again), and
    /// prints failures as they come again.
    pub fn release_failures(&self, print: bool) {
        let held = self.held.lock().unwrap_or_else(|p| p.into_inner()).take();
        for line in held.into_iter().flatten().filter(|_| print) {
            self.line(line);
        }
    }

    /// A node's failure: at its recipe entry, with the line quoted and the entry underlined,
    /// when the error starts with a recipe location (as the model's errors about regions, the
    /// box and trims do); else on one line.
    fn failure(&self, node: &str, error: &str) -> String {
        match self.recipe.located(error) {
            Some(mut d) => {
                d.message = format!("`{node}` failed: {}", d.message);
                d.to_string()
            }
            None => {
                let mut line = format!("       error `{node}` failed: {error}");
                if let Some(near) = self.nearest_input(node, error) {
                    line.push_str(&format!("\n{:>12} {near}", "note"));
                }
                line
            }
        }
    }

    /// For a failure at coordinates in any stage after import: the input triangle nearest to
    /// them (one line each). A node named after surfaces (a patch `<surface>#<k>`, a curve or an
    /// intersection `<a>/<b>`) looks among those surfaces, one note each, since those are the
    /// triangles to edit; a node of the whole model or of a region looks among all of them.
    fn nearest_input(&self, node: &str, error: &str) -> Option<String> {
        let only = self.surfaces_named_by(node)?;
        let at = super::culprit::failure_place(error)?;
        let surfaces = self
            .surfaces
            .get_or_init(|| super::culprit::import_all(&self.recipe));
        let units = self.recipe.model.units.as_str();
        let notes: Vec<String> = only
            .into_iter()
            .filter_map(|o| super::culprit::nearest_triangle(surfaces, o, at, units))
            .collect();
        (!notes.is_empty()).then(|| notes.join(&format!("\n{:>12} ", "note")))
    }

    /// The recipe's surfaces a node's name speaks of (`None` in the list: any surface); `None`
    /// for the nodes before the geometry (files, imports, whose errors name their line) and
    /// after it (exports).
    fn surfaces_named_by<'a>(&self, node: &'a str) -> Option<Vec<Option<&'a str>>> {
        let (kind, subject) = node.split_once(':').unwrap_or((node, ""));
        if matches!(kind, "file" | "import" | "export") {
            return None;
        }
        let named: Vec<Option<&str>> = subject
            .split('#')
            .next()
            .unwrap_or("")
            .split('/')
            .filter(|n| self.recipe.surfaces.contains_key(*n))
            .map(Some)
            .collect();
        Some(if named.is_empty() { vec![None] } else { named })
    }
}

/// A node's counts, ` (3 nodes, 4 triangles)`, or nothing.
fn counts(r: &NodeReport) -> String {
    if r.counts.is_empty() {
        return String::new();
    }
    let counts: Vec<String> = r.counts.iter().map(|(k, v)| format!("{v} {k}")).collect();
    format!(" ({})", counts.join(", "))
}

/// The verb of a Cargo-style line for an operation kind.
fn verb(kind: &str) -> &'static str {
    match kind {
        "file" => "Hashed",
        "import" => "Imported",
        "box" | "box_side" => "Boxed",
        "intersect" => "Intersected",
        "curves" | "curve" | "model" | "patch" => "Modelled",
        "surface_mesh" | "tet_mesh" => "Meshed",
        "mesh" => "Assembled",
        "discretize" => "Discretized",
        "export" => "Exported",
        _ => "Ran",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn shipped() -> Renderer {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("recipes");
        let recipe = crate::cli::load::load(&dir.join("didactic.toml"))
            .unwrap_or_else(|e| panic!("the example loads: {}", e.0));
        Renderer::new(&recipe, Verbosity::Quiet, false)
    }

    #[test]
    fn a_failure_at_coordinates_names_the_nearest_input_triangles_file_line() {
        let r = shipped();
        // On H2 near the box's y-min side, where F1 also passes: a patch's failure names its
        // own surface's triangle, a region's the nearest of any.
        let at = "at (501500.0, 7000010.0, -1180.0)";
        let patch = r.failure("surface_mesh:H2#1", &format!("triangle 3 folds {at}"));
        assert!(
            patch
                .contains("note the nearest input triangle is data/didactic/H2_base_reservoir.ts:"),
            "{patch}"
        );
        assert!(patch.contains("(surface `H2`)") && patch.ends_with(" m from there"));
        let region = r.failure("tet_mesh:reservoir_E", &format!("the front is stuck {at}"));
        assert!(region.contains("note the nearest input triangle is data/didactic/"));
        // An intersection's failure names the nearest triangle of each of its surfaces.
        let pair = r.failure(
            "intersect:F1/H2",
            &format!("surfaces `F1` and `H2` overlap where they are coplanar: triangle 1 × triangle 2 {at}"),
        );
        for file in ["F1_through.ts:", "H2_base_reservoir.ts:"] {
            assert!(pair.contains(&format!("is data/didactic/{file}")), "{pair}");
        }
        assert_eq!(
            pair.matches("note the nearest input triangle").count(),
            2,
            "{pair}"
        );
        // A curve's failure looks on its surfaces only (a box side has no input triangles); the
        // model's among every surface.
        let curve = r.failure("discretize:F1/box.ymin#1", &format!("two nodes meet {at}"));
        assert!(curve.contains("(surface `F1`)"), "{curve}");
        assert_eq!(curve.matches("note").count(), 1, "{curve}");
        let model = r.failure("model", &format!("two curve points are at one place {at}"));
        assert!(
            model.contains("note the nearest input triangle is data/didactic/"),
            "{model}"
        );
        // Without coordinates, or from a stage whose errors are not at a place in the model, the
        // error stays on its own.
        assert!(!r.failure("tet_mesh:x", "no place").contains("note"));
        assert!(!r.failure("export", &format!("oops {at}")).contains("note"));
        assert!(
            !r.failure("import:H1", &format!("oops {at}"))
                .contains("note")
        );
    }
}
