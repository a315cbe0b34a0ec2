//! Region names and the canonical order of regions and exterior shells.
//!
//! Order: by the lexicographically smallest vertex of the (outer) shell, then by the sorted
//! `(patch name, side)` list — a geometric key independent of the input order of patches. A
//! region holding a recipe naming point (exact `locate`) takes that name; the others are named
//! from the sorted surface names of their outer shell (`box+h1+h2`), with `#k` (k-th in canonical
//! order) only when several regions would share that name.

use super::assemble::Assembled;
use super::crowded::{Enclosed, check_lenses, mean_turn};
use super::locate::Locator;
use super::weld::fmt_point;
use super::{PatchIn, RegionError, RegionModel, Shell, Side};
use std::cmp::Ordering;
use std::collections::BTreeMap;

type Key = ([f64; 3], Vec<(String, Side)>);

fn shell_key(shell: &Shell, patches: &[PatchIn]) -> Key {
    let mut min = [f64::INFINITY; 3];
    for f in &shell.face_uses {
        for v in &patches[f.patch as usize].mesh.vertices {
            if lex(v, &min) == Ordering::Less {
                min = *v;
            }
        }
    }
    let mut names: Vec<(String, Side)> = shell
        .face_uses
        .iter()
        .map(|f| (patches[f.patch as usize].name.clone(), f.side))
        .collect();
    names.sort();
    (min, names)
}

fn lex(a: &[f64; 3], b: &[f64; 3]) -> Ordering {
    a[0].total_cmp(&b[0])
        .then(a[1].total_cmp(&b[1]))
        .then(a[2].total_cmp(&b[2]))
}

fn key_cmp(a: &Key, b: &Key) -> Ordering {
    lex(&a.0, &b.0).then_with(|| a.1.cmp(&b.1))
}

pub(super) fn name_regions(
    built: Assembled,
    patches: &[PatchIn],
    names: &[(String, [f64; 3])],
) -> Result<RegionModel, RegionError> {
    let Assembled {
        regions,
        exterior,
        dangling,
    } = built;
    let mut keyed: Vec<(Key, super::Region)> = regions
        .into_iter()
        .map(|r| (shell_key(&r.outer, patches), r))
        .collect();
    keyed.sort_by(|a, b| key_cmp(&a.0, &b.0));
    let mut regions: Vec<super::Region> = keyed.into_iter().map(|k| k.1).collect();
    let mut ext: Vec<(Key, Shell)> = exterior
        .into_iter()
        .map(|s| (shell_key(&s, patches), s))
        .collect();
    ext.sort_by(|a, b| key_cmp(&a.0, &b.0));
    let exterior: Vec<Shell> = ext.into_iter().map(|k| k.1).collect();

    let locator = Locator::from_regions(&regions, patches);
    let mut given: BTreeMap<usize, &str> = BTreeMap::new();
    let mut seen: BTreeMap<&str, usize> = BTreeMap::new();
    for (name, p) in names {
        if seen.insert(name.as_str(), 0).is_some() {
            return Err(RegionError::new(
                format!("the region name `{name}` is given twice"),
                None,
                Some(*p),
            ));
        }
        let hits: Vec<usize> = (0..regions.len())
            .filter(|&i| locator.contains(i, *p) == Some(true))
            .collect();
        let Some(&i) = hits.first() else {
            return Err(RegionError::new(
                format!(
                    "region name `{name}`: the point {} is strictly inside no region (outside the model or on a surface)",
                    fmt_point(p)
                ),
                None,
                Some(*p),
            ));
        };
        if let Some(other) = given.insert(i, name) {
            return Err(RegionError::new(
                format!(
                    "region names `{other}` and `{name}` both point into the same region (at {})",
                    fmt_point(p)
                ),
                None,
                Some(*p),
            ));
        }
    }
    let surfaces: Vec<Vec<&str>> = regions
        .iter()
        .map(|r| {
            let mut s: Vec<&str> = r
                .outer
                .face_uses
                .iter()
                .map(|f| patches[f.patch as usize].surface.as_str())
                .collect();
            s.sort_unstable();
            s.dedup();
            s
        })
        .collect();
    let enclosed: Vec<Enclosed> = (regions.iter().zip(&surfaces).enumerate())
        .map(|(i, (r, s))| Enclosed {
            named: given.contains_key(&i),
            surfaces: s.iter().map(|s| (*s, sample(r, s, patches))).collect(),
        })
        .collect();
    check_lenses(&enclosed, |s| mean_turn(patches, s))?;
    let base: Vec<String> = surfaces.iter().map(|s| s.join("+")).collect();
    let mut count: BTreeMap<&str, usize> = BTreeMap::new();
    for (i, b) in base.iter().enumerate() {
        if !given.contains_key(&i) {
            *count.entry(b.as_str()).or_default() += 1;
        }
    }
    let taken: Vec<&str> = given.values().copied().collect();
    let mut rank: BTreeMap<&str, usize> = BTreeMap::new();
    let mut out_names = Vec::with_capacity(regions.len());
    for (i, b) in base.iter().enumerate() {
        if let Some(n) = given.get(&i) {
            out_names.push(n.to_string());
            continue;
        }
        let k = rank.entry(b.as_str()).or_default();
        *k += 1;
        if count[b.as_str()] == 1 && !taken.contains(&b.as_str()) {
            out_names.push(b.clone());
        } else {
            out_names.push(format!("{b}#{k}"));
        }
    }
    for (r, n) in regions.iter_mut().zip(out_names) {
        r.name = n;
    }
    Ok(RegionModel {
        regions,
        exterior,
        dangling,
    })
}

/// The centroid of the first triangle of `surface` on the region's outer shell.
fn sample(r: &super::Region, surface: &str, patches: &[PatchIn]) -> [f64; 3] {
    let f = r.outer.face_uses.iter().map(|f| &patches[f.patch as usize]);
    let Some(p) = f
        .filter(|p| p.surface == surface)
        .find(|p| !p.mesh.triangles.is_empty())
    else {
        return [0.0; 3];
    };
    let [a, b, c] = p.mesh.corners(0);
    [0, 1, 2].map(|k| (a[k] + b[k] + c[k]) / 3.0)
}
