//! Exact integer evaluation of the insphere and orientation determinants: the cheap exact
//! stage before `robust`'s expansion arithmetic, for coordinates whose magnitudes do not
//! span too many binary orders.

/// Most bits of a scaled coordinate difference for the 128-bit evaluation: the degree-5
/// determinant then stays below `2^(5·20 + 7) < 2^127`.
const SMALL_BITS: u32 = 20;
/// Most bits of a scaled coordinate difference for the 512-bit evaluation: the
/// determinant stays below `2^(5·90 + 7) < 2^511`.
const WIDE_BITS: u32 = 90;

/// Exact sign of Shewchuk's insphere determinant (robust's sign convention) in integers,
/// when all 15 coordinates, scaled by one power of two (the lowest bit among them), are
/// integers of at most [`WIDE_BITS`] bits — true unless their magnitudes span more than
/// about 2^37: 128-bit arithmetic when the differences are small (grids, lattices),
/// 512-bit otherwise (e.g. points on a sphere). `None` otherwise.
#[cold]
#[inline(never)]
pub(crate) fn insphere_lattice(p: [&[f64; 3]; 4], e: &[f64; 3]) -> Option<f64> {
    let (m, max) = scaled_differences(p, e)?;
    if max >= 1i128 << SMALL_BITS {
        return Some(wide_det(&m));
    }
    let lift = |r: &[i128; 3]| r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
    // Expansion of det[[a, la], [b, lb], [c, lc], [d, ld]] along the lift column.
    let det = -lift(&m[0]) * det3(&m[1], &m[2], &m[3]) + lift(&m[1]) * det3(&m[0], &m[2], &m[3])
        - lift(&m[2]) * det3(&m[0], &m[1], &m[3])
        + lift(&m[3]) * det3(&m[0], &m[1], &m[2]);
    Some(det.signum() as f64)
}

/// Most bits of a scaled coordinate difference for the 128-bit orientation: the degree-3
/// determinant stays below `2^(3·40 + 3) < 2^127`.
const SMALL_BITS_ORIENT: u32 = 40;

/// Exact sign of Shewchuk's orient3d determinant `det[a − d; b − d; c − d]` in integers,
/// under the same condition as [`insphere_lattice`] (the 12 coordinates, scaled by one
/// power of two, are integers of at most [`WIDE_BITS`] bits): 128-bit arithmetic for small
/// differences, 512-bit otherwise. Much cheaper than `robust`'s expansions when the
/// answer is exactly zero (coplanar points, as the thesis's point scheme makes by the
/// hundred). `None` when the condition fails.
#[cold]
#[inline(never)]
pub(crate) fn orient_lattice(p: [&[f64; 3]; 3], d: &[f64; 3]) -> Option<f64> {
    let (m, max) = scaled_differences(p, d)?;
    if max >= 1i128 << SMALL_BITS_ORIENT {
        let w: [[W; 3]; 3] = m.map(|r| r.map(W::from_i128));
        return Some(det3_wide(&w[0], &w[1], &w[2]).signum());
    }
    Some(det3(&m[0], &m[1], &m[2]).signum() as f64)
}

/// The exact differences `p[i] − origin`, every coordinate scaled by 2^-low (the lowest
/// bit among all of them), and their largest magnitude; `None` if a difference needs more
/// than [`WIDE_BITS`] bits or a coordinate is not finite.
fn scaled_differences<const N: usize>(
    p: [&[f64; 3]; N],
    origin: &[f64; 3],
) -> Option<([[i128; 3]; N], i128)> {
    // Every coordinate as (sign, odd mantissa, exponent of its lowest bit); the exact
    // differences are integers once everything is scaled by 2^-low.
    let mut parts = [[(false, 0u64, 0i32); 3]; N];
    let mut origin_parts = [(false, 0u64, 0i32); 3];
    let mut low = i32::MAX;
    for (row, q) in parts
        .iter_mut()
        .chain(std::iter::once(&mut origin_parts))
        .zip(p.into_iter().chain(std::iter::once(origin)))
    {
        for k in 0..3 {
            if q[k] != 0.0 {
                let (mant, exp) = decompose(q[k])?;
                row[k] = (q[k] < 0.0, mant, exp);
                low = low.min(exp);
            }
        }
    }
    if low == i32::MAX {
        return Some(([[0; 3]; N], 0));
    }
    let scaled = |row: &[(bool, u64, i32); 3]| -> Option<[i128; 3]> {
        let mut out = [0i128; 3];
        for k in 0..3 {
            let (neg, mant, exp) = row[k];
            if mant == 0 {
                continue;
            }
            let shift = exp - low;
            if !(0..WIDE_BITS as i32).contains(&shift)
                || (64 - mant.leading_zeros()) + shift as u32 > WIDE_BITS
            {
                return None;
            }
            let v = (mant as i128) << shift;
            out[k] = if neg { -v } else { v };
        }
        Some(out)
    };
    let o = scaled(&origin_parts)?;
    let mut m = [[0i128; 3]; N];
    let mut max = 0i128;
    for (mr, row) in m.iter_mut().zip(&parts) {
        let ir = scaled(row)?;
        for k in 0..3 {
            let d = ir[k] - o[k];
            if d.unsigned_abs() >= 1u128 << WIDE_BITS {
                return None;
            }
            max = max.max(d.abs());
            mr[k] = d;
        }
    }
    Some((m, max))
}

