//! The size bound of the report's pictures on a mesh of about a million tets: a structured grid
//! of 80 × 80 × 26 cubes (six Kuhn tets each) in three layers, with box sides and two horizons
//! tagged. The page must stay under a few megabytes and still show every region.

use test_support::grid;

use georecipe::report::{FACE_CAP, ReportInput, render_html};
use grid::grid;

#[test]
fn a_million_tet_mesh_gives_a_page_of_a_few_megabytes_with_bounded_pictures() {
    let m = grid(80, 80, 26);
    assert!(m.tets.len() > 990_000);
    m.check_indices().unwrap();
    let html = render_html(&ReportInput::from_mesh("grid", "grid.toml", &m));
    if let Ok(out) = std::env::var("REPORT_OUT") {
        std::fs::write(format!("{out}/grid.html"), &html).unwrap();
    }
    let s_faces = html.matches("<path class=\"s").count();
    let r_faces = html.matches("<path class=\"r").count();
    eprintln!(
        "{} tets, {} triangles: report.html {} bytes; {s_faces} + {r_faces} faces drawn",
        m.tets.len(),
        m.triangles.len(),
        html.len()
    );
    assert!(s_faces <= FACE_CAP && r_faces <= FACE_CAP);
    assert!(
        s_faces > FACE_CAP / 8,
        "the bound keeps a picture, not a few faces"
    );
    assert!(
        html.contains("Size bound:"),
        "the caption says the bound applied"
    );
    assert!(html.len() < 4_000_000, "{} bytes", html.len());
    for r in ["overburden", "reservoir", "underburden"] {
        assert!(html.contains(r));
    }
}
