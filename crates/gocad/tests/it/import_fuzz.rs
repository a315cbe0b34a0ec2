//! No byte sequence makes the import panic: proptest mutates real gOcad files (byte flips,
//! insertions, truncations, line shuffles and duplications) and runs import, validation and
//! topology on whatever imports; lines and wells get the same treatment. Inputs the fuzzer found are kept in tests/data/gocad/fuzz/ and
//! replayed by `every_kept_fuzz_case_fails_or_imports_without_panicking`.

use geom::Tolerances;
use gocad::import::{ImportOptions, import_lines, import_surfaces, import_wells, parse_gocad};
use gocad::validate::{repair, validate};
use model::topology::SurfaceTopology;
use proptest::prelude::*;
use test_support::paths;

const SEEDS: &[&str] = &[
    "SCECcode__CFM/CFM5_release_2017/obj/CFM5_all/ETRA-BBFS-1992-Big_Bear_rupture_fault-nw.ts",
    "SCECcode__CFM/CFM5_release_2017/obj/CFM5_all/WTRA-NCVS-RDMT-Red_Mountain_fault-west-CFM1.ts",
    "ringmesh__RINGMesh/tests/data/split_cube.ml",
    "AuScope__geomodel-2-3dweb/test/unit/gocad_import/input/test032.ts",
    "AuScope__geomodel-2-3dweb/test/regression/input/gpColour.gp",
    "Geode-solutions__OpenGeode-GeosciencesIO/tests/data/ts-2props.ts",
    "youwol__io/src/tests/extracted/GalapagosObs_payload.ts",
];

const FALLBACK: &str = "GOCAD TSurf 1\nHEADER {\nname: t\n}\nGOCAD_ORIGINAL_COORDINATE_SYSTEM\nAXIS_UNIT \"km\" \"km\" \"m\"\nZPOSITIVE Depth\nEND_ORIGINAL_COORDINATE_SYSTEM\nPROPERTIES a\nTFACE\nPVRTX 1 0 0 0 1\nPVRTX 2 1 0 0 2\nPVRTX 3 0 1 0 3\nATOM 4 2\nTRGL 1 2 3\nTFACE\nVRTX 5 1 1 0\nTRGL 4 5 3\nBSTONE 1\nBORDER 6 1 2\nEND\n";

fn seeds() -> Vec<Vec<u8>> {
    let mut v: Vec<Vec<u8>> = paths::shared("data/gocad")
        .map(|root| {
            SEEDS
                .iter()
                .filter_map(|p| std::fs::read(root.join(p)).ok())
                .collect()
        })
        .unwrap_or_default();
    if v.is_empty() {
        eprintln!("note: no real seed file; fuzzing the built-in sample only");
    }
    v.push(FALLBACK.as_bytes().to_vec());
    v
}

const LINE_SEEDS: &[&str] = &[
    "AuScope__geomodel-2-3dweb/test/regression/input/plTest.pl",
    "AuScope__geomodel-2-3dweb/test/regression/input/2layer.gp",
];

const LINE_FALLBACK: &str = "GOCAD PLine 1\r\nHEADER {\r\nname: l\r\n}\r\nGOCAD_ORIGINAL_COORDINATE_SYSTEM\r\nAXIS_UNIT \"km\" \"km\" \"m\"\r\nZPOSITIVE Depth\r\nEND_ORIGINAL_COORDINATE_SYSTEM\r\nPROPERTIES a\r\nILINE\r\nPVRTX 1 1 2 300 7\r\nVRTX 2 1.5 2 310\r\nATOM 3 2\r\nVRTX 4 2 2 320\r\nSEG 1 2\r\nSEG 3 4\r\nILINE\r\nVRTX 5 0 0 0\r\nVRTX 6 0 1 0\r\nSEG 5 6\r\nEND";

const WELL_FALLBACK: &str = "GOCAD Well 1\nHEADER {\nname: W1\n}\nGOCAD_ORIGINAL_COORDINATE_SYSTEM\nAXIS_UNIT m m m\nZPOSITIVE Depth\nEND_ORIGINAL_COORDINATE_SYSTEM\nPATH_ZM_UNIT ft\nWREF 1000 2000 -25\nKB 25\nPATH 0 -25 0 0\nPATH 1000 279.8 0 0\nPATH 2000 520 150 50\nMRKR Top 1 1500\nUNIT A\nMRKR \"B c\" 1 2000\nZONE z 1500 2000 1\nWELL_CURVE\nPROPERTY GR\nREC 100 5\nEND_CURVE\nEND\nGOCAD Well 1\nHEADER {name: V}\nWREF 0 0 10\nVRTX 0 0 10\nVRTX 1 0 0 -90\nMRKR m 1 50\nEND\n";

fn line_and_well_seeds() -> Vec<Vec<u8>> {
    let mut v: Vec<Vec<u8>> = paths::shared("data/gocad")
        .map(|root| {
            LINE_SEEDS
                .iter()
                .filter_map(|p| std::fs::read(root.join(p)).ok())
                .collect()
        })
        .unwrap_or_default();
    v.push(LINE_FALLBACK.as_bytes().to_vec());
    v.push(WELL_FALLBACK.as_bytes().to_vec());
    v
}

