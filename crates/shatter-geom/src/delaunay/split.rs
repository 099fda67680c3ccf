//! Delaunay in two halves, one per core, joined exactly.
//!
//! 1. **Split.** The points are split across the widest extent of their box, at the
//!    median of a sample: below it on the left, at or above it on the right, so equal
//!    points always fall on one side. (Below the axis is called `x`.)
//! 2. **Halves.** Each half is triangulated on its own (`rayon::join`), in its own part of
//!    one shared record buffer ([`Slab`]), so that joining them moves records within it
//!    instead of copying them into a new one.
//! 3. **Safe tetrahedra.** A tetrahedron of a half whose circumsphere lies strictly on its
//!    own side of the plane halfway between the halves (between the left half's greatest
//!    `x` and the right half's least) has an empty sphere for all the points, so it is a
//!    tetrahedron of the whole triangulation. The test is in floating point with a margin
//!    wider than its rounding, so a sphere it cannot decide is unsafe: that only costs
//!    work. The unsafe ones are found by a search from the half's hull, which tests only
//!    them and their neighbours (see `build_half`).
//! 4. **The gap.** Let `S` be the vertices of the unsafe tetrahedra (the infinite ones
//!    included, so every vertex of a half's hull is in `S`). Every tetrahedron of the whole
//!    triangulation that is not safe has all its vertices in `S`: for a vertex `a` of the
//!    left half not on its hull, the centre of an empty sphere through `a` and a right
//!    point lies in `a`'s Voronoi cell of the left half, and the sphere's right end is a
//!    convex function of the centre, so it reaches as far at some vertex of that cell,
//!    that is at the circumcentre of a tetrahedron of `a` that is therefore unsafe (and
//!    likewise on the right). Those tetrahedra are Delaunay for `S` too, so they are
//!    tetrahedra of `DT(S)`, triangulated again on its own (the symbolic perturbation
//!    depends on positions only, so every subset agrees).
//! 5. **Join.** The safe tetrahedra's faces towards unsafe ones ("walls") are faces of
//!    `DT(S)` as well. The tetrahedra of `DT(S)` on the far side of a wall, and every one
//!    reached from them without crossing a wall, fill the gap exactly; the rest of `DT(S)`
//!    lies under safe tetrahedra and is dropped. Any inconsistency (a wall `DT(S)` does not
//!    have) gives up, and the caller triangulates sequentially.
//!
//! When most points are on their hull (points on a sphere), nearly all would be in `S`:
//! a sample of the points is split first, and if half of it lands in its gap the caller
//! triangulates sequentially. A gap of more than a third of the points is refused too
//! (its sequential triangulation would cost more than the second core saves). `S` itself
//! is triangulated sequentially, beside the halves' renumbering: it is a thin slab, most
//! of whose points are on its own hull, which does not split well.
//!
//! The result is the same set of tetrahedra as the sequential insertion's, in another
//! order, and it depends on the points only, not on the number of threads: one thread
//! runs both halves in turn.

use glam::DVec3;

use super::order::brio_order_of;
use super::output::{Rank, duplicates_of, fill_representative, vertex_names};
use super::packed::{Narrow, Slab, Store, Tets, Words};
use super::sequential::{StorePlan, first_simplex, insert_from, sequential, start};
use super::storage::{FLAGS, INF, MARK, Mesh, Points, SEEN, points_in_order, reserve_for};
use super::types::{FACES, NO_NEIGHBOR, Tetrahedralization};
use crate::util::{FastMap, bounds};

/// Fewest points for which [`tetrahedralize_split`] is used. Smaller sets gain less from
/// the second core and cost more memory and more on one core, because their gap holds a
/// larger share of the points (measured against the sequential insertion: at 50,000
/// points 1.35× faster on two cores, 1.13–1.33× slower on one, 230 B/pt at the peak
/// against 190; at 200,000, 1.6× faster on two cores and 202 B/pt).
pub(crate) const SPLIT_MIN_POINTS: usize = 200_000;

