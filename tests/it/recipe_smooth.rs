//! `smooth` and `retriangulate` on a surface: the support is made over before anything is cut on
//! it. Measured on a dome whose file is a coarse 200 m grid, meshed at 25 m: the FE nodes'
//! distance from the smooth surface the file samples, and the triangles' c/c*.

use engine::{BuildOptions, NodeState};
use georecipe::plan::ops::{PatchMesh, SurfaceData};
use surface_mesh::quality::stats;

/// The dome the file samples: 200 m high, 300 m wide (a Gaussian), centred in the box.
fn dome(x: f64, y: f64) -> f64 {
    let r2 = (x - 500.0).powi(2) + (y - 500.0).powi(2);
    -600.0 + 200.0 * (-r2 / (500.0 * 500.0)).exp()
}

/// A TSurf of `dome` on a `step` grid from (x0, y0) over 1400 m (past the box on every side).
fn dome_tsurf(step: f64, [x0, y0]: [f64; 2]) -> String {
    let n = (1400.0 / step) as usize + 1;
    let mut s = String::from("GOCAD TSurf 1\nHEADER {\nname:dome\n}\nTFACE\n");
    for j in 0..n {
        for i in 0..n {
            let (x, y) = (x0 + i as f64 * step, y0 + j as f64 * step);
            s += &format!("VRTX {} {x} {y} {}\n", j * n + i + 1, dome(x, y));
        }
    }
    for j in 0..n - 1 {
        for i in 0..n - 1 {
            let a = j * n + i + 1;
            s += &format!(
                "TRGL {} {} {}\nTRGL {} {} {}\n",
                a,
                a + 1,
                a + n + 1,
                a,
                a + n + 1,
                a + n
            );
        }
    }
    s + "END\n"
}

fn recipe(options: &str) -> String {
    format!(
        r#"[model]
name = "dome"
[surfaces]
dome = {{ file = "dome.ts", kind = "horizon"{options} }}
[box]
min = [0.0, 0.0, -900.0]
max = [1000.0, 1000.0, -100.0]
[intersect]
all = ["dome", "box"]
[mesh]
size = 200.0
[mesh.surfaces]
dome = {{ size = 25.0 }}
[mesh.curves]
"dome" = {{ size = 25.0 }}
"#
    )
}

/// What the dome's FE mesh came out as.
struct Measured {
    nodes: usize,
    max_dev: f64,
    mean_dev: f64,
    mean_c: f64,
    max_c: f64,
    support_triangles: u64,
    /// How far the farthest of the file's vertices moved (m, to the millimetre).
    moved: f64,
}

/// Builds `text` (a recipe in `dir`, whose files are there) with its cache in `dir`.
fn build_in(dir: &std::path::Path, text: &str) -> Result<engine::BuildReport, String> {
    let path = dir.join("recipe.toml");
    let recipe =
        georecipe::recipe::parse(&path, text).map_err(|d| georecipe::recipe::render(&d))?;
    let graph = georecipe::plan::lower(&recipe).map_err(|e| e.to_string())?;
    let opts = BuildOptions::new(dir.join("cache"), dir.join("out"));
    let report = engine::build(graph, &opts, &|_| {}).map_err(|e| e.to_string())?;
    if report.ok {
        Ok(report)
    } else {
        let failed = report.nodes.iter().filter_map(|n| n.error.clone());
        Err(failed.collect::<Vec<_>>().join("\n"))
    }
}

/// A temp dir holding the coarse dome's file, its grid from (-190, -170).
fn dome_dir() -> tempfile::TempDir {
    dome_dir_from([-190.0, -170.0])
}

fn dome_dir_from(origin: [f64; 2]) -> tempfile::TempDir {
    let dir = tempfile::tempdir().expect("a temp dir");
    let text = dome_tsurf(200.0, origin);
    std::fs::write(dir.path().join("dome.ts"), text).expect("write the dome");
    dir
}

/// Builds the dome recipe with these `dome` options; the dome patches' FE nodes measured against
/// the smooth surface (vertical distance), and their triangles' c/c*.
fn build(options: &str) -> Result<Measured, String> {
    let dir = dome_dir();
    let report = build_in(dir.path(), &recipe(options))?;
    let mut devs = Vec::new();
    let (mut nodes, mut tris) = (Vec::new(), Vec::new());
    for n in report
        .nodes
        .iter()
        .filter(|n| n.name.starts_with("surface_mesh:dome#"))
    {
        let m: PatchMesh = (report.artifact(&n.name).ok_or("no mesh")?)
            .decode()
            .map_err(|e| e.to_string())?;
        let base = nodes.len() as u32;
        devs.extend(
            m.mesh
                .vertices
                .iter()
                .map(|p| (p[2] - dome(p[0], p[1])).abs()),
        );
        nodes.extend(m.mesh.vertices.iter().copied());
        tris.extend(m.mesh.triangles.iter().map(|t| t.map(|v| v + base)));
    }
    let q = stats(&nodes, &tris);
    let support = report.nodes.iter().find(|n| n.name == "support:dome");
    let count = |k: &str| {
        support
            .and_then(|n| n.counts.get(k))
            .map_or(0.0, |&c| c as f64)
    };
    Ok(Measured {
        nodes: devs.len(),
        max_dev: devs.iter().copied().fold(0.0, f64::max),
        mean_dev: devs.iter().sum::<f64>() / devs.len().max(1) as f64,
        mean_c: q.mean,
        max_c: q.max,
        support_triangles: count("support_triangles") as u64,
        moved: count("max_moved_mm") / 1000.0,
    })
}

