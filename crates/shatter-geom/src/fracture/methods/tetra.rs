//! The thesis's method: a Delaunay tetrahedralization of surface vertices and random
//! points; every tetrahedron (inside the mesh) is a fragment, slivers merged into a
//! neighbour.

use std::collections::BTreeMap;

use glam::DVec3;
use rand::Rng;
use rand_chacha::ChaCha8Rng;

use crate::TriMesh;
use crate::delaunay::{NO_NEIGHBOR, Tetrahedralization, tetrahedralize};
use crate::fracture::kernel::Piece;
use crate::fracture::kernel::convex::{TET_FACES, tet_volume};
use crate::fracture::seeds::inside::{InsideSampler, InsideTester};
use crate::fracture::{Bond, FractureError, Fragment, Placement};
use crate::mesh::mass_properties;
use crate::util::UnionFind;

/// A tetrahedron (or group) below this fraction of the object's volume is a sliver.
pub const SLIVER_VOLUME_FRACTION: f64 = 1e-4;
/// A lone tetrahedron whose quality `6√2·V / L³` (1 for a regular tetrahedron, `L` its
/// longest edge) is below this is a sliver.
pub const SLIVER_QUALITY: f64 = 1e-2;

/// Options of the tetra method.
pub(crate) struct TetraOptions {
    pub random_vertices: usize,
    pub skip: usize,
    pub center: bool,
    pub placement: Placement,
}

/// The point set of the thesis: every `(skip + 1)`-th surface vertex, the random points,
/// then the centre if asked.
pub(crate) fn tetra_points(mesh: &Piece, opt: &TetraOptions, rng: &mut ChaCha8Rng) -> Vec<DVec3> {
    let mut pts: Vec<DVec3> = mesh.pos.iter().step_by(opt.skip + 1).copied().collect();
    let centre = mass_properties(&mesh.pos, &mesh.tris).1;
    match opt.placement {
        Placement::Interior => {
            let sampler = InsideSampler::new(mesh);
            for _ in 0..opt.random_vertices {
                pts.push(sampler.uniform(rng));
            }
        }
        Placement::Thesis => {
            // The thesis's scheme, except that a point it puts outside the mesh (which
            // happens for concave or asymmetric meshes) is redrawn, a bounded number of
            // times, so no fragment pokes out of the object.
            let tester = InsideTester::new(mesh);
            for _ in 0..opt.random_vertices {
                for _ in 0..64 {
                    let p = pts[rng.random_range(0..pts.len())];
                    let d = rng.random_range(0.0..=1.0) * (p - centre).length();
                    let q = centre + (centre - p).normalize_or_zero() * d;
                    if tester.contains(q) {
                        pts.push(q);
                        break;
                    }
                }
            }
        }
    }
    if opt.center {
        pts.push(centre);
    }
    pts
}

/// Tetra fracture of `mesh` (welded, outward, volume `mesh_volume`).
pub(crate) fn tetra(
    mesh: &Piece,
    mesh_volume: f64,
    opt: &TetraOptions,
    rng: &mut ChaCha8Rng,
    warnings: &mut Vec<String>,
) -> Result<(Vec<Fragment>, Vec<Bond>), FractureError> {
    let pts = tetra_points(mesh, opt, rng);
    let del = tetrahedralize(&pts)?;
    let nt = del.len();
    let corners = |t: usize| del.tetrahedron(t).map(|i| pts[i as usize]);
    let vols: Vec<f64> = (0..nt).map(|t| tet_volume(corners(t))).collect();
    let hull_volume: f64 = vols.iter().sum();

    // Keep every tetrahedron when the points' hull is the mesh (a convex mesh with all
    // points inside); otherwise only those whose centroid is inside the mesh.
    let all_inside = (hull_volume - mesh_volume).abs() <= 1e-9 * mesh_volume;
    let tester = InsideTester::new(mesh);
    let keep: Vec<bool> = (0..nt)
        .map(|t| {
            all_inside || {
                let c = corners(t);
                tester.contains((c[0] + c[1] + c[2] + c[3]) / 4.0)
            }
        })
        .collect();

    // Merge slivers (by groups) into the neighbour across their largest face.
    let vmin = SLIVER_VOLUME_FRACTION * mesh_volume;
    let face_area = |t: usize, f: usize| {
        let c = corners(t);
        let [a, b, cc] = TET_FACES[f].map(|i| c[i]);
        (b - a).cross(cc - a).length() / 2.0
    };
    let mut uf = UnionFind::new(nt);
    let mut gvol = vols.clone();
    let mut gcount = vec![1usize; nt];
    let bad: Vec<bool> = (0..nt)
        .map(|t| quality(corners(t)) < SLIVER_QUALITY)
        .collect();
    let mut order: Vec<usize> = (0..nt).filter(|&t| keep[t]).collect();
    order.sort_by(|&a, &b| vols[a].total_cmp(&vols[b]).then(a.cmp(&b)));
    loop {
        let mut changed = false;
        for &t in &order {
            let g = uf.find(t);
            let small = gvol[g] < vmin || (gcount[g] == 1 && bad[t]);
            if !small {
                continue;
            }
            let mut best: Option<(f64, usize)> = None;
            for f in 0..4 {
                let n = del.neighbors(t)[f];
                if n == NO_NEIGHBOR || !keep[n as usize] || uf.find(n as usize) == g {
                    continue;
                }
                let a = face_area(t, f);
                if best.is_none_or(|(ba, _)| a > ba) {
                    best = Some((a, n as usize));
                }
            }
            if let Some((_, n)) = best {
                let h = uf.find(n);
                let (v, c) = (gvol[g] + gvol[h], gcount[g] + gcount[h]);
                uf.union(g, h);
                let r = uf.find(g);
                gvol[r] = v;
                gcount[r] = c;
                changed = true;
            }
        }
        if !changed {
            break;
        }
    }

    // Groups in order of their first tetrahedron; small isolated groups are dropped.
    let mut frag_of_root: BTreeMap<usize, u32> = BTreeMap::new();
    let mut members: Vec<Vec<usize>> = Vec::new();
    let mut dropped = 0usize;
    let mut frag = vec![u32::MAX; nt];
    for t in 0..nt {
        if !keep[t] {
            continue;
        }
        let g = uf.find(t);
        if gvol[g] < vmin || (gcount[g] == 1 && bad[t]) {
            dropped += 1;
            continue;
        }
        let id = *frag_of_root.entry(g).or_insert_with(|| {
            members.push(Vec::new());
            (members.len() - 1) as u32
        });
        members[id as usize].push(t);
        frag[t] = id;
    }
    if dropped > 0 {
        warnings.push(format!(
            "{dropped} isolated sliver tetrahedra (no neighbour to merge into) were dropped"
        ));
    }

    // A tetrahedron is a collision piece unless its volume is negligible (a flat one
    // would make a degenerate collider; those only add mass to their group).
    let piece_ok: Vec<bool> = (0..nt).map(|t| vols[t] >= vmin).collect();
    let fragments = members
        .iter()
        .map(|ts| group_fragment(ts, &del, &frag, &pts, &piece_ok))
        .collect();

    // Bonds: shared faces between tetrahedra of different fragments.
    let mut acc: BTreeMap<(u32, u32), (f64, DVec3, DVec3)> = BTreeMap::new();
    for t in 0..nt {
        if frag[t] == u32::MAX {
            continue;
        }
        for (f, face) in TET_FACES.iter().enumerate() {
            let n = del.neighbors(t)[f];
            if n == NO_NEIGHBOR || frag[n as usize] == u32::MAX {
                continue;
            }
            let (a, b) = (frag[t], frag[n as usize]);
            if a >= b {
                continue;
            }
            let c = corners(t);
            let [p, q, r] = face.map(|i| c[i]);
            let cross = (q - p).cross(r - p);
            let area = cross.length() / 2.0;
            let e = acc.entry((a, b)).or_insert((0.0, DVec3::ZERO, DVec3::ZERO));
            e.0 += area;
            e.1 += (p + q + r) / 3.0 * area;
            // Outward from t (in a) means towards b.
            e.2 += cross / 2.0;
        }
    }
    let bonds = acc
        .into_iter()
        .filter(|(_, (area, _, _))| *area > 0.0)
        .map(|((a, b), (area, c, n))| Bond {
            a,
            b,
            area,
            centroid: c / area,
            normal: n.normalize_or_zero(),
        })
        .collect();
    Ok((fragments, bonds))
}

