//! The kernel: an incremental tetrahedralization (Bowyer–Watson) with adjacency and constraint
//! faces. A point is inserted by removing the cavity of tets whose circumsphere strictly contains
//! it (exact `insphere`) and starring the cavity's boundary from the point. Cavities never cross a
//! constraint face or the hull (a missing neighbour), and the cavity is shrunk until every
//! boundary face sees the point strictly (exact `orient3d`), so every new tet is positive whatever
//! the constraints do to the Delaunay property. Constraint edges (`edges`: recovered pieces of
//! embedded segments) are kept the same way: a cavity that would take every tet round one is
//! shrunk. Without constraints the result is the Delaunay tetrahedralization. Nothing here knows
//! about sizes or boundaries: callers pass the checks an insertion must pass (`Limits`).

use geom::predicates::{Orientation, cross, dot, insphere, sub};

use super::super::exact::orient3d;

mod edges;

pub type P = [f64; 3];
/// No neighbour (hull or removed) / dead tet marker.
pub const NONE: u32 = u32::MAX;

/// The face opposite each vertex of a positive tet, ordered so its normal points out of the tet.
pub const FACE: [[usize; 3]; 4] = [[1, 2, 3], [0, 3, 2], [0, 1, 3], [0, 2, 1]];

/// What an insertion must respect besides validity.
#[derive(Clone, Copy, Debug, Default)]
pub struct Limits {
    /// Reject the point if a vertex of its cavity is closer than this.
    pub min_dist: f64,
    /// Reject the point if it is closer than this to the plane of a cavity boundary face that is
    /// a constraint or on the hull, or to a constraint edge of the cavity.
    pub min_height: f64,
}

/// Why a point was not inserted.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Reject {
    /// The walk left the triangulation (across the hull).
    Outside,
    /// The point coincides with a vertex.
    Duplicate,
    /// The point lies on a constraint face or no valid cavity exists around it.
    NotVisible,
    /// `Limits` refused it.
    TooClose,
}

/// One tet slot. Everything a cavity's flood reads of a neighbour sits in one record (40
/// bytes), so visiting a tet costs one cache miss instead of one per array: the flood was bound
/// by those misses.
#[derive(Clone, Copy)]
pub struct Rec {
    /// Vertices, positively oriented; `[NONE; 4]` for a free slot.
    pub v: [u32; 4],
    /// `adj[i] = 4 u + j`: face `i` of this tet is face `j` of `u`; `NONE` on the hull.
    pub adj: [u32; 4],
    /// The last flood's stamp (see [`Tri::next_stamp`]).
    mark: u32,
    /// Bit `i`: face `i` is a constraint (cavities never cross it).
    pub cons: u8,
}

impl Rec {
    const FREE: Rec = Rec {
        v: [NONE; 4],
        adj: [NONE; 4],
        mark: 0,
        cons: 0,
    };
}

pub struct Tri {
    pub pts: Vec<P>,
    /// The tet slots.
    pub t: Vec<Rec>,
    free: Vec<u32>,
    stamp: u32,
    /// A live tet near the last insertion: where walks start by default.
    pub hint: u32,
    walk_turn: usize,
    cavity: Vec<u32>,
    /// A flood level's neighbours, as `4 u + j`.
    across: Vec<u32>,
    bnd: Vec<(u32, u8)>,
    keys: Vec<(u64, u32)>,
    /// Scratch hash table pairing `keys`.
    table: Vec<(u64, u32)>,
    /// The new tets of an insertion (vertices, outer neighbour, constraint), before they go in.
    recs: Vec<([u32; 4], u32, bool)>,
    /// Tets created by insertions, while `record` is on.
    pub created: Vec<u32>,
    pub record: bool,
    /// Edges no insertion may remove (see `edges`).
    cons_edges: edges::EdgeSet,
}

impl Tri {
    /// The single positive tet `super_tet` over `pts` (its four vertices must be in `pts`).
    pub fn new(pts: Vec<P>, super_tet: [u32; 4]) -> Self {
        Tri {
            pts,
            t: vec![Rec {
                v: super_tet,
                ..Rec::FREE
            }],
            free: Vec::new(),
            stamp: 0,
            hint: 0,
            walk_turn: 0,
            cavity: Vec::new(),
            across: Vec::new(),
            bnd: Vec::new(),
            keys: Vec::new(),
            table: Vec::new(),
            recs: Vec::new(),
            created: Vec::new(),
            record: false,
            cons_edges: Default::default(),
        }
    }

