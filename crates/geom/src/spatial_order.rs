//! Insertion orders for Delaunay triangulations: points sorted along a Hilbert curve, so
//! consecutive insertions are close and each walk is short ([`hilbert_sort`]); and a biased
//! randomized insertion order ([`brio`]), rounds of growing size each sorted along the curve, so
//! every round refines an even sample and cavities stay small, whose "random" rounds come from a
//! hash of the point's index, so the order, and the mesh, are the same on every run. The tet
//! mesher orders its points in 3D; the surface mesher its plane's points, lifted to `z = 0`.

type P = [f64; 3];

/// Bits per axis of the curve: cells of 1/65536 of the box, far finer than any mesh size (at
/// 10 km, 15 cm), and fewer steps per key than the 21 a 64-bit key allows (keys were 5 % of a
/// meshing run). Points in one cell keep their id order.
const BITS: u32 = 16;

/// The Hilbert key of a point with integer coordinates below `2^BITS`: Skilling's curve (his
/// transform from axes to the transposed index, then bit interleaving), read from the top bit
/// down as a finite automaton. Skilling's loop turns each level's three bits by a signed
/// permutation that the levels above chose, and its Gray decoding carries one parity bit down
/// the levels; the pair is the automaton's state, and [`hilbert_table`] tabulates, per state and
/// octant, the key's three bits there and the next state. One table step per level instead of a
/// dozen dependent bit operations (keys were a third of sorting a refinement round).
fn hilbert_key(x: [u32; 3], table: &HilbertTable) -> u64 {
    let mut state = 0usize;
    let mut key = 0u64;
    for level in (0..BITS).rev() {
        let octant = (((x[0] >> level) & 1) << 2
            | ((x[1] >> level) & 1) << 1
            | ((x[2] >> level) & 1)) as usize;
        let step = table[state][octant];
        key = (key << 3) | u64::from(step & 7);
        state = usize::from(step >> 3);
    }
    key
}

/// Per automaton state and octant (bits of x0, x1, x2 from high to low), the key digit (low 3
/// bits) and the next state (the rest).
type HilbertTable = [[u16; 8]; STATES];

/// 6 axis permutations × 8 reflections × 2 parities.
const STATES: usize = 96;

/// The six permutations of three axes, in the order states number them.
const PERMS: [[usize; 3]; 6] = [
    [0, 1, 2],
    [0, 2, 1],
    [1, 0, 2],
    [1, 2, 0],
    [2, 0, 1],
    [2, 1, 0],
];

/// A state: how the levels above transform this level's bits (bit `i` becomes bit `perm[i]` of
/// the input, flipped where `mask` has bit `i`) and the parity Gray decoding carries down.
#[derive(Clone, Copy)]
struct Turn {
    perm: usize,
    mask: u8,
    parity: u8,
}

impl Turn {
    fn index(self) -> usize {
        (self.perm * 8 + self.mask as usize) * 2 + self.parity as usize
    }

    fn of(index: usize) -> Turn {
        Turn {
            perm: index / 16,
            mask: (index / 2 % 8) as u8,
            parity: (index % 2) as u8,
        }
    }

    /// One level of Skilling's transform on the octant `b` (b[i]: bit of axis i): the key digit
    /// and the state the lower levels see.
    fn step(self, b: [u8; 3]) -> (u8, Turn) {
        let mut perm = PERMS[self.perm];
        let mut mask = [0, 1, 2].map(|i| (self.mask >> i) & 1);
        let c: [u8; 3] = [0, 1, 2].map(|i| b[perm[i]] ^ mask[i]);
        // Where bit i is set, the lower levels' bit 0 is inverted; else bits 0 and i exchange.
        for (i, &ci) in c.iter().enumerate() {
            if ci == 1 {
                mask[0] ^= 1;
            } else {
                perm.swap(0, i);
                mask.swap(0, i);
            }
        }
        // Gray decoding, then the parity of the third axis over the levels above.
        let g = [c[0], c[0] ^ c[1], c[0] ^ c[1] ^ c[2]].map(|v| v ^ self.parity);
        let digit = g[0] << 2 | g[1] << 1 | g[2];
        let next = Turn {
            perm: PERMS.iter().position(|p| *p == perm).unwrap_or(0),
            mask: mask[0] | mask[1] << 1 | mask[2] << 2,
            parity: self.parity ^ c[0] ^ c[1] ^ c[2],
        };
        (digit, next)
    }
}

