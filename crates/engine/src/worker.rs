//! What a worker thread does with one dispatched node: read a source file, or look the node's
//! key up in the cache (verifying what it reads, or leaving a lazy output in the store: see
//! `stored`) and run the operation on a miss, storing the result; then write any emitted files
//! (into the staging directory when the build has one), unless a cached node's files are on
//! disk as the record says it emitted them (`emitted`). Panics inside an operation become node
//! failures.

use crate::artifact::{Artifact, Hash};
use crate::build::Event;
use crate::emitted::NodeFiles;
use crate::op::{Operation, RunContext};
use crate::outputs::{unchanged_on_disk, write_fileset};
use crate::store::{ActionRecord, Load, Store};
use crate::stored::Stored;
use std::collections::BTreeMap;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

pub(crate) enum JobWork {
    File(PathBuf),
    Op {
        op: Arc<dyn Operation>,
        key: Hash,
        /// A cache hit may leave the output in the store.
        lazy: bool,
        /// The files the node emitted in the record's last build, for an emitting node.
        emitted: Option<NodeFiles>,
    },
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
        JobWork::Op {
            op,
            key,
            lazy,
            emitted,
        } => {
            done.result = resolve_op(
                &job,
                op,
                (*key, *lazy),
                store,
                on_event,
                &mut done.ran,
                &mut done.corrupt,
            );
            if op.emits_files() {
                emit(
                    &mut done,
                    emitted.as_ref(),
                    output_dir,
                    staging_dir,
                    on_event,
                );
            }
        }
    }
    done.duration_ms = t0.elapsed().as_secs_f64() * 1000.0;
    done
}

/// Puts the files of an emitting node's output into place: nothing to do for a cached node
/// whose files are on disk as the record says it emitted them (`emitted`), else the files that
/// differ are written from its output (read now if it was left in the store).
fn emit(
    done: &mut Done,
    emitted: Option<&NodeFiles>,
    output_dir: &Path,
    staging_dir: Option<&Path>,
    on_event: &(dyn Fn(&Event) + Sync),
) {
    let Ok(p) = &mut done.result else {
        return;
    };
    let kept = emitted
        .filter(|e| !done.ran && e.output == p.artifact.hash())
        .filter(|e| unchanged_on_disk(output_dir, &e.files));
    if let Some(e) = kept {
        done.files = e.files.clone();
        return;
    }
    let written = write_files(p, done.ran, output_dir, staging_dir);
    if let Some((name, detail)) = p.artifact.take_repair() {
        on_event(&Event::CacheCorrupt { name, detail });
    }
    match written {
        Ok(files) => done.files = files,
        Err(e) => done.result = Err(format!("emitted files: {e}")),
    }
}

/// Writes the files of `p`'s artifact that differ on disk (read in place: straight from the
/// artifact's bytes); a cached node notes the files it had to rewrite. Returns path → hash.
fn write_files(
    p: &mut Produced,
    ran: bool,
    output_dir: &Path,
    staging_dir: Option<&Path>,
) -> Result<BTreeMap<String, Hash>, String> {
    let files = p.artifact.file_entries().map_err(|e| e.message)?;
    let (hashes, written) = write_fileset(output_dir, staging_dir, &files)?;
    if !ran && !written.is_empty() {
        p.notes.push(format!("rewrote {}", written.join(", ")));
    }
    Ok(hashes)
}

/// The output of a cache hit: read and verified, or left in the store when the node's output is
/// lazy (then only its presence is checked).
fn load_hit(
    job: &Job,
    op: &Arc<dyn Operation>,
    (output, len): (Hash, Option<u64>),
    lazy: bool,
    store: &Store,
) -> Load<Artifact> {
    if !lazy {
        return store.load_object(output, len);
    }
    if !store.has_object(output) {
        return Load::Missing;
    }
    let stored = Stored::new(
        store,
        (output, len),
        &job.name,
        op.clone(),
        job.inputs.clone(),
    );
    Load::Hit(Artifact::stored(stored))
}

/// Reads every input of a node about to run (a lazy one is read from the store here, and made
/// again if damaged, which is told as a corrupt cache entry of the node that made it).
fn read_inputs(job: &Job, on_event: &(dyn Fn(&Event) + Sync)) -> Result<(), String> {
    for a in &job.inputs {
        a.bytes().map_err(|e| e.message)?;
        if let Some((name, detail)) = a.take_repair() {
            on_event(&Event::CacheCorrupt { name, detail });
        }
    }
    Ok(())
}

/// The failure of a node whose cache entry could not be read: an I/O error, not damage, so the
/// entry is neither used nor written over.
fn unreadable(error: &str) -> String {
    format!("the cache could not be read ({error}); the entry was left as it is")
}

fn resolve_op(
    job: &Job,
    op: &Arc<dyn Operation>,
    (key, lazy): (Hash, bool),
    store: &Store,
    on_event: &(dyn Fn(&Event) + Sync),
    ran: &mut bool,
    corrupt: &mut Option<String>,
) -> Result<Produced, String> {
    let hit = match store.load_action(key) {
        Load::Hit(rec) => match load_hit(job, op, (rec.output, rec.output_len), lazy, store) {
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
            Load::Unreadable(e) => return Err(unreadable(&e)),
        },
        Load::Missing => None,
        Load::Corrupt(d) => {
            *corrupt = Some(d);
            None
        }
        Load::Unreadable(e) => return Err(unreadable(&e)),
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
    read_inputs(job, on_event)?;
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
    let rec = ActionRecord::of(&out.artifact, out.counts.clone(), out.notes.clone());
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
