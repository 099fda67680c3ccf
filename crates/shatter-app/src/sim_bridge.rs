//! The only module that talks to the simulation.
//!
//! Everything else in the app sees [`SimBridge`]: it applies [`SimCommand`]s, advances
//! time, and reads back what to draw (fragment geometry once, poses every frame) and the
//! statistics for the overlay.
//!
//! STAND-IN: until `shatter-sim` lands, objects are box grids that stay where they were
//! put; the interface is the one the app keeps.

use std::collections::BTreeMap;
use std::path::Path;

use bevy::prelude::{Quat, Resource, Vec3};
use glam::{DMat3, DVec3};

/// Bevy's vector (glam 0.32) from the simulation's (glam 0.33).
pub fn to_bevy(v: glam::Vec3) -> Vec3 {
    Vec3::from_array(v.to_array())
}

/// The simulation's vector (glam 0.33) from Bevy's (glam 0.32).
pub fn to_sim(v: Vec3) -> glam::Vec3 {
    glam::Vec3::from_array(v.to_array())
}

/// Bevy's quaternion from the simulation's.
pub fn quat_to_bevy(q: glam::Quat) -> Quat {
    Quat::from_array(q.to_array())
}
use shatter_geom::TriMesh;
use shatter_geom::fracture::{Fracture, Fragment};

use crate::commands::{
    BondModelChoice, MethodChoice, ObjectId, ObjectSpec, PatternChoice, ShapeChoice, SimCommand,
};

/// Identifies one drawable piece: a fragment of one build of an object.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct PieceKey {
    /// Object (or projectile) id.
    pub object: ObjectId,
    /// Bumped each time the object is rebuilt, so stale meshes are replaced.
    pub build: u32,
    /// Fragment index.
    pub fragment: u32,
}

/// Where a piece is this frame: the transform from the fragment's mesh frame to the world.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PiecePose {
    /// Which piece.
    pub key: PieceKey,
    /// Translation.
    pub translation: Vec3,
    /// Rotation.
    pub rotation: Quat,
}

/// Numbers for the overlay and the autotest.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct SimStats {
    /// Rigid bodies in the world.
    pub bodies: usize,
    /// Fragments alive.
    pub fragments: usize,
    /// Bonds (joints or cluster bonds) in all objects.
    pub bonds_total: usize,
    /// Bonds broken since start.
    pub bonds_broken: usize,
    /// Mean wall-clock time of the last steps, in ms.
    pub step_ms: f64,
    /// Simulated seconds since start.
    pub time: f64,
    /// Started and not paused.
    pub running: bool,
    /// Paused.
    pub paused: bool,
}

struct Object {
    spec: ObjectSpec,
    build: u32,
    fracture: Fracture,
}

/// The simulation as the app sees it.
#[derive(Resource, Default)]
pub struct SimBridge {
    objects: BTreeMap<ObjectId, Object>,
    next_id: ObjectId,
    running: bool,
    paused: bool,
    time: f64,
    bond_model: Option<BondModelChoice>,
}

impl SimBridge {
    /// The default scene: a wall and a few objects on the ground.
    pub fn default_scene() -> Self {
        let mut b = Self::default();
        let base = ObjectSpec {
            shape: ShapeChoice::Cube,
            method: MethodChoice::Voronoi,
            pattern: PatternChoice::Uniform,
            random_vertices: 60,
            skip: 0,
            center: false,
            break_force: 200.0,
            lifetime: None,
            color: [0.75, 0.42, 0.3],
            material: "stone".to_owned(),
            position: DVec3::new(0.0, 2.0, 0.0),
            scale: DVec3::new(8.0, 4.0, 0.6),
        };
        b.add(base.clone());
        b.add(ObjectSpec {
            color: [0.3, 0.6, 0.85],
            material: "glass".to_owned(),
            position: DVec3::new(-4.0, 1.0, 4.0),
            scale: DVec3::new(2.0, 2.0, 2.0),
            ..base
        });
        b
    }

