//! World settings and the statistics reported after each step.

use glam::Vec3;

use crate::object::BondModel;

/// [`WorldSettings::stress_budget`] by default. Every shipped scene's solves converge
/// within it at every step, so they run as without a budget; a large object is held back
/// by [`DEFAULT_STRESS_SPRING_BUDGET`] first.
pub const DEFAULT_STRESS_BUDGET: usize = 64;

/// [`WorldSettings::stress_spring_budget`] by default: springs the stress solver visits per
/// object per step, about a millisecond of one core. A 20,000-bond object's solve then
/// advances one conjugate-gradient iteration per step (a hit on a 20,000-bond wall is
/// judged about 35 steps later); objects under 2,000 bonds do a dozen or more and
/// converge within a step or two.
pub const DEFAULT_STRESS_SPRING_BUDGET: usize = 24_000;

/// [`WorldSettings::stress_build_budget`] by default: block operations of multigrid
/// hierarchy building per object per step, 1.2 to 1.7 ms of one core. An island that a
/// split leaves with less than half of its hierarchy gets its own over the next steps
/// (about 50 for a 20,000-bond island; one under 400 bonds), using the one it split from
/// meanwhile, so no step pays for a whole hierarchy. (At 40,000, `collapse.toml` with a
/// stress budget of 4 iterations kept 87 of its 112 right-hand blocks standing instead of
/// at least 101: its outcome depends on when each sliced solve converges, and a part
/// converges a little slower on the hierarchy it split from.)
pub const DEFAULT_STRESS_BUILD_BUDGET: usize = 100_000;

/// [`WorldSettings::max_launch_speed`] by default (m/s): half of
/// [`WorldSettings::max_speed`]'s default, where a body counts as diverged, so a thrown
/// body keeps a margin for what contacts add; far above what the shipped scenes'
/// explosions throw (a few tens of m/s, 320 m/s for a brick at the heart of the
/// explosion test's 12 kN·s blast).
pub const DEFAULT_MAX_LAUNCH_SPEED: f32 = 500.0;

/// [`WorldSettings::max_debris`] by default: debris bodies kept. Above the 10,000 free
/// bodies issue 17 asks a 20,000-fragment world to carry, so it removes nothing the
/// benchmarks or the shipped scenes make; it bounds what an unbounded run piles up.
pub const DEFAULT_MAX_DEBRIS: usize = 10_000;

/// [`WorldSettings::tiny_debris`] by default (m): loose pieces smaller than 5 cm across
/// (slivers, chips) do not collide with each other.
pub const DEFAULT_TINY_DEBRIS: f32 = 0.05;

