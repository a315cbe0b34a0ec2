//! Walks every file under ../shared/data/gocad (sorted) and pins its import outcome: object,
//! surface, vertex, triangle and part counts, or the exact error line and message.

use geom::Tolerances;
use gocad::import::{ImportOptions, import_surfaces, parse_gocad};
use gocad::validate::validate;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use test_support::paths;

fn gocad_dir() -> Option<PathBuf> {
    paths::shared("data/gocad")
}

fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(rd) = std::fs::read_dir(dir) else {
        return;
    };
    for e in rd.flatten() {
        let p = e.path();
        if p.is_dir() {
            walk(&p, out);
        } else {
            out.push(p);
        }
    }
}

fn is_gocad(p: &Path) -> bool {
    matches!(
        p.extension().and_then(|e| e.to_str()),
        Some("ts" | "ml" | "gp" | "pl" | "vs" | "gcd")
    )
}

/// One-line outcome of a file: what parse_gocad and import_surfaces (skipping other types) say.
pub fn outcome(bytes: &[u8], label: &str) -> String {
    let parsed = match parse_gocad(bytes, label) {
        Ok(f) => f,
        Err(e) => return format!("parse error line {}: {}", e.line, e.message),
    };
    let opts = ImportOptions {
        skip_other_types: true,
        ..Default::default()
    };
    let regions = parsed.model3d.as_ref().map_or(0, |m| m.regions.len());
    match import_surfaces(bytes, label, &opts) {
        Ok(s) => {
            let v: usize = s.iter().map(|s| s.mesh.vertices.len()).sum();
            let t: usize = s.iter().map(|s| s.mesh.triangles.len()).sum();
            let p: usize = s.iter().map(|s| s.parts.len()).sum();
            let mut counts: BTreeMap<String, u64> = BTreeMap::new();
            for surf in &s {
                for (k, n) in validate(surf, &Tolerances::default()).counts() {
                    *counts.entry(k).or_insert(0) += n;
                }
            }
            let found: Vec<String> = counts
                .iter()
                .filter(|e| *e.1 > 0)
                .map(|(k, n)| format!("{k}={n}"))
                .collect();
            let found = if found.is_empty() {
                "clean".to_string()
            } else {
                found.join(" ")
            };
            format!(
                "objects={} surfaces={} V={v} T={t} parts={p} regions={regions} | {found}",
                parsed.objects.len(),
                s.len()
            )
        }
        Err(e) => format!(
            "objects={} error line {}: {}",
            parsed.objects.len(),
            e.line,
            e.message
        ),
    }
}

