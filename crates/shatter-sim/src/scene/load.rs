//! Parsing and validating a scene file into typed specs, and building its world.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use glam::{EulerRot, Quat, Vec3};
use toml::Spanned;

use crate::error::SimError;
use crate::runtime::RuntimeFracture;
use std::str::FromStr;

use shatter_geom::io::MemoryFiles;
use shatter_geom::shapes::Shape;
use shatter_geom::vocab::UnknownWord;

use crate::material::Material;
use crate::object::{
    BondModel, ExplosionSpec, FractureParams, FractureSource, ObjectSpec, ProjectileShape,
    ProjectileSpec,
};
use crate::scene::file::{ExplosionEntry, ObjectEntry, ProjectileEntry, SceneFile};
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

/// 1-based line and column of byte `offset` in `text`.
pub fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let offset = offset.min(text.len());
    let before = text.get(..offset).unwrap_or(text);
    let line = before.matches('\n').count() + 1;
    let column = before.rsplit('\n').next().map_or(0, |s| s.chars().count()) + 1;
    (line, column)
}

/// Context for error messages: the source text (for lines) and the scene's folder.
struct Ctx<'a> {
    text: &'a str,
    dir: Option<PathBuf>,
}

impl Ctx<'_> {
    /// `key (line N)`.
    fn key<T>(&self, key: &str, spanned: &Spanned<T>) -> String {
        let (line, _) = line_col(self.text, spanned.span().start);
        format!("{key} (line {line})")
    }

    fn path(&self, p: &str) -> String {
        match &self.dir {
            Some(d) if Path::new(p).is_relative() => d.join(p).to_string_lossy().into_owned(),
            _ => p.to_string(),
        }
    }
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
            // Type errors point at the value: name the key written before it.
            if !message.contains('`')
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
        settings.max_debris = w.max_debris;
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

/// A vocabulary word (a method, a pattern, a bond model, ...) at `key`.
fn word<T: FromStr<Err = UnknownWord>>(
    ctx: &Ctx,
    key: &str,
    v: &Spanned<String>,
) -> Result<T, SimError> {
    v.get_ref()
        .parse()
        .map_err(|e: UnknownWord| SimError::invalid(ctx.key(key, v), e.to_string()))
}

/// An optional vocabulary word at `key`.
fn opt_word<T: FromStr<Err = UnknownWord>>(
    ctx: &Ctx,
    key: &str,
    v: &Option<Spanned<String>>,
) -> Result<Option<T>, SimError> {
    v.as_ref().map(|v| word(ctx, key, v)).transpose()
}

fn count(
    ctx: &Ctx,
    key: &str,
    v: &Option<Spanned<i64>>,
    min: i64,
    default: u32,
) -> Result<u32, SimError> {
    match v {
        None => Ok(default),
        Some(s) if *s.get_ref() < min || *s.get_ref() > u32::MAX as i64 => Err(SimError::invalid(
            ctx.key(key, s),
            format!("must be an integer >= {min}, got {}", s.get_ref()),
        )),
        Some(s) => Ok(*s.get_ref() as u32),
    }
}

fn positive(ctx: &Ctx, key: &str, v: &Spanned<f32>) -> Result<f32, SimError> {
    let x = *v.get_ref();
    if x.is_finite() && x > 0.0 {
        Ok(x)
    } else {
        Err(SimError::invalid(
            ctx.key(key, v),
            format!("must be positive, got {x}"),
        ))
    }
}

fn time(ctx: &Ctx, key: &str, v: &Option<Spanned<f64>>) -> Result<f64, SimError> {
    match v {
        None => Ok(0.0),
        Some(t) if t.get_ref().is_finite() && *t.get_ref() >= 0.0 => Ok(*t.get_ref()),
        Some(t) => Err(SimError::invalid(
            ctx.key(key, t),
            format!("must be >= 0, got {}", t.get_ref()),
        )),
    }
}

fn color(
    ctx: &Ctx,
    key: &str,
    v: &Option<Spanned<[f32; 3]>>,
    default: [f32; 3],
) -> Result<[f32; 3], SimError> {
    match v {
        None => Ok(default),
        Some(c) if c.get_ref().iter().all(|x| (0.0..=1.0).contains(x)) => Ok(*c.get_ref()),
        Some(c) => Err(SimError::invalid(
            ctx.key(key, c),
            format!("components must be in 0..=1, got {:?}", c.get_ref()),
        )),
    }
}

