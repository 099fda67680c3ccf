//! Destruction for Bevy games: mark an entity [`Breakable`], and it is fractured by
//! shatter on a background task and replaced by fragment entities that are ordinary
//! [avian3d](avian3d) rigid bodies. Fragments held by intact bonds form one body (a
//! compound of their convex pieces, the cluster bond model); impacts load the bonds
//! through shatter-sim's engine-free break logic ([`shatter_sim::breaking`]), and a body
//! whose bonds break splits into islands. The game's own colliders hit the debris and
//! the debris hits them.
//!
//! Fragments are drawn with the entity's own material: their surface keeps the mesh's
//! `UV_0` and normals (so a textured wall's debris shows its texture), and their cut
//! faces, with generated UVs, take the plugin's interior material.
//!
//! The plugin adds no camera, light or UI, and not the physics engine either: add
//! avian's `PhysicsPlugins` yourself.
//!
//! ```no_run
//! use avian3d::prelude::*;
//! use bevy::prelude::*;
//! use bevy_shatter::{Breakable, ShatterPlugin};
//!
//! fn setup(
//!     mut commands: Commands,
//!     mut meshes: ResMut<Assets<Mesh>>,
//!     mut materials: ResMut<Assets<StandardMaterial>>,
//! ) {
//!     commands.spawn((
//!         Mesh3d(meshes.add(Cuboid::new(3.0, 1.5, 0.3))),
//!         MeshMaterial3d(materials.add(Color::srgb(0.7, 0.3, 0.2))),
//!         Transform::from_xyz(0.0, 0.75, 0.0),
//!         Breakable::grid([6, 3, 1]),
//!     ));
//! }
//!
//! App::new()
//!     .add_plugins((DefaultPlugins, PhysicsPlugins::default(), ShatterPlugin::default()))
//!     .add_systems(Startup, setup)
//!     .run();
//! ```
//!
//! A game can also fracture offline (`shatter fracture wall.obj --out wall.glb
//! --anchor lowest`) and load the result: see [`FractureAsset`].
//!
//! Or fracture at runtime, where the object is hit: see [`Breakable::runtime`] (an
//! `on_impact` object is one intact body until a hard hit cuts it; loose fragments are
//! cut again, `depth` levels deep) and the [`RuntimeFractured`] message.
//!
//! A tool that wants shatter's own world instead (its stress solver, runtime cuts and
//! damage, exactly as the CLI runs them), stepped and drawn by Bevy, uses [`world`]: the
//! sandbox is built on it. That part needs no physics engine; the game part above is the
//! `avian` feature (on by default).

#![cfg_attr(test, allow(clippy::unwrap_used))]

#[cfg(feature = "avian")]
pub mod asset;
#[cfg(feature = "avian")]
mod bonds;
#[cfg(feature = "avian")]
pub mod breakable;
#[cfg(feature = "avian")]
mod components;
mod convert;
#[cfg(feature = "avian")]
mod runtime;
#[cfg(feature = "avian")]
mod spawn;
pub mod world;

pub use convert::{from_bevy, quat_to_bevy, to_bevy};

#[cfg(feature = "avian")]
pub use game::*;

/// The game plugin over avian3d (the `avian` feature).
#[cfg(feature = "avian")]
mod game {
    use bevy::prelude::*;

    pub use crate::asset::{FractureAsset, FractureAssetError, FractureAssetLoader};
    pub use crate::breakable::{Breakable, BreakableError};
    pub use crate::components::{Fragment, ShatterBody, ShatterObject};
    use crate::{asset, bonds, breakable, runtime, spawn};

    /// The plugin: fractures [`Breakable`] entities and breaks their bonds.
    ///
    /// Its systems run in `FixedUpdate`, in [`ShatterSystems`]; they read the contacts of the
    /// last physics step (avian runs in `FixedPostUpdate` by default).
    #[derive(Debug, Clone)]
    pub struct ShatterPlugin {
        /// The material for the cut (interior) faces of fragments; `None`: a
        /// `StandardMaterial` of [`shatter_geom::io::INTERIOR_COLOR`] made by the plugin (the
        /// colour shatter's files give cut faces).
        pub interior_material: Option<Handle<StandardMaterial>>,
        /// Scales every contact force before it loads the bonds (1: as measured).
        pub contact_scale: f32,
        /// Fragments whose speed exceeds this (m/s) or whose state is not finite are removed
        /// (a `Diverged` outcome is logged).
        pub max_speed: f32,
    }

    impl Default for ShatterPlugin {
        fn default() -> Self {
            ShatterPlugin {
                interior_material: None,
                contact_scale: 1.0,
                max_speed: 500.0,
            }
        }
    }

    /// The plugin's settings, as a resource (a copy of [`ShatterPlugin`]'s fields).
    #[derive(Resource, Debug, Clone)]
    pub struct ShatterSettings {
        /// See [`ShatterPlugin::interior_material`] (filled in at startup).
        pub interior_material: Option<Handle<StandardMaterial>>,
        /// See [`ShatterPlugin::contact_scale`].
        pub contact_scale: f32,
        /// See [`ShatterPlugin::max_speed`].
        pub max_speed: f32,
    }

