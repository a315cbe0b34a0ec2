//! The warning for a model whose surfaces almost share vertices (`model::conformity`): one
//! sentence per pair of surfaces, with how many places, the widest gap and the first place, so
//! a geomodeller can find the contact in the data.

use super::ModelData;
use model::conformity::NearMiss;

/// At most this many pairs are named; the rest are counted.
const MAX_PAIRS: usize = 8;

/// One sentence per pair of surfaces that almost share vertices, in name order.
pub fn non_conformity_warnings(model: &ModelData) -> Vec<String> {
    let mut pairs: Vec<Vec<&NearMiss>> = Vec::new();
    for m in &model.near_misses {
        match pairs.last_mut() {
            Some(p) if p[0].a == m.a && p[0].b == m.b => p.push(m),
            _ => pairs.push(vec![m]),
        }
    }
    let mut out: Vec<String> = (pairs.iter().take(MAX_PAIRS))
        .map(|p| {
            let widest = p.iter().map(|m| m.distance).fold(0.0, f64::max);
            let at = p[0].at;
            format!(
                "surfaces `{}` and `{}` are not conformal: at {} place(s) a vertex of one lies within {:.3e} of a vertex of the other without being at its coordinates, first at ({}, {}, {}); the intersections join them, but the data should share those vertices bit for bit (a file written with too few digits?)",
                p[0].a,
                p[0].b,
                p.len(),
                widest,
                at[0],
                at[1],
                at[2]
            )
        })
        .collect();
    if pairs.len() > MAX_PAIRS {
        out.push(format!(
            "{} more pairs of surfaces are not conformal (the report lists them all)",
            pairs.len() - MAX_PAIRS
        ));
    }
    out
}
