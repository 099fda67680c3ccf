//! The conjugate-gradient iteration of [`StressSolver`] on one anchored island's load
//! cases, its preconditioning, and inertia relief for dynamic loads.

use glam::{DMat3, DVec3};

use super::hierarchies::Hierarchy;
use super::islands::{IslandState, Part};
use super::{Outcome, StressSolver};
use crate::stress::local::{Dof, LocalSprings, ZERO};
use crate::stress::multigrid::Work;
use crate::stress::multigrid::real::F32;
use crate::stress::spring::{invert, outer};

/// The solver's reusable vectors.
#[derive(Debug, Clone, Default)]
pub(super) struct Scratch {
    /// `K·p`, then the preconditioned residual.
    q: Vec<Dof>,
    /// The loads of the case being solved.
    f: Vec<Dof>,
    /// Gravity's loads, while the dynamic case is solved.
    g: Vec<Dof>,
    pre: PreWork,
}

/// The preconditioner's vectors: the multigrid's.
type PreWork = Work<F32>;

/// The preconditioner of one island.
struct Pre<'a> {
    multigrid: Option<&'a Hierarchy>,
    /// With a hierarchy built for more nodes: the island's rows in it.
    rows: Option<&'a [u32]>,
    jacobi: &'a [(DMat3, DMat3)],
}

impl StressSolver {
    /// Solves island `i`'s gravity case, then (once it has converged) the case of the
    /// dynamic `forces` (its free nodes'), with at most `cap` iterations and `units` starts
    /// and iterations in all; each case resumes its unfinished conjugate gradients or
    /// starts from its last solution. Stores the bond stresses once both have converged.
    pub(super) fn solve_island(
        &mut self,
        i: usize,
        forces: &[(u32, DVec3)],
        cap: usize,
        units: usize,
    ) -> Outcome {
        let mut island = std::mem::take(&mut self.islands[i]);
        let mut scratch = std::mem::take(&mut self.scratch);
        let n = island.free.len();
        let weight = 1.0 / (self.length_scale * self.length_scale);
        let tolerance = self.settings.tolerance;
        let mut outcome = Outcome {
            iterations: 0,
            units: 0,
            residual: 0.0,
            converged: false,
        };
        let IslandState {
            free,
            springs,
            gravity,
            dynamic,
            multigrid,
            rows,
            jacobi,
            load_scale,
            ..
        } = &mut island;
        // Both cases converge within the tolerance of all the island's loads.
        let loaded = !forces.is_empty();
        let total = match (loaded, *load_scale) {
            (false, _) => 0.0,
            (true, Some(t)) => t,
            (true, None) => {
                let t = self.total_loads(free, forces, &mut scratch, weight);
                *load_scale = Some(t);
                t
            }
        };
        let pre = Pre {
            multigrid: multigrid.and_then(|k| self.hierarchies.get(k)),
            rows: rows.as_deref(),
            jacobi,
        };
        if !loaded && gravity.converged && gravity.residual > tolerance * gravity.scale {
            // It converged within the tolerance of dynamic forces that are gone: gravity's
            // own is tighter.
            gravity.converged = false;
        }
        if !gravity.converged {
            if gravity.resume.is_none() {
                // A start: m·g at every free node.
                self.gravity_loads(free, &mut scratch.f);
                gravity.scale = norm(&scratch.f[..n], weight);
            }
            let scale = gravity.scale.max(total);
            let run = run(
                springs,
                &pre,
                gravity,
                tolerance * scale,
                (cap, units),
                &mut scratch,
                weight,
            );
            outcome.iterations += run.iterations;
            outcome.units += run.units;
            if run.units > 0 {
                outcome.residual = relative(run.residual, scale);
            }
        }
        if !gravity.converged {
            // Unfinished: the dynamic case waits.
        } else if !loaded {
            // Back at the gravity solution.
            dynamic.x.fill(ZERO);
            dynamic.converged = true;
            dynamic.resume = None;
        } else if !dynamic.converged {
            // Dynamic forces, balanced by the island's inertia (inertia relief): each free
            // node also takes `−m·a` for the island's mean acceleration `a = ΣF / Σm`, so
            // a short hit stresses the material around it rather than being carried to the
            // anchors.
            if dynamic.resume.is_none() {
                // A start: the loads in `scratch.f`.
                self.total_loads(free, forces, &mut scratch, weight);
            }
            let run = run(
                springs,
                &pre,
                dynamic,
                tolerance * total,
                (
                    cap - outcome.iterations.min(cap),
                    units - outcome.units.min(units),
                ),
                &mut scratch,
                weight,
            );
            outcome.iterations += run.iterations;
            outcome.units += run.units;
            if run.units > 0 {
                outcome.residual = outcome.residual.max(relative(run.residual, total));
            }
        }
        outcome.converged = gravity.converged && dynamic.converged;
        if outcome.converged {
            self.store_stresses(&island, loaded);
        }
        self.islands[i] = island;
        self.scratch = scratch;
        outcome
    }

