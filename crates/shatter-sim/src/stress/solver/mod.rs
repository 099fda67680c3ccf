//! The static stress solver: a rigid-body-spring network on the bond graph.
//!
//! Every node is a rigid block with a displacement `u` and a small rotation `θ`; every
//! intact bond is its shared face, modelled as springs at the face's centroid `c`: a
//! normal spring `E·A/L`, a shear spring `G·A/L` on the relative displacement of the two
//! blocks at `c`, `δ = (u_b + θ_b × r_b) − (u_a + θ_a × r_a)`, and bending / twisting
//! springs `E·I/L`, `G·J/L` (`I = A²/12`, `J = A²/6`, a square face) on `θ_b − θ_a`.
//! Anchored nodes do not move. Loads (gravity `m·g` at every node, plus this step's
//! dynamic forces) are balanced by the bond forces: `K·x = f`, solved per anchored island
//! with the conjugate-gradient method, preconditioned by a smoothed-aggregation multigrid
//! (see `stress/multigrid/`; a 3×3 block-Jacobi preconditioner is the alternative),
//! warm-started from the last solution. Gravity and the dynamic forces are solved as two
//! cases and added (`islands.rs`). This is the minimum-energy (weighted least-squares)
//! way the loads flow down to the anchors; force and moment balance hold at every node, so a
//! cantilever's root carries its weight as shear and its moment as tension on top and
//! compression below. The stiffness scale `E` cancels out of the stresses; only the
//! ratio `G/E` matters.
//!
//! Dynamic forces (a step's contacts and explosions) are balanced by the island's inertia
//! (inertia relief: every free node also takes `−m·ΣF/Σm`), so a hit stresses the
//! material around it, not the supports; gravity goes to the anchors.
//!
//! Islands without an anchor are not solved: they have no static load path and fall
//! freely. Settled islands (converged, loads and bonds unchanged) are skipped; so is
//! everything once a hit is gone (the island is back at its gravity solution).

use glam::DVec3;

use crate::stress::graph::BondGraph;
use crate::stress::limits::{BondStress, Failure, StressLimits};
use crate::stress::spring::Spring;

mod cg;
mod detach;
mod hierarchies;
mod islands;

use cg::Scratch;
use hierarchies::Hierarchies;
use islands::IslandState;

/// Nominal Young's modulus (Pa); it cancels out of the stresses.
const YOUNG: f64 = 1e10;

/// Solver settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolverSettings {
    /// Converged when `|f − K·x| ≤ tolerance · |f|`.
    pub tolerance: f64,
    /// Most conjugate-gradient iterations per island per [`StressSolver::solve`]; an island
    /// that needs more goes on from where it stopped at the next solve.
    pub max_iterations: usize,
    /// Most conjugate-gradient iterations per [`StressSolver::solve`], summed over the
    /// islands (`None`: no limit): time-slicing, as Blast's stress solver does, so a
    /// large graph costs a bounded time per step. An island left unfinished goes on at
    /// the next solve: its conjugate gradients resume where they stopped while its loads
    /// are unchanged, and a hit's forces stay on it until its solve has converged, so
    /// the hit is judged (a few steps late) rather than lost. Forces of the steps an
    /// unfinished solve spans are not summed: each node keeps the strongest, so a
    /// contact that presses every step loads its bonds once. No bond breaks on an
    /// unfinished solve.
    pub budget: Option<usize>,
    /// Most springs visited per [`StressSolver::solve`], summed over the islands (`None`:
    /// no limit): each conjugate-gradient iteration of an island, and each start of a run
    /// (its first residual and preconditioning), visits the island's springs once, and an
    /// iteration's time grows with them. So this, unlike `budget`, bounds a solve's time
    /// for objects of every size: at the World's default
    /// ([`DEFAULT_STRESS_SPRING_BUDGET`](crate::DEFAULT_STRESS_SPRING_BUDGET)) a
    /// 20,000-bond island advances one iteration per solve and a 1,000-bond one 24. An
    /// island that cannot afford its next start or iteration waits (and so do the islands
    /// after it), and the springs left are saved for it (up to that cost) and added to the
    /// next solve's: a 50,000-bond island iterates every third solve, so the springs
    /// visited per solve average to at most the budget however large the object (one
    /// solve visits at most the budget plus one unit). What is left goes on at the next
    /// solve, as with `budget`.
    pub spring_budget: Option<usize>,
    /// Most work per [`StressSolver::solve`] on multigrid hierarchies under construction,
    /// in block operations (a 6×6 block times a vector, 36 multiply-adds; `None`: an
    /// island builds its hierarchy at once, in the solve that needs it). With a budget,
    /// an island split from a larger one uses that island's hierarchy (restricted to its
    /// nodes) and an island with none to use block Jacobi, while its own is built a slice
    /// per solve; a slice stops at the end of the row of the build that reaches the
    /// budget. [`StressSolver::prepare`] always builds at once. At the World's default
    /// ([`DEFAULT_STRESS_BUILD_BUDGET`](crate::DEFAULT_STRESS_BUILD_BUDGET)) a
    /// 20,000-bond island's hierarchy takes about 50 solves.
    pub build_budget: Option<usize>,
    /// Shear over normal stiffness, `G/E`.
    pub shear_ratio: f64,
    /// How the conjugate gradients are preconditioned.
    pub preconditioner: Preconditioner,
}

