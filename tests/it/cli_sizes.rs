//! Sizes set on a region reach the surfaces and curves that bound it, on the shipped example: a
//! finer region is refined through its whole volume, a coarser one coarsens only the surfaces it
//! alone bounds.

use crate::common_cli;
use common_cli::*;

/// The example's `report.json` after a build of `s`.
fn report(s: &Scratch) -> serde_json::Value {
    let text = std::fs::read_to_string(s.path("out/didactic/report.json")).expect("report.json");
    serde_json::from_str(&text).expect("report.json parses")
}

fn region_tets(r: &serde_json::Value, name: &str) -> u64 {
    r["regions"]
        .as_array()
        .and_then(|a| a.iter().find(|x| x["name"] == name))
        .and_then(|x| x["tets"].as_u64())
        .unwrap_or_else(|| panic!("no region {name} in the report"))
}

fn patch_triangles(r: &serde_json::Value, name: &str) -> u64 {
    r["patches"]
        .as_array()
        .and_then(|a| a.iter().find(|x| x["name"] == name))
        .and_then(|x| x["triangles"].as_u64())
        .unwrap_or_else(|| panic!("no patch {name} in the report"))
}

/// A curve's length and node count, from the report.
fn curve(r: &serde_json::Value, name: &str) -> (f64, u64) {
    r["curves"]
        .as_array()
        .and_then(|a| a.iter().find(|x| x["name"] == name))
        .and_then(|x| Some((x["length"].as_f64()?, x["nodes"].as_u64()?)))
        .unwrap_or_else(|| panic!("no curve {name} in the report"))
}

/// The patches bounding `region`, from the report.
fn patches_of(r: &serde_json::Value, region: &str) -> Vec<String> {
    r["regions"]
        .as_array()
        .and_then(|a| a.iter().find(|x| x["name"] == region))
        .and_then(|x| x["patches"].as_array())
        .map(|a| {
            a.iter()
                .filter_map(|p| p["patch"].as_str().map(String::from))
                .collect()
        })
        .unwrap_or_default()
}

fn build_with(s: &Scratch, regions: &str) -> serde_json::Value {
    s.edit(
        "[regions]",
        &format!("[mesh.regions]\n{regions}\n\n[regions]"),
    );
    let (ok, _, err) = s.build(&[]);
    assert!(ok, "{err}");
    report(s)
}

#[test]
fn a_finer_region_size_refines_the_surfaces_that_bound_it_and_so_the_whole_region() {
    let before = report(&Scratch::didactic_built());
    let after = build_with(&Scratch::didactic_built(), "reservoir_E = { size = 50.0 }");
    let (b, a) = (
        region_tets(&before, "reservoir_E"),
        region_tets(&after, "reservoir_E"),
    );
    assert!(a > 8 * b, "reservoir_E: {b} tets at 200 m, {a} at 50 m");
    for p in patches_of(&before, "reservoir_E") {
        let (pb, pa) = (patch_triangles(&before, &p), patch_triangles(&after, &p));
        assert!(pa >= pb, "{p}: {pb} triangles before, {pa} after");
    }
    let h1 = patches_of(&before, "reservoir_E")
        .into_iter()
        .find(|p| p.starts_with("H1#"))
        .expect("reservoir_E is bounded by H1");
    let (pb, pa) = (patch_triangles(&before, &h1), patch_triangles(&after, &h1));
    assert!(pa > 8 * pb, "{h1}: {pb} triangles before, {pa} after");
}

#[test]
fn a_coarser_region_size_coarsens_only_the_surfaces_no_other_region_shares() {
    let before = report(&Scratch::didactic_built());
    let after = build_with(
        &Scratch::didactic_built(),
        "underburden_W = { size = 400.0 }",
    );
    let own = patches_of(&before, "underburden_W");
    let floor = own
        .iter()
        .find(|p| p.starts_with("box.zmin#"))
        .expect("underburden_W is bounded by the box's floor");
    let (fb, fa) = (
        patch_triangles(&before, floor),
        patch_triangles(&after, floor),
    );
    assert!(
        2 * fa < fb,
        "{floor}: {fb} triangles at 200 m, {fa} at 400 m"
    );
    let shared = own
        .iter()
        .find(|p| p.starts_with("H2#"))
        .expect("underburden_W is bounded by H2");
    assert_eq!(
        patch_triangles(&after, shared),
        patch_triangles(&before, shared),
        "{shared} also bounds reservoir_W, at the global size"
    );
}

