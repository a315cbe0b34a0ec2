use super::*;

/// How triangles `t` and `u` (ids into `pts`) meet, checked to be the same with the two swapped.
fn both_ways(pts: &[P], t: [u32; 3], u: [u32; 3]) -> Contact {
    let (a, b) = (Tri::of(t, pts), Tri::of(u, pts));
    let c = triangle_contact(&a, &b);
    assert_eq!(triangle_contact(&b, &a), c, "{t:?} and {u:?} swapped");
    c
}

/// Whether segments `e` and `f` meet, checked to be the same with the two swapped.
fn segments_both_ways(pts: &[P], e: [u32; 2], f: [u32; 2]) -> bool {
    let (a, b) = (Seg::of(e, pts), Seg::of(f, pts));
    let m = segments_meet(&a, &b);
    assert_eq!(segments_meet(&b, &a), m, "{e:?} and {f:?} swapped");
    m
}

fn seg_tri(pts: &[P], e: [u32; 2], t: [u32; 3]) -> bool {
    segment_meets_triangle(&Seg::of(e, pts), &Tri::of(t, pts))
}

/// The unit corner triangle 0-1-2 in z = 0, and points around it.
fn pts() -> Vec<P> {
    vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.2, 0.2, -1.0],
        [0.2, 0.2, 1.0],
        [1.0, 1.0, 0.0],
        [0.5, -0.5, 0.0],
    ]
}

#[test]
fn coplanar_triangles_that_overlap_are_an_overlap_not_a_crossing() {
    let p = vec![
        [0.0, 0.0, 0.0],
        [4.0, 0.0, 0.0],
        [0.0, 4.0, 0.0],
        [1.0, 1.0, 0.0],
        [5.0, 1.0, 0.0],
        [1.0, 5.0, 0.0],
    ];
    assert_eq!(
        both_ways(&p, [0, 1, 2], [3, 4, 5]),
        Contact::CoplanarOverlap
    );
}

#[test]
fn coplanar_triangles_sharing_a_vertex_overlap_only_when_one_turns_into_the_other() {
    let mut p = pts();
    p.push([-1.0, -1.0, 0.0]);
    p.push([-1.0, 0.5, 0.0]);
    p.push([2.0, 0.0, 0.0]);
    // A fan around vertex 0 on the other side.
    assert_eq!(both_ways(&p, [0, 1, 2], [0, 8, 9]), Contact::None);
    // An edge running from the shared vertex along the other's edge.
    assert_eq!(
        both_ways(&p, [0, 1, 2], [0, 10, 7]),
        Contact::CoplanarOverlap
    );
    // An edge from the shared vertex into the other's inside.
    assert_eq!(
        both_ways(&p, [0, 1, 2], [0, 6, 7]),
        Contact::CoplanarOverlap
    );
}

#[test]
fn triangles_touching_at_a_vertex_meet_unless_they_share_it() {
    let mut p = pts();
    // Vertex 8 sits on vertex 1's position under another id; 9 lies in triangle 0-1-2.
    p.push([1.0, 0.0, 0.0]);
    p.push([0.25, 0.25, 0.0]);
    p.push([1.0, 0.0, 1.0]);
    p.push([2.0, 1.0, 1.0]);
    assert_eq!(both_ways(&p, [0, 1, 2], [8, 10, 11]), Contact::Crossing);
    assert_eq!(both_ways(&p, [0, 1, 2], [1, 10, 11]), Contact::None);
    // A vertex touching the other triangle's inside from above.
    assert_eq!(both_ways(&p, [0, 1, 2], [9, 10, 11]), Contact::Crossing);
}

