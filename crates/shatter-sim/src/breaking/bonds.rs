//! The bond state of one object, bond loads and the break rule.
//!
//! Loads, in newtons, accumulate over one step and are compared with the break force
//! directly (not scaled by the bond's area):
//! - a contact force `F` on fragment `f` of a body of mass `M` loads the bonds at graph
//!   distance `d` from `f` with `F·(1 − m_f/M)·½^d`, for `d = 0, 1, 2` (the part of the
//!   impulse that must pass through the bonds to move the rest of the body; fixed bodies
//!   have `M = ∞`, see [`contact_share`]);
//! - an explosion of power `P` (N·s) and radius `r` loads each bond whose centroid is at
//!   distance `x < r` with `P·(1 − x/r)/dt` ([`explosion_load`]).
//!
//! A load below the break force wears the bond's health ([`BondState::apply`]).

use std::collections::{BTreeMap, BTreeSet};

use glam::Vec3;
use shatter_geom::fracture::Bond;

use super::events::{BondBroken, BreakCause};

/// Contact forces matter only above this fraction of the break force (engines may use it
/// as their contact-report threshold).
pub const EVENT_THRESHOLD_FRACTION: f32 = 0.25;
/// Graph distance over which a contact load spreads.
pub const LOAD_DEPTH: usize = 2;
/// Attenuation per graph step.
pub const LOAD_ATTENUATION: f32 = 0.5;

/// The fixed part of an object's bond graph: its bonds, each fragment's bonds and masses.
#[derive(Debug, Clone, Copy)]
pub struct Graph<'a> {
    /// The bonds (fragments `a`, `b`, area, centroid, normal in the object's frame).
    pub bonds: &'a [Bond],
    /// Per fragment, the indices of its bonds.
    pub adjacency: &'a [Vec<u32>],
    /// Per fragment, its mass (kg).
    pub masses: &'a [f32],
}

impl Graph<'_> {
    /// Per fragment (of `fragments`), the indices of its bonds, ascending.
    ///
    /// ```
    /// use shatter_sim::breaking::Graph;
    /// let wall = shatter_sim::testing::box_grid_fracture([3, 1, 1], [3.0, 1.0, 1.0].into());
    /// let adjacency = Graph::adjacency_of(&wall.bonds, 3);
    /// assert_eq!(adjacency[1].len(), 2);
    /// ```
    pub fn adjacency_of(bonds: &[Bond], fragments: usize) -> Vec<Vec<u32>> {
        let mut adjacency = vec![Vec::new(); fragments];
        for (i, b) in bonds.iter().enumerate() {
            for f in [b.a, b.b] {
                if let Some(list) = adjacency.get_mut(f as usize) {
                    list.push(i as u32);
                }
            }
        }
        adjacency
    }
}

/// The endurance limit: a load under this fraction of the break force wears a bond
/// not at all, however often it comes. Without it, the steady contact of an object
/// resting on the ground (a few percent of the break force, every step) wore its bonds
/// out within seconds.
pub const ENDURANCE: f32 = 0.2;

/// Per bond, broken or not and its health, with the object's break force and wear.
#[derive(Debug, Clone, PartialEq)]
pub struct BondState {
    /// Break force of every bond (N).
    pub strength: f32,
    /// Health lost to a hit at the full break force (the material's wear).
    pub wear: f32,
    /// Per bond, broken or not.
    pub broken: Vec<bool>,
    /// Per bond, its health: 1 when new, worn by hits below the break force.
    pub health: Vec<f32>,
    /// Broken bonds by cause (see [`BreakCause::index`]).
    pub broken_by: [usize; 3],
    /// Number of broken bonds.
    pub bonds_broken: usize,
    /// Bumped whenever a bond breaks or a fragment loses its body
    /// ([`BondState::touch`]).
    pub version: u64,
}

impl BondState {
    /// `bonds` intact bonds of break force `strength` (N) and wear `wear`.
    ///
    /// ```
    /// use shatter_sim::breaking::BondState;
    /// let s = BondState::new(4, 1000.0, 0.1);
    /// assert_eq!(s.intact(), 4);
    /// ```
    pub fn new(bonds: usize, strength: f32, wear: f32) -> BondState {
        BondState {
            strength,
            wear,
            broken: vec![false; bonds],
            health: vec![1.0; bonds],
            broken_by: [0; 3],
            bonds_broken: 0,
            version: 0,
        }
    }

    /// Number of intact bonds.
    pub fn intact(&self) -> usize {
        self.broken.len() - self.bonds_broken
    }

    /// Marks bond `b` broken by `cause` (idempotent; an index out of range is ignored);
    /// returns whether it was intact.
    ///
    /// ```
    /// use shatter_sim::breaking::{BondState, BreakCause};
    /// let mut s = BondState::new(2, 1.0, 0.0);
    /// assert!(s.mark_broken(1, BreakCause::Impact));
    /// assert!(!s.mark_broken(1, BreakCause::Impact));
    /// assert_eq!(s.bonds_broken, 1);
    /// ```
    pub fn mark_broken(&mut self, b: usize, cause: BreakCause) -> bool {
        match self.broken.get_mut(b) {
            Some(broken) if !*broken => *broken = true,
            _ => return false,
        }
        self.bonds_broken += 1;
        self.broken_by[cause.index()] += 1;
        self.version += 1;
        true
    }

    /// Records a change that is not a broken bond (a fragment lost its body).
    pub fn touch(&mut self) {
        self.version += 1;
    }

