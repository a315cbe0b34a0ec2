//! Renders report.html and report.json of the didactic model's six regions (boundaries meshed by
//! Gmsh in ../shared/data/peer-boundaries, tets by our mesher), to look at the pictures:
//!
//! ```sh
//! cargo run --release --example report_peers -- OUT_DIR [REGION ...]
//! ```

use test_support::peers;

use georecipe::report::{ReportInput, render_both};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let Some(out) = args.first() else {
        eprintln!("usage: report_peers OUT_DIR [REGION ...]");
        std::process::exit(2);
    };
    let Some(dir) = peers::shared_dir() else {
        return;
    };
    let all = [
        "overburden_W",
        "overburden_E",
        "reservoir_W",
        "reservoir_E",
        "underburden_W",
        "underburden_E",
    ];
    let regions: Vec<&str> = if args.len() > 1 {
        args[1..].iter().map(String::as_str).collect()
    } else {
        all.to_vec()
    };
    let (mesh, _) = match peers::peer_mesh(&dir, &regions) {
        Ok(m) => m,
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(1);
        }
    };
    let input = ReportInput::from_mesh("didactic", "peer-boundaries (L1)", &mesh);
    let t0 = std::time::Instant::now();
    let (html, json) = render_both(&input);
    let dt = t0.elapsed().as_secs_f64();
    for (name, text) in [("report.html", &html), ("report.json", &json)] {
        let path = format!("{out}/{name}");
        if let Err(e) = std::fs::write(&path, text) {
            eprintln!("error: cannot write {path}: {e}");
            std::process::exit(1);
        }
    }
    println!(
        "{} tets, {} triangles: report.html {} bytes, report.json {} bytes, rendered in {dt:.2} s",
        mesh.tets.len(),
        mesh.triangles.len(),
        html.len(),
        json.len()
    );
}
