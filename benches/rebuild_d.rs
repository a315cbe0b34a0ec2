//! Full build versus a one-curve rebuild of the seed's refinement (d) (`recipes/refinements/
//! d.toml`, ~500k tets), single job. The target: the rebuild costs no more than the
//! affected share of the full build plus a small constant, where the affected share is what the
//! nodes that re-run took in the full build. The edited curve is the top west edge of the box,
//! `box.xmin/box.zmax`: it bounds two box patches and one region (overburden_W).
//!
//! Builds take minutes, so this is a plain timed harness (one full build, then rebuilds
//! each giving the curve a new size), not criterion's ten samples. Run with
//! `cargo bench --bench rebuild_d`.

use engine::{self, BuildOptions, BuildReport, NodeState};
use georecipe::{plan, recipe};
use std::collections::BTreeMap;
use std::path::Path;
use std::time::Instant;

fn build(recipe_path: &Path, text: &str, dir: &Path) -> (BuildReport, f64) {
    let r = recipe::parse(recipe_path, text).expect("the refinement recipe parses");
    let g = plan::lower(&r).expect("lowers");
    let opts = BuildOptions {
        cache_dir: dir.join("cache"),
        output_dir: dir.join("out"),
        staging_dir: None,
        jobs: 1,
        keep_going: false,
        record: engine::DEFAULT_RECORD.to_string(),
        read_only: false,
    };
    let t = Instant::now();
    let report = engine::build(g, &opts, &|_| {}).expect("builds");
    let wall = t.elapsed().as_secs_f64();
    assert!(report.ok, "the build failed");
    (report, wall)
}

fn main() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("recipes/refinements/d.toml");
    let text = std::fs::read_to_string(&path).expect("recipes/refinements/d.toml");
    let with = |size: f64| {
        text.replace(
            "[mesh.curves]",
            &format!("[mesh.curves]\n\"box.xmin/box.zmax\" = {{ size = {size:.1} }}"),
        )
    };
    let dir = tempfile::tempdir().expect("temp dir");
    let (full, full_wall) = build(&path, &with(150.0), dir.path());
    let spent: BTreeMap<&str, f64> = full
        .nodes
        .iter()
        .map(|n| (n.name.as_str(), n.duration_ms / 1e3))
        .collect();
    let total: f64 = spent.values().sum();
    println!(
        "full build (d), -j 1: {full_wall:.2} s wall, {total:.2} s in {} nodes",
        full.nodes.len()
    );
    let mut rebuilds = Vec::new();
    // Every rebuild uses a size not seen before, so none is served from the cache.
    for (k, size) in [120.0, 130.0, 140.0].into_iter().enumerate() {
        let (r, wall) = build(&path, &with(size), dir.path());
        let ran: Vec<&str> = r
            .nodes
            .iter()
            .filter(|n| n.state == NodeState::Ran)
            .map(|n| n.name.as_str())
            .collect();
        let share: f64 = ran.iter().filter_map(|n| spent.get(n)).sum::<f64>() + 0.0;
        let heavy: Vec<&str> = ran
            .iter()
            .copied()
            .filter(|n| !n.starts_with("curve:") && !n.starts_with("patch:"))
            .collect();
        println!(
            "rebuild {k}: {wall:.2} s wall; {} nodes re-ran, whose full-build share is {share:.2} s \
             ({:.1}% of the full build); overhead {:.2} s; re-meshed: {heavy:?}",
            ran.len(),
            100.0 * share / total,
            wall - share
        );
        rebuilds.push(wall);
    }
    rebuilds.sort_by(f64::total_cmp);
    println!(
        "median one-curve rebuild {:.2} s versus full build {full_wall:.2} s ({:.1}%)",
        rebuilds[1],
        100.0 * rebuilds[1] / full_wall
    );
}
