//! The conjugate-gradient iteration of [`StressSolver`] on one anchored island, its
//! preconditioning, and inertia relief for dynamic loads.

use glam::{DMat3, DVec3};

use super::{IslandState, StressSolver};
use crate::stress::spring::{invert, outer};

impl StressSolver {
    /// Preconditioned conjugate gradients on island `i` under gravity and `forces` (its
    /// free nodes'), at most `cap` iterations, resumed from `resume` (`r·z` of the last,
    /// unfinished run with the same loads) or started from the last solution; stores the
    /// bond stresses.
    pub(super) fn solve_island(
        &mut self,
        i: usize,
        forces: &[(u32, DVec3)],
        cap: usize,
        resume: Option<f64>,
    ) -> Outcome {
        let island = std::mem::take(&mut self.islands[i]);
        let free = &island.free;
        for &v in free {
            self.fu[v as usize] = self.mass[v as usize] * self.gravity;
        }
        // Dynamic forces, balanced by the island's inertia (inertia relief): each free node
        // also takes `−m·a` for the island's mean acceleration `a = ΣF / Σm`, so a short
        // hit stresses the material around it rather than being carried to the anchors.
        for &(v, f) in forces {
            self.fu[v as usize] += f;
        }
        if !forces.is_empty() {
            self.relieve(free, forces);
        }
        let norm_f = free
            .iter()
            .map(|&v| self.fu[v as usize].length_squared())
            .sum::<f64>()
            .sqrt();
        let target = self.settings.tolerance * norm_f;
        let mut iterations = 0;
        let mut stopped = None;
        let (mut residual, mut rz) = match resume {
            // r and p are where the last run left them.
            Some(rz) => (self.norm_r(free), rz),
            None => {
                // r = f − K·x.
                self.apply(&island, Operand::X);
                for &v in free {
                    let v = v as usize;
                    self.ru[v] = self.fu[v] - self.qu[v];
                    self.rt[v] = -self.qt[v];
                }
                let residual = self.norm_r(free);
                let mut rz = 0.0;
                if residual > target {
                    rz = self.precondition(i as u32, &island);
                    for &v in free {
                        let v = v as usize;
                        self.pu[v] = self.qu[v];
                        self.pt[v] = self.qt[v];
                    }
                }
                (residual, rz)
            }
        };
        if residual > target {
            loop {
                if iterations >= cap {
                    stopped = Some(rz);
                    break;
                }
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
                let rz_new = self.precondition(i as u32, &island);
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
        Outcome {
            iterations,
            residual: relative,
            converged,
            resume: if converged { None } else { stopped },
        }
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

    /// `q = M⁻¹·r` on the island's free nodes (its multigrid's W-cycle, or block
    /// Jacobi); returns `r·q`.
    fn precondition(&mut self, id: u32, island: &IslandState) -> f64 {
        let free = &island.free;
        if let Some(h) = &island.multigrid {
            // On the hierarchy's nodes: the residual on this island's, zero on those it
            // lost (see `Hierarchy`).
            let here = |v: u32| self.node_island[v as usize] == id;
            let r: Vec<(DVec3, DVec3)> = h
                .nodes
                .iter()
                .map(|&v| {
                    if here(v) {
                        (self.ru[v as usize], self.rt[v as usize])
                    } else {
                        (DVec3::ZERO, DVec3::ZERO)
                    }
                })
                .collect();
            let z = h.multigrid.apply(&r);
            for (&v, z) in h.nodes.iter().zip(z) {
                if here(v) {
                    (self.qu[v as usize], self.qt[v as usize]) = z;
                }
            }
        } else {
            for &v in free {
                let v = v as usize;
                self.qu[v] = self.pre_u[v] * self.ru[v];
                self.qt[v] = self.pre_t[v] * self.rt[v];
            }
        }
        free.iter()
            .map(|&v| {
                let v = v as usize;
                self.qu[v].dot(self.ru[v]) + self.qt[v].dot(self.rt[v])
            })
            .sum()
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

/// What [`StressSolver::solve_island`] did.
pub(super) struct Outcome {
    pub iterations: usize,
    /// Relative residual.
    pub residual: f64,
    pub converged: bool,
    /// `r·z` to resume from when a limit stopped it.
    pub resume: Option<f64>,
}

#[derive(Clone, Copy)]
enum Operand {
    X,
    P,
}