/// Global settings of a simulation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WorldSettings {
    /// Gravity (m/s²).
    pub gravity: Vec3,
    /// Fixed time step in seconds (default 1/60).
    pub dt: f32,
    /// Bond model for objects that do not choose one.
    pub bond_model: BondModel,
    /// A static ground plane at y = 0 (a thin box, `ground_size` wide).
    pub ground: bool,
    /// Half-extent of the ground box in x and z.
    pub ground_size: f32,
    /// Friction of the ground.
    pub ground_friction: f32,
    /// Keep at most this many debris bodies (single fragments broken loose): beyond it,
    /// settled (sleeping) pieces go before moving ones, the smallest first (the oldest of
    /// equals first). `None`: no cap. Default [`DEFAULT_MAX_DEBRIS`].
    pub max_debris: Option<usize>,
    /// Linear speed (m/s) above which a body counts as diverging and is removed.
    pub max_speed: f32,
    /// Fastest an explosion throws a body, and a part broken out of an anchored body is
    /// launched by the impulses it took (m/s): a body the explosion would make faster
    /// gets this speed in the same direction (one already faster is not slowed). Keeps
    /// a strong explosion next to a small fragment from throwing it past `max_speed`.
    pub max_launch_speed: f32,
    /// Debris (a single loose fragment) whose bounding box's diagonal is under this size
    /// (m) does not collide with other such debris, only with everything else: chips
    /// and slivers fall through each other onto the ground and the larger pieces
    /// instead of piling up in contacts. 0: every piece collides with every piece.
    /// Default [`DEFAULT_TINY_DEBRIS`].
    pub tiny_debris: f32,
    /// A convex piece that is an axis-aligned box in its object's frame (a grid's brick)
    /// collides as Rapier's cuboid instead of its hull: box-box contacts, bounds and
    /// sweeps cost a fraction of a convex polyhedron's (bench scale's landing block of
    /// 20,000 bricks: about half the step time). Off by default: the contacts are not
    /// the hulls' (a block resting on the ground pushes on it less at its first step),
    /// so which bonds a hit or a fall breaks differs, and `collapse.toml` leaves 8 of
    /// the 40 bricks above its hole standing where the hulls bring all down.
    pub box_colliders: bool,
    /// Cluster objects give colliders to their enclosed fragments too
    /// ([`Prepared::enclosed`](crate::object::Prepared::enclosed): a fragment whose every face is
    /// a cut face bonded to a neighbour, such as a block's interior brick). Off by
    /// default: such a fragment gets its colliders only when a bond of it breaks (until
    /// then nothing can reach it without passing through its neighbours), and its mass
    /// counts in its body's additional mass. Bench scale's 20,000-brick block falls at
    /// 4 ms per step instead of 31 with them. Turn it on to have a deep interpenetration
    /// (a body moving more than a fragment's size in one step into another) met by
    /// every fragment it reaches, as before.
    pub enclosed_colliders: bool,
    /// Joints-model objects skip the contacts between fragments held within three intact
    /// bonds of each other (a brick's edge and corner neighbours: the joints keep them in
    /// place, as a cluster's fragments share a body; `crate::bonds::held`). Bench
    /// scale's 2,000-brick joints wall: about 2.5 times faster. Off by default: those
    /// contacts load the joints too, so fewer bonds break (the shots at the wall break
    /// 13 instead of 45) and the joints tests' thresholds were set with them.
    pub skip_held_contacts: bool,
    /// No body leaves a step faster than it moved when the step began plus the most an
    /// elastic hit by anything touching it could add (twice that one's speed at the
    /// contact when it is far heavier, less when it is lighter), plus what gravity and
    /// Rapier's penetration correction add in one step; a faster one has its velocity
    /// and spin scaled down together to that bound (its move in the step is kept).
    /// Bodies held by joints (the joints model) are left to them.
    /// Keeps a brick squeezed under a landing block from being flung out at hundreds of
    /// m/s, which Rapier's solver otherwise does at such mass ratios (bench scale's
    /// 5,000-brick landing: 202 m/s). Explosions, shots and split launches are not
    /// capped: they happen between steps. On by default.
    pub contact_speed_cap: bool,
    /// Solver iterations (Rapier substeps) per step.
    pub solver_iterations: usize,
    /// Run the stress solver on anchored cluster objects (gravity carried to the anchors,
    /// bonds over the material's stress limits break). On by default.
    pub stress: bool,
    /// Most conjugate-gradient iterations of the stress solver per object per step
    /// (`None`: solve to convergence every step). A large anchored object then costs a
    /// bounded time per step; an unfinished solve goes on at the next step and its bonds
    /// are judged when it has converged (see
    /// [`SolverSettings::budget`](crate::stress::SolverSettings::budget)).
    pub stress_budget: Option<usize>,
    /// Most springs the stress solver visits per object per step (`None`: no limit):
    /// each iteration, and each start of a solve, visits all of an object's intact bonds,
    /// so this bounds the time a large object's solve takes per step where
    /// `stress_budget` bounds only its iterations (see
    /// [`SolverSettings::spring_budget`](crate::stress::SolverSettings::spring_budget)).
    pub stress_spring_budget: Option<usize>,
    /// Most work per object per step on the stress solver's multigrid hierarchies under
    /// construction, in block operations (`None`: an island that needs a hierarchy builds
    /// it at once, in that step; see
    /// [`SolverSettings::build_budget`](crate::stress::SolverSettings::build_budget)).
    pub stress_build_budget: Option<usize>,
}

impl Default for WorldSettings {
    fn default() -> Self {
        WorldSettings {
            gravity: Vec3::new(0.0, -9.81, 0.0),
            dt: 1.0 / 60.0,
            bond_model: BondModel::Clusters,
            ground: true,
            ground_size: 100.0,
            ground_friction: 0.8,
            max_debris: Some(DEFAULT_MAX_DEBRIS),
            max_speed: 1000.0,
            max_launch_speed: DEFAULT_MAX_LAUNCH_SPEED,
            tiny_debris: DEFAULT_TINY_DEBRIS,
            box_colliders: false,
            enclosed_colliders: false,
            skip_held_contacts: false,
            contact_speed_cap: true,
            solver_iterations: 4,
            stress: true,
            stress_budget: Some(DEFAULT_STRESS_BUDGET),
            stress_spring_budget: Some(DEFAULT_STRESS_SPRING_BUDGET),
            stress_build_budget: Some(DEFAULT_STRESS_BUILD_BUDGET),
        }
    }
}

