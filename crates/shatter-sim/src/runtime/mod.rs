//! Runtime fracture: an object that starts whole and is cut where it is hit, and
//! fragments that are cut again when they are hit (depth levels).
//!
//! The cut itself is engine-free ([`cut_fragment`]): a radial Voronoi fracture of one
//! fragment around the impact point, exact cells clipped to the fragment (fine near the
//! impact, coarse away from it), keeping the fragment's UVs, normals and materials. The
//! new fragments' convex pieces are the fragment's own clipped by each cell
//! ([`shatter_geom::fracture::fracture_fragment`]), so an intact body starts with fine
//! convex pieces ([`whole`]) and no fragment is decomposed again. The
//! [`World`](crate::World) decides when to cut (`world/runtime_step.rs`): a hit on a
//! body holding a single fragment whose contact impulse passes the threshold, at a level
//! below the object's depth. The new fragments replace the old one as a new bonded
//! object that moves as the material did; the hit then loads their bonds, so only the
//! fine cells around the impact come loose.
//!
//! ```
//! use shatter_geom::{DVec3, shapes};
//! use shatter_geom::fracture::Fracture;
//! use shatter_sim::runtime::cut_fragment;
//!
//! // A cube cut once into one whole piece, then cut at runtime at the middle of its top.
//! let whole = shatter_sim::runtime::whole(&shatter_geom::model::Model::from_mesh(shapes::cube()))?;
//! let cut: Fracture = cut_fragment(&whole, 0, DVec3::new(0.0, 0.5, 0.0), 20, 7)?;
//! assert!(cut.fragments.len() > 5);
//! assert!((cut.total_volume() - 1.0).abs() < 1e-9);
//! // Each new fragment is a cell of the cube: one convex piece, with its hull.
//! assert!(cut.fragments.iter().all(|f| f.convex_hulls.len() == 1));
//! # Ok::<(), shatter_geom::fracture::FractureError>(())
//! ```

use glam::DVec3;
use shatter_geom::fracture::{self as geom, Fracture, FractureError};
use shatter_geom::model::Model;

use crate::error::SimError;

/// The seed of a runtime cut: the seed of the object's line of cuts mixed with which
/// fragment and level it cuts (not with object ids, which a reset does not repeat), so
/// every cut differs and a run repeats. The World and bevy_shatter both seed their cuts
/// with it.
///
/// ```
/// use shatter_sim::runtime::cut_seed;
/// assert_eq!(cut_seed(7, 3, 1), cut_seed(7, 3, 1));
/// assert_ne!(cut_seed(7, 3, 1), cut_seed(7, 3, 2));
/// assert_ne!(cut_seed(7, 3, 1), cut_seed(7, 4, 1));
/// ```
pub fn cut_seed(seed: u64, fragment: u32, level: u32) -> u64 {
    let mut h = seed ^ 0x9e37_79b9_7f4a_7c15;
    for v in [u64::from(fragment), u64::from(level)] {
        h = (h ^ v).wrapping_mul(0x0100_0000_01b3).rotate_left(17);
    }
    h
}

shatter_geom::vocabulary! {
    /// When a breakable object is cut into fragments.
    ///
    /// ```
    /// use shatter_sim::runtime::FractureTiming;
    /// assert_eq!("on_impact".parse(), Ok(FractureTiming::OnImpact));
    /// assert_eq!(FractureTiming::default().to_string(), "precomputed");
    /// ```
    pub enum FractureTiming: "fracture timing", default Precomputed {
        /// When the object is added: it starts as bonded fragments.
        Precomputed = "precomputed",
        /// At the first hit whose impulse passes the threshold: the object starts as one
        /// intact body and is cut around the hit point (radial Voronoi cells, fine near
        /// the impact and coarse away from it, clipped exactly to the mesh).
        OnImpact = "on_impact",
    }
}

/// How and when an object (and its fragments) fracture while the simulation runs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RuntimeFracture {
    /// When the object is first cut.
    pub timing: FractureTiming,
    /// Contact impulse (N·s) of a hit that cuts a body; `None`: the object's break force
    /// over one step (`break_force · dt`), so a hit that would break a bond cuts.
    pub impulse: Option<f32>,
    /// Fracture levels: a precomputed object's fragments are level 1, an `on_impact`
    /// object's intact body level 0 and its first cut's fragments level 1. A loose
    /// fragment of a level below `depth` is cut again when hit. `1`: no fragment is cut
    /// again (an `on_impact` object is still cut once).
    pub depth: u32,
    /// Fragments smaller than this (bounding-box diagonal, m) are not cut again.
    pub min_size: f32,
}

impl Default for RuntimeFracture {
    fn default() -> Self {
        RuntimeFracture {
            timing: FractureTiming::Precomputed,
            impulse: None,
            depth: 1,
            min_size: 0.1,
        }
    }
}

/// The largest `depth` accepted: each level cuts a fragment into at least four pieces,
/// so eight levels already make 4⁸ pieces of one fragment.
pub const MAX_DEPTH: u32 = 8;

