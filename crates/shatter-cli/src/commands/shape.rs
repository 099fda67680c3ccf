//! `shatter shape`: export a built-in shape as OBJ or GLB.

use std::path::PathBuf;

use clap::Args;
use shatter_geom::DVec3;

use shatter_geom::shapes::Shape;

use crate::args::{MeshFormat, check_writable, parse_vec3, validate_scale};
use crate::context::Context;
use crate::error::CliError;
use shatter_lab::fracture;

/// Arguments of `shatter shape`.
#[derive(Debug, Args)]
pub struct ShapeArgs {
    /// The shape.
    #[arg(value_enum, value_name = "NAME")]
    pub name: Shape,
    /// Output file, `.obj` or `.glb`.
    #[arg(long, value_name = "FILE.obj|FILE.glb")]
    pub out: PathBuf,
    /// Scale along x, y and z (each greater than 0).
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_vec3, allow_hyphen_values = true)]
    pub scale: Option<DVec3>,
}

struct Config {
    name: Shape,
    out: PathBuf,
    format: MeshFormat,
    scale: DVec3,
}

impl ShapeArgs {
    fn validate(&self) -> Result<Config, CliError> {
        let scale = validate_scale(self.scale)?;
        let format = MeshFormat::from_output_path(&self.out)?;
        let out = check_writable(&self.out)?;
        Ok(Config {
            name: self.name,
            out,
            format,
            scale,
        })
    }
}

/// Runs `shatter shape`.
pub fn run(args: &ShapeArgs, ctx: &Context) -> Result<(), CliError> {
    let config = args.validate()?;
    let mesh = fracture::scaled(fracture::builtin_shape(config.name)?, config.scale);
    shatter_lab::export::write_mesh(&config.out, config.format, &mesh, &ctx.progress)?;
    println!(
        "wrote {} ({} vertices, {} triangles, volume {}) to {}",
        config.name,
        mesh.positions.len(),
        mesh.triangles.len(),
        volume_text(&mesh),
        config.out.display()
    );
    Ok(())
}

/// The mesh's volume as text: `{:.6}` when `f64` holds it at full precision, otherwise
/// its order of magnitude ("about 1e900, beyond the range of f64").
fn volume_text(mesh: &shatter_geom::TriMesh) -> String {
    let v = mesh.signed_volume();
    if v.is_finite() && (v == 0.0 || v.abs() >= f64::MIN_POSITIVE) {
        return format!("{v:.6}");
    }
    let (m, e) = mesh.signed_volume_exp2();
    let log10 = m.abs().log10() + f64::from(e) * std::f64::consts::LOG10_2;
    format!("about 1e{:.0}, beyond the range of f64", log10)
}
