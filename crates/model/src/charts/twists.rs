//! Twists: a chart whose border crosses itself on the chart's own plane must be flattened by a
//! Tutte embedding, which squeezes the chart where its border doubles back; a surface mesh made
//! in such a plane folds on the support there, however small its triangles.
//!
//! Every triangle of a chart faces within the chart angle of one axis, yet its border may still
//! cross itself in projection: where a seam wanders along a sharp rim (a lens whose top and
//! bottom meet at a crease), the chart's border runs down the seam and back along the rim a few
//! metres away, with steep triangles between the two runs that overlap in map view. On a closed
//! lens 200 m thick, such a zigzag crossed itself on the plane, and 12 to 19 triangles of the
//! lens's bottom chart stayed folded after every repair.
//!
//! Decisions and why:
//! - A chart is judged by the surface mesher's own test (`projected_border_conflict`): only a
//!   chart that no projection flattens one to one, and whose border crosses itself on its mean
//!   plane, is changed; every chart that projects today keeps its triangles, so its mesh is the
//!   same.
//! - At the first crossing, of the chart's triangles on the two crossing edges, the steepest
//!   (facing furthest from its chart's mean) that a chart beside it takes moves there: it must
//!   face within the chart angle of that chart's mean normal. The steep triangles of a
//!   doubled-back run are the ones that overlap. When no chart beside them takes either, the
//!   steepest starts a new chart. Repeating peels the overlapping run away triangle by triangle.
//!   The crossing edges may be the patch's own border (the rim's creases): the triangles stay in
//!   the patch, only in another chart.
//! - Once every chart projects without a crossing, each new chart joins the chart beside it with
//!   which it shares the most edges, where the union still projects one to one and faces within
//!   the chart angle: the triangles peeled from one overlap end in one chart, not in many.
//! - A triangle moves at most once, so two charts never trade it back and forth, and there are
//!   at most `ROUNDS` rounds: a crossing that cannot be mended is left to the Tutte embedding,
//!   as before. Charts are visited in label order and ties go to the lower triangle index, so
//!   the result is the same on every machine.

use super::gaps::gap_at;
use super::{NONE, across_edges, add, area};
use geom::TriMesh;
use geom::predicates::dot;

/// Most rounds; each moves at most one triangle per chart.
const ROUNDS: usize = 256;

/// Moves triangles out of charts whose border crosses itself on their plane (see the module doc);
/// `group` is the chart of each of `mesh`'s triangles, `normals` their unit (or zero) normals.
/// Returns how many triangles moved: none when some chart could not be mended, which then keeps
/// the charts as they were.
pub fn untwist(mesh: &TriMesh, normals: &[[f64; 3]], max_deg: f64, group: &mut [u32]) -> usize {
    let mut s = Untwisting::new(mesh, normals, max_deg, group);
    let first_new = s.mean.len();
    for _ in 0..ROUNDS {
        match s.round() {
            Round::Moved => {}
            Round::Clean => {
                s.gather(first_new);
                group.copy_from_slice(&s.group);
                return s.moved;
            }
            Round::Stuck => return 0,
        }
    }
    0
}

/// What a round of [`Untwisting`] did.
enum Round {
    /// Every chart projects without a crossing.
    Clean,
    /// Some triangle moved.
    Moved,
    /// A chart crosses itself and neither crossing edge has a triangle left to move.
    Stuck,
}

/// The charts being mended, on a copy of the labels.
struct Untwisting<'a> {
    mesh: &'a TriMesh,
    normals: &'a [[f64; 3]],
    across: Vec<[u32; 3]>,
    cos_max: f64,
    group: Vec<u32>,
    /// Per chart, its triangles' normals summed, each weighted by its area.
    mean: Vec<[f64; 3]>,
    /// Per chart, whether it changed since it was last judged.
    dirty: Vec<bool>,
    moved_once: Vec<bool>,
    moved: usize,
}