/// Statistics after the last step.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Stats {
    /// Steps since start.
    pub steps: u64,
    /// Simulated time since start (s).
    pub time: f64,
    /// Rigid bodies (objects and projectiles; the ground is not counted).
    pub bodies: usize,
    /// Fragments with a body.
    pub fragments: usize,
    /// Dynamic bodies Rapier has put to sleep (at rest, not simulated until woken).
    pub sleeping_bodies: usize,
    /// Bonds of all objects.
    pub bonds_total: usize,
    /// Broken bonds since start (never decreases during a run: bonds of objects that
    /// expire or are deleted stay counted). The sum of the three causes below.
    pub bonds_broken: usize,
    /// Bonds broken by a load over the break force (contacts, explosions, explicit breaks,
    /// joints).
    pub bonds_broken_by_impact: usize,
    /// Bonds broken by the stress solver (a stress over the material's limits).
    pub bonds_broken_by_stress: usize,
    /// Bonds broken because repeated hits wore their health to 0.
    pub bonds_broken_by_damage: usize,
    /// Stress solves of anchored islands since start (settled islands are not solved).
    pub stress_solves: u64,
    /// Conjugate-gradient iterations of the stress solver in the last step.
    pub stress_iterations: usize,
    /// Wall-clock milliseconds of the last step's stress pass: the solves, the bonds they
    /// break and the bodies those breaks split.
    pub stress_ms: f64,
    /// Wall-clock milliseconds of the last step's stress solves alone (part of
    /// `stress_ms`): what the solver's budgets bound.
    pub stress_solve_ms: f64,
    /// CPU milliseconds of the stepping thread in the last step's stress solves, with a
    /// clock set by [`World::set_cpu_clock`](crate::World::set_cpu_clock) (`None`
    /// without): unlike `stress_solve_ms`, not inflated when other processes share the
    /// core.
    pub stress_solve_cpu_ms: Option<f64>,
    /// Bodies removed because their state diverged (NaN or runaway speed).
    pub diverged: usize,
    /// Bodies slowed by the contact speed cap since start
    /// ([`WorldSettings::contact_speed_cap`]).
    pub speeds_capped: usize,
    /// Debris bodies removed by the cap.
    pub debris_removed: usize,
    /// Wall-clock milliseconds of the last step.
    pub last_step_ms: f64,
    /// Runtime cuts applied since start (an `on_impact` object's first cut, fragments
    /// cut again).
    pub runtime_fractures: usize,
    /// Wall-clock milliseconds spent applying runtime cuts in the last step (or
    /// [`World::cut_now`](crate::World::cut_now)'s application): the new object, its
    /// bodies and colliders, and any wait for a cut's thread that has not finished. This
    /// is what the simulation's thread pays; the cut itself and its collision shapes are
    /// computed on a thread (native) before it.
    pub cut_apply_ms: f64,
    /// The deepest fracture level reached by a runtime cut (0: none yet).
    pub max_depth: u32,
    /// Intact bonds worn by hits below their break force (health under 1, damage).
    pub bonds_damaged: usize,
    /// The lowest health of an intact bond (1: none is worn; 0 would be broken).
    pub min_bond_health: f32,
}

/// Something noteworthy that happened during a step.
#[derive(Debug, Clone, PartialEq)]
pub enum SimEvent {
    /// A body's state became non-finite or its speed ran away; it was removed.
    Diverged {
        /// The object it belonged to (`None` for a projectile).
        object: Option<u32>,
        /// What was wrong.
        reason: String,
    },
    /// An object reached the end of its lifetime and was removed.
    Expired(u32),
    /// Bonds of an object broke during a step (one event per object and cause).
    BondsBroken {
        /// The object.
        object: u32,
        /// Why they broke.
        cause: BreakCause,
        /// How many.
        count: usize,
    },
    /// A body of an object split into parts when bonds broke: the fragments of each part,
    /// the part that kept the old body first (the others are new bodies).
    Split {
        /// The object.
        object: u32,
        /// Per part, its fragments (ascending).
        parts: Vec<Vec<u32>>,
    },
    /// A fragment was cut at runtime into a new object.
    Fractured {
        /// The object the fragment belonged to.
        object: u32,
        /// The fragment.
        fragment: u32,
        /// The new object holding the pieces.
        into: u32,
        /// How many pieces.
        fragments: usize,
        /// Their fracture level.
        level: u32,
    },
    /// A runtime cut failed; the fragment stays whole and is not cut again.
    FractureFailed {
        /// The object.
        object: u32,
        /// The fragment.
        fragment: u32,
        /// Why.
        reason: String,
    },
}

pub use crate::breaking::BreakCause;

/// Identifies a breakable object in a [`World`](crate::World).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct ObjectId(pub u32);

impl std::fmt::Display for ObjectId {
    /// The number alone, as the app's panels and the CLI's messages show it.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.0.fmt(f)
    }
}

/// Whether the simulation advances.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RunState {
    /// Built, not started (after construction, reset or clean).
    Stopped,
    /// Advancing on every [`World::step`](crate::World::step).
    Running,
    /// Started, held.
    Paused,
}