impl RuntimeFracture {
    /// Checks the values; `key` prefixes the errors.
    pub fn validate(&self, key: &str) -> Result<(), SimError> {
        if let Some(i) = self.impulse
            && !(i.is_finite() && i > 0.0)
        {
            return Err(SimError::invalid(
                format!("{key}.fracture_impulse"),
                format!("must be a positive number of N·s, got {i}"),
            ));
        }
        if self.depth == 0 || self.depth > MAX_DEPTH {
            return Err(SimError::invalid(
                format!("{key}.depth"),
                format!("must be 1..={MAX_DEPTH}, got {}", self.depth),
            ));
        }
        if !(self.min_size.is_finite() && self.min_size >= 0.0) {
            return Err(SimError::invalid(
                format!("{key}.min_size"),
                format!("must be a number of metres >= 0, got {}", self.min_size),
            ));
        }
        Ok(())
    }

    /// Whether a fragment at `level` with bounding-box diagonal `size` is cut when hit.
    pub fn cuts(&self, level: u32, size: f64) -> bool {
        level == 0 || (level < self.depth && size >= f64::from(self.min_size))
    }
}

/// Pieces of a runtime cut of a fragment at `level`: the object's `pieces` for the
/// intact body (level 0), a quarter as many per level after (at least 4).
pub fn pieces_at(pieces: u32, level: u32) -> u32 {
    if level == 0 {
        return pieces.max(1);
    }
    let shift = 2 * level.min(15);
    (pieces >> shift).max(4)
}

/// The model of fragment `f` of `fracture`: its surface, corner attributes, per-triangle
/// materials and the fracture's materials (so a cut keeps them).
pub fn fragment_model(fracture: &Fracture, f: usize) -> Model {
    let fragment = &fracture.fragments[f];
    Model {
        mesh: fragment.mesh.clone(),
        corners: fragment.corners.clone(),
        material: fragment.material.clone(),
        materials: fracture.materials.clone(),
    }
}

/// An intact object: `model` as a single fragment, with its mass properties and convex
/// pieces made to be cut ([`geom::intact`]: up to 64, each with its hull), which the
/// fragments of its cuts inherit ([`cut_fragment`]).
pub fn whole(model: &Model) -> Result<Fracture, FractureError> {
    geom::intact(model)
}

/// The parameters of a runtime cut: `pieces` radial Voronoi cells around `impact`.
fn radial(impact: DVec3, pieces: u32, seed: u64) -> geom::FractureParams {
    geom::FractureParams {
        method: geom::Method::Voronoi {
            seeds: geom::Seeds::Pattern {
                count: pieces as usize,
                pattern: geom::Pattern::Radial,
                impact: Some(impact),
            },
        },
        seed,
    }
}

/// Cuts fragment `f` of `fracture` into `pieces` radial Voronoi cells around `impact` (in
/// the fracture's frame), clipped exactly to it, as [`cut_at`] cuts its model; the new
/// fragments' convex pieces are the fragment's own pieces clipped by each cell (see
/// [`geom::fracture_fragment`]), not decomposed again. This is the cut the World and
/// bevy_shatter make. An `f` past the fragments is an error.
///
/// ```
/// use shatter_geom::{DVec3, model::Model, shapes};
/// use shatter_sim::runtime::{cut_fragment, whole};
///
/// let bird = whole(&Model::from_mesh(shapes::bird()))?;
/// let cut = cut_fragment(&bird, 0, DVec3::new(1.5, 0.0, 0.0), 20, 1)?;
/// assert!(cut.fragments.len() >= 20);
/// // Fragments of fragments inherit the same way.
/// let again = cut_fragment(&cut, 0, cut.fragments[0].centroid, 4, 2)?;
/// assert!(again.fragments.iter().all(|f| !f.convex_hulls.is_empty()));
/// # Ok::<(), shatter_geom::fracture::FractureError>(())
/// ```
pub fn cut_fragment(
    fracture: &Fracture,
    f: usize,
    impact: DVec3,
    pieces: u32,
    seed: u64,
) -> Result<Fracture, FractureError> {
    let impact = match fracture.fragments.get(f) {
        Some(fragment) => nearest_vertex(&fragment.mesh.positions, impact),
        None => impact,
    };
    let mut result = geom::fracture_fragment(fracture, f, &radial(impact, pieces, seed))?;
    merge_interior_materials(&mut result);
    Ok(result)
}

/// Cuts `model` into `pieces` radial Voronoi cells around `impact` (in the model's
/// frame), clipped exactly to it. An impact outside the model is moved onto its
/// nearest vertex, so the cells still crowd where the hit landed. The interior
/// material is not added twice when the model already has one (a fragment cut again).
/// Each new fragment's convex pieces are decomposed from scratch: a fragment of a
/// [`Fracture`] is cut faster by [`cut_fragment`].
pub fn cut_at(
    model: &Model,
    impact: DVec3,
    pieces: u32,
    seed: u64,
) -> Result<Fracture, FractureError> {
    let impact = nearest_vertex(&model.mesh.positions, impact);
    let mut result = geom::fracture_model(model, &radial(impact, pieces, seed))?;
    merge_interior_materials(&mut result);
    Ok(result)
}