    /// Room for `n` more tets without reallocating.
    pub fn reserve(&mut self, n: usize) {
        self.t.reserve(n);
    }

    #[inline]
    pub fn alive(&self, t: u32) -> bool {
        self.t[t as usize].v[0] != NONE
    }

    /// The outward face `i` of tet `t` as vertex ids.
    #[inline]
    pub fn face(&self, t: u32, i: usize) -> [u32; 3] {
        let tv = self.t[t as usize].v;
        let f = FACE[i];
        [tv[f[0]], tv[f[1]], tv[f[2]]]
    }

    /// Remove tet `t`: its neighbours see the hull there.
    pub fn kill(&mut self, t: u32) {
        for i in 0..4 {
            let n = self.t[t as usize].adj[i];
            if n != NONE {
                self.t[(n >> 2) as usize].adj[(n & 3) as usize] = NONE;
            }
        }
        self.t[t as usize].v = [NONE; 4];
        self.t[t as usize].adj = [NONE; 4];
        self.t[t as usize].cons = 0;
        self.free.push(t);
    }

    /// A slot for the tet `tv` (a free one first), with no neighbours and no constraint.
    pub fn alloc(&mut self, tv: [u32; 4]) -> u32 {
        let id = match self.free.pop() {
            Some(id) => id,
            None => {
                self.t.push(Rec::FREE);
                (self.t.len() - 1) as u32
            }
        };
        let r = &mut self.t[id as usize];
        r.v = tv;
        r.adj = [NONE; 4];
        r.cons = 0;
        id
    }

    /// Add positive tets that fill holes of the triangulation: their faces are linked to each
    /// other and to `surface` (sorted face → `4 u + j` of the kept tet across it); faces in
    /// `constraints` (sorted) are marked; the rest are hull.
    pub fn link_in(
        &mut self,
        tets: &[[u32; 4]],
        surface: &std::collections::HashMap<[u32; 3], u32>,
        constraints: &std::collections::HashSet<[u32; 3]>,
    ) {
        let mut open: std::collections::HashMap<[u32; 3], u32> = Default::default();
        for &tv in tets {
            let id = self.alloc(tv);
            for i in 0..4 {
                let mut key = self.face(id, i);
                key.sort_unstable();
                if constraints.contains(&key) {
                    self.t[id as usize].cons |= 1 << i;
                }
                let me = 4 * id + i as u32;
                let other = open.remove(&key).or_else(|| surface.get(&key).copied());
                match other {
                    Some(o) => {
                        self.t[id as usize].adj[i] = o;
                        self.t[(o >> 2) as usize].adj[(o & 3) as usize] = me;
                    }
                    None => {
                        open.insert(key, me);
                    }
                }
            }
            self.hint = id;
        }
    }

    /// Mark face `i` of `t` (and its twin) as a constraint.
    pub fn constrain(&mut self, t: u32, i: usize) {
        self.t[t as usize].cons |= 1 << i;
        let n = self.t[t as usize].adj[i];
        if n != NONE {
            self.t[(n >> 2) as usize].cons |= 1 << (n & 3);
        }
    }

