//! How much work the advancing front may spend on one region before it gives up.
//!
//! Where the front cannot fill a place (a recovery hole pinned between walls, two sheets nearly
//! touching), it back-tracks and re-meshes around it again and again. The back-track limits of
//! one front run (per face, and per run) bounded the count, not the cost: each try at a higher
//! level deletes and re-meshes a wider ball, and the Delaunay recovery runs the front once per
//! hole and per widening, then the whole region once more as its fallback. A region that could
//! not be meshed took 15 minutes to say so.
//!
//! So the work is counted, in units of 0.05 to 0.1 µs: a node or face the apex search scans is
//! one, a face taken from the front [`FACE_TAKEN`], a candidate apex tested exactly
//! [`APEX_TEST`]. A region's fronts may spend [`BASE`] units (about half a minute), [`PER_FACE`]
//! more per input face, and [`PER_TET`] more per tetrahedron the running front holds at its
//! fullest (so a region whose interior is far finer than its boundary is not cut short). Fronts
//! that meshed the peer model's L1 blocks spent 90 to 710 units per tet; across the suite the
//! fronts of every region that meshed spent at most 180 million units in all (CloudSpin's
//! HOUSTON and KOBE blocks, 6,680 faces, 26 s), while a region that failed spent all it had
//! (CloudSpin's KOBE region at 3 km: 1.25 billion units in 79 s when the base was a billion):
//! hence the base, near three times the most a region that meshed needed. The
//! Delaunay recovery's fronts and the whole-region fallback share one budget: the recovery stops
//! widening holes once it is spent, and the fallback meshes within what is left, or does not start
//! (nor where the recovery's own front already failed on exactly the region's triangles: it
//! would repeat it): where the recovery's front had failed on the whole region, the fallback
//! repeated it and failed too, so sharing and not repeating bring down the time a region takes
//! to fail. Within that, the front on one recovery hole smaller than the region may spend
//! at most [`HOLE_BASE`] and [`HOLE_PER_FACE`] per hole face (and the per-tet allowance): on the
//! corpus every front on such a hole that closed it spent under 11 million units, while modelA4's
//! front on a hole widened to 10,360 faces spent 500 million failing before a smaller hole
//! closed; capped at 41 million it gives way sooner, and that region meshes in 13 s instead of
//! 30, to the same bytes. A hole with at least as many faces as the region (its own front, or
//! one widened nearly as far; told by the count, which errs towards the old, uncapped budget)
//! keeps all the region has left.
//! The front on the whole region, after the Delaunay method gave way, has a budget of its own as
//! well: [`FALLBACK_BASE`] and [`PER_FACE`] per region face (and the per-tet allowance), within
//! what the region has left. Across the suite the fallback meshed three regions, the heaviest
//! (the onlap's overburden, 22,842 faces, 138,942 tets) with 111 million units in 6.6 s; the
//! eight where it failed (CloudSpin's regions at 3 km) spent up to 870 million, 19 to 58 s, each
//! time after the recovery's fronts had failed. Capped, the front on CloudSpin's first failing
//! region gives up after 10.5 s instead of 42.8 s (the region: 56 s to 24 s, the recovery's 14 s
//! included); the onlap's overburden spends the same 120 million units in all as before.
//! Counting, not timing: the same input gives up at the same place on every machine.

use std::cell::{Cell, OnceCell};

use super::RegionInput;
use super::pinch::{Pinch, narrowest};

/// Units of a face taken from the front.
pub const FACE_TAKEN: u64 = 10;
/// Units of one exact test of a candidate apex.
pub const APEX_TEST: u64 = 30;
/// Units per boundary or embedded triangle of the region.
pub const PER_FACE: u64 = 500;
/// Units every region may spend whatever its size.
pub const BASE: u64 = 500_000_000;
/// Units per tetrahedron of the running front, at its fullest.
pub const PER_TET: u64 = 2_000;
/// Units the front on one recovery hole may spend whatever the hole's size.
pub const HOLE_BASE: u64 = 20_000_000;
/// Units per face of a recovery hole.
pub const HOLE_PER_FACE: u64 = 2_000;
/// Units the front on the whole region, after the Delaunay method gave way, may spend whatever
/// the region's size.
pub const FALLBACK_BASE: u64 = 100_000_000;

/// The work the fronts of one region have spent, against what they may.
#[derive(Debug)]
pub struct FrontWork {
    spent: Cell<u64>,
    allowed: u64,
    per_tet: u64,
    /// The region's boundary and embedded triangles.
    faces: usize,
    /// Whether a front already failed on exactly the region's own triangles.
    whole_failed: Cell<bool>,
    /// The region's narrowest pinch, once measured.
    pinch: OnceCell<Option<Pinch>>,
    /// Whether a front that cannot close may have what it left open filled by the Delaunay
    /// method (`closing`): a region's fronts and their holes', not the fronts inside that fill.
    may_close: bool,
}

impl FrontWork {
    /// The budget of `input`'s fronts.
    pub fn for_region(input: &RegionInput) -> FrontWork {
        let faces = input.boundary.len() + input.embedded.len();
        FrontWork {
            faces,
            may_close: true,
            ..FrontWork::with(BASE + PER_FACE * faces as u64, PER_TET)
        }
    }

