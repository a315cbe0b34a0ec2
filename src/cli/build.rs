//! `recipe build`: load, lower, run the engine, keep the lock file and the recipe's record (its
//! last report and graph, in the cache: see `cache`).
//!
//! What it prints on stderr, in cargo's manner: a line per node that ran (`render`), each
//! failure in full, how many nodes were cached, what validation found on the surfaces imported,
//! then a short summary (regions, tets and the worst tet's quality, the output files) and the
//! `Finished` line, timed from the start of the command to the last file written. `-v` adds a
//! line per cached node and the full Tables 1 and 2; `--quiet` leaves errors and the final line.

use super::cache::{
    RecipeRecord, cache_dir, last_graph_path, last_report_path, lock_path, recipe_dir,
};
use super::render::{Renderer, Verbosity};
use super::report::{ReportPlace, write_report};
use super::report_state::ReportState;
use super::staging::Staging;
use super::user_file::{UserFile, read_text};
use super::{BuildArgs, Failure, load};
use crate::plan;
use engine::{self, BuildOptions, BuildReport, LockFile, NodeState};
use std::path::Path;

/// One build of `args.recipe`. Returns the report when the build succeeded.
///
/// The cache's lock is held for the whole command. With `--locked`, the lock file is read first,
/// and the build's output files (the engine's and the report) go to a staging directory that is
/// published into the output directory only when the build succeeded and matches the lock: a
/// locked build that fails changes nothing.
pub fn run(args: &BuildArgs) -> Result<BuildReport, Failure> {
    let started = std::time::Instant::now();
    let verbosity = args.verbosity();
    let recipe = load::load(&args.recipe)?;
    let graph = plan::lower(&recipe).map_err(|e| Failure(format!("error: {e}")))?;
    let cache = cache_dir(&args.recipe, &args.cache);
    let record = RecipeRecord::of(&args.recipe, &cache);
    let output_dir = recipe_dir(&args.recipe).join(&recipe.output.dir);
    let lock_file = lock_path(&args.recipe);
    let renderer = Renderer::new(&recipe, verbosity, args.explain);
    // Held until the command returns, from before the lock file is read to after the lock file,
    // the report and the published outputs are written: a build racing this one cannot
    // interleave its files with ours.
    let cache_lock = engine::lock_cache(
        &BuildOptions {
            record: record.name.clone(),
            read_only: args.read_only_cache,
            ..BuildOptions::new(&cache, &output_dir)
        },
        &|e| renderer.event(e),
    )?;
    // A cache the build may only read gets nothing written into it: no entries, no record.
    let read_only = cache_lock.read_only();
    if read_only && verbosity >= Verbosity::Normal {
        errln!(
            "{:>12} the cache {} is read-only: this build reads it and stores nothing in it",
            "Warning",
            cache.display()
        );
    }
    let record_dir = record.dir(&cache);
    let sweep_record = (!read_only).then_some(record_dir.as_path());
    super::debris::sweep_recipe(&lock_file, &output_dir, sweep_record);
    let (locked, staging) = if args.locked {
        (
            Some(read_lock(&lock_file)?),
            Some(Staging::beside(&output_dir)?),
        )
    } else {
        (None, None)
    };
    // Where this build writes its files: the output directory, or the staging directory.
    let write_dir = staging.as_ref().map_or(output_dir.as_path(), |s| s.path());
    let jobs = args
        .jobs
        .unwrap_or_else(|| {
            std::thread::available_parallelism()
                .map(|n| n.get())
                .unwrap_or(1)
        })
        .max(1);
    let opts = BuildOptions {
        cache_dir: cache.clone(),
        output_dir: output_dir.clone(),
        staging_dir: staging.as_ref().map(|s| s.path().to_path_buf()),
        jobs,
        keep_going: true,
        record: record.name.clone(),
        read_only,
    };
    // Where the meshes of two surfaces cross, or a mesh fails where curves come close, refined
    // there and built again (`crossings`, `close_places`).
    let mut recipe = recipe;
    let mut graph = Some(graph);
    let mut rounds = 0;
    let mut failed_before = std::collections::BTreeMap::new();
    let mut failed_names = std::collections::BTreeSet::new();
    let report = loop {
        let graph = match graph.take() {
            Some(g) => g,
            None => plan::lower(&recipe).map_err(|e| Failure(format!("error: {e}")))?,
        };
        let last = rounds == super::crossings::ROUNDS;
        if !last {
            renderer.hold_failures();
        }
        let on_event = |e: &engine::Event| renderer.event(e);
        let retry = engine::Retry {
            failed_before: std::mem::take(&mut failed_before),
            focus: std::mem::take(&mut failed_names),
        };
        let again = || plan::lower(&recipe).map_err(|e| Failure(format!("error: {e}")));
        let report = build_round(graph, again, &opts, &cache_lock, retry, &on_event)?;
        let model = (!report.ok && !last)
            .then(|| built_model(&report))
            .flatten();
        let (round, close) = match model {
            None => Default::default(),
            Some(m) => (
                super::crossings::refinements(&report, &recipe, Some(&m)),
                super::close_places::round(&report, &recipe, Some(&m)),
            ),
        };
        let added = round.added;
        let none = added.is_empty() && close.named.is_empty();
        renderer.release_failures(none);
        for why in round.refused.iter().chain(&close.refused).filter(|_| none) {
            errln!("{:>12} {why}", "note");
        }
        if none {
            break report;
        }
        if verbosity >= Verbosity::Normal {
            for r in &added {
                errln!("{:>12} {}", "Refining", super::crossings::said(r));
            }
            for said in &close.said {
                errln!("{:>12} {said}", "Refining");
            }
        }
        recipe.mesh.refine.extend(added);
        (recipe.mesh.refine_close_curves.named).extend(close.named);
        rounds += 1;
        // What failed and is out of the refinement's reach fails again at once; what failed
        // is built first.
        let failed = || report.nodes.iter().filter(|n| n.state == NodeState::Failed);
        failed_before = failed()
            .filter_map(|n| Some((n.key, n.error.clone()?)))
            .collect();
        failed_names = failed().map(|n| n.name.clone()).collect();
    };
    let cached = report.count(NodeState::Cached) + report.count(NodeState::CutOff);
    if verbosity == Verbosity::Normal && cached > 0 {
        let cut = report.count(NodeState::CutOff);
        let cut = if cut > 0 {
            format!(" ({cut} cut off: their inputs re-ran to the same outputs)")
        } else {
            String::new()
        };
        errln!("{:>12} {cached} node{}{cut}", "Cached", plural(cached));
    }

    // This recipe's record: where it is (for `gc`), its last report and graph.
    if !read_only {
        record.save(&cache)?;
        write_record(
            &last_report_path(&record_dir),
            report.to_json().to_string().as_bytes(),
        )?;
        write_record(&last_graph_path(&record_dir), report.to_dot().as_bytes())?;
    }
    // Printed once the report and the lock file are written, or as the build fails: a reader
    // that closes standard output early (`| head`) ends the command where it is printed, which
    // must not leave the report and the lock file as the last build's.
    let json = args.json.then(|| {
        let mut json = report.to_json();
        if let Some(model) = built_model(&report)
            && let Some(obj) = json.as_object_mut()
        {
            obj.insert("model".to_string(), model.summary());
        }
        serde_json::to_string_pretty(&json).unwrap_or_default()
    });
    let print_json = || -> Result<(), Failure> {
        if let Some(text) = &json {
            outln!("{text}");
        }
        Ok(())
    };
    if verbosity >= Verbosity::Normal {
        print_findings(&report);
        print_crossings(&report);
        print_thin_regions(&recipe, &report);
        print_close_curves(&recipe, &report);
        print_failures_near_close_curves(&recipe, &report);
        print_folds_on_faceted_supports(&recipe, &report);
    }
    let count = |s: NodeState| report.count(s);
    let summary = format!(
        "{} ran, {} cached, {} cut off",
        count(NodeState::Ran),
        count(NodeState::Cached),
        count(NodeState::CutOff),
    );
    // The report and the validation are written for failed builds too: they say what failed,
    // what ran and what is wrong with the surfaces (under `--locked` they are staged, and
    // dropped with the staging directory).
    let derivations = engine::Derivations::open(&opts)?;
    let place = ReportPlace {
        write_dir,
        output_dir: &output_dir,
        record_dir: &record_dir,
    };
    // The report's figures of a large mesh take seconds: measured on the build's `-j` threads.
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(jobs)
        .build()
        .map_err(|e| Failure(format!("error: report: no threads for it: {e}")))?;
    let report_state =
        pool.install(|| write_report(&recipe, &args.recipe, &report, &derivations, &place))?;
    derivations.save()?;
    super::report::write_validation(&report, write_dir)?;
    // The record describes the report in the output directory: a staged one once published.
    let save_state = |state: Option<ReportState>| match state {
        Some(s) if !read_only => s.save(&record_dir),
        _ => Ok(()),
    };
    let report_state = match staging {
        None => save_state(report_state).map(|()| None)?,
        Some(_) => report_state,
    };
    if !report.ok {
        print_json()?;
        let unfocused = (report.nodes.iter())
            .filter(|n| n.reason == engine::RebuildReason::Unfocused)
            .count();
        let left = match unfocused {
            0 => String::new(),
            n => format!(
                ", {n} not tried again (the last round built what had failed first, and it \
                 failed again)"
            ),
        };
        return Err(Failure(format!(
            "error: build of {} failed: {summary}, {} failed, {} skipped{left}",
            args.recipe.display(),
            count(NodeState::Failed),
            count(NodeState::Skipped) - unfocused
        )));
    }

    let new_lock = LockFile::from_report(&report);
    if let Some(old) = &locked {
        let diff = old.diff(&new_lock);
        if !diff.is_empty() {
            let mut msg = format!(
                "error: the build differs from {} (--locked):",
                lock_file.display()
            );
            for d in &diff {
                msg.push_str("\n  ");
                msg.push_str(d);
            }
            print_json()?;
            return Err(Failure(msg));
        }
        if let Some(staging) = staging {
            staging.publish(&output_dir)?;
            save_state(report_state)?;
        }
    } else {
        let text = new_lock.to_text();
        let old_text = match read_text(&lock_file) {
            Ok(UserFile::Text(t)) => Some(t),
            _ => None,
        };
        // A lock is never rewritten over an output that changed without its version.
        if let Some(old) = old_text.as_deref().and_then(|t| LockFile::parse(t).ok()) {
            let stale = old.unversioned_changes(&new_lock);
            if !stale.is_empty() {
                let mut msg = format!("error: not updating {}:", lock_file.display());
                for d in &stale {
                    msg.push_str("\n  ");
                    msg.push_str(d);
                }
                print_json()?;
                return Err(Failure(msg));
            }
        }
        if old_text.as_deref() != Some(text.as_str()) {
            write_atomic(&lock_file, text.as_bytes())?;
        }
    }
    print_json()?;
    if verbosity >= Verbosity::Normal {
        let model = &recipe.model.name;
        if verbosity == Verbosity::Verbose
            && let Ok(text) =
                std::fs::read_to_string(output_dir.join(format!("{model}.quality.txt")))
        {
            errln!("\n{text}");
        }
        let quality = std::fs::read(output_dir.join(format!("{model}.quality.json")))
            .ok()
            .and_then(|b| serde_json::from_slice(&b).ok());
        if let Some(line) = quality.as_ref().and_then(mesh_summary) {
            errln!("{:>12} {line}", "Mesh");
        }
        if let Some(warning) = quality
            .as_ref()
            .and_then(|q| thin_at_worst(&recipe, &report, q))
        {
            errln!("{:>12} {warning}", "Warning");
        }
        // Every file the build wrote (or, staged, published) into the output directory.
        let mut files: Vec<String> = report.output_files.keys().cloned().collect();
        files.push("validation.json".into());
        files.extend(super::report_state::FILES.map(String::from));
        errln!("{:>12} {}", "Outputs", files.join(", "));
    }
    errln!(
        "{:>12} {} in {:.2}s: {summary}; outputs in {}",
        "Finished",
        recipe.model.name,
        started.elapsed().as_secs_f64(),
        output_dir.display()
    );
    Ok(report)
}