/// The preconditioner of the stress solver's conjugate gradients.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Preconditioner {
    /// Rigid-group aggregation multigrid, one W-cycle (see `stress/multigrid.rs`): a few
    /// dozen iterations where block Jacobi needs thousands.
    #[default]
    Multigrid,
    /// The inverse of each node's 3×3 displacement and rotation blocks.
    BlockJacobi,
}

impl Preconditioner {
    /// Every preconditioner.
    pub const ALL: [Preconditioner; 2] = [Preconditioner::Multigrid, Preconditioner::BlockJacobi];

    /// Its name: `multigrid`, `block-jacobi`.
    pub fn name(self) -> &'static str {
        match self {
            Preconditioner::Multigrid => "multigrid",
            Preconditioner::BlockJacobi => "block-jacobi",
        }
    }
}

impl std::fmt::Display for Preconditioner {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for Preconditioner {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Preconditioner::ALL
            .into_iter()
            .find(|p| p.name() == s)
            .ok_or_else(|| {
                let names: Vec<&str> = Preconditioner::ALL.iter().map(|p| p.name()).collect();
                format!(
                    "unknown preconditioner `{s}`: expected one of {}",
                    names.join(", ")
                )
            })
    }
}

impl Default for SolverSettings {
    fn default() -> Self {
        SolverSettings {
            tolerance: 1e-5,
            max_iterations: 1000,
            budget: None,
            spring_budget: None,
            build_budget: None,
            shear_ratio: 0.4,
            preconditioner: Preconditioner::Multigrid,
        }
    }
}

/// What one [`StressSolver::solve`] did.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SolveReport {
    /// Anchored islands solved.
    pub islands_solved: usize,
    /// Anchored islands skipped because they were settled.
    pub islands_skipped: usize,
    /// Conjugate-gradient iterations, summed over the islands solved.
    pub iterations: usize,
    /// Whether every island solved converged.
    pub converged: bool,
    /// Largest relative residual of the islands solved.
    pub residual: f64,
    /// Anchored islands left for a later solve because the budget was spent.
    pub islands_deferred: usize,
    /// Multigrid hierarchies built or completed (after the bonds changed); an island
    /// that only lost bonds, or up to half its nodes, keeps its hierarchy.
    pub hierarchies_built: usize,
    /// Work done on hierarchies under construction, in block operations (see
    /// [`SolverSettings::build_budget`]).
    pub build_work: usize,
    /// Whether the islands were rebuilt from the bond mask, every bond read (an island
    /// split into parts that each have an anchor, or into large ones); bonds that break
    /// with a detour between their ends, or cut off small pieces without an anchor, are
    /// taken off in place.
    pub rebuilt: bool,
    /// Springs visited by starts and iterations (see [`SolverSettings::spring_budget`]).
    pub springs: usize,
}