    /// Apply a command; returns the new object's id for [`SimCommand::AddObject`].
    pub fn apply(&mut self, cmd: SimCommand) -> Result<Option<ObjectId>, String> {
        match cmd {
            SimCommand::Start => {
                self.running = true;
                self.paused = false;
            }
            SimCommand::TogglePause => {
                if self.running {
                    self.paused = !self.paused;
                }
            }
            SimCommand::Reset => {
                self.running = false;
                self.paused = false;
                self.time = 0.0;
            }
            SimCommand::Clean => self.objects.clear(),
            SimCommand::AddObject(spec) => return Ok(Some(self.add(spec))),
            SimCommand::EditObject(id, spec) => {
                let obj = self
                    .objects
                    .get_mut(&id)
                    .ok_or_else(|| format!("no object {id}"))?;
                obj.fracture = stand_in_fracture(&spec);
                obj.spec = spec;
                obj.build += 1;
            }
            SimCommand::DeleteObject(id) => {
                self.objects
                    .remove(&id)
                    .ok_or_else(|| format!("no object {id}"))?;
            }
            SimCommand::Fire { .. } | SimCommand::Explode { .. } => {}
            SimCommand::SetBondModel(m) => self.bond_model = Some(m),
            SimCommand::SaveScene(p) | SimCommand::LoadScene(p) => {
                return Err(format!("scene files not available yet ({})", p.display()));
            }
        }
        Ok(None)
    }

    fn add(&mut self, spec: ObjectSpec) -> ObjectId {
        let id = self.next_id;
        self.next_id += 1;
        let fracture = stand_in_fracture(&spec);
        self.objects.insert(
            id,
            Object {
                spec,
                build: 0,
                fracture,
            },
        );
        id
    }

    /// Advance by `dt` seconds of wall-clock time (fixed steps inside).
    pub fn advance(&mut self, dt: f64) {
        if self.running && !self.paused {
            self.time += dt;
        }
    }

    /// Every drawable piece and its pose.
    pub fn poses(&self) -> Vec<PiecePose> {
        let mut out = Vec::new();
        for (&id, o) in &self.objects {
            for f in 0..o.fracture.fragments.len() {
                out.push(PiecePose {
                    key: PieceKey {
                        object: id,
                        build: o.build,
                        fragment: f as u32,
                    },
                    translation: to_bevy(o.spec.position.as_vec3()),
                    rotation: Quat::IDENTITY,
                });
            }
        }
        out
    }

    /// Geometry and colour of a piece, to build its mesh once.
    pub fn piece_geometry(&self, key: PieceKey) -> Option<(&Fragment, [f32; 3])> {
        let o = self.objects.get(&key.object)?;
        if o.build != key.build {
            return None;
        }
        Some((
            o.fracture.fragments.get(key.fragment as usize)?,
            o.spec.color,
        ))
    }

    /// The specification an object was built from (for Edit).
    pub fn object_spec(&self, id: ObjectId) -> Option<&ObjectSpec> {
        self.objects.get(&id).map(|o| &o.spec)
    }

    /// The object and point hit first by a ray (`dir` need not be unit).
    pub fn ray_cast(&self, origin: glam::Vec3, dir: glam::Vec3) -> Option<(ObjectId, glam::Vec3)> {
        let (origin, dir) = (to_bevy(origin), to_bevy(dir));
        let mut best: Option<(f32, ObjectId)> = None;
        for (&id, o) in &self.objects {
            let half = to_bevy((o.spec.scale * 0.5).as_vec3());
            let c = to_bevy(o.spec.position.as_vec3());
            if let Some(t) = ray_box(origin, dir, c - half, c + half)
                && best.is_none_or(|(bt, _)| t < bt)
            {
                best = Some((t, id));
            }
        }
        best.map(|(t, id)| (id, to_sim(origin + dir * t)))
    }

