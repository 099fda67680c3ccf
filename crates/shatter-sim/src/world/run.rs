//! Running a world for many steps with progress and cancellation: the loop behind
//! `shatter simulate` and `shatter study`, usable by any front end.

use shatter_geom::progress::{Cancelled, Progress};

use crate::world::World;

impl World {
    /// Runs `steps` steps, calling `after_step(world, steps_done)` after each one. The
    /// stage `"steps"` of `progress` counts them; once `progress` is cancelled the run
    /// stops before the next step with [`Cancelled`] (converted into the caller's error
    /// type), leaving the world as it is after the last step it ran. An error from
    /// `after_step` stops the run too.
    ///
    /// ```
    /// use shatter_geom::progress::{Cancelled, Progress};
    /// use shatter_sim::{World, WorldSettings};
    ///
    /// let mut world = World::new(WorldSettings::default());
    /// world.start();
    /// let progress = Progress::new();
    /// world.run_steps(10, &progress, |_, _| Ok::<(), Cancelled>(()))?;
    /// assert_eq!(world.stats().steps, 10);
    /// assert_eq!(progress.snapshot().done, 10);
    ///
    /// progress.cancel();
    /// assert_eq!(world.run_steps(10, &progress, |_, _| Ok(())), Err(Cancelled));
    /// assert_eq!(world.stats().steps, 10);
    /// # Ok::<(), Cancelled>(())
    /// ```
    pub fn run_steps<E: From<Cancelled>>(
        &mut self,
        steps: u64,
        progress: &Progress,
        mut after_step: impl FnMut(&World, u64) -> Result<(), E>,
    ) -> Result<(), E> {
        progress.start_stage("steps", steps);
        for done in 1..=steps {
            progress.check()?;
            self.step();
            after_step(self, done)?;
            progress.advance(1);
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::WorldSettings;

    #[test]
    fn cancelling_from_the_observer_stops_after_that_step() {
        let mut world = World::new(WorldSettings::default());
        world.start();
        let progress = Progress::new();
        let r = world.run_steps(100, &progress, |_, done| {
            if done == 7 {
                progress.cancel();
            }
            Ok::<(), Cancelled>(())
        });
        assert_eq!(r, Err(Cancelled));
        assert_eq!(world.stats().steps, 7);
        assert_eq!(progress.snapshot().done, 7);
    }

    #[test]
    fn an_observer_error_stops_the_run() {
        #[derive(Debug, PartialEq)]
        enum E {
            Stop,
            Cancelled,
        }
        impl From<Cancelled> for E {
            fn from(_: Cancelled) -> Self {
                E::Cancelled
            }
        }
        let mut world = World::new(WorldSettings::default());
        world.start();
        let r = world.run_steps(5, &Progress::none(), |_, done| {
            if done == 2 { Err(E::Stop) } else { Ok(()) }
        });
        assert_eq!(r, Err(E::Stop));
        assert_eq!(world.stats().steps, 2);
    }
}
