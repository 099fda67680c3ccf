//! Parsing and validating a scene file into typed specs, and building its world.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use glam::Vec3;

use crate::error::SimError;

use shatter_geom::io::MemoryFiles;

use crate::object::{BondModel, ExplosionSpec, ObjectSpec, ProjectileSpec};
use crate::scene::checks::{Ctx, line_col, word};
use crate::scene::entries::{explosion, object, projectile};
use crate::scene::file::SceneFile;
use crate::world::{World, WorldSettings};

/// A validated scene: settings, objects and timed actions.
#[derive(Debug, Clone)]
pub struct Scene {
    /// World settings.
    pub settings: WorldSettings,
    /// Default run length for `shatter simulate` (s).
    pub seconds: f64,
    /// Objects, in file order.
    pub objects: Vec<ObjectSpec>,
    /// Projectiles with their firing times.
    pub projectiles: Vec<(f64, ProjectileSpec)>,
    /// Explosions with their times.
    pub explosions: Vec<(f64, ExplosionSpec)>,
}

impl Scene {
    /// Parses a scene from TOML text. Syntax errors, unknown keys and wrong types give
    /// [`SimError::SceneSyntax`] with the line and column; invalid values give errors
    /// naming the key and its line.
    ///
    /// ```
    /// let err = shatter_sim::scene::Scene::parse("[world]\ngravty = [0, -9.8, 0]\n").unwrap_err();
    /// assert!(err.to_string().contains("line 2"));
    /// assert!(err.to_string().contains("gravty"));
    /// ```
    pub fn parse(text: &str) -> Result<Scene, SimError> {
        Self::parse_in(text, None)
    }

    /// Reads and parses a scene file; mesh paths are relative to its folder.
    pub fn load(path: &Path) -> Result<Scene, SimError> {
        let text = std::fs::read_to_string(path).map_err(|e| SimError::Io {
            path: path.display().to_string(),
            source: e,
        })?;
        Self::parse_in(&text, path.parent().map(Path::to_path_buf))
    }

