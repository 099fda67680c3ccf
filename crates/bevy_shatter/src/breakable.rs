//! The [`Breakable`] component and the background fracture of its mesh, or the
//! pre-fractured asset it names ([`crate::FractureAsset`]).

use std::sync::Arc;

use bevy::prelude::*;
use bevy::tasks::{AsyncComputeTaskPool, Task};
use shatter_geom::fracture::{self as geom, Fracture};
use shatter_sim::runtime::{self, FractureTiming, RuntimeFracture};
use shatter_sim::{BondModel, Material, MaterialPreset, MethodKind, Pattern};

use crate::asset::FractureAsset;
use crate::{FractureFailed, convert};

/// Marks an entity with a `Mesh3d` and a `Transform` as breakable. At spawn its mesh is
/// fractured on a background task; then the mesh is removed from the entity and its
/// fragments are spawned as rigid bodies (see the crate docs).
///
/// ```
/// use bevy_shatter::Breakable;
/// use shatter_sim::{MethodKind, Material};
///
/// let glass = Breakable {
///     material: Material::preset("glass").expect("a preset"),
///     method: MethodKind::Voronoi,
///     pieces: 30,
///     ..Breakable::default()
/// };
/// assert_eq!(glass.seed, 1);
/// ```
///
/// An object that starts whole and is cut where it is hit ([`Breakable::runtime`]):
///
/// ```
/// use bevy_shatter::Breakable;
/// use shatter_sim::runtime::{FractureTiming, RuntimeFracture};
///
/// let vase = Breakable {
///     pieces: 30, // cells of the first cut, a quarter as many per level after
///     runtime: RuntimeFracture {
///         timing: FractureTiming::OnImpact,
///         impulse: Some(200.0), // N·s of a hit that cuts; `None`: strength · dt
///         depth: 2,             // loose fragments are cut once more when hit
///         min_size: 0.05,       // but not those smaller than 5 cm
///     },
///     ..Breakable::default()
/// };
/// assert!(vase.validate().is_ok());
/// let bad = Breakable { runtime: RuntimeFracture { depth: 0, ..vase.runtime }, ..vase };
/// assert!(bad.validate().is_err());
/// ```
#[derive(Component, Debug, Clone, PartialEq)]
pub struct Breakable {
    /// Density, friction, restitution, break force (`strength`) and wear.
    pub material: Material,
    /// How the mesh is cut.
    pub method: MethodKind,
    /// Voronoi seed pattern.
    pub pattern: Pattern,
    /// Number of pieces (Voronoi seeds, slice planes; tetra: random interior points).
    pub pieces: u32,
    /// Cells along x, y, z of the [`MethodKind::Grid`] method (cuts the mesh's bounding
    /// box into bricks).
    pub grid: [u32; 3],
    /// Random seed: the same seed gives the same fragments.
    pub seed: u64,
    /// Bond model. Only [`BondModel::Clusters`] is simulated by the plugin so far;
    /// [`BondModel::Joints`] is refused with [`BreakableError::Unsupported`].
    pub bond_model: BondModel,
    /// Break force of each bond (N); `None` uses `material.strength`.
    pub break_force: Option<f32>,
    /// Whether the object is fixed to the world (a static body until bonds break) by its
    /// bottom fragments. A pre-fractured asset with anchors is held by those, whatever
    /// this says.
    pub anchored: bool,
    /// A pre-fractured object (a GLB with the `SHATTER_fracture` extension): its
    /// fragments and bonds are used as they are, and the entity needs no mesh.
    pub prefractured: Option<Handle<FractureAsset>>,
    /// Runtime fracture, as shatter's own world does it: when the object is first cut,
    /// the contact impulse of a hit that cuts, how many levels deep loose fragments are
    /// cut again and the smallest fragment cut. The default is precomputed, depth 1: the
    /// mesh is fractured at spawn and nothing is cut later.
    ///
    /// With [`FractureTiming::OnImpact`] the mesh is not fractured at spawn: it becomes
    /// one intact dynamic body (anchored: static) holding a single fragment
    /// ([`shatter_sim::runtime::whole`], level 0). A hit on a body holding a single
    /// fragment that [`RuntimeFracture::cuts`] allows, whose contact impulse passes
    /// [`RuntimeFracture::impulse`] (or [`Breakable::strength`] · dt), cuts that
    /// fragment in that step around the hit ([`shatter_sim::runtime::cut_fragment`],
    /// [`shatter_sim::runtime::pieces_at`] of [`Breakable::pieces`] for its level) into
    /// a new bonded object one level deeper (a [`crate::RuntimeFractured`] message).
    pub runtime: RuntimeFracture,
}