/// One round of the build: `graph` built whole, or, after a failed round (`retry`), first only
/// what failed there and what it needs (the other nodes skipped as unfocused), and the whole
/// graph (`again`, lowered anew) only if that now succeeds. A refinement that does not reach a
/// failure so costs the failed nodes' part of the model, not all of it; and as the nodes a
/// focused build runs are a function of the graph, the rounds are the same for any `-j`.
fn build_round(
    graph: engine::BuildGraph,
    again: impl FnOnce() -> Result<engine::BuildGraph, Failure>,
    opts: &BuildOptions,
    lock: &engine::DirLock,
    retry: engine::Retry,
    on_event: &(dyn Fn(&engine::Event) + Sync),
) -> Result<BuildReport, Failure> {
    if retry.focus.is_empty() {
        return Ok(engine::build_again(graph, opts, lock, &retry, on_event)?);
    }
    let probe = engine::build_again(graph, opts, lock, &retry, on_event)?;
    let mended = (retry.focus.iter()).all(|n| probe.node(n).is_none_or(|r| r.state.is_ok()));
    if !mended {
        return Ok(probe);
    }
    let whole = engine::Retry {
        focus: Default::default(),
        ..retry
    };
    Ok(engine::build_again(again()?, opts, lock, &whole, on_event)?)
}

