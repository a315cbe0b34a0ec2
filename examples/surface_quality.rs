//! Re-meshes every patch of a built recipe in-process with the current surface mesher and prints
//! c/c* statistics per patch, per surface and in all (the seed's Table 1 columns), plus a
//! histogram and the single-thread throughput. It reads the patches and curve discretizations
//! from the cache of an earlier `recipe build` (through the recipe's lock file), so only the
//! surface mesher runs:
//!
//! ```sh
//! recipe build recipes/refinements/b.toml --cache-dir /tmp/sq-cache-b
//! cargo run --release --example surface_quality -- recipes/refinements/b.toml /tmp/sq-cache-b [PATCH]
//! ```
//!
//! With PATCH, only the patches whose name contains it run, and the worst triangles are listed.
//! `SQ_REPEAT=N` times each patch N times and keeps the fastest; `SQ_DUMP=DIR` writes each patch
//! (see `dump`).

use engine::store::{Load, Store};
use engine::{Artifact, LockFile};
use georecipe::plan::ops::{CurveNodes, PatchPiece};
use model::patch_input;
use std::collections::BTreeMap;
use std::path::Path;
use surface_mesh::quality::{QualityStats, c_ratio, stats};
use surface_mesh::{SurfaceSize, mesh_patch_with};

/// Nodes and triangles gathered from several patches.
type Soup = (Vec<[f64; 3]>, Vec<[u32; 3]>);

fn load(store: &Store, lock: &LockFile, node: &str) -> Result<Artifact, String> {
    let n = lock
        .nodes
        .get(node)
        .ok_or_else(|| format!("the lock file has no node `{node}`"))?;
    match store.load_object(n.output, None) {
        Load::Hit(a) => Ok(a),
        _ => Err(format!("the cache has no output for `{node}`")),
    }
}

fn row(name: &str, nodes: usize, q: &QualityStats) {
    println!(
        "{name:<16} {nodes:>7} {:>8} {:>8.4} {:>7.4} {:>7.3} {:>7.2} {:>7.2}",
        q.triangles, q.mean, q.sd, q.max, q.pct_above_1_15, q.pct_above_1_5
    );
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.len() < 2 {
        eprintln!("usage: surface_quality RECIPE CACHE_DIR [PATCH]");
        std::process::exit(2);
    }
    if let Err(e) = run(&args[0], &args[1], args.get(2).map(String::as_str)) {
        eprintln!("error: {e}");
        std::process::exit(1);
    }
}

