//! What the break logic reports, as plain data.

use glam::Vec3;

/// Why a bond broke.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum BreakCause {
    /// A load over the break force: a contact, an explosion, an explicit break, or a
    /// joint's force.
    Impact,
    /// The stress solver: gravity and the step's loads put a stress over the material's
    /// compression, tension or shear limit on the bond.
    Stress,
    /// Hits below the break force wore the bond's health down to 0.
    Damage,
}

impl BreakCause {
    /// All causes, in counter order.
    pub const ALL: [BreakCause; 3] = [BreakCause::Impact, BreakCause::Stress, BreakCause::Damage];

    /// Index into per-cause counters.
    ///
    /// ```
    /// use shatter_sim::BreakCause;
    /// assert_eq!(BreakCause::Damage.index(), 2);
    /// ```
    pub fn index(self) -> usize {
        match self {
            BreakCause::Impact => 0,
            BreakCause::Stress => 1,
            BreakCause::Damage => 2,
        }
    }

    /// `impact`, `stress` or `damage`.
    ///
    /// ```
    /// use shatter_sim::BreakCause;
    /// assert_eq!(BreakCause::Impact.name(), "impact");
    /// ```
    pub fn name(self) -> &'static str {
        match self {
            BreakCause::Impact => "impact",
            BreakCause::Stress => "stress",
            BreakCause::Damage => "damage",
        }
    }
}

/// One bond that broke.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BondBroken {
    /// The bond's index in the fracture's bond list.
    pub bond: u32,
    /// Its two fragments.
    pub fragments: [u32; 2],
    /// Why it broke.
    pub cause: BreakCause,
    /// The load that broke it or wore it out (N).
    pub load: f32,
}

/// A body split into islands of intact bonds.
#[derive(Debug, Clone, PartialEq)]
pub struct Split {
    /// The islands' fragments, each ascending, ordered by their smallest fragment. The
    /// first island keeps the old body; each other one gets a new body.
    pub parts: Vec<Vec<u32>>,
    /// The linear velocity each island starts with (world frame, m/s).
    pub velocities: Vec<Vec3>,
}

/// Something the break logic reports for an object.
#[derive(Debug, Clone, PartialEq)]
pub enum BreakEvent {
    /// A bond broke.
    BondBroken(BondBroken),
    /// A body split into islands.
    Split(Split),
    /// The object's lifetime ended; it was removed.
    Expired,
    /// A body's state became non-finite or its speed ran away; it was removed.
    Diverged {
        /// The fragments it held.
        fragments: Vec<u32>,
        /// What was wrong.
        reason: String,
    },
}
