//! The stress pass of a step (clusters model, objects with anchored fragments): gravity
//! and the step's contact and explosion forces carried through the intact bonds down to
//! the anchors by [`crate::stress::StressSolver`]; bonds over the material's limits break
//! and the bodies they held split (parts no anchor holds become dynamic and fall).

use std::collections::{BTreeMap, BTreeSet};

use glam::{DQuat, DVec3, Vec3};
use rapier3d::prelude::*;
use web_time::Instant;

use crate::bonds::tags::{Kind, untag};
use crate::object::ExplosionSpec;
use crate::world::settings::BreakCause;
use crate::world::settings::SimEvent;
use crate::world::state::World;
use crate::world::step::{ContactHit, split_bodies};

impl World {
    /// Solves the stresses of every anchored cluster object and breaks overloaded bonds.
    pub(crate) fn break_by_stress(&mut self, hits: &[ContactHit]) {
        if !self.settings.stress {
            return;
        }
        let t0 = Instant::now();
        let dt = self.settings.dt;
        // Contact forces on fragments of fixed bodies, per object, in the world frame.
        let mut contacts: BTreeMap<u32, Vec<(u32, Vec3)>> = BTreeMap::new();
        for hit in hits {
            for (collider, sign) in [(hit.collider1, -1.0), (hit.collider2, 1.0)] {
                let Some(co) = self.physics.colliders.get(collider) else {
                    continue;
                };
                let Some((Kind::Fragment, object, f)) = untag(co.user_data) else {
                    continue;
                };
                let fixed = co
                    .parent()
                    .and_then(|b| self.physics.bodies.get(b))
                    .is_some_and(|rb| rb.is_fixed());
                if fixed {
                    contacts
                        .entry(object)
                        .or_default()
                        .push((f, hit.impulse * sign / dt));
                }
            }
        }
        let gravity = self.settings.gravity.as_dvec3();
        let (mut iterations, mut solves) = (0, 0);
        let mut solve_ms = 0.0;
        let clock = self.cpu_clock;
        let mut solve_cpu_ns = clock.map(|_| 0u64);
        for (id, record) in self.objects.iter_mut() {
            let Some(live) = record.live.as_mut() else {
                continue;
            };
            let version = live.bonds.version;
            let Some(state) = live.stress.as_mut() else {
                continue;
            };
            let to_local = record.spec.rotation.as_dquat().inverse();
            if state.mask_version != version {
                for (b, bond) in live.prepared.fracture.bonds.iter().enumerate() {
                    state.mask[b] = live.bonds.broken[b]
                        || live.body[bond.a as usize].is_none()
                        || live.body[bond.b as usize].is_none();
                }
                state.mask_version = version;
            }
            let mut forces = std::mem::take(&mut state.pending);
            let impulses = std::mem::take(&mut state.pending_impulses);
            if let Some(list) = contacts.get(&id.0) {
                forces.extend(list.iter().map(|(f, v)| (*f, to_local * v.as_dvec3())));
            }
            let t1 = Instant::now();
            let c1 = clock.and_then(|c| c());
            let report = state
                .solver
                .solve(&state.graph, &state.mask, to_local * gravity, &forces);
            solve_ms += t1.elapsed().as_secs_f64() * 1e3;
            if let (Some(total), Some(c1), Some(c2)) =
                (&mut solve_cpu_ns, c1, clock.and_then(|c| c()))
            {
                *total += c2.saturating_sub(c1);
            }
            iterations += report.iterations;
            solves += report.islands_solved;
            let over = state.solver.overloaded(&state.limits);
            if over.is_empty() {
                continue;
            }
            let mut bodies = BTreeSet::new();
            for (b, _) in over {
                if live.mark_broken_by(b as usize, BreakCause::Stress) {
                    let a = live.prepared.fracture.bonds[b as usize].a;
                    if let Some(body) = live.body[a as usize] {
                        bodies.insert(body.into_raw_parts());
                    }
                }
            }
            let bodies = bodies
                .into_iter()
                .map(|(i, g)| RigidBodyHandle::from_raw_parts(i, g))
                .collect();
            let splits = split_bodies(
                &mut self.physics,
                &mut self.debris,
                live,
                id.0,
                bodies,
                &impulses,
                &self.settings,
            );
            for parts in splits {
                self.events.push(SimEvent::Split {
                    object: id.0,
                    parts,
                });
            }
        }
        self.stats.stress_solves += solves as u64;
        self.stats.stress_iterations = iterations;
        self.stats.stress_ms = t0.elapsed().as_secs_f64() * 1e3;
        self.stats.stress_solve_ms = solve_ms;
        self.stats.stress_solve_cpu_ms = solve_cpu_ns.map(|ns| ns as f64 / 1e6);
    }

    /// Queues an explosion's push on the fragments of fixed bodies for the next stress
    /// solve: `power·(1 − x/radius)/dt` away from the centre, as the bonds are loaded.
    pub(crate) fn queue_explosion_forces(&mut self, spec: &ExplosionSpec) {
        let dt = f64::from(self.settings.dt);
        let centre = spec.position.as_dvec3();
        let (radius, power) = (f64::from(spec.radius), f64::from(spec.power));
        for record in self.objects.values_mut() {
            let Some(live) = record.live.as_mut() else {
                continue;
            };
            let Some(state) = live.stress.as_mut() else {
                continue;
            };
            let rotation: DQuat = record.spec.rotation.as_dquat();
            let origin = record.spec.position.as_dvec3();
            for (f, fragment) in live.prepared.fracture.fragments.iter().enumerate() {
                let Some(rb) = live.body[f].and_then(|b| self.physics.bodies.get(b)) else {
                    continue;
                };
                if !rb.is_fixed() {
                    continue;
                }
                let p = origin + rotation * fragment.centroid;
                let d = p - centre;
                let x = d.length();
                if x < radius {
                    let dir = if x > 1e-9 { d / x } else { DVec3::Y };
                    let impulse = dir * power * (1.0 - x / radius);
                    state
                        .pending
                        .push((f as u32, rotation.inverse() * impulse / dt));
                    let entry = state
                        .pending_impulses
                        .entry(f as u32)
                        .or_insert((Vec3::ZERO, 0.0));
                    entry.0 += impulse.as_vec3();
                }
            }
        }
    }
}
