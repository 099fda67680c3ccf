//! `shatter fracture`: cut a mesh into bonded fragments.

use std::path::PathBuf;

use clap::{ArgGroup, Args, ValueEnum};
use shatter_geom::DVec3;
use shatter_geom::fracture::{Method, MethodKind, Pattern, Placement, Seeds};
use shatter_geom::shapes::Shape;
use shatter_lab::fracture::{
    FractureConfig, FractureReport, MeshSource, check_fracture, fracture_timed, load_source,
};
use shatter_lab::memory;

use crate::args::{MeshFormat, check_writable, parse_cells, parse_vec3, validate_scale};
use crate::commands::tetrahedralize::check_points_file;
use crate::context::Context;
use crate::error::{CliError, ResultExt};
use crate::points_file::read_points_file;

/// Arguments of `shatter fracture`.
#[derive(Debug, Args)]
#[command(group(ArgGroup::new("source").required(true).args(["meshes", "shape"])))]
pub struct FractureArgs {
    /// Mesh file: .obj, .stl or .glb/.gltf, repaired first (cracks welded, holes filled,
    /// shells oriented, loose sheets dropped, crossing parts united; see --strict).
    /// Several files or folders (their mesh files) fracture them all, in parallel, into
    /// --out-dir.
    #[arg(value_name = "MESH")]
    pub meshes: Vec<PathBuf>,
    /// A built-in shape instead of a file.
    #[arg(long, value_enum, value_name = "NAME")]
    pub shape: Option<Shape>,
    /// Scale along x, y and z (each greater than 0), applied before fracturing.
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_vec3, allow_hyphen_values = true)]
    pub scale: Option<DVec3>,
    /// Fracture method.
    #[arg(long, value_enum, default_value_t = MethodKind::Voronoi)]
    pub method: MethodKind,
    /// grid: cells along x, y and z of the mesh's bounding box (bricks of a box, cells
    /// clipped to any other mesh) [default: 4,4,4].
    #[arg(long, value_name = "NX,NY,NZ", value_parser = parse_cells)]
    pub grid: Option<[u32; 3]>,
    /// Number of pieces (voronoi seeds or slice planes) [default: 20 voronoi, 4 slice].
    #[arg(long, value_name = "K")]
    pub pieces: Option<usize>,
    /// tetra: number of random points added to the surface vertices [default: 50].
    #[arg(long, value_name = "N")]
    pub random_vertices: Option<usize>,
    /// tetra: use only every (S+1)-th surface vertex [default: 0].
    #[arg(long, value_name = "S")]
    pub skip: Option<usize>,
    /// tetra: also add the mesh's centre.
    #[arg(long)]
    pub center: bool,
    /// tetra: where random points go [default: interior].
    #[arg(long, value_enum)]
    pub placement: Option<Placement>,
    /// voronoi: seed pattern [default: uniform].
    #[arg(long, value_enum)]
    pub pattern: Option<Pattern>,
    /// voronoi radial: the impact point [default: the mesh's centroid].
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_vec3, allow_hyphen_values = true)]
    pub impact: Option<DVec3>,
    /// voronoi: read the seeds from a points file instead of generating them.
    #[arg(long, value_name = "POINTS.xyz", conflicts_with_all = ["pieces", "pattern"])]
    pub seeds_file: Option<PathBuf>,
    /// Random seed.
    #[arg(long, value_name = "S", default_value_t = 0)]
    pub seed: u64,
    /// Write the fragments: .obj (one object per fragment) or .glb (one node per fragment).
    #[arg(long, value_name = "FILE.obj|FILE.glb")]
    pub out: Option<PathBuf>,
    /// Batch: write one output per input into this folder, and summary.json.
    #[arg(long, value_name = "DIR", conflicts_with = "out")]
    pub out_dir: Option<PathBuf>,
    /// Batch: the outputs' format [default: glb].
    #[arg(long, value_enum, value_name = "FORMAT")]
    pub out_format: Option<OutFormat>,
    /// Batch: files fractured at once [default: the number of cores].
    #[arg(long, value_name = "N")]
    pub jobs: Option<usize>,
    /// Refuse a mesh that is not already a closed, manifold solid instead of repairing
    /// it (an inward-wound mesh is still flipped).
    #[arg(long)]
    pub strict: bool,
    /// Print one JSON object with counts, volumes and the time.
    #[arg(long)]
    pub json: bool,
    /// With --json: also list every bond (`bond_list`: fragments a < b, area, centroid,
    /// normal from a to b).
    #[arg(long, requires = "json")]
    pub json_bonds: bool,
    /// Check the result with `Fracture::validate` (closed 2-manifold fragments, volumes
    /// adding up to the mesh's within 1e-9, a well-formed bond graph); a failed check is
    /// an internal error (exit code 1) naming the fragment and edge.
    #[arg(long)]
    pub validate: bool,
    /// What a .glb's SHATTER_fracture extension carries beyond the geometry.
    #[command(flatten)]
    pub asset: super::fracture_asset::AssetArgs,
}

