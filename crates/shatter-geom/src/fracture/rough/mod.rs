//! Rough cut faces: a post-pass that displaces the interior faces of a finished
//! [`Fracture`] by fractal noise, the same for both sides of every bond, so the
//! fragments still fit together exactly.
//!
//! Steps, one file each: `regions` (the flat interior regions of each fragment and the
//! pairs of them that are the two sides of a cap), `tessellate` (a cap's shared,
//! displaced core and each side's flat collar), `noise` (the fBm), `apply` (the
//! fragment rebuilt with its rough caps and checked), `pieces` (the convex collision
//! pieces cut back inside the rough fragment).
//!
//! The displacement is along the cap's normal, so each rough cap is a height field over
//! its flat cap: no triangle of it can flip or fold over another. Its boundary does not
//! move and gets no new vertex. The amplitude is limited per cap to 0.4 times the
//! taper's width (two grid spacings or the cap's depth, whichever is smaller), and a
//! fragment whose new faces would touch or cross another of its faces (exact test)
//! has the amplitude of its caps halved, up to five times, then those caps left flat.

mod apply;
mod noise;
mod pieces;
mod regions;
mod tessellate;

#[cfg(test)]
mod tests;

use glam::DVec2;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use super::error::FractureError;
use super::types::{Fracture, Fragment};
use crate::mesh::mass_properties;
use apply::{Cap, UvSource, rebuild, sound};
use pieces::{Cut, clip_piece};
use regions::{Region, regions_of, shared_caps};
use tessellate::{build_core, collar};

/// How many times a cap's amplitude is halved before the cap is left flat.
const HALVINGS: usize = 5;

/// Fractal roughness of cut faces, in world units: each interior face is displaced along
/// its normal by `amplitude` times fBm noise (`octaves` octaves of value noise, the first
/// `frequency` cycles per unit, each next one twice the frequency and half the weight)
/// of the world position and `seed`. `amplitude == 0` is off (the default).
///
/// ```
/// use shatter_geom::fracture::Roughness;
/// assert!(Roughness::default().is_off());
/// assert!(Roughness::GLASS.is_off());
/// Roughness::STONE.validate()?;
/// assert!(Roughness { octaves: 0, ..Roughness::STONE }.validate().is_err());
/// # Ok::<(), shatter_geom::fracture::FractureError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Roughness {
    /// Largest displacement (world units), `≥ 0`; 0 turns roughness off.
    pub amplitude: f64,
    /// Cycles per world unit of the first octave, `> 0`.
    pub frequency: f64,
    /// Octaves of noise, 1 to 8.
    pub octaves: u32,
    /// Noise seed: the same seed gives the same faces.
    pub seed: u64,
}

impl Default for Roughness {
    fn default() -> Self {
        Roughness::OFF
    }
}

impl Roughness {
    /// No roughness: flat cut faces.
    pub const OFF: Roughness = Roughness {
        amplitude: 0.0,
        frequency: 4.0,
        octaves: 3,
        seed: 0,
    };
    /// Glass breaks along flat faces: off.
    pub const GLASS: Roughness = Roughness::OFF;
    /// Stone: coarse, deep relief (1.5 cm, features about 17 cm and finer, four
    /// octaves), for objects about a metre across.
    pub const STONE: Roughness = Roughness {
        amplitude: 0.015,
        frequency: 6.0,
        octaves: 4,
        seed: 0,
    };
    /// Concrete: finer and shallower than stone (8 mm, features about 10 cm and finer,
    /// three octaves).
    pub const CONCRETE: Roughness = Roughness {
        amplitude: 0.008,
        frequency: 10.0,
        octaves: 3,
        seed: 0,
    };
    /// The upper bound of [`Roughness::octaves`].
    pub const MAX_OCTAVES: u32 = 8;

    /// Whether it is off (`amplitude == 0`).
    pub fn is_off(&self) -> bool {
        self.amplitude == 0.0
    }

