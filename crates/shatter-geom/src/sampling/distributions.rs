//! The point distributions.

use std::str::FromStr;

use glam::DVec3;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// A named point distribution.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Distribution {
    /// Uniform in the cube `[-1, 1]³` ([`uniform`]).
    Uniform,
    /// Uniform in the unit ball ([`ball`]).
    Ball,
    /// Uniform on the unit sphere ([`sphere`]): every point cospherical.
    Sphere,
    /// Standard normal in each coordinate ([`gaussian`]).
    Gaussian,
    /// A regular integer grid ([`grid`]): massively coplanar and cospherical.
    Grid,
}

impl Distribution {
    /// Every distribution, in the order of the CLI's help.
    pub const ALL: [Distribution; 5] = [
        Self::Uniform,
        Self::Ball,
        Self::Sphere,
        Self::Gaussian,
        Self::Grid,
    ];

    /// The CLI name.
    pub fn name(self) -> &'static str {
        match self {
            Self::Uniform => "uniform",
            Self::Ball => "ball",
            Self::Sphere => "sphere",
            Self::Gaussian => "gaussian",
            Self::Grid => "grid",
        }
    }
}

impl FromStr for Distribution {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|d| d.name() == s)
            .ok_or_else(|| {
                format!(
                    "unknown distribution '{s}' (expected uniform, ball, sphere, gaussian or grid)"
                )
            })
    }
}

/// `n` points of distribution `dist` from `seed`.
///
/// ```
/// use shatter_geom::sampling::{Distribution, sample};
/// let a = sample(Distribution::Ball, 100, 7);
/// assert_eq!(a, sample(Distribution::Ball, 100, 7));
/// assert!(a.iter().all(|p| p.length() <= 1.0));
/// ```
pub fn sample(dist: Distribution, n: usize, seed: u64) -> Vec<DVec3> {
    match dist {
        Distribution::Uniform => uniform(n, seed),
        Distribution::Ball => ball(n, seed),
        Distribution::Sphere => sphere(n, seed),
        Distribution::Gaussian => gaussian(n, seed),
        Distribution::Grid => grid(n, seed),
    }
}

fn rng(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
}

fn in_cube(r: &mut ChaCha8Rng) -> DVec3 {
    DVec3::new(
        r.random_range(-1.0..1.0),
        r.random_range(-1.0..1.0),
        r.random_range(-1.0..1.0),
    )
}

/// `n` points uniform in the cube `[-1, 1]³`.
pub fn uniform(n: usize, seed: u64) -> Vec<DVec3> {
    let mut r = rng(seed);
    (0..n).map(|_| in_cube(&mut r)).collect()
}

/// `n` points uniform in the unit ball (rejection sampling from the cube).
pub fn ball(n: usize, seed: u64) -> Vec<DVec3> {
    let mut r = rng(seed);
    (0..n)
        .map(|_| {
            loop {
                let p = in_cube(&mut r);
                if p.length_squared() <= 1.0 {
                    break p;
                }
            }
        })
        .collect()
}

/// `n` points uniform on the unit sphere (normalised ball samples).
pub fn sphere(n: usize, seed: u64) -> Vec<DVec3> {
    let mut r = rng(seed);
    (0..n)
        .map(|_| {
            loop {
                let p = in_cube(&mut r);
                let l = p.length_squared();
                if l <= 1.0 && l > 1e-6 {
                    break p / l.sqrt();
                }
            }
        })
        .collect()
}

/// `n` points with independent standard normal coordinates (Box–Muller).
pub fn gaussian(n: usize, seed: u64) -> Vec<DVec3> {
    let mut r = rng(seed);
    let mut normal = move || {
        let u: f64 = 1.0 - r.random::<f64>(); // (0, 1]
        let v: f64 = r.random::<f64>();
        (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
    };
    (0..n)
        .map(|_| DVec3::new(normal(), normal(), normal()))
        .collect()
}

/// `n` points of the integer grid `k × k × k`, `k = ⌈∛n⌉`, taken in x-fastest order (the
/// last layer may be partial), then shuffled by `seed`.
pub fn grid(n: usize, seed: u64) -> Vec<DVec3> {
    let mut k = 1usize;
    while k * k * k < n {
        k += 1;
    }
    let mut pts: Vec<DVec3> = (0..n)
        .map(|i| DVec3::new((i % k) as f64, (i / k % k) as f64, (i / (k * k)) as f64))
        .collect();
    let mut r = rng(seed);
    for i in (1..pts.len()).rev() {
        let j = r.random_range(0..=i);
        pts.swap(i, j);
    }
    pts
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distributions_are_deterministic_and_in_range() {
        for d in Distribution::ALL {
            let a = sample(d, 500, 3);
            assert_eq!(a.len(), 500);
            assert_eq!(a, sample(d, 500, 3), "{d:?} not deterministic");
            assert_ne!(a, sample(d, 500, 4), "{d:?} ignores the seed");
            assert_eq!(d.name().parse::<Distribution>(), Ok(d));
        }
        assert!(uniform(500, 1).iter().all(|p| p.abs().max_element() <= 1.0));
        assert!(
            sphere(500, 1)
                .iter()
                .all(|p| (p.length() - 1.0).abs() < 1e-12)
        );
        let g = grid(1000, 1);
        assert!(
            g.iter()
                .all(|p| p.max_element() <= 9.0 && p.min_element() >= 0.0)
        );
        assert!("cube".parse::<Distribution>().is_err());
    }
}
