//! Splitting a body into the connected components of its intact bonds.
//!
//! Every component becomes a body with the old body's pose (all bodies of an object share
//! the object's frame, so colliders keep their offsets). A component of a moving body
//! moves as its material did: `v_i = v + ω × (c_i − c)`, `ω_i = ω`
//! ([`inherited_velocity`]). This conserves linear momentum and angular momentum about any
//! fixed point. A component freed from a fixed (anchored) body starts at rest and receives
//! the impulses its fragments took during the step ([`launch_velocity`]).

use std::collections::BTreeMap;

use glam::{DVec3, Vec3};

use shatter_geom::util::UnionFind;

use super::bonds::{BondState, Graph};

/// The connected components (fragment lists, ascending) of the fragments on `body`,
/// ordered by their smallest fragment. `body_of` gives each fragment's body (any key the
/// engine uses: a handle, an entity), `None` for a fragment without one.
pub fn components<K: Copy + PartialEq>(
    graph: &Graph<'_>,
    state: &BondState,
    body_of: &[Option<K>],
    body: K,
) -> Vec<Vec<u32>> {
    let n = body_of.len();
    // The smaller root wins, so the components come out in a deterministic order.
    let mut uf = UnionFind::new(n);
    for (b, bond) in graph.bonds.iter().enumerate() {
        if state.broken.get(b).is_none_or(|x| *x) {
            continue;
        }
        let on = |f: u32| body_of.get(f as usize).copied().flatten() == Some(body);
        if on(bond.a) && on(bond.b) {
            uf.union(bond.a as usize, bond.b as usize);
        }
    }
    let mut groups: BTreeMap<usize, Vec<u32>> = BTreeMap::new();
    for f in 0..n as u32 {
        if body_of[f as usize] == Some(body) {
            groups.entry(uf.find(f as usize)).or_default().push(f);
        }
    }
    groups.into_values().collect()
}

/// The centre of mass (object frame) of the fragments `part`, from their `centroids`
/// and the graph's masses; `None` if they weigh nothing.
///
/// ```
/// use glam::DVec3;
/// use shatter_sim::breaking::part_centre;
/// let c = part_centre(&[DVec3::ZERO, DVec3::X * 2.0], &[1.0, 3.0], &[0, 1]);
/// assert_eq!(c, Some(DVec3::X * 1.5));
/// ```
pub fn part_centre(centroids: &[DVec3], masses: &[f32], part: &[u32]) -> Option<DVec3> {
    let (mut sum, mut m) = (DVec3::ZERO, 0.0f64);
    for &f in part {
        let (Some(c), Some(mf)) = (centroids.get(f as usize), masses.get(f as usize)) else {
            continue;
        };
        sum += *c * f64::from(*mf);
        m += f64::from(*mf);
    }
    (m > 0.0).then(|| sum / m)
}

/// The velocity of a part whose centre of mass is `part_centre`, cut from a body moving
/// with `linvel` and `angvel` about its centre of mass `centre` (all world frame).
///
/// ```
/// use glam::Vec3;
/// use shatter_sim::breaking::inherited_velocity;
/// let v = inherited_velocity(Vec3::X, Vec3::Z, Vec3::ZERO, Vec3::Y);
/// assert_eq!(v, Vec3::X + Vec3::Z.cross(Vec3::Y));
/// ```
pub fn inherited_velocity(linvel: Vec3, angvel: Vec3, centre: Vec3, part_centre: Vec3) -> Vec3 {
    linvel + angvel.cross(part_centre - centre)
}

/// The velocity of a part of mass `mass` freed from a fixed body: the impulses its
/// fragments received this step (`impulses`, from [`Loads`](super::Loads)) over its mass
/// plus the heaviest body that hit it.
///
/// ```
/// use std::collections::BTreeMap;
/// use glam::Vec3;
/// use shatter_sim::breaking::launch_velocity;
/// let hits = BTreeMap::from([(3, (Vec3::X * 10.0, 1.0))]);
/// assert_eq!(launch_velocity(&hits, &[3], 4.0), Vec3::X * 2.0);
/// ```
pub fn launch_velocity(impulses: &BTreeMap<u32, (Vec3, f32)>, part: &[u32], mass: f32) -> Vec3 {
    let (mut j, mut m_other) = (Vec3::ZERO, 0.0f32);
    for (ji, mi) in part.iter().filter_map(|f| impulses.get(f)) {
        j += *ji;
        m_other = m_other.max(*mi);
    }
    let m = mass + m_other;
    if m > 0.0 { j / m } else { Vec3::ZERO }
}
