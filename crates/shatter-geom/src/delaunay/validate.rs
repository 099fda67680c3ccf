//! Exact checks of a result: orientation, adjacency, the (perturbed) Delaunay property on
//! every interior face, a locally convex closed hull and every distinct point used.

use std::collections::HashMap;

use glam::DVec3;

use super::predicates::{insphere_perturbed, orient};
use super::types::{FACES, NO_NEIGHBOR, Tetrahedralization};

/// A violated invariant, found by [`Tetrahedralization::validate`].
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ValidationError {
    /// Arrays of different lengths or an index out of range.
    #[error("malformed result: {0}")]
    Malformed(String),
    /// A tetrahedron is not positively oriented (exactly).
    #[error("tetrahedron {tet} {verts:?} is not positively oriented")]
    Orientation {
        /// The tetrahedron.
        tet: usize,
        /// Its vertices.
        verts: [u32; 4],
    },
    /// `neighbors` is not symmetric or neighbours do not share the face.
    #[error("tetrahedra {tet} and {other} are not mutual neighbours across face {face}")]
    Adjacency {
        /// The tetrahedron.
        tet: usize,
        /// The face index.
        face: usize,
        /// The claimed neighbour.
        other: u32,
    },
    /// A vertex lies inside the (perturbed) circumsphere of an adjacent tetrahedron.
    #[error("vertex {vertex} is inside the circumsphere of tetrahedron {tet}")]
    NotDelaunay {
        /// The tetrahedron.
        tet: usize,
        /// The offending vertex.
        vertex: u32,
    },
    /// The hull is not a closed surface or not convex.
    #[error("hull: {0}")]
    Hull(String),
    /// A distinct input point is not a vertex of any tetrahedron.
    #[error("point {0} is not used")]
    Unused(u32),
}

impl Tetrahedralization {
    /// Checks the result against `points` with exact predicates: positive orientation,
    /// symmetric adjacency across shared faces, every interior face locally Delaunay under
    /// the same symbolic perturbation as the construction ([`insphere_perturbed`]), the hull
    /// a closed, locally convex surface whose flat parts are (perturbed) 2D Delaunay, and
    /// every distinct point used. Together these imply a Delaunay tetrahedralization of the
    /// convex hull.
    pub fn validate(&self, points: &[DVec3]) -> Result<(), ValidationError> {
        let p: Vec<[f64; 3]> = points.iter().map(|q| q.to_array()).collect();
        let nt = self.len();
        if self.representative.len() != p.len() {
            return Err(ValidationError::Malformed(format!(
                "{} representatives for {} points",
                self.representative.len(),
                p.len()
            )));
        }
        let mut used = vec![false; p.len()];
        for (t, v) in self.tetrahedra().enumerate() {
            for &x in &v {
                if x as usize >= p.len() || self.representative[x as usize] != x {
                    return Err(ValidationError::Malformed(format!(
                        "tetrahedron {t} has vertex {x}, not a representative input point"
                    )));
                }
                used[x as usize] = true;
            }
            let q = |k: usize| &p[v[k] as usize];
            if orient(q(0), q(1), q(2), q(3)) <= 0.0 {
                return Err(ValidationError::Orientation { tet: t, verts: v });
            }
        }
        for (i, &r) in self.representative.iter().enumerate() {
            if r as usize == i && !used[i] {
                return Err(ValidationError::Unused(r));
            }
        }
        for (t, v) in self.tetrahedra().enumerate() {
            let q = |k: usize| &p[v[k] as usize];
            let nb = self.neighbors(t);
            for (face, &n) in nb.iter().enumerate() {
                if n == NO_NEIGHBOR {
                    continue;
                }
                let err = ValidationError::Adjacency {
                    tet: t,
                    face,
                    other: n,
                };
                if n as usize >= nt {
                    return Err(err);
                }
                let w = self.tetrahedron(n as usize);
                let back = (0..4)
                    .find(|&j| self.neighbors(n as usize)[j] == t as u32)
                    .ok_or_else(|| err.clone())?;
                let shared = (0..4).filter(|&k| k != face).all(|k| w.contains(&v[k]));
                if !shared || v.contains(&w[back]) {
                    return Err(err);
                }
                if insphere_perturbed(q(0), q(1), q(2), q(3), &p[w[back] as usize]) {
                    return Err(ValidationError::NotDelaunay {
                        tet: t,
                        vertex: w[back],
                    });
                }
            }
        }
        self.validate_hull(&p)
    }

    fn validate_hull(&self, p: &[[f64; 3]]) -> Result<(), ValidationError> {
        // Directed hull edge (u, v) -> (tetrahedron, the face's third vertex).
        let mut edges: HashMap<(u32, u32), (usize, u32)> = HashMap::new();
        for (t, v) in self.tetrahedra().enumerate() {
            let nb = self.neighbors(t);
            for (i, f) in FACES.iter().enumerate() {
                if nb[i] != NO_NEIGHBOR {
                    continue;
                }
                let tri = [v[f[0]], v[f[1]], v[f[2]]];
                for k in 0..3 {
                    let e = (tri[k], tri[(k + 1) % 3]);
                    if edges.insert(e, (t, tri[(k + 2) % 3])).is_some() {
                        return Err(ValidationError::Hull(format!("edge {e:?} used twice")));
                    }
                }
            }
        }
        for (&(a, b), &(t, c)) in &edges {
            let &(_, w) = edges
                .get(&(b, a))
                .ok_or_else(|| ValidationError::Hull(format!("boundary edge ({a}, {b})")))?;
            // Outward face (a, b, c): interior points have orient(a, b, c, ·) < 0, so w must
            // not be positive (strictly outside).
            let o = orient(
                &p[a as usize],
                &p[b as usize],
                &p[c as usize],
                &p[w as usize],
            );
            if o > 0.0 {
                return Err(ValidationError::Hull(format!(
                    "not convex at edge ({a}, {b}): {w} outside face ({a}, {b}, {c})"
                )));
            }
            if o == 0.0 {
                let v = self.tetrahedron(t);
                let q = |k: usize| &p[v[k] as usize];
                if insphere_perturbed(q(0), q(1), q(2), q(3), &p[w as usize]) {
                    return Err(ValidationError::NotDelaunay { tet: t, vertex: w });
                }
            }
        }
        Ok(())
    }
}