    pub fn live_tets(&self) -> impl Iterator<Item = u32> + '_ {
        (0..self.t.len() as u32).filter(move |&t| self.alive(t))
    }

    /// A fresh even stamp `s`: a flood marks the tets it takes `s` and those it refused `s + 1`.
    fn next_stamp(&mut self) -> u32 {
        self.stamp = self.stamp.wrapping_add(2);
        if self.stamp < 2 {
            self.t.iter_mut().for_each(|r| r.mark = 0);
            self.stamp = 2;
        }
        self.stamp
    }

    /// Walk from `start` towards `p`; the tet containing `p` (closed), or `Outside` if the walk
    /// has to cross the hull. A floating-point walk comes near `p` first (it never crosses the face it came through);
    /// the exact walk then decides from where it stopped, so the float only chooses the path.
    pub fn locate(&mut self, p: &P, start: u32) -> Result<u32, Reject> {
        let mut t = if start != NONE && self.alive(start) {
            start
        } else {
            self.any_live().ok_or(Reject::Outside)?
        };
        let mut came = 4;
        for _ in 0..FLOAT_WALK {
            let tv = self.t[t as usize].v;
            self.walk_turn = self.walk_turn.wrapping_add(1);
            let next = (0..4).map(|jj| (jj + self.walk_turn) & 3).find(|&i| {
                let f = FACE[i];
                i != came
                    && above(
                        &self.pts[tv[f[0]] as usize],
                        &self.pts[tv[f[1]] as usize],
                        &self.pts[tv[f[2]] as usize],
                        p,
                    )
            });
            let Some(i) = next else { break };
            let n = self.t[t as usize].adj[i];
            if n == NONE {
                break;
            }
            t = n >> 2;
            came = (n & 3) as usize;
        }
        let cap = 64 + 4 * self.t.len();
        for _ in 0..cap {
            let tv = self.t[t as usize].v;
            self.walk_turn = self.walk_turn.wrapping_add(1);
            let mut next = None;
            for jj in 0..4 {
                let i = (jj + self.walk_turn) & 3;
                let f = FACE[i];
                let (a, b, c) = (
                    &self.pts[tv[f[0]] as usize],
                    &self.pts[tv[f[1]] as usize],
                    &self.pts[tv[f[2]] as usize],
                );
                if orient3d(a, b, c, p) == Orientation::Positive {
                    next = Some(i);
                    break;
                }
            }
            match next {
                None => return Ok(t),
                Some(i) => {
                    let n = self.t[t as usize].adj[i];
                    if n == NONE {
                        return Err(Reject::Outside);
                    }
                    t = n >> 2;
                }
            }
        }
        // A walk that cycles (possible once constraints break the Delaunay property): scan.
        self.live_tets()
            .find(|&t| {
                let tv = self.t[t as usize].v;
                FACE.iter().all(|f| {
                    orient3d(
                        &self.pts[tv[f[0]] as usize],
                        &self.pts[tv[f[1]] as usize],
                        &self.pts[tv[f[2]] as usize],
                        p,
                    ) != Orientation::Positive
                })
            })
            .ok_or(Reject::Outside)
    }

    fn any_live(&self) -> Option<u32> {
        if self.hint != NONE && (self.hint as usize) < self.t.len() && self.alive(self.hint) {
            return Some(self.hint);
        }
        self.live_tets().next()
    }

    /// Insert a new point `p` starting the walk at `start` (or the hint); returns its vertex id.
    pub fn insert(&mut self, p: P, start: u32, lim: &Limits) -> Result<u32, Reject> {
        self.prepare(&p, start, lim)?;
        let v = self.pts.len() as u32;
        self.pts.push(p);
        self.apply(v);
        Ok(v)
    }

    /// Insert the existing point `v` (in `pts` but in no tet yet).
    pub fn insert_vertex(&mut self, v: u32, start: u32, lim: &Limits) -> Result<(), Reject> {
        let p = self.pts[v as usize];
        self.prepare(&p, start, lim)?;
        self.apply(v);
        Ok(())
    }

    /// Locate `p`, build and check its cavity (nothing changes yet).
    fn prepare(&mut self, p: &P, start: u32, lim: &Limits) -> Result<(), Reject> {
        let root = self.locate(p, start)?;
        let rv = self.t[root as usize].v;
        if rv.iter().any(|&v| self.pts[v as usize] == *p) {
            return Err(Reject::Duplicate);
        }
        let d2 = lim.min_dist * lim.min_dist;
        if rv.iter().any(|&v| dist2(&self.pts[v as usize], p) < d2) {
            return Err(Reject::TooClose);
        }
        self.grow_cavity(root, p, d2)?;
        self.make_star_shaped(root, p)?;
        self.check_limits(p, lim)
    }

    /// A new cavity grown from `root` across faces that are neither constraints nor hull, taking
    /// each neighbour `u` that `take(self, u, mark_of_u)` accepts (asked once per tet and flood).
    ///
    /// The cavity grows level by level (breadth first): all the records of a level's neighbours
    /// are requested, then the point each of them adds to the face it shares (its apex), then
    /// they are tested. A cavity of 20-30 tets is three or four levels deep, so its cache misses
    /// come in a few batches that overlap, instead of two waits (record, then apex) per tet: the
    /// floods were bound by those waits.
    fn flood(
        &mut self,
        root: u32,
        mut take: impl FnMut(&Self, u32, u32) -> Result<bool, Reject>,
    ) -> Result<(), Reject> {
        let s = self.next_stamp();
        self.cavity.clear();
        self.t[root as usize].mark = s;
        self.cavity.push(root);
        let mut level = 0;
        while level < self.cavity.len() {
            let end = self.cavity.len();
            // The neighbours across the level's open faces, as `4 u + j` (face j of u).
            self.across.clear();
            for k in level..end {
                let r = &self.t[self.cavity[k] as usize];
                for (i, &n) in r.adj.iter().enumerate() {
                    if r.cons & (1 << i) == 0 && n != NONE {
                        prefetch(&self.t[(n >> 2) as usize]);
                        self.across.push(n);
                    }
                }
            }
            for &n in &self.across {
                let apex = self.t[(n >> 2) as usize].v[(n & 3) as usize];
                if let Some(p) = self.pts.get(apex as usize) {
                    prefetch(p);
                }
            }
            for k in 0..self.across.len() {
                let u = self.across[k] >> 2;
                let m = self.t[u as usize].mark;
                // A tet refused once is refused again (the test depends on it alone): not retried.
                if m == s || m == s + 1 {
                    continue;
                }
                if take(self, u, m)? {
                    self.t[u as usize].mark = s;
                    self.cavity.push(u);
                } else {
                    self.t[u as usize].mark = s + 1;
                }
            }
            level = end;
        }
        Ok(())
    }

    /// Tets whose circumsphere strictly contains `p`, connected to `root` without crossing a
    /// constraint or the hull; `TooClose` as soon as one has a vertex nearer than `min_d2`.
    fn grow_cavity(&mut self, root: u32, p: &P, min_d2: f64) -> Result<(), Reject> {
        self.flood(root, |tri, u, _| {
            let [a, b, c, d] = tri.t[u as usize].v.map(|v| &tri.pts[v as usize]);
            if insphere(a, b, c, d, p) != Orientation::Positive {
                return Ok(false);
            }
            if min_d2 > 0.0 && [a, b, c, d].iter().any(|q| dist2(q, p) < min_d2) {
                return Err(Reject::TooClose);
            }
            Ok(true)
        })
    }

    /// Collect the cavity's boundary faces.
    fn collect_boundary(&mut self) {
        let s = self.stamp;
        self.bnd.clear();
        for &t in &self.cavity {
            for i in 0..4 {
                let n = self.t[t as usize].adj[i];
                if n == NONE || self.t[(n >> 2) as usize].mark != s {
                    self.bnd.push((t, i as u8));
                }
            }
        }
    }

    /// Shrink the cavity until every boundary face sees `p` strictly.
    fn make_star_shaped(&mut self, root: u32, p: &P) -> Result<(), Reject> {
        loop {
            self.collect_boundary();
            let mut bad: Vec<u32> = Vec::new();
            for &(t, i) in &self.bnd {
                let f = self.face(t, i as usize);
                let [a, b, c] = f.map(|v| &self.pts[v as usize]);
                if orient3d(a, b, c, p) != Orientation::Negative {
                    bad.push(t);
                }
            }
            // A constraint with the cavity on both sides (the cavity went round a dangling
            // face's edge): the side `p` cannot see leaves the cavity.
            let s = self.stamp;
            for &t in &self.cavity {
                let c = self.t[t as usize].cons;
                if c == 0 {
                    continue;
                }
                for i in 0..4 {
                    let n = self.t[t as usize].adj[i];
                    if c & (1 << i) == 0 || n == NONE || self.t[(n >> 2) as usize].mark != s {
                        continue;
                    }
                    let f = self.face(t, i);
                    let [a, b, c3] = f.map(|v| &self.pts[v as usize]);
                    bad.push(if orient3d(a, b, c3, p) == Orientation::Negative {
                        n >> 2
                    } else {
                        t
                    });
                }
            }
            if bad.is_empty() {
                bad = self.tets_freeing_edges(root);
            }
            if bad.is_empty() {
                return Ok(());
            }
            if bad.contains(&root) {
                return Err(Reject::NotVisible);
            }
            // Drop the offending tets, then keep what stays connected to the root.
            for &t in &bad {
                self.t[t as usize].mark = 0;
            }
            let kept = self.stamp;
            self.flood(root, |_, _, m| Ok(m == kept))?;
        }
    }

    /// The spacing was checked while the cavity grew; here the height over boundary faces and
    /// the distance to constraint edges.
    fn check_limits(&self, p: &P, lim: &Limits) -> Result<(), Reject> {
        if lim.min_height > 0.0 {
            if !self.clear_of_edges(p, lim.min_height) {
                return Err(Reject::TooClose);
            }
            for &(t, i) in &self.bnd {
                let hull = self.t[t as usize].adj[i as usize] == NONE;
                if !hull && self.t[t as usize].cons & (1 << i) == 0 {
                    continue;
                }
                let f = self.face(t, i as usize);
                let [a, b, c] = f.map(|v| self.pts[v as usize]);
                if height(&a, &b, &c, p) < lim.min_height {
                    return Err(Reject::TooClose);
                }
            }
        }
        Ok(())
    }

    /// Replace the cavity by the star of its boundary from the new vertex `p`.
    fn apply(&mut self, v: u32) {
        // New tets' records first: the cavity's slots are reused.
        let mut recs = std::mem::take(&mut self.recs);
        recs.clear();
        for &(t, i) in &self.bnd {
            let f = self.face(t, i as usize);
            let outer = self.t[t as usize].adj[i as usize];
            let con = self.t[t as usize].cons & (1 << i) != 0;
            recs.push(([f[0], f[2], f[1], v], outer, con));
        }
        for k in 0..self.cavity.len() {
            let t = self.cavity[k];
            self.t[t as usize].v = [NONE; 4];
            self.free.push(t);
        }
        self.keys.clear();
        let mut last = self.hint;
        for &(tv, outer, con) in &recs {
            let id = self.alloc(tv);
            self.t[id as usize].adj[3] = outer;
            if con {
                self.t[id as usize].cons = 1 << 3;
            }
            if outer != NONE {
                self.t[(outer >> 2) as usize].adj[(outer & 3) as usize] = 4 * id + 3;
            }
            // Faces 0, 1, 2 contain `v` and the base edge without vertex 0, 1, 2 respectively.
            for k in 0..3usize {
                let (x, y) = match k {
                    0 => (tv[1], tv[2]),
                    1 => (tv[0], tv[2]),
                    _ => (tv[0], tv[1]),
                };
                let (lo, hi) = if x < y { (x, y) } else { (y, x) };
                self.keys
                    .push((((lo as u64) << 32) | hi as u64, 4 * id + k as u32));
            }
            if self.record {
                self.created.push(id);
            }
            last = id;
        }
        self.recs = recs;
        // Each edge key comes twice (the two new tets on either side of one new face): pair
        // them through an open-addressing table twice the keys' size or more.
        let bits = (2 * self.keys.len())
            .next_power_of_two()
            .trailing_zeros()
            .max(4);
        self.table.clear();
        self.table.resize(1 << bits, (EMPTY, 0));
        let mask = (1usize << bits) - 1;
        for &(key, face) in &self.keys {
            let mut slot = (key.wrapping_mul(0x9e37_79b9_7f4a_7c15) >> (64 - bits)) as usize;
            loop {
                let (k, other) = self.table[slot];
                if k == EMPTY {
                    self.table[slot] = (key, face);
                    break;
                }
                if k == key {
                    self.t[(face >> 2) as usize].adj[(face & 3) as usize] = other;
                    self.t[(other >> 2) as usize].adj[(other & 3) as usize] = face;
                    break;
                }
                slot = (slot + 1) & mask;
            }
        }
        self.hint = last;
    }
}

