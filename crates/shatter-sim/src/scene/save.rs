//! Writing a world back as a scene file (the app's Save).

use glam::EulerRot;
use toml::Spanned;

use crate::error::SimError;
use crate::material::{MaterialPreset, MethodKind, Pattern};
use crate::object::FractureSource;
use crate::runtime::FractureTiming;
use crate::scene::file::{ExplosionEntry, ObjectEntry, ProjectileEntry, SceneFile, WorldSection};
use crate::world::World;
use crate::world::state::Action;

fn sp<T>(v: T) -> Spanned<T> {
    Spanned::new(0..0, v)
}

impl World {
    /// The world's objects, settings and scheduled actions as a scene file (TOML).
    /// Loading it gives the same initial state. Objects built from a prebuilt fracture and
    /// custom-mesh projectiles cannot be written (their geometry is not a file).
    pub fn to_scene_toml(&self) -> Result<String, SimError> {
        let s = &self.settings;
        let mut file = SceneFile {
            world: WorldSection {
                gravity: Some(s.gravity.to_array()),
                dt: Some(sp(s.dt)),
                bond_model: Some(sp(s.bond_model.name().to_string())),
                ground: Some(s.ground),
                box_colliders: Some(s.box_colliders),
                enclosed_colliders: Some(s.enclosed_colliders),
                skip_held_contacts: Some(s.skip_held_contacts),
                contact_speed_cap: Some(s.contact_speed_cap),
                max_debris: Some(sp(budget_value(s.max_debris))),
                max_launch_speed: Some(sp(s.max_launch_speed)),
                tiny_debris: Some(sp(s.tiny_debris)),
                stress_budget: Some(sp(budget_value(s.stress_budget))),
                stress_spring_budget: Some(sp(budget_value(s.stress_spring_budget))),
                stress_build_budget: Some(sp(budget_value(s.stress_build_budget))),
                seconds: None,
            },
            ..SceneFile::default()
        };
        for (id, record) in &self.objects {
            if record.parent.is_some() {
                // Cut at runtime: the object it came from is saved whole.
                continue;
            }
            let spec = &record.spec;
            let on_impact = spec.runtime.timing == FractureTiming::OnImpact;
            let (shape, mesh, params) = match &spec.source {
                FractureSource::Shape { shape, params } => {
                    (Some(sp(shape.to_string())), None, params)
                }
                FractureSource::MeshFile { path, params } => (None, Some(path.clone()), params),
                FractureSource::Prebuilt(_) => {
                    return Err(SimError::invalid(
                        format!("object {}", id.0),
                        "built from a prebuilt fracture, which a scene file cannot hold",
                    ));
                }
            };
            let (x, y, z) = spec.rotation.to_euler(EulerRot::XYZ);
            let preset = MaterialPreset::of(&spec.material);
            let rough = spec.material.roughness;
            let own_rough =
                (preset.map(|p| p.material().roughness) != Some(rough)).then_some(rough);
            file.objects.push(ObjectEntry {
                name: Some(spec.name.clone()),
                shape,
                mesh,
                // An on_impact object is cut by radial Voronoi cells (the only ones it
                // accepts), whatever its material's default method.
                method: Some(sp(if on_impact {
                    MethodKind::Voronoi.to_string()
                } else {
                    params.method.unwrap_or(spec.material.method).to_string()
                })),
                pattern: Some(sp(if on_impact {
                    Pattern::Radial.to_string()
                } else {
                    params.pattern.unwrap_or(spec.material.pattern).to_string()
                })),
                pieces: Some(sp(params.pieces as i64)),
                grid: Some(sp(params.grid.map(i64::from))),
                grid_voids: (!params.grid_voids.is_empty())
                    .then(|| sp(params.grid_voids.iter().map(|b| b.map(i64::from)).collect())),
                random_vertices: Some(sp(params.random_vertices as i64)),
                skip: Some(sp(params.skip as i64)),
                center: Some(params.center),
                placement: Some(sp(params.placement.to_string())),
                seed: Some(params.seed),
                // The preset, then what the object overrides: without it a glass pane
                // came back as stone (its strengths, wear and rough faces).
                material: preset.map(|p| sp(p.to_string())),
                density: Some(spec.material.density),
                friction: Some(spec.material.friction),
                restitution: Some(spec.material.restitution),
                break_force: Some(sp(spec.effective_break_force())),
                last: spec.last.map(sp),
                color: Some(sp(spec.color)),
                position: Some(spec.position.to_array()),
                rotation: Some([x, y, z].map(f32::to_degrees)),
                scale: Some(sp(spec.scale.to_array())),
                bond_model: spec.bond_model.map(|m| sp(m.name().to_string())),
                anchored: Some(spec.anchored),
                fracture: Some(sp(spec.runtime.timing.to_string())),
                fracture_impulse: spec.runtime.impulse.map(sp),
                depth: Some(sp(i64::from(spec.runtime.depth))),
                min_size: Some(sp(spec.runtime.min_size)),
                // Only a roughness of the object's own (the keys read in f32, which
                // would round a preset's f64 values).
                roughness: own_rough.map(|r| sp(r.amplitude as f32)),
                roughness_frequency: own_rough.map(|r| sp(r.frequency as f32)),
                roughness_octaves: own_rough.map(|r| sp(i64::from(r.octaves))),
            });
        }
        for (at, action) in &self.schedule {
            match action {
                Action::Fire(p) => {
                    let Some(shape) = p.shape.shape() else {
                        return Err(SimError::invalid(
                            "projectiles",
                            "a custom-mesh projectile cannot be written (its mesh is not a file)",
                        ));
                    };
                    file.projectiles.push(ProjectileEntry {
                        at: Some(sp(*at)),
                        shape: Some(sp(shape.to_string())),
                        mesh: None,
                        size: Some(sp(p.size)),
                        density: Some(sp(p.density)),
                        speed: Some(sp(p.speed)),
                        color: Some(sp(p.color)),
                        last: p.last.map(sp),
                        from: p.from.to_array(),
                        to: p.to.to_array(),
                    });
                }
                Action::Explode(e) => file.explosions.push(ExplosionEntry {
                    at: Some(sp(*at)),
                    position: e.position.to_array(),
                    radius: sp(e.radius),
                    power: sp(e.power),
                }),
            }
        }
        toml::to_string(&file).map_err(|e| SimError::invalid("scene", e.to_string()))
    }
}

/// A budget as the scene file writes it: an integer, or `"none"`.
fn budget_value(budget: Option<usize>) -> toml::Value {
    match budget {
        Some(n) => toml::Value::Integer(n as i64),
        None => toml::Value::String("none".to_string()),
    }
}