/// A half after its triangulation: its tetrahedra renumbered in its slab, and what the
/// join needs.
struct Half {
    /// Number of safe tetrahedra, written at the start of the half's slab.
    safe: u32,
    /// Faces of safe tetrahedra towards unsafe ones.
    walls: Vec<Wall>,
    /// Input index of internal vertex `k + 1`.
    order: Vec<u32>,
    /// Merged duplicates (internal slot, internal vertex).
    dups: Vec<(u32, u32)>,
}

/// A face of a safe tetrahedron whose neighbour in its half is not safe.
#[derive(Clone, Copy, Debug)]
struct Wall {
    /// The face's vertices (input indices), sorted: the key to find it in `DT(S)`.
    key: [u32; 3],
    /// Whether the safe tetrahedron's outward winding is an even permutation of `key`.
    even: bool,
    /// Output index of the safe tetrahedron.
    tet: u32,
    /// The face (opposite this vertex of the safe tetrahedron).
    face: u8,
}

/// The sorted key of a triangle and whether `f` is an even permutation of it.
fn face_key(f: [u32; 3]) -> ([u32; 3], bool) {
    let mut k = f;
    let mut even = true;
    if k[0] > k[1] {
        k.swap(0, 1);
        even = !even;
    }
    if k[1] > k[2] {
        k.swap(1, 2);
        even = !even;
    }
    if k[0] > k[1] {
        k.swap(0, 1);
        even = !even;
    }
    (k, even)
}

/// Which side of the split a half is, and the axis split.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Side {
    /// Below the median: safe spheres end before the bound.
    Left(usize),
    /// At or above it: safe spheres start after the bound.
    Right(usize),
}

/// Whether the circumsphere of `p` lies strictly on `side` of the plane `bound`, by a
/// margin wider than the rounding of the `f64` circumcentre; `false` when unsure.
fn sphere_within(p: [&[f64; 3]; 4], side: Side, bound: f64) -> bool {
    let q = p.map(|q| DVec3::from_array(*q));
    let a = q[0];
    let (u, v, w) = (q[1] - a, q[2] - a, q[3] - a);
    let (uu, vv, ww) = (u.length_squared(), v.length_squared(), w.length_squared());
    let vw = v.cross(w);
    let den = 2.0 * u.dot(vw);
    let inv = 1.0 / den;
    let o = (uu * vw + vv * w.cross(u) + ww * u.cross(v)) * inv;
    let r = o.length();
    if !(inv.is_finite() && r.is_finite()) {
        return false;
    }
    // Rounding: the differences carry `eps·|p|` each, the products `eps·L` relative; the
    // centre moves by about (δ)·(L³ + r·L²)/|den|. 64 times that is far beyond it.
    let eps = f64::EPSILON;
    let l = uu.max(vv).max(ww).sqrt();
    let mag = a
        .abs()
        .max(q[1].abs())
        .max(q[2].abs())
        .max(q[3].abs())
        .max_element();
    let delta = eps * (l + mag);
    let margin = 64.0 * delta * (l * l * (l + r)) * inv.abs() + 8.0 * eps * (mag + r);
    match side {
        Side::Left(k) => a[k] + o[k] + r + margin < bound,
        Side::Right(k) => a[k] + o[k] - r - margin > bound,
    }
}