#[test]
fn a_shared_edge_folding_onto_itself_overlaps_and_any_other_hinge_does_not() {
    let mut p = pts();
    p.push([0.5, 2.0, 0.0]);
    p.push([0.0, 1.0, 0.0]);
    // Coplanar, opposite sides of the shared edge 0-1.
    assert_eq!(both_ways(&p, [0, 1, 2], [0, 7, 1]), Contact::None);
    assert_eq!(both_ways(&p, [0, 1, 2], [1, 6, 2]), Contact::None);
    // Coplanar, same side: folded flat onto itself.
    assert_eq!(
        both_ways(&p, [0, 1, 2], [0, 1, 8]),
        Contact::CoplanarOverlap
    );
    assert_eq!(
        both_ways(&p, [0, 1, 2], [0, 1, 6]),
        Contact::CoplanarOverlap
    );
    // Folded exactly onto itself, the third vertex repeated under another id.
    assert_eq!(
        both_ways(&p, [0, 1, 2], [1, 0, 9]),
        Contact::CoplanarOverlap
    );
    // A hinge out of the plane.
    assert_eq!(both_ways(&p, [0, 1, 2], [0, 1, 3]), Contact::None);
}

#[test]
fn the_same_three_vertices_are_not_a_contact() {
    let p = pts();
    assert_eq!(both_ways(&p, [0, 1, 2], [2, 1, 0]), Contact::None);
}

#[test]
fn a_triangle_through_another_crosses_it_even_when_sharing_a_vertex() {
    let mut p = pts();
    assert_eq!(both_ways(&p, [0, 1, 2], [4, 5, 6]), Contact::Crossing);
    p.push([0.3, 0.3, -1.0]);
    p.push([0.3, 0.3, 1.0]);
    // Shares vertex 0 and crosses the inside of 0-1-2 along a segment.
    assert_eq!(both_ways(&p, [0, 1, 2], [0, 8, 9]), Contact::Crossing);
    // Shares vertex 0 only and lies above.
    assert_eq!(both_ways(&p, [0, 1, 2], [0, 3, 5]), Contact::None);
}

#[test]
fn near_tangent_triangles_at_utm_magnitudes_meet_only_when_they_touch_exactly() {
    let o = [512_345.125, 7_012_345.5, -1234.25];
    let at = |x: f64, y: f64, z: f64| [o[0] + x, o[1] + y, o[2] + z];
    let touching = at(1.0, 1.0, 0.0);
    let mut above = touching;
    above[2] = above[2].next_up();
    let p = vec![
        at(0.0, 0.0, 0.0),
        at(10.0, 0.0, 0.0),
        at(0.0, 10.0, 0.0),
        touching,
        above,
        at(1.0, 1.0, 1.0),
        at(5.0, -3.0, 0.5),
    ];
    assert_eq!(both_ways(&p, [0, 1, 2], [3, 5, 6]), Contact::Crossing);
    assert_eq!(both_ways(&p, [0, 1, 2], [4, 5, 6]), Contact::None);
}

#[test]
fn crossing_triangles_at_utm_magnitudes_are_found_and_ones_a_millimetre_off_are_not() {
    let o = [512_345.125, 7_012_345.5, -1234.25];
    let at = |x: f64, y: f64, z: f64| [o[0] + x, o[1] + y, o[2] + z];
    let p = vec![
        at(0.0, 0.0, 0.0),
        at(10.0, 0.0, 0.0),
        at(0.0, 10.0, 0.0),
        at(1.0, 1.0, -1.0),
        at(1.0, 1.0, 1.0),
        at(5.0, -3.0, 0.5),
        at(1.0, 1.0, 0.001),
    ];
    assert_eq!(both_ways(&p, [0, 1, 2], [3, 4, 5]), Contact::Crossing);
    assert_eq!(both_ways(&p, [0, 1, 2], [6, 4, 5]), Contact::None);
}