    /// The dynamic `forces`, relieved (see [`StressSolver::relieve`]), into `scratch.f`
    /// (gravity's into `scratch.g`); returns the norm of their sum.
    fn total_loads(
        &self,
        free: &[u32],
        forces: &[(u32, DVec3)],
        scratch: &mut Scratch,
        weight: f64,
    ) -> f64 {
        let n = free.len();
        self.gravity_loads(free, &mut scratch.g);
        let f = &mut scratch.f;
        f.clear();
        f.resize(n + 1, ZERO);
        for &(v, force) in forces {
            f[self.local[v as usize] as usize].0 += force;
        }
        self.relieve(free, forces, f);
        scratch
            .g
            .iter()
            .zip(scratch.f.iter())
            .take(n)
            .map(|(a, b)| (a.0 + b.0).length_squared() + (a.1 + b.1).length_squared() * weight)
            .sum::<f64>()
            .sqrt()
    }

    /// The mass of free node `v` of an island, zero if it was dropped from it (see
    /// `detach.rs`): it carries no load.
    fn live_mass(&self, v: u32) -> f64 {
        if self.local[v as usize] == u32::MAX {
            0.0
        } else {
            self.mass[v as usize]
        }
    }

    /// Gravity's loads on the free nodes `free`: `m·g`, then the anchored slot.
    fn gravity_loads(&self, free: &[u32], f: &mut Vec<Dof>) {
        f.clear();
        f.extend(
            free.iter()
                .map(|&v| (self.live_mass(v) * self.gravity, DVec3::ZERO)),
        );
        f.push(ZERO);
    }

    /// The stresses of the island's bonds, from the sum of its two cases.
    fn store_stresses(&mut self, island: &IslandState, loaded: bool) {
        for (s, &b) in island.springs.springs.iter().zip(&island.bonds) {
            let (a, bb) = (s.a as usize, s.b as usize);
            let (mut f, mut m) = s.load(island.gravity.x[a], island.gravity.x[bb]);
            if loaded {
                let (fd, md) = s.load(island.dynamic.x[a], island.dynamic.x[bb]);
                f += fd;
                m += md;
            }
            self.stress[b as usize] = self.springs[b as usize].stress(f, m);
        }
    }

    /// Inertia relief: adds `−m·(a + α × (x − c))` to every free node's load in `f`, the
    /// d'Alembert forces of the island's rigid acceleration under the dynamic forces, so
    /// they have no net force or moment left for the anchors.
    fn relieve(&self, free: &[u32], dynamic: &[(u32, DVec3)], f: &mut [Dof]) {
        let mass: f64 = free.iter().map(|&v| self.live_mass(v)).sum();
        if mass <= 0.0 {
            return;
        }
        let c = free
            .iter()
            .map(|&v| self.live_mass(v) * self.centroid[v as usize])
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
            let m = self.live_mass(v);
            inertia += (DMat3::from_diagonal(DVec3::splat(r.length_squared())) - outer(r, r)) * m;
        }
        let a = force / mass;
        let alpha = invert(inertia) * torque;
        for (k, &v) in free.iter().enumerate() {
            let r = self.centroid[v as usize] - c;
            f[k].0 -= self.live_mass(v) * (a + alpha.cross(r));
        }
    }
}

/// What [`run`] did.
struct Run {
    iterations: usize,
    /// Its start (if it started) and iterations.
    units: usize,
    /// Absolute residual left.
    residual: f64,
}