/// The position nearest `p` (`p` itself when there is none).
fn nearest_vertex(positions: &[DVec3], p: DVec3) -> DVec3 {
    positions
        .iter()
        .copied()
        .min_by(|a, b| a.distance_squared(p).total_cmp(&b.distance_squared(p)))
        .unwrap_or(p)
}

/// A fragment cut again already carries an `interior` material; the new cut appends
/// another. Both name the same thing, so the cut faces use the first one.
fn merge_interior_materials(fracture: &mut Fracture) {
    let interior: Vec<u32> = fracture
        .materials
        .iter()
        .enumerate()
        .filter(|(_, m)| m.name == "interior")
        .map(|(i, _)| i as u32)
        .collect();
    let [first, rest @ ..] = interior.as_slice() else {
        return;
    };
    if rest.is_empty() {
        return;
    }
    for fragment in &mut fracture.fragments {
        for m in &mut fragment.material {
            if rest.contains(m) {
                *m = *first;
            }
        }
    }
    // Drop the duplicates from the list and renumber what follows them.
    let keep: Vec<bool> = (0..fracture.materials.len() as u32)
        .map(|i| !rest.contains(&i))
        .collect();
    let mut new_index = Vec::with_capacity(keep.len());
    let mut next = 0u32;
    for &k in &keep {
        new_index.push(next);
        next += u32::from(k);
    }
    for fragment in &mut fracture.fragments {
        for m in &mut fragment.material {
            *m = new_index[*m as usize];
        }
    }
    let mut i = 0;
    fracture.materials.retain(|_| {
        i += 1;
        keep[i - 1]
    });
}

/// Bounding-box diagonal of a fragment's surface.
pub fn fragment_size(fracture: &Fracture, f: usize) -> f64 {
    fracture.fragments[f]
        .mesh
        .bounds()
        .map_or(0.0, |(lo, hi)| (hi - lo).length())
}

#[cfg(test)]
mod tests {
    use super::*;
    use shatter_geom::shapes;

    #[test]
    fn a_cut_crowds_its_cells_around_the_impact() {
        let whole = whole(&Model::from_mesh(shapes::cube())).unwrap();
        assert_eq!(whole.fragments.len(), 1);
        let impact = DVec3::new(0.5, 0.5, 0.5);
        let cut = cut_at(&fragment_model(&whole, 0), impact, 40, 3).unwrap();
        let near: Vec<f64> = cut
            .fragments
            .iter()
            .filter(|f| f.centroid.distance(impact) < 0.5)
            .map(|f| f.volume)
            .collect();
        let far: Vec<f64> = cut
            .fragments
            .iter()
            .filter(|f| f.centroid.distance(impact) >= 0.5)
            .map(|f| f.volume)
            .collect();
        assert!(
            near.len() > far.len(),
            "{} near, {} far",
            near.len(),
            far.len()
        );
        let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len().max(1) as f64;
        assert!(
            mean(&near) * 4.0 < mean(&far),
            "near cells {} m³ on average, far {} m³",
            mean(&near),
            mean(&far)
        );
        assert!((cut.total_volume() - 1.0).abs() < 1e-9);
    }

    #[test]
    fn a_fragment_cut_again_keeps_one_interior_material() {
        let first = cut_at(
            &Model::from_mesh(shapes::cube()),
            DVec3::new(0.0, 0.5, 0.0),
            12,
            1,
        )
        .unwrap();
        let second = cut_at(
            &fragment_model(&first, 0),
            first.fragments[0].centroid,
            8,
            2,
        )
        .unwrap();
        let names: Vec<&str> = second.materials.iter().map(|m| m.name.as_str()).collect();
        assert_eq!(
            names.iter().filter(|n| **n == "interior").count(),
            1,
            "{names:?}"
        );
        for f in &second.fragments {
            assert!(
                f.material
                    .iter()
                    .all(|&m| (m as usize) < second.materials.len())
            );
            for (t, &i) in f.interior.iter().enumerate() {
                if i {
                    assert_eq!(second.materials[f.material[t] as usize].name, "interior");
                }
            }
        }
        let v0 = first.fragments[0].volume;
        assert!((second.total_volume() - v0).abs() < 1e-9 * v0.max(1.0));
    }

    #[test]
    fn levels_and_sizes_decide_what_is_cut_again() {
        let r = RuntimeFracture {
            depth: 2,
            min_size: 0.2,
            ..RuntimeFracture::default()
        };
        assert!(r.cuts(0, 0.01), "the intact body is always cut");
        assert!(r.cuts(1, 0.5));
        assert!(!r.cuts(1, 0.1), "below min_size");
        assert!(!r.cuts(2, 0.5), "at depth");
        assert_eq!(pieces_at(50, 0), 50);
        assert_eq!(pieces_at(50, 1), 12);
        assert_eq!(pieces_at(50, 2), 4);
        assert!(RuntimeFracture { depth: 0, ..r }.validate("o").is_err());
        let err = RuntimeFracture {
            impulse: Some(-1.0),
            ..r
        }
        .validate("objects[0]")
        .unwrap_err();
        assert!(
            err.to_string().contains("objects[0].fracture_impulse"),
            "{err}"
        );
    }
}