#[test]
fn min_layers_refines_the_thin_reservoirs_from_their_measured_thickness_and_nothing_thick() {
    let s = Scratch::didactic_built();
    let before = report(&s);
    s.edit("size = 200.0", "size = 200.0\nmin_layers = 1");
    let (ok, json, err) = s.build(&[]);
    assert!(ok, "{err}");
    let after = report(&s);
    let thickness = |name: &str| {
        json["model"]["regions"]
            .as_array()
            .and_then(|a| a.iter().find(|x| x["name"] == name))
            .and_then(|x| x["thickness"].as_f64())
            .unwrap_or_else(|| panic!("no thickness for {name} in --json"))
    };
    for r in ["reservoir_W", "reservoir_E"] {
        let t = thickness(r);
        assert!((30.0..40.0).contains(&t), "{r} is about 35 m thick: {t}");
        let (b, a) = (region_tets(&before, r), region_tets(&after, r));
        assert!(
            a > 5 * b,
            "{r}: {b} tets at 200 m, {a} at one layer of {t:.1} m"
        );
    }
    for r in ["overburden_W", "underburden_E"] {
        assert!(thickness(r) > 1000.0, "{r} is over a kilometre thick");
    }
    // The fault's curves along the reservoir have a rule of 100; one layer of 35 m overrides it,
    // or the fault's strips across the reservoir stay one element across whatever its size.
    let reservoir = thickness("reservoir_E").max(thickness("reservoir_W"));
    for c in ["F1/H1", "F1/H2"] {
        let (len, nodes) = curve(&after, c);
        assert!(
            nodes as f64 >= len / reservoir,
            "{c}: {nodes} nodes over {len:.0} m, at most {reservoir:.1} apart"
        );
    }
    // The box's vertical edges above and below the reservoir, at the global 200 m, start from
    // the reservoir's size where they meet it and grow; the box's top edges, out of reach, do not.
    for c in ["box.xmax/box.ymin#1", "box.xmin/box.ymax#3"] {
        let (len, nodes) = curve(&after, c);
        let uniform = (len / 200.0).round() as u64 + 1;
        assert!(
            nodes >= uniform + 4,
            "{c}: {nodes} nodes over {len:.0} m, {uniform} at 200 m"
        );
    }
    for c in ["box.xmax/box.zmax", "box.ymin/box.zmax#2", "F1/box.zmax"] {
        assert_eq!(curve(&after, c), curve(&before, c), "{c}");
    }
    for p in patches_of(&before, "overburden_W")
        .iter()
        .filter(|p| p.starts_with("box.zmax#"))
    {
        assert_eq!(
            patch_triangles(&after, p),
            patch_triangles(&before, p),
            "{p} bounds only the thick overburden"
        );
    }
}

#[test]
fn a_refinement_near_a_fault_refines_it_and_its_surroundings_and_nothing_out_of_reach() {
    let s = Scratch::didactic_built();
    let before = report(&s);
    s.edit(
        "[mesh.curves]",
        "[[mesh.refine]]\nsurface = \"F1\"\nsize = 40.0\ndistance = 600.0\n\n[mesh.curves]",
    );
    let (ok, r, err) = s.build(&[]);
    assert!(ok, "{err}");
    let after = report(&s);
    let triangles = |rep: &serde_json::Value, prefix: &str| -> u64 {
        rep["patches"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|p| p["name"].as_str().unwrap().starts_with(prefix))
            .map(|p| p["triangles"].as_u64().unwrap())
            .sum()
    };
    let (fb, fa) = (triangles(&before, "F1#"), triangles(&after, "F1#"));
    assert!(fa > 8 * fb, "F1 at 40 m: {fb} triangles before, {fa} after");
    for region in ["overburden_W", "overburden_E"] {
        let (b, a) = (region_tets(&before, region), region_tets(&after, region));
        assert!(a > 3 * b, "{region} beside F1: {b} tets before, {a} after");
    }
    // The box's west and east sides are over a kilometre from F1: out of the reach of 40 m
    // growing at the surfaces' 15 % to the global 200 m.
    for side in ["box.xmin#", "box.xmax#"] {
        assert_eq!(triangles(&after, side), triangles(&before, side), "{side}");
    }
    let ran = nodes_in_state(&r, "ran");
    assert!(ran.contains(&"refine:1".to_string()), "{ran:?}");
    assert!(
        !ran.iter().any(|n| n == "model" || n.starts_with("import:")),
        "nothing upstream of the model re-ran: {ran:?}"
    );
}

