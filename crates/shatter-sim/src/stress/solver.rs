//! The static stress solver: a rigid-body-spring network on the bond graph.
//!
//! Every node is a rigid block with a displacement `u` and a small rotation `θ`; every
//! intact bond is its shared face, modelled as springs at the face's centroid `c`: a
//! normal spring `E·A/L`, a shear spring `G·A/L` on the relative displacement of the two
//! blocks at `c`, `δ = (u_b + θ_b × r_b) − (u_a + θ_a × r_a)`, and bending / twisting
//! springs `E·I/L`, `G·J/L` (`I = A²/12`, `J = A²/6`, a square face) on `θ_b − θ_a`.
//! Anchored nodes do not move. Loads (gravity `m·g` at every node, plus this step's
//! dynamic forces) are balanced by the bond forces: `K·x = f`, solved per anchored island
//! with the conjugate-gradient method and a 3×3 block-Jacobi preconditioner, warm-started
//! from the last solution. This is the minimum-energy (weighted least-squares) way the
//! loads flow down to the anchors; force and moment balance hold at every node, so a
//! cantilever's root carries its weight as shear and its moment as tension on top and
//! compression below. The stiffness scale `E` cancels out of the stresses; only the
//! ratio `G/E` matters.
//!
//! Dynamic forces (a step's contacts and explosions) are balanced by the island's inertia
//! (inertia relief: every free node also takes `−m·ΣF/Σm`), so a hit stresses the
//! material around it, not the supports; gravity goes to the anchors.
//!
//! Islands without an anchor are not solved: they have no static load path and fall
//! freely. Settled islands (converged, loads and bonds unchanged) are skipped.

use glam::{DMat3, DVec3};

use crate::stress::graph::BondGraph;
use crate::stress::limits::{BondStress, Failure, StressLimits};
use crate::stress::spring::{Spring, invert, outer, skew};

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
    /// Shear over normal stiffness, `G/E`.
    pub shear_ratio: f64,
}