#[test]
fn every_pair_of_lattice_triangles_meets_the_same_either_way_round() {
    // Points of a 3 x 3 x 2 lattice: many coplanar, collinear and shared-vertex configurations.
    let p: Vec<P> = (0..18)
        .map(|i| [(i % 3) as f64, ((i / 3) % 3) as f64, (i / 9) as f64])
        .collect();
    let mut tris = Vec::new();
    for a in 0..18u32 {
        for b in a + 1..18 {
            for c in b + 1..18 {
                let [x, y, z] = [a, b, c].map(|i| &p[i as usize]);
                if (a * 7 + b * 3 + c) % 5 == 0 && !triangle_is_degenerate(x, y, z) {
                    tris.push([a, b, c]);
                }
            }
        }
    }
    let mut seen = [0usize; 3];
    for (i, &t) in tris.iter().enumerate() {
        for &u in &tris[i + 1..] {
            seen[both_ways(&p, t, u) as usize] += 1;
        }
    }
    assert!(seen.iter().all(|&n| n > 0), "{seen:?}");
}

#[test]
fn segments_meeting_only_at_a_shared_end_are_apart_and_overlapping_or_crossing_ones_meet() {
    let p = vec![
        [0.0, 0.0, 0.0],
        [1.0, 1.0, 1.0],
        [2.0, 2.0, 2.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 1.0],
        [3.0, 3.0, 3.0],
        [1.0, 1.0, 0.0],
    ];
    // A polyline bending at vertex 1, and one going straight on.
    assert!(!segments_both_ways(&p, [0, 1], [1, 3]));
    assert!(!segments_both_ways(&p, [0, 1], [1, 2]));
    // Folding back over itself from the shared vertex.
    assert!(segments_both_ways(&p, [1, 2], [1, 5]));
    // Two diagonals of the unit square's shadow crossing at (0.5, 0.5, 0.5).
    assert!(segments_both_ways(&p, [0, 1], [3, 4]));
    // Skew segments do not meet.
    assert!(!segments_both_ways(&p, [0, 1], [3, 6]));
    // Collinear and apart, collinear and overlapping.
    assert!(!segments_both_ways(&p, [0, 1], [2, 5]));
    assert!(segments_both_ways(&p, [0, 2], [1, 5]));
    // The same segment twice.
    assert!(segments_both_ways(&p, [0, 1], [1, 0]));
}

#[test]
fn a_segment_along_a_triangle_edge_or_touching_its_inside_meets_it_and_one_from_a_vertex_does_not()
{
    let mut p = pts();
    p.push([0.25, 0.25, 0.0]);
    assert!(seg_tri(&p, [0, 1], [0, 1, 2]));
    assert!(!seg_tri(&p, [0, 3], [0, 1, 2]));
    assert!(seg_tri(&p, [3, 8], [0, 1, 2]));
    assert!(seg_tri(&p, [4, 5], [0, 1, 2]));
    // Beside the triangle.
    p.push([2.0, 2.0, -1.0]);
    p.push([2.0, 2.0, 1.0]);
    assert!(!seg_tri(&p, [9, 10], [0, 1, 2]));
}

#[test]
fn a_box_around_a_point_near_a_slanted_segment_meets_it_and_one_beside_it_does_not() {
    let (a, b) = ([0.0, 0.0, 0.0], [3.0, 1.0, 2.0]);
    let near = |c: P, r: f64| segment_meets_box(&a, &b, &c.map(|x| x - r), &c.map(|x| x + r));
    assert!(near([1.5, 0.5, 1.0], 1e-12));
    assert!(near([1.5, 0.5, 1.0 + 1e-3], 2e-3));
    assert!(!near([1.5, 0.5, 1.0 + 1e-3], 1e-4));
    assert!(!near([4.0, 1.5, 2.5], 0.1));
}

#[test]
fn collinear_and_coincident_corners_make_a_degenerate_triangle() {
    let (a, b) = ([0.0, 0.0, 0.0], [1.0, 2.0, 3.0]);
    assert!(triangle_is_degenerate(&a, &b, &[2.0, 4.0, 6.0]));
    assert!(triangle_is_degenerate(&a, &b, &b));
    assert!(!triangle_is_degenerate(&a, &b, &[2.0, 4.0, 6.5]));
    assert!(collinear(&a, &b, &[-1.0, -2.0, -3.0]));
}