    /// The plugin's system sets in `FixedUpdate`, in this order.
    #[derive(SystemSet, Debug, Clone, Copy, PartialEq, Eq, Hash)]
    pub enum ShatterSystems {
        /// Starts fracture tasks for new [`Breakable`]s and spawns the fragments of finished
        /// ones.
        Fracture,
        /// Loads bonds from the last step's contacts, breaks them and splits bodies;
        /// then cuts the bodies of single fragments hit hard enough
        /// ([`Breakable::runtime`]).
        Break,
    }

    /// A [`Breakable`] entity was fractured and replaced by fragments (an `on_impact`
    /// object by its intact body: one fragment, no bonds; its runtime cuts send
    /// [`RuntimeFractured`]).
    #[derive(Message, Debug, Clone, PartialEq)]
    pub struct Fractured {
        /// The entity (it stays, as the object's record: [`ShatterObject`]).
        pub object: Entity,
        /// Number of fragments.
        pub fragments: usize,
        /// Number of bonds.
        pub bonds: usize,
    }

    /// A fragment was cut at runtime ([`Breakable::runtime`]): a hit on the body holding
    /// it alone passed the threshold. The fragment's body is gone; the cut's fragments are
    /// a new object, `object`, on one bonded body at the same pose, moving as the
    /// material did there. The hit loads its bonds in the next step.
    ///
    /// ```
    /// use bevy::prelude::*;
    /// use bevy_shatter::{RuntimeFractured, ShatterObject};
    ///
    /// // A game's system: count the cuts, and see which level they reached.
    /// fn cuts(mut cut: MessageReader<RuntimeFractured>, objects: Query<&ShatterObject>) {
    ///     for m in cut.read() {
    ///         info!("{} cut into {} fragments (level {})", m.parent, m.fragments, m.level);
    ///         if let Ok(object) = objects.get(m.object) {
    ///             assert_eq!(object.parent, Some(m.parent));
    ///         }
    ///     }
    /// }
    /// # bevy::ecs::system::assert_is_system(cuts);
    /// ```
    #[derive(Message, Debug, Clone, PartialEq)]
    pub struct RuntimeFractured {
        /// The new object: an entity with the cut's [`ShatterObject`] (whose `parent` is
        /// `parent` and `level` is `level`).
        pub object: Entity,
        /// The object the fragment was cut from (it keeps its record; the fragment's slot
        /// in it has no body any more).
        pub parent: Entity,
        /// The fragment's index in `parent`'s fracture.
        pub fragment: u32,
        /// Number of fragments of the cut.
        pub fragments: usize,
        /// The new fragments' level: 1 for an intact body's cut, one more per cut after.
        pub level: u32,
    }

    /// A bond of an object broke.
    #[derive(Message, Debug, Clone, PartialEq)]
    pub struct BondBroken {
        /// The object.
        pub object: Entity,
        /// What broke (bond index, fragments, cause, load).
        pub bond: shatter_sim::breaking::BondBroken,
    }

    /// A body of an object split into islands of intact bonds.
    #[derive(Message, Debug, Clone, PartialEq)]
    pub struct Split {
        /// The object.
        pub object: Entity,
        /// The island bodies: the first is the old body, the others are new.
        pub bodies: Vec<Entity>,
        /// Each island's fragments.
        pub parts: Vec<Vec<u32>>,
    }

    /// A [`Breakable`] could not be fractured (bad mesh, bad parameters).
    #[derive(Message, Debug, Clone, PartialEq)]
    pub struct FractureFailed {
        /// The entity (it keeps its mesh; its [`Breakable`] is removed).
        pub object: Entity,
        /// Why.
        pub error: BreakableError,
    }

    impl Plugin for ShatterPlugin {
        fn build(&self, app: &mut App) {
            app.insert_resource(ShatterSettings {
                interior_material: self.interior_material.clone(),
                contact_scale: self.contact_scale,
                max_speed: self.max_speed,
            })
            .init_asset::<asset::FractureAsset>()
            .init_asset_loader::<asset::FractureAssetLoader>()
            .add_message::<Fractured>()
            .add_message::<BondBroken>()
            .add_message::<Split>()
            .add_message::<FractureFailed>()
            .add_message::<RuntimeFractured>()
            .configure_sets(
                FixedUpdate,
                (ShatterSystems::Fracture, ShatterSystems::Break).chain(),
            )
            .add_systems(
                FixedUpdate,
                (
                    (breakable::start_fractures, spawn::finish_fractures)
                        .chain()
                        .in_set(ShatterSystems::Fracture),
                    (bonds::break_bonds, runtime::cut_on_impact, bonds::guard)
                        .chain()
                        .in_set(ShatterSystems::Break),
                ),
            );
        }
    }
}
