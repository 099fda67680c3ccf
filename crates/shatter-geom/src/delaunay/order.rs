//! Insertion order: BRIO (biased randomized insertion order) with a Hilbert curve sort
//! inside every round.
//!
//! The points are shuffled (deterministically), then split into rounds of geometrically
//! growing size — the first `RATIO` of a range is ordered recursively and inserted first,
//! the rest is sorted along a Hilbert curve. Randomness between rounds keeps the expected
//! cost of Bowyer–Watson optimal; the curve order inside a round keeps consecutive points
//! close, so the walking point location takes a few steps and the memory it touches stays
//! in cache.

use glam::DVec3;

/// Fraction of a range inserted in the earlier (recursively ordered) rounds.
const RATIO: f64 = 0.125;
/// Ranges at most this long form a single round.
const THRESHOLD: usize = 256;

/// Deterministic 64-bit generator (xorshift64*), good enough for shuffling.
pub(crate) struct XorShift(u64);

impl XorShift {
    pub(crate) fn new(seed: u64) -> Self {
        Self(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1)
    }
    #[inline]
    pub(crate) fn next_u64(&mut self) -> u64 {
        let mut x = self.0;
        x ^= x >> 12;
        x ^= x << 25;
        x ^= x >> 27;
        self.0 = x;
        x.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
}

/// The BRIO order of `points`: a permutation of `0..points.len()`.
pub(crate) fn brio_order(points: &[DVec3]) -> Vec<u32> {
    brio_order_of(points, (0..points.len() as u32).collect())
}

/// The BRIO order of the points `idx` of `points`: a permutation of `idx`.
pub(crate) fn brio_order_of(points: &[DVec3], mut idx: Vec<u32>) -> Vec<u32> {
    let n = idx.len();
    let mut rng = XorShift::new(0x5EED_DE1A_u64);
    for i in (1..n).rev() {
        let j = (rng.next_u64() % (i as u64 + 1)) as usize;
        idx.swap(i, j);
    }
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for &i in &idx {
        let p = points[i as usize].to_array();
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let mut keys = Vec::with_capacity(n);
    let mut end = n;
    // Rounds from the largest (last inserted) down to the first.
    while end > 0 {
        let start = if end > THRESHOLD {
            (end as f64 * RATIO) as usize
        } else {
            0
        };
        hilbert_sort(points, &mut idx[start..end], &lo, &hi, &mut keys);
        end = start;
    }
    idx
}

/// Sorts `idx` along a Hilbert curve over the box `lo..hi`, at a resolution that suits the
/// number of points.
fn hilbert_sort(
    points: &[DVec3],
    idx: &mut [u32],
    lo: &[f64; 3],
    hi: &[f64; 3],
    keys: &mut Vec<u64>,
) {
    let n = idx.len();
    if n < 2 {
        return;
    }
    // About 8 cells per point: bits per axis = ceil(log2(n) / 3) + 1, within 2..=10.
    let log2 = usize::BITS - n.leading_zeros();
    let bits = (log2.div_ceil(3) + 1).clamp(2, 10);
    let cells = ((1u32 << bits) - 1) as f64;
    let mut scale = [0.0; 3];
    for k in 0..3 {
        let extent = hi[k] - lo[k];
        scale[k] = if extent > 0.0 { cells / extent } else { 0.0 };
    }
    keys.clear();
    keys.extend(idx.iter().map(|&i| {
        let p = points[i as usize].to_array();
        let mut q = [0u32; 3];
        for k in 0..3 {
            q[k] = (((p[k] - lo[k]) * scale[k]) as u32).min(cells as u32);
        }
        (hilbert_index(q, bits) << 32) | i as u64
    }));
    keys.sort_unstable();
    for (slot, key) in idx.iter_mut().zip(keys.iter()) {
        *slot = *key as u32;
    }
}

/// Index along the 3D Hilbert curve of the cell `x` on a `2^bits` grid (Skilling's
/// transpose algorithm, "Programming the Hilbert curve", 2004).
pub(crate) fn hilbert_index(mut x: [u32; 3], bits: u32) -> u64 {
    let m = 1u32 << (bits - 1);
    // Inverse undo.
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
    // Gray encode.
    x[1] ^= x[0];
    x[2] ^= x[1];
    let mut t = 0;
    q = m;
    while q > 1 {
        if x[2] & q != 0 {
            t ^= q - 1;
        }
        q >>= 1;
    }
    for v in &mut x {
        *v ^= t;
    }
    // Interleave the transposed bits, most significant first.
    let mut h = 0u64;
    for j in (0..bits).rev() {
        for v in &x {
            h = (h << 1) | ((v >> j) & 1) as u64;
        }
    }
    h
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hilbert_curve_is_a_unit_step_path() {
        // Walking the cells in curve order, consecutive cells are face neighbours.
        let bits = 3;
        let side = 1u32 << bits;
        let mut cells = Vec::new();
        for x in 0..side {
            for y in 0..side {
                for z in 0..side {
                    cells.push((hilbert_index([x, y, z], bits), [x, y, z]));
                }
            }
        }
        cells.sort();
        for (k, w) in cells.windows(2).enumerate() {
            assert_eq!(w[0].0 as usize, k, "indices form a permutation");
            let d: u32 = (0..3).map(|i| w[0].1[i].abs_diff(w[1].1[i])).sum();
            assert_eq!(d, 1, "cells {:?} and {:?} are not adjacent", w[0].1, w[1].1);
        }
    }

    #[test]
    fn brio_is_a_permutation() {
        let pts: Vec<DVec3> = (0..5000)
            .map(|i| DVec3::new((i % 17) as f64, (i % 31) as f64, i as f64))
            .collect();
        let mut o = brio_order(&pts);
        o.sort_unstable();
        assert!(o.iter().enumerate().all(|(i, &v)| i as u32 == v));
    }
}