    /// Checks the values: finite, `amplitude ≥ 0`, `frequency > 0`, `octaves` in
    /// `1..=8`; [`FractureError::BadRoughness`] names the first bad field.
    pub fn validate(&self) -> Result<(), FractureError> {
        let bad = |field, value, expected| {
            Err(FractureError::BadRoughness {
                field,
                value,
                expected,
            })
        };
        if !(self.amplitude.is_finite() && self.amplitude >= 0.0) {
            return bad("amplitude", self.amplitude, "finite and at least 0");
        }
        if !(self.frequency.is_finite() && self.frequency > 0.0) {
            return bad("frequency", self.frequency, "finite and above 0");
        }
        if !(1..=Self::MAX_OCTAVES).contains(&self.octaves) {
            return bad("octaves", f64::from(self.octaves), "1 to 8");
        }
        Ok(())
    }
}

/// What [`roughen`] did.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct RoughReport {
    /// Caps (both sides of a bond) made rough.
    pub caps: usize,
    /// Shared caps left flat: too small for an inner grid point, a triangulation that
    /// did not cover the cap, or faces that still crossed after the amplitude halvings.
    pub flat: usize,
    /// Flat interior regions with no matching other side (left flat).
    pub unmatched: usize,
    /// Rough caps whose amplitude is below the requested one (limited by the cap's size
    /// or halved to avoid crossing faces).
    pub reduced: usize,
    /// Caps whose amplitude was halved (at least once) because a fragment's new faces
    /// touched or crossed its other faces.
    pub halved: usize,
    /// Vertices added per side (each rough cap's core counted once).
    pub vertices: usize,
    /// The largest displacement of any vertex from its cap's plane.
    pub max_displacement: f64,
}

