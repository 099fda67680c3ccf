//! Seed patterns for Voronoi fracture, and uniform sampling inside a solid.

use glam::DVec3;
use rand::Rng;
use rand_chacha::ChaCha8Rng;

use super::inside::InsideSampler;
use crate::fracture::Pattern;
use crate::fracture::kernel::Piece;

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
            // seeds inside instead of losing most draws above and below.
            let extent = hi - lo;
            (0..k)
                .map(|_| {
                    let p = sampler.inside_from(rng, |r| {
                        // Radius ∝ u³: density falls off with distance from the impact.
                        let u: f64 = r.random();
                        centre + unit_vector(r) * extent * (u * u * u)
                    });
                    if sampler.contains(p) {
                        p
                    } else {
                        sampler.uniform(rng)
                    }
                })
                .collect()
        }
    }
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
