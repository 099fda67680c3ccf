//! Repair of real-world input: a [`Model`] as files hold it (cracks, holes, flipped or
//! duplicated triangles, loose sheets, parts that cross) into a closed solid that
//! fracture takes, with its attributes and materials carried along.
//!
//! The steps, each reported with counts in a [`RepairReport`]:
//! 1. weld vertices at equal positions, then boundary vertices within a tolerance
//!    relative to the model's size, so CAD cracks close;
//! 2. drop degenerate triangles (splitting the neighbour of a collinear one at its
//!    T-junction) and duplicate triangles;
//! 3. split into edge-connected shells and wind each consistently;
//! 4. fill each shell's holes with a fair patch, up to a size relative to the shell
//!    ([`RepairOptions::max_hole_area`]); a shell with a larger hole is an open sheet
//!    and is dropped, as are non-orientable shells and closed shells without volume;
//! 5. orient each closed shell outward, and a shell nested inside another inward (a
//!    cavity);
//! 6. replace shells that cross or touch by their union, the solid where the
//!    generalized winding number is at least ½ (see `union.rs` for how).
//!
//! A kept triangle keeps its corners' attributes and its material; patch triangles
//! take the attributes around the hole, flat normals and the material around the hole;
//! union triangles take those of the input triangle they lie on. If nothing with a
//! volume is left, [`RepairError::NoSolid`] says what was found.
//!
//! ```
//! use shatter_geom::mesh::repair::{repair, RepairOptions};
//! use shatter_geom::model::Model;
//! use shatter_geom::shapes;
//!
//! // A cube with one face (two triangles) missing.
//! let mut cube = shapes::cube();
//! cube.triangles.truncate(10);
//! let (fixed, report) = repair(&Model::from_mesh(cube), &RepairOptions::default())?;
//! assert_eq!(report.holes_filled, 1);
//! assert!(fixed.mesh.check().is_solid());
//! assert!((fixed.mesh.volume() - 1.0).abs() < 1e-12);
//! # Ok::<(), shatter_geom::mesh::repair::RepairError>(())
//! ```

mod clean;
mod fill;
mod orient;
mod refine;
mod report;
mod soup;
#[cfg(test)]
mod tests;
mod union;
pub(crate) use union::retreat_pinches;
mod weld;

pub use report::{RepairError, RepairOptions, RepairReport, UnionReport};

use glam::DVec3;

use self::orient::Shell;
use self::soup::Soup;
use crate::model::Model;

/// Volumes below this fraction of the bounding box's volume count as none.
const FLAT_VOLUME: f64 = 1e-12;

/// Repairs `model` into a closed solid (see the module docs).
pub fn repair(
    model: &Model,
    options: &RepairOptions,
) -> Result<(Model, RepairReport), RepairError> {
    model.check()?;
    model.mesh.validate_indices()?;
    let mut report = RepairReport::default();
    let mut soup = Soup::from_model(model);
    weld::exact(&mut soup);
    let (lo, hi) = model.mesh.bounds().unwrap_or((DVec3::ZERO, DVec3::ZERO));
    let diagonal = (hi - lo).length();
    report.weld_tolerance = options.weld_tolerance * diagonal;
    report.welded_vertices = weld::boundary(&mut soup, report.weld_tolerance);
    let degenerate = clean::degenerate(&mut soup);
    report.degenerate_triangles = degenerate.dropped;
    report.t_junctions_split = degenerate.split;
    let duplicates = clean::duplicates(&mut soup);
    report.duplicate_triangles = duplicates.copies;
    report.opposite_pairs_dropped = duplicates.opposite;

    let (shells, rewound) = orient::shells_wound(&mut soup);
    report.rewound_triangles = rewound;
    let mut closed: Vec<Shell> = Vec::new();
    for mut shell in shells {
        if shell.conflicts > 0 {
            report.non_orientable_dropped += 1;
            continue;
        }
        if close_shell(&mut soup, &mut shell, options, &mut report) {
            closed.push(shell);
        } else {
            report.open_sheets_dropped += 1;
            report.open_sheet_triangles += shell.tris.len();
        }
    }
    let flat = FLAT_VOLUME
        * (hi - lo)
            .abs()
            .element_product()
            .max(diagonal.powi(3) * 1e-9);
    let mut kept = Vec::new();
    for shell in closed {
        let v = orient::volume(&soup, &shell);
        if v.abs() <= flat || !v.is_finite() {
            report.flat_shells_dropped += 1;
            continue;
        }
        if v < 0.0 {
            orient::flip_shell(&mut soup, &shell);
            report.inverted_shells += 1;
        }
        kept.push(shell);
    }
    for (shell, cavity) in kept.iter().zip(orient::cavities(&soup, &kept)) {
        if cavity {
            orient::flip_shell(&mut soup, shell);
            report.cavities += 1;
        }
    }
    if kept.is_empty() {
        return Err(nothing_solid(&report));
    }
    // Kept triangles in input order, patches after them.
    let mut order: Vec<usize> = kept
        .iter()
        .flat_map(|s| s.tris.iter().map(|&t| t as usize))
        .collect();
    order.sort_unstable();
    soup.select(&order);
    report.shells = kept.len();
    if options.union && needs_union(&soup) {
        let before = soup.tris.len();
        let united = union::union(&soup, diagonal).map_err(|e| RepairError::Union(e.0))?;
        soup = united.soup;
        let snapped = united.snapped;
        let snap = union::SNAP_TOLERANCE * diagonal;
        let slivers = drop_flat_shells(&mut soup, flat);
        let (rounding_crossings, rounding_depth) = crossings(&soup);
        report.union = Some(UnionReport {
            shells: kept.len(),
            triangles_before: before,
            triangles_after: soup.tris.len(),
            sliver_shells_dropped: slivers,
            snapped_coordinates: snapped,
            snap_tolerance: snap,
            rounding_crossings,
            rounding_depth,
        });
        report.shells = soup.mesh().check().components;
    }
    let fixed = soup.into_model(model.materials.clone());
    report.volume = fixed.mesh.signed_volume();
    Ok((fixed, report))
}