/// Output format of a batch.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum OutFormat {
    /// Wavefront OBJ (with MTL).
    Obj,
    /// Binary glTF.
    Glb,
}

impl FractureArgs {
    /// Whether this is a batch: several inputs, a folder, or --out-dir.
    pub fn is_batch(&self) -> bool {
        self.meshes.len() > 1 || self.out_dir.is_some() || self.meshes.iter().any(|p| p.is_dir())
    }
}

impl FractureArgs {
    /// Validates the arguments into a configuration and the optional output.
    pub(crate) fn validate(
        &self,
        ctx: &Context,
    ) -> Result<(FractureConfig, Option<(PathBuf, MeshFormat)>), CliError> {
        let source = match (self.meshes.as_slice(), self.shape) {
            ([path], None) => MeshSource::File(path.clone()),
            ([], Some(shape)) => MeshSource::Shape(shape),
            ([_, _, ..], None) => MeshSource::File(self.meshes[0].clone()),
            _ => return Err(CliError::input("give either a MESH file or --shape")),
        };
        if !self.is_batch() && (self.out_format.is_some() || self.jobs.is_some()) {
            return Err(CliError::input(
                "--out-format and --jobs apply to a batch (several MESH files, a folder, or --out-dir)",
            ));
        }
        if self.is_batch() && self.validate {
            return Err(CliError::input(
                "--validate applies to one MESH or --shape, not to a batch",
            ));
        }
        let scale = validate_scale(self.scale)?;
        let method = self.method;
        let refuse = |flag: &str, applies_to: MethodKind| {
            CliError::input(format!(
                "{flag} applies to --method {applies_to}, not --method {}",
                method.name()
            ))
        };
        if method != MethodKind::Tetra {
            if self.random_vertices.is_some() {
                return Err(refuse("--random-vertices", MethodKind::Tetra));
            }
            if self.skip.is_some() {
                return Err(refuse("--skip", MethodKind::Tetra));
            }
            if self.center {
                return Err(refuse("--center", MethodKind::Tetra));
            }
            if self.placement.is_some() {
                return Err(refuse("--placement", MethodKind::Tetra));
            }
        }
        if method != MethodKind::Voronoi {
            if self.pattern.is_some() {
                return Err(refuse("--pattern", MethodKind::Voronoi));
            }
            if self.impact.is_some() {
                return Err(refuse("--impact", MethodKind::Voronoi));
            }
            if self.seeds_file.is_some() {
                return Err(refuse("--seeds-file", MethodKind::Voronoi));
            }
        }
        if method != MethodKind::Grid && self.grid.is_some() {
            return Err(refuse("--grid", MethodKind::Grid));
        }
        if method == MethodKind::Grid && self.pieces.is_some() {
            return Err(CliError::input(
                "--pieces applies to --method voronoi and slice; \
                 --method grid makes one fragment per cell (see --grid)",
            ));
        }
        if method == MethodKind::Tetra && self.pieces.is_some() {
            return Err(CliError::input(
                "--pieces applies to --method voronoi and slice; \
                 --method tetra makes one fragment per tetrahedron (see --random-vertices)",
            ));
        }
        if self.pieces == Some(0) {
            return Err(CliError::input("--pieces 0: at least 1 piece is needed"));
        }
        if self.impact.is_some() && self.pattern != Some(Pattern::Radial) {
            return Err(CliError::input("--impact applies to --pattern radial only"));
        }
        let method = match method {
            MethodKind::Tetra => Method::Tetra {
                random_vertices: self.random_vertices.unwrap_or(50),
                skip: self.skip.unwrap_or(0),
                center: self.center,
                placement: self.placement.unwrap_or(Placement::Interior),
            },
            MethodKind::Voronoi => {
                let seeds = match &self.seeds_file {
                    Some(path) => {
                        check_points_file(ctx, "--seeds-file", path)?;
                        Seeds::Points(read_points_file(path).map_err(CliError::input)?)
                    }
                    None => Seeds::Pattern {
                        count: self.pieces.unwrap_or(20),
                        pattern: self.pattern.unwrap_or(Pattern::Uniform),
                        impact: self.impact,
                    },
                };
                Method::Voronoi { seeds }
            }
            MethodKind::Slice => Method::Slice {
                pieces: self.pieces.unwrap_or(4),
                planes: None,
            },
            MethodKind::Grid => Method::Grid {
                cells: self.grid.unwrap_or([4, 4, 4]),
                voids: Vec::new(),
            },
        };
        let out = match &self.out {
            Some(path) => {
                let format = MeshFormat::from_output_path(path)?;
                Some((check_writable(path)?, format))
            }
            None => None,
        };
        Ok((
            FractureConfig {
                source,
                scale,
                method,
                seed: self.seed,
                strict: self.strict,
                // Without an output file, none are needed.
                convex_pieces: out.as_ref().is_some_and(|(_, f)| f.carries_convex_pieces()),
            },
            out,
        ))
    }
}

