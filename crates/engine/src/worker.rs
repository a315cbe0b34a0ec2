//! What a worker thread does with one dispatched node: read a source file, or look the node's
//! key up in the cache (verifying what it reads) and run the operation on a miss, storing the
//! result; then write any emitted files (into the staging directory when the build has one). Panics inside an operation become node failures.

use crate::artifact::{Artifact, Hash};
use crate::build::Event;
use crate::op::{Operation, RunContext};
use crate::outputs::write_fileset;
use crate::store::{ActionRecord, Load, Store};
use std::collections::BTreeMap;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

pub(crate) enum JobWork {
    File(PathBuf),
    Op { op: Arc<dyn Operation>, key: Hash },
}

pub(crate) struct Job {
    pub id: usize,
    pub name: String,
    pub work: JobWork,
    pub inputs: Vec<Artifact>,
}

#[derive(Clone)]
pub(crate) struct Produced {
    pub artifact: Artifact,
    pub counts: BTreeMap<String, u64>,
    pub notes: Vec<String>,
}

#[derive(Clone)]
pub(crate) struct Done {
    pub id: usize,
    pub result: Result<Produced, String>,
    /// The operation actually ran (cache miss).
    pub ran: bool,
    /// A cache entry for this key was found corrupt (and the node re-ran).
    pub corrupt: Option<String>,
    pub files: BTreeMap<String, Hash>,
    pub duration_ms: f64,
}

impl Done {
    pub(crate) fn failed(id: usize, error: String) -> Done {
        Done {
            id,
            result: Err(error),
            ran: false,
            corrupt: None,
            files: BTreeMap::new(),
            duration_ms: 0.0,
        }
    }
}

struct Ctx<'a> {
    name: &'a str,
    on_event: &'a (dyn Fn(&Event) + Sync),
}

impl RunContext for Ctx<'_> {
    fn progress(&self, done: u64, total: u64) {
        (self.on_event)(&Event::Progress {
            name: self.name.to_string(),
            done,
            total,
        });
    }
}

pub(crate) fn panic_text(p: &(dyn std::any::Any + Send)) -> String {
    p.downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| p.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "unknown panic".to_string())
}

pub(crate) fn run_job(
    job: Job,
    store: &Store,
    output_dir: &Path,
    staging_dir: Option<&Path>,
    on_event: &(dyn Fn(&Event) + Sync),
) -> Done {
    let t0 = Instant::now();
    let mut done = Done {
        id: job.id,
        result: Err(String::new()),
        ran: false,
        corrupt: None,
        files: BTreeMap::new(),
        duration_ms: 0.0,
    };
    match &job.work {
        JobWork::File(path) => {
            done.result = std::fs::read(path)
                .map(|b| Produced {
                    artifact: Artifact::from_bytes(b),
                    counts: BTreeMap::new(),
                    notes: vec![],
                })
                .map_err(|e| format!("cannot read input file {}: {e}", path.display()));
        }
        JobWork::Op { op, key } => {
            done.result = resolve_op(
                &job,
                op.as_ref(),
                *key,
                store,
                on_event,
                &mut done.ran,
                &mut done.corrupt,
            );
            if op.emits_files()
                && let Ok(p) = &done.result
            {
                // Read in place: the files are written straight from the artifact's bytes.
                let written = p
                    .artifact
                    .file_entries()
                    .map_err(|e| e.message)
                    .and_then(|files| write_fileset(output_dir, staging_dir, &files));
                match written {
                    Ok((hashes, written)) => {
                        done.files = hashes;
                        if !done.ran
                            && !written.is_empty()
                            && let Ok(p) = &mut done.result
                        {
                            p.notes.push(format!("rewrote {}", written.join(", ")));
                        }
                    }
                    Err(e) => done.result = Err(format!("emitted files: {e}")),
                }
            }
        }
    }
    done.duration_ms = t0.elapsed().as_secs_f64() * 1000.0;
    done
}

fn resolve_op(
    job: &Job,
    op: &dyn Operation,
    key: Hash,
    store: &Store,
    on_event: &(dyn Fn(&Event) + Sync),
    ran: &mut bool,
    corrupt: &mut Option<String>,
) -> Result<Produced, String> {
    let hit = match store.load_action(key) {
        Load::Hit(rec) => match store.load_object(rec.output) {
            Load::Hit(a) => Some(Produced {
                artifact: a,
                counts: rec.counts,
                notes: rec.notes,
            }),
            Load::Missing => None,
            Load::Corrupt(d) => {
                *corrupt = Some(d);
                None
            }
        },
        Load::Missing => None,
        Load::Corrupt(d) => {
            *corrupt = Some(d);
            None
        }
    };
    if let Some(d) = corrupt.as_ref() {
        on_event(&Event::CacheCorrupt {
            name: job.name.clone(),
            detail: d.clone(),
        });
    }
    if let Some(p) = hit {
        return Ok(p);
    }
    *ran = true;
    on_event(&Event::Started {
        name: job.name.clone(),
        kind: op.kind().to_string(),
    });
    let ctx = Ctx {
        name: &job.name,
        on_event,
    };
    let out = match catch_unwind(AssertUnwindSafe(|| op.run(&ctx, &job.inputs))) {
        Ok(Ok(out)) => out,
        Ok(Err(e)) => return Err(e.message),
        Err(p) => return Err(format!("operation panicked: {}", panic_text(p.as_ref()))),
    };
    let rec = ActionRecord {
        output: out.artifact.hash(),
        counts: out.counts.clone(),
        notes: out.notes.clone(),
    };
    let mut notes = out.notes;
    if let Err(e) = store
        .put_object(&out.artifact)
        .and_then(|()| store.put_action(key, &rec))
    {
        notes.push(format!("not cached: {e}"));
    }
    Ok(Produced {
        artifact: out.artifact,
        counts: out.counts,
        notes,
    })
}
