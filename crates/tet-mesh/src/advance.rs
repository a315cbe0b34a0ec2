//! The advancing-front loop: take the smallest front face, rank candidate apexes (existing front
//! nodes near the ideal apex by the mean ratio of the tetrahedron they would make, and the ideal
//! point itself), accept the first one that passes the exact validity test, update the front.
//! When no candidate is valid the front is stuck there: delete the tetrahedra around the face
//! (a wider ball at each retry), restore the front around the cavity and carry on — an explicit
//! loop, never recursion. A flat pocket (a front face within rounding of the boundary
//! triangles behind it, which back-tracking keeps re-creating) is closed by an exactly positive
//! sliver that the optimizer's flips later remove. Gives up with an error naming the region and
//! the stuck face, when a face stays stuck or when the region's work (`work`) is spent.
//!
//! Cost: a face tests at most `MAX_TRIES` candidates per pass before it is deferred (all of them
//! on its last attempt), the wide second pass scans the front's node grid rather than its face
//! grid, and the validity test decides each nearby front node's sides against the candidate's
//! four planes once (`sides`), skipping every front face strictly outside one plane before any
//! triangle-triangle test.
//!
//! Progress (`geom::progress`), measured every [`MEASURE_EVERY`] steps: first the volume of the
//! tets built against the region's (from its boundary); then, once [`CLOSING_AT`] of it is
//! filled, how much of the front left at that moment has closed. On the refinement (b) meshed
//! by the front, the last 1 % of a bulk region's volume took a quarter of its steps (deferred
//! faces, pockets): by volume alone the bar stood still there. Back-tracking builds some volume
//! twice and re-opens faces, so either measure may run ahead of the work; the bar never goes
//! back.

use std::collections::HashMap;

use geom::predicates::{Orientation, cross, dist, dot, sub};
use geom::progress::Span;

use super::closing;
use super::exact::orient3d;
use super::front::{FaceMap, Front, bbox_of};
use super::sides::{SideCache, orientation_of};
use super::sizing::Background;
use super::verify::{canon, outward_faces};
use super::work::{self, FrontWork};
use super::{RegionInput, SizeField, TetMeshError};
use geom::contact::{Contact, Tri, triangle_contact_with};

type P = [f64; 3];

/// Ideal apexes closer than this fraction of the local size to an existing front node are not
/// created (the node is used instead): avoids near-duplicate nodes and the slivers they cause.
const NEW_NODE_CLEARANCE: f64 = 0.55;
/// Score factor of a new node against reusing an existing one of the same quality.
const NEW_NODE_PREFERENCE: f64 = 0.75;
/// `NEW_NODE_PREFERENCE` cubed, for scores in cubed mean ratios (`rank_ratio3`).
const PREF3: f64 = NEW_NODE_PREFERENCE * NEW_NODE_PREFERENCE * NEW_NODE_PREFERENCE;
/// Search radius for existing candidate nodes, in local sizes, on the first and second passes.
const SEARCH_RADIUS: [f64; 2] = [1.6, 4.0];
/// How many times the same face may trigger back-tracking before the region is declared stuck.
const MAX_LEVEL: u32 = 8;
/// Minimum mean ratio a tetrahedron must reach on the successive attempts at one face; between
/// attempts the face is deferred (re-queued behind the others). The last entry accepts any valid
/// tetrahedron; failing that, the mesher back-tracks.
const MIN_QUALITY: [f64; 6] = [0.3, 0.15, 0.05, 0.02, 0.005, 0.0];
/// New nodes closer than this fraction of the local size to a front face are not created.
const FACE_CLEARANCE: f64 = 0.3;
/// Cell size of the front's grid, in mean boundary edge lengths.
const FRONT_CELL: f64 = 1.0;
/// Candidate apexes whose tetrahedron has a (float) mean ratio below this are never considered.
const FLAT: f64 = 1e-9;
/// Heights of last-resort Steiner apexes over a stuck face, in local target sizes (not the
/// face's own size, so that tiny faces do not seed tinier nodes): down to 1/200 of the size, for
/// layers far thinner than their boundary triangles.
const STEINER_HEIGHTS: [f64; 5] = [0.4, 0.2, 0.1, 0.05, 0.025];
/// No new node is created closer than this (in local background sizes) to an existing node:
/// without it, slivers over slivers seed ever tinier faces and the front never closes.
const MIN_NODE_GAP: f64 = 0.004;
/// Steiner apexes keep at least this (in local sizes) from every node near the stuck face.
const STEINER_GAP: f64 = 0.05;
/// Back-tracks at one place after which a flat pocket there is closed by a sliver.
const POCKET_LEVEL: u32 = 4;
/// Candidates tested per pass before a face is deferred (all of them on the last attempt).
const MAX_TRIES: usize = 8;
/// On the first pass only existing nodes this close (in local sizes) to the ideal apex compete.
const NEAR_IDEAL: f64 = 1.0;
/// Times the pieces a front that cannot close leaves, and the Delaunay method cannot fill, are
/// widened and tried again (`State::close`).
const CLOSING_ROUNDS: u32 = 3;
/// Open faces the pieces that closing could not fill may have in all for it to widen them and
/// try again: more is no last gap of the front, and widening it would only open the front more.
const CLOSING_WIDENS: usize = 512;
/// Back-tracks before the first try at closing by the Delaunay method once [`CLOSING_AT`] of the
/// region's volume is filled, and between the first two tries (twice as many before each next).
const CLOSE_EVERY: usize = 16;
/// Steps of the front between two measures of its progress.
const MEASURE_EVERY: usize = 64;
/// The share of the region's volume filled after which progress follows the front's closing.
const CLOSING_AT: f64 = 0.95;
/// The share of the front's progress bar that follows the volume filled.
const FILLING_SHARE: f64 = 0.8;