/// Runs `shatter fracture` on one mesh or shape (`main` sends a batch to
/// [`super::batch::run`]).
pub fn run(args: &FractureArgs, ctx: &Context) -> Result<(), CliError> {
    args.asset.check(args.out.as_deref(), false)?;
    let (config, out) = args.validate(ctx)?;
    let (model, mut warnings) = load_source(&config)?;
    let mesh = &model.mesh;
    let estimate = check_fracture(ctx, mesh, &config)?;
    ctx.progress.check()?;
    let bar = ctx.follow(
        &format!("fracture ({})", config.describe()),
        &estimate,
        args.json,
    );
    let (fracture, more_warnings, millis) = fracture_timed(&model, &config)?;
    drop(bar);
    ctx.progress.check()?;
    if args.validate {
        fracture
            .validate(Some(mesh.volume()))
            .map_err(|e| CliError::internal(format!("the fracture failed validation: {e}")))?;
    }
    warnings.extend(more_warnings);
    for w in &warnings {
        eprintln!("warning: {w}");
    }
    if let Some((path, format)) = &out {
        super::fracture_asset::write(path, *format, &fracture, &args.asset, &ctx.progress)?;
    }
    let mut report = FractureReport::new(mesh, &fracture, millis, warnings);
    report.estimate = Some(estimate.into());
    report.peak_rss_bytes = memory::peak_rss_bytes();
    if args.json_bonds {
        report = report.with_bond_list(&fracture);
    }
    if args.json {
        println!(
            "{}",
            serde_json::to_string(&report).internal_err("cannot encode the report")?
        );
    } else {
        println!(
            "{} fragments, {} bonds in {:.3} ms; volume {:.6} of {:.6} (smallest fragment {:.3e})",
            report.fragments,
            report.bonds,
            report.millis,
            report.fragments_volume,
            report.mesh_volume,
            report.min_fragment_volume
        );
        if let Some((path, _)) = &out {
            println!("wrote {}", path.display());
        }
    }
    Ok(())
}
