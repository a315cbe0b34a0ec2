//! Cargo-style status lines and progress bars for build events.
//!
//! What a build says, by verbosity: by default one line per node that ran (with its notes) and
//! every failure in full, cached nodes only counted (the command line prints the count); `-v`
//! also a line per cached, cut-off or skipped node and each expansion; `--quiet` only failures.

use engine::{Event, NodeReport, NodeState};
use indicatif::{MultiProgress, ProgressBar, ProgressStyle};
use std::collections::BTreeMap;
use std::io::IsTerminal;
use std::sync::Mutex;

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
    verbosity: Verbosity,
    explain: bool,
    bars: Option<MultiProgress>,
    active: Mutex<BTreeMap<String, ProgressBar>>,
}

impl Renderer {
    pub fn new(verbosity: Verbosity, explain: bool) -> Self {
        let bars = (verbosity > Verbosity::Quiet && std::io::stderr().is_terminal())
            .then(MultiProgress::new);
        Renderer {
            verbosity,
            explain,
            bars,
            active: Mutex::new(BTreeMap::new()),
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
            Event::Progress { name, done, total } => self.progress(name, *done, *total),
            Event::Finished(r) => self.finished(r),
            _ => {}
        }
    }

    fn progress(&self, name: &str, done: u64, total: u64) {
        let Some(m) = &self.bars else { return };
        let mut active = self.active.lock().unwrap_or_else(|p| p.into_inner());
        let bar = active.entry(name.to_string()).or_insert_with(|| {
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
                self.line(format!(
                    "       error `{}` failed: {}",
                    r.name,
                    r.error.as_deref().unwrap_or("unknown error")
                ));
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
