//! The operations report progress through the engine: a `tet_mesh` node run by `engine::build`
//! emits `Event::Progress` events that make a good bar (`test_support::progress`), and `export`
//! one step per file it writes.

use std::sync::Mutex;

use engine::{
    Artifact, BuildGraph, BuildOptions, Event, OpError, Operation, Output, Params, RunContext,
};
use geom::TriMesh;
use geom::mesh::SurfaceKind;
use geom::mesh::read::read_by_extension;
use georecipe::plan::ops::{CurveNodes, ExportOp, PatchMesh, TetMeshOp, Wiring};
use model::regions::{FaceUse, Side};
use test_support::export_support::layered_box;
use test_support::paths;
use test_support::progress::assert_a_good_bar;
use tet_mesh::{Method, SizeField};

/// A source node: a patch mesh given as it is.
struct Given(PatchMesh);

impl Operation for Given {
    fn kind(&self) -> &'static str {
        "given"
    }
    fn version(&self) -> u32 {
        1
    }
    fn params(&self) -> Params {
        Params::new()
            .with("patch", self.0.name.as_str())
            .expect("string")
    }
    fn run(&self, _: &dyn RunContext, _: &[Artifact]) -> Result<Output, OpError> {
        Ok(Output::new(Artifact::encode(&self.0)?))
    }
}

/// A patch mesh read from one of the shipped example's region cases (`tests/data/tet_mesh`).
fn patch(name: &str, file: &str, kind: SurfaceKind) -> PatchMesh {
    let path = paths::data("tet_mesh/quality").join(file);
    let bytes = std::fs::read(&path).expect("case file");
    let m = read_by_extension(&path.display().to_string(), &bytes).expect("an OFF file");
    PatchMesh {
        name: name.into(),
        surface: name.into(),
        kind,
        mesh: TriMesh::new(m.vertices, m.triangles),
    }
}

#[test]
fn a_tet_mesh_node_built_by_the_engine_emits_progress_events_that_make_a_good_bar() {
    let dir = tempfile::tempdir().unwrap();
    let mut graph = BuildGraph::new();
    // The east overburden of the shipped example: its outward boundary, and the dangling fault
    // inside it (both sides of one patch).
    let boundary = patch("boundary", "shipped_overburden_E.off", SurfaceKind::Other);
    let fault = patch(
        "F2",
        "shipped_overburden_E.embedded.off",
        SurfaceKind::Fault,
    );
    let b = graph
        .add_op("given:boundary", std::sync::Arc::new(Given(boundary)), &[])
        .unwrap();
    let f = graph
        .add_op("given:F2", std::sync::Arc::new(Given(fault)), &[])
        .unwrap();
    let op = TetMeshOp {
        name: "overburden_E".into(),
        patches: vec!["boundary".into(), "F2".into()],
        smoothed: vec![false, false],
        sides: vec![
            FaceUse {
                patch: 0,
                side: Side::Back,
            },
            FaceUse {
                patch: 1,
                side: Side::Back,
            },
            FaceUse {
                patch: 1,
                side: Side::Front,
            },
        ],
        size_path: "mesh".into(),
        size: SizeField {
            size: 200.0,
            min_size: 2.0,
            max_size: 2000.0,
            growth: 1.3,
            refine: Vec::new(),
        },
        method: Method::Delaunay,
        refinements: 0,
        wells: false,
        layer: None,
    };
    graph
        .add_op("tet_mesh:overburden_E", std::sync::Arc::new(op), &[b, f])
        .unwrap();
    let events = Mutex::new(Vec::new());
    let opts = BuildOptions::new(dir.path().join("cache"), dir.path().join("out"));
    let report = engine::build(graph, &opts, &|e| {
        if let Event::Progress { name, done, total } = e {
            events.lock().unwrap().push((name.clone(), *done, *total));
        }
    })
    .unwrap();
    assert!(report.ok, "{:?}", report.to_json());
    let events = events.into_inner().unwrap();
    assert!(
        events.iter().all(|(n, _, _)| n == "tet_mesh:overburden_E"),
        "{events:?}"
    );
    let seen: Vec<(u64, u64)> = events.iter().map(|&(_, d, t)| (d, t)).collect();
    assert_a_good_bar("tet_mesh:overburden_E", &seen);
}

/// Records the progress an operation reports.
#[derive(Default)]
struct Recorder(Mutex<Vec<(u64, u64)>>);

impl RunContext for Recorder {
    fn progress(&self, done: u64, total: u64) {
        self.0.lock().unwrap().push((done, total));
    }
}

#[test]
fn the_export_reports_one_step_per_file_it_writes() {
    let mesh = layered_box(4, 3);
    let curve = CurveNodes {
        name: "c".into(),
        nodes: mesh.nodes[..4].to_vec(),
    };
    let (_, inputs) = Wiring::new()
        .group("curves", [()])
        .group("mesh", [()])
        .finish();
    let op = ExportOp {
        model: "m".into(),
        recipe_file: "m.toml".into(),
        formats: ["msh", "vtu", "tetgen"]
            .map(|f| export::Format::from_name(f).expect("a format"))
            .to_vec(),
        inputs,
    };
    let ctx = Recorder::default();
    let out = op
        .run(
            &ctx,
            &[
                Artifact::encode(&curve).unwrap(),
                Artifact::encode(&mesh).unwrap(),
            ],
        )
        .unwrap();
    let files = out.counts["files"];
    // The curves, msh, vtu, TetGen's .node, .ele and .face, the two quality tables.
    assert_eq!(files, 8);
    let steps: Vec<(u64, u64)> = (1..=files).map(|k| (k, files)).collect();
    assert_eq!(ctx.0.into_inner().unwrap(), steps);
}
