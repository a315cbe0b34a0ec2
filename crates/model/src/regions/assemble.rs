//! From shells to regions: which shell of each connected body faces the unbounded outside, which
//! region hosts a nested body (a lens: its outside shell becomes a cavity of the host) or a
//! free-floating dangling surface, and a point strictly inside each region.
//!
//! A shell's side is decided exactly: a point is built just off one of its face-uses and verified
//! (see `exact::near_point`) to lie in the cell that face-use faces; ray-casting parity against
//! the shell's one-sided patches then says whether that cell is enclosed (a region) or not (the
//! outside of the body). Each body has exactly one outside shell. A body's host is the innermost
//! region whose outer shell encloses a point just outside the body.

use super::exact::{Indexed, Loc, Tri, near_point, one_sided, parity};
use super::radial::UnionFind;
use super::shells::Shells;
use super::weld::{P3, Soup, fmt_point};
use super::{FaceUse, PatchIn, Region, RegionError, Shell, Side};
use geom::BBox;
use geom::predicates::signed_volume;
use geom::trimesh::triangle_area;

fn lex(a: &P3, b: &P3) -> std::cmp::Ordering {
    a[0].total_cmp(&b[0])
        .then(a[1].total_cmp(&b[1]))
        .then(a[2].total_cmp(&b[2]))
}

pub(super) struct Assembled {
    pub regions: Vec<Region>,
    pub exterior: Vec<Shell>,
    pub dangling: Vec<u32>,
}

#[derive(Clone, Copy, PartialEq)]
enum Kind {
    Bounded,
    Outside,
    Dangling,
}

struct Info {
    kind: Kind,
    /// A verified point in the cell the shell faces.
    point: P3,
    sigma: Vec<Tri>,
}

fn shell_value(soup: &Soup, shells: &Shells, s: usize) -> Shell {
    let origin = soup.points.first().copied().unwrap_or([0.0; 3]);
    let mut v = 0.0;
    for f in &shells.shells[s] {
        let sign = if f.side == Side::Front { -1.0 } else { 1.0 };
        for t in soup.patch_tris(f.patch as usize) {
            let [a, b, c] = soup.corners(t);
            v += sign * signed_volume(&origin, &a, &b, &c);
        }
    }
    Shell {
        face_uses: shells.shells[s].clone(),
        signed_volume: v,
    }
}

