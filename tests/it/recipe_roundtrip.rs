//! Valid recipes parse to the values they say: the DESIGN.md sample (in our schema), the fully
//! commented reference recipe, and the documented defaults and precedence rules.

use std::path::{Path, PathBuf};
use test_support::paths;

use georecipe::recipe::{
    BoxExtent, Format, Grading, ImportFormat, OnInvalid, Recipe, Side, Subdivision, SurfaceKind,
    TetMethod, TrimAction, Units, parse,
};

fn load(name: &str) -> (PathBuf, String) {
    let path = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/recipes")).join(name);
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    (path, text)
}

fn ok(label: &Path, text: &str) -> Recipe {
    parse(label, text).unwrap_or_else(|d| {
        panic!(
            "{}",
            d.iter()
                .map(|d| d.to_string())
                .collect::<Vec<_>>()
                .join("\n")
        )
    })
}

fn pair(a: &str, b: &str) -> (String, String) {
    (a.to_string(), b.to_string())
}

#[test]
fn the_design_sample_recipe_parses_to_the_expected_values() {
    let (_, text) = load("didactic.toml");
    let r = ok(Path::new("recipes/didactic.toml"), &text);
    assert_eq!(r.model.name, "didactic");
    assert_eq!(r.model.units, Units::Metre);
    assert_eq!(r.base_dir, Path::new("recipes"));
    assert_eq!(
        r.surfaces.keys().collect::<Vec<_>>(),
        ["base", "f1", "f2", "top"]
    );
    let f2 = &r.surfaces["f2"];
    assert_eq!(f2.kind, SurfaceKind::Fault);
    assert_eq!(f2.retriangulate, Some(100.0));
    assert_eq!(f2.path, Path::new("recipes/data/f2.ts"));
    assert_eq!(f2.format, ImportFormat::TSurf);
    assert_eq!(f2.on_invalid, OnInvalid::Repair);
    assert_eq!(r.surfaces["top"].kind, SurfaceKind::Horizon);
    let b = r.bbox.as_ref().expect("box");
    assert_eq!(
        b.extent,
        BoxExtent::Explicit {
            min: [0.0, 0.0, -2500.0],
            max: [5000.0, 5000.0, 0.0]
        }
    );
    // 3 surfaces x 6 box sides + 4 surface pairs, sorted and each pair sorted.
    assert_eq!(r.intersect.len(), 3 * 6 + 4);
    assert_eq!(r.intersect.len(), r.intersect_spans.len());
    assert!(r.intersect.windows(2).all(|w| w[0] < w[1]));
    assert!(r.intersect.iter().all(|(a, b)| a < b));
    assert!(r.intersect.contains(&pair("box.zmax", "top")));
    assert!(r.intersect.contains(&pair("f2", "top")));
    assert!(
        !r.intersect
            .iter()
            .any(|(a, b)| a == "f2" && b.starts_with("box"))
    );
    assert_eq!(r.trims.len(), 1);
    assert_eq!(r.trims[0].surface.pattern, "f2");
    assert_eq!(
        r.trims[0].action,
        TrimAction::Keep {
            side: Side::Below,
            of: "top".into()
        }
    );
    assert_eq!(r.mesh.size, 200.0);
    assert_eq!(r.mesh.min_size, 2.0);
    assert_eq!(r.mesh.max_size, 2000.0);
    assert_eq!(r.mesh.growth, 1.3);
    let texts: Vec<&str> = r
        .mesh
        .curves
        .iter()
        .map(|c| c.selector.text.as_str())
        .collect();
    assert_eq!(
        texts,
        ["top/f1", "base/f1", "top/box.*", "f1/box.*"],
        "recipe order is kept"
    );
    assert_eq!(r.mesh.curves[2].subdivision, Subdivision::Count(40));
    assert_eq!(
        r.mesh.curves[3].subdivision,
        Subdivision::Size {
            size: 100.0,
            ratio: 1.2,
            grading: Grading::Geometric
        }
    );
    assert_eq!(r.mesh.surface_size("f2"), 50.0);
    assert_eq!(r.mesh.surface_size("top"), 200.0);
    let res = &r.mesh.regions["reservoir"];
    assert_eq!(
        (res.size, res.min_size, res.max_size, res.growth),
        (50.0, 2.0, 2000.0, 1.3)
    );
    assert_eq!(r.regions["reservoir"].point, [2500.0, 2500.0, -1217.0]);
    assert_eq!(r.regions["reservoir"].material, Some(2));
    assert_eq!(r.output.dir, Path::new("out"));
    assert_eq!(r.output.path, Path::new("recipes/out"));
    assert_eq!(r.output.formats, [Format::Msh, Format::Vtu]);
}

