//! Hand-built models for region finding: a cube, a cube split by a horizon, dangling faults
//! (free-floating and hanging from the top), a lens (closed octahedron) inside the cube, a
//! horizon that stops short — each also at UTM offsets — plus naming, locating and the
//! independence from the order of the patches.

use geom::TriMesh;
use model::regions::{
    Dangling, FaceUse, PatchIn, RegionModel, RegionOptions, Side, find_regions, find_regions_with,
    locate,
};

const STEP: f64 = 0.25;

/// An axis-aligned rectangle at `axis = c`, spanning `u` on axis+1 and `v` on axis+2 (cyclic),
/// gridded with STEP; its right-hand normal points to +axis, or -axis when `flip`.
pub(crate) fn rect(
    name: &str,
    surface: &str,
    axis: usize,
    c: f64,
    u: (f64, f64),
    v: (f64, f64),
    flip: bool,
) -> PatchIn {
    let nu = ((u.1 - u.0) / STEP).round() as usize;
    let nv = ((v.1 - v.0) / STEP).round() as usize;
    let mut vertices = Vec::new();
    for j in 0..=nv {
        for i in 0..=nu {
            let mut p = [0.0; 3];
            p[axis] = c;
            p[(axis + 1) % 3] = u.0 + STEP * i as f64;
            p[(axis + 2) % 3] = v.0 + STEP * j as f64;
            vertices.push(p);
        }
    }
    let id = |i: usize, j: usize| (j * (nu + 1) + i) as u32;
    let mut triangles = Vec::new();
    for j in 0..nv {
        for i in 0..nu {
            let (a, b, cc, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            if flip {
                triangles.push([a, cc, b]);
                triangles.push([a, d, cc]);
            } else {
                triangles.push([a, b, cc]);
                triangles.push([a, cc, d]);
            }
        }
    }
    PatchIn {
        chart_of: None,
        name: name.to_string(),
        surface: surface.to_string(),
        mesh: TriMesh::new(vertices, triangles),
    }
}

/// The unit cube's six faces with outward normals, each side face split at the given heights.
pub(crate) fn cube(cuts: &[f64]) -> Vec<PatchIn> {
    let mut zs = vec![0.0];
    zs.extend_from_slice(cuts);
    zs.push(1.0);
    let mut out = vec![
        rect("bottom", "box", 2, 0.0, (0.0, 1.0), (0.0, 1.0), true),
        rect("top", "box", 2, 1.0, (0.0, 1.0), (0.0, 1.0), false),
    ];
    for k in 0..zs.len() - 1 {
        let z = (zs[k], zs[k + 1]);
        // axis 0: u = y, v = z; axis 1: u = z, v = x.
        out.push(rect(
            &format!("west{k}"),
            "box",
            0,
            0.0,
            (0.0, 1.0),
            z,
            true,
        ));
        out.push(rect(
            &format!("east{k}"),
            "box",
            0,
            1.0,
            (0.0, 1.0),
            z,
            false,
        ));
        out.push(rect(
            &format!("south{k}"),
            "box",
            1,
            0.0,
            z,
            (0.0, 1.0),
            true,
        ));
        out.push(rect(
            &format!("north{k}"),
            "box",
            1,
            1.0,
            z,
            (0.0, 1.0),
            false,
        ));
    }
    out
}

pub(crate) fn octahedron(name: &str, c: [f64; 3], r: f64) -> PatchIn {
    let v = vec![
        [c[0] + r, c[1], c[2]],
        [c[0] - r, c[1], c[2]],
        [c[0], c[1] + r, c[2]],
        [c[0], c[1] - r, c[2]],
        [c[0], c[1], c[2] + r],
        [c[0], c[1], c[2] - r],
    ];
    // Outward normals.
    let t = vec![
        [0, 2, 4],
        [2, 1, 4],
        [1, 3, 4],
        [3, 0, 4],
        [2, 0, 5],
        [1, 2, 5],
        [3, 1, 5],
        [0, 3, 5],
    ];
    PatchIn {
        chart_of: None,
        name: name.to_string(),
        surface: name.to_string(),
        mesh: TriMesh::new(v, t),
    }
}

pub(crate) fn shifted(mut patches: Vec<PatchIn>, d: [f64; 3]) -> Vec<PatchIn> {
    for p in &mut patches {
        for v in &mut p.mesh.vertices {
            for k in 0..3 {
                v[k] += d[k];
            }
        }
    }
    patches
}

fn add(p: [f64; 3], d: [f64; 3]) -> [f64; 3] {
    [p[0] + d[0], p[1] + d[1], p[2] + d[2]]
}

pub(crate) const OFFSETS: [[f64; 3]; 2] = [[0.0; 3], [5e5, 7e6, 0.0]];

fn idx(patches: &[PatchIn], name: &str) -> u32 {
    patches.iter().position(|p| p.name == name).expect("patch") as u32
}

/// The sides of a region as (patch name, side), sorted.
fn named_sides(m: &RegionModel, r: usize, patches: &[PatchIn]) -> Vec<(String, Side)> {
    let mut v: Vec<(String, Side)> = m.regions[r]
        .sides
        .iter()
        .map(|f| (patches[f.patch as usize].name.clone(), f.side))
        .collect();
    v.sort();
    v
}

#[test]
fn a_unit_cube_of_six_patches_is_one_region_bounded_by_the_inner_sides() {
    for d in OFFSETS {
        let patches = shifted(cube(&[]), d);
        let m = find_regions(&patches, &[]).expect("regions");
        assert_eq!(m.regions.len(), 1);
        assert_eq!(m.exterior.len(), 1);
        assert!(m.dangling.is_empty());
        let r = &m.regions[0];
        assert_eq!(r.sides.len(), 6);
        assert!(
            r.sides.iter().all(|f| f.side == Side::Back),
            "outward normals: the region is behind every face"
        );
        assert!(
            (r.outer.signed_volume - 1.0).abs() < 1e-6,
            "volume {}",
            r.outer.signed_volume
        );
        assert!((m.exterior[0].signed_volume + 1.0).abs() < 1e-6);
        assert!(
            m.exterior[0]
                .face_uses
                .iter()
                .all(|f| f.side == Side::Front)
        );
        assert_eq!(r.name, "box");
        assert_eq!(locate(&m, &patches, r.interior_point), Some(0));
        assert_eq!(locate(&m, &patches, add([0.5, 0.5, 0.5], d)), Some(0));
        assert_eq!(locate(&m, &patches, add([1.5, 0.5, 0.5], d)), None);
        assert_eq!(
            locate(&m, &patches, add([0.0, 0.5, 0.5], d)),
            None,
            "a point on the box is in no region"
        );
    }
}

pub(crate) fn split_cube() -> Vec<PatchIn> {
    let mut p = cube(&[0.5]);
    p.push(rect("h1#1", "h1", 2, 0.5, (0.0, 1.0), (0.0, 1.0), false));
    p
}

#[test]
fn a_cube_split_by_a_horizontal_square_has_two_regions_on_either_side_of_it() {
    for d in OFFSETS {
        let patches = shifted(split_cube(), d);
        let m = find_regions(&patches, &[]).expect("regions");
        assert_eq!(m.regions.len(), 2);
        // Canonical order: the lower region holds the smallest vertex (the origin corner).
        let lower = named_sides(&m, 0, &patches);
        let upper = named_sides(&m, 1, &patches);
        assert!(lower.contains(&("h1#1".to_string(), Side::Back)));
        assert!(upper.contains(&("h1#1".to_string(), Side::Front)));
        assert!(lower.contains(&("bottom".to_string(), Side::Back)));
        assert!(upper.contains(&("top".to_string(), Side::Back)));
        assert_eq!(lower.len(), 6);
        assert_eq!(upper.len(), 6);
        assert_eq!(m.regions[0].name, "box+h1#1");
        assert_eq!(m.regions[1].name, "box+h1#2");
        for r in &m.regions {
            assert!((r.outer.signed_volume - 0.5).abs() < 1e-6);
        }
        assert_eq!(locate(&m, &patches, add([0.3, 0.3, 0.2], d)), Some(0));
        assert_eq!(locate(&m, &patches, add([0.3, 0.3, 0.8], d)), Some(1));
        assert_eq!(
            locate(&m, &patches, add([0.3, 0.3, 0.5], d)),
            None,
            "on the horizon"
        );
    }
}

#[test]
fn recipe_names_by_point_name_the_regions_that_hold_the_points() {
    let patches = split_cube();
    let names = vec![
        ("upper".to_string(), [0.5, 0.5, 0.75]),
        ("lower".to_string(), [0.25, 0.75, 0.25]),
    ];
    let m = find_regions(&patches, &names).expect("regions");
    assert_eq!(m.regions[0].name, "lower");
    assert_eq!(m.regions[1].name, "upper");
    let outside = vec![("air".to_string(), [0.5, 0.5, 1.5])];
    let e = find_regions(&patches, &outside).expect_err("a point outside the model");
    assert!(e.message.contains("`air`"), "{}", e.message);
    assert_eq!(e.at, Some([0.5, 0.5, 1.5]));
    let twice = vec![
        ("a".to_string(), [0.5, 0.5, 0.75]),
        ("b".to_string(), [0.25, 0.25, 0.875]),
    ];
    let e = find_regions(&patches, &twice).expect_err("two names in one region");
    assert!(
        e.message.contains("`a`") && e.message.contains("`b`"),
        "{}",
        e.message
    );
}

#[test]
fn a_free_floating_fault_inside_the_cube_bounds_the_region_with_both_sides() {
    for d in OFFSETS {
        let mut patches = cube(&[]);
        patches.push(rect(
            "f1#1",
            "f1",
            0,
            0.5,
            (0.25, 0.75),
            (0.25, 0.75),
            false,
        ));
        let patches = shifted(patches, d);
        let e = find_regions(&patches, &[]).expect_err("a fault may not dangle by default");
        assert_eq!(e.surface.as_deref(), Some("f1"));
        let m =
            find_regions_with(&patches, &[], &RegionOptions::with_faults(["f1"])).expect("regions");
        assert_eq!(m.regions.len(), 1);
        let f = idx(&patches, "f1#1");
        assert_eq!(m.dangling, vec![f]);
        let sides = &m.regions[0].sides;
        assert!(sides.contains(&FaceUse {
            patch: f,
            side: Side::Front
        }));
        assert!(sides.contains(&FaceUse {
            patch: f,
            side: Side::Back
        }));
        assert_eq!(sides.len(), 8);
        assert!(m.regions[0].cavities.is_empty());
        assert_eq!(
            locate(&m, &patches, add([0.5, 0.5, 0.5], d)),
            None,
            "on the fault"
        );
        assert_eq!(locate(&m, &patches, add([0.375, 0.5, 0.5], d)), Some(0));
    }
}

#[test]
fn a_fault_hanging_from_the_top_joins_the_cube_region_with_both_sides() {
    for d in OFFSETS {
        let mut patches = cube(&[]);
        patches.push(rect("f2#1", "f2", 0, 0.5, (0.25, 0.75), (0.5, 1.0), true));
        let patches = shifted(patches, d);
        let m =
            find_regions_with(&patches, &[], &RegionOptions::with_faults(["f2"])).expect("regions");
        assert_eq!(m.regions.len(), 1);
        let f = idx(&patches, "f2#1");
        assert_eq!(m.dangling, vec![f]);
        assert!(m.regions[0].outer.face_uses.contains(&FaceUse {
            patch: f,
            side: Side::Front
        }));
        assert!(m.regions[0].outer.face_uses.contains(&FaceUse {
            patch: f,
            side: Side::Back
        }));
        assert!((m.regions[0].outer.signed_volume - 1.0).abs() < 1e-6);
    }
}

#[test]
fn a_lens_inside_the_cube_is_a_region_and_a_cavity_of_the_cube_region() {
    for d in OFFSETS {
        let mut patches = cube(&[]);
        patches.push(octahedron("lens", [0.5, 0.5, 0.5], 0.25));
        let patches = shifted(patches, d);
        let m = find_regions(&patches, &[]).expect("regions");
        assert_eq!(m.regions.len(), 2);
        assert_eq!(m.exterior.len(), 1, "the lens is not outside the model");
        let lens = idx(&patches, "lens");
        let host = m
            .regions
            .iter()
            .position(|r| r.cavities.len() == 1)
            .expect("a host");
        let inner = 1 - host;
        assert_eq!(
            m.regions[host].cavities[0].face_uses,
            vec![FaceUse {
                patch: lens,
                side: Side::Front
            }]
        );
        assert!(m.regions[host].sides.contains(&FaceUse {
            patch: lens,
            side: Side::Front
        }));
        assert_eq!(
            m.regions[inner].sides,
            vec![FaceUse {
                patch: lens,
                side: Side::Back
            }]
        );
        assert_eq!(m.regions[inner].name, "lens");
        assert_eq!(m.regions[host].name, "box");
        assert_eq!(locate(&m, &patches, add([0.5, 0.5, 0.5], d)), Some(inner));
        assert_eq!(locate(&m, &patches, add([0.1, 0.1, 0.1], d)), Some(host));
        assert_eq!(
            locate(&m, &patches, m.regions[host].interior_point),
            Some(host)
        );
        assert_eq!(
            locate(&m, &patches, m.regions[inner].interior_point),
            Some(inner)
        );
    }
}

#[test]
fn a_horizon_that_stops_short_is_reported_by_name_with_the_ends_of_the_gap() {
    for d in OFFSETS {
        let mut patches = cube(&[]);
        // Reaches the west, south and north faces, stops at x = 0.5 before the east face.
        // The west face is one patch crossed along its interior edge z = 0.5.
        patches.push(rect("h2#1", "h2", 2, 0.5, (0.0, 0.5), (0.0, 1.0), false));
        let patches = shifted(patches, d);
        let e = find_regions(&patches, &[]).expect_err("stops short");
        assert_eq!(e.surface.as_deref(), Some("h2"));
        let a = add([0.5, 0.0, 0.5], d);
        let b = add([0.5, 1.0, 0.5], d);
        assert!(
            e.message.contains("surface `h2` stops short"),
            "{}",
            e.message
        );
        assert!(
            e.message.contains(&format!(
                "from ({}, {}, {}) to ({}, {}, {})",
                a[0], a[1], a[2], b[0], b[1], b[2]
            )),
            "{}",
            e.message
        );
        assert_eq!(e.at, Some(a));
        // Allowed to dangle, it is one region holding both sides of the horizon.
        let opts = RegionOptions {
            dangling: Dangling::Allowed,
        };
        let m = find_regions_with(&patches, &[], &opts).expect("regions");
        assert_eq!(m.regions.len(), 1);
        assert_eq!(m.dangling, vec![idx(&patches, "h2#1")]);
    }
}

#[test]
fn six_separate_squares_with_gaps_are_reported_as_an_open_box() {
    let mut patches = cube(&[]);
    // Shrink the top face so that it no longer meets the sides.
    patches[1] = rect("top", "box", 2, 1.0, (0.25, 0.75), (0.25, 0.75), false);
    let e = find_regions(&patches, &[]).expect_err("not sealed");
    assert_eq!(e.surface.as_deref(), Some("box"));
    assert!(e.message.contains("stops short"), "{}", e.message);
}

#[test]
fn overlapping_patches_are_reported_with_the_shared_edge() {
    let mut patches = split_cube();
    // A second horizon in the same place overlaps the first one.
    patches.push(rect("h9#1", "h9", 2, 0.5, (0.0, 1.0), (0.0, 1.0), true));
    let e = find_regions(&patches, &[]).expect_err("overlap");
    assert!(e.message.contains("overlap"), "{}", e.message);
    assert!(e.at.is_some());
}

#[test]
fn a_side_face_crossed_by_the_horizon_without_a_curve_is_reported() {
    let mut patches = cube(&[]);
    patches.push(rect("h1#1", "h1", 2, 0.5, (0.0, 1.0), (0.0, 1.0), false));
    let e = find_regions(&patches, &[]).expect_err("side faces are not split at the horizon");
    assert_eq!(e.surface.as_deref(), Some("box"));
    assert!(
        e.message.contains("crosses it without a shared curve"),
        "{}",
        e.message
    );
}

#[test]
fn bad_patches_are_errors_naming_the_patch() {
    let mut patches = cube(&[]);
    patches[0].mesh.triangles[0][1] = 999;
    let e = find_regions(&patches, &[]).expect_err("index out of range");
    assert!(
        e.message.contains("`bottom`") && e.message.contains("999"),
        "{}",
        e.message
    );
    let mut patches = cube(&[]);
    patches[2].mesh.vertices[0][0] = f64::NAN;
    assert!(
        find_regions(&patches, &[])
            .expect_err("nan")
            .message
            .contains("non-finite")
    );
    let mut patches = cube(&[]);
    patches[3].mesh.triangles[0] = [0, 1, 2]; // three points on one grid line
    assert!(
        find_regions(&patches, &[])
            .expect_err("zero area")
            .message
            .contains("zero area")
    );
    let mut patches = cube(&[]);
    patches[3].name = "bottom".into();
    assert!(
        find_regions(&patches, &[])
            .expect_err("dup")
            .message
            .contains("both named")
    );
}

/// (name, sorted (patch name, side) sides, interior point) of every region, and exterior shells.
type Summary = (
    Vec<(String, Vec<(String, Side)>, [f64; 3])>,
    Vec<Vec<(String, Side)>>,
    Vec<String>,
);

fn summary(m: &RegionModel, patches: &[PatchIn]) -> Summary {
    let conv = |fus: &[FaceUse]| {
        let mut v: Vec<(String, Side)> = fus
            .iter()
            .map(|f| (patches[f.patch as usize].name.clone(), f.side))
            .collect();
        v.sort();
        v
    };
    let regions = m
        .regions
        .iter()
        .map(|r| (r.name.clone(), conv(&r.sides), r.interior_point))
        .collect();
    let ext = m.exterior.iter().map(|s| conv(&s.face_uses)).collect();
    let mut dangling: Vec<String> = m
        .dangling
        .iter()
        .map(|&p| patches[p as usize].name.clone())
        .collect();
    dangling.sort();
    (regions, ext, dangling)
}

#[test]
fn shuffling_the_patch_order_gives_the_same_regions_names_and_order() {
    let mut patches = cube(&[0.5]);
    patches.push(rect("h1#1", "h1", 2, 0.5, (0.0, 1.0), (0.0, 1.0), false));
    patches.push(octahedron("lens", [0.5, 0.5, 0.25], 0.125));
    patches.push(rect("f2#1", "f2", 0, 0.5, (0.25, 0.75), (0.5, 1.0), true));
    let opts = RegionOptions::with_faults(["f2"]);
    let base = find_regions_with(&patches, &[], &opts).expect("regions");
    assert_eq!(base.regions.len(), 3);
    let want = summary(&base, &patches);
    let n = patches.len();
    for seed in [1usize, 5, 7, 11] {
        let order: Vec<usize> = (0..n).map(|i| (i * seed + 3) % n).collect();
        let mut sorted = order.clone();
        sorted.sort_unstable();
        sorted.dedup();
        if sorted.len() != n {
            continue;
        }
        let shuffled: Vec<PatchIn> = order.iter().map(|&i| patches[i].clone()).collect();
        let m = find_regions_with(&shuffled, &[], &opts).expect("regions");
        assert_eq!(summary(&m, &shuffled), want, "order {order:?}");
    }
    let mut reversed = patches.clone();
    reversed.reverse();
    let m = find_regions_with(&reversed, &[], &opts).expect("regions");
    assert_eq!(summary(&m, &reversed), want);
}

#[test]
fn a_fault_sticking_out_of_the_box_is_reported_even_when_faults_may_dangle() {
    let mut patches = cube(&[]);
    // Crosses the top face along x = 0.5 without being cut there: it is only welded to the top
    // face's grid edge and continues above it.
    patches.push(rect("f3#1", "f3", 0, 0.5, (0.25, 0.75), (1.0, 1.5), false));
    let e = find_regions_with(&patches, &[], &RegionOptions::with_faults(["f3"]))
        .expect_err("sticks out");
    assert_eq!(e.surface.as_deref(), Some("f3"));
    assert!(
        e.message.contains("sticks out of the model"),
        "{}",
        e.message
    );
}

/// Ranges between consecutive cuts of [0, 1].
fn spans(cuts: &[f64]) -> Vec<(f64, f64)> {
    let mut v = vec![0.0];
    v.extend_from_slice(cuts);
    v.push(1.0);
    v.windows(2).map(|w| (w[0], w[1])).collect()
}

/// The unit cube's faces with outward normals, split along z = zcuts and x = xcuts.
fn cube_xz(zcuts: &[f64], xcuts: &[f64]) -> Vec<PatchIn> {
    let mut out = Vec::new();
    for (i, x) in spans(xcuts).into_iter().enumerate() {
        out.push(rect(
            &format!("bottom{i}"),
            "box",
            2,
            0.0,
            x,
            (0.0, 1.0),
            true,
        ));
        out.push(rect(
            &format!("top{i}"),
            "box",
            2,
            1.0,
            x,
            (0.0, 1.0),
            false,
        ));
        for (k, z) in spans(zcuts).into_iter().enumerate() {
            out.push(rect(&format!("south{k}.{i}"), "box", 1, 0.0, z, x, true));
            out.push(rect(&format!("north{k}.{i}"), "box", 1, 1.0, z, x, false));
        }
    }
    for (k, z) in spans(zcuts).into_iter().enumerate() {
        out.push(rect(
            &format!("west{k}"),
            "box",
            0,
            0.0,
            (0.0, 1.0),
            z,
            true,
        ));
        out.push(rect(
            &format!("east{k}"),
            "box",
            0,
            1.0,
            (0.0, 1.0),
            z,
            false,
        ));
    }
    out
}

#[test]
fn a_horizon_crossed_by_a_through_going_fault_makes_four_regions_around_their_shared_curve() {
    for d in OFFSETS {
        let mut patches = cube_xz(&[0.5], &[0.5]);
        patches.push(rect("h#1", "h", 2, 0.5, (0.0, 0.5), (0.0, 1.0), false));
        patches.push(rect("h#2", "h", 2, 0.5, (0.5, 1.0), (0.0, 1.0), true));
        patches.push(rect("f#1", "f", 0, 0.5, (0.0, 1.0), (0.0, 0.5), false));
        patches.push(rect("f#2", "f", 0, 0.5, (0.0, 1.0), (0.5, 1.0), true));
        let patches = shifted(patches, d);
        let m = find_regions(&patches, &[]).expect("regions");
        assert_eq!(m.regions.len(), 4);
        for (p, want) in [
            ([0.25, 0.5, 0.25], "f#1"),
            ([0.75, 0.5, 0.25], "f#1"),
            ([0.25, 0.5, 0.75], "f#2"),
        ] {
            let r = locate(&m, &patches, add(p, d)).expect("inside");
            let sides = named_sides(&m, r, &patches);
            assert_eq!(
                sides.iter().filter(|s| s.0.starts_with("h#")).count(),
                1,
                "{sides:?}"
            );
            assert_eq!(sides.iter().filter(|s| s.0 == want).count(), 1, "{sides:?}");
            assert!((m.regions[r].outer.signed_volume - 0.25).abs() < 1e-9);
        }
        // The lower-west quarter is behind h#1's front (h#1 normal +z points up, away from it)
        // and on f#1's back (normal +x).
        let r = locate(&m, &patches, add([0.25, 0.5, 0.25], d)).expect("inside");
        let sides = named_sides(&m, r, &patches);
        assert!(
            sides.contains(&("h#1".to_string(), Side::Back)),
            "{sides:?}"
        );
        assert!(
            sides.contains(&("f#1".to_string(), Side::Back)),
            "{sides:?}"
        );
        let distinct: std::collections::BTreeSet<String> =
            m.regions.iter().map(|r| r.name.clone()).collect();
        assert_eq!(distinct.len(), 4, "generated names are unique");
    }
}

#[test]
fn a_fault_ending_on_a_horizon_makes_three_regions_around_a_t_junction() {
    for d in OFFSETS {
        let mut patches = cube_xz(&[0.5], &[0.5]);
        // The lower south/north/bottom faces are not split by the fault: merge them back.
        patches.retain(|p| {
            !matches!(
                p.name.as_str(),
                "bottom0" | "bottom1" | "south0.0" | "south0.1" | "north0.0" | "north0.1"
            )
        });
        patches.push(rect("bottom", "box", 2, 0.0, (0.0, 1.0), (0.0, 1.0), true));
        patches.push(rect("south0", "box", 1, 0.0, (0.0, 0.5), (0.0, 1.0), true));
        patches.push(rect("north0", "box", 1, 1.0, (0.0, 0.5), (0.0, 1.0), false));
        patches.push(rect("h#1", "h", 2, 0.5, (0.0, 0.5), (0.0, 1.0), false));
        patches.push(rect("h#2", "h", 2, 0.5, (0.5, 1.0), (0.0, 1.0), false));
        patches.push(rect("f#1", "f", 0, 0.5, (0.0, 1.0), (0.5, 1.0), false));
        let patches = shifted(patches, d);
        let m = find_regions(&patches, &[]).expect("regions");
        assert_eq!(m.regions.len(), 3);
        let lower = locate(&m, &patches, add([0.5, 0.5, 0.25], d)).expect("lower");
        assert!((m.regions[lower].outer.signed_volume - 0.5).abs() < 1e-9);
        let sides = named_sides(&m, lower, &patches);
        assert!(
            sides.contains(&("h#1".to_string(), Side::Back))
                && sides.contains(&("h#2".to_string(), Side::Back))
        );
        assert!(!sides.iter().any(|s| s.0 == "f#1"));
        let west = locate(&m, &patches, add([0.25, 0.5, 0.75], d)).expect("upper west");
        let east = locate(&m, &patches, add([0.75, 0.5, 0.75], d)).expect("upper east");
        assert_ne!(west, east);
        assert!(named_sides(&m, west, &patches).contains(&("f#1".to_string(), Side::Back)));
        assert!(named_sides(&m, east, &patches).contains(&("f#1".to_string(), Side::Front)));
    }
}

/// The triangles of `p` whose centroid satisfies `keep`, as a new patch named `name`.
fn filtered(p: &PatchIn, name: &str, keep: impl Fn([f64; 3]) -> bool) -> PatchIn {
    let m = &p.mesh;
    let triangles = m
        .triangles
        .iter()
        .copied()
        .filter(|t| {
            let c = t.map(|v| m.vertices[v as usize]);
            keep([0, 1, 2].map(|k| (c[0][k] + c[1][k] + c[2][k]) / 3.0))
        })
        .collect();
    PatchIn {
        chart_of: None,
        name: name.to_string(),
        surface: p.surface.clone(),
        mesh: TriMesh::new(m.vertices.clone(), triangles),
    }
}

#[test]
fn two_faults_in_one_half_turn_around_a_curve_are_ordered_exactly() {
    // Around the curve x = z = 0.5: horizon east (0°), slanted fault z = x (45°), vertical fault
    // (90°), horizon west (180°). Two half-planes always share a half turn, whatever the first.
    for d in OFFSETS {
        let mut patches = cube_xz(&[0.5], &[0.5]);
        let lower = [
            "bottom0", "bottom1", "south0.0", "south0.1", "north0.0", "north0.1",
        ];
        patches.retain(|p| {
            !lower.contains(&p.name.as_str()) && p.name != "south1.1" && p.name != "north1.1"
        });
        patches.push(rect("bottom", "box", 2, 0.0, (0.0, 1.0), (0.0, 1.0), true));
        patches.push(rect("south0", "box", 1, 0.0, (0.0, 0.5), (0.0, 1.0), true));
        patches.push(rect("north0", "box", 1, 1.0, (0.0, 0.5), (0.0, 1.0), false));
        let s = rect("s", "box", 1, 0.0, (0.5, 1.0), (0.5, 1.0), true);
        let n = rect("n", "box", 1, 1.0, (0.5, 1.0), (0.5, 1.0), false);
        patches.push(filtered(&s, "south1.1.up", |c| c[2] > c[0]));
        patches.push(filtered(&s, "south1.1.down", |c| c[2] < c[0]));
        patches.push(filtered(&n, "north1.1.up", |c| c[2] > c[0]));
        patches.push(filtered(&n, "north1.1.down", |c| c[2] < c[0]));
        patches.push(rect("h#1", "h", 2, 0.5, (0.0, 0.5), (0.0, 1.0), false));
        patches.push(rect("h#2", "h", 2, 0.5, (0.5, 1.0), (0.0, 1.0), false));
        patches.push(rect("f#1", "f", 0, 0.5, (0.0, 1.0), (0.5, 1.0), false));
        // The slanted fault: (0.5 + s, y, 0.5 + s), s in [0, 0.5], y in [0, 1].
        let mut g = rect("g#1", "g", 2, 0.0, (0.0, 0.5), (0.0, 1.0), false);
        for v in &mut g.mesh.vertices {
            *v = [0.5 + v[0], v[1], 0.5 + v[0]];
        }
        patches.push(g);
        let patches = shifted(patches, d);
        for first in [0usize, 1, 2, 3] {
            // Rotate which triangle comes first at the curve by rotating the patch order.
            let mut order = patches.clone();
            order.rotate_left(first * 3);
            let m = find_regions(&order, &[]).expect("regions");
            assert_eq!(m.regions.len(), 4);
            let wedge =
                locate(&m, &order, add([0.875, 0.5, 0.625], d)).expect("below the slanted fault");
            let between =
                locate(&m, &order, add([0.625, 0.5, 0.875], d)).expect("between the faults");
            let west = locate(&m, &order, add([0.25, 0.5, 0.75], d)).expect("west of both");
            let sides = |r: usize| named_sides(&m, r, &order);
            assert!(
                sides(wedge).contains(&("h#2".to_string(), Side::Front)),
                "{:?}",
                sides(wedge)
            );
            assert!(
                sides(wedge).iter().any(|s| s.0 == "g#1")
                    && !sides(wedge).iter().any(|s| s.0 == "f#1")
            );
            assert!(
                sides(between).iter().any(|s| s.0 == "g#1")
                    && sides(between).iter().any(|s| s.0 == "f#1")
            );
            assert!(
                !sides(between).iter().any(|s| s.0.starts_with("h#")),
                "{:?}",
                sides(between)
            );
            assert!(sides(west).contains(&("f#1".to_string(), Side::Back)));
            assert!((m.regions[wedge].outer.signed_volume - 0.125).abs() < 1e-9);
            assert!((m.regions[between].outer.signed_volume - 0.125).abs() < 1e-9);
        }
    }
}

#[test]
fn a_patch_with_one_flipped_triangle_is_reported_as_not_consistently_oriented() {
    let mut patches = cube(&[]);
    patches[0].mesh.triangles[5].swap(1, 2);
    let e = find_regions(&patches, &[]).expect_err("flipped triangle");
    assert_eq!(e.surface.as_deref(), Some("box"));
    assert!(
        e.message.contains("`bottom`") && e.message.contains("not consistently oriented"),
        "{}",
        e.message
    );
    let at = e.at.expect("a location");
    assert_eq!(at[2], 0.0, "on the bottom face");
}

#[test]
fn a_lens_inside_a_lens_is_attached_to_the_innermost_region_that_holds_it() {
    for d in OFFSETS {
        let mut patches = cube(&[]);
        patches.push(octahedron("big", [0.5, 0.5, 0.5], 0.375));
        patches.push(octahedron("small", [0.5, 0.5, 0.5], 0.125));
        let patches = shifted(patches, d);
        let m = find_regions(&patches, &[]).expect("regions");
        assert_eq!(m.regions.len(), 3);
        let by_name = |n: &str| m.regions.iter().position(|r| r.name == n).expect(n);
        let (outer, big, small) = (by_name("box"), by_name("big"), by_name("small"));
        let (ib, is) = (idx(&patches, "big"), idx(&patches, "small"));
        assert_eq!(m.regions[outer].cavities.len(), 1);
        assert_eq!(
            m.regions[outer].cavities[0].face_uses,
            vec![FaceUse {
                patch: ib,
                side: Side::Front
            }]
        );
        assert_eq!(m.regions[big].cavities.len(), 1);
        assert_eq!(
            m.regions[big].cavities[0].face_uses,
            vec![FaceUse {
                patch: is,
                side: Side::Front
            }]
        );
        assert!(m.regions[small].cavities.is_empty());
        assert_eq!(locate(&m, &patches, add([0.5, 0.5, 0.5], d)), Some(small));
        assert_eq!(locate(&m, &patches, add([0.5, 0.5, 0.75], d)), Some(big));
        assert_eq!(locate(&m, &patches, add([0.5, 0.5, 0.95], d)), Some(outer));
    }
}