/// Triangulates one half (input indices `idx`) in `slab`, classifies its tetrahedra and
/// renumbers the safe ones to the start of the slab. `None` when the half is degenerate
/// or does not fit its slab.
fn build_half<'a>(
    points: &[DVec3],
    idx: Vec<u32>,
    slab: Slab<'a>,
    side: Side,
    bound: f64,
) -> Option<Built<'a>> {
    let order = brio_order_of(points, idx);
    let xyz = points_in_order(points, &order);
    let pts = Points::copied(&xyz);
    let first = first_simplex(pts)?;
    let mut mesh = Mesh::new(pts, Narrow::in_slab(slab), usize::MAX);
    start(&mut mesh, first);
    let mut dups = Vec::new();
    if insert_from(&mut mesh, (1, None), first, &mut dups).is_some() {
        return None;
    }
    let Mesh { mut tets, .. } = mesh;

    // Unsafe tetrahedra, flagged MARK, by a search from the hull: only they and their
    // neighbours are tested, not every tetrahedron. It finds them all because `bound`
    // lies strictly between the halves, outside this half's hull: a tetrahedron whose
    // sphere reaches past it contains a point `p` beyond it, and `p`'s conflict region
    // (every tetrahedron whose sphere contains `p`, and the infinite ones whose hull face
    // `p` sees) is connected, holds an infinite tetrahedron, and none of its spheres is
    // certified on this side.
    let total = tets.len();
    let dead = tets.vertex_marker();
    let live_infinite = |t: u32| {
        let v = tets.verts(t);
        v[0] != dead && v.contains(&INF)
    };
    let first_infinite = (0..total as u32).find(|&t| live_infinite(t))?;
    let mut in_gap = vec![0u64; (pts.len() + 1).div_ceil(64)];
    let mut stack = vec![first_infinite];
    tets.add_flags(first_infinite, MARK);
    while let Some(t) = stack.pop() {
        for k in tets.verts(t) {
            in_gap[k as usize / 64] |= 1 << (k % 64);
        }
        for a in tets.adjs(t) {
            let nb = a >> 2;
            if tets.flags(nb) & FLAGS != 0 {
                continue;
            }
            let v = tets.verts(nb);
            if v.contains(&INF) || !sphere_within(v.map(|k| &pts[k as usize]), side, bound) {
                tets.add_flags(nb, MARK);
                stack.push(nb);
            } else {
                tets.add_flags(nb, SEEN);
            }
        }
    }
    let safe = Rank::new(total, |t| {
        tets.verts(t)[0] != dead && tets.flags(t) & MARK == 0
    });
    drop(xyz);
    let name = vertex_names(&order, &dups);
    let gap_vertices: Vec<u32> = (1..name.len())
        .filter(|&k| in_gap[k / 64] >> (k % 64) & 1 != 0)
        .map(|k| name[k])
        .collect();
    drop(in_gap);
    Some(Built {
        tets,
        safe,
        name,
        gap_vertices,
        order,
        dups,
    })
}

/// Renumbers a half's safe tetrahedra to the start of its slab, in place (a safe
/// tetrahedron's new index never exceeds its old one); the other half's offset is added
/// at the join. A face towards an unsafe neighbour is a wall, its field the marker until
/// the join sets it.
fn renumber(built: Built<'_>) -> Half {
    let Built {
        mut tets,
        safe,
        name,
        order,
        dups,
        ..
    } = built;
    let total = tets.len();
    let none = tets.adjacency_marker();
    let mut walls = Vec::new();
    let mut out = 0u32;
    for t in 0..total as u32 {
        if !safe.has(t) {
            continue;
        }
        let v = tets.verts(t).map(|x| name[x as usize]);
        let adj = tets.adjs(t);
        let mut a = [none; 4];
        for i in 0..4 {
            let nb = adj[i] >> 2;
            if safe.has(nb) {
                a[i] = safe.rank(nb);
            } else {
                let f = FACES[i];
                let (key, even) = face_key([v[f[0]], v[f[1]], v[f[2]]]);
                walls.push(Wall {
                    key,
                    even,
                    tet: out,
                    face: i as u8,
                });
            }
        }
        tets.write(out, v, a);
        out += 1;
    }
    tets.truncate(out as usize);
    Half {
        safe: out,
        walls,
        order,
        dups,
    }
}

/// A half triangulated and classified, its records still as built in its slab.
struct Built<'a> {
    tets: Narrow<Slab<'a>>,
    /// The safe tetrahedra.
    safe: Rank,
    /// Output name of each internal vertex.
    name: Vec<u32>,
    /// Output names of the vertices of unsafe tetrahedra.
    gap_vertices: Vec<u32>,
    /// Input index of internal vertex `k + 1`.
    order: Vec<u32>,
    /// Merged duplicates (internal slot, internal vertex).
    dups: Vec<(u32, u32)>,
}

/// Where the points split: their indices on either side, the axis, and the plane
/// strictly between the halves that safe spheres must not reach.
struct Plan {
    left: Vec<u32>,
    right: Vec<u32>,
    axis: usize,
    bound: f64,
    /// Records reserved for each half.
    caps: [usize; 2],
}