#[test]
fn editing_a_refinement_reruns_it_and_what_it_reaches_and_a_far_point_touches_nothing_else() {
    let s = Scratch::didactic_built();
    s.edit(
        "[mesh.curves]",
        "[[mesh.refine]]\npoint = [503000.0, 7002000.0, -400.0]\nsize = 150.0\ndistance = 300.0\n\n[mesh.curves]",
    );
    let (ok, r, err) = s.build(&[]);
    assert!(ok, "{err}");
    let ran = nodes_in_state(&r, "ran");
    assert!(ran.contains(&"refine:1".to_string()), "{ran:?}");
    // A point 400 m deep in the eastern overburden, reaching 300-333 m: its region re-meshes,
    // no surface is within reach, nothing else re-runs.
    assert!(
        ran.contains(&"tet_mesh:overburden_E".to_string()),
        "{ran:?}"
    );
    for n in &ran {
        assert!(
            !n.starts_with("surface_mesh:")
                && !n.starts_with("discretize:")
                && n != "tet_mesh:overburden_W",
            "`{n}` is out of the point's reach but re-ran"
        );
    }
    s.edit("size = 150.0\ndistance", "size = 170.0\ndistance");
    let (ok, r, err) = s.build(&[]);
    assert!(ok, "{err}");
    let again = nodes_in_state(&r, "ran");
    assert!(again.contains(&"refine:1".to_string()), "{again:?}");
    assert!(
        again.iter().all(|n| ran.contains(n)),
        "a finer reach re-runs only what the first one reached: {again:?} (first: {ran:?})"
    );
}

#[test]
fn a_curve_rule_whose_size_exceeds_its_curves_is_warned_about_at_the_rule_with_their_lengths() {
    let s = Scratch::didactic_built();
    // The box's top edges along x and y are 5 km long: none fits a 6 km segment.
    s.edit(
        "[mesh.curves]\n",
        "[mesh.curves]\n\"box.zmax/box.x*\" = { size = 6000.0 }\n",
    );
    let (ok, _, err) = s.build(&[]);
    assert!(ok, "{err}");
    let line = err
        .lines()
        .find(|l| l.contains("asks for segments of 6000"));
    let line = line.unwrap_or_else(|| panic!("no warning:\n{err}"));
    assert!(line.contains("didactic.toml:"), "{line}");
    assert!(line.contains("rule `box.zmax/box.x*`"), "{line}");
    assert!(line.contains("its 2 curves are all shorter"), "{line}");
    assert!(line.contains("(5000)"), "{line}");
    // The shipped rules fit some of their curves (`F2`'s pieces of 40 m between the horizons
    // excepted): no such warning.
    let (ok, _, err) = Scratch::didactic().build(&[]);
    assert!(ok && !err.contains("asks for segments of"), "{err}");
}

/// A TSurf of the plane `z = z0 + slope x`, two triangles from -100 to `to` m on both axes.
fn dipping_plane(name: &str, (z0, slope): (f64, f64), to: f64) -> String {
    let z = |x: f64| z0 + slope * x;
    format!(
        "GOCAD TSurf 1\nHEADER {{\nname:{name}\n}}\nTFACE\nVRTX 1 -100 -100 {a}\nVRTX 2 {to} -100 \
         {b}\nVRTX 3 {to} {to} {b}\nVRTX 4 -100 {to} {a}\nTRGL 1 2 3\nTRGL 1 3 4\nEND\n",
        a = z(-100.0),
        b = z(to)
    )
}

/// Builds a layer between the planes `top` and `base` (`(z0, slope)` each, see
/// [`dipping_plane`]) in the box `[0, side]² × [-500, -100]` with `layers = 3` and the global
/// size 100, and reads its mesh back.
fn three_layers_between(top: (f64, f64), base: (f64, f64), side: f64) -> geom::mesh::VolumeMesh {
    layers_between(top, base, side, "layers = 3").0
}

