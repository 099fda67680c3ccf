//! `shatter inspect`: what a mesh file holds and what repair would do, without fracturing.

use std::path::PathBuf;

use clap::Args;
use shatter_geom::io::{self, Inspection};

use crate::error::{CliError, ResultExt};

/// Arguments of `shatter inspect`.
#[derive(Debug, Args)]
pub struct InspectArgs {
    /// Mesh file: .obj, .stl, .gltf or .glb.
    #[arg(value_name = "MESH")]
    pub mesh: PathBuf,
    /// Print one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
}

/// Runs `shatter inspect`.
pub fn run(args: &InspectArgs) -> Result<(), CliError> {
    if args.mesh.is_dir() {
        return Err(CliError::input(format!(
            "{}: is a folder: inspect takes one mesh file (.obj, .stl, .gltf or .glb)",
            args.mesh.display()
        )));
    }
    let loaded = shatter_lab::fracture::load_model(&args.mesh)?;
    let report = io::inspect(&loaded);
    let extension = super::fracture_asset::inspect(&args.mesh);
    if args.json {
        let mut value = serde_json::to_value(&report).internal_err("cannot encode the report")?;
        value["file"] = serde_json::json!(args.mesh.display().to_string());
        if let Some(e) = &extension {
            value["shatter_fracture"] =
                serde_json::to_value(e).internal_err("cannot encode the report")?;
        }
        println!("{value}");
    } else {
        print!("{}", text(&args.mesh.display().to_string(), &report));
        if let Some(e) = &extension {
            println!("{}", super::fracture_asset::text(e));
        }
    }
    Ok(())
}

fn plural(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

/// The report as text, one fact a line.
fn text(file: &str, r: &Inspection) -> String {
    let mut out = String::new();
    let mut line = |s: String| {
        out.push_str(&s);
        out.push('\n');
    };
    line(format!(
        "{file}: {}, {}",
        plural(r.triangles, "triangle", "triangles"),
        plural(r.vertices, "vertex", "vertices")
    ));
    let closed = r.shells.iter().filter(|s| s.closed).count();
    line(format!(
        "shells: {} ({closed} closed, {} open), {}",
        r.shells.len(),
        r.shells.len() - closed,
        plural(r.holes, "hole", "holes")
    ));
    for (i, s) in r.shells.iter().enumerate().take(10) {
        let state = if s.closed {
            format!("closed, volume {:.6}", s.signed_volume)
        } else {
            format!("open, {}", plural(s.holes, "hole", "holes"))
        };
        let mut extra = String::new();
        if s.non_manifold_edges > 0 {
            extra += &format!(", {} non-manifold edges", s.non_manifold_edges);
        }
        if s.inconsistent_edges > 0 {
            extra += &format!(", {} inconsistently wound edges", s.inconsistent_edges);
        }
        line(format!(
            "  shell {i}: {}, {state}{extra}",
            plural(s.triangles, "triangle", "triangles")
        ));
    }
    if r.shells.len() > 10 {
        line(format!("  ... {} more shells", r.shells.len() - 10));
    }
    if r.degenerate_triangles > 0 {
        line(format!("degenerate triangles: {}", r.degenerate_triangles));
    }
    line(format!(
        "volume: {:.6}{}",
        r.signed_volume,
        if r.solid {
            " (a valid solid: fractures as it is)"
        } else {
            " (not a valid solid as it is)"
        }
    ));
    if let Some((lo, hi)) = r.bounds {
        line(format!(
            "bounds: [{}, {}, {}] .. [{}, {}, {}]",
            lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]
        ));
    }
    line(format!(
        "materials: {}",
        plural(r.materials.len(), "material", "materials")
    ));
    for m in &r.materials {
        let [cr, cg, cb, ca] = m.base_color;
        line(format!(
            "  {}: {}, base colour {cr} {cg} {cb} {ca}{}",
            m.name,
            plural(m.triangles, "triangle", "triangles"),
            m.texture
                .as_ref()
                .map(|t| format!(", texture {t}"))
                .unwrap_or_default()
        ));
    }
    line(format!(
        "attributes: {} UV set{}, normals {}, colours {}",
        r.uv_sets,
        if r.uv_sets == 1 { "" } else { "s" },
        if r.normals { "yes" } else { "no" },
        if r.colors { "yes" } else { "no" }
    ));
    for w in &r.warnings {
        line(format!("warning: {w}"));
    }
    if r.repair.is_empty() {
        line("repair: nothing to repair".to_string());
    } else {
        for step in &r.repair {
            line(format!("repair: {step}"));
        }
    }
    out
}