/// Splits `points` across the widest extent at the median of a sample (the halves need
/// only be about even). `None` when the split is uneven (below a quarter on one side).
fn plan(points: &[DVec3]) -> Option<Plan> {
    let n = points.len();
    if !(64..=<Narrow>::MAX_POINTS).contains(&n) {
        return None;
    }
    let (lo, hi) = bounds(points);
    let extent = hi - lo;
    let axis = if extent.x >= extent.y && extent.x >= extent.z {
        0
    } else if extent.y >= extent.z {
        1
    } else {
        2
    };
    let stride = (n / SAMPLE).max(1);
    let mut sample: Vec<f64> = points.iter().step_by(stride).map(|p| p[axis]).collect();
    let mid = sample.len() / 2;
    let (_, &mut m, _) = sample.select_nth_unstable_by(mid, f64::total_cmp);
    let m = m + 0.0;
    let on_left = |p: &DVec3| p[axis] < m;
    let count_l = points.iter().filter(|p| on_left(p)).count();
    if count_l < n / 4 || n - count_l < n / 4 {
        return None;
    }
    let mut left = Vec::with_capacity(count_l);
    let mut right = Vec::with_capacity(n - count_l);
    let (mut left_max, mut right_min) = (f64::NEG_INFINITY, f64::INFINITY);
    for (i, p) in points.iter().enumerate() {
        if on_left(p) {
            left.push(i as u32);
            left_max = left_max.max(p[axis]);
        } else {
            right.push(i as u32);
            right_min = right_min.min(p[axis]);
        }
    }
    // Safe spheres end (left) or start (right) strictly before a plane strictly between
    // the halves, outside both hulls.
    let bound = 0.5 * (left_max + right_min);
    if !(left_max < bound && bound < right_min) {
        return None;
    }
    let caps = [reserve_for(left.len()), reserve_for(right.len())];
    Some(Plan {
        left,
        right,
        axis,
        bound,
        caps,
    })
}

/// One buffer of zeroed records for both halves (allocated zeroed, so pages become
/// resident only as they are written).
fn buffer(plan: &Plan) -> Vec<Words> {
    vec![[0; 3]; plan.caps[0] + plan.caps[1]]
}

/// Triangulates and classifies both halves at once, each in its part of `buf`. `None`
/// when a half is degenerate or outgrows its part.
fn build_both<'a>(
    points: &[DVec3],
    plan: Plan,
    buf: &'a mut [Words],
) -> Option<(Built<'a>, Built<'a>)> {
    let Plan {
        left,
        right,
        axis,
        bound,
        caps,
    } = plan;
    let (bl, br) = buf.split_at_mut(caps[0]);
    let (bl, br) = (bytemuck::cast_slice_mut(bl), bytemuck::cast_slice_mut(br));
    let (l, r) = rayon::join(
        || build_half(points, left, Slab::new(bl), Side::Left(axis), bound),
        || build_half(points, right, Slab::new(br), Side::Right(axis), bound),
    );
    Some((l?, r?))
}

/// Whether the split is worth it: a sample of [`GAP_SAMPLE`] points, split the same
/// way, leaves at most half of itself in the gap. Points mostly on their hull (on a
/// sphere, say) put nearly all in it, and are triangulated sequentially without paying
/// for two halves first.
fn sample_splits(points: &[DVec3]) -> bool {
    let n = points.len();
    if n < 4 * GAP_SAMPLE {
        return true;
    }
    let sample: Vec<DVec3> = points.iter().step_by(n / GAP_SAMPLE).copied().collect();
    let Some(plan) = plan(&sample) else {
        return false;
    };
    let mut buf = buffer(&plan);
    build_both(&sample, plan, &mut buf).is_some_and(|(l, r)| {
        let gap = l.gap_vertices.len() + r.gap_vertices.len();
        gap * 2 <= sample.len()
    })
}

/// Points in the sample that [`sample_splits`] triangulates.
const GAP_SAMPLE: usize = 8192;