impl Default for SolverSettings {
    fn default() -> Self {
        SolverSettings {
            tolerance: 1e-5,
            max_iterations: 1000,
            shear_ratio: 0.4,
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
}

/// An anchored island being solved.
#[derive(Debug, Clone, Default)]
struct IslandState {
    /// Its free (not anchored) nodes.
    free: Vec<u32>,
    /// Its intact bonds.
    bonds: Vec<u32>,
    /// Converged with the loads it has; nothing to do until they change.
    settled: bool,
    /// Took dynamic forces at its last solve (so it must be solved again without them).
    dynamic: bool,
    /// Converged at its last solve.
    converged: bool,
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
    gravity: DVec3,
    /// Mean bond length: torque residuals are divided by it to compare with forces.
    length_scale: f64,
    xu: Vec<DVec3>,
    xt: Vec<DVec3>,
    ru: Vec<DVec3>,
    rt: Vec<DVec3>,
    pu: Vec<DVec3>,
    pt: Vec<DVec3>,
    qu: Vec<DVec3>,
    qt: Vec<DVec3>,
    fu: Vec<DVec3>,
    pre_u: Vec<DMat3>,
    pre_t: Vec<DMat3>,
    stress: Vec<BondStress>,
    /// Islands solved by the last solve.
    last_solved: Vec<u32>,
}

impl StressSolver {
    /// A solver for `graph` (its geometry is read once; pass the same graph to
    /// [`StressSolver::solve`]).
    pub fn new(graph: &BondGraph, settings: SolverSettings) -> StressSolver {
        let nodes = graph.nodes();
        let springs = graph
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
            .collect();
        let n = nodes.len();
        let zeros = vec![DVec3::ZERO; n];
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
            gravity: DVec3::ZERO,
            length_scale,
            xu: zeros.clone(),
            xt: zeros.clone(),
            ru: zeros.clone(),
            rt: zeros.clone(),
            pu: zeros.clone(),
            pt: zeros.clone(),
            qu: zeros.clone(),
            qt: zeros.clone(),
            fu: zeros,
            pre_u: vec![DMat3::IDENTITY; n],
            pre_t: vec![DMat3::IDENTITY; n],
            stress: vec![BondStress::default(); graph.bonds().len()],
            last_solved: Vec::new(),
        }
    }

    /// The settings.
    pub fn settings(&self) -> &SolverSettings {
        &self.settings
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
        if changed {
            self.rebuild(graph, broken);
        }
        if gravity != self.gravity {
            self.gravity = gravity;
            self.islands.iter_mut().for_each(|i| i.settled = false);
        }
        let mut loaded = vec![false; self.islands.len()];
        for &(node, _) in forces {
            if let Some(&i) = self.node_island.get(node as usize)
                && i != u32::MAX
            {
                loaded[i as usize] = true;
            }
        }
        let mut report = SolveReport {
            converged: true,
            ..SolveReport::default()
        };
        self.last_solved.clear();
        for (i, &loaded) in loaded.iter().enumerate() {
            let island = &self.islands[i];
            if island.settled && !island.dynamic && !loaded {
                report.islands_skipped += 1;
                continue;
            }
            let (iterations, residual, converged) = self.solve_island(i, forces);
            let island = &mut self.islands[i];
            island.dynamic = loaded;
            island.converged = converged;
            island.settled = converged && !loaded;
            report.islands_solved += 1;
            report.iterations += iterations;
            report.residual = report.residual.max(residual);
            report.converged &= converged;
            self.last_solved.push(i as u32);
        }
        report
    }

    /// The stresses of bond `b` at the last solve (zero for broken bonds and bonds of
    /// islands without an anchor).
    pub fn stress(&self, b: u32) -> BondStress {
        self.stress.get(b as usize).copied().unwrap_or_default()
    }

    /// The force (on `b`'s side, from `a` to `b` positive = pulling `b` back, i.e. the
    /// bond's normal component is its tension) and the moment that bond `b` carries at the
    /// last solve, in the graph's frame. Zero for bonds of islands without an anchor.
    pub fn bond_load(&self, b: u32) -> (DVec3, DVec3) {
        match self.springs.get(b as usize) {
            Some(s)
                if self.is_supported(s.a)
                    && self
                        .topology
                        .as_ref()
                        .is_some_and(|t| !t.get(b as usize).copied().unwrap_or(false)) =>
            {
                s.load(&self.xu, &self.xt)
            }
            _ => (DVec3::ZERO, DVec3::ZERO),
        }
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

    /// Rebuilds the anchored islands and their preconditioner from the bond mask; the
    /// last solution stays as the warm start.
    fn rebuild(&mut self, graph: &BondGraph, broken: &[bool]) {
        self.islands.clear();
        self.node_island.iter_mut().for_each(|i| *i = u32::MAX);
        self.stress
            .iter_mut()
            .for_each(|s| *s = BondStress::default());
        let mut block_u = vec![DMat3::ZERO; self.mass.len()];
        let mut block_t = vec![DMat3::ZERO; self.mass.len()];
        for island in graph.islands(broken) {
            if !island.anchored {
                for &v in &island.nodes {
                    self.xu[v as usize] = DVec3::ZERO;
                    self.xt[v as usize] = DVec3::ZERO;
                }
                continue;
            }
            let id = self.islands.len() as u32;
            let mut free = Vec::new();
            for &v in &island.nodes {
                self.node_island[v as usize] = id;
                if self.anchored[v as usize] {
                    self.xu[v as usize] = DVec3::ZERO;
                    self.xt[v as usize] = DVec3::ZERO;
                } else {
                    free.push(v);
                }
            }
            for &b in &island.bonds {
                let s = &self.springs[b as usize];
                let nn = outer(s.n, s.n);
                let k = DMat3::from_diagonal(DVec3::splat(s.ks)) + nn * (s.kn - s.ks);
                let kr = DMat3::from_diagonal(DVec3::splat(s.kb)) + nn * (s.kt - s.kb);
                for (v, r) in [(s.a, s.ra), (s.b, s.rb)] {
                    let rx = skew(r);
                    block_u[v as usize] += k;
                    block_t[v as usize] += rx.transpose() * k * rx + kr;
                }
            }
            for &v in &free {
                self.pre_u[v as usize] = invert(block_u[v as usize]);
                self.pre_t[v as usize] = invert(block_t[v as usize]);
            }
            self.islands.push(IslandState {
                free,
                bonds: island.bonds,
                ..IslandState::default()
            });
        }
        self.topology = Some(broken.to_vec());
    }

    /// Preconditioned conjugate gradients on island `i`; returns (iterations, relative
    /// residual, converged) and stores the bond stresses.
    fn solve_island(&mut self, i: usize, forces: &[(u32, DVec3)]) -> (usize, f64, bool) {
        let island = std::mem::take(&mut self.islands[i]);
        let free = &island.free;
        for &v in free {
            self.fu[v as usize] = self.mass[v as usize] * self.gravity;
        }
        // Dynamic forces, balanced by the island's inertia (inertia relief): each free node
        // also takes `−m·a` for the island's mean acceleration `a = ΣF / Σm`, so a short
        // hit stresses the material around it rather than being carried to the anchors.
        let mut dynamic = Vec::new();
        for &(v, f) in forces {
            if self.node_island.get(v as usize) == Some(&(i as u32)) && !self.anchored[v as usize] {
                self.fu[v as usize] += f;
                dynamic.push((v, f));
            }
        }
        if !dynamic.is_empty() {
            self.relieve(free, &dynamic);
        }
        let norm_f = free
            .iter()
            .map(|&v| self.fu[v as usize].length_squared())
            .sum::<f64>()
            .sqrt();
        // r = f − K·x.
        self.apply(&island, Operand::X);
        for &v in free {
            let v = v as usize;
            self.ru[v] = self.fu[v] - self.qu[v];
            self.rt[v] = -self.qt[v];
        }
        let target = self.settings.tolerance * norm_f;
        let mut residual = self.norm_r(free);
        let mut iterations = 0;
        if residual > target {
            let mut rz = self.precondition_into_p(free);
            while iterations < self.settings.max_iterations {
                iterations += 1;
                self.apply(&island, Operand::P);
                let pq: f64 = free
                    .iter()
                    .map(|&v| {
                        let v = v as usize;
                        self.pu[v].dot(self.qu[v]) + self.pt[v].dot(self.qt[v])
                    })
                    .sum();
                if !(pq > 0.0 && pq.is_finite()) {
                    break;
                }
                let alpha = rz / pq;
                for &v in free {
                    let v = v as usize;
                    self.xu[v] += alpha * self.pu[v];
                    self.xt[v] += alpha * self.pt[v];
                    self.ru[v] -= alpha * self.qu[v];
                    self.rt[v] -= alpha * self.qt[v];
                }
                residual = self.norm_r(free);
                if residual <= target {
                    break;
                }
                // z = P·r, β = (r·z)/(r·z)_old, p = z + β·p.
                let mut rz_new = 0.0;
                for &v in free {
                    let v = v as usize;
                    let zu = self.pre_u[v] * self.ru[v];
                    let zt = self.pre_t[v] * self.rt[v];
                    rz_new += zu.dot(self.ru[v]) + zt.dot(self.rt[v]);
                    self.qu[v] = zu;
                    self.qt[v] = zt;
                }
                let beta = rz_new / rz;
                rz = rz_new;
                for &v in free {
                    let v = v as usize;
                    self.pu[v] = self.qu[v] + beta * self.pu[v];
                    self.pt[v] = self.qt[v] + beta * self.pt[v];
                }
            }
        }
        for &b in &island.bonds {
            let s = &self.springs[b as usize];
            let (f, m) = s.load(&self.xu, &self.xt);
            self.stress[b as usize] = s.stress(f, m);
        }
        let relative = if norm_f > 0.0 { residual / norm_f } else { 0.0 };
        let converged = residual <= target;
        self.islands[i] = island;
        (iterations, relative, converged)
    }

    /// Inertia relief: adds `−m·(a + α × (x − c))` to every free node, the d'Alembert
    /// forces of the island's rigid acceleration under the dynamic forces, so they have
    /// no net force or moment left for the anchors.
    fn relieve(&mut self, free: &[u32], dynamic: &[(u32, DVec3)]) {
        let mass: f64 = free.iter().map(|&v| self.mass[v as usize]).sum();
        if mass <= 0.0 {
            return;
        }
        let c = free
            .iter()
            .map(|&v| self.mass[v as usize] * self.centroid[v as usize])
            .sum::<DVec3>()
            / mass;
        let (mut force, mut torque) = (DVec3::ZERO, DVec3::ZERO);
        for &(v, f) in dynamic {
            force += f;
            torque += (self.centroid[v as usize] - c).cross(f);
        }
        // Point-mass inertia about c: Σ m (|r|² I − r rᵀ).
        let mut inertia = DMat3::ZERO;
        for &v in free {
            let r = self.centroid[v as usize] - c;
            let m = self.mass[v as usize];
            inertia += (DMat3::from_diagonal(DVec3::splat(r.length_squared())) - outer(r, r)) * m;
        }
        let a = force / mass;
        let alpha = invert(inertia) * torque;
        for &v in free {
            let r = self.centroid[v as usize] - c;
            self.fu[v as usize] -= self.mass[v as usize] * (a + alpha.cross(r));
        }
    }

    /// `p = P·r` on the free nodes; returns `r·p`.
    fn precondition_into_p(&mut self, free: &[u32]) -> f64 {
        let mut rz = 0.0;
        for &v in free {
            let v = v as usize;
            self.pu[v] = self.pre_u[v] * self.ru[v];
            self.pt[v] = self.pre_t[v] * self.rt[v];
            rz += self.pu[v].dot(self.ru[v]) + self.pt[v].dot(self.rt[v]);
        }
        rz
    }

    /// `|r|` with torques divided by the length scale.
    fn norm_r(&self, free: &[u32]) -> f64 {
        let w = 1.0 / (self.length_scale * self.length_scale);
        free.iter()
            .map(|&v| {
                let v = v as usize;
                self.ru[v].length_squared() + self.rt[v].length_squared() * w
            })
            .sum::<f64>()
            .sqrt()
    }

    /// `q = K·(x or p)` over the island (anchored entries of the operand are zero).
    fn apply(&mut self, island: &IslandState, operand: Operand) {
        for &b in &island.bonds {
            let s = &self.springs[b as usize];
            self.qu[s.a as usize] = DVec3::ZERO;
            self.qt[s.a as usize] = DVec3::ZERO;
            self.qu[s.b as usize] = DVec3::ZERO;
            self.qt[s.b as usize] = DVec3::ZERO;
        }
        for &v in &island.free {
            self.qu[v as usize] = DVec3::ZERO;
            self.qt[v as usize] = DVec3::ZERO;
        }
        let (u, t) = match operand {
            Operand::X => (&self.xu, &self.xt),
            Operand::P => (&self.pu, &self.pt),
        };
        for &b in &island.bonds {
            let s = &self.springs[b as usize];
            let (f, m) = s.load(u, t);
            let (a, bb) = (s.a as usize, s.b as usize);
            self.qu[bb] += f;
            self.qt[bb] += s.rb.cross(f) + m;
            self.qu[a] -= f;
            self.qt[a] -= s.ra.cross(f) + m;
        }
    }
}

#[derive(Clone, Copy)]
enum Operand {
    X,
    P,
}
