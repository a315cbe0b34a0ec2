//! Toy operations for the engine's tests: integers flowing through a DAG, with a shared run
//! counter so tests can prove that a node did or did not execute.
#![allow(dead_code)]

use engine::*;
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};

/// Counts executions, per node kind+params text and in total.
#[derive(Default, Clone)]
pub struct Runs {
    total: Arc<AtomicUsize>,
    log: Arc<Mutex<Vec<String>>>,
}

impl Runs {
    pub fn total(&self) -> usize {
        self.total.load(Ordering::SeqCst)
    }
    pub fn reset(&self) {
        self.total.store(0, Ordering::SeqCst);
        self.log.lock().unwrap().clear();
    }
    fn hit(&self, what: String) {
        self.total.fetch_add(1, Ordering::SeqCst);
        self.log.lock().unwrap().push(what);
    }
}

type F = fn(&Params, &[i64]) -> Result<i64, String>;

/// A pure integer operation.
pub struct Toy {
    pub kind: &'static str,
    pub version: u32,
    pub params: Params,
    pub f: F,
    pub runs: Runs,
}

fn int(p: &Params, k: &str) -> i64 {
    match p.get(k) {
        Some(Param::Int(i)) => *i,
        _ => 0,
    }
}

impl Operation for Toy {
    fn kind(&self) -> &'static str {
        self.kind
    }
    fn version(&self) -> u32 {
        self.version
    }
    fn params(&self) -> Params {
        self.params.clone()
    }
    fn run(&self, ctx: &dyn RunContext, inputs: &[Artifact]) -> Result<Output, OpError> {
        self.runs.hit(format!("{}:{:?}", self.kind, self.params));
        ctx.progress(0, 1);
        let mut vals = Vec::new();
        for a in inputs {
            vals.push(decode_int(a)?);
        }
        let v = (self.f)(&self.params, &vals).map_err(OpError::from)?;
        ctx.progress(1, 1);
        Ok(Output::new(Artifact::encode(&v)?).count("value", v.unsigned_abs()))
    }
}

/// Inputs are postcard i64, or UTF-8 decimal text (file nodes).
pub fn decode_int(a: &Artifact) -> Result<i64, OpError> {
    if let Ok(s) = std::str::from_utf8(a.bytes()?)
        && let Ok(v) = s.trim().parse::<i64>()
    {
        return Ok(v);
    }
    a.decode::<i64>()
}

pub fn konst(v: i64, runs: &Runs) -> Arc<dyn Operation> {
    Arc::new(Toy {
        kind: "const",
        version: 1,
        params: Params::new().with("value", v).unwrap(),
        f: |p, _| Ok(int(p, "value")),
        runs: runs.clone(),
    })
}

/// Sum of inputs plus `extra`.
pub fn add(extra: i64, runs: &Runs) -> Arc<dyn Operation> {
    Arc::new(Toy {
        kind: "add",
        version: 1,
        params: Params::new().with("extra", extra).unwrap(),
        f: |p, v| Ok(v.iter().sum::<i64>() + int(p, "extra")),
        runs: runs.clone(),
    })
}

pub fn add_v(extra: i64, version: u32, runs: &Runs) -> Arc<dyn Operation> {
    Arc::new(Toy {
        kind: "add",
        version,
        params: Params::new().with("extra", extra).unwrap(),
        f: |p, v| Ok(v.iter().sum::<i64>() + int(p, "extra")),
        runs: runs.clone(),
    })
}

/// Sum of inputs modulo `m`.
pub fn modulo(m: i64, runs: &Runs) -> Arc<dyn Operation> {
    Arc::new(Toy {
        kind: "mod",
        version: 1,
        params: Params::new().with("m", m).unwrap(),
        f: |p, v| {
            v.iter()
                .sum::<i64>()
                .checked_rem_euclid(int(p, "m"))
                .ok_or_else(|| "modulo by zero".to_string())
        },
        runs: runs.clone(),
    })
}

/// Always fails.
pub fn fail(runs: &Runs) -> Arc<dyn Operation> {
    Arc::new(Toy {
        kind: "fail",
        version: 1,
        params: Params::new(),
        f: |_, _| Err("toy failure: always fails".into()),
        runs: runs.clone(),
    })
}

/// Emits `out/<stem>.txt` with the sum of its inputs.
pub struct Export {
    pub stem: String,
    pub runs: Runs,
}