impl Default for Breakable {
    fn default() -> Self {
        let material = MaterialPreset::Concrete.material();
        Breakable {
            material,
            method: MethodKind::Voronoi,
            pattern: Pattern::Uniform,
            pieces: 20,
            grid: [4, 4, 1],
            seed: 1,
            bond_model: BondModel::Clusters,
            break_force: None,
            anchored: false,
            prefractured: None,
            runtime: RuntimeFracture::default(),
        }
    }
}

impl Breakable {
    /// Bricks: the mesh's bounding box cut into `cells` boxes.
    ///
    /// ```
    /// let wall = bevy_shatter::Breakable::grid([6, 3, 1]);
    /// assert_eq!(wall.grid, [6, 3, 1]);
    /// ```
    pub fn grid(cells: [u32; 3]) -> Breakable {
        Breakable {
            method: MethodKind::Grid,
            grid: cells,
            ..Breakable::default()
        }
    }

    /// A pre-fractured object: the fracture is `asset`'s (see [`crate::FractureAsset`]).
    /// Its anchors, if it has any, hold it; its break force is the file's when it has
    /// thresholds and `break_force` is not set.
    pub fn prefractured(asset: Handle<FractureAsset>) -> Breakable {
        Breakable {
            prefractured: Some(asset),
            ..Breakable::default()
        }
    }

    /// The break force of each bond (N).
    pub fn strength(&self) -> f32 {
        self.break_force.unwrap_or(self.material.strength)
    }

    /// Checks the settings the fracture itself does not: the bond model, the break
    /// force and [`Breakable::runtime`] ([`RuntimeFracture::validate`]).
    pub fn validate(&self) -> Result<(), BreakableError> {
        if self.bond_model != BondModel::Clusters {
            return Err(BreakableError::Unsupported(format!(
                "bond model `{}` (only `clusters` so far)",
                self.bond_model.name()
            )));
        }
        let s = self.strength();
        if !(s.is_finite() && s > 0.0) {
            return Err(BreakableError::Fracture(format!(
                "break force must be > 0, got {s}"
            )));
        }
        self.runtime
            .validate("runtime")
            .map_err(|e| BreakableError::Runtime(e.to_string()))?;
        if self.prefractured.is_some() && self.runtime.timing == FractureTiming::OnImpact {
            return Err(BreakableError::Unsupported(
                "`on_impact` timing for a pre-fractured asset (it is already cut)".into(),
            ));
        }
        Ok(())
    }

    /// Fractures `mesh` (the entity's mesh, in its local frame) with these parameters;
    /// with [`FractureTiming::OnImpact`], `mesh` whole as a single fragment
    /// ([`shatter_sim::runtime::whole`]).
    ///
    /// ```
    /// use bevy::prelude::*;
    /// let mesh = Mesh::from(Cuboid::new(2.0, 1.0, 1.0));
    /// let fracture = bevy_shatter::Breakable::grid([2, 1, 1]).fracture(&mesh)?;
    /// assert_eq!(fracture.fragments.len(), 2);
    /// assert_eq!(fracture.bonds.len(), 1);
    /// # Ok::<(), bevy_shatter::BreakableError>(())
    /// ```
    pub fn fracture(&self, mesh: &Mesh) -> Result<Fracture, BreakableError> {
        self.validate()?;
        let model = convert::model(mesh).ok_or(BreakableError::NotATriangleMesh)?;
        if self.runtime.timing == FractureTiming::OnImpact {
            return runtime::whole(&model).map_err(|e| BreakableError::Fracture(e.to_string()));
        }
        let method = match self.method {
            MethodKind::Voronoi => geom::Method::voronoi(self.pieces as usize, self.pattern),
            MethodKind::Slice => geom::Method::Slice {
                pieces: self.pieces as usize,
                planes: None,
            },
            MethodKind::Tetra => {
                geom::Method::tetra(self.pieces as usize, geom::Placement::Interior)
            }
            MethodKind::Grid => geom::Method::Grid {
                cells: self.grid,
                voids: Vec::new(),
            },
        };
        // With the mesh's UVs and normals: the entity's own (textured) material draws
        // the fragments' surface as it drew the whole.
        geom::fracture_model(
            &model,
            &geom::FractureParams {
                method,
                seed: self.seed,
            },
        )
        .map_err(|e| BreakableError::Fracture(e.to_string()))
    }
}

