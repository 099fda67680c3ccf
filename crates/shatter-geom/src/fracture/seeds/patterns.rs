//! Seed patterns for Voronoi fracture, and uniform sampling inside a solid.

use glam::DVec3;
use rand::Rng;
use rand_chacha::ChaCha8Rng;

use super::inside::InsideSampler;
use crate::fracture::kernel::Piece;
use crate::fracture::{Pattern, SLIVER_VOLUME_FRACTION};

/// A standard normal deviate (Box–Muller).
pub(crate) fn gaussian(rng: &mut ChaCha8Rng) -> f64 {
    let u1: f64 = rng.random::<f64>().max(f64::MIN_POSITIVE);
    let u2: f64 = rng.random();
    (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
}

/// A uniform random unit vector.
pub(crate) fn unit_vector(rng: &mut ChaCha8Rng) -> DVec3 {
    let z: f64 = rng.random_range(-1.0..=1.0);
    let phi: f64 = rng.random_range(0.0..std::f64::consts::TAU);
    let r = (1.0 - z * z).max(0.0).sqrt();
    DVec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// `k` seeds of `pattern` inside the solid. `impact` is used by [`Pattern::Radial`]
/// (default: a random surface vertex).
pub(crate) fn seeds(
    piece: &Piece,
    k: usize,
    pattern: Pattern,
    impact: Option<DVec3>,
    rng: &mut ChaCha8Rng,
) -> Vec<DVec3> {
    let sampler = InsideSampler::new(piece);
    let (lo, hi) = sampler.bounds();
    let diag = (hi - lo).length();
    match pattern {
        Pattern::Uniform | Pattern::Splinter => (0..k).map(|_| sampler.uniform(rng)).collect(),
        Pattern::Clustered => {
            let clusters = ((k as f64).sqrt() / 2.0).ceil().max(1.0) as usize;
            let centres: Vec<DVec3> = (0..clusters).map(|_| sampler.uniform(rng)).collect();
            let sigma = 0.08 * diag;
            (0..k)
                .map(|i| {
                    let c = centres[i % clusters];
                    sampler.inside_from(rng, |r| {
                        c + DVec3::new(gaussian(r), gaussian(r), gaussian(r)) * sigma
                    })
                })
                .collect()
        }
        Pattern::Radial => {
            // Default impact: the middle of the largest face of the bounds (the face of a
            // pane, the top of a slab), where a blow usually lands.
            let centre = impact.unwrap_or_else(|| {
                let e = hi - lo;
                let mid = (lo + hi) * 0.5;
                if e.y <= e.x && e.y <= e.z {
                    DVec3::new(mid.x, hi.y, mid.z)
                } else if e.x <= e.z {
                    DVec3::new(hi.x, mid.y, mid.z)
                } else {
                    DVec3::new(mid.x, mid.y, hi.z)
                }
            });
            // The spread follows the object's extents, so thin objects (panes) keep their
            // seeds inside instead of losing most draws above and below. Distances below
            // are measured in that frame (each axis over its extent).
            let extent = hi - lo;
            let unit = extent.max(DVec3::splat(f64::MIN_POSITIVE));
            let spacing = radial_spacing(piece.volume(), extent);
            let mut out: Vec<DVec3> = Vec::with_capacity(k);
            // The seeds placed so far in the frame of the extents (each axis over its
            // extent), so the spacing test of a draw against each is a subtraction and
            // a dot product (most draws near the impact are turned down by it).
            let mut scaled: Vec<DVec3> = Vec::with_capacity(k);
            for _ in 0..k {
                let mut placed = None;
                for _ in 0..RADIAL_TRIES {
                    // Radius ∝ u³: density falls off with distance from the impact.
                    let u: f64 = rng.random();
                    let p = centre + unit_vector(rng) * extent * (u * u * u);
                    // A seed is kept at a distance from the others that grows with its
                    // distance from the impact (a fifth of it), and is at least `spacing`:
                    // the u³ law alone puts seeds within 1e-5 of the extent of each
                    // other near the impact, whose cells (down to 1e-15 of the volume)
                    // are only merged away again, so 50 seeds made 26 fragments.
                    // (Checked before the inside test, which costs more.)
                    let q = (p - centre) / unit;
                    let min = (0.2 * q.length()).max(spacing);
                    let ps = p / unit;
                    let clear = scaled
                        .iter()
                        .all(|&o| (o - ps).length_squared() >= min * min);
                    if clear && sampler.contains(p) {
                        placed = Some(p);
                        break;
                    }
                }
                let p = placed.unwrap_or_else(|| sampler.uniform(rng));
                scaled.push(p / unit);
                out.push(p);
            }
            out
        }
    }
}

/// Draws per radial seed before it is placed anywhere inside.
const RADIAL_TRIES: usize = 400;

/// The least distance between radial seeds, as a fraction of the extents: twice the
/// radius of a ball whose volume is four times the sliver threshold (a ten-thousandth of
/// the solid, [`SLIVER_VOLUME_FRACTION`]), in the frame of the extents, so that a cell at
/// the impact, a fraction of such a ball inside the solid, is still about as big as the
/// sliver threshold. (The bird's bounding box is about four times its volume: 0.06.)
fn radial_spacing(volume: f64, extent: DVec3) -> f64 {
    let boxed = extent.x * extent.y * extent.z;
    if !(boxed > 0.0 && volume > 0.0) {
        return 0.0;
    }
    let ball = 4.0 * SLIVER_VOLUME_FRACTION * (volume / boxed).min(1.0);
    2.0 * (ball * 3.0 / (4.0 * std::f64::consts::PI)).cbrt()
}

/// The metric weights of [`Pattern::Splinter`] for a solid of box extents `e` (in the
/// input's frame): distances along the longest axis count a quarter, so cells are four
/// times longer along it.
pub(crate) fn splinter_weights(e: DVec3) -> DVec3 {
    let axis = if e.x >= e.y && e.x >= e.z {
        DVec3::X
    } else if e.y >= e.z {
        DVec3::Y
    } else {
        DVec3::Z
    };
    DVec3::ONE - axis * (1.0 - 1.0 / 16.0)
}
