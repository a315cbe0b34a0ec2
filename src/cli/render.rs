//! Cargo-style status lines and progress bars for build events.

use engine::{Event, NodeReport, NodeState};
use indicatif::{MultiProgress, ProgressBar, ProgressStyle};
use std::collections::BTreeMap;
use std::io::IsTerminal;
use std::sync::Mutex;

/// Renders events on stderr. Only nodes that ran or failed get a line; cached ones are counted.
pub struct Renderer {
    quiet: bool,
    explain: bool,
    bars: Option<MultiProgress>,
    active: Mutex<BTreeMap<String, ProgressBar>>,
}

impl Renderer {
    pub fn new(quiet: bool, explain: bool) -> Self {
        let bars = (!quiet && std::io::stderr().is_terminal()).then(MultiProgress::new);
        Renderer {
            quiet,
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
        match e {
            Event::WaitingForLock { path } => self.line(format!(
                "    Blocking waiting for another build holding the cache lock at {}",
                path.display()
            )),
            Event::CacheCorrupt { name, detail } => self.line(format!(
                "     Warning cache entry of `{name}` is corrupt ({detail}): rebuilding it"
            )),
            Event::Expanded { by, added } if !self.quiet => {
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
        match r.state {
            NodeState::Failed => {
                self.line(format!(
                    "       error `{}` failed: {}",
                    r.name,
                    r.error.as_deref().unwrap_or("unknown error")
                ));
            }
            NodeState::Ran if !self.quiet => {
                let counts: Vec<String> =
                    r.counts.iter().map(|(k, v)| format!("{v} {k}")).collect();
                let counts = if counts.is_empty() {
                    String::new()
                } else {
                    format!(" ({})", counts.join(", "))
                };
                let why = if self.explain {
                    format!(" [{}]", r.reason)
                } else {
                    String::new()
                };
                self.line(format!(
                    "{:>12} {}{} in {:.2}s{}",
                    verb(&r.kind),
                    r.name,
                    counts,
                    r.duration_ms / 1000.0,
                    why
                ));
                for n in &r.notes {
                    self.line(format!("{:>12} {n}", "note"));
                }
            }
            _ => {}
        }
    }
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