/// Quality `6√2·V / L³` of a tetrahedron (1 when regular, 0 when flat).
pub(crate) fn quality(c: [DVec3; 4]) -> f64 {
    let mut l2: f64 = 0.0;
    for i in 0..4 {
        for j in i + 1..4 {
            l2 = l2.max((c[i] - c[j]).length_squared());
        }
    }
    if l2 == 0.0 {
        return 0.0;
    }
    6.0 * std::f64::consts::SQRT_2 * tet_volume(c) / (l2 * l2.sqrt())
}

/// The flat-shaded fragment of a group of tetrahedra: every face not shared inside the
/// group, three own vertices each, wound outward; interior when another kept
/// tetrahedron lies across it. Its collision pieces are its tetrahedra (`piece_ok`
/// ones): the hull of a merged group can be larger than the group and would overlap its
/// neighbours, which the physics engine then pushes apart violently.
fn group_fragment(
    ts: &[usize],
    del: &Tetrahedralization,
    frag: &[u32],
    pts: &[DVec3],
    piece_ok: &[bool],
) -> Fragment {
    let id = frag[ts[0]];
    let mut positions = Vec::with_capacity(ts.len() * 12);
    let mut triangles = Vec::with_capacity(ts.len() * 4);
    let mut interior = Vec::with_capacity(ts.len() * 4);
    let mut piece_pts: Vec<u32> = Vec::with_capacity(ts.len() * 4);
    for &t in ts {
        let tet = del.tetrahedron(t);
        let nb = del.neighbors(t);
        piece_pts.extend(tet);
        for (f, face) in TET_FACES.iter().enumerate() {
            let n = nb[f];
            let across = if n == NO_NEIGHBOR {
                u32::MAX
            } else {
                frag[n as usize]
            };
            if across == id {
                continue;
            }
            let base = positions.len() as u32;
            positions.extend(face.map(|i| pts[tet[i] as usize]));
            triangles.push([base, base + 1, base + 2]);
            interior.push(across != u32::MAX);
        }
    }
    let mesh = TriMesh::new(positions, triangles);
    let (volume, centroid, inertia) = mass_properties(&mesh.positions, &mesh.triangles);
    let mut convex_pieces: Vec<Vec<DVec3>> = ts
        .iter()
        .filter(|&&t| piece_ok[t] || ts.len() == 1)
        .map(|&t| {
            del.tetrahedron(t)
                .iter()
                .map(|&i| pts[i as usize])
                .collect()
        })
        .collect();
    if convex_pieces.is_empty() {
        // Only slivers (merged up to the volume threshold): their common hull.
        piece_pts.sort_unstable();
        piece_pts.dedup();
        convex_pieces.push(piece_pts.iter().map(|&i| pts[i as usize]).collect());
    }
    Fragment {
        mesh,
        interior,
        // Set at the end from the interior flags (`attributes::tags_of_flags`).
        corners: Default::default(),
        material: Vec::new(),
        convex_pieces,
        volume,
        centroid,
        inertia,
    }
}
