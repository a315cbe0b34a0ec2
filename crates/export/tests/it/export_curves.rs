//! The curves VTU read by meshio and by VTK (through PyVista): one line cell per segment, each
//! with its curve's id, and the names table. A reader that is absent skips with a note.

use test_support::export_support;

use export::curves::write_curves_vtu;
use export_support::python_has;

fn curves() -> Vec<(String, Vec<[f64; 3]>)> {
    let line = |n: usize, y: f64| (0..n).map(|i| [i as f64 * 0.5, y, -1.0]).collect();
    vec![
        ("F1/H1".to_string(), line(4, 0.0)),
        ("box.xmin#2".to_string(), line(2, 1.0)),
        ("H2/box.ymax".to_string(), line(5, 2.0)),
    ]
}

/// Writes the curves VTU into a temporary directory and runs `script` on it.
fn read_with(script: &str) -> String {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("m.curves.vtu");
    std::fs::write(&path, write_curves_vtu(&curves())).unwrap();
    export_support::python(script, &[path.to_str().unwrap()])
}

const MESHIO: &str = r#"
import sys, meshio
m = meshio.read(sys.argv[1])
print("CELLS", ";".join(f"{b.type}:{len(b.data)}" for b in m.cells), len(m.points))
print("CURVE", ",".join(str(x) for x in m.cell_data["curve"][0]))
print("FIRST", ",".join(str(x) for x in m.cells[0].data[0]))
print("NAMES", ";".join(f"{k}={int(v[0])}" for k, v in m.field_data.items()))
"#;

#[test]
fn meshio_reads_each_curve_segment_as_a_line_with_its_curve_id_and_name() {
    if !python_has("meshio") {
        return;
    }
    let out = read_with(MESHIO);
    for want in [
        "CELLS line:8 11",
        "CURVE 1,1,1,2,3,3,3,3",
        "FIRST 0,1",
        "NAMES curve:F1/H1=1;curve:box.xmin#2=2;curve:H2/box.ymax=3",
    ] {
        assert!(out.lines().any(|l| l == want), "{want} not in\n{out}");
    }
}

const PYVISTA: &str = r#"
import sys, pyvista
m = pyvista.read(sys.argv[1])
print("LINES", m.n_cells, sorted(set(int(c) for c in m.celltypes)), m.n_points)
print("LENGTH", round(sum(m.compute_cell_sizes()["Length"]), 6))
"#;

#[test]
fn vtk_reads_the_curves_as_lines_with_their_lengths() {
    if !python_has("pyvista") {
        return;
    }
    let out = read_with(PYVISTA);
    assert!(out.contains("LINES 8 [3] 11\n"), "{out}");
    assert!(out.contains("LENGTH 4.0\n"), "{out}");
}