impl<'a> Untwisting<'a> {
    fn new(mesh: &'a TriMesh, normals: &'a [[f64; 3]], max_deg: f64, group: &[u32]) -> Self {
        let groups = group.iter().map(|&g| g as usize + 1).max().unwrap_or(0);
        let mut mean = vec![[0.0; 3]; groups];
        for (t, n) in normals.iter().enumerate() {
            add(&mut mean[group[t] as usize], n, area(mesh, t));
        }
        Untwisting {
            mesh,
            normals,
            across: across_edges(mesh),
            cos_max: max_deg.to_radians().cos(),
            group: group.to_vec(),
            mean,
            dirty: vec![true; groups],
            moved_once: vec![false; mesh.triangles.len()],
            moved: 0,
        }
    }

    /// Judges every changed chart and moves one triangle out of each that crosses itself.
    fn round(&mut self) -> Round {
        let mut members: Vec<Vec<u32>> = vec![Vec::new(); self.mean.len()];
        for (t, &g) in self.group.iter().enumerate() {
            members[g as usize].push(t as u32);
        }
        let mut moved = false;
        for (g, members) in members.iter().enumerate() {
            if !std::mem::take(&mut self.dirty[g]) {
                continue;
            }
            let Some(edges) = conflict(self.mesh, members) else {
                continue;
            };
            let Some((t, to)) = self.pick(g, members, edges) else {
                return Round::Stuck;
            };
            self.take(t, to);
            self.close_gaps(t, to);
            moved = true;
        }
        if moved { Round::Moved } else { Round::Clean }
    }

    /// The triangle of chart `g` to move at its crossing `edges`, and where: of the triangles
    /// on the two edges, the steepest that a chart across one of its edges takes (facing
    /// within the chart angle of it), else the steepest left to move, to a new chart.
    fn pick(&mut self, g: usize, members: &[u32], edges: [[u32; 2]; 2]) -> Option<(u32, u32)> {
        let steepness = |t: u32| cosine(&self.normals[t as usize], &self.mean[g]);
        let by_steepness = |x: &(u32, u32), y: &(u32, u32)| {
            steepness(x.0)
                .total_cmp(&steepness(y.0))
                .then(x.0.cmp(&y.0))
        };
        let runs: Vec<u32> = edges
            .iter()
            .filter_map(|&e| self.runs(members, e))
            .filter(|&t| !self.moved_once[t as usize])
            .collect();
        let taken = runs
            .iter()
            .filter_map(|&t| self.taker(t).map(|to| (t, to)))
            .min_by(by_steepness);
        if taken.is_some() {
            return taken;
        }
        let t = runs.into_iter().map(|t| (t, 0)).min_by(by_steepness)?.0;
        self.mean.push([0.0; 3]);
        self.dirty.push(true);
        Some((t, self.mean.len() as u32 - 1))
    }

    /// The triangle of `members` that runs the border edge `[a, b]`.
    fn runs(&self, members: &[u32], [a, b]: [u32; 2]) -> Option<u32> {
        members.iter().copied().find(|&t| {
            let tri = self.mesh.triangles[t as usize];
            (0..3).any(|k| tri[k] == a && tri[(k + 1) % 3] == b)
        })
    }

    /// The chart across one of triangle `t`'s edges that `t` faces most, when it faces within
    /// the chart angle of that chart's mean normal (the lower chart on ties).
    fn taker(&self, t: u32) -> Option<u32> {
        let own = self.group[t as usize];
        let facing = |h: u32| cosine(&self.normals[t as usize], &self.mean[h as usize]);
        self.across[t as usize]
            .iter()
            .filter(|&&u| u != NONE && self.group[u as usize] != own)
            .map(|&u| self.group[u as usize])
            .filter(|&h| facing(h) >= self.cos_max)
            .max_by(|&x, &y| facing(x).total_cmp(&facing(y)).then(y.cmp(&x)))
    }

