//! Regions whose tets are far worse than the rest of the mesh: the reader of a report should not
//! have to find a one-element-thick layer in Table 2 by eye.
//!
//! A region is flagged when its average mean ratio is more than [`FAR_BELOW`] under the median
//! of the regions' averages (a fixed gap, not a ratio: mean ratios live in [0, 1] and a good mesh
//! averages about 0.85). With fewer than three meshed regions there is no "rest" to compare with.

use export::quality::TetQuality;

/// How far under the median region average a region's average must fall to be flagged.
pub const FAR_BELOW: f64 = 0.15;

/// One sentence per flagged region of Table 2 (`rows`, the "all" row last), in row order.
pub fn poor_regions(rows: &[TetQuality]) -> Vec<String> {
    let regions: Vec<&TetQuality> = rows
        .split_last()
        .map(|(_, r)| r.iter().filter(|q| q.elements > 0).collect())
        .unwrap_or_default();
    if regions.len() < 3 {
        return Vec::new();
    }
    let mut avgs: Vec<f64> = regions.iter().map(|q| q.avg).collect();
    avgs.sort_by(f64::total_cmp);
    let median = avgs[avgs.len() / 2];
    regions
        .iter()
        .filter(|q| q.avg < median - FAR_BELOW)
        .map(|q| {
            format!(
                "region '{}' is meshed far worse than the rest: mean ratio {:.3} on average \
                 against {median:.3} for the median region, worst dihedral {:.1}° (a layer one \
                 element thick? see `layers` in `[mesh.regions]`)",
                q.name, q.avg, q.min_dihedral_deg
            )
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(name: &str, avg: f64) -> TetQuality {
        TetQuality {
            name: name.into(),
            nodes: 10,
            elements: 10,
            avg,
            sd: 0.0,
            min: avg,
            pct_lt_0_3: 0.0,
            pct_lt_0_2: 0.0,
            pct_lt_0_1: 0.0,
            min_dihedral_deg: 20.0,
            min_dihedral_bound_deg: None,
            min_dihedral_bound_at: None,
            min_dihedral_at: None,
            avg_paper: avg,
            min_paper: avg,
        }
    }

    #[test]
    fn a_region_far_below_the_median_is_flagged_and_the_others_are_not() {
        let rows = [
            row("over", 0.86),
            row("res", 0.53),
            row("under", 0.85),
            row("all", 0.83),
        ];
        let flags = poor_regions(&rows);
        assert_eq!(flags.len(), 1, "{flags:?}");
        assert!(flags[0].contains("'res'") && flags[0].contains("0.530"));
    }

    #[test]
    fn two_regions_or_an_even_mesh_flag_nothing() {
        assert!(poor_regions(&[row("a", 0.9), row("b", 0.4), row("all", 0.6)]).is_empty());
        let even = [
            row("a", 0.8),
            row("b", 0.75),
            row("c", 0.7),
            row("all", 0.75),
        ];
        assert!(poor_regions(&even).is_empty());
    }
}