    /// The break rule: breaks the bonds whose load exceeds the strength (cause: impact)
    /// and wears the others down: a load `x·strength` with [`ENDURANCE`] `≤ x < 1` takes
    /// `wear·x` of the bond's health, and a bond whose health reaches 0 breaks (cause:
    /// damage). Loads under the endurance limit (an object resting on the ground,
    /// settling after it lands) wear nothing. Returns the bonds that broke, in bond order.
    pub fn apply(&mut self, graph: &Graph<'_>, loads: &Loads) -> Vec<BondBroken> {
        let mut out = Vec::new();
        for (&b, &load) in &loads.bonds {
            let i = b as usize;
            if self.broken.get(i).is_none_or(|x| *x) {
                continue;
            }
            let cause = if load > self.strength {
                BreakCause::Impact
            } else {
                let x = load / self.strength;
                if x.is_nan() || x < ENDURANCE {
                    continue;
                }
                self.health[i] -= self.wear * x;
                if self.health[i] > 0.0 {
                    continue;
                }
                BreakCause::Damage
            };
            self.mark_broken(i, cause);
            let bond = &graph.bonds[i];
            out.push(BondBroken {
                bond: b,
                fragments: [bond.a, bond.b],
                cause,
                load,
            });
        }
        out
    }
}

/// The share of a contact force on a fragment of mass `fragment_mass` that its bonds
/// carry: `1 − m_f/M` on a dynamic body of mass `M`, all of it on a fixed body (`None`).
///
/// ```
/// use shatter_sim::breaking::contact_share;
/// assert_eq!(contact_share(1.0, Some(4.0)), 0.75);
/// assert_eq!(contact_share(1.0, None), 1.0);
/// ```
pub fn contact_share(fragment_mass: f32, body_mass: Option<f32>) -> f32 {
    match body_mass {
        Some(m) if m > 0.0 => (1.0 - fragment_mass / m).max(0.0),
        _ => 1.0,
    }
}

/// The fraction of a dynamic body's summed contact forces `sum` (N) that does more than
/// hold up its weight `mass·gravity`: `max(0, (S − M·g) / S)`. A body resting on the
/// ground puts no load on its bonds; a hard landing or a hit nearly all of it.
///
/// ```
/// use shatter_sim::breaking::weight_relief;
/// assert_eq!(weight_relief(9.81, 1.0, 9.81), 0.0);
/// assert!(weight_relief(1000.0, 1.0, 9.81) > 0.99);
/// ```
pub fn weight_relief(sum: f32, mass: f32, gravity: f32) -> f32 {
    if sum <= 0.0 {
        return 0.0;
    }
    ((sum - mass * gravity) / sum).max(0.0)
}

/// The load (N) an explosion of `power` (N·s) and `radius` puts on a bond at distance
/// `distance` over a step `dt`, or `None` outside the radius.
///
/// ```
/// use shatter_sim::breaking::explosion_load;
/// assert_eq!(explosion_load(0.5, 1.0, 10.0, 0.1), Some(50.0));
/// assert_eq!(explosion_load(2.0, 1.0, 10.0, 0.1), None);
/// ```
pub fn explosion_load(distance: f32, radius: f32, power: f32, dt: f32) -> Option<f32> {
    (distance < radius && dt > 0.0).then(|| power * (1.0 - distance / radius) / dt)
}

/// Bond loads of one object during one step, and the impulses its fragments received.
#[derive(Debug, Default, Clone, PartialEq)]
pub struct Loads {
    /// Bond index → load (N).
    pub bonds: BTreeMap<u32, f32>,
    /// Fragment → impulse received (N·s, world frame) and the mass of the dynamic body
    /// that gave it, used to launch pieces freed from fixed bodies.
    pub impulses: BTreeMap<u32, (Vec3, f32)>,
}

impl Loads {
    /// Loads the bonds around fragment `f` with a contact force `force` (N, already
    /// multiplied by [`contact_share`] and any relief), spreading it [`LOAD_DEPTH`] bonds
    /// deep with [`LOAD_ATTENUATION`] per step; records `impulse` from a body of mass
    /// `other_mass` (0 when static) on `f`.
    pub fn add_contact(
        &mut self,
        graph: &Graph<'_>,
        state: &BondState,
        f: u32,
        force: f32,
        impulse: Vec3,
        other_mass: f32,
    ) {
        if f as usize >= graph.adjacency.len() {
            return;
        }
        let entry = self.impulses.entry(f).or_insert((Vec3::ZERO, 0.0));
        entry.0 += impulse;
        entry.1 = entry.1.max(other_mass);
        let mut frontier = vec![f];
        let mut seen_fragments = BTreeSet::from([f]);
        let mut seen_bonds = BTreeSet::new();
        let mut load = force;
        for _ in 0..=LOAD_DEPTH {
            let mut next = Vec::new();
            for &g in &frontier {
                for &b in &graph.adjacency[g as usize] {
                    if state.broken[b as usize] || !seen_bonds.insert(b) {
                        continue;
                    }
                    *self.bonds.entry(b).or_insert(0.0) += load;
                    let bond = &graph.bonds[b as usize];
                    let other = if bond.a == g { bond.b } else { bond.a };
                    if seen_fragments.insert(other) {
                        next.push(other);
                    }
                }
            }
            frontier = next;
            load *= LOAD_ATTENUATION;
        }
    }

    /// Adds `load` (N) to bond `b` (an explosion, an explicit break).
    pub fn add_bond(&mut self, b: u32, load: f32) {
        *self.bonds.entry(b).or_insert(0.0) += load;
    }

    /// Whether nothing was loaded.
    pub fn is_empty(&self) -> bool {
        self.bonds.is_empty() && self.impulses.is_empty()
    }
}