/// Why a [`Breakable`] could not be fractured.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BreakableError {
    /// The entity has no `Mesh3d`, or its mesh asset is gone.
    #[error("the breakable entity has no mesh")]
    NoMesh,
    /// The mesh is not a triangle list with positions.
    #[error("the mesh is not a triangle list with positions")]
    NotATriangleMesh,
    /// The fracture refused the mesh or the parameters.
    #[error("fracture failed: {0}")]
    Fracture(String),
    /// A setting the plugin does not simulate yet.
    #[error("not supported by bevy_shatter yet: {0}")]
    Unsupported(String),
    /// The pre-fractured asset failed to load (the loader's message).
    #[error("the pre-fractured asset failed to load: {0}")]
    Asset(String),
    /// [`Breakable::runtime`] has a bad value ([`RuntimeFracture::validate`]'s message).
    #[error("bad runtime fracture settings: {0}")]
    Runtime(String),
}

/// What a fracture task gives: the fracture, and the asset's anchors and break force.
pub(crate) struct Outcome {
    pub fracture: Arc<Fracture>,
    pub anchors: Option<Vec<u32>>,
    pub strength: Option<f32>,
    /// The fragments' fracture level (0: an `on_impact` object's intact body).
    pub level: u32,
    /// The object it was cut from at runtime.
    pub parent: Option<Entity>,
}

/// A fracture running on the async compute pool.
#[derive(Component)]
pub(crate) struct FractureTask(pub(crate) Task<Result<Outcome, BreakableError>>);

/// Starts a background fracture for each new [`Breakable`].
pub(crate) fn start_fractures(
    mut commands: Commands,
    new: Query<(Entity, &Breakable, Option<&Mesh3d>), Without<FractureTask>>,
    meshes: Res<Assets<Mesh>>,
    (assets, server): (Res<Assets<FractureAsset>>, Res<AssetServer>),
    mut failed: MessageWriter<FractureFailed>,
) {
    for (entity, breakable, mesh) in &new {
        if let Some(handle) = &breakable.prefractured {
            let outcome = match (breakable.validate(), assets.get(handle)) {
                (Err(e), _) => Err(e),
                (Ok(()), Some(asset)) => Ok(Outcome {
                    fracture: asset.fracture.clone(),
                    anchors: (!asset.meta.anchors.is_empty()).then(|| asset.meta.anchors.clone()),
                    strength: asset.meta.thresholds.map(|t| t.strength as f32),
                    level: 1,
                    parent: None,
                }),
                (Ok(()), None) => match server.load_state(handle) {
                    bevy::asset::LoadState::Failed(e) => Err(BreakableError::Asset(e.to_string())),
                    // Not loaded yet: look again next step.
                    _ => continue,
                },
            };
            let task = AsyncComputeTaskPool::get().spawn(async move { outcome });
            commands.entity(entity).insert(FractureTask(task));
            continue;
        }
        let Some(mesh) = mesh.and_then(|m| meshes.get(&m.0)) else {
            failed.write(FractureFailed {
                object: entity,
                error: BreakableError::NoMesh,
            });
            commands.entity(entity).remove::<Breakable>();
            continue;
        };
        let (breakable, mesh) = (breakable.clone(), mesh.clone());
        let level = u32::from(breakable.runtime.timing != FractureTiming::OnImpact);
        let task = AsyncComputeTaskPool::get().spawn(async move {
            breakable.fracture(&mesh).map(|f| Outcome {
                fracture: Arc::new(f),
                anchors: None,
                strength: None,
                level,
                parent: None,
            })
        });
        commands.entity(entity).insert(FractureTask(task));
    }
}
