//! A fast hasher for small integer keys (the fracture's maps).

use std::collections::{HashMap, HashSet};
use std::hash::{BuildHasherDefault, Hasher};

/// A fast multiplicative hasher for the small integer keys of the clipping maps (the
/// default SipHash dominated the profile; the keys are not attacker-controlled).
#[derive(Debug, Default, Clone, Copy)]
pub(crate) struct FastHasher(u64);

impl FastHasher {
    #[inline]
    fn add(&mut self, word: u64) {
        self.0 = (self.0.rotate_left(5) ^ word).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }
}

impl Hasher for FastHasher {
    #[inline]
    fn finish(&self) -> u64 {
        self.0
    }
    /// Eight bytes a step (an array key, as a position's three coordinates, comes here
    /// whole; byte by byte it took 24 dependent multiplications), the rest byte by byte.
    /// A word whose low bits are zero (a dyadic coordinate: 0.5, 0.25) leaves the
    /// product's low bits zero, and the table indexes by the low bits: the state is
    /// mixed at the end (MurmurHash3's finaliser) so every bit reaches the low ones.
    #[inline]
    fn write(&mut self, bytes: &[u8]) {
        let mut words = bytes.chunks_exact(8);
        for w in &mut words {
            let mut word = [0u8; 8];
            word.copy_from_slice(w);
            self.add(u64::from_le_bytes(word));
        }
        for &b in words.remainder() {
            self.add(u64::from(b));
        }
        let mut h = self.0;
        h ^= h >> 33;
        h = h.wrapping_mul(0xff51_afd7_ed55_8ccd);
        h ^= h >> 33;
        h = h.wrapping_mul(0xc4ce_b9fe_1a85_ec53);
        self.0 = h ^ (h >> 33);
    }
    #[inline]
    fn write_u32(&mut self, i: u32) {
        self.add(u64::from(i));
    }
    #[inline]
    fn write_u64(&mut self, i: u64) {
        self.add(i);
    }
    #[inline]
    fn write_usize(&mut self, i: usize) {
        self.add(i as u64);
    }
}

/// A hash map with [`FastHasher`].
pub(crate) type FastMap<K, V> = HashMap<K, V, BuildHasherDefault<FastHasher>>;
/// A hash set with [`FastHasher`].
pub(crate) type FastSet<K> = HashSet<K, BuildHasherDefault<FastHasher>>;

#[cfg(test)]
mod tests {
    use super::*;
    use std::hash::{BuildHasher, Hash};

    fn hash<T: Hash>(x: &T) -> u64 {
        BuildHasherDefault::<FastHasher>::default().hash_one(x)
    }

    /// Keys of dyadic coordinates (a grid of halves and quarters, whose bit patterns end
    /// in zeros) still spread over the low bits a table indexes by.
    #[test]
    fn dyadic_positions_spread_over_the_low_bits() {
        let mut low = std::collections::HashSet::new();
        for x in 0..8 {
            for y in 0..8 {
                for z in 0..8 {
                    let key = [x, y, z].map(|k| (f64::from(k) * 0.25).to_bits());
                    low.insert(hash(&key) & 1023);
                }
            }
        }
        // 512 keys into 1024 slots: about 400 distinct by chance, a handful if clumped.
        assert!(low.len() > 300, "{} distinct low parts", low.len());
    }
}