#[derive(Debug)]
pub struct RawMesh {
    pub nodes: Vec<P>,
    pub tets: Vec<[u32; 4]>,
    pub backtracks: usize,
}

struct State<'a> {
    name: &'a str,
    nodes: Vec<P>,
    tets: Vec<[u32; 4]>,
    tet_alive: Vec<bool>,
    /// Live tets now, and the most there have been.
    alive: usize,
    fullest: usize,
    work: &'a FrontWork,
    node_tets: Vec<Vec<u32>>,
    front: Front,
    bg: Background,
    /// Embedded triangles (sorted vertex triples): constraints back-tracking must not dissolve.
    constrained: std::collections::HashSet<[u32; 3]>,
    scratch: Vec<u32>,
    scratch2: Vec<u32>,
    signs: SideCache,
    /// Per node: the last first-pass search that listed it (de-duplication without sorting).
    seen: Vec<u32>,
    seen_gen: u32,
}

#[derive(Clone, Copy)]
enum Cand {
    Node(u32),
    New(P),
}

/// The front's mesh of `input`, spending at most what `work` allows (see `work`).
pub fn advance_front(
    input: &RegionInput,
    size: &SizeField,
    work: &FrontWork,
) -> Result<RawMesh, TetMeshError> {
    advance_front_reporting(input, size, Span::none(), work)
}

/// [`advance_front`], reporting on `bar` the share of the region's volume meshed.
pub fn advance_front_reporting(
    input: &RegionInput,
    size: &SizeField,
    bar: Span<'_>,
    work: &FrontWork,
) -> Result<RawMesh, TetMeshError> {
    let volume = super::progress::enclosed_volume(input);
    // Tets built so far whose volume is counted, and that volume.
    let mut built = (0usize, 0.0f64);
    // The front faces alive when the volume filled reached `CLOSING_AT`.
    let mut closing: Option<usize> = None;
    let pts = &input.vertices;
    let mut mean_edge_sum = 0.0;
    let mut cap: f64 = 0.0;
    for t in &input.boundary {
        let le = mean_edge(t, pts);
        mean_edge_sum += le;
        cap = cap.max(le);
    }
    let avg = mean_edge_sum / input.boundary.len().max(1) as f64;
    let (lo, hi) = bbox_of(pts.iter());
    let mut st = State {
        name: &input.name,
        nodes: pts.clone(),
        tets: Vec::new(),
        tet_alive: Vec::new(),
        alive: 0,
        fullest: 0,
        work,
        node_tets: vec![Vec::new(); pts.len()],
        front: Front::new(lo, hi, FRONT_CELL * avg),
        bg: {
            let mut all = input.boundary.clone();
            all.extend_from_slice(&input.embedded);
            let _ = cap;
            Background::new(pts, &all, size)
        },
        scratch: Vec::new(),
        scratch2: Vec::new(),
        signs: SideCache::default(),
        seen: Vec::new(),
        seen_gen: 0,
        constrained: input
            .embedded
            .iter()
            .map(|t| {
                let mut k = *t;
                k.sort_unstable();
                k
            })
            .collect(),
    };
    for (v, p) in pts.iter().enumerate() {
        st.front.add_node(v as u32, p);
    }
    for t in &input.boundary {
        st.add_face([t[0], t[2], t[1]]);
    }
    for t in &input.embedded {
        st.add_face(*t);
        st.add_face([t[0], t[2], t[1]]);
    }
    // Keyed by the stuck face's centroid bits, not its node ids: re-meshing a cavity re-creates
    // nodes at the same places under new ids, and the retry level must still grow.
    let mut levels: HashMap<[u64; 3], u32> = HashMap::new();
    let mut defers: FaceMap<u32> = FaceMap::default();
    let mut backtracks = 0usize;
    // The back-tracks after which closing is next tried, and their step (`CLOSE_EVERY` first).
    let (mut close_at, mut close_every) = (CLOSE_EVERY, CLOSE_EVERY);
    let max_backtracks = 100 + input.boundary.len() / 8;
    // Where the front was last stuck: the place a front that runs out of work names.
    let mut stuck_at = None;
    let mut steps = 0usize;
    while let Some(fid) = st.front.pop() {
        steps += 1;
        work.spend(work::FACE_TAKEN);
        if steps.is_multiple_of(MEASURE_EVERY) {
            for t in &st.tets[built.0..] {
                built.1 += tet_volume(t, &st.nodes);
            }
            built.0 = st.tets.len();
            let filled = (built.1 / volume).min(1.0);
            if closing.is_none() && filled >= CLOSING_AT {
                closing = Some(st.front.n_alive.max(1));
            }
            let closed = closing.map_or(0.0, |at| 1.0 - st.front.n_alive as f64 / at as f64);
            bar.reach(FILLING_SHARE * filled + (1.0 - FILLING_SHARE) * closed);
        }
        if work.exhausted(st.fullest) {
            if st.close(size) {
                break;
            }
            let f = st.front.faces[fid as usize];
            return Err(gave_up(
                &st,
                backtracks,
                stuck_at.unwrap_or_else(|| centroid(&f, &st.nodes)),
            ));
        }
        let f = st.front.faces[fid as usize];
        let mut key = f;
        key.sort_unstable();
        let deferred = defers.get(&key).copied().unwrap_or(0);
        let q_min = MIN_QUALITY.get(deferred as usize).copied();
        if let Some(c) = st.find_apex(fid, q_min.unwrap_or(0.0)) {
            st.build(fid, c);
            continue;
        }
        if q_min.is_some() && (deferred as usize) + 1 < MIN_QUALITY.len() {
            // Defer: other faces advance meanwhile and often make a good apex available.
            defers.insert(key, deferred + 1);
            let k = mean_edge(&f, &st.nodes) * (1u64 << (2 * (deferred + 1))) as f64;
            st.front.requeue(fid, k);
            continue;
        }
        let level = levels
            .entry(centroid(&f, &st.nodes).map(f64::to_bits))
            .or_insert(0);
        // A flat pocket (see `flat_apex`) that back-tracking has already re-created here is
        // closed: back-tracking would only re-create it again. (Not on the first time, so that
        // regions that back-tracking does clear keep their meshes.)
        if *level >= POCKET_LEVEL
            && let Some(c) = st.flat_apex(fid, f, true)
        {
            st.build(fid, c);
            continue;
        }
        *level += 1;
        backtracks += 1;
        let at = centroid(&f, &st.nodes);
        stuck_at = Some(at);
        // Closing by the Delaunay method once the front is nearly done and keeps back-tracking:
        // its last gaps are where it fails, and each back-track re-meshes a ball round one.
        // A failed try waits twice as many back-tracks as the last before the next: tries that
        // keep failing (a front far from done) cost a bounded share of its work.
        if closing.is_some() && backtracks >= close_at {
            if st.close(size) {
                break;
            }
            close_every *= 2;
            close_at = backtracks + close_every;
        }
        if *level > MAX_LEVEL || backtracks > max_backtracks {
            // Last resort before giving up: a Steiner point low over the stuck face.
            let m = centroid(&f, &st.nodes);
            let hc = st
                .target(mean_edge(&f, &st.nodes), &m)
                .max(0.8 * st.bg.size_at(&m));
            if let Some(c) = st.steiner_apex(fid, f, hc) {
                st.build(fid, c);
                continue;
            }
            // Then a flat gap: a front face lying (to rounding) on the boundary surface it must
            // close against, which only a near-zero-volume tetrahedron can fill.
            if let Some(c) = st.flat_apex(fid, f, false) {
                st.build(fid, c);
                continue;
            }
            if st.close(size) {
                break;
            }
            return Err(TetMeshError::new(
                st.name,
                format!(
                    "the front is stuck at face {f:?} ({:?}, {:?}, {:?}): no valid apex after {backtracks} back-tracks",
                    st.nodes[f[0] as usize], st.nodes[f[1] as usize], st.nodes[f[2] as usize]
                ),
                Some(at),
            )
            .of_the_front());
        }
        let lvl = *level;
        st.backtrack(fid, lvl);
    }
    let mut nodes = st.nodes;
    let mut tets = Vec::with_capacity(st.tets.len());
    for (t, alive) in st.tets.iter().zip(&st.tet_alive) {
        if *alive {
            tets.push(*t);
        }
    }
    nodes.shrink_to_fit();
    Ok(RawMesh {
        nodes,
        tets,
        backtracks,
    })
}

