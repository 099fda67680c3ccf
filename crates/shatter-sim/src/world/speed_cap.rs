//! The contact speed cap ([`WorldSettings::contact_speed_cap`]): no body leaves a step
//! much faster than anything that touched it moved.
//!
//! A light body squeezed between a heavy one and the ground (a 2.6 kg brick under a block
//! of tens of tonnes landing at 9 m/s) asks the solver for what it cannot give in a few
//! iterations, and Rapier answers by throwing the brick out at up to 190 m/s, spinning at
//! 3,000 rad/s. Game engines bound this with a speed limit per body (PhysX's
//! `maxAngularVelocity`); Rapier 0.36 has none. A fixed limit is wrong for a world where
//! a shot flies at 40 m/s and an explosion throws debris at hundreds, so the cap here is
//! relative, from what the step started with:
//!
//! - a body's *speed* is `|v| + sqrt(ωᵀIω / m)`: its linear speed plus the speed its
//!   rotation gives its mass on average (the radius of gyration times `|ω|`), so a spin
//!   counts as the motion it is;
//! - its *bound* is its own speed before the step, plus the most a perfectly elastic hit
//!   by anything it touches could add, plus what the step itself may add (gravity over
//!   one step and Rapier's largest penetration-correcting speed). A body of mass `m`
//!   moving at `u` (before the step, at the point where they touch) adds at most
//!   `2·u·m / (m + m_b)` to a body of mass `m_b`: twice its speed when it is far
//!   heavier, its speed when they weigh the same, little when it is light;
//! - only what touches a body counts, not what pushes that: Rapier passes a push on one
//!   body per step (a block driven into a row of two loose bricks moves the far one at
//!   the next step, when the near one already moves; `tests/speed_cap.rs`). A bound
//!   followed through rows of bodies (tried, eight deep) allows every brick in a landing
//!   pile twice the block's speed, and it slowed 21 bodies of bench scale's 2k landing
//!   where this one slows 51;
//! - a body held by joints (the thesis's joints model) is not capped: Rapier solves a
//!   structure of joints as one, so a shot moves bricks many joints from the one it hits
//!   within the step (bench scale's 2k joints wall: a bound from the joints' partners
//!   slowed 746 bodies over the run, and 38 bonds broke instead of 45), and no
//!   jointed body was seen flung (the joints landing: fastest 8.9 m/s, the block's
//!   speed);
//! - a body faster than its bound after the step gets its bound: its velocity and spin
//!   are scaled down together. Its move in the step stays as Rapier made it: shortened
//!   alike, it put the body back into the squeeze, which flung it again at the next
//!   step (tried: bench scale's landings then had bodies at 23–35 m/s, some 2–4 steps
//!   later; as it is, 9–13 m/s, the block having landed at 9).
//!
//! Explosions, shots and split launches happen outside Rapier's step (before it, or after
//! it as the next step's start), so what they give a body is part of its speed before
//! the step, never capped here (explosions have [`WorldSettings::max_launch_speed`]).
//!
//! [`WorldSettings::contact_speed_cap`]: crate::WorldSettings::contact_speed_cap
//! [`WorldSettings::max_launch_speed`]: crate::WorldSettings::max_launch_speed

use glam::Vec3;
use rapier3d::prelude::*;

/// The moving bodies' velocities (linear, angular) at the start of a step, by body index.
/// Recorded afresh before each step and read just after it: Rapier's step neither adds
/// nor removes bodies, so an index names the same body in both.
#[derive(Debug, Default, Clone)]
pub(crate) struct SpeedCap {
    before: Vec<Option<(Vec3, Vec3)>>,
}

impl SpeedCap {
    /// Records every awake body's velocity before a step runs. (From the body
    /// set, not Rapier's active set: bodies added since the last step, such as the parts
    /// of a split and their launch velocities, join that set only during the step.)
    pub(crate) fn record(&mut self, physics: &PhysicsWorld) {
        self.before.clear();
        for (h, rb) in physics.bodies.iter() {
            if rb.is_fixed() || rb.is_sleeping() {
                continue;
            }
            let index = h.into_raw_parts().0 as usize;
            if self.before.len() <= index {
                self.before.resize(index + 1, None);
            }
            self.before[index] = Some((rb.linvel(), rb.angvel()));
        }
    }

    /// A body's velocity and spin before the step; `None` when it was asleep (at rest) or
    /// fixed.
    fn before(&self, h: RigidBodyHandle) -> Option<(Vec3, Vec3)> {
        *self.before.get(h.into_raw_parts().0 as usize)?
    }