fn plural(n: usize) -> &'static str {
    if n == 1 { "" } else { "s" }
}

/// The mesh in one line from the quality tables (`<model>.quality.json`): how many regions and
/// tets, and the worst tet's quality, its smallest normalised mean ratio and smallest dihedral
/// angle, each with its region. `None` when nothing was meshed.
fn mesh_summary(quality: &serde_json::Value) -> Option<String> {
    let regions: Vec<&serde_json::Value> = quality["table2"]
        .as_array()?
        .iter()
        .filter(|r| r["name"] != "all")
        .collect();
    let tets: u64 = regions.iter().filter_map(|r| r["elements"].as_u64()).sum();
    if tets == 0 {
        return None;
    }
    let worst = |key: &str| {
        regions
            .iter()
            .filter_map(|r| Some((r[key].as_f64()?, r["name"].as_str()?)))
            .min_by(|a, b| a.0.total_cmp(&b.0))
    };
    let (ratio, ratio_in) = worst("min")?;
    let (dihedral, dihedral_in) = worst("min_dihedral_deg")?;
    let row = regions.iter().find(|r| r["name"] == dihedral_in)?;
    Some(format!(
        "{} region{}, {tets} tets; worst tet: mean ratio {ratio:.4} ({ratio_in}), \
         dihedral {dihedral:.2}° ({dihedral_in}{})",
        regions.len(),
        plural(regions.len()),
        sharp_boundary(row)
    ))
}