/// The stress solver of one bond graph; keeps its solution between solves.
///
/// ```
/// use glam::DVec3;
/// use shatter_sim::stress::{BondGraph, GraphBond, Node, SolverSettings, StressSolver};
///
/// // A block hanging under an anchored one: the bond carries its weight in tension.
/// let graph = BondGraph::new(
///     vec![
///         Node { mass: 0.0, centroid: DVec3::new(0.0, 1.0, 0.0) },
///         Node { mass: 10.0, centroid: DVec3::ZERO },
///     ],
///     vec![GraphBond {
///         a: 0,
///         b: 1,
///         area: 0.01,
///         centroid: DVec3::new(0.0, 0.5, 0.0),
///         normal: DVec3::NEG_Y,
///     }],
///     vec![true, false],
/// )?;
/// let mut solver = StressSolver::new(&graph, SolverSettings::default());
/// let report = solver.solve(&graph, &[false], DVec3::new(0.0, -10.0, 0.0), &[]);
/// assert!(report.converged);
/// let s = solver.stress(0);
/// assert!((s.tension - 100.0 / 0.01).abs() < 1e-3 * s.tension);
/// assert!(s.compression == 0.0 && s.shear < 1e-6 * s.tension);
/// # Ok::<(), shatter_sim::SimError>(())
/// ```
#[derive(Debug, Clone)]
pub struct StressSolver {
    settings: SolverSettings,
    springs: Vec<Spring>,
    mass: Vec<f64>,
    centroid: Vec<DVec3>,
    anchored: Vec<bool>,
    /// The bond mask the islands were built from (`None`: not built yet).
    topology: Option<Vec<bool>>,
    islands: Vec<IslandState>,
    /// Per node, its anchored island (`u32::MAX`: none).
    node_island: Vec<u32>,
    /// Per node, its index among its island's free nodes (`u32::MAX`: anchored or none).
    local: Vec<u32>,
    gravity: DVec3,
    /// Mean bond length: torque residuals are divided by it to compare with forces.
    length_scale: f64,
    /// The multigrid hierarchies the islands use.
    hierarchies: Hierarchies,
    /// Rebuilds of the islands so far.
    rebuilds: u64,
    /// Springs of the spring budget saved by solves that could not afford an island's
    /// next start or iteration (see [`SolverSettings::spring_budget`]).
    credit: usize,
    scratch: Scratch,
    /// Per node, the search that last reached it (see `islands.rs`, `detour`).
    seen: Vec<u32>,
    stamp: u32,
    stress: Vec<BondStress>,
    /// Islands solved by the last solve.
    last_solved: Vec<u32>,
}

/// What [`StressSolver::solve_island`] did.
pub(super) struct Outcome {
    pub iterations: usize,
    /// Starts and iterations.
    pub units: usize,
    /// Relative residual.
    pub residual: f64,
    pub converged: bool,
}

impl StressSolver {
    /// A solver for `graph` (its geometry is read once; pass the same graph to
    /// [`StressSolver::solve`]).
    pub fn new(graph: &BondGraph, settings: SolverSettings) -> StressSolver {
        let nodes = graph.nodes();
        let springs = springs(graph, &settings);
        let n = nodes.len();
        let lengths: f64 = graph
            .bonds()
            .iter()
            .map(|b| (nodes[b.b as usize].centroid - nodes[b.a as usize].centroid).length())
            .sum();
        let length_scale = if graph.bonds().is_empty() {
            1.0
        } else {
            (lengths / graph.bonds().len() as f64).max(1e-9)
        };
        StressSolver {
            settings,
            springs,
            mass: nodes.iter().map(|node| node.mass).collect(),
            centroid: nodes.iter().map(|node| node.centroid).collect(),
            anchored: graph.anchored().to_vec(),
            topology: None,
            islands: Vec::new(),
            node_island: vec![u32::MAX; n],
            local: vec![u32::MAX; n],
            gravity: DVec3::ZERO,
            length_scale,
            hierarchies: Hierarchies::default(),
            rebuilds: 0,
            credit: 0,
            scratch: Scratch::default(),
            seen: vec![0; n],
            stamp: 0,
            stress: vec![BondStress::default(); graph.bonds().len()],
            last_solved: Vec::new(),
        }
    }

    /// The settings.
    pub fn settings(&self) -> &SolverSettings {
        &self.settings
    }

    /// Builds the anchored islands of the intact bonds (`broken[b]`: bond `b` is gone) and
    /// their preconditioners, which the first [`StressSolver::solve`] with this mask would
    /// otherwise build: an object's creation can pay for it once, so that no step does.
    /// Returns the multigrid hierarchies built.
    pub fn prepare(&mut self, graph: &BondGraph, broken: &[bool]) -> usize {
        if self.topology.as_deref() == Some(broken) {
            return 0;
        }
        self.update_topology(graph, broken, true)
    }