#[test]
fn the_reference_recipe_parses_and_sets_every_key() {
    let (path, text) = load("reference.toml");
    let r = ok(&path, &text);
    assert_eq!(r.tolerances.kink_angle_deg, 30.0);
    assert_eq!(r.tolerances.support_distance_rel, 1e-6);
    let lens = &r.surfaces["lens"];
    assert_eq!(lens.format, ImportFormat::Model3d);
    assert_eq!(
        lens.object,
        Some(gocad::import::ObjectRef::Name("lens_1".into()))
    );
    assert!(lens.skip_other_types);
    assert_eq!(r.surfaces["base"].on_invalid, OnInvalid::Stop);
    let actions: Vec<&TrimAction> = r.trims.iter().map(|t| &t.action).collect();
    assert_eq!(
        actions,
        [
            &TrimAction::Keep {
                side: Side::Below,
                of: "top".into()
            },
            &TrimAction::DiscardAreaBelow(1000.0),
            &TrimAction::DiscardContaining([2500.0, 2500.0, -1200.0]),
            &TrimAction::DiscardNearest([100.0, 100.0, -2400.0]),
        ]
    );
    assert_eq!(
        r.mesh.curves[1].subdivision,
        Subdivision::Size {
            size: 50.0,
            ratio: 1.1,
            grading: Grading::Bump
        }
    );
    assert_eq!(r.mesh.surface_size("box.zmin"), 400.0);
    assert_eq!(r.mesh.tet_method, TetMethod::Delaunay);
    assert_eq!(r.mesh.regions["reservoir"].tet_method, TetMethod::Front);
    assert_eq!(r.regions["reservoir"].properties["permeability"], 1e-13);
    assert_eq!(r.output.formats.len(), 5);
    // `all` among top, base, f1 and the box: 3 pairs plus 3 x 6 with the sides; plus explicit ones.
    assert!(r.intersect.contains(&pair("base", "top")));
    assert!(r.intersect.contains(&pair("lens", "top")));
    assert!(
        !r.intersect
            .iter()
            .any(|(a, b)| a.starts_with("box.") && b.starts_with("box."))
    );
    assert_eq!(r.intersect.len(), 3 + 18 + 3);
}

#[test]
fn the_most_specific_curve_rule_wins_and_ties_go_to_the_last_written() {
    let (path, text) = load("reference.toml");
    let r = ok(&path, &text);
    let rule = |c: &str| r.mesh.curve_rule(c).map(|x| x.selector.text.clone());
    assert_eq!(rule("top/f1").as_deref(), Some("top/f1"));
    assert_eq!(rule("f1/top#2").as_deref(), Some("top/f1#2"));
    assert_eq!(rule("box.xmin/f1").as_deref(), Some("f1/box.*"));
    assert_eq!(rule("lens/top").as_deref(), Some("lens"));
    assert_eq!(rule("lens#1").as_deref(), Some("lens"));
    assert_eq!(rule("base/f2"), None);
    let text = "[model]\nname = \"t\"\n[surfaces]\na = { file = \"a.ts\" }\nb = { file = \"b.ts\" }\n[mesh]\nsize = 1\n[mesh.curves]\n\"a\" = { count = 1 }\n\"b\" = { count = 2 }\n";
    let r = ok(Path::new("t.toml"), text);
    assert_eq!(
        r.mesh.curve_rule("a/b").map(|x| x.subdivision.clone()),
        Some(Subdivision::Count(2))
    );
}