    /// The budget of the front on one recovery hole of `faces` faces: [`HOLE_BASE`] and
    /// [`HOLE_PER_FACE`] per face at most, within what the region has left; a hole with at least
    /// as many faces as the region (its own front, or nearly) gets all that is left. The caller
    /// [`spend`](Self::spend)s here what the hole's front spent.
    pub fn for_hole(&self, faces: usize) -> FrontWork {
        let own = HOLE_BASE.saturating_add(HOLE_PER_FACE.saturating_mul(faces as u64));
        let allowed = if faces >= self.faces {
            self.left()
        } else {
            self.left().min(own)
        };
        FrontWork {
            may_close: self.may_close,
            ..FrontWork::with(allowed, self.per_tet)
        }
    }

    /// The budget of the front on the whole region after the Delaunay method gave way:
    /// [`FALLBACK_BASE`] and [`PER_FACE`] per face of the region at most, within what the region
    /// has left (and the per-tet allowance). The caller [`spend`](Self::spend)s here what the
    /// front spent.
    pub fn for_fallback(&self) -> FrontWork {
        let own = FALLBACK_BASE.saturating_add(PER_FACE.saturating_mul(self.faces as u64));
        FrontWork {
            faces: self.faces,
            may_close: self.may_close,
            ..FrontWork::with(self.left().min(own), self.per_tet)
        }
    }

    /// The units not yet spent of the fixed part of the budget (the per-tet allowance aside).
    fn left(&self) -> u64 {
        self.allowed.saturating_sub(self.spent.get())
    }

    /// A budget of `allowed` units plus `per_tet` per tet of the running front at its fullest,
    /// whose fronts leave what they cannot close open.
    pub fn with(allowed: u64, per_tet: u64) -> FrontWork {
        FrontWork {
            spent: Cell::new(0),
            allowed,
            per_tet,
            faces: 0,
            whole_failed: Cell::new(false),
            pinch: OnceCell::new(),
            may_close: false,
        }
    }

    /// Whether a front that cannot close may have the Delaunay method fill what it left open.
    pub fn may_close(&self) -> bool {
        self.may_close
    }

    /// Count `n` units.
    pub fn spend(&self, n: u64) {
        self.spent.set(self.spent.get().saturating_add(n));
    }

    pub fn spent(&self) -> u64 {
        self.spent.get()
    }

    /// Records that a front failed on the region's own triangles, no other: the Delaunay
    /// recovery's hole had become the whole region.
    pub fn whole_region_failed(&self) {
        self.whole_failed.set(true);
    }

    /// The narrowest pinch of `input`, the region this budget is for (`pinch::narrowest`):
    /// measured the first time it is asked for, since it costs a twentieth to a fifth of the
    /// region's meshing, and only recoveries and fallbacks that fail need it.
    pub fn pinch(&self, input: &RegionInput) -> Option<Pinch> {
        *self.pinch.get_or_init(|| narrowest(input))
    }

    /// Whether a front failed on the whole region already: the fallback would run it again.
    pub fn failed_on_whole_region(&self) -> bool {
        self.whole_failed.get()
    }

    /// Whether the fronts have spent more than they may, the running one holding at most
    /// `fullest` tetrahedra so far.
    pub fn exhausted(&self, fullest: usize) -> bool {
        self.spent.get()
            > self
                .allowed
                .saturating_add(self.per_tet.saturating_mul(fullest as u64))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_budget_grows_with_the_faces_and_with_the_tets_the_front_holds() {
        let input = RegionInput {
            boundary: vec![[0, 1, 2]; 10],
            embedded: vec![[0, 1, 3]; 5],
            ..RegionInput::default()
        };
        let w = FrontWork::for_region(&input);
        w.spend(BASE + 15 * PER_FACE);
        assert!(!w.exhausted(0));
        w.spend(1);
        assert!(w.exhausted(0));
        assert!(!w.exhausted(1));
        w.spend(PER_TET);
        assert!(w.exhausted(1));
        assert_eq!(w.spent(), BASE + 15 * PER_FACE + 1 + PER_TET);
    }

    #[test]
    fn a_hole_smaller_than_the_region_gets_its_own_cap_within_what_the_region_has_left() {
        let input = RegionInput {
            boundary: vec![[0, 1, 2]; 1000],
            ..RegionInput::default()
        };
        let region = FrontWork::for_region(&input);
        let hole = region.for_hole(100);
        hole.spend(HOLE_BASE + 100 * HOLE_PER_FACE);
        assert!(!hole.exhausted(0));
        hole.spend(1);
        assert!(hole.exhausted(0) && !hole.exhausted(1));
        // The region's own front (a hole of all its faces) gets all that is left.
        region.spend(BASE);
        let whole = region.for_hole(1000);
        whole.spend(1000 * PER_FACE);
        assert!(!whole.exhausted(0));
        // Once the region has nothing left, neither has a hole.
        region.spend(1000 * PER_FACE);
        let empty = region.for_hole(10);
        assert!(!empty.exhausted(0));
        empty.spend(1);
        assert!(empty.exhausted(0));
    }

    #[test]
    fn the_front_after_delaunay_gave_way_gets_its_own_cap_within_what_the_region_has_left() {
        let input = RegionInput {
            boundary: vec![[0, 1, 2]; 1000],
            ..RegionInput::default()
        };
        let region = FrontWork::for_region(&input);
        let fallback = region.for_fallback();
        assert!(
            fallback.may_close(),
            "what it leaves open may still be closed"
        );
        fallback.spend(FALLBACK_BASE + 1000 * PER_FACE);
        assert!(!fallback.exhausted(0));
        fallback.spend(1);
        assert!(fallback.exhausted(0) && !fallback.exhausted(1));
        // With less left than its cap, it has what is left.
        region.spend(BASE);
        let late = region.for_fallback();
        late.spend(1000 * PER_FACE);
        assert!(!late.exhausted(0));
        late.spend(1);
        assert!(late.exhausted(0));
    }
}
