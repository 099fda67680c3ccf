//! Grid fracture: the mesh's bounding box cut into equal cells along the axes.
//!
//! A box-shaped mesh (its volume that of its bounding box) is cut analytically into
//! bricks: eight corners and twelve triangles each, the bonds from the grid, no clipping
//! (a 20,000-brick wall in milliseconds). Any other mesh is sliced by the grid's planes
//! through the exact kernel, as [`fn@slice`] does, and each piece is placed in the cell
//! that holds it. Either way, cells inside a void are dropped and the faces that border
//! one become surface.

use glam::{DMat3, DVec3};

use super::slice::slice;
use crate::TriMesh;
use crate::fracture::kernel::{Piece, SURFACE, is_surface};
use crate::fracture::{Bond, Fragment};
use crate::model::Corners;
use crate::util::{bounds, box_corners};

/// Bounding boxes whose volume is the mesh's within this relative tolerance are boxes.
const BOX_VOLUME_TOLERANCE: f64 = 1e-12;

/// The cells of a grid over a box.
#[derive(Debug, Clone)]
pub(crate) struct Grid {
    lo: DVec3,
    cell: DVec3,
    n: [u32; 3],
    voids: Vec<[u32; 6]>,
}

impl Grid {
    /// `cells` over the bounds of `piece` (each count at least 1: the caller checks).
    pub(crate) fn over(piece: &Piece, cells: [u32; 3], voids: &[[u32; 6]]) -> Grid {
        let (lo, hi) = bounds(&piece.pos);
        Grid {
            lo,
            cell: (hi - lo) / DVec3::new(cells[0] as f64, cells[1] as f64, cells[2] as f64),
            n: cells,
            voids: voids.to_vec(),
        }
    }

    /// The volume of one cell.
    pub(crate) fn cell_volume(&self) -> f64 {
        self.cell.x * self.cell.y * self.cell.z
    }

    fn count(&self) -> usize {
        self.n.iter().map(|&c| c as usize).product()
    }

    fn index(&self, c: [u32; 3]) -> usize {
        c[0] as usize + self.n[0] as usize * (c[1] as usize + self.n[1] as usize * c[2] as usize)
    }

    fn is_void(&self, c: [u32; 3]) -> bool {
        self.voids
            .iter()
            .any(|v| (0..3).all(|a| (v[a]..v[a + 3]).contains(&c[a])))
    }

    /// The cell `c` moved by `step` along `axis`, if it is in the grid and not void.
    fn solid_neighbour(&self, c: [u32; 3], axis: usize, step: i64) -> Option<[u32; 3]> {
        let mut d = c;
        let k = c[axis] as i64 + step;
        if k < 0 || k >= self.n[axis] as i64 {
            return None;
        }
        d[axis] = k as u32;
        (!self.is_void(d)).then_some(d)
    }

    /// The cell holding `p` (clamped into the grid).
    fn cell_of(&self, p: DVec3) -> [u32; 3] {
        let t = (p - self.lo) / self.cell;
        let at = |axis: usize| (t[axis].floor().max(0.0) as u32).min(self.n[axis] - 1);
        [at(0), at(1), at(2)]
    }

    /// The grid's inner planes `(point, normal)` in tag order: the `x` planes, then `y`,
    /// then `z`, each from low to high; with each one's axis.
    fn planes(&self) -> (Vec<(DVec3, DVec3)>, Vec<usize>) {
        let mut planes = Vec::new();
        let mut axes = Vec::new();
        for axis in 0..3 {
            let normal = DVec3::AXES[axis];
            for k in 1..self.n[axis] {
                planes.push((self.lo + normal * (self.cell[axis] * k as f64), normal));
                axes.push(axis);
            }
        }
        (planes, axes)
    }

    /// The tag of the inner plane between cells `k - 1` and `k` along `axis`.
    fn plane_tag(&self, axis: usize, k: u32) -> u64 {
        let before: u32 = self.n[..axis].iter().map(|n| n - 1).sum();
        u64::from(before + k - 1)
    }
}

/// Whether `piece` is its own bounding box (so [`bricks`] cuts it exactly).
pub(crate) fn is_box(piece: &Piece) -> bool {
    let (lo, hi) = bounds(&piece.pos);
    fills_box(piece.volume(), lo, hi)
}

/// Whether a solid of `volume` inside the box `lo..hi` fills it.
pub(crate) fn fills_box(volume: f64, lo: DVec3, hi: DVec3) -> bool {
    let e = hi - lo;
    let boxed = e.x * e.y * e.z;
    boxed > 0.0 && (volume - boxed).abs() <= BOX_VOLUME_TOLERANCE * boxed
}

