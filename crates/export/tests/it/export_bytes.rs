//! The export writers' bytes are pinned: every format's files for a mesh with awkward floats
//! (long fractions, tiny and huge magnitudes, negative zero, NaN properties), an empty region
//! and an empty surface group hash to the values pinned here: those the writers produced before
//! their memory rework, except where a format's content changed on purpose since (VTU: the
//! `MaterialIDs` array, 1-based ids, 32-bit indices, fault side cells; TetGen: each face's front
//! and back tets; the curves VTU: line cells; Abaqus: materials, sections, fault sides; Exodus: as first written, and its QA record
//! names the crate version, so a version bump changes its digest; msh: surface entities per
//! piece, volume boundaries, material and fault side groups). A change here changes every
//! cached export and every lock file.

use test_support::export_support;

use export::curves::write_curves_vtu;
use export::{Format, export};
use export_support::layered_box;
use geom::mesh::RegionGroup;
use std::collections::BTreeMap;

fn awkward_mesh() -> geom::mesh::VolumeMesh {
    let mut m = layered_box(6, 6);
    for (i, p) in m.nodes.iter_mut().enumerate() {
        p[0] += (i as f64) * 0.1;
        p[1] += 1.0 / (1.0 + i as f64);
        if i % 7 == 0 {
            p[2] = -p[2] * 1e-9;
        }
    }
    m.nodes[3][2] = -0.0;
    m.nodes[5][0] = 1e21;
    m.nodes[6][1] = 5e-324;
    m.regions[1].properties.insert("porosity".into(), 0.1 + 0.2);
    m.regions[0]
        .properties
        .insert("perm".into(), f64::MIN_POSITIVE);
    m.regions[2].material = Some(-7);
    m.regions.push(RegionGroup {
        name: "empty <&\"'> region".into(),
        material: Some(9),
        properties: BTreeMap::from([("density".to_string(), 1e300)]),
    });
    m.surface_groups[0].name = "x\"min\" side".into();
    m
}

fn digest(files: &[(String, Vec<u8>)]) -> String {
    let mut h = blake3::Hasher::new();
    for (name, bytes) in files {
        h.update(name.as_bytes());
        h.update(&(bytes.len() as u64).to_le_bytes());
        h.update(bytes);
    }
    h.finalize().to_hex()[..16].to_string()
}

#[test]
fn every_format_writes_its_pinned_bytes() {
    let m = awkward_mesh();
    let expected = [
        "e1e71222e1443f52",
        "becbc940ee335808",
        "b59cdab6efeda829",
        "505a190bc4c2d34d",
        "b66818121fb99aff",
        "f0e39c1f9f040e15",
        "232bcc0c55073417",
        "b88c6441049d56b7",
    ];
    assert_eq!(expected.len(), Format::EVERY.len(), "a digest per format");
    for (f, want) in Format::EVERY.into_iter().zip(expected) {
        let files = export(&m, "golden", f).unwrap();
        assert_eq!(digest(&files), want, "{f:?} bytes changed");
    }
}

#[test]
fn the_curves_vtu_writes_its_pinned_bytes() {
    let m = awkward_mesh();
    let curves = vec![
        ("a&b".to_string(), m.nodes[..5].to_vec()),
        ("c".to_string(), m.nodes[10..40].to_vec()),
        ("empty".to_string(), vec![]),
    ];
    let bytes = write_curves_vtu(&curves);
    assert_eq!(digest(&[("c".into(), bytes)]), "9af83117c32930df");
}
