//! Deterministic fractal noise for rough cut faces: 3D value noise on the integer
//! lattice (a hash of the lattice point and the seed, quintic interpolation), summed over
//! octaves (fBm: each octave twice the frequency, half the weight).

use glam::DVec3;

/// A 64-bit mix of `x` (SplitMix64's finaliser).
fn mix64(mut x: u64) -> u64 {
    x = (x ^ (x >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    x = (x ^ (x >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    x ^ (x >> 31)
}

/// The value at lattice point `(i, j, k)`, in `[-1, 1]`.
fn lattice(i: i64, j: i64, k: i64, seed: u64) -> f64 {
    let mut h = mix64(seed ^ 0x9e37_79b9_7f4a_7c15);
    for c in [i, j, k] {
        h = mix64(h ^ (c as u64));
    }
    // 53 random bits to [0, 1), then to [-1, 1).
    (h >> 11) as f64 * (2.0 / (1u64 << 53) as f64) - 1.0
}

/// Quintic fade `6t⁵ − 15t⁴ + 10t³` (zero first and second derivatives at 0 and 1).
fn fade(t: f64) -> f64 {
    t * t * t * (t * (t * 6.0 - 15.0) + 10.0)
}

/// Value noise at `p` (lattice spacing 1), in `[-1, 1]`. Points beyond ±2⁶² lattice
/// cells give 0.
fn value_noise(p: DVec3, seed: u64) -> f64 {
    let f = p.floor();
    if !f.is_finite() || f.abs().max_element() > 4.6e18 {
        return 0.0;
    }
    let (i, j, k) = (f.x as i64, f.y as i64, f.z as i64);
    let t = p - f;
    let (u, v, w) = (fade(t.x), fade(t.y), fade(t.z));
    let lerp = |a: f64, b: f64, s: f64| a + (b - a) * s;
    let l = |di: i64, dj: i64, dk: i64| lattice(i + di, j + dj, k + dk, seed);
    let x00 = lerp(l(0, 0, 0), l(1, 0, 0), u);
    let x10 = lerp(l(0, 1, 0), l(1, 1, 0), u);
    let x01 = lerp(l(0, 0, 1), l(1, 0, 1), u);
    let x11 = lerp(l(0, 1, 1), l(1, 1, 1), u);
    lerp(lerp(x00, x10, v), lerp(x01, x11, v), w)
}

/// Fractal (fBm) noise at world position `p`: `octaves` octaves of value noise, the
/// first at `frequency` (cycles per world unit), each next one at twice the frequency
/// and half the weight, normalised to `[-1, 1]`. A function of `p` and `seed` alone.
pub(crate) fn fbm(p: DVec3, frequency: f64, octaves: u32, seed: u64) -> f64 {
    let mut sum = 0.0;
    let mut weight = 1.0;
    let mut total = 0.0;
    let mut f = frequency;
    for o in 0..octaves.max(1) {
        // Each octave its own lattice (and an offset, so lattice points do not line up).
        let s = mix64(seed.wrapping_add(u64::from(o)));
        let offset = DVec3::new(0.31, 0.57, 0.73) * f64::from(o);
        sum += weight * value_noise(p * f + offset, s);
        total += weight;
        weight *= 0.5;
        f *= 2.0;
    }
    sum / total
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fbm_is_deterministic_bounded_and_seeded() {
        let mut differs = false;
        for i in 0..200 {
            let p = DVec3::new(
                i as f64 * 0.137,
                (i * 7 % 13) as f64 * 0.21,
                -0.4 * i as f64,
            );
            let a = fbm(p, 3.0, 4, 11);
            assert_eq!(a, fbm(p, 3.0, 4, 11));
            assert!((-1.0..=1.0).contains(&a));
            differs |= a != fbm(p, 3.0, 4, 12);
        }
        assert!(differs);
    }

    #[test]
    fn value_noise_is_continuous_across_lattice_cells() {
        for k in -3..3 {
            let x = k as f64;
            let a = value_noise(DVec3::new(x - 1e-12, 0.3, 0.6), 5);
            let b = value_noise(DVec3::new(x + 1e-12, 0.3, 0.6), 5);
            assert!((a - b).abs() < 1e-9, "{a} vs {b}");
        }
    }

    #[test]
    fn far_points_give_zero_not_a_panic() {
        assert_eq!(value_noise(DVec3::splat(1e300), 1), 0.0);
        assert_eq!(value_noise(DVec3::splat(f64::NAN), 1), 0.0);
    }
}
