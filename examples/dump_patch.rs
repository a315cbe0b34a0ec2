//! Writes the surface mesher's input for one patch of a recipe's model, so a patch that fails (or
//! meshes badly) in a build can be reproduced and meshed alone:
//!
//! ```text
//! cargo run --release --example dump_patch -- recipes/didactic.toml 'H1#2' /tmp/h1
//! cargo run --release --example dump_patch -- --mesh /tmp/h1/H1#2.patch /tmp/h1/H1#2.obj
//! ```
//!
//! The first form builds with a cache in `OUT_DIR/cache` (the surface meshing nodes may fail:
//! only the model and the curve discretizations are needed) and writes `<patch>.patch` (the
//! input, with full-precision numbers, and the recipe's sizes) and `<patch>.input.obj` (the
//! support, the loops and constraints as lines and the isolated points as points, to look at).
//! The second meshes a `.patch` file and writes the mesh as OBJ, or prints the mesher's error.

use engine::{self, BuildOptions};
use geom::TriMesh;
use georecipe::plan::ops::{CurveNodes, PatchPiece};
use model::patch_input;
use std::fmt::Write as _;
use std::path::Path;
use surface_mesh::{PatchInput, SurfaceSize, mesh_patch};

fn main() -> Result<(), String> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match args.as_slice() {
        [flag, file, out] if flag == "--mesh" => mesh(Path::new(file), Path::new(out)),
        [recipe, patch, out] => dump(Path::new(recipe), patch, Path::new(out)),
        _ => Err("usage: dump_patch RECIPE PATCH OUT_DIR | dump_patch --mesh FILE OUT.obj".into()),
    }
}

fn dump(recipe_path: &Path, patch: &str, out: &Path) -> Result<(), String> {
    let text = std::fs::read_to_string(recipe_path).map_err(|e| e.to_string())?;
    let recipe =
        georecipe::recipe::parse(recipe_path, &text).map_err(|d| georecipe::recipe::render(&d))?;
    let size = SurfaceSize {
        size: recipe.mesh.size,
        min_size: recipe.mesh.min_size,
        max_size: recipe.mesh.max_size,
        growth: recipe.mesh.growth,
    };
    let graph = georecipe::plan::lower(&recipe).map_err(|e| e.to_string())?;
    std::fs::create_dir_all(out).map_err(|e| e.to_string())?;
    let opts = BuildOptions {
        cache_dir: out.join("cache"),
        output_dir: out.join("outputs"),
        staging_dir: None,
        jobs: 2,
        keep_going: true,
        record: engine::DEFAULT_RECORD.to_string(),
        read_only: false,
    };
    let report = engine::build(graph, &opts, &|_| {}).map_err(|e| e.to_string())?;
    let piece: PatchPiece = report
        .artifact(&format!("patch:{patch}"))
        .ok_or_else(|| format!("no patch `{patch}` was extracted"))?
        .decode()
        .map_err(|e| e.to_string())?;
    let curves: Vec<CurveNodes> = piece
        .curves
        .iter()
        .map(|c| {
            report
                .artifact(&format!("discretize:{c}"))
                .ok_or_else(|| format!("curve `{c}` was not discretized"))?
                .decode()
                .map_err(|e| e.to_string())
        })
        .collect::<Result<_, _>>()?;
    let nodes = |c: u32| curves.get(c as usize).map(|c| c.nodes.as_slice());
    let input = patch_input(&piece.name, &piece.support, &piece.boundary, &nodes)
        .map_err(|e| e.to_string())?;
    // Appended, not replaced: a chart's name (`SALT#3.2`) already has a dot.
    let file = |ext: &str| out.join(format!("{patch}.{ext}"));
    write(&file("patch"), &patch_text(&input, &size))?;
    write(&file("input.obj"), &input_obj(&input))?;
    println!("{}", file("patch").display());
    Ok(())
}

fn mesh(file: &Path, out: &Path) -> Result<(), String> {
    let text = std::fs::read_to_string(file).map_err(|e| e.to_string())?;
    let (input, size) = read_patch(&text)?;
    let started = std::time::Instant::now();
    let m = mesh_patch(&input, &size).map_err(|e| e.to_string())?;
    println!(
        "{} triangles, {} nodes in {:.2?}",
        m.triangles.len(),
        m.nodes.len(),
        started.elapsed()
    );
    let mut s = String::new();
    obj_mesh(&mut s, &TriMesh::new(m.nodes, m.triangles));
    write(out, &s)
}

fn write(path: &Path, text: &str) -> Result<(), String> {
    std::fs::write(path, text).map_err(|e| format!("{}: {e}", path.display()))
}

