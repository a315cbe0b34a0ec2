//! Wells cut by hand-built models: a cube split by a horizon, a dangling fault, a lens — each at
//! UTM offsets too — with crossings through support faces, edges, vertices and stations, the
//! pieces' regions, paths lying on a surface (runs), and the refusals (a path along a surface onto
//! its border, a crossing on a curve).

use super::regions_cases::{OFFSETS, cube, octahedron, rect, shifted, split_cube};
use model::regions::{Locator, PatchIn, RegionOptions, find_regions_with, locate};
use model::wells::{CurveIndex, WellCut, WellError, cut_well, resample};

fn add(p: [f64; 3], d: [f64; 3]) -> [f64; 3] {
    [p[0] + d[0], p[1] + d[1], p[2] + d[2]]
}

fn cut(patches: &[PatchIn], faults: &[&str], path: &[[f64; 3]]) -> Result<WellCut, WellError> {
    let m = find_regions_with(
        patches,
        &[],
        &RegionOptions::with_faults(faults.iter().copied()),
    )
    .expect("regions");
    cut_well(path, patches, &borders(patches), &Locator::new(&m, patches))
}

/// The patches' border edges, each a curve of its own (the models here have no topology).
fn borders(patches: &[PatchIn]) -> CurveIndex {
    let mut curves = Vec::new();
    for p in patches {
        let v = &p.mesh.vertices;
        curves.extend(
            (p.mesh.border_edges().into_iter()).map(|(a, b)| vec![v[a as usize], v[b as usize]]),
        );
    }
    CurveIndex::new(curves)
}

fn region_at(patches: &[PatchIn], faults: &[&str], p: [f64; 3]) -> u32 {
    let m = find_regions_with(
        patches,
        &[],
        &RegionOptions::with_faults(faults.iter().copied()),
    )
    .expect("regions");
    locate(&m, patches, p).expect("a region holds the point") as u32
}

fn surfaces(c: &WellCut, patches: &[PatchIn]) -> Vec<String> {
    c.crossings
        .iter()
        .map(|x| patches[x.patch as usize].name.clone())
        .collect()
}

/// Every piece starts and ends on the crossing or path end next to it, bit for bit.
fn assert_pieces_join(c: &WellCut) {
    for w in c.pieces.windows(2) {
        let (a, b) = (&w[0].points, &w[1].points);
        assert_eq!(
            a.last(),
            b.first(),
            "consecutive pieces share their crossing"
        );
        assert!(
            c.crossings.iter().any(|x| Some(&x.point) == a.last()),
            "a piece ends at a crossing"
        );
    }
}

#[test]
fn a_vertical_well_through_a_split_cube_crosses_top_horizon_and_bottom_with_one_piece_per_region() {
    for d in OFFSETS {
        let patches = shifted(split_cube(), d);
        let path = [add([0.3, 0.4, 1.5], d), add([0.3, 0.4, -0.5], d)];
        let c = cut(&patches, &[], &path).expect("cut");
        assert_eq!(surfaces(&c, &patches), ["top", "h1#1", "bottom"]);
        let z: Vec<f64> = c.crossings.iter().map(|x| x.point[2]).collect();
        assert_eq!(z, [1.0 + d[2], 0.5 + d[2], d[2]]);
        assert!(c.crossings.windows(2).all(|w| w[0].along < w[1].along));
        assert_eq!(
            c.pieces.len(),
            2,
            "the pieces above and below the box are left out"
        );
        assert_eq!(
            c.pieces[0].points,
            [c.crossings[0].point, c.crossings[1].point]
        );
        assert_eq!(
            c.pieces[1].points,
            [c.crossings[1].point, c.crossings[2].point]
        );
        assert_eq!(
            c.pieces[0].region,
            region_at(&patches, &[], add([0.3, 0.4, 0.75], d))
        );
        assert_eq!(
            c.pieces[1].region,
            region_at(&patches, &[], add([0.3, 0.4, 0.25], d))
        );
        assert_ne!(c.pieces[0].region, c.pieces[1].region);
    }
}