/// Preconditioned conjugate gradients on `K·x = f` for one case of an island, to
/// `|f − K·x| ≤ target`, with at most `cap` iterations and `units` starts
/// and iterations: resumed when the case was stopped by a limit with the same loads, else
/// started from its last solution (`f` in `scratch.f`, read only then).
fn run(
    springs: &LocalSprings,
    pre: &Pre<'_>,
    part: &mut Part,
    target: f64,
    (cap, mut units): (usize, usize),
    scratch: &mut Scratch,
    weight: f64,
) -> Run {
    let n = springs.n;
    for v in [&mut part.r, &mut part.p, &mut scratch.q] {
        v.resize(n + 1, ZERO);
    }
    let started = part.resume.is_none();
    if started && units == 0 {
        return Run {
            iterations: 0,
            units: 0,
            residual: f64::INFINITY,
        };
    }
    units -= usize::from(started);
    let cap = cap.min(units);
    let (mut residual, mut rz) = match part.resume.take() {
        // r and p are where the last run left them.
        Some(rz) => (part.residual, rz),
        None => {
            // r = f − K·x.
            springs.times(&part.x, &mut scratch.q);
            for ((r, f), q) in part.r.iter_mut().zip(&scratch.f).zip(&scratch.q) {
                *r = (f.0 - q.0, f.1 - q.1);
            }
            part.r[n] = ZERO;
            let residual = norm(&part.r[..n], weight);
            let mut rz = 0.0;
            if residual > target {
                rz = precondition(pre, &part.r, &mut scratch.q, &mut scratch.pre);
                part.p.copy_from_slice(&scratch.q);
            }
            (residual, rz)
        }
    };
    let mut iterations = 0;
    let mut stopped = None;
    if residual > target {
        loop {
            if iterations >= cap {
                stopped = Some(rz);
                break;
            }
            iterations += 1;
            let pq = springs.times(&part.p, &mut scratch.q);
            if !(pq > 0.0 && pq.is_finite()) {
                break;
            }
            let alpha = rz / pq;
            let mut squared = 0.0;
            for ((x, r), (p, q)) in part
                .x
                .iter_mut()
                .zip(part.r.iter_mut())
                .zip(part.p.iter().zip(&scratch.q))
                .take(n)
            {
                x.0 += alpha * p.0;
                x.1 += alpha * p.1;
                r.0 -= alpha * q.0;
                r.1 -= alpha * q.1;
                squared += r.0.length_squared() + r.1.length_squared() * weight;
            }
            residual = squared.sqrt();
            if residual <= target {
                break;
            }
            // z = P·r, β = (r·z)/(r·z)_old, p = z + β·p.
            let rz_new = precondition(pre, &part.r, &mut scratch.q, &mut scratch.pre);
            let beta = rz_new / rz;
            rz = rz_new;
            for (p, z) in part.p.iter_mut().zip(&scratch.q).take(n) {
                p.0 = z.0 + beta * p.0;
                p.1 = z.1 + beta * p.1;
            }
        }
    }
    part.converged = residual <= target;
    part.resume = if part.converged { None } else { stopped };
    part.residual = residual;
    Run {
        iterations,
        units: iterations + usize::from(started),
        residual,
    }
}

/// `z = M⁻¹·r` on the island's free nodes (its multigrid, or block Jacobi); returns `r·z`
/// (summed as `z` is written).
fn precondition(pre: &Pre<'_>, r: &[Dof], z: &mut [Dof], work: &mut PreWork) -> f64 {
    match (pre.multigrid, pre.rows) {
        (Some(h), None) => h.multigrid.apply(r, z, work),
        // On the island's rows of the hierarchy: the residual there, zero on the rows it
        // lost (see `Hierarchy`).
        (Some(h), Some(rows)) => h.multigrid.apply_rows(rows, r, z, work),
        (None, _) => {
            let n = r.len() - 1;
            let mut rz = 0.0;
            for ((z, r), (pu, pt)) in z.iter_mut().zip(r).zip(pre.jacobi) {
                *z = (*pu * r.0, *pt * r.1);
                rz += r.0.dot(z.0) + r.1.dot(z.1);
            }
            z[n] = ZERO;
            rz
        }
    }
}

/// `|v|` with moments weighted by `weight` (one over the length scale squared).
fn norm(v: &[Dof], weight: f64) -> f64 {
    v.iter()
        .map(|(u, t)| u.length_squared() + t.length_squared() * weight)
        .sum::<f64>()
        .sqrt()
}

fn relative(residual: f64, scale: f64) -> f64 {
    if scale > 0.0 { residual / scale } else { 0.0 }
}