fn surfaces_of(patches: &[PatchIn], fus: &[FaceUse]) -> String {
    let mut s: Vec<&str> = fus
        .iter()
        .map(|f| patches[f.patch as usize].surface.as_str())
        .collect();
    s.sort_unstable();
    s.dedup();
    s.iter()
        .map(|x| format!("`{x}`"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// Classifies shell `s`: a verified point in the cell it faces and whether that cell is enclosed.
fn classify(
    soup: &Soup,
    patches: &[PatchIn],
    all: &Indexed,
    shells: &Shells,
    s: usize,
    bbox: &BBox,
) -> Result<Info, RegionError> {
    let fus = &shells.shells[s];
    let sigma_ids = one_sided(fus);
    let side_of = |p: u32| {
        fus.iter()
            .find(|f| f.patch == p)
            .map_or(Side::Front, |f| f.side)
    };
    // (area, sorted corners, triangle, front): largest triangles first (a heuristic for the
    // construction only), ties by their corners, so the choice is independent of patch order.
    let mut cands: Vec<(f64, [P3; 3], usize, bool)> = Vec::new();
    let ids: Vec<u32> = if sigma_ids.is_empty() {
        fus.iter().map(|f| f.patch).collect()
    } else {
        sigma_ids.clone()
    };
    for &p in &ids {
        let front = sigma_ids.is_empty() || side_of(p) == Side::Front;
        for t in soup.patch_tris(p as usize) {
            let c = soup.corners(t);
            let mut key = c;
            key.sort_by(lex);
            cands.push((triangle_area([&c[0], &c[1], &c[2]]), key, t, front));
        }
    }
    let order = |a: &(f64, [P3; 3], usize, bool), b: &(f64, [P3; 3], usize, bool)| {
        b.0.total_cmp(&a.0).then_with(|| {
            (0..3)
                .map(|i| lex(&a.1[i], &b.1[i]))
                .find(|o| o.is_ne())
                .unwrap_or(std::cmp::Ordering::Equal)
        })
    };
    const TRIES: usize = 24;
    if cands.len() > TRIES {
        cands.select_nth_unstable_by(TRIES, order);
        cands.truncate(TRIES);
    }
    cands.sort_by(order);
    let sigma: Vec<Tri> = sigma_ids
        .iter()
        .flat_map(|&p| soup.patch_tris(p as usize))
        .map(|t| soup.corners(t))
        .collect();
    for &(_, _, t, front) in &cands {
        let Some(q) = near_point(all, t, front) else {
            continue;
        };
        if sigma_ids.is_empty() {
            return Ok(Info {
                kind: Kind::Dangling,
                point: q,
                sigma,
            });
        }
        match parity(&q, &sigma, bbox) {
            Some(Loc::Inside) => {
                return Ok(Info {
                    kind: Kind::Bounded,
                    point: q,
                    sigma,
                });
            }
            Some(Loc::Outside) => {
                return Ok(Info {
                    kind: Kind::Outside,
                    point: q,
                    sigma,
                });
            }
            _ => continue,
        }
    }
    let at = cands.first().map(|c| c.1[0]);
    Err(RegionError::new(
        format!(
            "could not decide which side of the shell bounded by {} is enclosed{}",
            surfaces_of(patches, fus),
            at.map(|p| format!(" (near {})", fmt_point(&p)))
                .unwrap_or_default()
        ),
        fus.first()
            .map(|f| patches[f.patch as usize].surface.as_str()),
        at,
    ))
}

pub(super) fn assemble(
    soup: &Soup,
    patches: &[PatchIn],
    shells: &Shells,
) -> Result<Assembled, RegionError> {
    let n = shells.shells.len();
    let all: Vec<Tri> = (0..soup.tris.len()).map(|t| soup.corners(t)).collect();
    let indexed = Indexed::new(&all);
    let bbox = BBox::from_points(soup.points.iter());
    let mut comp = UnionFind::new(n);
    for pair in &shells.shell_of {
        comp.union(pair[0] as usize, pair[1] as usize);
    }
    let infos: Vec<Info> = (0..n)
        .map(|s| classify(soup, patches, &indexed, shells, s, &bbox))
        .collect::<Result<_, _>>()?;

    // Each body: its shells; exactly one faces the outside unless it is a dangling sheet.
    let mut bodies: std::collections::BTreeMap<usize, Vec<usize>> =
        std::collections::BTreeMap::new();
    for s in 0..n {
        bodies.entry(comp.find(s)).or_default().push(s);
    }
    // (sample point just outside the body, the body's outside or dangling shell, root)
    let mut samples: Vec<(P3, usize, usize)> = Vec::new();
    for (&root, members) in &bodies {
        let outs: Vec<usize> = members
            .iter()
            .copied()
            .filter(|&s| infos[s].kind != Kind::Bounded)
            .collect();
        if outs.len() != 1 {
            let fus: Vec<FaceUse> = members
                .iter()
                .flat_map(|&s| shells.shells[s].iter().copied())
                .collect();
            let at = infos[members[0]].point;
            return Err(RegionError::new(
                format!(
                    "the surfaces {} form a body with {} shells facing the outside (expected one) near {}: \
                     the model is not a valid partition of space",
                    surfaces_of(patches, &fus),
                    outs.len(),
                    fmt_point(&at)
                ),
                fus.first()
                    .map(|f| patches[f.patch as usize].surface.as_str()),
                Some(at),
            ));
        }
        samples.push((infos[outs[0]].point, outs[0], root));
    }

    let bounded: Vec<usize> = (0..n).filter(|&s| infos[s].kind == Kind::Bounded).collect();
    let inside = |p: &P3, b: usize| -> Result<bool, RegionError> {
        match parity(p, &infos[b].sigma, &bbox) {
            Some(Loc::Inside) => Ok(true),
            Some(Loc::Outside) => Ok(false),
            _ => Err(RegionError::new(
                format!(
                    "could not locate the point {} against the shell bounded by {}",
                    fmt_point(p),
                    surfaces_of(patches, &shells.shells[b])
                ),
                None,
                Some(*p),
            )),
        }
    };
    let mut hosted: Vec<Vec<usize>> = vec![Vec::new(); n];
    let mut exterior = Vec::new();
    for &(q, shell, root) in &samples {
        let mut containers = Vec::new();
        for &b in &bounded {
            if comp.find(b) != root && inside(&q, b)? {
                containers.push(b);
            }
        }
        // The innermost container lies inside every other one.
        let mut host = None;
        let mut best = 0usize;
        for &c in &containers {
            let mut depth = 0;
            for &d in &containers {
                if d != c && inside(&infos[c].point, d)? {
                    depth += 1;
                }
            }
            if host.is_none() || depth > best {
                host = Some(c);
                best = depth;
            }
        }
        match host {
            Some(h) => hosted[h].push(shell),
            None if infos[shell].kind == Kind::Dangling => {
                let p = shells.shells[shell][0].patch as usize;
                let surface = &patches[p].surface;
                return Err(RegionError::new(
                    format!(
                        "surface `{surface}` (patch `{}`) lies outside every region near {}",
                        patches[p].name,
                        fmt_point(&q)
                    ),
                    Some(surface),
                    Some(q),
                ));
            }
            None => {
                let sh = shell_value(soup, shells, shell);
                let fus = &sh.face_uses;
                if let Some(w) = fus.windows(2).find(|w| w[0].patch == w[1].patch) {
                    let p = w[0].patch as usize;
                    let at = soup.corners(soup.patch_tris(p).start)[0];
                    let surface = &patches[p].surface;
                    return Err(RegionError::new(
                        format!(
                            "surface `{surface}` (patch `{}`) sticks out of the model: it dangles outside every region near {}",
                            patches[p].name,
                            fmt_point(&at)
                        ),
                        Some(surface),
                        Some(at),
                    ));
                }
                exterior.push(sh);
            }
        }
    }

    let mut regions = Vec::with_capacity(bounded.len());
    for &b in &bounded {
        let outer = shell_value(soup, shells, b);
        let mut sides = outer.face_uses.clone();
        let mut cavities = Vec::new();
        for &h in &hosted[b] {
            let sh = shell_value(soup, shells, h);
            sides.extend_from_slice(&sh.face_uses);
            if infos[h].kind == Kind::Outside {
                cavities.push(sh);
            }
        }
        sides.sort_unstable();
        sides.dedup();
        regions.push(Region {
            name: String::new(),
            outer,
            cavities,
            sides,
            interior_point: infos[b].point,
        });
    }
    let dangling = (0..patches.len())
        .filter(|&p| shells.is_dangling(p))
        .map(|p| p as u32)
        .collect();
    Ok(Assembled {
        regions,
        exterior,
        dangling,
    })
}