    /// Merges the charts made since `first_new`, the smallest first, each into the chart beside
    /// it with the longest shared border with which it still projects one to one and faces
    /// within the chart angle, until none can merge: the triangles peeled from one overlap end
    /// in one chart, not many.
    fn gather(&mut self, first_new: usize) {
        loop {
            let mut members: Vec<Vec<u32>> = vec![Vec::new(); self.mean.len()];
            for (t, &g) in self.group.iter().enumerate() {
                members[g as usize].push(t as u32);
            }
            let mut order: Vec<usize> = (first_new..members.len())
                .filter(|&g| !members[g].is_empty())
                .collect();
            order.sort_by_key(|&g| (members[g].len(), g));
            let merge =
                (order.into_iter()).find_map(|g| self.merge_target(&members, g).map(|h| (g, h)));
            let Some((g, h)) = merge else { return };
            for &t in &members[g] {
                self.group[t as usize] = h;
            }
            let sum = std::mem::take(&mut self.mean[g]);
            add(&mut self.mean[h as usize], &sum, 1.0);
        }
    }

    /// The chart beside chart `g` that can take all of it (see [`Untwisting::gather`]).
    fn merge_target(&self, members: &[Vec<u32>], g: usize) -> Option<u32> {
        let mut shared: Vec<u32> = members[g]
            .iter()
            .flat_map(|&t| self.across[t as usize])
            .filter(|&u| u != NONE && self.group[u as usize] != g as u32)
            .map(|u| self.group[u as usize])
            .collect();
        shared.sort_unstable();
        let mut runs: Vec<(usize, u32)> = shared
            .chunk_by(|a, b| a == b)
            .map(|run| (run.len(), run[0]))
            .collect();
        runs.sort_by(|a, b| b.0.cmp(&a.0).then(a.1.cmp(&b.1)));
        runs.into_iter().map(|(_, h)| h).find(|&h| {
            let (a, b) = (&members[g], &members[h as usize]);
            let means = [self.mean[g], self.mean[h as usize]];
            union_flattens(self.mesh, self.normals, [a, b], means, [self.cos_max; 2])
        })
    }

    /// Closes the gaps that moving triangle `t` to chart `to` left round `t`'s corners (see
    /// `gaps`), each where all of its triangles face within the chart angle of `to` and none
    /// has moved yet: else the chart is pinched there, `unpinch` gives `t` back, and the two
    /// passes undo each other for ever.
    fn close_gaps(&mut self, t: u32, to: u32) {
        for v in self.mesh.triangles[t as usize] {
            let Some(gap) = gap_at(self.mesh, &self.across, &self.group, t, v) else {
                continue;
            };
            let fits = |u: &u32| {
                let u = *u as usize;
                !self.moved_once[u]
                    && cosine(&self.normals[u], &self.mean[to as usize]) >= self.cos_max
            };
            if gap.iter().all(fits) {
                for u in gap {
                    self.take(u, to);
                }
            }
        }
    }

    /// Moves triangle `t` to chart `to`.
    fn take(&mut self, t: u32, to: u32) {
        let g = self.group[t as usize] as usize;
        let (n, a) = (&self.normals[t as usize], area(self.mesh, t as usize));
        add(&mut self.mean[g], n, -a);
        add(&mut self.mean[to as usize], n, a);
        self.group[t as usize] = to;
        self.moved_once[t as usize] = true;
        self.dirty[g] = true;
        self.dirty[to as usize] = true;
        self.moved += 1;
    }
}

/// The two border edges of the chart made of `members` (global vertex ids, as the chart's
/// triangles run them) that conflict on its plane, when no projection flattens it.
fn conflict(mesh: &TriMesh, members: &[u32]) -> Option<[[u32; 2]; 2]> {
    if members.is_empty() {
        return None;
    }
    let (chart, global) = chart_mesh(mesh, members);
    let edges = surface_mesh::projected_border_conflict(&chart)?;
    Some(edges.map(|e| e.map(|v| global[v as usize])))
}

/// The triangles `members` of `mesh` as a mesh of their own, with the global id of each of its
/// vertices.
fn chart_mesh(mesh: &TriMesh, members: &[u32]) -> (TriMesh, Vec<u32>) {
    let mut global: Vec<u32> = members
        .iter()
        .flat_map(|&t| mesh.triangles[t as usize])
        .collect();
    global.sort_unstable();
    global.dedup();
    let local = |v: u32| global.binary_search(&v).unwrap_or(0) as u32;
    let chart = TriMesh::new(
        global.iter().map(|&v| mesh.vertices[v as usize]).collect(),
        members
            .iter()
            .map(|&t| mesh.triangles[t as usize].map(local))
            .collect(),
    );
    (chart, global)
}

