//! `[model] sealed = true`: parsed as a bool (a wrong type names `file:line:col`), defaulting to
//! false; a sealed recipe gets the `model` node (which drives meshing) without a `[box]`, while
//! a recipe with neither keeps the curves-only graph.

use georecipe::plan::lower;
use georecipe::recipe::parse;
use std::path::Path;

const FILE: &str = "recipes/sealed.toml";

fn recipe(model_extra: &str) -> String {
    format!(
        "[model]\nname = \"t\"\n{model_extra}\n\n[surfaces]\n\
         top = {{ file = \"data/top.ts\", kind = \"horizon\" }}\n\
         base = {{ file = \"data/base.ts\", kind = \"horizon\" }}\n\n\
         [intersect]\npairs = [[\"top\", \"base\"]]\n\n[mesh]\nsize = 1.0\n"
    )
}

#[test]
fn sealed_defaults_to_false_and_reads_true() {
    let r = parse(Path::new(FILE), &recipe("")).expect("parses");
    assert!(!r.model.sealed);
    let r = parse(Path::new(FILE), &recipe("sealed = true")).expect("parses");
    assert!(r.model.sealed);
}

#[test]
fn a_sealed_value_that_is_not_a_bool_names_its_line_and_column() {
    let d = parse(Path::new(FILE), &recipe("sealed = \"yes\"")).expect_err("rejected");
    assert_eq!(d.len(), 1, "{d:?}");
    assert_eq!((d[0].file.as_str(), d[0].line, d[0].col), (FILE, 3, 10));
    assert!(d[0].message.contains("model.sealed"), "{}", d[0].message);
    assert!(
        d[0].message.contains("`true` or `false`"),
        "{}",
        d[0].message
    );
}

#[test]
fn a_sealed_recipe_without_a_box_gets_the_model_node_and_an_unsealed_one_does_not() {
    let sealed = parse(Path::new(FILE), &recipe("sealed = true")).expect("parses");
    let g = lower(&sealed).expect("lowers");
    assert!(g.node("model").is_some());
    assert!(g.node("curves").is_none());
    let open = parse(Path::new(FILE), &recipe("")).expect("parses");
    let g = lower(&open).expect("lowers");
    assert!(g.node("model").is_none());
    assert!(g.node("curves").is_some());
}