/// Where a region's surfaces leave its tets an angle under the seed's dihedral bar
/// ([`plan::ops::DIHEDRAL_BAR`]), the angle and its place, said after the region's name: no mesh of that
/// boundary does better there.
fn sharp_boundary(row: &serde_json::Value) -> String {
    let (Some(deg), Some(at)) = (
        row["min_dihedral_bound_deg"].as_f64(),
        row["min_dihedral_bound_at"].as_array(),
    ) else {
        return String::new();
    };
    let at: Vec<f64> = at.iter().filter_map(|x| x.as_f64()).collect();
    match at[..] {
        [x, y, z] if deg < plan::ops::DIHEDRAL_BAR => {
            format!(", whose surfaces meet at {deg:.2}° near ({x:.1}, {y:.1}, {z:.1})")
        }
        _ => String::new(),
    }
}

/// Where the worst tet of the summary's region is under the bar though the region's surfaces
/// allow more, and the region is thinner there than its elements: why, and what to write.
fn thin_at_worst(
    recipe: &crate::recipe::Recipe,
    report: &BuildReport,
    quality: &serde_json::Value,
) -> Option<String> {
    // Row by row: an empty region's row (its angles written as null) is left out, not all.
    let table2: Vec<export::quality::TetQuality> = (quality["table2"].as_array()?.iter())
        .filter_map(|row| serde_json::from_value(row.clone()).ok())
        .collect();
    plan::ops::thin_at_worst(recipe, &built_model(report)?, &table2)
}