    fn parse_in(text: &str, dir: Option<PathBuf>) -> Result<Scene, SimError> {
        let file: SceneFile = toml::from_str(text).map_err(|e| {
            let (line, column) = e.span().map_or((0, 0), |s| line_col(text, s.start));
            let mut message = e.message().trim().to_string();
            // Type errors point at the value: name the key written before it (an unknown or
            // missing field's message names it already).
            if !message.contains("field `")
                && let Some(key) = text
                    .lines()
                    .nth(line.saturating_sub(1))
                    .and_then(|l| l.split_once('='))
                    .map(|(k, _)| k.trim())
                    .filter(|k| !k.is_empty())
            {
                message = format!("key `{key}`: {message}");
            }
            SimError::SceneSyntax {
                line,
                column,
                message,
            }
        })?;
        let ctx = Ctx { text, dir };
        let mut settings = WorldSettings::default();
        let w = &file.world;
        if let Some(g) = w.gravity {
            settings.gravity = Vec3::from(g);
        }
        if let Some(dt) = &w.dt {
            let v = *dt.get_ref();
            if !(v.is_finite() && v > 0.0 && v <= 0.1) {
                return Err(SimError::invalid(
                    ctx.key("world.dt", dt),
                    format!("must be in (0, 0.1] seconds, got {v}"),
                ));
            }
            settings.dt = v;
        }
        if let Some(m) = &w.bond_model {
            settings.bond_model = word(&ctx, "world.bond_model", m)?;
        }
        if let Some(g) = w.ground {
            settings.ground = g;
        }
        if let Some(b) = w.box_colliders {
            settings.box_colliders = b;
        }
        if let Some(b) = w.enclosed_colliders {
            settings.enclosed_colliders = b;
        }
        if let Some(b) = w.skip_held_contacts {
            settings.skip_held_contacts = b;
        }
        if let Some(b) = w.contact_speed_cap {
            settings.contact_speed_cap = b;
        }
        if let Some(m) = &w.max_debris {
            settings.max_debris = match m.get_ref() {
                toml::Value::Integer(n) if *n >= 0 => Some(*n as usize),
                toml::Value::String(s) if s == "none" => None,
                other => {
                    return Err(SimError::invalid(
                        ctx.key("world.max_debris", m),
                        format!("must be an integer ≥ 0 or \"none\", got {other}"),
                    ));
                }
            };
        }
        if let Some(v) = &w.max_launch_speed {
            let speed = *v.get_ref();
            if !(speed.is_finite() && speed > 0.0) {
                return Err(SimError::invalid(
                    ctx.key("world.max_launch_speed", v),
                    format!("must be a positive speed in m/s, got {speed}"),
                ));
            }
            settings.max_launch_speed = speed;
        }
        if let Some(v) = &w.tiny_debris {
            let size = *v.get_ref();
            if !(size.is_finite() && size >= 0.0) {
                return Err(SimError::invalid(
                    ctx.key("world.tiny_debris", v),
                    format!("must be a size ≥ 0 in metres, got {size}"),
                ));
            }
            settings.tiny_debris = size;
        }
        for (key, value, setting) in [
            (
                "world.stress_budget",
                &w.stress_budget,
                &mut settings.stress_budget,
            ),
            (
                "world.stress_spring_budget",
                &w.stress_spring_budget,
                &mut settings.stress_spring_budget,
            ),
            (
                "world.stress_build_budget",
                &w.stress_build_budget,
                &mut settings.stress_build_budget,
            ),
        ] {
            if let Some(b) = value {
                *setting = match b.get_ref() {
                    toml::Value::Integer(n) if *n >= 1 => Some(*n as usize),
                    toml::Value::String(s) if s == "none" => None,
                    other => {
                        return Err(SimError::invalid(
                            ctx.key(key, b),
                            format!("must be an integer ≥ 1 or \"none\", got {other}"),
                        ));
                    }
                };
            }
        }
        let seconds = match &w.seconds {
            Some(s) if !(s.get_ref().is_finite() && *s.get_ref() > 0.0) => {
                return Err(SimError::invalid(
                    ctx.key("world.seconds", s),
                    format!("must be positive, got {}", s.get_ref()),
                ));
            }
            Some(s) => *s.get_ref(),
            None => 3.0,
        };
        let objects = file
            .objects
            .iter()
            .enumerate()
            .map(|(i, o)| object(&ctx, &format!("objects[{i}]"), o))
            .collect::<Result<Vec<_>, _>>()?;
        let projectiles = file
            .projectiles
            .iter()
            .enumerate()
            .map(|(i, p)| projectile(&ctx, &format!("projectiles[{i}]"), p))
            .collect::<Result<Vec<_>, _>>()?;
        let explosions = file
            .explosions
            .iter()
            .enumerate()
            .map(|(i, e)| explosion(&ctx, &format!("explosions[{i}]"), e))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Scene {
            settings,
            seconds,
            objects,
            projectiles,
            explosions,
        })
    }

    /// Builds the world: objects added in file order (ids 0, 1, …), actions scheduled.
    /// `bond_model` overrides every object's model (the CLI's `--bonds`). Mesh files are
    /// read from the disk.
    pub fn build(&self, bond_model: Option<BondModel>) -> Result<World, SimError> {
        self.build_with_files(bond_model, Arc::default())
    }

    /// [`Scene::build`], the world reading mesh files from `files` before the disk
    /// ([`World::files`]).
    pub fn build_with_files(
        &self,
        bond_model: Option<BondModel>,
        files: Arc<MemoryFiles>,
    ) -> Result<World, SimError> {
        let mut settings = self.settings;
        if let Some(m) = bond_model {
            settings.bond_model = m;
        }
        let mut world = World::new(settings);
        world.set_files(files);
        for (i, spec) in self.objects.iter().enumerate() {
            let mut spec = spec.clone();
            if bond_model.is_some() {
                spec.bond_model = None;
            }
            world.add_object(spec).map_err(|e| match e {
                SimError::InvalidParameter { key, reason } => SimError::InvalidParameter {
                    key: key.replace(&format!("object {i}"), &format!("objects[{i}]")),
                    reason,
                },
                SimError::Fracture { key, source } => SimError::Fracture {
                    key: key.replace(&format!("object {i}"), &format!("objects[{i}]")),
                    source,
                },
                other => other,
            })?;
        }
        for (at, p) in &self.projectiles {
            world.schedule_projectile(*at, p.clone());
        }
        for (at, e) in &self.explosions {
            world.schedule_explosion(*at, *e);
        }
        Ok(world)
    }
}