/// The bricks of a box-shaped piece, in grid order without the void cells: the
/// fragments (mass properties exact for a box, the brick its own convex piece), their
/// triangles' tags as the kernel's would be (cuts by their plane, the box's faces and
/// the faces on a void [`SURFACE`]), and their bonds sorted by `(a, b)`.
pub(crate) fn bricks(grid: &Grid) -> (Vec<Fragment>, Vec<Vec<u64>>, Vec<Bond>) {
    let n = grid.n;
    let mut number = vec![u32::MAX; grid.count()];
    let mut pieces = Vec::new();
    let mut tags = Vec::new();
    for z in 0..n[2] {
        for y in 0..n[1] {
            for x in 0..n[0] {
                let c = [x, y, z];
                if grid.is_void(c) {
                    continue;
                }
                number[grid.index(c)] = pieces.len() as u32;
                let (fragment, brick_tags) = brick(grid, c);
                pieces.push(fragment);
                tags.push(brick_tags);
            }
        }
    }
    let mut bonds = Vec::new();
    for z in 0..n[2] {
        for y in 0..n[1] {
            for x in 0..n[0] {
                let c = [x, y, z];
                let a = number[grid.index(c)];
                if a == u32::MAX {
                    continue;
                }
                for axis in 0..3 {
                    let Some(d) = grid.solid_neighbour(c, axis, 1) else {
                        continue;
                    };
                    let normal = DVec3::AXES[axis];
                    let centre = grid.lo
                        + grid.cell * (DVec3::new(x as f64, y as f64, z as f64) + 0.5)
                        + normal * (grid.cell * 0.5);
                    let e = grid.cell;
                    bonds.push(Bond {
                        a,
                        b: number[grid.index(d)],
                        area: [e.y * e.z, e.x * e.z, e.x * e.y][axis],
                        centroid: centre,
                        normal,
                    });
                }
            }
        }
    }
    (pieces, tags, bonds)
}

/// The brick of cell `c`: its eight corners, two outward triangles per face in the
/// order −x, +x, −y, +y, −z, +z; with their tags.
fn brick(grid: &Grid, c: [u32; 3]) -> (Fragment, Vec<u64>) {
    let lo = grid.lo + grid.cell * DVec3::new(c[0] as f64, c[1] as f64, c[2] as f64);
    let hi = lo + grid.cell;
    let pos = box_corners(lo, hi);
    const FACES: [[u32; 4]; 6] = [
        [0, 4, 6, 2],
        [1, 3, 7, 5],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 2, 3, 1],
        [4, 5, 7, 6],
    ];
    let mut tris = Vec::with_capacity(12);
    let mut tags = Vec::with_capacity(12);
    for (face, [a, b, d, e]) in FACES.iter().enumerate() {
        let (axis, step) = (face / 2, if face % 2 == 0 { -1 } else { 1 });
        let tag = match grid.solid_neighbour(c, axis, step) {
            // The plane between this cell and the next one up (or this one and the one
            // below).
            Some(_) => grid.plane_tag(axis, c[axis] + u32::from(step > 0)),
            None => SURFACE,
        };
        tris.extend([[*a, *b, *d], [*a, *d, *e]]);
        tags.extend([tag; 2]);
    }
    let e = grid.cell;
    let volume = grid.cell_volume();
    let inertia = DMat3::from_diagonal(
        DVec3::new(
            e.y * e.y + e.z * e.z,
            e.x * e.x + e.z * e.z,
            e.x * e.x + e.y * e.y,
        ) * (volume / 12.0),
    );
    let fragment = Fragment {
        mesh: TriMesh::new(pos.clone(), tris),
        interior: tags.iter().map(|&t| !is_surface(t)).collect(),
        // Set at the end, from the tags (see `attributes`).
        corners: Corners::default(),
        material: Vec::new(),
        convex_pieces: vec![pos],
        convex_hulls: Vec::new(),
        volume,
        centroid: (lo + hi) / 2.0,
        inertia,
    };
    (fragment, tags)
}

/// `piece` sliced by the grid's planes through the kernel, its parts placed in their
/// cells: in grid order (parts of one cell in the order the cut made them), without the
/// parts in void cells, the caps that face a void made surface; with their bonds.
pub(crate) fn sliced(piece: &Piece, grid: &Grid, eps: f64) -> (Vec<Piece>, Vec<Bond>) {
    let (planes, axes) = grid.planes();
    let (parts, bonds) = slice(piece, &planes, eps);
    // A part lies inside its cell's box, so the middle of its bounds does too.
    let cells: Vec<[u32; 3]> = parts
        .iter()
        .map(|p| {
            let (lo, hi) = bounds(&p.pos);
            grid.cell_of((lo + hi) / 2.0)
        })
        .collect();
    // The parts outside the voids, by cell (a stable sort: a cell's parts in cut order).
    let mut kept: Vec<(usize, Piece)> = parts
        .into_iter()
        .enumerate()
        .filter(|(i, _)| !grid.is_void(cells[*i]))
        .collect();
    kept.sort_by_key(|(i, _)| grid.index(cells[*i]));
    let mut number = vec![u32::MAX; cells.len()];
    let pieces = kept
        .into_iter()
        .enumerate()
        .map(|(new, (old, mut p))| {
            number[old] = new as u32;
            let c = cells[old];
            for (t, tag) in p.tags.iter_mut().enumerate() {
                if is_surface(*tag) {
                    continue;
                }
                let axis = axes[*tag as usize];
                let [a, b, d] = p.tris[t].map(|i| p.pos[i as usize]);
                let up = (b - a).cross(d - a)[axis] > 0.0;
                if grid
                    .solid_neighbour(c, axis, if up { 1 } else { -1 })
                    .is_none()
                {
                    *tag = SURFACE;
                }
            }
            p
        })
        .collect();
    let mut bonds: Vec<Bond> = bonds
        .into_iter()
        .filter_map(|b| {
            let (a, c) = (number[b.a as usize], number[b.b as usize]);
            if a == u32::MAX || c == u32::MAX {
                None
            } else if a < c {
                Some(Bond { a, b: c, ..b })
            } else {
                Some(Bond {
                    a: c,
                    b: a,
                    normal: -b.normal,
                    ..b
                })
            }
        })
        .collect();
    bonds.sort_by_key(|b| (b.a, b.b));
    (pieces, bonds)
}
