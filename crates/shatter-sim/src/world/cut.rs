//! A runtime cut under way: what it computes, on a thread (native) or at its step (web),
//! and the seed of each cut.

use std::sync::Arc;

use glam::{DVec3, Vec3};
use shatter_geom::fracture::{Fracture, FractureError};

use crate::object::prepare::PieceShape;
use crate::runtime;
use crate::world::settings::ObjectId;

/// A cut under way.
pub(crate) struct PendingCut {
    /// The object and fragment being cut.
    pub object: ObjectId,
    pub fragment: u32,
    /// The hit point in the object's frame.
    pub impact: DVec3,
    /// The hit that started it (force in N, impulse on the fragment in N·s, the other
    /// body's mass), to load the new bonds with.
    pub force: f32,
    pub impulse: Vec3,
    pub other_mass: f32,
    /// The step at whose end the cut is applied.
    pub due: u64,
    pub job: CutJob,
}

/// What a cut computes: [`runtime::cut_fragment`] of these.
pub(crate) struct CutInput {
    /// The object's fracture (shared, not copied) and the fragment cut.
    fracture: Arc<Fracture>,
    fragment: usize,
    impact: DVec3,
    pieces: u32,
    seed: u64,
}

impl CutInput {
    /// The cut of `fracture`'s fragment `fragment` at `impact` into `pieces` cells, from
    /// `seed`.
    pub(crate) fn new(
        fracture: Arc<Fracture>,
        fragment: usize,
        impact: DVec3,
        pieces: u32,
        seed: u64,
    ) -> CutInput {
        CutInput {
            fracture,
            fragment,
            impact,
            pieces,
            seed,
        }
    }

    /// The estimate of the cut (a Voronoi fracture of its pieces).
    pub(crate) fn estimate(&self) -> shatter_geom::budget::Estimate {
        let triangles = self
            .fracture
            .fragments
            .get(self.fragment)
            .map_or(0, |f| f.mesh.triangles.len() as u64);
        shatter_geom::budget::Estimate::voronoi_fracture(u64::from(self.pieces), triangles)
    }

    /// The cut, and its fragments' collision shapes (built here, off the simulation's
    /// thread, rather than when the cut is applied).
    pub(crate) fn run(self) -> Result<CutResult, FractureError> {
        let fracture = runtime::cut_fragment(
            &self.fracture,
            self.fragment,
            self.impact,
            self.pieces,
            self.seed,
        )?;
        let shapes = crate::object::prepare::collision_shapes(&fracture, Vec3::ONE);
        Ok(CutResult { fracture, shapes })
    }
}

/// What a cut computed.
pub(crate) struct CutResult {
    pub fracture: Fracture,
    /// [`crate::object::prepare::collision_shapes`] of `fracture` (unscaled).
    pub shapes: Vec<Vec<PieceShape>>,
}

/// The cut's computation.
pub(crate) enum CutJob {
    #[cfg(not(target_arch = "wasm32"))]
    Thread(std::thread::JoinHandle<Result<CutResult, FractureError>>),
    /// Not started yet (no threads): run when due. (Plain data, not a closure: the world
    /// is shared between threads, as a Bevy resource is.)
    #[cfg(target_arch = "wasm32")]
    Later(Box<CutInput>),
}

impl CutJob {
    pub(crate) fn start(input: CutInput) -> CutJob {
        #[cfg(not(target_arch = "wasm32"))]
        {
            CutJob::Thread(std::thread::spawn(move || input.run()))
        }
        #[cfg(target_arch = "wasm32")]
        {
            CutJob::Later(Box::new(input))
        }
    }

    pub(crate) fn finish(self) -> Result<CutResult, String> {
        match self {
            #[cfg(not(target_arch = "wasm32"))]
            CutJob::Thread(handle) => match handle.join() {
                Ok(result) => result.map_err(|e| e.to_string()),
                Err(_) => Err("the cut's thread panicked".to_string()),
            },
            #[cfg(target_arch = "wasm32")]
            CutJob::Later(input) => input.run().map_err(|e| e.to_string()),
        }
    }
}

impl std::fmt::Debug for PendingCut {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("PendingCut")
            .field("object", &self.object)
            .field("fragment", &self.fragment)
            .field("due", &self.due)
            .finish_non_exhaustive()
    }
}