/// The error of a front that spent its region's work (`work`) without closing; `at` is where it
/// was last stuck, else where it stood.
fn gave_up(st: &State<'_>, backtracks: usize, at: P) -> TetMeshError {
    let why = if backtracks > 0 {
        format!("{backtracks} back-tracks, the last here")
    } else {
        "no back-track: the candidate apexes here are many and few are valid".to_string()
    };
    TetMeshError::new(
        st.name,
        format!(
            "the front gave up after {} units of work, all it was allowed (it holds {} tets, \
             with {} faces left open): {why}",
            st.work.spent(),
            st.alive,
            st.front.n_alive
        ),
        Some(at),
    )
    .of_the_front()
}

fn tet_volume(t: &[u32; 4], pts: &[P]) -> f64 {
    let [a, b, c, d] = t.map(|i| pts[i as usize]);
    dot(&sub(&b, &a), &cross(&sub(&c, &a), &sub(&d, &a))).abs() / 6.0
}

fn mean_edge(t: &[u32; 3], pts: &[P]) -> f64 {
    let [a, b, c] = t.map(|i| pts[i as usize]);
    (dist(&a, &b) + dist(&b, &c) + dist(&c, &a)) / 3.0
}

#[inline]
fn dist2(a: &P, b: &P) -> f64 {
    (a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)
}

fn centroid(f: &[u32; 3], pts: &[P]) -> P {
    let [a, b, c] = f.map(|i| pts[i as usize]);
    [
        (a[0] + b[0] + c[0]) / 3.0,
        (a[1] + b[1] + c[1]) / 3.0,
        (a[2] + b[2] + c[2]) / 3.0,
    ]
}