/// Makes the interior faces of `fracture` rough (see the module docs); off (amplitude
/// 0) leaves it untouched.
///
/// Both sides of a bond get the same displaced surface (the same points, wound the
/// other way), so the fragments still fit together and their volumes still add up to
/// the object's; each fragment stays closed and its new faces cross none of its others.
/// Fragment volumes, centroids and inertia are recomputed; convex pieces are cut back
/// inside the rough faces. Interior corners keep their planar UVs (the projection of
/// the displaced point onto the cap's plane), get the new faces' flat normals and the
/// old interior colour. Bonds are unchanged: their area, centroid and normal stay those
/// of the flat cap (the nominal contact). The same fracture, roughness and seed always
/// give the same result.
///
/// ```
/// use shatter_geom::fracture::{fracture, roughen, FractureParams, Method, Seeds, Pattern, Roughness};
/// use shatter_geom::shapes;
///
/// let params = FractureParams {
///     method: Method::Voronoi { seeds: Seeds::count(8) },
///     seed: 1,
/// };
/// let mut rough = fracture(&shapes::cube(), &params)?;
/// let report = roughen(&mut rough, &Roughness { amplitude: 0.02, ..Roughness::STONE })?;
/// assert!(report.caps > 0);
/// assert!((rough.total_volume() - 1.0).abs() < 1e-9);
/// # Ok::<(), shatter_geom::fracture::FractureError>(())
/// ```
pub fn roughen(fracture: &mut Fracture, rough: &Roughness) -> Result<RoughReport, FractureError> {
    rough.validate()?;
    let mut report = RoughReport::default();
    if rough.is_off() || fracture.fragments.is_empty() {
        return Ok(report);
    }
    for (i, f) in fracture.fragments.iter().enumerate() {
        check_fragment(f).map_err(|reason| FractureError::BadFragment {
            fragment: i,
            reason,
        })?;
    }
    let fragments = &fracture.fragments;
    let regions: Vec<Region> = fragments
        .par_iter()
        .enumerate()
        .map(|(i, f)| regions_of(i, f))
        .collect::<Vec<_>>()
        .into_iter()
        .flatten()
        .collect();
    let size = fragments
        .iter()
        .filter_map(|f| f.mesh.bounds())
        .map(|(lo, hi)| (hi - lo).length())
        .fold(0.0, f64::max);
    let pairs = shared_caps(&fracture.bonds, &regions, 1e-9 * size);
    report.unmatched = regions.len() - 2 * pairs.len();
    let built: Vec<Option<Cap>> = pairs
        .par_iter()
        .map(|&(i, j)| new_cap(fragments, &regions, [i, j], rough))
        .collect();
    report.flat = built.iter().filter(|c| c.is_none()).count();
    let mut caps: Vec<Cap> = built.into_iter().flatten().collect();
    let mut halved = vec![0usize; caps.len()];
    // Rebuild, check, and calm the caps of fragments that fail, until none fails; each
    // round rebuilds only the fragments whose caps changed.
    let mut rebuilt: Vec<Option<Fragment>> = vec![None; fragments.len()];
    let mut dirty = vec![true; fragments.len()];
    loop {
        let mine = caps_of(fragments.len(), &regions, &caps);
        let todo: Vec<usize> = (0..fragments.len()).filter(|&i| dirty[i]).collect();
        let redone: Vec<(usize, Option<Fragment>)> = todo
            .into_par_iter()
            .with_max_len(1)
            .map(|i| (i, finish(&fragments[i], &regions, &caps, &mine[i])))
            .collect();
        for (i, f) in redone {
            rebuilt[i] = f;
        }
        dirty.fill(false);
        let failing: Vec<usize> = (0..fragments.len())
            .filter(|&i| rebuilt[i].is_none())
            .collect();
        if failing.is_empty() {
            break;
        }
        for &i in &failing {
            for &(c, _) in &mine[i] {
                if caps[c].amplitude > 0.0 && halved[c] < HALVINGS {
                    caps[c].amplitude *= 0.5;
                    halved[c] += 1;
                } else {
                    caps[c].amplitude = 0.0;
                }
                for side in caps[c].sides {
                    dirty[regions[side].fragment] = true;
                }
            }
        }
    }
    for (f, new) in fracture.fragments.iter_mut().zip(rebuilt) {
        if let Some(new) = new {
            *f = new;
        }
    }
    for cap in caps.iter().filter(|c| c.amplitude > 0.0) {
        report.caps += 1;
        report.vertices += cap.core.points.len();
        if cap.amplitude < rough.amplitude {
            report.reduced += 1;
        }
        let deepest = cap
            .core
            .heights(cap.amplitude)
            .iter()
            .fold(0.0f64, |m, h| m.max(h.abs()));
        report.max_displacement = report.max_displacement.max(deepest);
    }
    report.flat += caps.iter().filter(|c| c.amplitude == 0.0).count();
    report.halved = halved.iter().filter(|&&h| h > 0).count();
    Ok(report)
}

/// Whether `f`'s parts fit together (what [`roughen`] indexes): triangle indices in
/// range, finite positions, one interior flag per triangle, one material per triangle
/// (or none) and one entry per triangle in each corner attribute present.
fn check_fragment(f: &Fragment) -> Result<(), &'static str> {
    let n = f.mesh.triangles.len();
    let vertices = f.mesh.positions.len();
    if f.mesh
        .triangles
        .iter()
        .flatten()
        .any(|&i| i as usize >= vertices)
    {
        return Err("a triangle index past its vertices");
    }
    if !f.mesh.positions.iter().all(|p| p.is_finite()) {
        return Err("a vertex is not finite");
    }
    if f.interior.len() != n {
        return Err("not one interior flag per triangle");
    }
    if !(f.material.is_empty() || f.material.len() == n) {
        return Err("not one material per triangle");
    }
    let c = &f.corners;
    let fits = |len: Option<usize>| len.is_none_or(|l| l == n);
    if !(fits(c.uv.as_ref().map(Vec::len))
        && fits(c.normal.as_ref().map(Vec::len))
        && fits(c.color.as_ref().map(Vec::len)))
    {
        return Err("corner attributes not one entry per triangle");
    }
    Ok(())
}