/// As [`three_layers_between`] with the layer's `[mesh.regions]` entry `entry` (`layers = 1`);
/// the mesh and what the build printed.
fn layers_between(
    top: (f64, f64),
    base: (f64, f64),
    side: f64,
    entry: &str,
) -> (geom::mesh::VolumeMesh, String) {
    let dir = tempfile::tempdir().expect("a scratch folder");
    let file = |name: &str, plane: (f64, f64)| {
        let path = dir.path().join(format!("{name}.ts"));
        std::fs::write(path, dipping_plane(name, plane, side + 100.0)).unwrap();
    };
    file("top", top);
    file("base", base);
    let inside = (top.0 + base.0) / 2.0;
    let recipe = format!(
        r#"[model]
name = "layer"
[surfaces]
top = {{ file = "top.ts", kind = "horizon" }}
base = {{ file = "base.ts", kind = "horizon" }}
[box]
min = [0.0, 0.0, -500.0]
max = [{side:?}, {side:?}, -100.0]
[intersect]
all = ["top", "base", "box"]
[mesh]
size = 100.0
[mesh.regions]
layer = {{ {entry} }}
[regions]
layer = {{ point = [0.5, 0.5, {inside:?}] }}
[output]
dir = "out"
formats = ["msh"]
"#
    );
    std::fs::write(dir.path().join("layer.toml"), recipe).unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_recipe"))
        .args(["build", "layer.toml"])
        .current_dir(dir.path())
        .env_remove("RECIPE_CACHE_DIR")
        .output()
        .expect("run recipe");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    let bytes = std::fs::read(dir.path().join("out/layer.msh")).expect("the mesh");
    let mesh = geom::mesh::read::read_volume_msh(&bytes, "layer.msh").expect("it reads");
    (mesh, err.into_owned())
}

/// The fewest tet edges from a node of surface `from` to a node of surface `to` through the
/// tets of `region` of `mesh` (breadth first from every node of `from`).
fn fewest_edges_across(mesh: &geom::mesh::VolumeMesh, region: &str, from: &str, to: &str) -> u32 {
    let group = |name: &str| {
        let g = mesh.surface_groups.iter().position(|g| g.name == name);
        let g = g.unwrap_or_else(|| panic!("no surface {name}")) as u32;
        let mut on = vec![false; mesh.nodes.len()];
        for (t, _) in (mesh.triangles.iter().zip(&mesh.triangle_group)).filter(|(_, k)| **k == g) {
            t.iter().for_each(|&v| on[v as usize] = true);
        }
        on
    };
    let (start, goal) = (group(from), group(to));
    let r = mesh.regions.iter().position(|g| g.name == region);
    let r = r.unwrap_or_else(|| panic!("no region {region}")) as u32;
    let mut links: Vec<Vec<u32>> = vec![Vec::new(); mesh.nodes.len()];
    for (t, _) in (mesh.tets.iter().zip(&mesh.tet_region)).filter(|(_, k)| **k == r) {
        for (i, j) in [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)] {
            links[t[i] as usize].push(t[j]);
            links[t[j] as usize].push(t[i]);
        }
    }
    let mut seen: Vec<bool> = start.clone();
    let mut front: Vec<u32> = (0..mesh.nodes.len() as u32)
        .filter(|&v| start[v as usize] && !links[v as usize].is_empty())
        .collect();
    for level in 0.. {
        if front.iter().any(|&v| goal[v as usize]) {
            return level;
        }
        assert!(
            !front.is_empty(),
            "{to} is not reached from {from} in {region}"
        );
        let mut next = Vec::new();
        for v in front {
            for &w in &links[v as usize] {
                if !std::mem::replace(&mut seen[w as usize], true) {
                    next.push(w);
                }
            }
        }
        front = next;
    }
    unreachable!()
}

#[test]
fn three_layers_are_three_tet_edges_across_everywhere_even_where_a_box_side_cuts_the_layer() {
    let mesh = three_layers_between((-300.0, 0.05), (-324.0, 0.05), 400.0);
    assert_eq!(fewest_edges_across(&mesh, "layer", "top", "base"), 3);
    assert_eq!(fewest_edges_across(&mesh, "layer", "base", "top"), 3);
}