    /// Solves the anchored islands of the intact bonds (`broken[b]`: bond `b` is gone)
    /// under `gravity` (in the graph's frame) plus `forces` (node, force) for this solve
    /// only. Islands whose bonds, gravity and forces did not change since they converged
    /// are skipped.
    pub fn solve(
        &mut self,
        graph: &BondGraph,
        broken: &[bool],
        gravity: DVec3,
        forces: &[(u32, DVec3)],
    ) -> SolveReport {
        let changed = self
            .topology
            .as_deref()
            .is_none_or(|t| t.len() != broken.len() || t != broken);
        let rebuilds = self.rebuilds;
        let mut built = if changed {
            self.update_topology(graph, broken, false)
        } else {
            0
        };
        // Hierarchies under construction go on (and are used from this solve if done).
        let (build_work, completed) =
            self.advance_builds(self.settings.build_budget.unwrap_or(usize::MAX));
        built += completed;
        if gravity != self.gravity {
            self.gravity = gravity;
            self.islands.iter_mut().for_each(|i| {
                i.settled = false;
                i.gravity.converged = false;
                i.gravity.resume = None;
                i.load_scale = None;
            });
        }
        // This solve's forces, per island.
        let mut by_island: Vec<Vec<(u32, DVec3)>> = vec![Vec::new(); self.islands.len()];
        for &(node, f) in forces {
            if let Some(&i) = self.node_island.get(node as usize)
                && i != u32::MAX
                && !self.anchored[node as usize]
            {
                by_island[i as usize].push((node, f));
            }
        }
        let mut report = SolveReport {
            converged: true,
            hierarchies_built: built,
            build_work,
            rebuilt: self.rebuilds != rebuilds,
            ..SolveReport::default()
        };
        let mut budget = self.settings.budget.unwrap_or(usize::MAX);
        // The springs of this solve, and those saved by the solves before it that could not
        // afford an iteration.
        let mut springs_left = self
            .settings
            .spring_budget
            .map_or(usize::MAX, |b| b.saturating_add(self.credit));
        // The next unit of the first island that could not afford one.
        let mut owed = 0;
        self.last_solved.clear();
        for (i, fresh) in by_island.into_iter().enumerate() {
            let island = &mut self.islands[i];
            if island.settled && !island.had_forces && fresh.is_empty() && island.carry.is_empty() {
                report.islands_skipped += 1;
                continue;
            }
            // The loads of this solve: those of an unfinished solve, each node's replaced
            // by this step's if stronger (never summed: a contact that presses every step
            // is one force, not one more each step).
            if merge_strongest(&mut island.carry, fresh) {
                island.dynamic.converged = false;
                island.dynamic.resume = None;
                island.load_scale = None;
            }
            // Starts and iterations this island may have: what is left of the springs.
            let bonds = island.cost(&self.hierarchies);
            // Once an island waits for springs, the islands after it wait too, so that the
            // springs saved are its.
            let units = match springs_left {
                usize::MAX => usize::MAX,
                _ if owed > 0 => 0,
                left => left / bonds,
            };
            if units == 0 && owed == 0 {
                owed = bonds;
            }
            if budget == 0 || units == 0 {
                // Not solved this time: still owed, with its loads kept for it.
                island.settled = false;
                report.islands_deferred += 1;
                report.converged = false;
                continue;
            }
            let loads = std::mem::take(&mut island.carry);
            let cap = self.settings.max_iterations.min(budget);
            let outcome = self.solve_island(i, &loads, cap, units);
            budget = budget.saturating_sub(outcome.iterations);
            let visited = outcome.units.saturating_mul(bonds);
            springs_left = springs_left.saturating_sub(visited);
            report.springs += visited;
            let island = &mut self.islands[i];
            island.had_forces = !loads.is_empty();
            island.converged = outcome.converged;
            if !outcome.converged {
                island.carry = loads;
            }
            island.settled = outcome.converged && !island.had_forces;
            report.islands_solved += 1;
            report.iterations += outcome.iterations;
            report.residual = report.residual.max(outcome.residual);
            report.converged &= outcome.converged;
            self.last_solved.push(i as u32);
        }
        // An island that could not afford a unit has the springs left saved for it, up to
        // what the unit costs.
        self.credit = if self.settings.spring_budget.is_some() {
            springs_left.min(owed)
        } else {
            0
        };
        report
    }

    /// The stresses of bond `b` at the last solve of its island that converged (zero for
    /// broken bonds, bonds of islands without an anchor, and before the first converged
    /// solve since the bonds changed).
    pub fn stress(&self, b: u32) -> BondStress {
        self.stress.get(b as usize).copied().unwrap_or_default()
    }