/// The cap whose sides are `regions[sides[0]]` and `regions[sides[1]]`, or `None` when
/// it has no inner grid point or a side's collar does not cover it.
fn new_cap(
    fragments: &[Fragment],
    regions: &[Region],
    sides: [usize; 2],
    rough: &Roughness,
) -> Option<Cap> {
    let [r0, r1] = sides.map(|s| &regions[s]);
    let (f0, f1) = (&fragments[r0.fragment], &fragments[r1.fragment]);
    let core = build_core(f0, r0, rough)?;
    let collars = [collar(f0, r0, &core)?, collar(f1, r1, &core)?];
    let core_uv =
        UvSource::of(f0, r0, &core).map(|s| core.points.iter().map(|&q| s.at(q)).collect());
    Some(Cap {
        sides,
        amplitude: rough.amplitude.min(core.max_amplitude),
        core,
        collars,
        core_uv,
    })
}

/// Per fragment, its caps with an amplitude as `(cap, side)` pairs, in cap order.
fn caps_of(n: usize, regions: &[Region], caps: &[Cap]) -> Vec<Vec<(usize, usize)>> {
    let mut mine = vec![Vec::new(); n];
    for (c, cap) in caps.iter().enumerate() {
        if cap.amplitude > 0.0 {
            for side in 0..2 {
                mine[regions[cap.sides[side]].fragment].push((c, side));
            }
        }
    }
    mine
}

/// Fragment `f` rebuilt with its caps `mine`, checked, its pieces cut back and its mass
/// properties recomputed; `None` when it is not sound or would lose all its pieces (the
/// fragment unchanged when `mine` is empty).
fn finish(
    f: &Fragment,
    regions: &[Region],
    caps: &[Cap],
    mine: &[(usize, usize)],
) -> Option<Fragment> {
    if mine.is_empty() {
        return Some(f.clone());
    }
    let (mut new, patches) = rebuild(f, regions, caps, mine);
    if !sound(&new, &patches) {
        return None;
    }
    let (lo, hi) = new.mesh.bounds()?;
    let tol = 1e-9 * (hi - lo).length();
    let mut pieces = new.convex_pieces.clone();
    for &(c, side) in mine {
        let cap = &caps[c];
        let sign = if side == 0 { 1.0 } else { -1.0 };
        // The deepest point of the cap inside this fragment (heights are along side 0's
        // outward normal).
        let depth = cap
            .core
            .heights(cap.amplitude)
            .iter()
            .fold(0.0f64, |m, &h| m.max(-h * sign));
        if depth == 0.0 {
            continue;
        }
        // Cut back, the pieces' hulls are no longer known.
        new.convex_hulls.clear();
        let frame = &cap.core.frame;
        let (mut blo, mut bhi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
        for &q in &cap.core.points {
            blo = blo.min(q);
            bhi = bhi.max(q);
        }
        let n = frame.n * sign;
        let cut = Cut {
            point: frame.origin - n * depth,
            n,
            u: frame.u,
            v: frame.v,
            lo: blo,
            hi: bhi,
        };
        pieces = pieces
            .iter()
            .filter_map(|p| clip_piece(p, &cut, tol))
            .collect();
    }
    // (A fragment without pieces, of a surfaces-only fracture, has none to lose.)
    if pieces.is_empty() && !f.convex_pieces.is_empty() {
        return None;
    }
    new.convex_pieces = pieces;
    let (volume, centroid, inertia) = mass_properties(&new.mesh.positions, &new.mesh.triangles);
    new.volume = volume;
    new.centroid = centroid;
    new.inertia = inertia;
    Some(new)
}