/// Pinned outcome of every gOcad file, in sorted path order: counts, or the error line and message,
/// then the validation findings summed over the file's surfaces.
const EXPECTED: &[(&str, &str)] = &[
    (
        "AuScope__geomodel-2-3dweb/test/regression/input/2layer.gp",
        "objects=3 error line 13: the file holds no GOCAD TSurf object (its first object is a GOCAD PLine)",
    ),
    (
        "AuScope__geomodel-2-3dweb/test/regression/input/gpColour.gp",
        "objects=1 surfaces=1 V=3 T=1 parts=1 regions=0 | clean",
    ),
    (
        "AuScope__geomodel-2-3dweb/test/regression/input/gpTest.gp",
        "objects=6 error line 37: the file holds no GOCAD TSurf object (its first object is a GOCAD VSet)",
    ),
    (
        "AuScope__geomodel-2-3dweb/test/regression/input/plTest.pl",
        "objects=1 error line 1: the file holds no GOCAD TSurf object (its first object is a GOCAD PLine)",
    ),
    (
        "AuScope__geomodel-2-3dweb/test/regression/input/tsTest.ts",
        "objects=1 surfaces=1 V=582 T=989 parts=3 regions=0 | clean",
    ),
    (
        "AuScope__geomodel-2-3dweb/test/regression/input/vsTest.vs",
        "objects=1 error line 1: the file holds no GOCAD TSurf object (its first object is a GOCAD VSet)",
    ),
    (
        "AuScope__geomodel-2-3dweb/test/unit/assimp_kit/otway_test.ts",
        "objects=1 surfaces=1 V=49 T=55 parts=1 regions=0 | clean",
    ),
    (
        "AuScope__geomodel-2-3dweb/test/unit/gocad_import/input/test002.ts",
        "objects=1 surfaces=1 V=3 T=1 parts=1 regions=0 | clean",
    ),
    (
        "AuScope__geomodel-2-3dweb/test/unit/gocad_import/input/test003.pl",
        "objects=1 error line 1: the file holds no GOCAD TSurf object (its first object is a GOCAD PLine)",
    ),
    (
        "AuScope__geomodel-2-3dweb/test/unit/gocad_import/input/test004.vs",
        "objects=1 error line 1: the file holds no GOCAD TSurf object (its first object is a GOCAD VSet)",
    ),
    (
        "AuScope__geomodel-2-3dweb/test/unit/gocad_import/input/test010.ts",
        "objects=1 error line 1: TSurf object has no triangles",
    ),
    (
        "AuScope__geomodel-2-3dweb/test/unit/gocad_import/input/test011.ts",
        "objects=1 error line 1: TSurf object has no triangles",
    ),
    (
        "AuScope__geomodel-2-3dweb/test/unit/gocad_import/input/test012.ts",
        "objects=1 error line 1: TSurf object has no triangles",
    ),
    (
        "AuScope__geomodel-2-3dweb/test/unit/gocad_import/input/test013.ts",
        "objects=1 error line 1: TSurf object 'Testing12/3' has no triangles",
    ),
    (
        "AuScope__geomodel-2-3dweb/test/unit/gocad_import/input/test014.ts",
        "objects=1 surfaces=1 V=3 T=1 parts=1 regions=0 | clean",
    ),
    (
        "AuScope__geomodel-2-3dweb/test/unit/gocad_import/input/test015.ts",
        "parse error line 2: VRTX 1: x coordinate 'inf' is infinite or NaN",
    ),
    (
        "AuScope__geomodel-2-3dweb/test/unit/gocad_import/input/test016.ts",
        "parse error line 2: VRTX 1: x coordinate '-inf' is infinite or NaN",
    ),
    (
        "AuScope__geomodel-2-3dweb/test/unit/gocad_import/input/test017.ts",
        "parse error line 2: VRTX 1: x coordinate '1.#INF' is infinite or NaN",
    ),
    (
        "AuScope__geomodel-2-3dweb/test/unit/gocad_import/input/test018.ts",
        "parse error line 2: VRTX 1: x coordinate '-1.#INF' is infinite or NaN",
    ),
    (
        "AuScope__geomodel-2-3dweb/test/unit/gocad_import/input/test019.ts",
        "parse error line 2: VRTX 1: x coordinate 'blah' is not a number",
    ),
    (
        "AuScope__geomodel-2-3dweb/test/unit/gocad_import/input/test020.vs",
        "objects=1 error line 1: the file holds no GOCAD TSurf object (its first object is a GOCAD VSet)",
    ),
    (
        "AuScope__geomodel-2-3dweb/test/unit/gocad_import/input/test021.vs",
        "objects=1 error line 1: the file holds no GOCAD TSurf object (its first object is a GOCAD VSet)",
    ),
    (
        "AuScope__geomodel-2-3dweb/test/unit/gocad_import/input/test022.vs",
        "objects=1 error line 1: the file holds no GOCAD TSurf object (its first object is a GOCAD VSet)",
    ),
    (
        "AuScope__geomodel-2-3dweb/test/unit/gocad_import/input/test026.ts",
        "objects=1 surfaces=1 V=3 T=1 parts=1 regions=0 | clean",
    ),
    (
        "AuScope__geomodel-2-3dweb/test/unit/gocad_import/input/test027.vs",
        "objects=1 error line 1: the file holds no GOCAD TSurf object (its first object is a GOCAD VSet)",
    ),
    (
        "AuScope__geomodel-2-3dweb/test/unit/gocad_import/input/test028.ts",
        "objects=1 surfaces=1 V=9 T=5 parts=1 regions=0 | inconsistent_orientation=1 self_intersection=2",
    ),
    (
        "AuScope__geomodel-2-3dweb/test/unit/gocad_import/input/test029.ts",
        "objects=1 surfaces=1 V=3 T=1 parts=1 regions=0 | clean",
    ),
    (
        "AuScope__geomodel-2-3dweb/test/unit/gocad_import/input/test031.ts",
        "objects=1 surfaces=1 V=9 T=5 parts=1 regions=0 | inconsistent_orientation=1 self_intersection=2",
    ),
    (
        "AuScope__geomodel-2-3dweb/test/unit/gocad_import/input/test032.ts",
        "objects=1 surfaces=1 V=9 T=5 parts=1 regions=0 | inconsistent_orientation=1 self_intersection=2",
    ),
    (
        "AuScope__geomodel-2-3dweb/test/unit/gocad_import/input/test033.gp",
        "objects=6 error line 12: the file holds no GOCAD TSurf object (its first object is a GOCAD VSet)",
    ),
    (
        "AuScope__geomodel-2-3dweb/test/unit/gocad_import/input/test034.ts",
        "objects=1 error line 1: TSurf object 'Testing123' has no triangles",
    ),
    (
        "AuScope__geomodel-2-3dweb/test/unit/gocad_import/input/test035.ts",
        "objects=1 error line 1: TSurf object 'Testing124' has no triangles",
    ),
    (
        "AuScope__geomodel-2-3dweb/test/unit/gocad_import/input/test036.ts",
        "objects=1 error line 1: TSurf object 'Testing123' has no triangles",
    ),
    (
        "AuScope__geomodel-2-3dweb/test/unit/gocad_import/input/test037.pl",
        "objects=1 error line 1: the file holds no GOCAD TSurf object (its first object is a GOCAD PLine)",
    ),
    (
        "AuScope__geomodel-2-3dweb/test/unit/gocad_import/input/test040.gp",
        "objects=10 error line 12: the file holds no GOCAD TSurf object (its first object is a GOCAD Voxet)",
    ),
    (
        "Geode-solutions__OpenGeode-GeosciencesIO/tests/data/2triangles.ts",
        "objects=1 surfaces=1 V=4 T=2 parts=1 regions=0 | inconsistent_orientation=1",
    ),
    (
        "Geode-solutions__OpenGeode-GeosciencesIO/tests/data/Fault_without_crs.ts",
        "objects=1 surfaces=1 V=189 T=324 parts=1 regions=0 | clean",
    ),
    (
        "Geode-solutions__OpenGeode-GeosciencesIO/tests/data/closed_lines.pl",
        "objects=1 error line 1: the file holds no GOCAD TSurf object (its first object is a GOCAD PLine)",
    ),
    (
        "Geode-solutions__OpenGeode-GeosciencesIO/tests/data/normal_lines.pl",
        "objects=1 error line 1: the file holds no GOCAD TSurf object (its first object is a GOCAD PLine)",
    ),
    (
        "Geode-solutions__OpenGeode-GeosciencesIO/tests/data/points.vs",
        "objects=1 error line 1: the file holds no GOCAD TSurf object (its first object is a GOCAD VSet)",
    ),
    (
        "Geode-solutions__OpenGeode-GeosciencesIO/tests/data/sgrid_tsurf.ts",
        "objects=2 surfaces=1 V=4 T=2 parts=1 regions=0 | clean",
    ),
    (
        "Geode-solutions__OpenGeode-GeosciencesIO/tests/data/surf2d.ts",
        "objects=1 surfaces=1 V=46 T=46 parts=3 regions=0 | coplanar_overlap=5",
    ),
    (
        "Geode-solutions__OpenGeode-GeosciencesIO/tests/data/surf2d_multi.ts",
        "objects=2 surfaces=2 V=92 T=92 parts=6 regions=0 | coplanar_overlap=10",
    ),
    (
        "Geode-solutions__OpenGeode-GeosciencesIO/tests/data/ts-2props.ts",
        "objects=1 surfaces=1 V=4 T=2 parts=1 regions=0 | clean",
    ),
    (
        "GeoscienceAustralia__earthsci/plugins/au.gov.ga.earthsci.worldwind.tests/resources/au/gov/ga/earthsci/worldwind/common/layers/model/gocad/pline.gp",
        "objects=1 error line 9: the file holds no GOCAD TSurf object (its first object is a GOCAD PLine)",
    ),
    (
        "GeoscienceAustralia__earthsci/plugins/au.gov.ga.earthsci.worldwind.tests/resources/au/gov/ga/earthsci/worldwind/common/layers/model/gocad/tsurf.ts",
        "objects=1 surfaces=1 V=3 T=1 parts=1 regions=0 | clean",
    ),
    (
        "GeoscienceAustralia__earthsci/plugins/au.gov.ga.earthsci.worldwind.tests/resources/au/gov/ga/earthsci/worldwind/common/layers/model/gocad/vset.vs",
        "objects=1 error line 1: the file holds no GOCAD TSurf object (its first object is a GOCAD VSet)",
    ),
    (
        "OPM__ResInsight/ApplicationLibCode/UnitTests/TestData/RifSurfaceImporter/geom_with_properties.ts",
        "objects=1 surfaces=1 V=5215 T=10066 parts=1 regions=0 | inconsistent_orientation=14864",
    ),
    (
        "OPM__ResInsight/ApplicationLibCode/UnitTests/TestData/RifSurfaceImporter/tsurf_eks.ts",
        "objects=1 surfaces=1 V=159 T=253 parts=1 regions=0 | clean",
    ),
    (
        "OPM__ResInsight/ApplicationLibCode/UnitTests/TestData/RifSurfaceImporter/tsurf_invalid.ts",
        "parse error line 30: TRGL points at vertex 59, which is not defined",
    ),
    (
        "SCECcode__CFM/CFM5.3_4/ts/1000m/CRFA-BPPM-LKWV-Lockwood_Valley_fault-CFM2_1000m.ts",
        "objects=1 surfaces=1 V=418 T=753 parts=1 regions=0 | clean",
    ),
    (
        "SCECcode__CFM/CFM5.3_4/ts/1000m/CRFA-BPPM-PMTS-Pine_Mountain_fault-CFM2_1000m.ts",
        "objects=1 surfaces=1 V=1623 T=3084 parts=1 regions=0 | clean",
    ),
    (
        "SCECcode__CFM/CFM5.3_4/ts/1000m/CRFA-BPPM-WEST-Big_Pine_fault-CFM2_1000m.ts",
        "objects=1 surfaces=1 V=311 T=557 parts=1 regions=0 | clean",
    ),
    (
        "SCECcode__CFM/CFM5.3_4/ts/1000m/GRFS-GRFZ-WEST-Garlock_fault-CFM5_1000m.ts",
        "objects=1 surfaces=1 V=1746 T=3262 parts=1 regions=0 | clean",
    ),
    (
        "SCECcode__CFM/CFM5.3_4/ts/1000m/GVFA-PLFZ-MULT-Pleito_fault-CFM2_1000m.ts",
        "objects=1 surfaces=1 V=862 T=1592 parts=1 regions=0 | clean",
    ),
    (
        "SCECcode__CFM/CFM5.3_4/ts/1000m/GVFA-WWFZ-MULT-White_Wolf_fault-CFM5_1000m.ts",
        "objects=1 surfaces=1 V=2698 T=4985 parts=1 regions=0 | duplicate_vertex=15 non_manifold_edge=14",
    ),
    (
        "SCECcode__CFM/CFM5.3_4/ts/1000m/SAFS-SAFZ-1857-San_Andreas_fault_rupture-CFM5_1000m.ts",
        "objects=1 surfaces=1 V=5524 T=10248 parts=1 regions=0 | duplicate_vertex=3 non_manifold_edge=2",
    ),
    (
        "SCECcode__CFM/CFM5.3_4/ts/1000m/SAFS-SAFZ-CRRZ-San_Andreas_fault-CFM4_1000m.ts",
        "objects=1 surfaces=1 V=2728 T=5133 parts=1 regions=0 | clean",
    ),
    (
        "SCECcode__CFM/CFM5.3_4/ts/1000m/SAFS-SAFZ-MJVS-San_Andreas_fault-CFM4_1000m.ts",
        "objects=1 surfaces=1 V=1464 T=2711 parts=1 regions=0 | clean",
    ),
    (
        "SCECcode__CFM/CFM5_release_2017/obj/CFM5_all/ETRA-BBFS-1992-Big_Bear_rupture_fault-nw.ts",
        "objects=1 surfaces=1 V=18 T=16 parts=1 regions=0 | degenerate_triangle=2 duplicate_vertex=1",
    ),
    (
        "SCECcode__CFM/CFM5_release_2017/obj/CFM5_all/GVFA-WWFZ-EAST-Scodie_Lineament-CFM1.ts",
        "objects=1 surfaces=1 V=6 T=4 parts=1 regions=0 | clean",
    ),
    (
        "SCECcode__CFM/CFM5_release_2017/obj/CFM5_all/GVFA-WWFZ-MULT-White_Wolf_fault-original.ts",
        "objects=1 surfaces=1 V=370 T=596 parts=2 regions=0 | clean",
    ),
    (
        "SCECcode__CFM/CFM5_release_2017/obj/CFM5_all/PNRA-ELSZ-LGSD-Laguna_Salada_fault-west_branch-deep_splay-CFM4.ts",
        "objects=1 surfaces=1 V=6 T=4 parts=1 regions=0 | clean",
    ),
    (
        "SCECcode__CFM/CFM5_release_2017/obj/CFM5_all/SAFS-SGPR-MTSJ-Potatochip1_blind_fault-CRNA-CFM5.ts",
        "objects=1 surfaces=1 V=145 T=251 parts=1 regions=0 | duplicate_vertex=1 unreferenced_vertex=11",
    ),
    (
        "SCECcode__CFM/CFM5_release_2017/obj/CFM5_all/WTRA-NCVS-RDMT-Red_Mountain_fault-west-CFM1.ts",
        "objects=1 surfaces=1 V=12 T=8 parts=2 regions=0 | duplicate_vertex=2 inconsistent_orientation=1",
    ),
    (
        "SCECcode__CFM/CFM5_release_2017/obj/CFM5_preferred/native/MJVA-HPFZ-HPVS-Harper_Valley-Mt_General_fault-CFM5.ts",
        "objects=1 surfaces=1 V=144 T=239 parts=2 regions=0 | duplicate_vertex=2",
    ),
    (
        "equinor__fmu-dataio/tests/data/drogon/rms/output/structural/F5.ts",
        "objects=1 surfaces=1 V=44 T=65 parts=1 regions=0 | clean",
    ),
    (
        "equinor__fmu-dataio/tests/data/drogon/rms/output/structural/basic_tsurf_file_with_errors.ts",
        "objects=1 error line 10: ZPOSITIVE must be Elevation or Depth, found 'wrong'",
    ),
    (
        "equinor__fmu-dataio/tests/data/drogon/rms/output/structural/basic_tsurf_file_with_warnings.ts",
        "objects=1 error line 10: AXIS_UNIT 'pico-meter' is not a length unit this importer knows (m, km, ft)",
    ),
    (
        "ringmesh__RINGMesh/tests/data/CloudSpin.ml",
        "objects=23 surfaces=22 V=19538 T=30751 parts=115 regions=8 | duplicate_vertex=2223",
    ),
    (
        "ringmesh__RINGMesh/tests/data/CloudSpin_fixed.ml",
        "objects=23 surfaces=22 V=19518 T=30751 parts=115 regions=8 | duplicate_vertex=2203",
    ),
    (
        "ringmesh__RINGMesh/tests/data/modelA1.ml",
        "objects=10 surfaces=9 V=5118 T=7932 parts=21 regions=5 | duplicate_vertex=750",
    ),
    (
        "ringmesh__RINGMesh/tests/data/modelA2.ml",
        "objects=7 surfaces=6 V=13234 T=16346 parts=61 regions=13 | duplicate_vertex=3320",
    ),
    (
        "ringmesh__RINGMesh/tests/data/modelA4.ml",
        "objects=12 surfaces=11 V=28002 T=48903 parts=55 regions=9 | duplicate_vertex=1446",
    ),
    (
        "ringmesh__RINGMesh/tests/data/modelA5.ml",
        "objects=7 surfaces=6 V=11670 T=14553 parts=64 regions=13 | duplicate_vertex=2871",
    ),
    (
        "ringmesh__RINGMesh/tests/data/non_split_cube.ml",
        "objects=3 surfaces=2 V=16 T=22 parts=2 regions=2 | inconsistent_orientation=4",
    ),
    (
        "ringmesh__RINGMesh/tests/data/not_sealed_cube.ml",
        "objects=7 surfaces=6 V=24 T=12 parts=6 regions=1 | clean",
    ),
    (
        "ringmesh__RINGMesh/tests/data/split_cube.ml",
        "objects=3 surfaces=2 V=16 T=22 parts=3 regions=3 | inconsistent_orientation=4",
    ),
    (
        "simpeg-research__Astic-2020-JointInversion/Geology_Surfaces/CDED_Lake_Coarse.ts",
        "objects=1 surfaces=1 V=34665 T=68816 parts=1 regions=0 | clean",
    ),
    (
        "simpeg-research__Astic-2020-JointInversion/Geology_Surfaces/HK1.ts",
        "objects=1 surfaces=1 V=3389 T=6774 parts=1 regions=0 | clean",
    ),
    (
        "simpeg-research__Astic-2020-JointInversion/Geology_Surfaces/PK1.ts",
        "objects=1 surfaces=1 V=5838 T=11672 parts=1 regions=0 | clean",
    ),
    (
        "simpeg-research__Astic-2020-JointInversion/Geology_Surfaces/PK2.ts",
        "objects=1 surfaces=1 V=205 T=406 parts=1 regions=0 | clean",
    ),
    (
        "simpeg-research__Astic-2020-JointInversion/Geology_Surfaces/PK3.ts",
        "objects=1 surfaces=1 V=362 T=720 parts=1 regions=0 | clean",
    ),
    (
        "simpeg-research__Astic-2020-JointInversion/Geology_Surfaces/Till.ts",
        "objects=1 surfaces=1 V=34665 T=68816 parts=1 regions=0 | clean",
    ),
    (
        "simpeg-research__Astic-2020-JointInversion/Geology_Surfaces/VK.ts",
        "objects=1 surfaces=1 V=2790 T=5576 parts=1 regions=0 | clean",
    ),
    (
        "xaliphostes__xali-pytools/data/models/chimney.ts",
        "objects=1 surfaces=1 V=2086 T=3272 parts=24 regions=0 | duplicate_vertex=69 non_manifold_edge=32",
    ),
    (
        "xaliphostes__xali-pytools/data/models/gom.ts",
        "objects=1 surfaces=1 V=5347 T=10650 parts=11 regions=0 | clean",
    ),
    (
        "xaliphostes__xali-pytools/data/models/oseberg.ts",
        "objects=58 surfaces=58 V=4479 T=7045 parts=58 regions=0 | duplicate_vertex=62",
    ),
    (
        "xaliphostes__xali-pytools/data/models/planar.ts",
        "objects=1 surfaces=1 V=228 T=383 parts=2 regions=0 | duplicate_vertex=11",
    ),
    (
        "xaliphostes__xali-pytools/data/models/sphere.ts",
        "objects=1 surfaces=1 V=195 T=358 parts=1 regions=0 | clean",
    ),
    (
        "xaliphostes__xali-pytools/data/models/tindel.ts",
        "objects=11 surfaces=11 V=2319 T=4017 parts=11 regions=0 | duplicate_vertex=42",
    ),
    (
        "xaliphostes__xali-pytools/tests/surfaces.ts",
        "objects=33 surfaces=33 V=8566 T=13712 parts=33 regions=0 | clean",
    ),
    (
        "xaliphostes__xali-pytools/tests/two-triangles.gcd",
        "objects=1 surfaces=1 V=4 T=2 parts=1 regions=0 | clean",
    ),
    (
        "youwol__io/src/tests/extracted/GalapagosObs_payload.ts",
        "objects=1 surfaces=1 V=9 T=3 parts=2 regions=0 | self_intersection=1",
    ),
    (
        "youwol__io/src/tests/extracted/S1_payload.ts",
        "objects=1 surfaces=1 V=246 T=438 parts=1 regions=0 | clean",
    ),
];

#[test]
fn every_shared_gocad_file_imports_or_fails_exactly_as_pinned() {
    let Some(root) = gocad_dir() else {
        return;
    };
    let mut files = Vec::new();
    walk(&root, &mut files);
    files.sort();
    let mut actual = Vec::new();
    for f in files.iter().filter(|p| is_gocad(p)) {
        let rel = f
            .strip_prefix(&root)
            .map(|r| r.to_string_lossy().to_string())
            .unwrap_or_default();
        let bytes = std::fs::read(f).expect("readable");
        actual.push((rel.clone(), outcome(&bytes, &rel)));
    }
    let listing: String = actual
        .iter()
        .map(|(f, o)| format!("    (\"{f}\", \"{}\"),\n", o.replace('"', "\\\"")))
        .collect();
    assert_eq!(
        actual.len(),
        EXPECTED.len(),
        "file list changed:\n{listing}"
    );
    for ((file, got), (want_file, want)) in actual.iter().zip(EXPECTED) {
        assert_eq!(file, want_file, "file list changed:\n{listing}");
        assert_eq!(got, want, "{file}\nfull table:\n{listing}");
    }
}