/// The Delaunay tetrahedralization of `points` (already checked by the caller) built as
/// two halves on two threads, or `None` when the split does not apply (too uneven a
/// split, a degenerate half, a half beyond its reservation, or a join that does not add
/// up); the caller then triangulates sequentially.
pub(crate) fn tetrahedralize_split(points: &[DVec3]) -> Option<Tetrahedralization> {
    let n = points.len();
    if !sample_splits(points) {
        return None;
    }
    let plan = plan(points)?;
    let cap_l = plan.caps[0];
    let mut buf = buffer(&plan);
    // 2–4. Both halves; then their renumbering beside DT(S).
    let (hl, hr, gap, dts) = {
        let (mut bl, mut br) = build_both(points, plan, &mut buf)?;
        let mut gap = std::mem::take(&mut bl.gap_vertices);
        gap.append(&mut br.gap_vertices);
        // At most a third in the gap, so that triangulating it always pays.
        if gap.len() * 3 > n {
            return None;
        }
        let ((hl, hr), dts) = rayon::join(
            || rayon::join(|| renumber(bl), || renumber(br)),
            || {
                let gap_pts: Vec<DVec3> = gap.iter().map(|&i| points[i as usize]).collect();
                sequential(&gap_pts, StorePlan::for_points(gap_pts.len()))
            },
        );
        (hl, hr, gap, dts)
    };
    let dts = dts.ok()?;
    debug_assert!(
        dts.duplicates.is_empty(),
        "the halves merged their duplicates"
    );

    // 5. The walls' far sides in DT(S) and the gap filled from them, while the right
    // half's records move behind the left's and the points get their names.
    let (safe_l, safe_r) = (hl.safe, hr.safe);
    let mut walls = hl.walls;
    walls.extend(hr.walls.into_iter().map(|w| Wall {
        tet: w.tet + safe_l,
        ..w
    }));
    let names = [(hl.order, hl.dups), (hr.order, hr.dups)];
    let (join, (mut recs, representative)) = rayon::join(
        || Join::new(&dts, &gap, &walls, n),
        || {
            // Never upwards, so in one forward pass; neighbours shift by the left's count.
            let mut recs = Narrow::from_records(buf);
            let none = recs.adjacency_marker();
            for t in 0..safe_r {
                let from = cap_l as u32 + t;
                let a = recs
                    .adjs(from)
                    .map(|x| if x == none { none } else { x + safe_l });
                let v = recs.verts(from);
                recs.write(safe_l + t, v, a);
            }
            recs.truncate((safe_l + safe_r) as usize);
            let mut representative = vec![0u32; n];
            // The halves' names are made again here rather than kept from their
            // renumbering: kept, they would add 4 B/pt to this step's peak (measured:
            // 190 -> 193 B/pt on 1M points), to save a few milliseconds.
            for (order, dups) in names {
                let name = vertex_names(&order, &dups);
                fill_representative(&mut representative, &order, &dups, &name);
            }
            (recs, representative)
        },
    );
    let join = join?;
    let (duplicates, unique_points) = duplicates_of(&representative);

    // The gap's tetrahedra behind the safe ones; then the walls' other sides. Every index
    // must fit the narrow records' neighbour fields.
    let none = recs.adjacency_marker();
    let base = safe_l + safe_r;
    if base as usize + dts.len() > <Narrow>::MAX_TETS {
        return None;
    }
    for g in 0..dts.len() as u32 {
        if !join.fill.has(g) {
            continue;
        }
        let v = dts.tetrahedron(g as usize).map(|k| gap[k as usize]);
        let nb = dts.neighbors(g as usize);
        let mut a = [none; 4];
        for j in 0..4 {
            if let Some(w) = join.wall_at(g, j) {
                a[j] = walls[w as usize].tet;
            } else if nb[j] != NO_NEIGHBOR {
                if !join.fill.has(nb[j]) {
                    return None;
                }
                a[j] = base + join.fill.rank(nb[j]);
            }
        }
        let t = recs.push();
        recs.write(t, v, a);
    }
    for (w, &g) in walls.iter().zip(&join.across) {
        // Nothing across: a face of the hull of all the points.
        let a = if g == SAME_SIDE {
            none
        } else {
            base + join.fill.rank(g)
        };
        recs.set_adj(w.tet, w.face as usize, a);
    }
    Some(Tetrahedralization::from_parts(
        Tets::Narrow(recs),
        representative,
        unique_points,
        duplicates,
    ))
}

