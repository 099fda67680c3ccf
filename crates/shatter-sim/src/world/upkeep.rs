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

    /// Removes debris beyond the cap ([`WorldSettings::max_debris`]): settled (sleeping)
    /// pieces before moving ones, the smallest first, the oldest of equals first.
    ///
    /// [`WorldSettings::max_debris`]: crate::WorldSettings::max_debris
    pub(super) fn cap_debris(&mut self) {
        let Some(cap) = self.settings.max_debris else {
            return;
        };
        self.debris
            .retain(|(_, h)| self.physics.bodies.contains(*h));
        if self.debris.len() <= cap {
            return;
        }
        let pieces: Vec<DebrisPiece> = self
            .debris
            .iter()
            .map(|&(_, h)| {
                let rb = &self.physics.bodies[h];
                let volume = match untag(rb.user_data) {
                    Some((Kind::Fragment, o, f)) => self
                        .objects
                        .get(&ObjectId(o))
                        .and_then(|r| r.live.as_ref())
                        .and_then(|live| live.prepared.fracture.fragments.get(f as usize))
                        .map_or(0.0, |fragment| fragment.volume),
                    _ => 0.0,
                };
                DebrisPiece {
                    settled: rb.is_sleeping(),
                    volume,
                }
            })
            .collect();
        let remove = debris_to_remove(&pieces, cap);
        let mut kept = std::collections::VecDeque::with_capacity(cap);
        for (i, (object, h)) in std::mem::take(&mut self.debris).into_iter().enumerate() {
            if remove.binary_search(&i).is_ok() {
                self.forget_body(object, h);
                self.physics.remove_body(h);
                self.stats.debris_removed += 1;
            } else {
                kept.push_back((object, h));
            }
        }
        self.debris = kept;
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

/// What the debris cap ranks a debris body by.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct DebrisPiece {
    /// At rest (Rapier put it to sleep).
    pub settled: bool,
    /// Its fragment's volume (m³).
    pub volume: f64,
}

/// Which of `pieces` (oldest first) go so that at most `cap` stay, ascending: settled
/// pieces before moving ones, the smallest first, the oldest of equals first.
pub(crate) fn debris_to_remove(pieces: &[DebrisPiece], cap: usize) -> Vec<usize> {
    let excess = pieces.len().saturating_sub(cap);
    let mut order: Vec<usize> = (0..pieces.len()).collect();
    order.sort_by(|&a, &b| {
        let (p, q) = (pieces[a], pieces[b]);
        q.settled
            .cmp(&p.settled)
            .then(p.volume.total_cmp(&q.volume))
            .then(a.cmp(&b))
    });
    let mut remove = order[..excess].to_vec();
    remove.sort_unstable();
    remove
}

#[cfg(test)]
mod tests {
    use super::*;

    fn piece(settled: bool, volume: f64) -> DebrisPiece {
        DebrisPiece { settled, volume }
    }

    #[test]
    fn the_cap_takes_settled_pieces_first_and_the_smallest_of_them() {
        let pieces = [
            piece(false, 0.1),
            piece(true, 3.0),
            piece(true, 1.0),
            piece(false, 0.2),
            piece(true, 2.0),
        ];
        assert_eq!(debris_to_remove(&pieces, 4), vec![2]);
        assert_eq!(debris_to_remove(&pieces, 2), vec![1, 2, 4]);
        // All settled ones gone, then the smallest moving one.
        assert_eq!(debris_to_remove(&pieces, 1), vec![0, 1, 2, 4]);
        assert_eq!(debris_to_remove(&pieces, 0), vec![0, 1, 2, 3, 4]);
        assert!(debris_to_remove(&pieces, 5).is_empty());
        assert!(debris_to_remove(&pieces, 9).is_empty());
    }

    #[test]
    fn equal_pieces_go_oldest_first() {
        let pieces = [piece(true, 1.0); 4];
        assert_eq!(debris_to_remove(&pieces, 2), vec![0, 1]);
    }
}