impl State<'_> {
    /// Fills what is still open by the Delaunay method (`closing`), when the work allows it and
    /// the front built something: whether it did (the tets are then the mesh's, the front is
    /// done). Asked as the front gives up, and before, every so many back-tracks, once
    /// [`CLOSING_AT`] of the volume is filled. A piece it cannot fill (walls at a few degrees to
    /// one another, where the front gave up) is widened by the tets round its vertices, up to
    /// [`CLOSING_ROUNDS`] times, while such pieces hold at most [`CLOSING_WIDENS`] faces in all:
    /// the front's own tets there go, and the walls with them (only when the fill succeeds: a
    /// failed try leaves the front as it was, so a front that would close on its own still
    /// does).
    fn close(&mut self, size: &SizeField) -> bool {
        if !self.work.may_close() || self.alive == 0 {
            return false;
        }
        let open: Vec<[u32; 3]> = (0..self.front.faces.len())
            .filter(|&k| self.front.alive[k])
            .map(|k| self.front.faces[k])
            .collect();
        // The tets the widening takes (sorted, each once): taken only if the fill succeeds, so
        // a failed try leaves the front as it was.
        let mut taken: Vec<u32> = Vec::new();
        for round in 0..=CLOSING_ROUNDS {
            let faces = self.open_without(&open, &taken);
            match closing::fill_open(self.name, &self.nodes, &faces, size) {
                Ok((nodes, tets)) => {
                    for &t in &taken {
                        self.delete_tet(t);
                    }
                    self.nodes.extend(nodes);
                    self.tet_alive.extend(tets.iter().map(|_| true));
                    self.tets.extend(tets);
                    return true;
                }
                Err(failed) if round == CLOSING_ROUNDS || failed.len() > CLOSING_WIDENS => {
                    return false;
                }
                Err(failed) => {
                    for &v in failed.iter().flatten() {
                        let live = self.node_tets[v as usize].iter();
                        taken.extend(live.filter(|&&t| self.tet_alive[t as usize]));
                    }
                    taken.sort_unstable();
                    taken.dedup();
                }
            }
        }
        false
    }

    /// The open faces `open` as deleting the tets `taken` would leave them (`delete_tet`: a face
    /// of a taken tet closes the open face it meets, else opens facing into the tet; an embedded
    /// face stays open on both sides), in a deterministic order.
    fn open_without(&self, open: &[[u32; 3]], taken: &[u32]) -> Vec<[u32; 3]> {
        let mut faces: Vec<Option<[u32; 3]>> = open.iter().map(|&f| Some(f)).collect();
        let mut at: HashMap<[u32; 3], usize> = (open.iter().enumerate())
            .map(|(k, &f)| (canon(f), k))
            .collect();
        for &t in taken {
            for fo in outward_faces(self.tets[t as usize]) {
                let mut k = fo;
                k.sort_unstable();
                if !self.constrained.contains(&k)
                    && let Some(i) = at.remove(&canon(fo))
                {
                    faces[i] = None;
                    continue;
                }
                let inward = [fo[0], fo[2], fo[1]];
                at.insert(canon(inward), faces.len());
                faces.push(Some(inward));
            }
        }
        faces.into_iter().flatten().collect()
    }

    fn add_face(&mut self, f: [u32; 3]) {
        let key = mean_edge(&f, &self.nodes);
        self.front.add(f, key, &self.nodes);
    }

    /// Local target size for a face of mean edge `le` centred at `m`: the background size there,
    /// kept within a factor of the face's own size so the tetrahedron stays well shaped.
    fn target(&self, le: f64, m: &P) -> f64 {
        self.bg.size_at(m).clamp(0.7 * le, 1.5 * le)
    }

    fn find_apex(&mut self, fid: u32, q_min: f64) -> Option<Cand> {
        let f = self.front.faces[fid as usize];
        let [a, b, c] = f.map(|i| self.nodes[i as usize]);
        let m = centroid(&f, &self.nodes);
        let nu = unit_normal(&a, &b, &c)?;
        let le = mean_edge(&f, &self.nodes);
        let h = self.target(le, &m);
        let r2 = (dist(&m, &a).powi(2) + dist(&m, &b).powi(2) + dist(&m, &c).powi(2)) / 3.0;
        let height = (h * h - r2).max(0.09 * h * h).sqrt();
        let ideal = [
            m[0] + nu[0] * height,
            m[1] + nu[1] * height,
            m[2] + nu[2] * height,
        ];

        let mut tried: Vec<u32> = Vec::new();
        for (pass, &radius) in SEARCH_RADIUS.iter().enumerate() {
            let rad = radius * h.max(le);
            let (lo, hi) = if pass == 0 {
                // The first pass only looks at nodes within NEAR_IDEAL·h of the ideal apex and at
                // clearances around it: a box around the ideal apex finds every face that matters.
                let hc = h.max(0.8 * self.bg.size_at(&m));
                let r0 = (NEAR_IDEAL * h)
                    .max(NEW_NODE_CLEARANCE * hc)
                    .max(FACE_CLEARANCE * hc);
                (ideal.map(|x| x - r0), ideal.map(|x| x + r0))
            } else {
                (
                    [0, 1, 2].map(|k| m[k].min(ideal[k]) - rad),
                    [0, 1, 2].map(|k| m[k].max(ideal[k]) + rad),
                )
            };
            let mut near = std::mem::take(&mut self.scratch);
            let mut cand_nodes: Vec<u32>;
            if pass == 0 {
                self.front.query(&lo, &hi, &mut near);
                // Each node once (a stamp per node, not a sort: every use below is
                // order-independent — minima, and a ranking sorted by score then index).
                cand_nodes = Vec::with_capacity(near.len());
                self.seen_gen = self.seen_gen.wrapping_add(1);
                if self.seen_gen == 0 {
                    self.seen.iter_mut().for_each(|s| *s = 0);
                    self.seen_gen = 1;
                }
                if self.seen.len() < self.nodes.len() {
                    self.seen.resize(self.nodes.len(), 0);
                }
                for &g in &near {
                    for w in self.front.faces[g as usize] {
                        let s = &mut self.seen[w as usize];
                        if *s != self.seen_gen {
                            *s = self.seen_gen;
                            cand_nodes.push(w);
                        }
                    }
                }
            } else {
                // The wide search scans the node grid; the faces `clear_of_faces` needs are
                // those near the segment from the face to the ideal apex.
                cand_nodes = Vec::new();
                self.front.query_nodes(&lo, &hi, &mut cand_nodes);
                let hc = h.max(0.8 * self.bg.size_at(&m));
                let r = 0.5 * FACE_CLEARANCE * hc;
                self.front.query(
                    &[0, 1, 2].map(|k| m[k].min(ideal[k]) - r),
                    &[0, 1, 2].map(|k| m[k].max(ideal[k]) + r),
                    &mut near,
                );
            }
            self.work.spend((cand_nodes.len() + near.len()) as u64);
            self.scratch = near;
            let mut cands: Vec<(f64, u32, Cand, f64)> = Vec::new();
            // Squared distances throughout (same comparisons, no roots).
            let mut nearest2 = f64::INFINITY;
            let (far2, near_ideal2) = ((rad + h) * (rad + h), (NEAR_IDEAL * h) * (NEAR_IDEAL * h));
            for &w in &cand_nodes {
                if f.contains(&w) {
                    continue;
                }
                let p = self.nodes[w as usize];
                let dw2 = dist2(&p, &ideal);
                nearest2 = nearest2.min(dw2);
                if dist2(&p, &m) > far2 || (pass == 0 && dw2 > near_ideal2) {
                    continue;
                }
                // Ranking only (validity is decided exactly in `valid`): a candidate the float
                // measure finds flat or inverted is skipped before the costlier exact test, which
                // coplanar boundary nodes would send down its slow exact path.
                let q = rank_ratio3(&a, &b, &c, &p);
                if q < FLAT * FLAT * FLAT || orient3d(&a, &b, &c, &p) != Orientation::Positive {
                    continue;
                }
                cands.push((q, w, Cand::Node(w), q));
            }
            if pass == 0 {
                // Clearances use the background size so that small faces close on existing
                // nodes instead of seeding ever smaller ones.
                let hc = h.max(0.8 * self.bg.size_at(&m));
                if nearest2 > (NEW_NODE_CLEARANCE * hc).powi(2)
                    && self.clear_of_faces(&ideal, fid, FACE_CLEARANCE * hc)
                {
                    let q = rank_ratio3(&a, &b, &c, &ideal);
                    cands.push((q * PREF3, u32::MAX, Cand::New(ideal), q));
                }
            } else {
                for frac in [0.6, 0.35, 0.2, 0.1] {
                    let p = [
                        m[0] + nu[0] * height * frac,
                        m[1] + nu[1] * height * frac,
                        m[2] + nu[2] * height * frac,
                    ];
                    let hc = h.max(0.8 * self.bg.size_at(&m));
                    let closest2 = |ws: &[u32]| {
                        ws.iter()
                            .map(|&w| dist2(&self.nodes[w as usize], &p))
                            .fold(f64::INFINITY, f64::min)
                    };
                    let dc2 = closest2(&cand_nodes);
                    let near_node = dc2 < (0.3 * hc).powi(2);
                    let tiny = dc2.min(closest2(&f)) < (MIN_NODE_GAP * hc).powi(2);
                    if tiny {
                        continue;
                    }
                    // On the last attempt before back-tracking, any valid point will do.
                    if q_min > 0.0
                        && (near_node || !self.clear_of_faces(&p, fid, 0.5 * FACE_CLEARANCE * hc))
                    {
                        continue;
                    }
                    let q = rank_ratio3(&a, &b, &c, &p);
                    cands.push((q * PREF3 * 0.125, u32::MAX, Cand::New(p), q));
                }
            }
            cands.sort_by(|x, y| y.0.total_cmp(&x.0).then(x.1.cmp(&y.1)));
            // Before the last attempt only the best few are tested: a face whose best candidates
            // all fail is deferred, and the front around it usually offers a good apex later.
            let mut budget = if q_min > 0.0 { MAX_TRIES } else { usize::MAX };
            let q_min3 = q_min * q_min * q_min;
            for &(_, _, cand, q) in &cands {
                if q < q_min3 {
                    continue;
                }
                if let Cand::Node(w) = cand {
                    // Already tested (and failed) on the first pass.
                    if pass > 0 && tried.contains(&w) {
                        continue;
                    }
                    tried.push(w);
                }
                if budget == 0 {
                    break;
                }
                budget -= 1;
                if self.valid(fid, f, cand) {
                    return Some(cand);
                }
            }
        }
        None
    }

    /// Last resort before back-tracking (thin layers: the opposite front is closer than any
    /// standard candidate): a Steiner point low over the face. Candidates sit above interior
    /// points of the face at decreasing heights (down to a tiny fraction of the local size, for
    /// gaps far thinner than the faces), and part-way from the face towards each nearby front
    /// node (the centre of the cavity lies in that direction). Ranked by the float mean ratio;
    /// each is accepted only by the exact validity test, so the tetrahedron is positive and
    /// crosses nothing — a flat one is left to the optimizer.
    fn steiner_apex(&mut self, fid: u32, f: [u32; 3], height: f64) -> Option<Cand> {
        let [a, b, c] = f.map(|i| self.nodes[i as usize]);
        let nu = unit_normal(&a, &b, &c)?;
        let mut pts: Vec<P> = Vec::new();
        const BARY: [[f64; 3]; 7] = [
            [1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0],
            [0.6, 0.2, 0.2],
            [0.2, 0.6, 0.2],
            [0.2, 0.2, 0.6],
            [0.2, 0.4, 0.4],
            [0.4, 0.2, 0.4],
            [0.4, 0.4, 0.2],
        ];
        for frac in STEINER_HEIGHTS {
            let t = height * frac;
            for w in &BARY {
                pts.push([0, 1, 2].map(|k| w[0] * a[k] + w[1] * b[k] + w[2] * c[k] + nu[k] * t));
            }
        }
        let m = centroid(&f, &self.nodes);
        let r = 3.0 * height.max(mean_edge(&f, &self.nodes));
        let mut near = std::mem::take(&mut self.scratch);
        self.front
            .query(&m.map(|x| x - r), &m.map(|x| x + r), &mut near);
        let mut others: Vec<u32> = near
            .iter()
            .flat_map(|&g| self.front.faces[g as usize])
            .filter(|w| !f.contains(w))
            .collect();
        self.scratch = near;
        others.sort_unstable();
        others.dedup();
        for &w in &others {
            let q = self.nodes[w as usize];
            if orient3d(&a, &b, &c, &q) != Orientation::Positive {
                continue;
            }
            for s in [0.5, 0.3, 0.15, 0.05] {
                pts.push([0, 1, 2].map(|k| m[k] + (q[k] - m[k]) * s));
            }
        }
        // Never a node nearly on top of another: that would seed ever smaller faces.
        let clear = STEINER_GAP * height;
        let mut cands: Vec<(f64, usize)> = pts
            .iter()
            .enumerate()
            .filter(|(_, p)| p.iter().all(|x| x.is_finite()))
            .filter(|(_, p)| {
                others
                    .iter()
                    .chain(&f)
                    .all(|&w| dist(&self.nodes[w as usize], p) >= clear)
            })
            .map(|(i, p)| (rank_ratio3(&a, &b, &c, p), i))
            .filter(|(q, _)| *q > FLAT * FLAT * FLAT)
            .collect();
        cands.sort_by(|x, y| y.0.total_cmp(&x.0).then(x.1.cmp(&y.1)));
        for &(_, i) in &cands {
            let cand = Cand::New(pts[i]);
            if self.valid(fid, f, cand) {
                return Some(cand);
            }
        }
        None
    }

    /// The very last resort: an existing front node that makes an exactly positive but nearly
    /// flat tetrahedron with the stuck face — the candidates the `FLAT` cut skips everywhere
    /// else. Needed where a front face lies within rounding of the boundary triangles behind it:
    /// a boundary quad split along one diagonal, nearly coplanar, and a tetrahedron that took
    /// the other diagonal as a face leaves a gap of volume ~1e-14 that no Steiner point fits in
    /// and that back-tracking re-creates (the same face picks the same best apex again). The
    /// sliver closing the gap is accepted by the exact validity test like any other tetrahedron
    /// and left to the optimizer's flips. Nodes are ranked by their float mean ratio, then by
    /// distance, then by index. With `pocket_only`, only apexes that close a pocket
    /// (`closes_pocket`) count: tried before every back-track, since a flat pocket is exactly
    /// what back-tracking re-creates.
    fn flat_apex(&mut self, fid: u32, f: [u32; 3], pocket_only: bool) -> Option<Cand> {
        let [a, b, c] = f.map(|i| self.nodes[i as usize]);
        let m = centroid(&f, &self.nodes);
        let r = 1.5 * mean_edge(&f, &self.nodes);
        if !r.is_finite() {
            return None;
        }
        let mut ws = Vec::new();
        self.front
            .query_nodes(&m.map(|x| x - r), &m.map(|x| x + r), &mut ws);
        let mut cands: Vec<(f64, f64, u32)> = ws
            .into_iter()
            .filter(|w| !f.contains(w))
            .filter(|&w| !pocket_only || self.closes_pocket(f, w))
            .filter(|&w| {
                let p = &self.nodes[w as usize];
                dist(p, &m) <= r && orient3d(&a, &b, &c, p) == Orientation::Positive
            })
            .map(|w| {
                let p = &self.nodes[w as usize];
                (rank_ratio3(&a, &b, &c, p), dist2(p, &m), w)
            })
            .collect();
        cands.sort_by(|x, y| {
            y.0.total_cmp(&x.0)
                .then(x.1.total_cmp(&y.1))
                .then(x.2.cmp(&y.2))
        });
        for &(_, _, w) in &cands {
            if self.valid(fid, f, Cand::Node(w)) {
                return Some(Cand::Node(w));
            }
        }
        None
    }

    /// Would the tetrahedron `f + w` close a pocket of the front: are at least two of its new
    /// faces already on the front, facing it? Then it adds at most one face.
    fn closes_pocket(&self, f: [u32; 3], w: u32) -> bool {
        let [a, b, c] = f;
        [[a, w, b], [b, w, c], [c, w, a]]
            .iter()
            .filter(|r| self.front.find(**r).is_some())
            .count()
            >= 2
    }

    /// Is `p` at least `clear` away from every front face near it (in the last apex search box)
    /// other than `fid`? (A float heuristic steering node placement, not a validity decision.)
    fn clear_of_faces(&self, p: &P, fid: u32, clear: f64) -> bool {
        // `scratch` holds the faces near the apex search box (the caller's last query).
        for &g in &self.scratch {
            if g == fid {
                continue;
            }
            let [a, b, c] = self.front.faces[g as usize].map(|i| self.nodes[i as usize]);
            // A triangle whose bounding box is farther than `clear` is farther than `clear`.
            if (0..3).any(|k| {
                p[k] + clear < a[k].min(b[k]).min(c[k]) || p[k] - clear > a[k].max(b[k]).max(c[k])
            }) {
                continue;
            }
            if point_triangle_distance(p, &a, &b, &c) < clear {
                return false;
            }
        }
        true
    }

    /// Exact validity of the tetrahedron `f + cand`.
    fn valid(&mut self, fid: u32, f: [u32; 3], cand: Cand) -> bool {
        let d = match cand {
            Cand::Node(w) => w,
            Cand::New(p) => {
                if !p.iter().all(|x| x.is_finite()) {
                    return false;
                }
                self.nodes.push(p);
                (self.nodes.len() - 1) as u32
            }
        };
        self.work.spend(work::APEX_TEST);
        let ok = self.valid_with(fid, f, d);
        if let Cand::New(_) = cand {
            self.nodes.pop();
        }
        ok
    }

    fn valid_with(&mut self, fid: u32, f: [u32; 3], d: u32) -> bool {
        let [a, b, c] = f;
        let pts = &self.nodes;
        let (pa, pb, pc, pd) = (
            &pts[a as usize],
            &pts[b as usize],
            &pts[c as usize],
            &pts[d as usize],
        );
        if orient3d(pa, pb, pc, pd) != Orientation::Positive {
            return false;
        }
        let tet = [a, b, c, d];
        // The tet's outward faces; the last three are the new faces `abd`, `bcd`, `cad`.
        let planes = outward_faces(tet);
        for nf in &planes[1..] {
            // The same orientation already on the front means overlap — unless the reverse is
            // there too: both sides of an open embedded face, and the tet closes the near one.
            if self.front.find(*nf).is_some() && self.front.find([nf[0], nf[2], nf[1]]).is_none() {
                return false;
            }
        }
        let (lo, hi) = bbox_of([pa, pb, pc, pd].into_iter());
        let new_boxes = [1, 2, 3].map(|k| bbox_of(planes[k].iter().map(|&i| &pts[i as usize])));
        let mut near = std::mem::take(&mut self.scratch2);
        self.front.query(&lo, &hi, &mut near);
        self.signs.start(self.nodes.len());
        let mut ok = true;
        for &g in &near {
            if g == fid {
                continue;
            }
            let gv = self.front.faces[g as usize];
            let (glo, ghi) = bbox_of(gv.iter().map(|&i| &self.nodes[i as usize]));
            // Bounding boxes first (exact comparisons): triangles with disjoint boxes do not meet.
            if (0..3).any(|k| glo[k] > hi[k] || ghi[k] < lo[k]) {
                continue;
            }
            // Exact sides of g's vertices against the tet's four planes (+1 outside), shared by
            // every face around a node.
            let sg = gv.map(|w| self.signs.of(w, &tet, &planes, &self.nodes));
            // All of g strictly outside one plane, but for the tet vertices it shares on that
            // plane: g meets the closed tet at most in shared vertices or a shared edge.
            if (0..4).any(|k| (0..3).all(|i| sg[i][k] > 0 || planes[k].contains(&gv[i]))) {
                continue;
            }
            // A front node in the closed tet (on no plane's outer side).
            if (0..3).any(|i| !tet.contains(&gv[i]) && sg[i].iter().all(|&s| s <= 0)) {
                ok = false;
                break;
            }
            for k in 1..4 {
                let nf = planes[k];
                let (flo, fhi) = &new_boxes[k - 1];
                if same_set(&nf, &gv) || (0..3).any(|j| glo[j] > fhi[j] || ghi[j] < flo[j]) {
                    continue;
                }
                let ou = [0, 1, 2].map(|i| orientation_of(sg[i][k]));
                let (nf, gv) = (Tri::of(nf, &self.nodes), Tri::of(gv, &self.nodes));
                if triangle_contact_with(&nf, &gv, ou) != Contact::None {
                    ok = false;
                    break;
                }
            }
            if !ok {
                break;
            }
        }
        self.scratch2 = near;
        ok
    }

    fn build(&mut self, fid: u32, cand: Cand) {
        let d = match cand {
            Cand::Node(w) => w,
            Cand::New(p) => {
                self.nodes.push(p);
                self.node_tets.push(Vec::new());
                let v = (self.nodes.len() - 1) as u32;
                self.front.add_node(v, &p);
                v
            }
        };
        let [a, b, c] = self.front.faces[fid as usize];
        self.front.remove(fid);
        for nf in [[a, b, d], [b, c, d], [c, a, d]] {
            match self.front.find([nf[0], nf[2], nf[1]]) {
                Some(r) => self.front.remove(r),
                None => self.add_face(nf),
            }
        }
        let t = self.tets.len() as u32;
        self.tets.push([a, b, c, d]);
        self.tet_alive.push(true);
        self.alive += 1;
        self.fullest = self.fullest.max(self.alive);
        for v in [a, b, c, d] {
            self.node_tets[v as usize].push(t);
        }
    }

    /// Delete the tetrahedra around a stuck face — those touching its vertices, plus every tet
    /// with a node within `level` local sizes of it — and restore the front around the cavity.
    fn backtrack(&mut self, fid: u32, level: u32) {
        let f = self.front.faces[fid as usize];
        let m = centroid(&f, &self.nodes);
        let h = self.target(mean_edge(&f, &self.nodes), &m);
        let rad = h * level as f64;
        let mut del: Vec<u32> = Vec::new();
        for &v in &f {
            del.extend(
                self.node_tets[v as usize]
                    .iter()
                    .copied()
                    .filter(|&t| self.tet_alive[t as usize]),
            );
        }
        if level > 1 {
            // Tets with a node within `rad`: the live tets around every such node (`node_tets`
            // lists only live tets), the nodes found through the node grid.
            let mut near = Vec::new();
            self.front
                .nodes_near(&m.map(|x| x - rad), &m.map(|x| x + rad), &mut near);
            for &v in &near {
                if dist(&self.nodes[v as usize], &m) <= rad {
                    del.extend_from_slice(&self.node_tets[v as usize]);
                }
            }
        }
        del.sort_unstable();
        del.dedup();
        for &t in &del {
            self.delete_tet(t);
        }
        let key = mean_edge(&f, &self.nodes);
        self.front.requeue(fid, key);
    }

    fn delete_tet(&mut self, t: u32) {
        let tet = self.tets[t as usize];
        self.tet_alive[t as usize] = false;
        self.alive -= 1;
        for fo in outward_faces(tet) {
            let mut k = fo;
            k.sort_unstable();
            if self.constrained.contains(&k) {
                // An embedded face stays in the front on both sides.
                self.add_face([fo[0], fo[2], fo[1]]);
                continue;
            }
            match self.front.find(fo) {
                Some(id) => self.front.remove(id),
                None => self.add_face([fo[0], fo[2], fo[1]]),
            }
        }
        for v in tet {
            self.node_tets[v as usize].retain(|&x| x != t);
        }
    }
}

