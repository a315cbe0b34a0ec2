//! The report of a realistic mesh: the three western regions of the didactic model (boundaries
//! meshed by Gmsh, tets by us), with surface triangles tagged box / H1 / H2 / F1. Checks names,
//! counts, volumes against the peer's enclosed volumes, and the size of the page.

use test_support::peers;

use georecipe::report::{ReportInput, render_both};

#[test]
fn the_report_of_three_meshed_peer_regions_is_complete_and_small() {
    let Some(dir) = peers::shared_dir() else {
        return;
    };
    // REPORT_ALL=1 meshes the six regions (slower); REPORT_OUT=DIR writes the two documents there.
    let regions: Vec<&str> = if std::env::var("REPORT_ALL").is_ok() {
        vec![
            "overburden_W",
            "overburden_E",
            "reservoir_W",
            "reservoir_E",
            "underburden_W",
            "underburden_E",
        ]
    } else {
        vec!["overburden_W", "reservoir_W", "underburden_W"]
    };
    let (mesh, volumes) = peers::peer_mesh(&dir, &regions).unwrap_or_else(|e| panic!("{e}"));
    mesh.check_indices().expect("a consistent mesh");
    let input = ReportInput::from_mesh("didactic_W", "peer-boundaries", &mesh);
    let (html, json) = render_both(&input);
    eprintln!(
        "{} tets, {} surface triangles: report.html {} bytes, report.json {} bytes",
        mesh.tets.len(),
        mesh.triangles.len(),
        html.len(),
        json.len()
    );
    if let Ok(out) = std::env::var("REPORT_OUT") {
        std::fs::write(format!("{out}/report.html"), &html).unwrap();
        std::fs::write(format!("{out}/report.json"), &json).unwrap();
    }
    for name in
        regions
            .iter()
            .chain(&["box", "H1_top_reservoir", "H2_base_reservoir", "F1_through"])
    {
        assert!(html.contains(name), "{name} missing");
    }
    assert!(html.len() < 4_000_000, "the page stays under a few MB");
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    assert_eq!(
        v["counts"]["tets"].as_u64().unwrap() as usize,
        mesh.tets.len()
    );
    for (i, want) in volumes.iter().enumerate() {
        let got = v["mesh"]["regions"][i]["volume"].as_f64().unwrap();
        assert!(
            ((got - want) / want).abs() < 1e-6,
            "{}: tets fill {got} m³, the boundary encloses {want} m³",
            regions[i]
        );
    }
    // Every tet is in its region's histogram.
    for (i, h) in v["histograms"]["mean_ratio"]
        .as_array()
        .unwrap()
        .iter()
        .enumerate()
    {
        let n: u64 = h["counts"]
            .as_array()
            .unwrap()
            .iter()
            .map(|c| c.as_u64().unwrap())
            .sum();
        assert_eq!(n, v["mesh"]["regions"][i]["tets"].as_u64().unwrap());
    }
    // Both pictures draw faces.
    assert!(html.matches("<path class=\"s").count() > 1000);
    assert!(html.matches("<path class=\"r").count() > 1000);
}
