//! Writes the tet mesher's input for one region of a recipe's model as OFF files, so a region
//! that fails (or meshes badly) in a build can be reproduced alone with `recipe tetmesh`:
//!
//! ```text
//! cargo run --release --example dump_region -- recipes/didactic.toml reservoir_E /tmp/res_E
//! cargo run --release -- tetmesh /tmp/res_E/boundary.off --embed /tmp/res_E/embedded.off -o /tmp/res_E.msh
//! ```
//!
//! The files are `OUT_DIR/boundary.off` and `OUT_DIR/embedded.off` (a region's name can be longer
//! than a file name may be). The build runs with a cache in `OUT_DIR/cache` (the tet meshing nodes may fail: only the model
//! and the surface meshes are needed).

use engine::{self, BuildOptions};
use georecipe::plan::ops::{ModelData, PatchMesh};
use model::{drop_pinched_faces, region_input};
use std::fmt::Write as _;
use std::path::PathBuf;

fn off(vertices: &[[f64; 3]], triangles: &[[u32; 3]]) -> String {
    let mut s = format!("OFF\n{} {} 0\n", vertices.len(), triangles.len());
    for v in vertices {
        let _ = writeln!(s, "{:?} {:?} {:?}", v[0], v[1], v[2]);
    }
    for t in triangles {
        let _ = writeln!(s, "3 {} {} {}", t[0], t[1], t[2]);
    }
    s
}

fn main() -> Result<(), String> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [recipe_path, region, out] = args.as_slice() else {
        return Err("usage: dump_region RECIPE REGION OUT_DIR".into());
    };
    let recipe_path = PathBuf::from(recipe_path);
    let text = std::fs::read_to_string(&recipe_path).map_err(|e| e.to_string())?;
    let recipe =
        georecipe::recipe::parse(&recipe_path, &text).map_err(|d| georecipe::recipe::render(&d))?;
    let graph = georecipe::plan::lower(&recipe).map_err(|e| e.to_string())?;
    let out = PathBuf::from(out);
    std::fs::create_dir_all(&out).map_err(|e| e.to_string())?;
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
    let model: ModelData = report
        .artifact("model")
        .ok_or("the model was not built")?
        .decode()
        .map_err(|e| e.to_string())?;
    let r = model
        .regions
        .regions
        .iter()
        .find(|r| &r.name == region)
        .ok_or_else(|| format!("no region `{region}`"))?;
    let meshes: Vec<Option<PatchMesh>> = model
        .patches
        .iter()
        .map(|p| {
            report
                .artifact(&format!("surface_mesh:{}", p.name))
                .and_then(|a| a.decode().ok())
        })
        .collect();
    let get = |p: u32| meshes.get(p as usize)?.as_ref().map(|m| &m.mesh);
    let mut input = region_input(region, &r.sides, &get).map_err(|e| e.to_string())?;
    // As the tet mesh op meshes it.
    drop_pinched_faces(&mut input);
    let b = out.join("boundary.off");
    std::fs::write(&b, off(&input.vertices, &input.boundary)).map_err(|e| e.to_string())?;
    println!(
        "{} ({} boundary triangles)",
        b.display(),
        input.boundary.len()
    );
    if !input.embedded.is_empty() {
        let e = out.join("embedded.off");
        std::fs::write(&e, off(&input.vertices, &input.embedded)).map_err(|e| e.to_string())?;
        println!(
            "{} ({} embedded triangles)",
            e.display(),
            input.embedded.len()
        );
    }
    Ok(())
}