/// The cube of the normalised mean ratio of `abcd` (signed like the volume), without a root:
/// `1728·(3V)² / (Σ l²)³`. It ranks every candidate apex, so it is on the hot path; the cube is
/// monotone, so rankings and thresholds (compared cubed) are those of `quality::mean_ratio`. A
/// float measure for ranking only; validity is decided exactly elsewhere.
#[inline]
fn rank_ratio3(a: &P, b: &P, c: &P, d: &P) -> f64 {
    let sub = |x: &P, y: &P| [x[0] - y[0], x[1] - y[1], x[2] - y[2]];
    let l2 = |v: &P| v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    let (u, v, w) = (sub(b, a), sub(c, a), sub(d, a));
    let vol = (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
        + u[2] * (v[0] * w[1] - v[1] * w[0]))
        / 6.0;
    let s = l2(&u) + l2(&v) + l2(&w) + l2(&sub(c, b)) + l2(&sub(d, b)) + l2(&sub(d, c));
    if s <= 0.0 || !s.is_finite() {
        return 0.0;
    }
    let t = 3.0 * vol;
    let m = 1728.0 * (t * t) / (s * s * s);
    if vol < 0.0 { -m } else { m }
}

#[inline]
fn same_set(a: &[u32; 3], b: &[u32; 3]) -> bool {
    b.contains(&a[0]) && b.contains(&a[1]) && b.contains(&a[2])
}

