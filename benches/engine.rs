//! Engine overhead with trivial operations: a cold build (everything runs and is stored) and a
//! warm build (everything is verified from the cache) of a layered 500-node graph.

use criterion::{Criterion, criterion_group, criterion_main};
use engine::*;
use std::sync::Arc;

struct Sum(i64);

impl Operation for Sum {
    fn kind(&self) -> &'static str {
        "sum"
    }
    fn version(&self) -> u32 {
        1
    }
    fn params(&self) -> Params {
        Params::new().with("extra", self.0).unwrap_or_default()
    }
    fn run(&self, _: &dyn RunContext, inputs: &[Artifact]) -> Result<Output, OpError> {
        let mut s = self.0;
        for a in inputs {
            s = s.wrapping_add(a.decode::<i64>()?);
        }
        // A few KiB per artifact so hashing and I/O are visible.
        let payload: Vec<i64> = (0..512).map(|i| s.wrapping_mul(i)).collect();
        Ok(Output::new(Artifact::encode(&(s, payload))?))
    }
}

struct First;
impl Operation for First {
    fn kind(&self) -> &'static str {
        "first"
    }
    fn version(&self) -> u32 {
        1
    }
    fn params(&self) -> Params {
        Params::new()
    }
    fn run(&self, _: &dyn RunContext, inputs: &[Artifact]) -> Result<Output, OpError> {
        let (s, _): (i64, Vec<i64>) = inputs.first().ok_or("no input")?.decode()?;
        Ok(Output::new(Artifact::encode(&s)?))
    }
}

fn layered(width: usize, depth: usize) -> BuildGraph {
    let mut g = BuildGraph::new();
    let mut prev: Vec<NodeId> = Vec::new();
    for d in 0..depth {
        let mut layer = Vec::new();
        for w in 0..width {
            let id = if prev.is_empty() {
                g.add_op(&format!("n{d}/{w}"), Arc::new(Sum((w + 1) as i64)), &[])
            } else {
                let a = g
                    .add_op(&format!("u{d}/{w}"), Arc::new(First), &[prev[w]])
                    .expect("unique");
                let b = g
                    .add_op(
                        &format!("v{d}/{w}"),
                        Arc::new(First),
                        &[prev[(w + 1) % width]],
                    )
                    .expect("unique");
                g.add_op(&format!("n{d}/{w}"), Arc::new(Sum(d as i64)), &[a, b])
            }
            .expect("unique");
            layer.push(id);
        }
        prev = layer;
    }
    g
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("engine");
    group.sample_size(10);
    for jobs in [1, 2] {
        group.bench_function(format!("cold build, 500 nodes, -j{jobs}"), |b| {
            b.iter(|| {
                let dir = tempfile::tempdir().expect("tempdir");
                let o = BuildOptions {
                    jobs,
                    ..BuildOptions::new(dir.path().join("c"), dir.path().join("o"))
                };
                let r = build(layered(20, 9), &o, &|_| {}).expect("build");
                assert!(r.ok);
            })
        });
        let dir = tempfile::tempdir().expect("tempdir");
        let o = BuildOptions {
            jobs,
            ..BuildOptions::new(dir.path().join("c"), dir.path().join("o"))
        };
        build(layered(20, 9), &o, &|_| {}).expect("build");
        group.bench_function(format!("warm build, 500 nodes, -j{jobs}"), |b| {
            b.iter(|| {
                let r = build(layered(20, 9), &o, &|_| {}).expect("build");
                assert_eq!(r.count(NodeState::Cached), r.nodes.len());
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