#[test]
fn a_box_around_surfaces_takes_a_scalar_or_per_axis_margin() {
    let base = "[model]\nname = \"t\"\n[surfaces]\na = { file = \"a.ts\" }\n[mesh]\nsize = 1\n";
    let r = ok(
        Path::new("t.toml"),
        &format!("{base}[box]\naround = [\"a\"]\nmargin = 5\n"),
    );
    let expected = BoxExtent::Around {
        surfaces: vec!["a".into()],
        margin: [5.0; 3],
    };
    assert_eq!(r.bbox.map(|b| b.extent), Some(expected));
    let r = ok(
        Path::new("t.toml"),
        &format!("{base}[box]\naround = [\"a\"]\nmargin = [1, 2, 3.5]\n"),
    );
    let expected = BoxExtent::Around {
        surfaces: vec!["a".into()],
        margin: [1.0, 2.0, 3.5],
    };
    assert_eq!(r.bbox.map(|b| b.extent), Some(expected));
    let d = parse(
        Path::new("t.toml"),
        &format!("{base}[box]\naround = [\"a\"]\nmin = [0, 0, 0]\n"),
    )
    .unwrap_err();
    assert!(d[0].message.contains("mixes"));
}

#[test]
fn defaults_fill_a_minimal_recipe() {
    let r = ok(
        Path::new("m.toml"),
        "[model]\nname = \"m\"\n[mesh]\nsize = 10\n",
    );
    assert_eq!(r.model.units, Units::Metre);
    assert!(
        r.surfaces.is_empty() && r.bbox.is_none() && r.intersect.is_empty() && r.trims.is_empty()
    );
    assert_eq!(
        (r.mesh.min_size, r.mesh.max_size, r.mesh.growth),
        (0.1, 100.0, 1.3)
    );
    assert_eq!(r.output.formats, [Format::Msh, Format::Vtu]);
    assert_eq!(r.output.path, Path::new("out"));
    assert_eq!(r.base_dir, Path::new(""));
}

#[test]
fn region_sizes_default_to_the_global_bounds_clamped_around_the_region_size() {
    let text = "[model]\nname = \"t\"\n[mesh]\nsize = 10\n[mesh.regions]\nr = { size = 2000 }\n[regions]\nr = { point = [0, 0, 0] }\n";
    let r = ok(Path::new("t.toml"), text);
    let s = &r.mesh.regions["r"];
    assert_eq!((s.size, s.min_size, s.max_size), (2000.0, 0.1, 2000.0));
}

#[test]
fn the_real_recipes_of_the_shared_data_parse_if_present() {
    let Some(design) = paths::shared("DESIGN.md") else {
        return;
    };
    // The DESIGN.md sample, verbatim, puts `intersect` under `[box]` (TOML scoping): the error
    // must explain the trap rather than say only "unknown key".
    let design = std::fs::read_to_string(design).unwrap_or_default();
    let Some(sample) = design
        .split("```toml\n")
        .nth(1)
        .and_then(|s| s.split("```").next())
    else {
        eprintln!("skipping: no toml sample in DESIGN.md");
        return;
    };
    let d = parse(Path::new("DESIGN.toml"), sample).unwrap_err();
    assert!(
        d.iter().any(|d| d
            .help
            .as_deref()
            .is_some_and(|h| h.contains("move it above `[box]`"))),
        "{d:#?}"
    );
}