/// Fills the holes of `shell` if each is within the size limit; returns whether the
/// shell is closed (it is then extended by the patches).
fn close_shell(
    soup: &mut Soup,
    shell: &mut Shell,
    options: &RepairOptions,
    report: &mut RepairReport,
) -> bool {
    let (loops, stray) = fill::boundary_loops(soup, &shell.tris);
    if loops.is_empty() {
        return stray == 0;
    }
    if stray > 0 {
        return false;
    }
    let area: f64 = shell
        .tris
        .iter()
        .map(|&t| 0.5 * soup.face_normal(t as usize).length())
        .sum();
    let mut patches = Vec::with_capacity(loops.len());
    let mut base = soup.pos.len();
    for hole in &loops {
        // Each patch numbers its new vertices from the soup's end as it will be.
        let Some(mut patch) = fill::patch(soup, hole) else {
            return false;
        };
        if patch.area.is_nan() || patch.area > options.max_hole_area * area {
            return false;
        }
        let shift = (base - soup.pos.len()) as u32;
        for t in &mut patch.tris {
            for v in t.iter_mut() {
                if *v as usize >= soup.pos.len() {
                    *v += shift;
                }
            }
        }
        base += patch.new_pos.len();
        patches.push(patch);
    }
    for patch in patches {
        soup.pos.extend(patch.new_pos);
        report.holes_filled += 1;
        report.fill_triangles += patch.tris.len();
        for (tri, corners) in patch.tris.into_iter().zip(patch.corners) {
            shell.tris.push(soup.tris.len() as u32);
            soup.push(tri, corners, patch.material);
        }
    }
    true
}

/// Drops the closed shells of `soup` whose volume is at most `flat` (slivers the union's
/// rounding leaves); returns how many.
fn drop_flat_shells(soup: &mut Soup, flat: f64) -> usize {
    let (shells, _) = orient::shells_wound(soup);
    let mut keep = vec![true; soup.tris.len()];
    let mut dropped = 0;
    for shell in &shells {
        let v = orient::volume(soup, shell);
        if v.abs() <= flat || !v.is_finite() {
            dropped += 1;
            for &t in &shell.tris {
                keep[t as usize] = false;
            }
        }
    }
    if dropped > 0 && keep.iter().any(|&k| k) {
        soup.retain(&keep);
        dropped
    } else {
        0
    }
}

/// Whether the closed shells cross, touch, or share edges or vertices (what a solid's
/// validation refuses).
fn needs_union(soup: &Soup) -> bool {
    let mesh = soup.mesh();
    let r = mesh.check();
    if !r.is_manifold() || r.boundary_edges > 0 || r.inconsistent_edges > 0 {
        return true;
    }
    !mesh.self_intersections(1).is_empty()
}

/// Pairs of triangles of the soup that touch or cross (sharing no vertex), and the depth
/// of the deepest crossing (`mesh::intersect`'s measure, in model units).
fn crossings(soup: &Soup) -> (usize, f64) {
    let mesh = soup.mesh();
    let pairs = mesh.self_intersections(usize::MAX);
    let depth = pairs
        .iter()
        .map(|&(a, b)| {
            crate::mesh::intersect::crossing_depth(
                mesh.triangle(a as usize),
                mesh.triangle(b as usize),
            )
        })
        .fold(0.0, f64::max);
    (pairs.len(), depth)
}

/// The error when no closed part is left.
fn nothing_solid(r: &RepairReport) -> RepairError {
    let mut found = Vec::new();
    let s = |n: usize| if n == 1 { "" } else { "s" };
    if r.open_sheets_dropped > 0 {
        found.push(format!(
            "{} open sheet{}",
            r.open_sheets_dropped,
            s(r.open_sheets_dropped)
        ));
    }
    if r.non_orientable_dropped > 0 {
        found.push(format!(
            "{} non-orientable surface{}",
            r.non_orientable_dropped,
            s(r.non_orientable_dropped)
        ));
    }
    if r.flat_shells_dropped > 0 {
        found.push(format!(
            "{} closed shell{} without volume",
            r.flat_shells_dropped,
            s(r.flat_shells_dropped)
        ));
    }
    if found.is_empty() {
        found.push(format!(
            "only degenerate or cancelling triangles ({} degenerate, {} in opposite pairs)",
            r.degenerate_triangles, r.opposite_pairs_dropped
        ));
    }
    RepairError::NoSolid {
        found: found.join(", "),
    }
}