/// The automaton of [`hilbert_key`], built once.
fn hilbert_table() -> &'static HilbertTable {
    static TABLE: std::sync::OnceLock<HilbertTable> = std::sync::OnceLock::new();
    TABLE.get_or_init(|| {
        let mut table = [[0u16; 8]; STATES];
        for (index, row) in table.iter_mut().enumerate() {
            for (octant, cell) in row.iter_mut().enumerate() {
                let b = [
                    (octant >> 2) as u8 & 1,
                    (octant >> 1) as u8 & 1,
                    octant as u8 & 1,
                ];
                let (digit, next) = Turn::of(index).step(b);
                *cell = u16::from(digit) | (next.index() as u16) << 3;
            }
        }
        table
    })
}

/// Sort `ids` along a Hilbert curve through the bounding box of their points (ties by id).
pub fn hilbert_sort(ids: &mut [u32], pts: &[P]) {
    let point = |i: u32| pts[i as usize];
    if ids.len() < 2 {
        return;
    }
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for &i in ids.iter() {
        let p = point(i);
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let ext = (0..3).map(|k| hi[k] - lo[k]).fold(0.0f64, f64::max);
    let scale = if ext > 0.0 {
        ((1u64 << BITS) - 1) as f64 / ext
    } else {
        0.0
    };
    let table = hilbert_table();
    let mut keyed: Vec<(u64, u32)> = ids
        .iter()
        .map(|&i| {
            let p = point(i);
            let c = [0, 1, 2].map(|k| (((p[k] - lo[k]) * scale) as u32).min((1 << BITS) - 1));
            (hilbert_key(c, table), i)
        })
        .collect();
    sort_keyed(&mut keyed, 3 * BITS);
    for (slot, (_, i)) in ids.iter_mut().zip(keyed) {
        *slot = i;
    }
}

/// Digits of the radix sort: 4096 counters stay in the first-level cache.
const RADIX_BITS: u32 = 12;

/// Sort `keyed` by key then id, the keys being below `2^key_bits`: what `sort_unstable` does,
/// in stable least-significant-digit radix passes (the ids' first, when they are not already
/// ascending). A comparison sort of the refinement rounds' points and of a million-tet layout
/// was 5 % of a large region's meshing; this is a few linear passes.
fn sort_keyed(keyed: &mut Vec<(u64, u32)>, key_bits: u32) {
    if keyed.len() < 256 {
        keyed.sort_unstable();
        return;
    }
    let mut tmp = vec![(0u64, 0u32); keyed.len()];
    if keyed.windows(2).any(|w| w[0].1 > w[1].1) {
        for shift in (0..32).step_by(RADIX_BITS as usize) {
            radix_pass(keyed, &mut tmp, |e| u64::from(e.1) >> shift);
        }
    }
    for shift in (0..key_bits).step_by(RADIX_BITS as usize) {
        radix_pass(keyed, &mut tmp, |e| e.0 >> shift);
    }
}

/// One stable counting pass on the digit `digit(e) mod 2^RADIX_BITS`, through `tmp`.
fn radix_pass(
    v: &mut Vec<(u64, u32)>,
    tmp: &mut Vec<(u64, u32)>,
    digit: impl Fn(&(u64, u32)) -> u64,
) {
    let mask = (1u64 << RADIX_BITS) - 1;
    let mut start = vec![0usize; 1 << RADIX_BITS];
    for e in v.iter() {
        start[(digit(e) & mask) as usize] += 1;
    }
    let mut sum = 0;
    for c in start.iter_mut() {
        (*c, sum) = (sum, sum + *c);
    }
    for e in v.iter() {
        let d = (digit(e) & mask) as usize;
        tmp[start[d]] = *e;
        start[d] += 1;
    }
    std::mem::swap(v, tmp);
}

fn mix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// Biased randomized insertion order: round `r` from the end holds about half of what is left,
/// each round Hilbert-sorted. Deterministic (the rounds come from a hash of the index).
pub fn brio(ids: &[u32], pts: &[P]) -> Vec<u32> {
    const ROUNDS: u32 = 12;
    let mut rounds: Vec<Vec<u32>> = vec![Vec::new(); ROUNDS as usize + 1];
    for &i in ids {
        let level = mix(i as u64).trailing_zeros().min(ROUNDS);
        rounds[(ROUNDS - level) as usize].push(i);
    }
    let mut out = Vec::with_capacity(ids.len());
    for mut r in rounds {
        hilbert_sort(&mut r, pts);
        out.extend(r);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hilbert_keys_of_a_grid_are_distinct_and_neighbours_follow_each_other() {
        let n = 8u32;
        let mut keys = Vec::new();
        for x in 0..n {
            for y in 0..n {
                for z in 0..n {
                    let s = 1 << (BITS - 3);
                    keys.push((
                        hilbert_key([x * s, y * s, z * s], hilbert_table()),
                        [x, y, z],
                    ));
                }
            }
        }
        keys.sort_unstable();
        keys.dedup_by_key(|k| k.0);
        assert_eq!(keys.len(), (n * n * n) as usize);
        for w in keys.windows(2) {
            let d: u32 = (0..3).map(|k| w[0].1[k].abs_diff(w[1].1[k])).sum();
            assert_eq!(
                d, 1,
                "consecutive cells {:?} and {:?} are not neighbours",
                w[0].1, w[1].1
            );
        }
    }

    /// The low `BITS` bits of `v` moved to every third bit (bit b to bit 3b), by masked shifts.
    #[inline]
    fn spread(v: u32) -> u64 {
        let mut x = u64::from(v) & ((1 << BITS) - 1);
        x = (x | (x << 32)) & 0x001f_0000_0000_ffff;
        x = (x | (x << 16)) & 0x001f_0000_ff00_00ff;
        x = (x | (x << 8)) & 0x100f_00f0_0f00_f00f;
        x = (x | (x << 4)) & 0x10c3_0c30_c30c_30c3;
        x = (x | (x << 2)) & 0x1249_2492_4924_9249;
        x
    }

    /// Skilling's transform as he wrote it (axes to transposed index, bit by bit), then the
    /// interleaving: the reference the automaton must reproduce.
    fn skilling_key(mut x: [u32; 3]) -> u64 {
        let m = 1u32 << (BITS - 1);
        let mut q = m;
        while q > 1 {
            let p = q - 1;
            for i in 0..3 {
                if x[i] & q != 0 {
                    x[0] ^= p;
                } else {
                    let t = (x[0] ^ x[i]) & p;
                    x[0] ^= t;
                    x[i] ^= t;
                }
            }
            q >>= 1;
        }
        for i in 1..3 {
            x[i] ^= x[i - 1];
        }
        let mut t = 0;
        let mut q = m;
        while q > 1 {
            if x[2] & q != 0 {
                t ^= q - 1;
            }
            q >>= 1;
        }
        for xi in &mut x {
            *xi ^= t;
        }
        (spread(x[0]) << 2) | (spread(x[1]) << 1) | spread(x[2])
    }

    #[test]
    fn the_automaton_gives_the_keys_of_skillings_transform() {
        let mut v = 0x9e37_79b9u32;
        let mut points = vec![[0, 0, 0], [(1 << BITS) - 1; 3], [1, 0, 0], [0, 0, 1]];
        for _ in 0..20_000 {
            v ^= v << 13;
            v ^= v >> 17;
            v ^= v << 5;
            points.push([v, v.rotate_left(11), v.rotate_left(23)].map(|c| c & ((1 << BITS) - 1)));
        }
        for x in points {
            assert_eq!(hilbert_key(x, hilbert_table()), skilling_key(x), "{x:?}");
        }
    }

    #[test]
    fn spreading_bits_interleaves_them_like_a_bit_by_bit_loop() {
        let mut v = 0x2545_f491u32;
        for _ in 0..1000 {
            v ^= v << 13;
            v ^= v >> 17;
            v ^= v << 5;
            let x = [v, v.rotate_left(7), v.rotate_left(19)].map(|c| c & ((1 << BITS) - 1));
            let mut want = 0u64;
            for b in (0..BITS).rev() {
                for xi in &x {
                    want = (want << 1) | ((xi >> b) & 1) as u64;
                }
            }
            assert_eq!(
                (spread(x[0]) << 2) | (spread(x[1]) << 1) | spread(x[2]),
                want
            );
        }
    }

    #[test]
    fn the_radix_sort_orders_like_the_comparison_sort_with_ties_and_shuffled_ids() {
        for n in [0usize, 1, 255, 256, 5000] {
            let mut v: Vec<(u64, u32)> = (0..n as u32)
                .map(|i| {
                    let h = u64::from(i).wrapping_mul(0x9e37_79b9_7f4a_7c15);
                    // Few distinct keys, so many ties; ids in a scrambled order.
                    ((h >> 20) % 97 * 0x1_0001_0001, (h >> 7) as u32)
                })
                .collect();
            let mut want = v.clone();
            want.sort_unstable();
            sort_keyed(&mut v, 48);
            assert_eq!(v, want, "n = {n}");
            let mut asc: Vec<(u64, u32)> = (0..n as u32)
                .map(|i| ((u64::from(i) * 7919) % 1013, i))
                .collect();
            let mut want = asc.clone();
            want.sort_unstable();
            sort_keyed(&mut asc, 48);
            assert_eq!(asc, want, "ascending ids, n = {n}");
        }
    }

    #[test]
    fn brio_keeps_every_point_once() {
        let pts: Vec<P> = (0..1000)
            .map(|i| [(i % 10) as f64, (i / 10 % 10) as f64, (i / 100) as f64])
            .collect();
        let ids: Vec<u32> = (0..1000).collect();
        let mut o = brio(&ids, &pts);
        assert_eq!(o.len(), 1000);
        o.sort_unstable();
        assert_eq!(o, ids);
    }
}