/// `name`, `size s min max growth`, `v x y z`, `t a b c`, then `loop`/`constraint` headers each
/// followed by its `p x y z` points, then one `point x y z` line per isolated point.
fn patch_text(input: &PatchInput, size: &SurfaceSize) -> String {
    let mut s = format!("name {}\n", input.name);
    let _ = writeln!(
        s,
        "size {:?} {:?} {:?} {:?}",
        size.size, size.min_size, size.max_size, size.growth
    );
    for v in &input.support.vertices {
        let _ = writeln!(s, "v {:?} {:?} {:?}", v[0], v[1], v[2]);
    }
    for t in &input.support.triangles {
        let _ = writeln!(s, "t {} {} {}", t[0], t[1], t[2]);
    }
    for (head, lines) in [("loop", &input.loops), ("constraint", &input.constraints)] {
        for l in lines {
            let _ = writeln!(s, "{head}");
            for p in l {
                let _ = writeln!(s, "p {:?} {:?} {:?}", p[0], p[1], p[2]);
            }
        }
    }
    for p in &input.points {
        let _ = writeln!(s, "point {:?} {:?} {:?}", p[0], p[1], p[2]);
    }
    s
}

fn read_patch(text: &str) -> Result<(PatchInput, SurfaceSize), String> {
    let mut input = PatchInput {
        name: String::new(),
        support: TriMesh::new(Vec::new(), Vec::new()),
        loops: Vec::new(),
        constraints: Vec::new(),
        points: Vec::new(),
        facets: Vec::new(),
    };
    let mut size = None;
    let mut into_loops = true;
    for (i, line) in text.lines().enumerate() {
        let bad = || format!("line {}: `{line}`", i + 1);
        let mut w = line.split_whitespace();
        let head = w.next().unwrap_or("");
        let nums: Vec<f64> = w.clone().filter_map(|x| x.parse().ok()).collect();
        match head {
            "name" => input.name = w.collect::<Vec<_>>().join(" "),
            "size" if nums.len() == 4 => {
                size = Some(SurfaceSize {
                    size: nums[0],
                    min_size: nums[1],
                    max_size: nums[2],
                    growth: nums[3],
                })
            }
            "v" if nums.len() == 3 => input.support.vertices.push([nums[0], nums[1], nums[2]]),
            "t" if nums.len() == 3 => {
                input
                    .support
                    .triangles
                    .push([nums[0] as u32, nums[1] as u32, nums[2] as u32])
            }
            "loop" | "constraint" => {
                into_loops = head == "loop";
                let lines = if into_loops {
                    &mut input.loops
                } else {
                    &mut input.constraints
                };
                lines.push(Vec::new());
            }
            "p" if nums.len() == 3 => {
                let lines = if into_loops {
                    &mut input.loops
                } else {
                    &mut input.constraints
                };
                lines
                    .last_mut()
                    .ok_or_else(bad)?
                    .push([nums[0], nums[1], nums[2]]);
            }
            "point" if nums.len() == 3 => input.points.push([nums[0], nums[1], nums[2]]),
            "" => {}
            _ => return Err(bad()),
        }
    }
    let support = TriMesh::new(input.support.vertices, input.support.triangles);
    input.support = support;
    Ok((input, size.ok_or("no `size` line")?))
}

fn input_obj(input: &PatchInput) -> String {
    let mut s = String::new();
    obj_mesh(&mut s, &input.support);
    let mut base = input.support.vertices.len();
    let lines = input.loops.iter().map(|l| (l, true));
    for (l, closed) in lines.chain(input.constraints.iter().map(|l| (l, false))) {
        for p in l {
            let _ = writeln!(s, "v {:?} {:?} {:?}", p[0], p[1], p[2]);
        }
        let ids: Vec<String> = (0..l.len() + usize::from(closed))
            .map(|k| (base + k % l.len() + 1).to_string())
            .collect();
        let _ = writeln!(s, "l {}", ids.join(" "));
        base += l.len();
    }
    for p in &input.points {
        base += 1;
        let _ = writeln!(s, "v {:?} {:?} {:?}", p[0], p[1], p[2]);
        let _ = writeln!(s, "p {base}");
    }
    s
}

fn obj_mesh(s: &mut String, m: &TriMesh) {
    for v in &m.vertices {
        let _ = writeln!(s, "v {:?} {:?} {:?}", v[0], v[1], v[2]);
    }
    for t in &m.triangles {
        let _ = writeln!(s, "f {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1);
    }
}
