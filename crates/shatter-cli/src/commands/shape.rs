//! `shatter shape`: export a built-in shape as OBJ or GLB.

use std::path::PathBuf;

use clap::Args;
use shatter_geom::DVec3;

use crate::args::{MeshFormat, ShapeName, check_writable, parse_vec3, validate_scale};
use crate::context::Context;
use crate::error::CliError;
use crate::library;

/// Arguments of `shatter shape`.
#[derive(Debug, Args)]
pub struct ShapeArgs {
    /// The shape.
    #[arg(value_enum, value_name = "NAME")]
    pub name: ShapeName,
    /// Output file, `.obj` or `.glb`.
    #[arg(long, value_name = "FILE.obj|FILE.glb")]
    pub out: PathBuf,
    /// Scale along x, y and z (each greater than 0).
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_vec3, allow_hyphen_values = true)]
    pub scale: Option<DVec3>,
}

struct Config {
    name: ShapeName,
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
    let mesh = library::scaled(library::builtin_shape(config.name)?, config.scale);
    library::write_mesh(&config.out, config.format, &mesh, &ctx.progress)?;
    println!(
        "wrote {} ({} vertices, {} triangles, volume {:.6}) to {}",
        config.name,
        mesh.positions.len(),
        mesh.triangles.len(),
        mesh.signed_volume(),
        config.out.display()
    );
    Ok(())
}
