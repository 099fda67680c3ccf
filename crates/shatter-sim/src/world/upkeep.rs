//! A step's upkeep after the physics: lifetimes that ended, the guard against bodies
//! that diverged (NaN or runaway), and the debris cap.

use rapier3d::prelude::RigidBodyHandle;

use crate::bonds::tags::{Kind, untag};
use crate::world::settings::SimEvent;
use crate::world::state::{ObjectId, World};

impl World {
    /// Removes objects and projectiles whose lifetime ended.
    pub(super) fn expire(&mut self) {
        let time = self.stats.time;
        let expired: Vec<ObjectId> = self
            .objects
            .iter()
            .filter(|(_, r)| r.live.is_some() && r.spec.last.is_some_and(|t| time >= t as f64))
            .map(|(id, _)| *id)
            .collect();
        for id in expired {
            self.remove_live(id);
            self.events.push(SimEvent::Expired(id.0));
        }
        for p in &mut self.projectiles {
            if let (Some(body), Some(last)) = (p.body, p.spec.last)
                && time >= p.fired_at + last as f64
            {
                self.physics.remove_body(body);
                p.body = None;
            }
        }
    }

    /// Removes bodies whose pose or velocity is not finite or whose speed ran away.
    pub(super) fn guard(&mut self) {
        let max_speed = self.settings.max_speed;
        let mut bad = Vec::new();
        for (h, rb) in self.physics.bodies.iter() {
            let p = rb.position();
            let finite = p.translation.is_finite()
                && p.rotation.is_finite()
                && rb.linvel().is_finite()
                && rb.angvel().is_finite();
            if !finite {
                bad.push((h, rb.user_data, "non-finite state".to_string()));
            } else if rb.linvel().length() > max_speed {
                bad.push((
                    h,
                    rb.user_data,
                    format!("speed {} m/s", rb.linvel().length()),
                ));
            } else if !rb.is_enabled() {
                bad.push((
                    h,
                    rb.user_data,
                    "disabled by Rapier's quarantine".to_string(),
                ));
            }
        }
        for (h, data, reason) in bad {
            if Some(h) == self.ground {
                continue;
            }
            let object = match untag(data) {
                Some((Kind::Fragment, object, _)) => {
                    self.forget_body(object, h);
                    Some(object)
                }
                Some((Kind::Projectile, index, _)) => {
                    if let Some(p) = self.projectiles.get_mut(index as usize) {
                        p.body = None;
                    }
                    None
                }
                _ => None,
            };
            self.physics.remove_body(h);
            self.stats.diverged += 1;
            self.events.push(SimEvent::Diverged { object, reason });
        }
    }

    /// Removes the oldest debris beyond the cap.
    pub(super) fn cap_debris(&mut self) {
        let Some(cap) = self.settings.max_debris else {
            return;
        };
        self.debris
            .retain(|(_, h)| self.physics.bodies.contains(*h));
        while self.debris.len() > cap {
            let Some((object, h)) = self.debris.pop_front() else {
                break;
            };
            self.forget_body(object, h);
            self.physics.remove_body(h);
            self.stats.debris_removed += 1;
        }
    }

    /// Drops the fragments of `object` that body `h` carries (before `h` is removed).
    fn forget_body(&mut self, object: u32, h: RigidBodyHandle) {
        if let Some(live) = self
            .objects
            .get_mut(&ObjectId(object))
            .and_then(|r| r.live.as_mut())
        {
            for f in 0..live.body.len() {
                if live.body[f] == Some(h) {
                    live.drop_fragment(f);
                }
            }
        }
    }
}