/// Euclidean distance from `p` to the closed triangle `abc` (float).
fn point_triangle_distance(p: &P, a: &P, b: &P, c: &P) -> f64 {
    let sub = |x: &P, y: &P| [x[0] - y[0], x[1] - y[1], x[2] - y[2]];
    let dot = |x: &P, y: &P| x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
    let ab = sub(b, a);
    let ac = sub(c, a);
    let ap = sub(p, a);
    let d1 = dot(&ab, &ap);
    let d2 = dot(&ac, &ap);
    let at = |s: f64, t: f64| {
        [
            a[0] + ab[0] * s + ac[0] * t,
            a[1] + ab[1] * s + ac[1] * t,
            a[2] + ab[2] * s + ac[2] * t,
        ]
    };
    let q = if d1 <= 0.0 && d2 <= 0.0 {
        *a
    } else {
        let bp = sub(p, b);
        let d3 = dot(&ab, &bp);
        let d4 = dot(&ac, &bp);
        if d3 >= 0.0 && d4 <= d3 {
            *b
        } else {
            let vc = d1 * d4 - d3 * d2;
            if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
                let v = d1 / (d1 - d3);
                at(v, 0.0)
            } else {
                let cp = sub(p, c);
                let d5 = dot(&ab, &cp);
                let d6 = dot(&ac, &cp);
                if d6 >= 0.0 && d5 <= d6 {
                    *c
                } else {
                    let vb = d5 * d2 - d1 * d6;
                    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
                        let w = d2 / (d2 - d6);
                        at(0.0, w)
                    } else {
                        let va = d3 * d6 - d5 * d4;
                        if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
                            let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
                            [
                                b[0] + (c[0] - b[0]) * w,
                                b[1] + (c[1] - b[1]) * w,
                                b[2] + (c[2] - b[2]) * w,
                            ]
                        } else {
                            let denom = 1.0 / (va + vb + vc);
                            let v = vb * denom;
                            let w = vc * denom;
                            at(v, w)
                        }
                    }
                }
            }
        }
    };
    dist(p, &q)
}