#[test]
fn a_well_through_a_support_vertex_and_one_along_a_support_edge_cross_each_patch_once() {
    let patches = split_cube();
    // (0.5, 0.5) is a grid vertex of every horizontal rectangle; (0.5, 0.3) lies on a grid edge.
    for xy in [[0.5, 0.5], [0.5, 0.3], [0.3, 0.5]] {
        let path = [[xy[0], xy[1], 1.5], [xy[0], xy[1], -0.5]];
        let c = cut(&patches, &[], &path).expect("cut");
        assert_eq!(
            surfaces(&c, &patches),
            ["top", "h1#1", "bottom"],
            "at {xy:?}"
        );
        assert_eq!(c.crossings[1].point, [xy[0], xy[1], 0.5]);
        assert_pieces_join(&c);
    }
}

#[test]
fn a_well_ending_inside_a_region_ends_its_last_piece_at_its_last_station() {
    let patches = split_cube();
    let path = [[0.3, 0.4, 1.5], [0.35, 0.4, 0.7], [0.4, 0.45, 0.2]];
    let c = cut(&patches, &[], &path).expect("cut");
    assert_eq!(surfaces(&c, &patches), ["top", "h1#1"]);
    assert_eq!(c.pieces.len(), 2);
    assert_eq!(
        c.pieces[0].points.len(),
        3,
        "top crossing, a station, the horizon crossing"
    );
    assert_eq!(c.pieces[0].points[1], path[1]);
    assert_eq!(c.pieces[1].points.last(), Some(&path[2]));
    assert_pieces_join(&c);
}

#[test]
fn a_station_on_a_horizon_is_the_crossing_itself() {
    let patches = split_cube();
    let path = [[0.3, 0.4, 0.9], [0.35, 0.4, 0.5], [0.4, 0.4, 0.1]];
    let c = cut(&patches, &[], &path).expect("cut");
    assert_eq!(surfaces(&c, &patches), ["h1#1"]);
    assert_eq!(c.crossings[0].point, path[1]);
    assert_eq!(c.pieces.len(), 2);
    assert_eq!(c.pieces[0].points, path[..2]);
    assert_eq!(c.pieces[1].points, path[1..]);
}

#[test]
fn a_well_that_goes_down_through_a_horizon_and_back_up_has_three_pieces() {
    let patches = split_cube();
    let path = [
        [0.2, 0.3, 0.9],
        [0.3, 0.3, 0.3],
        [0.6, 0.35, 0.2],
        [0.7, 0.4, 0.8],
    ];
    let c = cut(&patches, &[], &path).expect("cut");
    assert_eq!(surfaces(&c, &patches), ["h1#1", "h1#1"]);
    let regions: Vec<u32> = c.pieces.iter().map(|p| p.region).collect();
    let (up, down) = (
        region_at(&patches, &[], [0.5, 0.5, 0.75]),
        region_at(&patches, &[], [0.5, 0.5, 0.25]),
    );
    assert_eq!(regions, [up, down, up]);
    assert_eq!(
        c.pieces[1].points.len(),
        4,
        "crossing, two stations, crossing"
    );
    assert_pieces_join(&c);
}

#[test]
fn a_well_through_a_dangling_fault_has_both_pieces_in_the_one_region() {
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
        let path = [add([-0.5, 0.4, 0.6], d), add([1.5, 0.4, 0.6], d)];
        let c = cut(&patches, &["f1"], &path).expect("cut");
        let names = surfaces(&c, &patches);
        assert_eq!(names[1], "f1#1");
        assert_eq!(names.len(), 3);
        assert_eq!(c.pieces.len(), 2);
        assert_eq!(c.pieces[0].region, c.pieces[1].region);
        assert_pieces_join(&c);
    }
}

#[test]
fn a_well_through_a_lens_has_a_piece_in_the_lens_between_two_in_its_host() {
    let mut patches = cube(&[]);
    patches.push(octahedron("lens", [0.5, 0.5, 0.5], 0.3));
    let path = [[0.45, 0.52, 1.5], [0.45, 0.52, -0.5]];
    let c = cut(&patches, &[], &path).expect("cut");
    assert_eq!(surfaces(&c, &patches), ["top", "lens", "lens", "bottom"]);
    let regions: Vec<u32> = c.pieces.iter().map(|p| p.region).collect();
    let host = region_at(&patches, &[], [0.1, 0.1, 0.1]);
    let lens = region_at(&patches, &[], [0.5, 0.5, 0.5]);
    assert_eq!(regions, [host, lens, host]);
}

