//! Shells (connected components) of a closed mesh and their nesting, to check that every
//! shell is wound the right way: outward for a solid, inward for a cavity.

use glam::DVec3;

use super::TriMesh;
use super::winding::solid_angle;
use crate::util::UnionFind;

/// One connected component of a welded mesh.
pub(super) struct Shell {
    /// Its triangles (indices into the mesh).
    pub triangles: Vec<u32>,
    /// Signed volume.
    pub volume: f64,
    /// Bounds.
    pub lo: DVec3,
    /// Bounds.
    pub hi: DVec3,
    /// One of its vertices: the origin of its volume sum.
    pub probe: DVec3,
}

/// Points of a shell at which the other shells' winding numbers are asked: centroids of
/// up to this many of its triangles, spread over it.
const PROBES: usize = 7;

/// Whether every shell is wound consistently with its nesting.
pub(super) enum ShellOrientation {
    /// Every solid outward, every cavity inward.
    Outward,
    /// Flipping every triangle would make it outward.
    Inward,
    /// This many shells of `total` are wound against their nesting (or nested oddly).
    Mixed {
        /// Shells in error.
        wrong: usize,
        /// All shells.
        total: usize,
    },
}

/// The shells of a welded mesh whose indices are in range.
pub(super) fn shells(mesh: &TriMesh) -> Vec<Shell> {
    let mut sets = UnionFind::new(mesh.positions.len());
    for &[a, b, c] in &mesh.triangles {
        sets.union(a as usize, b as usize);
        sets.union(b as usize, c as usize);
    }
    let mut index_of_root = std::collections::HashMap::new();
    let mut out: Vec<Shell> = Vec::new();
    for (t, tri) in mesh.triangles.iter().enumerate() {
        let root = sets.find(tri[0] as usize);
        let k = *index_of_root.entry(root).or_insert_with(|| {
            let p = mesh.positions[tri[0] as usize];
            out.push(Shell {
                triangles: Vec::new(),
                volume: 0.0,
                lo: p,
                hi: p,
                probe: p,
            });
            out.len() - 1
        });
        let shell = &mut out[k];
        shell.triangles.push(t as u32);
        let [a, b, c] = mesh.triangle(t);
        let o = shell.probe;
        shell.volume += (a - o).dot((b - o).cross(c - o)) / 6.0;
        shell.lo = shell.lo.min(a).min(b).min(c);
        shell.hi = shell.hi.max(a).max(b).max(c);
    }
    out
}

/// Classifies the winding of the shells of a closed, manifold, non-self-intersecting
/// welded mesh. A shell enclosed by none of the others must have a positive volume; one
/// enclosed once (a cavity) a negative one; deeper nesting alternates. Winding numbers
/// are only computed for shells whose bounds lie inside another shell's bounds.
pub(super) fn orientation(mesh: &TriMesh) -> ShellOrientation {
    let shells = shells(mesh);
    let total = shells.len();
    let mut wrong = 0;
    let mut wrong_if_flipped = 0;
    for (i, s) in shells.iter().enumerate() {
        // Triangle centroids, not a vertex: where two shells touch (a face of one lying on
        // a face of the other, as parts that met face to face do after their union) a
        // point on the touching face has a winding number of ½ for the other shell, which
        // says nothing. The median over probes spread across the shell is robust to that.
        let step = (s.triangles.len() / PROBES).max(1);
        let probes: Vec<DVec3> = s
            .triangles
            .iter()
            .step_by(step)
            .take(PROBES)
            .map(|&t| {
                let [a, b, c] = mesh.triangle(t as usize);
                (a + b + c) / 3.0
            })
            .collect();
        let mut windings = vec![0.0; probes.len()];
        for (j, other) in shells.iter().enumerate() {
            let inside_bounds = (s.lo.cmpge(other.lo) & s.hi.cmple(other.hi)).all();
            if i == j || !inside_bounds {
                continue;
            }
            for (w, &p) in windings.iter_mut().zip(&probes) {
                let mut angle = 0.0;
                for &t in &other.triangles {
                    let [a, b, c] = mesh.triangle(t as usize);
                    angle += solid_angle(a - p, b - p, c - p);
                }
                *w += angle / (4.0 * std::f64::consts::PI);
            }
        }
        windings.sort_unstable_by(f64::total_cmp);
        let w = windings
            .get(windings.len() / 2)
            .copied()
            .unwrap_or(0.0)
            .round();
        let ok = |w: f64, volume: f64| (w == 0.0 && volume > 0.0) || (w == 1.0 && volume < 0.0);
        if !ok(w, s.volume) {
            wrong += 1;
        }
        if !ok(-w, -s.volume) {
            wrong_if_flipped += 1;
        }
    }
    if wrong == 0 {
        ShellOrientation::Outward
    } else if wrong_if_flipped == 0 {
        ShellOrientation::Inward
    } else {
        ShellOrientation::Mixed { wrong, total }
    }
}