/// The committed lock file, for `--locked`.
fn read_lock(lock_file: &Path) -> Result<LockFile, Failure> {
    let cannot = |why: String| {
        Failure(format!(
            "error: --locked, but the lock file {} cannot be read: {why}",
            lock_file.display()
        ))
    };
    let text = match read_text(lock_file) {
        Ok(UserFile::Text(text)) => text,
        Ok(UserFile::Missing) => {
            return Err(Failure(format!(
                "error: --locked, but there is no lock file {}: build once without --locked and commit it",
                lock_file.display()
            )));
        }
        Ok(UserFile::Not(what)) => return Err(cannot(format!("it is {what}, not a file"))),
        Err(e) => return Err(cannot(e.to_string())),
    };
    LockFile::parse(&text).map_err(|e| Failure(format!("error: {}: {e}", lock_file.display())))
}

/// Writes a file atomically and durably (`engine::write_atomic`), naming the file on failure.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), Failure> {
    engine::write_atomic(path, bytes, true)
        .map_err(|e| Failure(format!("error: cannot write {}: {e}", path.display())))
}

/// Writes a file of the recipe's record (`engine::checked`: atomic, checksummed, left alone when
/// it holds `bytes` already). Not synced to disk, as the engine's manifest: a record lost in a
/// crash only costs the next build some work (explanations, a report written again), never a
/// wrong output.
pub fn write_record(path: &Path, bytes: &[u8]) -> Result<(), Failure> {
    engine::checked::write(path, bytes)
        .map_err(|e| Failure(format!("error: cannot write {}: {e}", path.display())))
}

/// The surfaces that meet without being paired, when the check ran in this build.
fn print_crossings(report: &BuildReport) {
    let ran = report
        .node("crossings")
        .is_some_and(|n| n.state == NodeState::Ran);
    for c in plan::ops::unpaired_crossings(report).iter().filter(|_| ran) {
        errln!("{:>12} {}", "Warning", c.message());
    }
}

/// Whether node `name` ran in this build.
fn ran(report: &BuildReport, name: &str) -> bool {
    (report.nodes.iter()).any(|n| n.name == name && n.state == NodeState::Ran)
}

/// The sizes' warnings for the regions whose tet mesh ran and the curves whose discretization
/// ran in this build (a cached one was warned about when it ran; the report keeps every
/// warning).
fn print_thin_regions(recipe: &crate::recipe::Recipe, report: &BuildReport) {
    let Some(model) = built_model(report) else {
        return;
    };
    let thin = plan::ops::thin_region_warnings(recipe, &model);
    let thin: Vec<_> = (thin.iter())
        .filter(|t| ran(report, &format!("tet_mesh:{}", t.region)))
        .collect();
    // Many regions one element across (surfaces crossing over and over) are told at once.
    let across: Vec<_> = thin
        .iter()
        .copied()
        .filter(|t| t.one_across.is_some())
        .collect();
    let summed = across.len() > plan::ops::THIN_REGIONS_TOLD;
    for t in thin.iter().filter(|t| !summed || t.one_across.is_none()) {
        errln!("{:>12} {}", "Warning", t.message);
    }
    if summed {
        errln!(
            "{:>12} {}",
            "Warning",
            plan::ops::one_across_summary(&across)
        );
    }
    for (curves, warning) in plan::ops::short_curve_warnings(recipe, &model) {
        if curves
            .iter()
            .any(|c| ran(report, &format!("discretize:{c}")))
        {
            errln!("{:>12} {warning}", "Warning");
        }
    }
}

/// Which surfaces have no part in the model, where the imported surfaces almost share vertices
/// (a non-conformal contact) and where the model's curves come closer than their mesh can
/// resolve, when the model was built in this build (the report keeps the warnings).
fn print_close_curves(recipe: &crate::recipe::Recipe, report: &BuildReport) {
    if (report.node("model")).is_none_or(|n| n.state != NodeState::Ran) {
        return;
    }
    let Some(model) = built_model(report) else {
        return;
    };
    let close = plan::ops::close_curve_warnings(recipe, &model);
    for warning in plan::ops::vanished_surface_warnings(recipe, &model)
        .into_iter()
        .chain(plan::ops::non_conformity_warnings(&model))
        .chain(close)
    {
        errln!("{:>12} {warning}", "Warning");
    }
}