fn run(recipe_path: &str, cache: &str, only: Option<&str>) -> Result<(), String> {
    let text = std::fs::read_to_string(recipe_path).map_err(|e| format!("{recipe_path}: {e}"))?;
    let recipe = georecipe::recipe::parse(Path::new(recipe_path), &text)
        .map_err(|d| format!("{recipe_path}: {} diagnostics", d.len()))?;
    let lock_path = format!("{recipe_path}.lock");
    let lock_text = std::fs::read_to_string(&lock_path).map_err(|e| format!("{lock_path}: {e}"))?;
    let lock = LockFile::parse(&lock_text)?;
    let store = Store::open(Path::new(cache)).map_err(|e| e.to_string())?;
    let m = &recipe.mesh;

    let mut inputs = Vec::new();
    for name in lock.nodes.keys() {
        let Some(p) = name.strip_prefix("patch:") else {
            continue;
        };
        if only.is_some_and(|o| !p.contains(o)) {
            continue;
        }
        let piece: PatchPiece = load(&store, &lock, name)?
            .decode()
            .map_err(|e| e.to_string())?;
        if !lock.nodes.contains_key(&format!("surface_mesh:{p}")) {
            continue; // trimmed away
        }
        let curves: Vec<CurveNodes> = piece
            .curves
            .iter()
            .map(|c| {
                load(&store, &lock, &format!("discretize:{c}"))?
                    .decode()
                    .map_err(|e| e.to_string())
            })
            .collect::<Result<_, String>>()?;
        let nodes = |c: u32| curves.get(c as usize).map(|c| c.nodes.as_slice());
        let input = patch_input(&piece.name, &piece.support, &piece.boundary, &nodes)
            .map_err(|e| e.to_string())?;
        let size = SurfaceSize {
            size: m.surface_size(&piece.surface),
            min_size: m.min_size,
            max_size: m.max_size,
            growth: std::env::var("SQ_GROWTH")
                .ok()
                .and_then(|g| g.parse().ok())
                .unwrap_or(m.growth),
        };
        inputs.push((piece.surface.clone(), input, size));
    }

    println!(
        "{:<16} {:>7} {:>8} {:>8} {:>7} {:>7} {:>7} {:>7}",
        "patch", "nodes", "tris", "avg", "SD", "max", ">1.15", ">1.5"
    );
    let mut per_surface: BTreeMap<String, Soup> = BTreeMap::new();
    let mut all_nodes = Vec::new();
    let mut all_tris = Vec::new();
    let mut secs = 0.0;
    let mut worst: Vec<(f64, String, [f64; 3])> = Vec::new();
    for (surface, input, size) in &inputs {
        // SQ_REPEAT=N meshes each patch N times and keeps the fastest (a loaded machine).
        let repeat: usize = std::env::var("SQ_REPEAT")
            .ok()
            .and_then(|r| r.parse().ok())
            .unwrap_or(1);
        let mut dt = f64::INFINITY;
        let mut out = None;
        for _ in 0..repeat.max(1) {
            let t0 = std::time::Instant::now();
            let o = mesh_patch_with(input, size, &recipe.tolerances).map_err(|e| e.to_string())?;
            dt = dt.min(t0.elapsed().as_secs_f64());
            out = Some(o);
        }
        let Some(out) = out else {
            continue;
        };
        secs += dt;
        if let Ok(dir) = std::env::var("SQ_DUMP") {
            let head = Head {
                surface,
                size: size.size,
                secs: dt,
            };
            dump(&dir, &head, input, &out.nodes, &out.triangles)?;
        }
        row(
            &input.name,
            out.nodes.len(),
            &stats(&out.nodes, &out.triangles),
        );
        for t in &out.triangles {
            let p = t.map(|v| out.nodes[v as usize]);
            let q = c_ratio(&p[0], &p[1], &p[2]);
            let g = [0, 1, 2].map(|k| (p[0][k] + p[1][k] + p[2][k]) / 3.0);
            worst.push((q, input.name.clone(), g));
        }
        let e = per_surface.entry(surface.clone()).or_default();
        for (dst_n, dst_t) in [(&mut e.0, &mut e.1), (&mut all_nodes, &mut all_tris)] {
            let base = dst_n.len() as u32;
            dst_n.extend_from_slice(&out.nodes);
            dst_t.extend(out.triangles.iter().map(|t| t.map(|v| v + base)));
        }
    }
    println!();
    for (s, (n, t)) in &per_surface {
        row(s, n.len(), &stats(n, t));
    }
    let q = stats(&all_nodes, &all_tris);
    row("all", all_nodes.len(), &q);
    println!(
        "\n{} triangles in {secs:.3} s: {:.0} triangles/s (one thread)",
        q.triangles,
        q.triangles as f64 / secs.max(1e-9)
    );
    let edges = [1.0, 1.05, 1.1, 1.15, 1.2, 1.3, 1.5, 2.0, 3.0, f64::INFINITY];
    let mut hist = vec![0usize; edges.len() - 1];
    for (c, _, _) in &worst {
        if let Some(k) = edges.windows(2).position(|w| *c >= w[0] && *c < w[1]) {
            hist[k] += 1;
        }
    }
    println!("histogram of c/c*:");
    for (k, n) in hist.iter().enumerate() {
        println!(
            "  [{:.2}, {:.2}) {n:>8} {:>6.2} %",
            edges[k],
            edges[k + 1],
            100.0 * *n as f64 / worst.len().max(1) as f64
        );
    }
    if only.is_some() {
        worst.sort_by(|a, b| b.0.total_cmp(&a.0));
        println!("worst triangles:");
        for (c, p, g) in worst.iter().take(25) {
            println!("  {c:.3} {p} at ({:.1}, {:.1}, {:.1})", g[0], g[1], g[2]);
        }
    }
    Ok(())
}

/// What a dump says about its patch besides the meshes.
struct Head<'a> {
    surface: &'a str,
    size: f64,
    secs: f64,
}

/// Writes `DIR/<patch>.txt`, for pictures and for the Gmsh comparison
/// (`benches/peers/gmsh_same_curves.py`): a header (`surface NAME`, `size S` the surface's target
/// size, `secs T` our meshing time of this patch, `loops L constraints C`), then `v x y z`,
/// `t a b c` (0-based) and `l x y z` for each discretized curve node: the L closed loops first
/// (first node not repeated), then the C open constraints, each ended by `e`; then the support
/// (`sv`, `st`).
fn dump(
    dir: &str,
    head: &Head,
    input: &surface_mesh::PatchInput,
    nodes: &[[f64; 3]],
    tris: &[[u32; 3]],
) -> Result<(), String> {
    use std::fmt::Write;
    let mut s = String::new();
    let _ = writeln!(s, "surface {}", head.surface);
    let _ = writeln!(s, "size {}", head.size);
    let _ = writeln!(s, "secs {}", head.secs);
    let _ = writeln!(
        s,
        "loops {} constraints {}",
        input.loops.len(),
        input.constraints.len()
    );
    for p in nodes {
        let _ = writeln!(s, "v {} {} {}", p[0], p[1], p[2]);
    }
    for t in tris {
        let _ = writeln!(s, "t {} {} {}", t[0], t[1], t[2]);
    }
    for l in input.loops.iter().chain(&input.constraints) {
        for p in l {
            let _ = writeln!(s, "l {} {} {}", p[0], p[1], p[2]);
        }
        s.push_str("e\n");
    }
    for p in &input.support.vertices {
        let _ = writeln!(s, "sv {} {} {}", p[0], p[1], p[2]);
    }
    for t in &input.support.triangles {
        let _ = writeln!(s, "st {} {} {}", t[0], t[1], t[2]);
    }
    let path = format!("{dir}/{}.txt", input.name);
    std::fs::write(&path, s).map_err(|e| format!("{path}: {e}"))
}