/// Imports the lines and wells; what imports must be consistent, panics are the other failure.
fn exercise_lines_and_wells(bytes: &[u8]) {
    let opts = ImportOptions {
        skip_other_types: true,
        ..Default::default()
    };
    if let Ok(lines) = import_lines(bytes, "fuzz.pl", &opts) {
        for l in lines {
            let n = l.vertices.len() as u32;
            assert!(l.segments.iter().flatten().all(|&v| v < n));
            assert!(l.segment_part.iter().all(|&p| (p as usize) < l.parts.len()));
        }
    }
    if let Ok(wells) = import_wells(bytes, "fuzz.wl", &opts) {
        for w in wells {
            assert_eq!(w.stations.len(), w.measured_depth.len());
            assert!(w.measured_depth.windows(2).all(|p| p[0] <= p[1]));
            let (first, last) = (
                w.measured_depth[0],
                w.measured_depth[w.measured_depth.len() - 1],
            );
            assert!(w.markers.iter().all(|m| m.md >= first && m.md <= last));
        }
    }
}

/// Runs the whole chain; panics are the only failure.
fn exercise(bytes: &[u8]) {
    let _ = parse_gocad(bytes, "fuzz.ts");
    let opts = ImportOptions {
        skip_other_types: true,
        ..Default::default()
    };
    if let Ok(surfaces) = import_surfaces(bytes, "fuzz.ts", &opts) {
        let tol = Tolerances::default();
        for s in surfaces {
            assert_eq!(s.triangle_part.len(), s.mesh.triangles.len());
            assert!(
                s.mesh
                    .triangles
                    .iter()
                    .flatten()
                    .all(|&i| (i as usize) < s.mesh.vertices.len())
            );
            let raw = SurfaceTopology::build(&s.mesh, &s.bstones, &tol);
            let _ = raw.boundary_loops().len();
            let r = validate(&s, &tol);
            let _ = r.render_text();
            let (fixed, _) = repair(&s, &r, &tol);
            let topo = SurfaceTopology::build_with_parts(
                &fixed.mesh,
                &fixed.triangle_part,
                &fixed.bstones,
                &tol,
            );
            let _ = topo.curves().len();
        }
    }
}

#[derive(Debug, Clone)]
enum Mutation {
    Flip(usize, u8),
    Insert(usize, u8),
    Truncate(usize),
    SwapLines(usize, usize),
    DuplicateLine(usize),
    DeleteLine(usize),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        (any::<usize>(), any::<u8>()).prop_map(|(p, b)| Mutation::Flip(p, b)),
        (
            any::<usize>(),
            prop::sample::select(b" \t\r\n-.e0123456789#\"{}:".to_vec())
        )
            .prop_map(|(p, b)| Mutation::Insert(p, b)),
        any::<usize>().prop_map(Mutation::Truncate),
        (any::<usize>(), any::<usize>()).prop_map(|(a, b)| Mutation::SwapLines(a, b)),
        any::<usize>().prop_map(Mutation::DuplicateLine),
        any::<usize>().prop_map(Mutation::DeleteLine),
    ]
}

fn apply(mut bytes: Vec<u8>, muts: &[Mutation]) -> Vec<u8> {
    for m in muts {
        let n = bytes.len().max(1);
        match *m {
            Mutation::Flip(p, b) => {
                if let Some(x) = bytes.get_mut(p % n) {
                    *x ^= b;
                }
            }
            Mutation::Insert(p, b) => bytes.insert((p % n).min(bytes.len()), b),
            Mutation::Truncate(p) => bytes.truncate(p % n),
            Mutation::SwapLines(a, b) => {
                bytes = edit_lines(&bytes, |l| {
                    let n = l.len();
                    l.swap(a % n, b % n)
                })
            }
            Mutation::DuplicateLine(a) => {
                bytes = edit_lines(&bytes, |l| {
                    let k = a % l.len();
                    let dup = l[k].clone();
                    l.insert(k, dup);
                })
            }
            Mutation::DeleteLine(a) => {
                bytes = edit_lines(&bytes, |l| {
                    l.remove(a % l.len());
                })
            }
        }
    }
    bytes
}

fn edit_lines(bytes: &[u8], f: impl FnOnce(&mut Vec<Vec<u8>>)) -> Vec<u8> {
    let mut lines: Vec<Vec<u8>> = bytes.split(|&c| c == b'\n').map(|l| l.to_vec()).collect();
    f(&mut lines);
    lines.join(&b'\n')
}

proptest! {
    #![proptest_config(ProptestConfig {
        // FUZZ_CASES=20000 for a longer hunt.
        failure_persistence: None,
        ..test_support::proptest_config(test_support::fuzz_cases(192))
    })]
    #[test]
    fn mutated_real_files_never_panic(seed in any::<prop::sample::Index>(), muts in prop::collection::vec(mutation(), 1..6)) {
        let all = seeds();
        let base = all[seed.index(all.len())].clone();
        exercise(&apply(base, &muts));
    }

    #[test]
    fn mutated_lines_and_wells_never_panic(seed in any::<prop::sample::Index>(), muts in prop::collection::vec(mutation(), 1..6)) {
        let all = line_and_well_seeds();
        let base = all[seed.index(all.len())].clone();
        exercise_lines_and_wells(&apply(base, &muts));
    }
}

#[test]
fn every_kept_fuzz_case_fails_or_imports_without_panicking() {
    let dir = paths::data("gocad/fuzz");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .map(|d| d.flatten().map(|e| e.path()).collect())
        .unwrap_or_default();
    files.sort();
    assert!(
        !files.is_empty(),
        "tests/data/gocad/fuzz holds the kept cases"
    );
    for f in files {
        exercise(&std::fs::read(&f).unwrap());
    }
}