/// For each surface or tet mesh that failed at coordinates near where curves come closer than
/// their mesh can resolve: that place, as the likely cause.
fn print_failures_near_close_curves(recipe: &crate::recipe::Recipe, report: &BuildReport) {
    let failed_at: Vec<(&str, [f64; 3])> = (report.nodes.iter())
        .filter(|n| n.state == NodeState::Failed)
        .filter(|n| n.kind == "tet_mesh" || n.kind == "surface_mesh")
        .filter_map(|n| {
            Some((
                n.name.as_str(),
                super::culprit::failure_place(n.error.as_deref()?)?,
            ))
        })
        .collect();
    if failed_at.is_empty() {
        return;
    }
    let Some(model) = built_model(report) else {
        return;
    };
    let places: Vec<[f64; 3]> = failed_at.iter().map(|&(_, at)| at).collect();
    let causes = plan::ops::close_curves_near(recipe, &model, &places);
    for ((node, _), cause) in failed_at.iter().zip(causes) {
        if let Some(cause) = cause {
            errln!("{:>12} `{node}` failed {cause}", "note");
        }
    }
}

/// Prints what validation found on every surface imported in this build that had findings, what
/// repair removed and what remains, then the report (`validation.json` beside the outputs has
/// all of it).
fn print_findings(report: &BuildReport) {
    for n in report
        .nodes
        .iter()
        .filter(|n| n.kind == "import" && n.counts.get("findings").is_some_and(|&f| f > 0))
    {
        let Some(data) = report
            .artifact(&n.name)
            .and_then(|a| a.decode::<crate::plan::ops::SurfaceData>().ok())
        else {
            continue;
        };
        if n.state == NodeState::Ran {
            let (found, remaining) = plan::ops::findings_by_kind(&data.report_json, &n.counts);
            errln!(
                "{:>12} surface `{}`: {}",
                "Warning",
                data.name,
                gocad::validate::repair_summary(&found, &remaining)
            );
            for line in data.report_text.lines().take(20) {
                errln!("             {line}");
            }
        }
    }
}

/// For each surface mesh that folded where its support turns sharply, on a surface meshed on its
/// facets as read: the recipe switch that makes its curves and meshes follow such bends.
fn print_folds_on_faceted_supports(recipe: &crate::recipe::Recipe, report: &BuildReport) {
    let folded: Vec<(&str, &str)> = (report.nodes.iter())
        .filter(|n| n.state == NodeState::Failed)
        .filter(|n| n.error.as_deref().is_some_and(|e| e.contains("folds")))
        .filter_map(|n| Some((n.name.as_str(), n.name.strip_prefix("surface_mesh:")?)))
        .collect();
    if folded.is_empty() {
        return;
    }
    let Some(model) = built_model(report) else {
        return;
    };
    for (node, patch) in folded {
        let Some(p) = model.patches.iter().find(|p| p.name == patch) else {
            continue;
        };
        let faceted = recipe
            .surfaces
            .get(&p.surface)
            .is_some_and(|s| s.smooth.is_none());
        if faceted {
            errln!(
                "{:>12} `{}` folded where the facets of `{}` (meshed as read) turn faster than \
                 its elements can follow: `smooth = true` in its `[surfaces]` entry makes its \
                 curves and meshes follow such bends",
                "note",
                node,
                p.surface
            );
        }
    }
}

/// The model the build made (or found in the cache), if it was built.
fn built_model(report: &BuildReport) -> Option<crate::plan::ops::ModelData> {
    report.artifact("model")?.decode().ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn region(name: &str, dihedral: f64, bound: f64) -> serde_json::Value {
        serde_json::json!({
            "name": name, "elements": 10, "min": 0.3, "min_dihedral_deg": dihedral,
            "min_dihedral_bound_deg": bound, "min_dihedral_bound_at": [1.0, 2.0, 3.0],
        })
    }

    #[test]
    fn the_summary_says_where_the_worst_regions_surfaces_meet_under_the_dihedral_bar() {
        let tables = |bound| {
            serde_json::json!({ "table2": [
                region("upper", 18.0, 60.0), region("wedge", 1.1, bound), region("all", 1.1, bound),
            ]})
        };
        let sharp = mesh_summary(&tables(1.2)).expect("a summary");
        assert!(
            sharp.ends_with(
                "dihedral 1.10° (wedge, whose surfaces meet at 1.20° near (1.0, 2.0, 3.0))"
            ),
            "{sharp}"
        );
        let wide = mesh_summary(&tables(45.0)).expect("a summary");
        assert!(wide.ends_with("dihedral 1.10° (wedge)"), "{wide}");
    }
}