/// Whether the union of two charts (their ascending `members`, and the area-weighted sums of
/// their normals, `means`) is a chart: the triangles of each face within the angle of its
/// `cos_max` of the union's mean normal, and the union projects one to one.
pub(super) fn union_flattens(
    mesh: &TriMesh,
    normals: &[[f64; 3]],
    members: [&[u32]; 2],
    means: [[f64; 3]; 2],
    cos_max: [f64; 2],
) -> bool {
    let mut mean = means[0];
    add(&mut mean, &means[1], 1.0);
    let faces =
        |k: usize| (members[k].iter()).all(|&t| cosine(&normals[t as usize], &mean) >= cos_max[k]);
    let mut both = members.concat();
    both.sort_unstable();
    faces(0) && faces(1) && surface_mesh::projects_one_to_one(&chart_mesh(mesh, &both).0)
}

/// The cosine of the angle between a unit normal `n` and the direction of `mean` (1 for a zero
/// normal, which faces any way; -1 for a zero mean).
fn cosine(n: &[f64; 3], mean: &[f64; 3]) -> f64 {
    let len = dot(mean, mean).sqrt();
    if *n == [0.0; 3] {
        1.0
    } else if len > 0.0 {
        dot(n, mean) / len
    } else {
        -1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A ramp of `turn_deg` in `segs` steps (`test_support::shapes::ramp`).
    fn ramp(turn_deg: f64, segs: usize) -> TriMesh {
        let (v, t) = test_support::shapes::ramp(turn_deg, turn_deg / segs as f64);
        TriMesh::new(v, t)
    }

    /// The triangles of each chart of `group`.
    fn charts(group: &[u32]) -> Vec<Vec<u32>> {
        let mut out: Vec<Vec<u32>> = Vec::new();
        for (t, &g) in group.iter().enumerate() {
            if out.len() <= g as usize {
                out.resize(g as usize + 1, Vec::new());
            }
            out[g as usize].push(t as u32);
        }
        out
    }

    #[test]
    fn a_chart_whose_border_overlaps_itself_in_map_view_is_cut_until_each_piece_projects() {
        // A ramp of 400°: its last 40° lie over its first in map view.
        let m = ramp(400.0, 80);
        let normals = m.unit_normals();
        let mut group = vec![0; m.triangles.len()];
        assert!(conflict(&m, &charts(&group)[0]).is_some());
        let moved = untwist(&m, &normals, 60.0, &mut group);
        assert!(moved > 0);
        let pieces = charts(&group);
        assert!(pieces.len() >= 2, "{group:?}");
        for piece in &pieces {
            assert_eq!(conflict(&m, piece), None, "{piece:?}");
        }
        // Only the overlap moved: the first 360° stay together.
        assert!(moved <= 20, "{moved} moved");
    }

    #[test]
    fn triangles_peeled_from_an_overlap_join_the_chart_beside_them() {
        // The ramp's first 80 steps (400°) are one chart, overlapping itself in map view; its
        // last 10 steps (50°) another.
        let m = ramp(450.0, 90);
        let normals = m.unit_normals();
        let mut group: Vec<u32> = (0..m.triangles.len())
            .map(|t| u32::from(t >= 160))
            .collect();
        let moved = untwist(&m, &normals, 60.0, &mut group);
        assert!(moved > 0);
        assert_eq!(
            charts(&group),
            vec![(0..142).collect::<Vec<u32>>(), (142..180).collect()]
        );
        for piece in &charts(&group) {
            assert_eq!(conflict(&m, piece), None);
        }
    }

    #[test]
    fn a_chart_that_projects_is_left_as_it_was() {
        let m = ramp(300.0, 60);
        let normals = m.unit_normals();
        let mut group = vec![0; m.triangles.len()];
        assert_eq!(untwist(&m, &normals, 60.0, &mut group), 0);
        assert_eq!(group, vec![0; m.triangles.len()]);
    }
}
