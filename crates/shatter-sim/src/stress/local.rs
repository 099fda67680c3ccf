//! An anchored island's springs with island-local ends, and `K·x` over contiguous
//! vectors: the pass every conjugate-gradient iteration makes.
//!
//! The island's free nodes are numbered `0..n` (ascending graph order); an anchored end
//! is numbered `n`, a slot every vector has and keeps at zero, so the pass has no branch.

use glam::DVec3;

use crate::stress::spring::Spring;

/// A node's displacement `u` and small rotation `θ` (or a force and a moment).
pub(super) type Dof = (DVec3, DVec3);

/// The zero [`Dof`].
pub(super) const ZERO: Dof = (DVec3::ZERO, DVec3::ZERO);

/// A bond's springs with island-local ends, laid out for the pass over them: the
/// constants as `ks`, `kn − ks`, `kb`, `kt − kb`.
#[derive(Debug, Clone, Copy)]
pub(super) struct LocalSpring {
    /// Local ends (`n`: anchored).
    pub a: u32,
    pub b: u32,
    pub ra: DVec3,
    pub rb: DVec3,
    pub n: DVec3,
    pub ks: f64,
    pub dn: f64,
    pub kb: f64,
    pub dt: f64,
}

impl LocalSpring {
    /// `s` with its ends numbered `a` and `b`.
    pub fn new(s: &Spring, a: u32, b: u32) -> LocalSpring {
        LocalSpring {
            a,
            b,
            ra: s.ra,
            rb: s.rb,
            n: s.n,
            ks: s.ks,
            dn: s.kn - s.ks,
            kb: s.kb,
            dt: s.kt - s.kb,
        }
    }

    /// Force on `b`'s side and moment of the bond when its ends move by `xa` and `xb`
    /// (see [`Spring::load`]).
    #[inline]
    pub fn load(&self, xa: Dof, xb: Dof) -> Dof {
        let d = (xb.0 + xb.1.cross(self.rb)) - (xa.0 + xa.1.cross(self.ra));
        let f = self.ks * d + (self.dn * self.n.dot(d)) * self.n;
        let dt = xb.1 - xa.1;
        let m = self.kb * dt + (self.dt * self.n.dot(dt)) * self.n;
        (f, m)
    }
}

/// The springs of one island, local ends.
#[derive(Debug, Clone, Default)]
pub(super) struct LocalSprings {
    /// Free nodes (the anchored slot is `n`).
    pub n: usize,
    pub springs: Vec<LocalSpring>,
}

impl LocalSprings {
    /// The springs `springs` (indices into `all`, in that order) of the island whose free
    /// nodes have the local indices `local` (`u32::MAX`: anchored); a spring between two
    /// anchored nodes stays, with both ends at `n` (it carries nothing).
    pub fn new(all: &[Spring], springs: &[u32], local: &[u32], n: usize) -> LocalSprings {
        let end = |v: u32| match local[v as usize] {
            u32::MAX => n as u32,
            l => l,
        };
        let springs = springs
            .iter()
            .map(|&b| &all[b as usize])
            .map(|s| LocalSpring::new(s, end(s.a), end(s.b)))
            .collect();
        LocalSprings { n, springs }
    }

    /// `out = K·x`; both have `n + 1` entries, `x[n]` zero (`out[n]` is left zero).
    /// Returns `x·K·x`, the springs' energy (twice it), summed in the same pass.
    pub fn times(&self, x: &[Dof], out: &mut [Dof]) -> f64 {
        times(&self.springs, x, out)
    }
}

/// `out = K·x` over `springs` (see [`LocalSprings::times`]): one pass, each spring once;
/// returns `x·K·x` as `Σ δ·f + Δθ·m` over the springs (their relative motion times their
/// force and moment), which saves a pass over the vectors.
pub(super) fn times(springs: &[LocalSpring], x: &[Dof], out: &mut [Dof]) -> f64 {
    out.fill(ZERO);
    let mut energy = 0.0;
    for s in springs {
        let (a, b) = (s.a as usize, s.b as usize);
        let (xa, xb) = (x[a], x[b]);
        let d = (xb.0 + xb.1.cross(s.rb)) - (xa.0 + xa.1.cross(s.ra));
        let f = s.ks * d + (s.dn * s.n.dot(d)) * s.n;
        let dt = xb.1 - xa.1;
        let m = s.kb * dt + (s.dt * s.n.dot(dt)) * s.n;
        energy += d.dot(f) + dt.dot(m);
        let ob = &mut out[b];
        ob.0 += f;
        ob.1 += s.rb.cross(f) + m;
        let oa = &mut out[a];
        oa.0 -= f;
        oa.1 -= s.ra.cross(f) + m;
    }
    if let Some(last) = out.last_mut() {
        *last = ZERO;
    }
    energy
}
