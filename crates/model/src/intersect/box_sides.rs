//! The model's bounding box as six planar surfaces `box.xmin` … `box.zmax`, each two triangles
//! with normals pointing out of the box. Every side uses the box's own corner coordinates, so
//! shared corners and edges are bit-identical between sides (the exact predicates then see the
//! sides meet exactly along the box edges).

use geom::{BBox, TriMesh};

/// The six sides, in the order xmin, xmax, ymin, ymax, zmin, zmax.
pub fn box_sides(b: &BBox) -> Vec<(String, TriMesh)> {
    let [x0, y0, z0] = b.min;
    let [x1, y1, z1] = b.max;
    // Each quad is counter-clockwise seen from outside the box.
    let quads: [(&str, [[f64; 3]; 4]); 6] = [
        (
            "box.xmin",
            [[x0, y0, z0], [x0, y0, z1], [x0, y1, z1], [x0, y1, z0]],
        ),
        (
            "box.xmax",
            [[x1, y0, z0], [x1, y1, z0], [x1, y1, z1], [x1, y0, z1]],
        ),
        (
            "box.ymin",
            [[x0, y0, z0], [x1, y0, z0], [x1, y0, z1], [x0, y0, z1]],
        ),
        (
            "box.ymax",
            [[x0, y1, z0], [x0, y1, z1], [x1, y1, z1], [x1, y1, z0]],
        ),
        (
            "box.zmin",
            [[x0, y0, z0], [x0, y1, z0], [x1, y1, z0], [x1, y0, z0]],
        ),
        (
            "box.zmax",
            [[x0, y0, z1], [x1, y0, z1], [x1, y1, z1], [x0, y1, z1]],
        ),
    ];
    quads
        .iter()
        .map(|(name, q)| {
            (
                name.to_string(),
                TriMesh::new(q.to_vec(), vec![[0, 1, 2], [0, 2, 3]]),
            )
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use geom::{Orientation, orient3d};

    #[test]
    fn every_side_faces_away_from_the_box_centre() {
        let b = BBox {
            min: [500_000.0, 7_000_000.0, -3000.0],
            max: [501_000.5, 7_002_000.25, 100.0],
        };
        let c = [500_500.25, 7_001_000.125, -1450.0];
        let sides = box_sides(&b);
        assert_eq!(sides.len(), 6);
        for (name, m) in &sides {
            for t in 0..2 {
                let [p, q, r] = m.corners(t);
                assert_eq!(
                    orient3d(p, q, r, &c),
                    Orientation::Negative,
                    "{name} triangle {t}"
                );
            }
        }
        assert_eq!(sides[0].0, "box.xmin");
        assert_eq!(sides[5].0, "box.zmax");
    }
}