#[test]
fn a_smoothed_coarse_dome_meshed_at_25_m_lies_far_closer_to_the_surface_it_samples() {
    let plain = build("").unwrap_or_else(|e| panic!("{e}"));
    let smooth = build(", smooth = true").unwrap_or_else(|e| panic!("{e}"));
    let taubin = build(", smooth = { passes = 3 }").unwrap_or_else(|e| panic!("{e}"));
    for (what, m) in [
        ("as read", &plain),
        ("smooth = true", &smooth),
        ("passes = 3", &taubin),
    ] {
        eprintln!(
            "{what}: {} nodes, distance max {:.2} mean {:.2} m, c/c* mean {:.3} max {:.3}, support {} triangles, file vertices moved up to {:.3} m",
            m.nodes, m.max_dev, m.mean_dev, m.mean_c, m.max_c, m.support_triangles, m.moved
        );
    }
    for m in [&smooth, &taubin] {
        assert!(m.mean_dev < plain.mean_dev / 3.0 && m.max_dev < plain.max_dev / 3.0);
        assert!(m.mean_c < plain.mean_c + 0.01);
    }
    assert_eq!(
        smooth.moved, 0.0,
        "without passes the file's vertices are interpolated"
    );
    assert!(taubin.moved > 0.0);
    assert!(
        taubin.max_dev < smooth.max_dev,
        "the passes even the refined facets' bends"
    );
}

#[test]
fn editing_smooth_reruns_that_surface_and_what_is_cut_on_it_but_not_its_import_or_the_box() {
    let dir = dome_dir();
    build_in(dir.path(), &recipe(", smooth = true")).unwrap_or_else(|e| panic!("{e}"));
    let again = build_in(dir.path(), &recipe(", smooth = { levels = 1 }"))
        .unwrap_or_else(|e| panic!("{e}"));
    let state = |name: &str| {
        let n = again.nodes.iter().find(|n| n.name == name);
        n.unwrap_or_else(|| panic!("no node {name}")).state
    };
    assert_eq!(state("support:dome"), NodeState::Ran);
    assert_eq!(state("intersect:box.xmin/dome"), NodeState::Ran);
    assert_eq!(state("model"), NodeState::Ran);
    for name in ["import:dome", "file:dome", "box", "surface:box.xmin"] {
        assert_eq!(state(name), NodeState::Cached, "{name} re-ran");
    }
    let plain = build_in(dir.path(), &recipe("")).unwrap_or_else(|e| panic!("{e}"));
    assert!(
        plain.nodes.iter().all(|n| !n.name.starts_with("support:")),
        "without `smooth` or `retriangulate` the surface has no support node"
    );
}

#[test]
fn retriangulate_remeshes_the_support_at_its_size_and_the_model_builds_on_it() {
    let dir = dome_dir();
    let report =
        build_in(dir.path(), &recipe(", retriangulate = 50.0")).unwrap_or_else(|e| panic!("{e}"));
    let support = report
        .nodes
        .iter()
        .find(|n| n.name == "support:dome")
        .expect("a support node");
    let (given, now) = (
        support.counts["given_triangles"],
        support.counts["support_triangles"],
    );
    // 1400 m square at 50 m: about 2 × 28² triangles instead of 2 × 7².
    assert_eq!(given, 98);
    assert!((1200..=2400).contains(&now), "{now} triangles");
}

#[test]
fn retriangulating_a_surface_of_two_tfaces_keeps_both_and_the_model_builds_on_it() {
    let dir = dome_dir();
    let text = std::fs::read_to_string(dir.path().join("dome.ts")).expect("read the dome");
    // The second half of the triangles in a second TFACE.
    let trgl: Vec<usize> = (text.lines().enumerate())
        .filter(|(_, l)| l.starts_with("TRGL"))
        .map(|(i, _)| i)
        .collect();
    let split_at = trgl[trgl.len() / 2];
    let lines: Vec<&str> = text.lines().collect();
    let two = format!(
        "{}\nTFACE\n{}\n",
        lines[..split_at].join("\n"),
        lines[split_at..].join("\n")
    );
    std::fs::write(dir.path().join("dome.ts"), two).expect("write the dome");
    let report =
        build_in(dir.path(), &recipe(", retriangulate = 50.0")).unwrap_or_else(|e| panic!("{e}"));
    let support: SurfaceData = (report.artifact("support:dome").expect("the support"))
        .decode()
        .expect("decodes");
    // Re-triangulated piece by piece, each new triangle in the TFACE it meshes.
    let count = |part: u32| support.triangle_part.iter().filter(|&&p| p == part).count();
    let (first, second) = (count(0), count(1));
    assert!(
        first > 400 && second > 400,
        "{first} and {second} triangles"
    );
    assert_eq!(first + second, support.mesh.triangles.len());
    // Smoothing keeps the border between the TFACEs and builds too.
    build_in(dir.path(), &recipe(", smooth = true")).unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn a_smoothed_support_edge_passing_a_box_edge_a_rounding_error_away_still_meshes() {
    // The grid's diagonals run along x = y, through the box's corner edge x = y = 0; smoothed,
    // one passes it some 1e-14 m away, so the box side gets two curve points that close and a
    // support triangle whose rotated projection rounds the wrong way.
    let dir = dome_dir_from([-190.0, -190.0]);
    build_in(
        dir.path(),
        &recipe(", smooth = { levels = 1, passes = 10 }"),
    )
    .unwrap_or_else(|e| panic!("{e}"));
}
