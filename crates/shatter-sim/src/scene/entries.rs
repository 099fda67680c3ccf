//! One scene entry at a time: an object, a projectile or an explosion, its values
//! checked and named by their keys (`objects[2].scale`), into the simulation's specs.

use glam::{EulerRot, Quat, Vec3};

use shatter_geom::shapes::Shape;

use crate::error::SimError;
use crate::material::Material;
use crate::object::{
    ExplosionSpec, FractureParams, FractureSource, ObjectSpec, ProjectileShape, ProjectileSpec,
};
use crate::runtime::RuntimeFracture;
use crate::scene::checks::{Ctx, color, count, opt_word, positive, time, word};
use crate::scene::file::{ExplosionEntry, ObjectEntry, ProjectileEntry};

pub(super) fn object(ctx: &Ctx, key: &str, o: &ObjectEntry) -> Result<ObjectSpec, SimError> {
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

pub(super) fn projectile(
    ctx: &Ctx,
    key: &str,
    p: &ProjectileEntry,
) -> Result<(f64, ProjectileSpec), SimError> {
    let d = ProjectileSpec::default();
    let shape = match (&p.shape, &p.mesh) {
        (_, Some(m)) => {
            let path = ctx.path(m);
            let mesh = shatter_geom::io::load_mesh(&path).map_err(|e| SimError::mesh(&path, e))?;
            // As the Fire panel makes it: centred, its largest extent `size` metres.
            ProjectileShape::from_mesh(&mesh).ok_or_else(|| {
                SimError::invalid(
                    format!("{key}.mesh"),
                    format!("{path} has no extent to scale to `size`"),
                )
            })?
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

pub(super) fn explosion(
    ctx: &Ctx,
    key: &str,
    e: &ExplosionEntry,
) -> Result<(f64, ExplosionSpec), SimError> {
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
