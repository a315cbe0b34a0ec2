//! `jobs` bounds all the work: nodes and the parallel loops inside them share one pool of `jobs`
//! threads, so a build never computes on more threads than it was given.

use crate::engine_support::{opts, run};
use engine::*;
use rayon::prelude::*;
use std::collections::{BTreeSet, HashSet};
use std::sync::{Arc, Mutex};
use std::thread::ThreadId;

/// Runs a parallel loop (as the intersection and validation stages do) and records the threads
/// that computed it and the size of the pool it saw.
struct Spread {
    seen: Arc<Mutex<(HashSet<ThreadId>, BTreeSet<usize>)>>,
    salt: i64,
}

impl Operation for Spread {
    fn kind(&self) -> &'static str {
        "spread"
    }
    fn version(&self) -> u32 {
        1
    }
    fn params(&self) -> Params {
        let mut p = Params::new();
        p.set("salt", self.salt).unwrap();
        p
    }
    fn run(&self, _ctx: &dyn RunContext, _inputs: &[Artifact]) -> Result<Output, OpError> {
        let threads: HashSet<ThreadId> = (0..2000u64)
            .into_par_iter()
            .map(|i| {
                // A little work per item, so idle threads have time to steal.
                let mut x = i;
                for _ in 0..2000 {
                    x = x.wrapping_mul(6364136223846793005).wrapping_add(1);
                }
                std::hint::black_box(x);
                std::thread::current().id()
            })
            .collect();
        let mut seen = self.seen.lock().unwrap();
        seen.0.extend(threads);
        seen.0.insert(std::thread::current().id());
        seen.1.insert(rayon::current_num_threads());
        Ok(Output::new(Artifact::encode(&self.salt)?))
    }
}

/// Builds eight independent spreading nodes with `jobs` and returns the threads that computed
/// and the pool sizes the nodes saw.
fn spread(jobs: usize) -> (HashSet<ThreadId>, BTreeSet<usize>) {
    let seen = Arc::new(Mutex::new((HashSet::new(), BTreeSet::new())));
    let mut g = BuildGraph::new();
    for salt in 0..8 {
        let op = Spread {
            seen: seen.clone(),
            salt,
        };
        g.add_op(&format!("spread:{salt}"), Arc::new(op), &[])
            .unwrap();
    }
    let dir = tempfile::tempdir().unwrap();
    let report = run(g, &opts(dir.path(), jobs));
    assert!(report.ok, "{:?}", report.nodes);
    let seen = seen.lock().unwrap();
    (seen.0.clone(), seen.1.clone())
}

#[test]
fn one_job_computes_nodes_and_their_parallel_loops_on_one_thread() {
    let (threads, pools) = spread(1);
    assert_eq!(threads.len(), 1, "{threads:?}");
    assert_eq!(pools, BTreeSet::from([1]));
}

#[test]
fn two_jobs_never_compute_on_more_than_two_threads() {
    let (threads, pools) = spread(2);
    assert!(threads.len() <= 2, "{threads:?}");
    assert_eq!(pools, BTreeSet::from([2]));
}

#[test]
fn the_pool_is_the_builds_own_whatever_the_global_pool_is() {
    // The global pool has one thread per core; the build's pool has what `jobs` says.
    let (_, pools) = spread(3);
    assert_eq!(pools, BTreeSet::from([3]));
}