impl Operation for Export {
    fn kind(&self) -> &'static str {
        "export"
    }
    fn version(&self) -> u32 {
        1
    }
    fn params(&self) -> Params {
        Params::new().with("stem", self.stem.as_str()).unwrap()
    }
    fn run(&self, _: &dyn RunContext, inputs: &[Artifact]) -> Result<Output, OpError> {
        self.runs.hit("export".into());
        let mut sum = 0;
        for a in inputs {
            sum += decode_int(a)?;
        }
        let set = FileSet::new().with(
            &format!("out/{}.txt", self.stem),
            format!("{sum}\n").into_bytes(),
        );
        Ok(Output::new(Artifact::encode(&set)?).count("files", 1))
    }
    fn emits_files(&self) -> bool {
        true
    }
}

/// Splits its node's integer output `n` into parts `part:0..n` (each = n + i) and a `join`
/// summing them; with `cascade`, `part:0` expands again into `sub:0`.
pub struct Split {
    pub runs: Runs,
    pub cascade: bool,
}

impl Expander for Split {
    fn expand(&self, output: &Artifact, x: &mut Expansion) -> Result<(), OpError> {
        let n = decode_int(output)?;
        if n < 0 {
            return Err(OpError::from(
                "cannot split into a negative number of parts",
            ));
        }
        let parent = x.node("count").ok_or("no count node")?;
        let mut parts = Vec::new();
        for i in 0..n {
            let id = x
                .add_op(&format!("part:{i}"), add(i, &self.runs), &[parent])
                .map_err(|e| e.to_string())?;
            if i == 0 && self.cascade {
                x.set_expander(
                    id,
                    Arc::new(Sub {
                        runs: self.runs.clone(),
                    }),
                )
                .map_err(|e| e.to_string())?;
            }
            parts.push(id);
        }
        x.add_op("join", add(0, &self.runs), &parts)
            .map_err(|e| e.to_string())?;
        Ok(())
    }
}

pub struct Sub {
    pub runs: Runs,
}

impl Expander for Sub {
    fn expand(&self, _output: &Artifact, x: &mut Expansion) -> Result<(), OpError> {
        let p = x.node("part:0").ok_or("no part:0")?;
        x.add_op("sub:0", add(100, &self.runs), &[p])
            .map_err(|e| e.to_string())?;
        Ok(())
    }
}

pub fn opts(dir: &Path, jobs: usize) -> BuildOptions {
    BuildOptions {
        cache_dir: dir.join("cache"),
        output_dir: dir.join("work"),
        staging_dir: None,
        jobs,
        keep_going: true,
        record: DEFAULT_RECORD.to_string(),
        read_only: false,
    }
}

pub fn quiet(_: &Event) {}

pub fn run(g: BuildGraph, o: &BuildOptions) -> BuildReport {
    build(g, o, &quiet).expect("engine error")
}

pub fn state(r: &BuildReport, name: &str) -> NodeState {
    r.node(name)
        .unwrap_or_else(|| panic!("no node {name}"))
        .state
}

pub fn value(r: &BuildReport, name: &str) -> i64 {
    decode_int(
        r.artifact(name)
            .unwrap_or_else(|| panic!("no artifact {name}")),
    )
    .unwrap()
}

/// Every state in the report, by name.
pub fn states(r: &BuildReport) -> Vec<(String, NodeState)> {
    r.nodes.iter().map(|n| (n.name.clone(), n.state)).collect()
}

/// `op` whose cached output may stay unread in the store (`Operation::lazy_output`).
pub struct Lazy(pub Arc<dyn Operation>);

impl Operation for Lazy {
    fn kind(&self) -> &'static str {
        self.0.kind()
    }
    fn version(&self) -> u32 {
        self.0.version()
    }
    fn params(&self) -> Params {
        self.0.params()
    }
    fn run(&self, ctx: &dyn RunContext, inputs: &[Artifact]) -> Result<Output, OpError> {
        self.0.run(ctx, inputs)
    }
    fn emits_files(&self) -> bool {
        self.0.emits_files()
    }
    fn lazy_output(&self) -> bool {
        true
    }
}

pub fn lazy(op: Arc<dyn Operation>) -> Arc<dyn Operation> {
    Arc::new(Lazy(op))
}
