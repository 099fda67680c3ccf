//! Rebuilding a fragment with its roughened caps: the caps' old triangles out, each
//! cap's core (displaced, shared with the other side) and the side's own flat collar in,
//! with materials and corner attributes; and the check that the result does not cut
//! itself.

use glam::{DVec2, DVec3};

use super::regions::Region;
use super::tessellate::{CORE_ID, Core, barycentric2, region_triangles};
use crate::TriMesh;
use crate::fracture::Fragment;
use crate::mesh::MeshReport;
use crate::model::Corners;

/// One cap being roughened.
#[derive(Debug, Clone)]
pub(crate) struct Cap {
    /// Its two regions (indices into the region list): side 0 (whose normal is the
    /// core's `frame.n`) and side 1.
    pub sides: [usize; 2],
    /// The shared core.
    pub core: Core,
    /// Each side's collar (see [`super::tessellate::collar`]).
    pub collars: [Vec<[u32; 3]>; 2],
    /// The amplitude used (0: the cap is left flat).
    pub amplitude: f64,
    /// The core's UVs, from side 0's planar UVs (when the fragments have UVs).
    pub core_uv: Option<Vec<[f32; 2]>>,
}

impl Cap {
    /// The core's positions for the current amplitude.
    pub fn positions(&self) -> Vec<DVec3> {
        let n = self.core.frame.n;
        self.core
            .flat
            .iter()
            .zip(self.core.heights(self.amplitude))
            .map(|(&p, h)| if h == 0.0 { p } else { p + n * h })
            .collect()
    }
}

/// A region's old triangles in 2D with their UVs, for interpolating UVs of new points.
pub(crate) struct UvSource {
    tris: Vec<[DVec2; 3]>,
    uv: Vec<[[f32; 2]; 3]>,
}

impl UvSource {
    /// The source of region `r` of `f` (`None` when `f` has no UVs).
    pub fn of(f: &Fragment, r: &Region, core: &Core) -> Option<UvSource> {
        let uv = f.corners.uv.as_ref()?;
        Some(UvSource {
            tris: region_triangles(f, r, &core.frame),
            uv: r.tris.iter().map(|&t| uv[t as usize]).collect(),
        })
    }

    /// The UV at `q`: interpolated in the old triangle that contains it best (the
    /// largest smallest barycentric coordinate). Planar UVs are affine on the plane, so
    /// this is the projection itself, up to `f32`.
    pub fn at(&self, q: DVec2) -> [f32; 2] {
        let mut best: Option<(f64, usize, [f64; 3])> = None;
        for (t, tri) in self.tris.iter().enumerate() {
            let Some(w) = barycentric2(tri, q) else {
                continue;
            };
            let m = w[0].min(w[1]).min(w[2]);
            if best.is_none_or(|(b, _, _)| m > b) {
                best = Some((m, t, w));
            }
        }
        let Some((_, t, w)) = best else {
            return [0.0, 0.0];
        };
        let c = &self.uv[t];
        std::array::from_fn(|i| (0..3).map(|k| f64::from(c[k][i]) * w[k]).sum::<f64>() as f32)
    }
}

/// Fragment `f` (index `index`) rebuilt with the caps in `mine` (`(cap, side)` pairs):
/// the other triangles in their order, then per cap its core and the side's collar.
/// Side 1 gets the core wound the other way. Returns the fragment (convex pieces and
/// mass properties still the old ones) and the index of its first new triangle.
pub(crate) fn rebuild(
    f: &Fragment,
    regions: &[Region],
    caps: &[Cap],
    mine: &[(usize, usize)],
) -> (Fragment, usize) {
    let mut drop = vec![false; f.mesh.triangles.len()];
    for &(c, side) in mine {
        for &t in &regions[caps[c].sides[side]].tris {
            drop[t as usize] = true;
        }
    }
    let keep: Vec<usize> = (0..drop.len()).filter(|&t| !drop[t]).collect();
    let mut positions = f.mesh.positions.clone();
    let mut triangles: Vec<[u32; 3]> = keep.iter().map(|&t| f.mesh.triangles[t]).collect();
    let mut interior: Vec<bool> = keep.iter().map(|&t| f.interior[t]).collect();
    let mut material: Vec<u32> = keep
        .iter()
        .map(|&t| f.material.get(t).copied().unwrap_or(0))
        .collect();
    let mut corners: Corners = f.corners.select(&keep);
    let first_new = triangles.len();
    for &(c, side) in mine {
        let cap = &caps[c];
        let region = &regions[cap.sides[side]];
        let old = region.tris[0] as usize;
        let mat = f.material.get(old).copied().unwrap_or(0);
        let color = f.corners.color.as_ref().map(|c| c[old][0]);
        let uv_source = UvSource::of(f, region, &cap.core);
        let base = positions.len() as u32;
        positions.extend(cap.positions());
        let id = |i: u32| {
            if i >= CORE_ID {
                base + (i - CORE_ID)
            } else {
                i
            }
        };
        let uv_of = |i: u32| -> [f32; 2] {
            if i >= CORE_ID {
                cap.core_uv
                    .as_ref()
                    .map_or([0.0; 2], |uv| uv[(i - CORE_ID) as usize])
            } else {
                uv_source.as_ref().map_or([0.0; 2], |s| {
                    s.at(cap.core.frame.to2(f.mesh.positions[i as usize]))
                })
            }
        };
        let core_tris = cap.core.tris.iter().map(|t| t.map(|k| CORE_ID + k));
        for t in core_tris.chain(cap.collars[side].iter().copied()) {
            // Counter-clockwise in the frame: side 0's winding; side 1 is reversed.
            let t = if side == 0 { t } else { [t[0], t[2], t[1]] };
            let tri = t.map(id);
            triangles.push(tri);
            interior.push(true);
            material.push(mat);
            let p = tri.map(|i| positions[i as usize]);
            if let Some(out) = &mut corners.uv {
                out.push(t.map(uv_of));
            }
            if let Some(out) = &mut corners.normal {
                let n = (p[1] - p[0]).cross(p[2] - p[0]).normalize_or_zero();
                out.push([n.as_vec3().to_array(); 3]);
            }
            if let (Some(out), Some(col)) = (&mut corners.color, color) {
                out.push([col; 3]);
            }
        }
    }
    let fragment = Fragment {
        mesh: TriMesh::new(positions, triangles),
        interior,
        corners,
        material,
        convex_pieces: f.convex_pieces.clone(),
        volume: f.volume,
        centroid: f.centroid,
        inertia: f.inertia,
    };
    (fragment, first_new)
}

/// Whether the rebuilt fragment is sound: its topology no worse than `before`'s (the
/// old fragment's check: closed, manifold and consistently wound fragments stay so) and
/// no new triangle touching or crossing another triangle it shares no vertex with
/// (exact predicates).
pub(crate) fn sound(f: &Fragment, first_new: usize, before: &MeshReport) -> bool {
    let r = f.mesh.check();
    let worse = r.boundary_edges > before.boundary_edges
        || r.non_manifold_edges > before.non_manifold_edges
        || r.non_manifold_vertices > before.non_manifold_vertices
        || r.inconsistent_edges > before.inconsistent_edges
        || r.invalid_triangles > before.invalid_triangles
        || r.degenerate_triangles > before.degenerate_triangles;
    if worse {
        return false;
    }
    f.mesh
        .self_intersections(usize::MAX)
        .iter()
        .all(|&(s, t)| (s as usize) < first_new && (t as usize) < first_new)
}