    /// Overlay numbers.
    pub fn stats(&self) -> SimStats {
        let fragments = self
            .objects
            .values()
            .map(|o| o.fracture.fragments.len())
            .sum();
        SimStats {
            bodies: self.objects.len(),
            fragments,
            bonds_total: self.objects.values().map(|o| o.fracture.bonds.len()).sum(),
            bonds_broken: 0,
            step_ms: 0.0,
            time: self.time,
            running: self.running && !self.paused,
            paused: self.paused,
        }
    }
}

/// Whether a custom mesh file can be read (for the forms' validation).
pub fn check_custom_mesh(path: &Path) -> Result<(), String> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("obj" | "stl" | "glb" | "gltf") => {}
        _ => {
            return Err(format!(
                "'{}': expected an .obj, .stl, .gltf or .glb file",
                path.display()
            ));
        }
    }
    std::fs::metadata(path)
        .map_err(|e| format!("cannot read '{}': {e}", path.display()))
        .and_then(|m| {
            if m.is_file() {
                Ok(())
            } else {
                Err(format!("'{}' is not a file", path.display()))
            }
        })
}

fn ray_box(o: Vec3, d: Vec3, lo: Vec3, hi: Vec3) -> Option<f32> {
    let inv = d.recip();
    let t0 = (lo - o) * inv;
    let t1 = (hi - o) * inv;
    let tmin = t0.min(t1).max_element().max(0.0);
    let tmax = t0.max(t1).min_element();
    (tmin <= tmax).then_some(tmin)
}

/// STAND-IN fracture: the scaled unit box cut into a grid.
fn stand_in_fracture(spec: &ObjectSpec) -> Fracture {
    let n = [4u32, 3, 1];
    let size = spec.scale;
    let mut fragments = Vec::new();
    for i in 0..n[0] {
        for j in 0..n[1] {
            for k in 0..n[2] {
                let cell = DVec3::new(i as f64, j as f64, k as f64);
                let cnt = DVec3::new(n[0] as f64, n[1] as f64, n[2] as f64);
                let lo = size * (cell / cnt - 0.5);
                let hi = size * ((cell + 1.0) / cnt - 0.5);
                let on = [
                    i == 0,
                    i + 1 == n[0],
                    j == 0,
                    j + 1 == n[1],
                    k == 0,
                    k + 1 == n[2],
                ];
                fragments.push(box_fragment(lo, hi, on));
            }
        }
    }
    Fracture {
        fragments,
        bonds: Vec::new(),
    }
}

fn box_fragment(lo: DVec3, hi: DVec3, on_boundary: [bool; 6]) -> Fragment {
    let p = |x: bool, y: bool, z: bool| {
        DVec3::new(
            if x { hi.x } else { lo.x },
            if y { hi.y } else { lo.y },
            if z { hi.z } else { lo.z },
        )
    };
    let positions: Vec<DVec3> = (0..8)
        .map(|i| p(i & 1 != 0, i & 2 != 0, i & 4 != 0))
        .collect();
    // Faces -x, +x, -y, +y, -z, +z as two outward triangles each.
    let quads: [[u32; 4]; 6] = [
        [0, 4, 6, 2],
        [1, 3, 7, 5],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 2, 3, 1],
        [4, 5, 7, 6],
    ];
    let mut triangles = Vec::new();
    let mut interior = Vec::new();
    for (f, q) in quads.iter().enumerate() {
        triangles.push([q[0], q[1], q[2]]);
        triangles.push([q[0], q[2], q[3]]);
        interior.extend([!on_boundary[f]; 2]);
    }
    let mesh = TriMesh::new(positions, triangles);
    let volume = mesh.signed_volume();
    let centroid = mesh.centroid();
    Fragment {
        mesh,
        interior,
        convex_pieces: Vec::new(),
        volume,
        centroid,
        inertia: DMat3::IDENTITY,
    }
}
