//! Rebuilding a fragment with its roughened caps: the caps' old triangles out, each
//! cap's core (displaced, shared with the other side) and the side's own flat collar in,
//! with materials and corner attributes; and the check that the result does not cut
//! itself.

use glam::{DVec2, DVec3};

use super::regions::Region;
use super::tessellate::{CORE_ID, Core, barycentric2, region_triangles};
use crate::TriMesh;
use crate::fracture::Fragment;
use crate::mesh::triangles_meet;
use crate::model::Corners;
use crate::util::FastSet;

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
/// mass properties still the old ones) and the new patches, one per entry of `mine`.
pub(crate) fn rebuild(
    f: &Fragment,
    regions: &[Region],
    caps: &[Cap],
    mine: &[(usize, usize)],
) -> (Fragment, Vec<Patch>) {
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
    let mut patches = Vec::with_capacity(mine.len());
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
        let start = triangles.len();
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
        patches.push(Patch {
            start,
            core_end: start + cap.core.tris.len(),
            end: triangles.len(),
            boundary: region.boundary.clone(),
        });
    }
    let fragment = Fragment {
        mesh: TriMesh::new(positions, triangles),
        interior,
        corners,
        material,
        convex_pieces: f.convex_pieces.clone(),
        convex_hulls: f.convex_hulls.clone(),
        volume: f.volume,
        centroid: f.centroid,
        inertia: f.inertia,
    };
    (fragment, patches)
}

/// The new triangles of one cap side in a rebuilt fragment: `start..core_end` the
/// (displaced) core, `core_end..end` the flat collar; `boundary` the old cap's boundary
/// edges, which the patch must have as its own.
#[derive(Debug, Clone)]
pub(crate) struct Patch {
    pub start: usize,
    pub core_end: usize,
    pub end: usize,
    pub boundary: Vec<(u32, u32)>,
}

/// Whether the rebuilt fragment is sound. Each patch is a consistently wound surface
/// (every directed edge once) whose boundary is the old cap's, edge for edge, so the
/// fragment's topology is the old one's. And no displaced (core) triangle touches or
/// crosses a triangle outside its own patch (exact predicates; it shares no vertex with
/// them); within a patch the faces are a height field over the flat cap, so they cannot
/// meet.
pub(crate) fn sound(f: &Fragment, patches: &[Patch]) -> bool {
    let tris = &f.mesh.triangles;
    for p in patches {
        let mut directed: FastSet<(u32, u32)> = FastSet::default();
        for t in &tris[p.start..p.end] {
            for e in 0..3 {
                if !directed.insert((t[e], t[(e + 1) % 3])) {
                    return false;
                }
            }
        }
        let mut open: Vec<(u32, u32)> = directed
            .iter()
            .copied()
            .filter(|&(a, b)| !directed.contains(&(b, a)))
            .collect();
        let mut want = p.boundary.clone();
        open.sort_unstable();
        want.sort_unstable();
        if open != want {
            return false;
        }
    }
    let corners = |t: usize| f.mesh.triangle(t);
    let bounds = |c: [DVec3; 3]| (c[0].min(c[1]).min(c[2]), c[0].max(c[1]).max(c[2]));
    let meet = |(lo, hi): (DVec3, DVec3), (lo2, hi2): (DVec3, DVec3)| {
        !(lo2.cmpgt(hi).any() || lo.cmpgt(hi2).any())
    };
    for p in patches {
        let core: Vec<([DVec3; 3], (DVec3, DVec3))> = (p.start..p.core_end)
            .map(|t| (corners(t), bounds(corners(t))))
            .collect();
        let Some(all) = core
            .iter()
            .map(|c| c.1)
            .reduce(|a, b| (a.0.min(b.0), a.1.max(b.1)))
        else {
            continue;
        };
        for u in (0..tris.len()).filter(|&u| u < p.start || u >= p.end) {
            let cu = corners(u);
            let bu = bounds(cu);
            if !meet(all, bu) {
                continue;
            }
            if core
                .iter()
                .any(|(ct, bt)| meet(*bt, bu) && triangles_meet(*ct, cu))
            {
                return false;
            }
        }
    }
    true
}