    /// The force (on `b`'s side, from `a` to `b` positive = pulling `b` back, i.e. the
    /// bond's normal component is its tension) and the moment that bond `b` carries in
    /// the current solution, in the graph's frame. Zero for broken bonds and bonds of
    /// islands without an anchor.
    pub fn bond_load(&self, b: u32) -> (DVec3, DVec3) {
        let none = (DVec3::ZERO, DVec3::ZERO);
        let Some(s) = self.springs.get(b as usize) else {
            return none;
        };
        let intact = self
            .topology
            .as_ref()
            .is_some_and(|t| !t.get(b as usize).copied().unwrap_or(false));
        let Some(island) = self
            .node_island
            .get(s.a as usize)
            .and_then(|&i| self.islands.get(i as usize))
            .filter(|_| intact)
        else {
            return none;
        };
        let Ok(k) = island.bonds.binary_search(&b) else {
            return none;
        };
        let spring = &island.springs.springs[k];
        let (a, bb) = (spring.a as usize, spring.b as usize);
        let (f, m) = spring.load(island.gravity.x[a], island.gravity.x[bb]);
        let (fd, md) = spring.load(island.dynamic.x[a], island.dynamic.x[bb]);
        (f + fd, m + md)
    }

    /// Whether node `f` belongs to an anchored island (one that carries static load).
    pub fn is_supported(&self, f: u32) -> bool {
        self.node_island
            .get(f as usize)
            .is_some_and(|&i| i != u32::MAX)
    }

    /// Bonds over `limits` in the islands the last solve solved and converged, with the
    /// limit each passed, ascending. (Islands that did not converge yet are left for a
    /// later solve, so no bond breaks on an unfinished solution.)
    pub fn overloaded(&self, limits: &StressLimits) -> Vec<(u32, Failure)> {
        let mut out = Vec::new();
        for &i in &self.last_solved {
            let island = &self.islands[i as usize];
            if !island.converged {
                continue;
            }
            for &b in &island.bonds {
                if let Some(f) = limits.failure(&self.stress[b as usize]) {
                    out.push((b, f));
                }
            }
        }
        out.sort_unstable_by_key(|(b, _)| *b);
        out
    }
}

/// The springs of `graph`'s bonds (see the module's doc).
pub(super) fn springs(graph: &BondGraph, settings: &SolverSettings) -> Vec<Spring> {
    let nodes = graph.nodes();
    graph
        .bonds()
        .iter()
        .map(|bond| {
            let (xa, xb) = (
                nodes[bond.a as usize].centroid,
                nodes[bond.b as usize].centroid,
            );
            let mut n = bond.normal.normalize_or(xb - xa).normalize_or(DVec3::Y);
            if n.dot(xb - xa) < 0.0 {
                n = -n;
            }
            let length = (xb - xa).length().max(1e-9);
            let area = bond.area.max(1e-6 * length * length);
            let e = YOUNG / length;
            let g = e * settings.shear_ratio;
            Spring {
                a: bond.a,
                b: bond.b,
                ra: bond.centroid - xa,
                rb: bond.centroid - xb,
                n,
                kn: e * area,
                ks: g * area,
                kb: e * area * area / 12.0,
                kt: g * area * area / 6.0,
                area,
            }
        })
        .collect()
}

/// Merges this step's forces `fresh` (summed per node: several contacts of one step
/// add up) into `carry`, the per-node loads of an unfinished solve (sorted by node):
/// each node keeps the stronger of its carried and its fresh force. Returns whether
/// `carry` changed.
pub(super) fn merge_strongest(carry: &mut Vec<(u32, DVec3)>, mut fresh: Vec<(u32, DVec3)>) -> bool {
    if fresh.is_empty() {
        return false;
    }
    fresh.sort_unstable_by_key(|(node, _)| *node);
    let mut summed: Vec<(u32, DVec3)> = Vec::with_capacity(fresh.len());
    for (node, f) in fresh {
        match summed.last_mut() {
            Some((last, sum)) if *last == node => *sum += f,
            _ => summed.push((node, f)),
        }
    }
    let mut changed = false;
    for (node, f) in summed {
        match carry.binary_search_by_key(&node, |(n, _)| *n) {
            Ok(k) => {
                if f != carry[k].1 && f.length_squared() >= carry[k].1.length_squared() {
                    carry[k].1 = f;
                    changed = true;
                }
            }
            Err(k) => {
                carry.insert(k, (node, f));
                changed = true;
            }
        }
    }
    changed
}