/// Points in the sample whose median splits the points.
const SAMPLE: usize = 4095;

/// `Join::across` of a wall that `DT(S)` has only on its safe tetrahedron's side.
const SAME_SIDE: u32 = u32::MAX - 1;
/// `Join::across` of a wall not (yet) found in `DT(S)`.
const UNMATCHED: u32 = u32::MAX;

/// The walls found in `DT(S)` and the tetrahedra of `DT(S)` that fill the gap.
struct Join {
    /// For every wall: the tetrahedron of `DT(S)` across it, or [`SAME_SIDE`].
    across: Vec<u32>,
    /// The gap's tetrahedra of `DT(S)`.
    fill: Rank,
    /// `(tetrahedron of DT(S) << 2 | face, wall)` for every wall face of a gap tetrahedron,
    /// sorted.
    wall_faces: Vec<(u32, u32)>,
}

impl Join {
    /// Finds every wall in `dts` (over the points `gap`, of `n` input points), then floods
    /// the gap from the walls' far sides without crossing a wall. `None` when a wall is
    /// missing from `dts` or found twice on its far side.
    fn new(dts: &Tetrahedralization, gap: &[u32], walls: &[Wall], n: usize) -> Option<Self> {
        // A bit per input point on a wall: most faces of DT(S) are not looked up.
        let mut wall_bits = vec![0u64; n.div_ceil(64)];
        for w in walls {
            for g in w.key {
                wall_bits[g as usize / 64] |= 1 << (g % 64);
            }
        }
        let on_wall: Vec<bool> = gap
            .iter()
            .map(|&g| wall_bits[g as usize / 64] >> (g % 64) & 1 != 0)
            .collect();
        drop(wall_bits);
        let index: FastMap<u64, u32> = walls
            .iter()
            .enumerate()
            .map(|(i, w)| (pack(w.key), i as u32))
            .collect();
        if index.len() != walls.len() {
            // Two safe tetrahedra on one wall face: not a triangulation.
            return None;
        }
        let m = dts.len();
        let mut across = vec![UNMATCHED; walls.len()];
        let mut is_gap = vec![false; m];
        let mut walled = vec![0u8; m];
        let mut wall_faces = Vec::new();
        let mut stack: Vec<u32> = Vec::new();
        for g in 0..m {
            let tv = dts.tetrahedron(g);
            for (j, f) in FACES.iter().enumerate() {
                if !f.iter().all(|&k| on_wall[tv[k] as usize]) {
                    continue;
                }
                let (key, even) = face_key(f.map(|k| gap[tv[k] as usize]));
                let Some(&w) = index.get(&pack(key)) else {
                    continue;
                };
                walled[g] |= 1 << j;
                if even == walls[w as usize].even {
                    // On the safe tetrahedron's side: `g` lies under it.
                    if across[w as usize] == UNMATCHED {
                        across[w as usize] = SAME_SIDE;
                    }
                } else {
                    if across[w as usize] < SAME_SIDE {
                        return None;
                    }
                    across[w as usize] = g as u32;
                    wall_faces.push(((g as u32) << 2 | j as u32, w));
                    if !is_gap[g] {
                        is_gap[g] = true;
                        stack.push(g as u32);
                    }
                }
            }
        }
        if across.contains(&UNMATCHED) {
            return None;
        }
        while let Some(g) = stack.pop() {
            for (j, h) in dts.neighbors(g as usize).into_iter().enumerate() {
                if walled[g as usize] >> j & 1 != 0 || h == NO_NEIGHBOR {
                    continue;
                }
                let h = h as usize;
                if !is_gap[h] {
                    is_gap[h] = true;
                    stack.push(h as u32);
                }
            }
        }
        wall_faces.sort_unstable();
        Some(Self {
            across,
            fill: Rank::new(m, |g| is_gap[g as usize]),
            wall_faces,
        })
    }

    /// The wall on face `j` of gap tetrahedron `g`, if it is one.
    fn wall_at(&self, g: u32, j: usize) -> Option<u32> {
        let key = g << 2 | j as u32;
        self.wall_faces
            .binary_search_by_key(&key, |&(k, _)| k)
            .ok()
            .map(|at| self.wall_faces[at].1)
    }
}