fn object(ctx: &Ctx, key: &str, o: &ObjectEntry) -> Result<ObjectSpec, SimError> {
    let mut material = match &o.material {
        Some(m) => Material::preset_or_error(m.get_ref(), &ctx.key(&format!("{key}.material"), m))?,
        None => Material::default(),
    };
    if let Some(d) = o.density {
        material.density = d;
    }
    if let Some(f) = o.friction {
        material.friction = f;
    }
    if let Some(r) = o.restitution {
        material.restitution = r;
    }
    roughness(ctx, key, o, &mut material.roughness)?;
    let method = opt_word(ctx, &format!("{key}.method"), &o.method)?;
    let pattern = opt_word(ctx, &format!("{key}.pattern"), &o.pattern)?;
    let defaults = FractureParams::default();
    let grid = match &o.grid {
        None => defaults.grid,
        Some(g) => {
            let v = *g.get_ref();
            if v.iter().any(|c| *c < 1 || *c > 1000) {
                return Err(SimError::invalid(
                    ctx.key(&format!("{key}.grid"), g),
                    format!("cell counts must be in 1..=1000, got {v:?}"),
                ));
            }
            v.map(|c| c as u32)
        }
    };
    let mut grid_voids = Vec::new();
    if let Some(v) = &o.grid_voids {
        for (i, b) in v.get_ref().iter().enumerate() {
            let ok = (0..3).all(|a| b[a] >= 0 && b[a] < b[a + 3] && b[a + 3] <= i64::from(grid[a]));
            if !ok {
                return Err(SimError::invalid(
                    ctx.key(&format!("{key}.grid_voids[{i}]"), v),
                    format!(
                        "must be [x0, y0, z0, x1, y1, z1] with 0 <= x0 < x1 <= {} (and so on \
                         for y and z, the grid's cell counts), got {b:?}",
                        grid[0]
                    ),
                ));
            }
            grid_voids.push(b.map(|c| c as u32));
        }
    }
    let params = FractureParams {
        method,
        pattern,
        pieces: count(ctx, &format!("{key}.pieces"), &o.pieces, 1, defaults.pieces)?,
        random_vertices: count(
            ctx,
            &format!("{key}.random_vertices"),
            &o.random_vertices,
            0,
            defaults.random_vertices,
        )?,
        skip: count(ctx, &format!("{key}.skip"), &o.skip, 0, defaults.skip)?,
        center: o.center.unwrap_or(defaults.center),
        placement: opt_word(ctx, &format!("{key}.placement"), &o.placement)?
            .unwrap_or(defaults.placement),
        seed: o.seed.unwrap_or(defaults.seed),
        grid,
        grid_voids,
    };
    let source = match (&o.shape, &o.mesh) {
        (Some(_), Some(_)) => {
            return Err(SimError::invalid(
                format!("{key}.mesh"),
                "give either shape or mesh, not both",
            ));
        }
        (Some(s), None) => FractureSource::Shape {
            shape: s.get_ref().parse().map_err(|_| SimError::UnknownShape {
                key: ctx.key(&format!("{key}.shape"), s),
                name: s.get_ref().clone(),
            })?,
            params,
        },
        (None, Some(m)) => FractureSource::MeshFile {
            path: ctx.path(m),
            params,
        },
        (None, None) => FractureSource::Shape {
            shape: Shape::Cube,
            params,
        },
    };
    let break_force = o
        .break_force
        .as_ref()
        .map(|b| positive(ctx, &format!("{key}.break_force"), b))
        .transpose()?;
    let last = o
        .last
        .as_ref()
        .map(|l| positive(ctx, &format!("{key}.last"), l))
        .transpose()?;
    let scale = match &o.scale {
        None => Vec3::ONE,
        Some(s) => {
            let v = Vec3::from(*s.get_ref());
            if !(v.is_finite() && v.min_element() > 0.0) {
                return Err(SimError::invalid(
                    ctx.key(&format!("{key}.scale"), s),
                    format!("every component must be positive, got {:?}", s.get_ref()),
                ));
            }
            v
        }
    };
    let r = o.rotation.unwrap_or([0.0; 3]).map(f32::to_radians);
    let spec = ObjectSpec {
        name: o.name.clone().unwrap_or_else(|| key.to_string()),
        source,
        material,
        break_force,
        position: Vec3::from(o.position.unwrap_or([0.0, 10.0, 0.0])),
        rotation: Quat::from_euler(EulerRot::XYZ, r[0], r[1], r[2]),
        scale,
        color: color(ctx, &format!("{key}.color"), &o.color, [0.7, 0.7, 0.7])?,
        last,
        bond_model: o
            .bond_model
            .as_ref()
            .map(|m| word(ctx, &format!("{key}.bond_model"), m))
            .transpose()?,
        anchored: o.anchored.unwrap_or(false),
        runtime: runtime_fracture(ctx, key, o)?,
    };
    spec.validate(key)?;
    Ok(spec)
}

