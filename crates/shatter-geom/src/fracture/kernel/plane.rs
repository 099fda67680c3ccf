//! Oriented cutting planes.

use glam::DVec3;

/// An oriented plane `n · x = d`; its negative side `n · x < d` is kept by
/// [`clip`](super::clip::clip). `tag` is written on the cap triangles the plane creates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Plane {
    pub n: DVec3,
    pub d: f64,
    pub tag: u64,
}

impl Plane {
    /// The same plane with the other side kept (negation is exact in floating point, so
    /// both sides classify every vertex identically and share their cut vertices).
    pub fn flipped(self) -> Self {
        Self {
            n: -self.n,
            d: -self.d,
            tag: self.tag,
        }
    }

    /// Signed distance times `|n|`.
    #[inline]
    pub fn eval(&self, p: DVec3) -> f64 {
        self.n.dot(p) - self.d
    }
}