#[test]
fn a_layer_with_an_aspect_keeps_three_edges_across_in_far_fewer_flat_tets() {
    // A 24 m layer dipping 3°, 1.2 km across: flat tets, four times as wide as thick, keep three
    // edges across it everywhere (its strips along the box's sides included) in a fraction of
    // the isotropic count, and are as good as those once stretched across the layer.
    let (top, base, side) = ((-300.0, 0.05), (-324.0, 0.05), 1200.0);
    let (iso, _) = layers_between(top, base, side, "layers = 3");
    let (flat, err) = layers_between(top, base, side, "layers = 3, aspect = 4");
    assert_eq!(fewest_edges_across(&flat, "layer", "top", "base"), 3);
    assert_eq!(fewest_edges_across(&flat, "layer", "base", "top"), 3);
    let count = |m: &geom::mesh::VolumeMesh| m.tets.len();
    assert!(
        4 * count(&flat) < count(&iso),
        "{} flat tets, {} isotropic",
        count(&flat),
        count(&iso)
    );
    let said = err
        .split("`aspect`): stretched by that across the layer its tets reach a mean ratio of ")
        .nth(1)
        .unwrap_or_else(|| panic!("no note on the stretched quality:\n{err}"));
    let ratio: f64 = said.split(' ').next().unwrap().parse().unwrap();
    assert!(ratio > 0.3, "{said}");
}

#[test]
fn three_layers_stay_three_edges_across_where_the_layer_thins_to_half_its_median() {
    // 16 m thick at x = 0, 8 m at x = 200: sized from its median (12 m), the thin end would
    // be two edges across; its local thickness refines it there.
    let mesh = three_layers_between((-300.0, 0.02), (-316.0, 0.06), 200.0);
    assert_eq!(fewest_edges_across(&mesh, "layer", "top", "base"), 3);
    assert_eq!(fewest_edges_across(&mesh, "layer", "base", "top"), 3);
}

#[test]
fn a_layer_thinning_over_square_kilometres_stays_at_its_median_size_and_says_what_would_fit() {
    // 60 m thick at x = 0 and 0.5 m at x = 4000: one layer where it is under 25 m thick, down
    // to `min_size` (1 m) near its thin end, would be millions of tets.
    let (mesh, err) = layers_between((-250.0, 0.0), (-310.0, 0.014875), 4000.0, "layers = 1");
    let line = (err.lines()).find(|l| l.contains("region `layer` thins to"));
    let line = line.unwrap_or_else(|| panic!("no warning:\n{err}"));
    for needle in [
        "`mesh.regions.layer.layers = 1`",
        "million tets",
        "`min_size = ",
    ] {
        assert!(line.contains(needle), "{needle}: {line}");
    }
    let layer = mesh.regions.iter().position(|r| r.name == "layer").unwrap() as u32;
    let tets = mesh.tet_region.iter().filter(|&&r| r == layer).count();
    assert!(
        tets < 200_000,
        "meshed from its median thickness: {tets} tets"
    );
}

#[test]
fn a_size_a_thousand_times_too_fine_fails_at_once_naming_the_region_and_the_recipe_entry() {
    // `size = 0.05` for 50: about 10¹⁵ tets in the example's box. Meshing its first surfaces ran
    // for minutes without an answer; the build now stops before any mesher.
    let s = Scratch::didactic();
    s.edit("size = 200.0", "size = 0.05\nmin_size = 0.01");
    let (ok, r, err) = s.build(&[]);
    assert!(!ok, "{err}");
    assert!(
        err.contains("the mesh sizes ask for about 4.2e15 tets, over the 1e9 a build may make")
            && err.contains("region `overburden_E` alone")
            && err.contains("from `size` in `[mesh]`: raise it"),
        "{err}"
    );
    let meshed = (r["nodes"].as_array().expect("nodes").iter())
        .filter(|n| n["kind"] == "surface_mesh" || n["kind"] == "tet_mesh")
        .count();
    assert_eq!(meshed, 0, "no mesher ran");
    // A region's own size is named as its entry.
    let s = Scratch::didactic();
    s.edit(
        "size = 200.0",
        "size = 200.0\n\n[mesh.regions]\nunderburden_E = { size = 0.5 }",
    );
    let (ok, _, err) = s.build(&[]);
    assert!(!ok);
    assert!(
        err.contains("region `underburden_E` alone")
            && err.contains("`size` in `[mesh.regions]`'s entry underburden_E"),
        "{err}"
    );
}