    /// Velocity of body `h` before the step at world point `p`, a point of the body now
    /// (the lever arm is taken from its centre of mass now, since the body may have moved
    /// far in the step); zero for a body that was at rest or is fixed. A kinematic body
    /// moves as it is told, so its velocity now is the one it had.
    fn velocity_at(&self, physics: &PhysicsWorld, h: RigidBodyHandle, p: Vec3) -> Vec3 {
        let Some(rb) = physics.bodies.get(h) else {
            return Vec3::ZERO;
        };
        let arm = p - rb.mass_properties().world_com;
        match self.before(h) {
            Some((v, w)) => v + w.cross(arm),
            None if rb.is_kinematic() => rb.velocity_at_point(p),
            None => Vec3::ZERO,
        }
    }

    /// Caps every awake dynamic body that left the step faster than its bound (see the
    /// module's doc); `margin` is the speed the step may add on its own (m/s). Returns how
    /// many bodies were capped.
    pub(crate) fn apply(&self, physics: &mut PhysicsWorld, margin: f32) -> usize {
        let mut capped = Vec::new();
        for h in physics.islands.active_bodies() {
            let Some(rb) = physics.bodies.get(h) else {
                continue;
            };
            // A body held by joints is left to them (see the module's doc).
            if !rb.is_dynamic() || physics.impulse_joints.attached_joints(h).next().is_some() {
                continue;
            }
            let (v0, w0) = self.before(h).unwrap_or((Vec3::ZERO, Vec3::ZERO));
            let now = speed(rb, rb.linvel(), rb.angvel());
            let own = speed(rb, v0, w0);
            // Cheap test first: the bound is at least its own speed and the margin.
            if now <= own + margin {
                continue;
            }
            let bound = own + self.strongest_push(physics, rb) + margin;
            if now > bound {
                capped.push((h, bound / now));
            }
        }
        for &(h, factor) in &capped {
            if let Some(rb) = physics.bodies.get_mut(h) {
                rb.set_linvel(rb.linvel() * factor, true);
                rb.set_angvel(rb.angvel() * factor, true);
            }
        }
        capped.len()
    }

    /// The most speed anything touching body `rb` could give it in an elastic hit: `2·μ·u`
    /// for a body that moved at `u` before the step (at the contact points of its
    /// colliders' touching pairs), with `μ = m / (m + m_b)` of the two masses (1 for a
    /// fixed or kinematic body): twice its speed when it is far heavier, its speed when
    /// they weigh the same.
    fn strongest_push(&self, physics: &PhysicsWorld, rb: &RigidBody) -> f32 {
        let mass = rb.mass();
        let share = |other: RigidBodyHandle| match physics.bodies.get(other) {
            Some(o) if o.is_dynamic() && o.mass() + mass > 0.0 => o.mass() / (o.mass() + mass),
            _ => 1.0,
        };
        let mut strongest = 0.0f32;
        for &c in rb.colliders() {
            for pair in physics.narrow_phase.contact_pairs_with(c) {
                if !pair.has_any_active_contact() {
                    continue;
                }
                // The points on the other collider's surface, in its frame.
                let other_is_first = pair.collider2 == c;
                let other = if other_is_first {
                    pair.collider1
                } else {
                    pair.collider2
                };
                let Some(co) = physics.colliders.get(other) else {
                    continue;
                };
                let Some(other_body) = co.parent() else {
                    continue;
                };
                let pose = *co.position();
                let twice = 2.0 * share(other_body);
                for manifold in pair.manifolds() {
                    for point in &manifold.points {
                        let local = if other_is_first {
                            point.local_p1
                        } else {
                            point.local_p2
                        };
                        let u = self.velocity_at(physics, other_body, pose.transform_point(local));
                        strongest = strongest.max(twice * u.length());
                    }
                }
            }
        }
        strongest
    }
}

/// A body's speed with velocity `v` and spin `w` (see the module's doc): `|v|` plus the
/// radius of gyration about the spin's axis times `|w|`.
fn speed(rb: &RigidBody, v: Vec3, w: Vec3) -> f32 {
    let m = rb.mass();
    if m <= 0.0 || !m.is_finite() {
        return v.length();
    }
    let mprops = &rb.mass_properties().local_mprops;
    // The spin in the body's principal frame: Σ I_i ω_i² is ωᵀIω.
    let frame = rb.position().rotation * mprops.principal_inertia_local_frame;
    let local = frame.inverse() * w;
    let inertia = mprops.principal_inertia();
    let iww = inertia.x * local.x * local.x
        + inertia.y * local.y * local.y
        + inertia.z * local.z * local.z;
    v.length() + (iww.max(0.0) / m).sqrt()
}