/// Three vertex ids below 2^21 (the narrow layout's) in one `u64`.
fn pack(k: [u32; 3]) -> u64 {
    (k[0] as u64) << 42 | (k[1] as u64) << 21 | k[2] as u64
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::{Distribution, sample};

    /// Every tetrahedron as its sorted vertices, sorted.
    fn tet_set(t: &Tetrahedralization) -> Vec<[u32; 4]> {
        let mut v: Vec<[u32; 4]> = t
            .tetrahedra()
            .map(|mut q| {
                q.sort_unstable();
                q
            })
            .collect();
        v.sort_unstable();
        v
    }

    /// The split builds exactly the sequential triangulation (validated on its own) on
    /// uniform, clustered, cospherical and lattice points and with duplicates, and it
    /// does apply to each of them.
    #[test]
    fn the_split_builds_the_sequential_triangulation() {
        let mut sets: Vec<(&str, Vec<DVec3>)> = [
            ("uniform", Distribution::Uniform),
            ("grid", Distribution::Grid),
            ("gaussian", Distribution::Gaussian),
        ]
        .into_iter()
        .flat_map(|(name, d)| [(name, sample(d, 12_000, 3)), (name, sample(d, 40_000, 5))])
        .collect();
        let mut dups = sample(Distribution::Ball, 6000, 2);
        dups.extend_from_within(..2500);
        sets.push(("duplicates", dups));
        // A fifth of the points on one plane across the widest axis, where the median
        // falls: the right half's least x is that plane, and many spheres touch it.
        let mut plane = sample(Distribution::Uniform, 20_000, 6);
        for (k, q) in plane.iter_mut().enumerate() {
            q.x = if k % 5 == 0 { 0.0 } else { q.x * 3.0 };
        }
        sets.push(("plane", plane));
        for (name, p) in &sets {
            let split = tetrahedralize_split(p)
                .unwrap_or_else(|| panic!("{name} ({} points): the split gave up", p.len()));
            split
                .validate(p)
                .unwrap_or_else(|e| panic!("{name} ({} points): {e}", p.len()));
            let seq = sequential(p, StorePlan::for_points(p.len())).expect("sequential");
            assert_eq!(
                tet_set(&split),
                tet_set(&seq),
                "{name} ({} points)",
                p.len()
            );
            assert_eq!(split.representative, seq.representative, "{name}");
            assert_eq!(split.duplicates, seq.duplicates, "{name}");
            assert_eq!(split.unique_points, seq.unique_points, "{name}");
        }
    }

    /// Inputs made to tie where the halves meet, each with three seeds: points on planes
    /// across the split axis (the median on one of them), a lattice with half its
    /// points dropped (cospherical ties everywhere, across the gap too), and tight clusters
    /// (large empty spheres between them). The split equals the sequential insertion on
    /// every one, or declines.
    #[test]
    fn ties_at_the_seam_give_the_sequential_triangulation() {
        use rand::{Rng, SeedableRng};
        let mut applied = 0;
        for seed in 0..3u64 {
            let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
            let n = 12_000;
            let planes: Vec<DVec3> = (0..n)
                .map(|_| {
                    // 41 planes 0.1 apart, about as far as the points on each.
                    let x = rng.random_range(-20..=20) as f64 * 0.1;
                    DVec3::new(x, rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0))
                })
                .collect();
            let lattice: Vec<DVec3> = (0..40 * 25 * 25)
                .filter(|_| rng.random_bool(0.5))
                .map(|k| DVec3::new((k / 625) as f64, (k / 25 % 25) as f64, (k % 25) as f64))
                .collect();
            let centres: Vec<DVec3> = (0..12)
                .map(|_| {
                    DVec3::new(
                        rng.random_range(-3.0..3.0),
                        rng.random_range(-1.0..1.0),
                        0.0,
                    )
                })
                .collect();
            let clusters: Vec<DVec3> = (0..n)
                .map(|k| {
                    let off = DVec3::new(
                        rng.random_range(-1.0..1.0),
                        rng.random_range(-1.0..1.0),
                        rng.random_range(-1.0..1.0),
                    );
                    centres[k % centres.len()] + 0.02 * off
                })
                .collect();
            for (name, p) in [
                ("planes", planes),
                ("lattice", lattice),
                ("clusters", clusters),
            ] {
                let Some(split) = tetrahedralize_split(&p) else {
                    continue;
                };
                applied += 1;
                split
                    .validate(&p)
                    .unwrap_or_else(|e| panic!("{name}, seed {seed}: {e}"));
                let seq = sequential(&p, StorePlan::for_points(p.len())).expect("sequential");
                assert_eq!(tet_set(&split), tet_set(&seq), "{name}, seed {seed}");
                assert_eq!(
                    split.representative, seq.representative,
                    "{name}, seed {seed}"
                );
            }
        }
        // The test is about the split: these must take it.
        assert_eq!(applied, 9, "the split applied to only {applied} of 9");
    }

    /// The public call takes the split from [`SPLIT_MIN_POINTS`] on, and its result is
    /// exactly Delaunay.
    #[test]
    fn a_large_input_is_split_and_exact() {
        let p = sample(Distribution::Uniform, SPLIT_MIN_POINTS + 1000, 9);
        let t = crate::delaunay::tetrahedralize(&p).expect("uniform points");
        let split = tetrahedralize_split(&p).expect("the split applies");
        // The same tetrahedra in the same order: the split's, not the sequential path's.
        assert!(t.tetrahedra().eq(split.tetrahedra()));
        t.validate(&p).expect("Delaunay");
        let seq = sequential(&p, StorePlan::for_points(p.len())).expect("sequential");
        assert_eq!(tet_set(&t), tet_set(&seq));
    }

    /// Points on a sphere are all on both halves' hulls, so all would be in the gap: the
    /// split declines them, from its sample when there are enough points for one.
    #[test]
    fn points_on_a_sphere_are_not_split() {
        for n in [3000, 40_000] {
            let p = sample(Distribution::Sphere, n, 4);
            let plan = plan(&p).expect("an even split");
            let mut buf = buffer(&plan);
            let (l, r) = build_both(&p, plan, &mut buf).expect("the halves themselves build");
            // Nearly every point is in the gap.
            assert!(
                (l.gap_vertices.len() + r.gap_vertices.len()) * 10 > n * 9,
                "{n}"
            );
            assert!(tetrahedralize_split(&p).is_none(), "{n}");
        }
        let p = sample(Distribution::Sphere, 40_000, 4);
        assert!(!sample_splits(&p));
        assert!(sample_splits(&sample(Distribution::Uniform, 40_000, 4)));
    }

    /// A split that cannot be even (most points share the median x) is declined.
    #[test]
    fn an_uneven_split_is_declined() {
        // x is the widest extent, and most points share one x.
        let mut p = sample(Distribution::Uniform, 3000, 1);
        for (k, q) in p.iter_mut().enumerate() {
            q.x = if k < 2400 { 2.5 } else { q.x * 10.0 };
        }
        assert!(tetrahedralize_split(&p).is_none());
        sequential(&p, StorePlan::for_points(p.len()))
            .expect("sequential")
            .validate(&p)
            .expect("Delaunay");
    }

    /// The sphere test keeps its promise: a sphere it calls safe ends strictly before the
    /// bound, checked with the exact insphere test against points at the bound.
    #[test]
    fn a_safe_sphere_is_strictly_on_its_side() {
        let q = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
        ];
        let p = q.each_ref();
        // Circumcentre (0.5, 0.5, 0.5), radius sqrt(0.75) ≈ 0.866: x in [-0.366, 1.366].
        assert!(sphere_within(p, Side::Left(0), 1.367));
        assert!(!sphere_within(p, Side::Left(0), 1.366));
        assert!(!sphere_within(p, Side::Left(0), 0.5 + 0.75f64.sqrt()));
        assert!(sphere_within(p, Side::Right(0), -0.367));
        assert!(!sphere_within(p, Side::Right(0), -0.366));
        // A flat tetrahedron has no sphere to trust.
        let flat = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 1.0, 0.0],
        ];
        let f = flat.each_ref();
        assert!(!sphere_within(f, Side::Left(0), 1e9));
    }
}