#[test]
fn a_reversed_path_crosses_the_same_patches_in_reverse_order() {
    let patches = split_cube();
    let path = vec![[0.21, 0.33, 1.4], [0.52, 0.46, 0.6], [0.77, 0.61, -0.3]];
    let forward = cut(&patches, &[], &path).expect("forward");
    let mut back_path = path.clone();
    back_path.reverse();
    let back = cut(&patches, &[], &back_path).expect("back");
    let mut f = surfaces(&forward, &patches);
    f.reverse();
    assert_eq!(f, surfaces(&back, &patches));
    for (a, b) in forward.crossings.iter().zip(back.crossings.iter().rev()) {
        let gap = (0..3)
            .map(|k| (a.point[k] - b.point[k]).abs())
            .fold(0.0, f64::max);
        assert!(gap < 1e-12, "{:?} against {:?}", a.point, b.point);
    }
    let regions = |c: &WellCut| c.pieces.iter().map(|p| p.region).collect::<Vec<_>>();
    let mut r = regions(&forward);
    r.reverse();
    assert_eq!(r, regions(&back));
}

#[test]
fn a_well_landing_on_a_horizon_running_along_it_and_leaving_has_a_run_between_two_pieces() {
    for d in OFFSETS {
        let patches = shifted(split_cube(), d);
        // Along y = 0.4 it crosses the support's grid and diagonal edges; along x = y it runs
        // on support edges and through support vertices.
        for (a, b) in [([0.3, 0.4], [0.7, 0.4]), ([0.25, 0.25], [0.75, 0.75])] {
            let path = [
                add([a[0], a[1], 0.9], d),
                add([a[0], a[1], 0.5], d),
                add([b[0], b[1], 0.5], d),
                add([b[0], b[1], 0.1], d),
            ];
            let c = cut(&patches, &[], &path).expect("cut");
            assert_eq!(surfaces(&c, &patches), ["h1#1", "h1#1"], "{path:?}");
            assert_eq!(c.crossings[0].point, path[1]);
            assert_eq!(c.crossings[1].point, path[2]);
            assert_eq!(c.runs.len(), 1);
            assert_eq!(c.runs[0].points, [path[1], path[2]]);
            assert_eq!(patches[c.runs[0].patch as usize].name, "h1#1");
            assert_eq!(c.pieces.len(), 2);
            assert_eq!(c.pieces[0].points, [path[0], path[1]]);
            assert_eq!(c.pieces[1].points, [path[2], path[3]]);
            assert_ne!(c.pieces[0].region, c.pieces[1].region);
        }
    }
}

#[test]
fn a_well_ending_on_a_horizon_after_running_along_it_ends_its_run_at_its_last_station() {
    let patches = split_cube();
    let path = [
        [0.3, 0.4, 0.9],
        [0.3, 0.4, 0.5],
        [0.5, 0.4, 0.5],
        [0.7, 0.6, 0.5],
    ];
    let c = cut(&patches, &[], &path).expect("cut");
    assert_eq!(surfaces(&c, &patches), ["h1#1"]);
    assert_eq!(c.runs.len(), 1);
    assert_eq!(c.runs[0].points, path[1..]);
    assert_eq!(c.pieces.len(), 1);
}

#[test]
fn a_well_running_along_a_horizon_onto_a_box_side_is_refused_as_meeting_a_curve() {
    let patches = split_cube();
    let path = [[0.3, 0.4, 0.9], [0.3, 0.4, 0.5], [1.5, 0.4, 0.5]];
    let e = cut(&patches, &[], &path).expect_err("along h1 onto the east side");
    assert!(e.message.contains("runs along surface `h1`"), "{e}");
    assert!(e.message.contains("border"), "{e}");
    assert_eq!(e.segment, Some(1));
}

#[test]
fn a_vertical_well_running_down_a_box_side_lies_on_it_and_crosses_nothing_inside() {
    let patches = split_cube();
    // Down the west side from the top edge's middle to the bottom: on `west1`, then the curve
    // where h1 meets the side.
    let path = [[0.0, 0.4, 0.9], [0.0, 0.4, 0.7]];
    let c = cut(&patches, &[], &path).expect("cut");
    assert!(c.crossings.is_empty() && c.pieces.is_empty());
    assert_eq!(c.runs.len(), 1);
    assert_eq!(patches[c.runs[0].patch as usize].name, "west1");
    let e = cut(&patches, &[], &[[0.0, 0.4, 0.9], [0.0, 0.4, 0.1]]).expect_err("onto h1's curve");
    assert!(e.message.contains("border"), "{e}");
}

