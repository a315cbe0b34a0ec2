//! Summaries of the topological model for the report: the patches (with whether they dangle)
//! and the regions (with their bounding patch sides and enclosed volume) of a
//! [`RegionModel`], named as the model names them. Mesh figures (FE triangles, tets) are left at
//! 0 for the caller to fill once the patches and regions are meshed.

use super::input::{PatchSide, PatchSummary, RegionSummary};
use model::regions::RegionModel;

/// `patches[i]` is the `(name, surface)` of patch `i` as given to region finding. A patch index
/// of the model beyond `patches` is named `patch #i` rather than dropped. A region's volume is
/// its outer shell's signed volume plus its cavities' (which are negative): a measure.
pub fn model_summaries(
    patches: &[(&str, &str)],
    model: &RegionModel,
) -> (Vec<PatchSummary>, Vec<RegionSummary>) {
    let name = |i: u32| {
        patches
            .get(i as usize)
            .map_or_else(|| format!("patch #{i}"), |p| p.0.to_string())
    };
    let ps = patches
        .iter()
        .enumerate()
        .map(|(i, (n, s))| PatchSummary {
            name: n.to_string(),
            surface: s.to_string(),
            triangles: 0,
            dangling: model.dangling.binary_search(&(i as u32)).is_ok(),
        })
        .collect();
    let rs = model
        .regions
        .iter()
        .map(|r| RegionSummary {
            name: r.name.clone(),
            material: None,
            patches: r
                .sides
                .iter()
                .map(|f| PatchSide {
                    patch: name(f.patch),
                    side: f.side,
                })
                .collect(),
            tets: 0,
            volume: r.outer.signed_volume + r.cavities.iter().map(|c| c.signed_volume).sum::<f64>(),
        })
        .collect();
    (ps, rs)
}

#[cfg(test)]
mod tests {
    use super::*;
    use model::regions::{FaceUse, Region, Shell, Side};

    fn shell(uses: &[(u32, Side)], v: f64) -> Shell {
        Shell {
            face_uses: uses
                .iter()
                .map(|&(patch, side)| FaceUse { patch, side })
                .collect(),
            signed_volume: v,
        }
    }

    #[test]
    fn regions_name_their_patch_sides_and_subtract_their_cavities() {
        let model = RegionModel {
            regions: vec![Region {
                name: "host".into(),
                outer: shell(&[(0, Side::Back)], 1000.0),
                cavities: vec![shell(&[(1, Side::Front)], -10.0)],
                sides: vec![
                    FaceUse {
                        patch: 0,
                        side: Side::Back,
                    },
                    FaceUse {
                        patch: 1,
                        side: Side::Front,
                    },
                    FaceUse {
                        patch: 2,
                        side: Side::Front,
                    },
                    FaceUse {
                        patch: 2,
                        side: Side::Back,
                    },
                    FaceUse {
                        patch: 9,
                        side: Side::Back,
                    },
                ],
                interior_point: [0.0; 3],
            }],
            exterior: vec![],
            dangling: vec![2],
        };
        let (p, r) = model_summaries(
            &[("box#0", "box"), ("lens#0", "lens"), ("F1#0", "F1")],
            &model,
        );
        assert_eq!(p.len(), 3);
        assert!(p[2].dangling && !p[0].dangling);
        assert_eq!(p[1].surface, "lens");
        assert_eq!(r[0].volume, 990.0);
        let names: Vec<&str> = r[0].patches.iter().map(|s| s.patch.as_str()).collect();
        assert_eq!(names, ["box#0", "lens#0", "F1#0", "F1#0", "patch #9"]);
        assert_eq!(r[0].patches[3].side, Side::Back);
    }
}