/// The object's `roughness`, `roughness_frequency` and `roughness_octaves` over the
/// material's roughness (a material without any, like glass, keeps its frequency of 4
/// per metre and 3 octaves when only `roughness` is given).
fn roughness(
    ctx: &Ctx,
    key: &str,
    o: &ObjectEntry,
    r: &mut shatter_geom::fracture::Roughness,
) -> Result<(), SimError> {
    if let Some(a) = &o.roughness {
        let v = *a.get_ref();
        if !(v.is_finite() && v >= 0.0) {
            return Err(SimError::invalid(
                ctx.key(&format!("{key}.roughness"), a),
                format!("must be a number of metres >= 0 (0: flat cut faces), got {v}"),
            ));
        }
        r.amplitude = f64::from(v);
    }
    if let Some(f) = &o.roughness_frequency {
        r.frequency = f64::from(positive(ctx, &format!("{key}.roughness_frequency"), f)?);
    }
    let max = shatter_geom::fracture::Roughness::MAX_OCTAVES;
    if let Some(n) = &o.roughness_octaves {
        let v = *n.get_ref();
        if !(1..=i64::from(max)).contains(&v) {
            return Err(SimError::invalid(
                ctx.key(&format!("{key}.roughness_octaves"), n),
                format!("must be 1..={max}, got {v}"),
            ));
        }
        r.octaves = v as u32;
    }
    Ok(())
}

/// The object's runtime-fracture keys: `fracture`, `fracture_impulse`, `depth`,
/// `min_size`.
fn runtime_fracture(ctx: &Ctx, key: &str, o: &ObjectEntry) -> Result<RuntimeFracture, SimError> {
    let d = RuntimeFracture::default();
    let min_size = match &o.min_size {
        None => d.min_size,
        Some(v) if v.get_ref().is_finite() && *v.get_ref() >= 0.0 => *v.get_ref(),
        Some(v) => {
            return Err(SimError::invalid(
                ctx.key(&format!("{key}.min_size"), v),
                format!("must be a number of metres >= 0, got {}", v.get_ref()),
            ));
        }
    };
    let depth = count(ctx, &format!("{key}.depth"), &o.depth, 1, d.depth)?;
    if depth > crate::runtime::MAX_DEPTH {
        let span = o.depth.as_ref().map_or_else(
            || format!("{key}.depth"),
            |v| ctx.key(&format!("{key}.depth"), v),
        );
        return Err(SimError::invalid(
            span,
            format!("must be 1..={}, got {depth}", crate::runtime::MAX_DEPTH),
        ));
    }
    Ok(RuntimeFracture {
        timing: opt_word(ctx, &format!("{key}.fracture"), &o.fracture)?.unwrap_or(d.timing),
        impulse: o
            .fracture_impulse
            .as_ref()
            .map(|v| positive(ctx, &format!("{key}.fracture_impulse"), v))
            .transpose()?,
        depth,
        min_size,
    })
}

fn projectile(
    ctx: &Ctx,
    key: &str,
    p: &ProjectileEntry,
) -> Result<(f64, ProjectileSpec), SimError> {
    let d = ProjectileSpec::default();
    let shape = match (&p.shape, &p.mesh) {
        (_, Some(m)) => {
            let path = ctx.path(m);
            let mesh = shatter_geom::io::load_mesh(&path).map_err(|e| SimError::mesh(&path, e))?;
            ProjectileShape::Custom(mesh.positions)
        }
        (Some(s), None) => {
            ProjectileShape::from_name(s.get_ref()).ok_or_else(|| SimError::UnknownShape {
                key: ctx.key(&format!("{key}.shape"), s),
                name: s.get_ref().clone(),
            })?
        }
        (None, None) => d.shape.clone(),
    };
    let speed = match &p.speed {
        None => d.speed,
        Some(s) if s.get_ref().is_finite() && *s.get_ref() >= 0.0 => *s.get_ref(),
        Some(s) => {
            return Err(SimError::invalid(
                ctx.key(&format!("{key}.speed"), s),
                format!("must be >= 0, got {}", s.get_ref()),
            ));
        }
    };
    let spec = ProjectileSpec {
        shape,
        size: p
            .size
            .as_ref()
            .map(|s| positive(ctx, &format!("{key}.size"), s))
            .transpose()?
            .unwrap_or(d.size),
        density: p
            .density
            .as_ref()
            .map(|s| positive(ctx, &format!("{key}.density"), s))
            .transpose()?
            .unwrap_or(d.density),
        speed,
        color: color(ctx, &format!("{key}.color"), &p.color, d.color)?,
        last: match &p.last {
            None => d.last,
            Some(l) => Some(positive(ctx, &format!("{key}.last"), l)?),
        },
        from: Vec3::from(p.from),
        to: Vec3::from(p.to),
    };
    spec.validate(key)?;
    Ok((time(ctx, &format!("{key}.at"), &p.at)?, spec))
}

fn explosion(ctx: &Ctx, key: &str, e: &ExplosionEntry) -> Result<(f64, ExplosionSpec), SimError> {
    let radius = positive(ctx, &format!("{key}.radius"), &e.radius)?;
    let power = *e.power.get_ref();
    if !(power.is_finite() && power >= 0.0) {
        return Err(SimError::invalid(
            ctx.key(&format!("{key}.power"), &e.power),
            format!("must be >= 0, got {power}"),
        ));
    }
    let spec = ExplosionSpec {
        position: Vec3::from(e.position),
        radius,
        power,
    };
    spec.validate(key)?;
    Ok((time(ctx, &format!("{key}.at"), &e.at)?, spec))
}