#[test]
fn a_well_crossing_where_a_horizon_meets_a_box_side_crosses_every_patch_there_at_one_curve_point() {
    for d in OFFSETS {
        let patches = shifted(split_cube(), d);
        let path = [add([-0.1, 0.4, 0.6], d), add([0.1, 0.4, 0.4], d)];
        let c = cut(&patches, &[], &path).expect("through the curve h1/west");
        let mut names = surfaces(&c, &patches);
        names.sort();
        assert_eq!(names, ["h1#1", "west0", "west1"]);
        let at = c.crossings[0].point;
        assert!(
            c.crossings
                .iter()
                .all(|x| x.point == at && x.curve.is_some())
        );
        assert_eq!(
            (at[0], (at[1] - 0.4 - d[1]).abs() < 1e-9, at[2]),
            (d[0], true, 0.5)
        );
        // The part outside the box is left out; the rest is in the lower layer.
        assert_eq!(c.pieces.len(), 1);
        assert_eq!(c.pieces[0].points, [at, path[1]]);
        assert_eq!(c.pieces[0].region, region_at(&patches, &[], path[1]));
    }
}

#[test]
fn a_crossing_on_a_border_that_is_no_curve_is_refused_as_on_a_border() {
    let patches = split_cube();
    let path = [[-0.1, 0.4, 0.6], [0.1, 0.4, 0.4]];
    let m = find_regions_with(
        &patches,
        &[],
        &RegionOptions::with_faults::<[&str; 0], &str>([]),
    )
    .expect("regions");
    let e = cut_well(
        &path,
        &patches,
        &CurveIndex::default(),
        &Locator::new(&m, &patches),
    )
    .expect_err("no curves given");
    assert!(e.message.contains("border of its patch"), "{e}");
}

#[test]
fn a_path_with_a_repeated_station_is_refused() {
    let patches = split_cube();
    let path = [[0.3, 0.4, 0.9], [0.3, 0.4, 0.9], [0.3, 0.4, 0.1]];
    let e = cut(&patches, &[], &path).expect_err("repeated station");
    assert_eq!(e.segment, Some(0));
}

#[test]
fn a_well_outside_the_model_has_no_crossing_and_no_piece() {
    let patches = split_cube();
    let c = cut(&patches, &[], &[[2.0, 2.0, 2.0], [3.0, 2.0, -1.0]]).expect("cut");
    assert!(c.crossings.is_empty() && c.pieces.is_empty());
}

#[test]
fn resampling_keeps_both_ends_bit_for_bit_and_evens_the_segments() {
    let points = [
        [0.1, 0.2, 0.3],
        [0.1, 0.2, 0.31],
        [0.4, 0.2, 0.31],
        [0.4, 0.9, 1.7],
    ];
    let r = resample(&points, 0.2);
    assert_eq!(r.first(), points.first());
    assert_eq!(r.last(), points.last());
    let lengths: Vec<f64> = points
        .windows(2)
        .map(|w| {
            (0..3)
                .map(|k| (w[1][k] - w[0][k]).powi(2))
                .sum::<f64>()
                .sqrt()
        })
        .collect();
    let total: f64 = lengths.iter().sum();
    assert_eq!(r.len() - 1, (total / 0.2).round() as usize);
    assert_eq!(
        resample(&points[..2], 0.2).len(),
        2,
        "a short piece is one segment"
    );
}

#[test]
fn an_oblique_well_crosses_a_flat_horizon_at_its_height_exactly() {
    for d in OFFSETS {
        let patches = shifted(split_cube(), d);
        let path = [add([0.13, 0.27, 0.93], d), add([0.71, 0.58, 0.11], d)];
        let c = cut(&patches, &[], &path).expect("cut");
        assert_eq!(surfaces(&c, &patches), ["h1#1"]);
        assert_eq!(c.crossings[0].point[2], 0.5 + d[2]);
    }
}