/// `a · (b × c)` in 128-bit integers (the caller bounds the magnitudes).
fn det3(a: &[i128; 3], b: &[i128; 3], c: &[i128; 3]) -> i128 {
    a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
        + a[2] * (b[0] * c[1] - b[1] * c[0])
}

/// `a · (b × c)` in 512-bit integers.
fn det3_wide(a: &[W; 3], b: &[W; 3], c: &[W; 3]) -> W {
    a[0].mul(b[1].mul(c[2]).sub(b[2].mul(c[1])))
        .sub(a[1].mul(b[0].mul(c[2]).sub(b[2].mul(c[0]))))
        .add(a[2].mul(b[0].mul(c[1]).sub(b[1].mul(c[0]))))
}

/// `|x| = mant · 2^exp` with an odd integer `mant` (finite non-zero `x`).
fn decompose(x: f64) -> Option<(u64, i32)> {
    let bits = x.to_bits();
    let exp_field = ((bits >> 52) & 0x7ff) as i32;
    let frac = bits & ((1u64 << 52) - 1);
    let (mant, exp) = match exp_field {
        0 => (frac, -1074),
        0x7ff => return None,
        _ => (frac | (1u64 << 52), exp_field - 1075),
    };
    if mant == 0 {
        return None;
    }
    let tz = mant.trailing_zeros();
    Some((mant >> tz, exp + tz as i32))
}

/// The same determinant as [`insphere_lattice`]'s small path, in 512-bit two's complement
/// (every intermediate is below `2^511` in magnitude, so wrapping arithmetic is exact).
fn wide_det(m: &[[i128; 3]; 4]) -> f64 {
    let w: [[W; 3]; 4] = m.map(|r| r.map(W::from_i128));
    let lift = |r: &[W; 3]| r[0].mul(r[0]).add(r[1].mul(r[1])).add(r[2].mul(r[2]));
    let det = lift(&w[1])
        .mul(det3_wide(&w[0], &w[2], &w[3]))
        .sub(lift(&w[0]).mul(det3_wide(&w[1], &w[2], &w[3])))
        .sub(lift(&w[2]).mul(det3_wide(&w[0], &w[1], &w[3])))
        .add(lift(&w[3]).mul(det3_wide(&w[0], &w[1], &w[2])));
    det.signum()
}

/// A 512-bit two's complement integer, little-endian limbs.
#[derive(Clone, Copy)]
struct W([u64; 8]);

impl W {
    fn from_i128(v: i128) -> Self {
        let fill = if v < 0 { u64::MAX } else { 0 };
        let mut l = [fill; 8];
        l[0] = v as u64;
        l[1] = (v >> 64) as u64;
        W(l)
    }

    fn add(self, o: W) -> W {
        let mut r = [0u64; 8];
        let mut carry = false;
        for ((out, a), b) in r.iter_mut().zip(self.0).zip(o.0) {
            let (s1, c1) = a.overflowing_add(b);
            let (s2, c2) = s1.overflowing_add(carry as u64);
            *out = s2;
            carry = c1 | c2;
        }
        W(r)
    }

    fn neg(self) -> W {
        let mut r = self.0.map(|x| !x);
        for limb in &mut r {
            let (s, c) = limb.overflowing_add(1);
            *limb = s;
            if !c {
                break;
            }
        }
        W(r)
    }

    fn sub(self, o: W) -> W {
        self.add(o.neg())
    }

    /// The low 512 bits of the product (exact when the product fits), multiplying
    /// magnitudes over their non-zero limbs only.
    fn mul(self, o: W) -> W {
        let (na, a) = self.abs();
        let (nb, b) = o.abs();
        let la = 8 - a.0.iter().rev().take_while(|&&x| x == 0).count();
        let lb = 8 - b.0.iter().rev().take_while(|&&x| x == 0).count();
        let mut r = [0u64; 8];
        for i in 0..la {
            let mut carry = 0u128;
            let top = lb.min(8 - i);
            for j in 0..top {
                let t = a.0[i] as u128 * b.0[j] as u128 + r[i + j] as u128 + carry;
                r[i + j] = t as u64;
                carry = t >> 64;
            }
            if i + top < 8 {
                r[i + top] = carry as u64;
            }
        }
        let r = W(r);
        if na != nb { r.neg() } else { r }
    }

    /// (is negative, magnitude).
    fn abs(self) -> (bool, W) {
        if self.0[7] >> 63 == 1 {
            (true, self.neg())
        } else {
            (false, self)
        }
    }

    fn signum(self) -> f64 {
        if self.0[7] >> 63 == 1 {
            -1.0
        } else if self.0.iter().all(|&x| x == 0) {
            0.0
        } else {
            1.0
        }
    }
}