/// Ask for the cache line holding `x` without waiting for it (a hint: no effect on results).
#[inline(always)]
fn prefetch<T>(x: &T) {
    #[cfg(target_arch = "x86_64")]
    // SAFETY: a prefetch reads nothing architecturally and cannot fault; `x` is a valid reference.
    unsafe {
        std::arch::x86_64::_mm_prefetch(
            (x as *const T).cast::<i8>(),
            std::arch::x86_64::_MM_HINT_T0,
        );
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = x;
}

#[inline]
fn dist2(a: &P, b: &P) -> f64 {
    let e = sub(a, b);
    dot(&e, &e)
}

/// A free slot of the edge table (no edge has both ends `u32::MAX`).
const EMPTY: u64 = u64::MAX;

/// Steps of the floating-point walk before the exact one takes over.
const FLOAT_WALK: usize = 1 << 16;

/// Floating-point `orient3d(a, b, c, p) == Positive` (the same sign convention), to steer walks
/// only.
#[inline]
fn above(a: &P, b: &P, c: &P, p: &P) -> bool {
    let (ad, bd, cd) = (sub(a, p), sub(b, p), sub(c, p));
    dot(&ad, &cross(&bd, &cd)) < 0.0
}

/// Distance from `p` to the plane of `abc` (float: a size test, not a decision of validity).
pub fn height(a: &P, b: &P, c: &P, p: &P) -> f64 {
    let n = cross(&sub(b, a), &sub(c, a));
    let l = dot(&n, &n).sqrt();
    if l == 0.0 {
        return 0.0;
    }
    dot(&sub(p, a), &n).abs() / l
}
