//! A recipe over real public gOcad files (SCEC Community Fault Model) builds: imports with their
//! quirks repaired and reported, an exact intersection of two real faults, curves discretized.

use crate::common_cli;
use common_cli::*;
use test_support::paths;

#[test]
fn a_recipe_over_real_cfm_faults_builds_and_reports_what_it_repaired() {
    let Some(shared) = paths::shared("data/gocad/SCECcode__CFM") else {
        return;
    };
    let s = Scratch::didactic();
    let d = shared.display();
    let recipe = format!(
        r#"
[model]
name = "bigbend"

[surfaces]
garlock = {{ file = "{d}/CFM5.3_4/ts/1000m/GRFS-GRFZ-WEST-Garlock_fault-CFM5_1000m.ts", kind = "fault" }}
pleito = {{ file = "{d}/CFM5.3_4/ts/1000m/GVFA-PLFZ-MULT-Pleito_fault-CFM2_1000m.ts", kind = "fault" }}
bigbear = {{ file = "{d}/CFM5_release_2017/obj/CFM5_all/ETRA-BBFS-1992-Big_Bear_rupture_fault-nw.ts", kind = "fault" }}
whitewolf = {{ file = "{d}/CFM5_release_2017/obj/CFM5_all/GVFA-WWFZ-MULT-White_Wolf_fault-original.ts", kind = "fault" }}

[intersect]
pairs = [["garlock", "pleito"]]

[mesh]
size = 2000.0

[mesh.curves]
"garlock/pleito" = {{ size = 500.0 }}

[output]
dir = "out/bigbend"
"#
    );
    std::fs::write(s.path("bigbend.toml"), recipe).unwrap();
    let out = s.recipe_cmd(&["build", "--json", "bigbend.toml"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    let r: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let node = |name: &str| {
        r["nodes"]
            .as_array()
            .unwrap()
            .iter()
            .find(|n| n["name"] == name)
            .cloned()
            .unwrap_or_else(|| panic!("no node {name}"))
    };
    assert_eq!(node("import:garlock")["counts"]["triangles"], 3262);
    assert!(
        node("import:bigbear")["counts"]["findings"]
            .as_u64()
            .unwrap()
            > 0,
        "Big Bear's zero-area triangles are found"
    );
    assert!(
        err.contains("bigbear"),
        "the repaired findings are printed: {err}"
    );
    assert!(
        node("intersect:garlock/pleito")["counts"]["curves"]
            .as_u64()
            .unwrap()
            >= 1
    );
    assert!(all_nodes(&r).contains(&"discretize:garlock/pleito".to_string()));
    let validation: serde_json::Value =
        serde_json::from_slice(&std::fs::read(s.path("out/bigbend/validation.json")).unwrap())
            .unwrap();
    assert!(validation.get("bigbear").is_some());
}

#[test]
fn a_file_whose_tsurf_objects_share_a_name_imports_by_position_and_the_name_says_how() {
    let Some(file) = paths::shared(
        "data/gocad/Geode-solutions__OpenGeode-GeosciencesIO/tests/data/surf2d_multi.ts",
    ) else {
        return;
    };
    let s = Scratch::didactic();
    let recipe = |object: &str| {
        format!(
            "[model]\nname = \"section\"\n\n[surfaces]\n\
             section = {{ file = \"{}\", object = {object} }}\n\n\
             [mesh]\nsize = 1.0\n\n[output]\ndir = \"out/section\"\n",
            file.display()
        )
    };
    // The two objects are both named `section1`: by name the import cannot choose, and says how.
    std::fs::write(s.path("section.toml"), recipe("\"section1\"")).unwrap();
    let (ok, r, err) = s.build_recipe("section.toml", &[]);
    assert!(!ok, "{err}");
    assert_eq!(nodes_in_state(&r, "failed"), ["import:section"]);
    for said in [
        "surf2d_multi.ts:1:",
        "2 objects are named 'section1'",
        "#1 'section1' (line 1)",
        "#2 'section1' (line 134)",
        "select one by its position in the file, e.g. `object = 1`",
    ] {
        assert!(err.contains(said), "`{said}` not in {err}");
    }
    // By position, the second object imports (SOURCES.md: 46 triangles in 3 TFACEs).
    std::fs::write(s.path("section.toml"), recipe("2")).unwrap();
    let (ok, r, err) = s.build_recipe("section.toml", &[]);
    assert!(ok, "{err}");
    let import = r["nodes"]
        .as_array()
        .unwrap()
        .iter()
        .find(|n| n["name"] == "import:section")
        .expect("the import node");
    assert_eq!(import["state"], "ran");
    assert_eq!(import["counts"]["triangles"], 46);
    assert_eq!(import["counts"]["parts"], 3);
}

/// A recipe meshing the TKC topography, the till's base and `bodies` (files in `d`), with the
/// pipes kept below the till and the further `[[trim]]` tables `trims`.
fn tkc_recipe(d: &std::path::Path, bodies: &[&str], trims: &str) -> String {
    let d = d.display();
    let surfaces: Vec<String> = (bodies.iter())
        .map(|b| format!("{b} = {{ file = \"{d}/{b}.ts\" }}"))
        .collect();
    let all: Vec<String> = (["box", "topo", "till"].iter().chain(bodies))
        .map(|n| format!("\"{n}\""))
        .collect();
    format!(
        r#"
[model]
name = "tkc"

[surfaces]
topo = {{ file = "{d}/CDED_Lake_Coarse.ts", kind = "horizon" }}
till = {{ file = "{d}/Till.ts", kind = "horizon" }}
{}

[box]
min = [556900.0, 7133200.0, -200.0]
max = [557800.0, 7134300.0, 500.0]

[intersect]
all = [{}]

[[trim]]
surface = "PK*"
keep = {{ below = "till" }}
{trims}
[mesh]
size = 50.0

[output]
dir = "out/tkc"
"#,
        surfaces.join("\n"),
        all.join(", ")
    )
}

/// Builds `recipe`, written as `file` in a scratch folder; returns it and the build's JSON.
fn build_json(recipe: &str, file: &str) -> (Scratch, serde_json::Value) {
    let s = Scratch::didactic();
    std::fs::write(s.path(file), recipe).unwrap();
    let out = s.recipe_cmd(&["build", "--json", file]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    (s, serde_json::from_slice(&out.stdout).unwrap())
}

/// Builds `recipe` in a scratch folder; returns it and the model's region names.
fn build_tkc(recipe: &str) -> (Scratch, Vec<String>) {
    let (s, r) = build_json(recipe, "tkc.toml");
    let regions = (r["model"]["regions"].as_array().expect("regions").iter())
        .map(|g| g["name"].as_str().expect("a name").to_string())
        .collect();
    (s, regions)
}

#[test]
fn the_tkc_kimberlite_pipes_under_till_and_topography_mesh_into_their_regions() {
    // A GOCAD model of the Tli Kwi Cho kimberlites (Astic 2020): topography and the till's base
    // as 13 km grids (their no-data vertices, at z = -99999 and -3.3e6, lie on the grids' edges,
    // outside this box), and two closed pipes that reach up into the till, where the till's base
    // truncates them. The other three bodies overlap each other; the next test meshes them.
    let Some(shared) = paths::shared("data/gocad/simpeg-research__Astic-2020-JointInversion")
    else {
        return;
    };
    let d = shared.join("Geology_Surfaces");
    let (s, regions) = build_tkc(&tkc_recipe(&d, &["PK2", "PK3"], ""));
    // The air, the till, the rock below it, and each pipe below the till.
    assert_eq!(regions.len(), 5, "{regions:?}");
    for pipe in ["PK2+till", "PK3+till"] {
        assert!(regions.iter().any(|r| r == pipe), "{regions:?}");
    }
    passes_check_mesh(&s.path("out/tkc/tkc.msh"), 5, "tkc");
    // The pipes' rough facets are cut into strips metres wide where they meet the till: 1.0°
    // with elements of 50 m across them, 5.9° with their curves as fine as the strips are wide.
    let worst = worst_dihedral(&s.path("out/tkc/tkc.quality.json"));
    assert!(worst > 4.0, "worst dihedral {worst}°");
}

#[test]
fn all_five_tkc_bodies_mesh_once_the_recipe_says_which_body_cuts_which() {
    // PK1, HK1 and VK overlap in the files: read as they are, their overlaps are regions of
    // their own, parted from each other by centimetres, and some do not mesh. The geomodeller
    // says which body is younger, as `keep = { outside = .. }` trims, and drops the one facet
    // of PK1 that lies on the till's base (the place the failing build names).
    let Some(shared) = paths::shared("data/gocad/simpeg-research__Astic-2020-JointInversion")
    else {
        return;
    };
    let trims = r#"
[[trim]]
surface = "HK1"
keep = { outside = "PK1" }

[[trim]]
surface = "VK"
keep = { outside = "PK1" }

[[trim]]
surface = "VK"
keep = { outside = "HK1" }

[[trim]]
surface = "VK"
discard = { within = 0.5 }

[[trim]]
surface = "PK1"
discard = { nearest = [557378.1, 7133579.8, 369.9] }
"#;
    let d = shared.join("Geology_Surfaces");
    let bodies = ["PK1", "PK2", "PK3", "HK1", "VK"];
    let (s, regions) = build_tkc(&tkc_recipe(&d, &bodies, trims));
    // The air, the till, the rock below it and the five bodies: PK1 whole, HK1 where PK1 cuts
    // it, VK where both do.
    assert_eq!(regions.len(), 8, "{regions:?}");
    for body in ["PK1+till", "PK2+till", "PK3+till", "HK1+PK1", "HK1+PK1+VK"] {
        assert!(
            regions.iter().any(|r| r == body),
            "{body} not in {regions:?}"
        );
    }
    passes_check_mesh(&s.path("out/tkc/tkc.msh"), 8, "tkc");
}

/// A recipe meshing one closed TKC body alone in a box, as read.
fn tkc_body(shared: &std::path::Path, body: &str) -> String {
    let d = shared.join("Geology_Surfaces");
    format!(
        r#"
[model]
name = "body"

[surfaces]
{body} = {{ file = "{}/{body}.ts" }}

[box]
min = [556900.0, 7133200.0, -200.0]
max = [557800.0, 7134300.0, 500.0]

[mesh]
size = 50.0

[output]
dir = "out/body"
"#,
        d.display()
    )
}

#[test]
fn every_tkc_body_alone_in_a_box_meshes_as_read() {
    // Each TKC body alone in a box, as read: rough all over, next to one another their facets
    // face up to 100° apart a few metres across. Creases and chart seams cut them into strips
    // metres wide, and elements as long as the recipe's 50 m across them were needles (PK2 at
    // 0.6°, VK's front stuck after 40 s); PK1 and HK1 folded. Curves inside one surface are now
    // discretized no coarser than the patches along them are wide, and a triangle folded across
    // a crumpled bend is unfolded. PK2, PK3 and VK reach 15.5° to 17°; HK1 12°; PK1 0.75° inside
    // it, at a sharp thin edge where its facets meet at 4.5° (the bound), and 2° outside, where a
    // sliver facet 0.3 m wide along that edge leaves needle triangles on the outside's wall.
    let Some(shared) = paths::shared("data/gocad/simpeg-research__Astic-2020-JointInversion")
    else {
        return;
    };
    for (body, bar) in [
        ("PK2", 12.0),
        ("PK3", 12.0),
        ("VK", 12.0),
        ("HK1", 10.0),
        ("PK1", 0.0),
    ] {
        let s = Scratch::didactic();
        std::fs::write(s.path("body.toml"), tkc_body(&shared, body)).unwrap();
        let out = s.recipe_cmd(&["build", "body.toml"]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{body}: {err}");
        let worst = worst_dihedral(&s.path("out/body/body.quality.json"));
        assert!(worst > bar, "{body}: worst dihedral {worst}°");
        passes_check_mesh(&s.path("out/body/body.msh"), 2, body);
    }
}

#[test]
fn a_rough_closed_tkc_body_retriangulates_piece_by_piece_and_meshes() {
    // A closed body has no border: re-triangulated whole, it had no loop to flatten ("the patch
    // has no boundary loop"). Cut as the model cuts it (creases, charts), each piece is meshed
    // on the old support and the pieces welded.
    let Some(shared) = paths::shared("data/gocad/simpeg-research__Astic-2020-JointInversion")
    else {
        return;
    };
    let text = tkc_body(&shared, "PK2").replace(".ts\" }", ".ts\", retriangulate = 15.0 }");
    assert!(text.contains("retriangulate = 15.0"), "{text}");
    let (s, r) = build_json(&text, "body.toml");
    let support = (r["nodes"].as_array().expect("nodes").iter())
        .find(|n| n["name"] == "support:PK2")
        .expect("a support node");
    let (given, now) = (
        support["counts"]["given_triangles"].as_u64().unwrap(),
        support["counts"]["support_triangles"].as_u64().unwrap(),
    );
    assert!(now > given, "{given} triangles became {now}");
    passes_check_mesh(&s.path("out/body/body.msh"), 2, "PK2");
}

#[test]
fn the_gulf_of_mexico_salt_bodies_mesh_at_every_size() {
    // Eleven closed salt bodies in one TSurf, one TFACE each, faceted by triangles 500 m to 1 km
    // wide whose normals turn by 50° to 70° from one to the next. At 1 km and above, curve
    // segments cut across the bodies' shoulders (130 m off the curve on a 490 m chord) and a
    // surface mesh along them folded, at every size from 600 m up.
    let Some(shared) = paths::shared("data/gocad/xaliphostes__xali-pytools/data/models") else {
        return;
    };
    for (size, checked) in [(1000.0, false), (3000.0, true)] {
        let s = Scratch::didactic();
        let recipe = format!(
            r#"
[model]
name = "gom"

[surfaces]
salt = {{ file = "{}" }}

[box]
min = [540000.0, 0.0, -11000.0]
max = [620000.0, 58000.0, -2000.0]

[mesh]
size = {size:.1}

[output]
dir = "out/gom"
"#,
            shared.join("gom.ts").display()
        );
        std::fs::write(s.path("gom.toml"), recipe).unwrap();
        let out = s.recipe_cmd(&["build", "--json", "gom.toml"]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "at {size}: {err}");
        let r: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        let regions = r["model"]["regions"].as_array().expect("regions").len();
        assert_eq!(regions, 12, "at {size}: the host and the eleven bodies");
        let worst = worst_dihedral(&s.path("out/gom/gom.quality.json"));
        assert!(worst > 8.0, "at {size}: worst dihedral {worst}°");
        if checked {
            passes_check_mesh(&s.path("out/gom/gom.msh"), 12, "gom");
        }
    }
}

/// The names of the TSurf objects in `file`, in file order.
fn tsurf_names(file: &std::path::Path) -> Vec<String> {
    let text =
        String::from_utf8_lossy(&std::fs::read(file).expect("read the TSurf file")).into_owned();
    (text.lines())
        .filter_map(|l| l.trim_end().strip_prefix("name:").map(str::to_string))
        .collect()
}

/// A recipe meshing every object of `file` as a fault, in the box `[lo, hi]`, at `size`.
fn fault_network(file: &std::path::Path, lo: [f64; 3], hi: [f64; 3], size: f64) -> String {
    let names = tsurf_names(file);
    let surfaces: Vec<String> = (names.iter())
        .map(|n| {
            format!(
                "{n} = {{ file = \"{}\", object = \"{n}\", kind = \"fault\" }}",
                file.display()
            )
        })
        .collect();
    let all: Vec<String> = (std::iter::once("box".to_string()))
        .chain(names.iter().cloned())
        .map(|n| format!("\"{n}\""))
        .collect();
    format!(
        "[model]\nname = \"net\"\n\n[surfaces]\n{}\n\n[box]\nmin = {lo:?}\nmax = {hi:?}\n\n\
         [intersect]\nall = [{}]\n\n[mesh]\nsize = {size:.1}\n\n[output]\ndir = \"out/net\"\n",
        surfaces.join("\n"),
        all.join(", ")
    )
}

/// Builds `recipe` and checks the mesh; returns the JSON report.
fn fault_network_meshes(recipe: &str, regions: usize) -> serde_json::Value {
    let s = Scratch::didactic();
    std::fs::write(s.path("net.toml"), recipe).unwrap();
    let out = s.recipe_cmd(&["build", "--json", "net.toml"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    let r: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let found = r["model"]["regions"].as_array().expect("regions").len();
    assert_eq!(found, regions);
    passes_check_mesh(&s.path("out/net/net.msh"), regions, "net");
    r
}

#[test]
fn the_oseberg_network_of_fifty_eight_faults_meshes_with_every_fault_embedded() {
    // Fifty-eight faults of the Oseberg field in one file, none cutting the box through: one
    // region, every fault a dangling sheet inside it, crossing and abutting one another.
    let Some(shared) = paths::shared("data/gocad/xaliphostes__xali-pytools/data/models") else {
        return;
    };
    let file = shared.join("oseberg.ts");
    assert_eq!(tsurf_names(&file).len(), 58);
    let recipe = fault_network(
        &file,
        [-2000.0, -5000.0, -200.0],
        [9000.0, 10000.0, 600.0],
        300.0,
    );
    let r = fault_network_meshes(&recipe, 1);
    let patches = r["model"]["patches"].as_array().expect("patches");
    let dangling: std::collections::BTreeSet<&str> = (patches.iter())
        .filter(|p| p["dangling"] == true)
        .filter_map(|p| p["surface"].as_str())
        .collect();
    assert_eq!(dangling.len(), 58, "every fault is embedded: {dangling:?}");
}

#[test]
fn the_tindel_faults_that_branch_and_truncate_mesh_into_their_blocks() {
    // Eleven faults, some branching off and some truncated by others; in this box three of them
    // cut it into three blocks and the rest end inside.
    let Some(shared) = paths::shared("data/gocad/xaliphostes__xali-pytools/data/models") else {
        return;
    };
    let file = shared.join("tindel.ts");
    assert_eq!(tsurf_names(&file).len(), 11);
    let recipe = fault_network(
        &file,
        [-1000.0, -1500.0, -2400.0],
        [3000.0, 5500.0, -1700.0],
        200.0,
    );
    fault_network_meshes(&recipe, 3);
}

#[test]
fn the_chimney_faults_whose_sheets_branch_along_shared_edges_mesh() {
    // One TSurf of 24 TFACEs, vertical sheets between two depths that meet three and four to an
    // edge along branch lines. Taken as one patch across such a line, the sheets had a boundary
    // that could not be chained into loops: `the boundary of patch ... is open`.
    let Some(shared) = paths::shared("data/gocad/xaliphostes__xali-pytools/data/models") else {
        return;
    };
    let recipe = format!(
        r#"
[model]
name = "net"

[surfaces]
B = {{ file = "{}", kind = "fault" }}

[box]
min = [539000.0, 4339000.0, 1400.0]
max = [545200.0, 4344200.0, 1750.0]

[intersect]
all = ["box", "B"]

[mesh]
size = 200.0

[output]
dir = "out/net"
"#,
        shared.join("chimney.ts").display()
    );
    let r = fault_network_meshes(&recipe, 1);
    // The sheets are parted where they branch: a branch line bounds three patches or more.
    let mut bounded: std::collections::BTreeMap<&str, usize> = Default::default();
    for p in r["model"]["patches"].as_array().expect("patches") {
        let curves = (p["loops"].as_array().into_iter().flatten())
            .flat_map(|l| l.as_array().into_iter().flatten())
            .filter_map(|c| c.as_str());
        for c in curves.collect::<std::collections::BTreeSet<_>>() {
            *bounded.entry(c).or_default() += 1;
        }
    }
    let branches = bounded.values().filter(|&&n| n >= 3).count();
    assert!(branches > 0, "no curve bounds three patches: {bounded:?}");
}