#[test]
fn a_surface_given_as_a_bare_file_string_takes_every_default() {
    let text = "[model]\nname = \"t\"\n[surfaces]\ntop = \"data/top.TS\"\n[mesh]\nsize = 1\n";
    let r = ok(Path::new("r/t.toml"), text);
    let top = &r.surfaces["top"];
    assert_eq!(top.path, Path::new("r/data/top.TS"));
    assert_eq!(
        (top.format, top.kind, top.on_invalid),
        (ImportFormat::TSurf, SurfaceKind::Other, OnInvalid::Repair)
    );
    assert_eq!(top.file_span.line, 4);
    let d = parse(Path::new("t.toml"), &text.replace("top.TS", "top.tsurf")).unwrap_err();
    assert_eq!(d.len(), 1);
    assert!(
        d[0].help
            .as_deref()
            .is_some_and(|h| h.starts_with("did you mean `.ts`?")),
        "{}",
        d[0]
    );
}

#[test]
fn check_reports_missing_files_and_render_counts_the_errors() {
    let (_, text) = load("didactic.toml");
    let label = Path::new("recipes/didactic.toml");
    let exists = |p: &Path| !p.ends_with("f2.ts") && !p.ends_with("top.ts");
    let d = georecipe::recipe::check(label, &text, &exists).unwrap_err();
    assert_eq!(d.len(), 2);
    assert!(d[0].line < d[1].line, "source order");
    let out = georecipe::recipe::render(&d);
    assert!(
        out.ends_with("error: could not use `recipes/didactic.toml`: 2 errors\n"),
        "{out}"
    );
    assert!(georecipe::recipe::check(label, &text, &|_| true).is_ok());
}

#[test]
fn spans_do_not_reach_the_serialized_specs() {
    let (_, text) = load("didactic.toml");
    let a = ok(Path::new("d.toml"), &text);
    let b = ok(Path::new("d.toml"), &format!("\n\n# moved\n{text}"));
    assert_ne!(a.surfaces["f2"].span, b.surfaces["f2"].span);
    let ser = |r: &Recipe| {
        serde_json::to_string(&(
            &r.surfaces,
            &r.mesh,
            &r.trims,
            &r.regions,
            &r.output,
            &r.bbox,
        ))
        .unwrap_or_default()
    };
    assert!(!ser(&a).is_empty());
    assert_eq!(ser(&a), ser(&b));
}

#[test]
fn a_curve_rule_that_matches_no_curve_of_the_built_model_is_reported_at_the_rule() {
    let (_, text) = load("didactic.toml");
    let r = ok(Path::new("recipes/didactic.toml"), &text);
    let curves: Vec<String> = [
        "f1/top#1",
        "f1/top#2",
        "base/box.xmin",
        "box.xmin/top",
        "box.zmax/top",
        "f1/box.xmin",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    let d = r.check_curve_rules(&curves);
    // `base/f1` does not exist in this model; every other rule matches something.
    assert_eq!(d.len(), 1, "{d:#?}");
    assert_eq!(
        d[0].line,
        text.lines()
            .position(|l| l.starts_with("\"base/f1\""))
            .map_or(0, |i| i + 1)
    );
    assert!(d[0].message.contains("`base/f1` matches no curve"));
    assert!(
        d[0].help
            .as_deref()
            .is_some_and(|h| h.contains("`base/box.xmin`")),
        "{}",
        d[0]
    );
}

#[test]
fn tolerances_given_in_the_recipe_replace_the_defaults_field_by_field() {
    let text = "[model]\nname = \"t\"\n[tolerances]\nkink_angle_deg = 45\nmerge_distance = 0.01\n[mesh]\nsize = 1\n";
    let r = ok(Path::new("t.toml"), text);
    assert_eq!(r.tolerances.kink_angle_deg, 45.0);
    assert_eq!(r.tolerances.merge_distance, 0.01);
    assert_eq!(
        r.tolerances.support_distance_rel,
        geom::Tolerances::default().support_distance_rel
    );
}