/// The unit normal of triangle `a b c` (right-handed), or `None` when it is degenerate. A float
/// direction for placing candidate apexes; validity is decided exactly elsewhere.
fn unit_normal(a: &P, b: &P, c: &P) -> Option<P> {
    let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    let n = [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ];
    let nl = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    if nl <= 0.0 || !nl.is_finite() {
        return None;
    }
    Some(n.map(|x| x / nl))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A cube of side 10 split into 5 x 5 squares per side, two triangles each, outward.
    fn cube() -> RegionInput {
        let (vertices, boundary) = test_support::shapes::gridded_cube(5, 10.0);
        RegionInput {
            name: "cube".into(),
            vertices,
            boundary,
            ..RegionInput::default()
        }
    }

    #[test]
    fn a_meshing_front_spends_well_under_its_budget_per_tetrahedron() {
        let input = cube();
        let work = FrontWork::for_region(&input);
        let m = advance_front(&input, &SizeField::default(), &work).expect("the cube meshes");
        assert!(m.tets.len() > 500, "{} tets", m.tets.len());
        let per_tet = work.spent() / m.tets.len() as u64;
        assert!(per_tet < work::PER_TET / 2, "{per_tet} units per tet");
    }

    #[test]
    fn a_front_out_of_work_gives_up_at_the_same_place_every_time() {
        let input = cube();
        let fail = || {
            let work = FrontWork::with(5_000, 0);
            advance_front(&input, &SizeField::default(), &work).expect_err("no work to mesh")
        };
        let e = fail();
        assert!(e.message.starts_with("the front gave up after"), "{e}");
        // The budget is the caller's (a hole's is a second's work, a region's a minute's).
        assert!(
            e.message.contains("units of work, all it was allowed"),
            "{e}"
        );
        let at = e.at.expect("a place");
        assert!(at.iter().all(|x| (0.0..=10.0).contains(x)), "{at:?}");
        assert_eq!(fail(), e);
    }
}
