//! The export operation produces its files one at a time in path order and appends them to its
//! artifact as they come; its artifact must still be byte for byte the postcard encoding of the
//! whole `FileSet` assembled the straightforward way (every format's files inserted in recipe
//! order, a later format replacing an earlier one of the same name), so cache keys and lock
//! files do not change.

use test_support::export_support;

use engine::{Artifact, FileSet, Operation, RunContext};
use export::curves::write_curves_vtu;
use export::quality;
use export::{Format, export};
use export_support::layered_box;
use georecipe::plan::ops::{CurveNodes, ExportOp, Groups, Wiring};

struct Quiet;
impl RunContext for Quiet {
    fn progress(&self, _: u64, _: u64) {}
}

fn curve(name: &str, nodes: Vec<[f64; 3]>) -> CurveNodes {
    CurveNodes {
        name: name.into(),
        nodes,
    }
}

/// An export wired with `n_curves` curves and the mesh (ids do not matter here).
fn groups(n_curves: usize) -> Groups {
    Wiring::new()
        .group("curves", vec![(); n_curves])
        .group("mesh", [()])
        .finish()
        .1
}

fn run(formats: &[&str], model: &str) -> (Artifact, FileSet) {
    let mesh = layered_box(6, 6);
    let curves = vec![
        curve("a/b", mesh.nodes[..4].to_vec()),
        curve("c", mesh.nodes[7..19].to_vec()),
    ];
    let op = ExportOp {
        model: model.into(),
        recipe_file: "m.toml".into(),
        formats: formats
            .iter()
            .map(|s| export::Format::from_name(s).expect("a format"))
            .collect(),
        inputs: groups(curves.len()),
    };
    let mut inputs: Vec<Artifact> = curves
        .iter()
        .map(|c| Artifact::encode(c).unwrap())
        .collect();
    inputs.push(Artifact::encode(&mesh).unwrap());
    let out = op.run(&Quiet, &inputs).unwrap();

    // The same files, assembled whole.
    let mut set = FileSet::new().with(
        &format!("{model}.curves.vtu"),
        write_curves_vtu(
            &curves
                .into_iter()
                .map(|c| (c.name, c.nodes))
                .collect::<Vec<_>>(),
        ),
    );
    for f in formats {
        for (name, bytes) in export(&mesh, model, Format::from_name(f).unwrap()).unwrap() {
            set.files.insert(name, bytes);
        }
    }
    let q = quality::report(&mesh);
    set.files
        .insert(format!("{model}.quality.txt"), q.render().into_bytes());
    set.files.insert(
        format!("{model}.quality.json"),
        serde_json::to_string_pretty(&q).unwrap().into_bytes(),
    );
    (out.artifact, set)
}

#[test]
fn the_export_artifact_is_the_postcard_encoding_of_all_its_files() {
    for (formats, model) in [
        (&["msh", "vtu"][..], "layered"),
        (&["tetgen", "medit", "msh-binary", "vtu"][..], "m"),
        // The same name from two formats: the later one wins, as in a map.
        (&["msh", "msh-binary", "tetgen"][..], "zz"),
        (&["vtu-binary", "inp", "tetgen"][..], "a"),
    ] {
        let (artifact, set) = run(formats, model);
        let want = postcard::to_stdvec(&set).unwrap();
        let bytes = artifact.bytes().unwrap();
        assert_eq!(bytes.len(), want.len(), "{formats:?}");
        assert!(bytes == &want[..], "{formats:?}: bytes differ");
        assert_eq!(artifact.decode::<FileSet>().unwrap(), set);
    }
}
