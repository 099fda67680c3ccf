//! One bond's springs (normal, shear, bending, twisting) and the small matrix helpers
//! of the solver.

use glam::{DMat3, DVec3};

use crate::stress::limits::BondStress;

/// Per-bond spring constants and lever arms.
#[derive(Debug, Clone, Copy)]
pub(super) struct Spring {
    pub a: u32,
    pub b: u32,
    pub ra: DVec3,
    pub rb: DVec3,
    pub n: DVec3,
    pub kn: f64,
    pub ks: f64,
    pub kb: f64,
    pub kt: f64,
    pub area: f64,
}

impl Spring {
    /// Force on `b`'s side and moment of the bond for the state `(u, θ)`.
    #[cfg(test)]
    pub fn load(&self, u: &[DVec3], t: &[DVec3]) -> (DVec3, DVec3) {
        let (a, b) = (self.a as usize, self.b as usize);
        let d = (u[b] + t[b].cross(self.rb)) - (u[a] + t[a].cross(self.ra));
        let f = self.ks * d + ((self.kn - self.ks) * self.n.dot(d)) * self.n;
        let dt = t[b] - t[a];
        let m = self.kb * dt + ((self.kt - self.kb) * self.n.dot(dt)) * self.n;
        (f, m)
    }

    pub fn stress(&self, f: DVec3, m: DVec3) -> BondStress {
        let area = self.area;
        let edge = area * area.sqrt();
        let fnormal = self.n.dot(f);
        let fshear = (f - fnormal * self.n).length();
        let twist = self.n.dot(m);
        let bend = (m - twist * self.n).length();
        let sigma_bend = 6.0 * bend / edge;
        BondStress {
            tension: (fnormal / area + sigma_bend).max(0.0),
            compression: (-fnormal / area + sigma_bend).max(0.0),
            shear: fshear / area + 3.0 * twist.abs() / edge,
        }
    }
}

pub(super) fn outer(a: DVec3, b: DVec3) -> DMat3 {
    DMat3::from_cols(a * b.x, a * b.y, a * b.z)
}

/// The matrix of `r × ·`.
pub(super) fn skew(r: DVec3) -> DMat3 {
    DMat3::from_cols(
        DVec3::new(0.0, r.z, -r.y),
        DVec3::new(-r.z, 0.0, r.x),
        DVec3::new(r.y, -r.x, 0.0),
    )
}

/// The inverse of a symmetric positive block, or of its diagonal if it is singular.
pub(super) fn invert(m: DMat3) -> DMat3 {
    let det = m.determinant();
    let scale = m.x_axis.x.abs() * m.y_axis.y.abs() * m.z_axis.z.abs();
    if det.is_finite() && det > 1e-12 * scale && scale > 0.0 {
        m.inverse()
    } else {
        let d = DVec3::new(m.x_axis.x, m.y_axis.y, m.z_axis.z);
        DMat3::from_diagonal(DVec3::select(d.cmpgt(DVec3::ZERO), 1.0 / d, DVec3::ZERO))
    }
}
