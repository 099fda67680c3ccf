//! `shatter fracture A.obj B.glb DIR/ --out-dir OUT`: fractures many files in parallel,
//! one output per input, with a progress bar and a JSON summary (`OUT/summary.json`).
//!
//! A file that fails is reported and the others go on. Exit code: 0 when every file
//! fractured; otherwise 2 when every failure was bad input (a file that cannot be read
//! or is no solid), 1 when any failure was internal. Bad flags are refused (exit 2)
//! before any file is read.

use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};

use serde::Serialize;
use shatter_geom::io::MeshFormat as InputFormat;

use shatter_lab::fracture::{
    FractureConfig, FractureReport, MeshSource, check_fracture, fracture_timed, load_source,
};

use super::fracture::{FractureArgs, OutFormat};
use crate::args::MeshFormat;
use crate::context::Context;
use crate::error::{CliError, ResultExt};

/// What happened to one input.
#[derive(Debug, Serialize)]
pub struct FileResult {
    /// The input file.
    pub input: String,
    /// The output written, when it succeeded.
    pub output: Option<String>,
    /// Whether it succeeded.
    pub ok: bool,
    /// Why not: the message, and the exit code it would have had alone (2 bad input,
    /// 1 internal).
    pub error: Option<String>,
    /// Exit code alone: 0, 1 or 2.
    pub exit_code: u8,
    /// The fracture's figures, when it succeeded.
    pub report: Option<FractureReport>,
}

/// The batch's summary, written to `summary.json`.
#[derive(Debug, Serialize)]
pub struct Summary {
    /// Inputs.
    pub files: usize,
    /// Inputs fractured.
    pub succeeded: usize,
    /// Inputs that failed.
    pub failed: usize,
    /// The batch's exit code.
    pub exit_code: u8,
    /// Per input, in input order.
    pub results: Vec<FileResult>,
}

/// The mesh files among `inputs` (a folder gives its mesh files, by name, not recursing).
fn collect_inputs(inputs: &[PathBuf]) -> Result<Vec<PathBuf>, CliError> {
    let mut files = Vec::new();
    for p in inputs {
        if p.is_dir() {
            let mut found: Vec<PathBuf> = std::fs::read_dir(p)
                .input_err(format!("cannot read the folder {}", p.display()))?
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|f| f.is_file() && InputFormat::from_path(f).is_some())
                .collect();
            if found.is_empty() {
                return Err(CliError::input(format!(
                    "{}: no .obj, .stl, .gltf or .glb file in this folder",
                    p.display()
                )));
            }
            found.sort();
            files.extend(found);
        } else {
            files.push(p.clone());
        }
    }
    Ok(files)
}

/// One output name per input in `dir`: the input's stem, with its extension added when
/// two inputs share a stem.
fn output_paths(inputs: &[PathBuf], dir: &Path, format: OutFormat) -> Vec<PathBuf> {
    let ext = match format {
        OutFormat::Obj => "obj",
        OutFormat::Glb => "glb",
    };
    let stem = |p: &Path| {
        p.file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| "mesh".into())
    };
    let mut used = std::collections::HashSet::new();
    inputs
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let base = stem(p);
            let shared = inputs.iter().filter(|q| stem(q) == base).count() > 1;
            let mut name = if shared {
                let from = p
                    .extension()
                    .map(|e| e.to_string_lossy().to_ascii_lowercase())
                    .unwrap_or_default();
                format!("{base}_{from}")
            } else {
                base
            };
            if !used.insert(name.clone()) {
                name = format!("{name}_{i}");
                used.insert(name.clone());
            }
            dir.join(format!("{name}.{ext}"))
        })
        .collect()
}

/// Fractures one input; any failure (a panic included) becomes its result.
fn one(
    ctx: &Context,
    config: &FractureConfig,
    input: &Path,
    output: &Path,
    format: MeshFormat,
) -> FileResult {
    let config = FractureConfig {
        source: MeshSource::File(input.to_path_buf()),
        convex_pieces: format.carries_convex_pieces(),
        ..config.clone()
    };
    let work = || -> Result<FractureReport, CliError> {
        let (model, mut warnings) = load_source(&config)?;
        check_fracture(ctx, &model.mesh, &config)?;
        let (fracture, more, millis) = fracture_timed(&model, &config)?;
        warnings.extend(more);
        shatter_lab::export::write_fracture(output, format, &fracture, &ctx.progress)?;
        Ok(FractureReport::new(
            &model.mesh,
            &fracture,
            millis,
            warnings,
        ))
    };
    let result =
        std::panic::catch_unwind(std::panic::AssertUnwindSafe(work)).unwrap_or_else(|_| {
            Err(CliError::internal(format!(
                "{}: internal error (a bug in shatter, please report it)",
                input.display()
            )))
        });
    let input = input.display().to_string();
    match result {
        Ok(report) => FileResult {
            input,
            output: Some(output.display().to_string()),
            ok: true,
            error: None,
            exit_code: 0,
            report: Some(report),
        },
        Err(e) => FileResult {
            input,
            output: None,
            ok: false,
            error: Some(e.to_string()),
            exit_code: e.exit_code(),
            report: None,
        },
    }
}

/// Runs a batch `shatter fracture`.
pub fn run(args: &FractureArgs, ctx: &Context) -> Result<(), CliError> {
    args.asset.check(args.out.as_deref(), true)?;
    if args.shape.is_some() {
        return Err(CliError::input(
            "--shape fractures one shape; a batch takes MESH files",
        ));
    }
    let Some(dir) = &args.out_dir else {
        return Err(CliError::input(
            "several MESH files (or a folder) need --out-dir DIR for their outputs",
        ));
    };
    // Flags are checked before any file is read.
    let (config, _) = args.validate(ctx)?;
    let inputs = collect_inputs(&args.meshes)?;
    if dir.exists() && !dir.is_dir() {
        return Err(CliError::input(format!("{}: not a folder", dir.display())));
    }
    std::fs::create_dir_all(dir).input_err(format!("cannot create {}", dir.display()))?;
    let out_format = args.out_format.unwrap_or(OutFormat::Glb);
    let format = match out_format {
        OutFormat::Obj => MeshFormat::Obj,
        OutFormat::Glb => MeshFormat::Glb,
    };
    let outputs = output_paths(&inputs, dir, out_format);
    let jobs = match args.jobs {
        Some(0) => return Err(CliError::input("--jobs 0: at least 1 is needed")),
        Some(n) => n,
        None => std::thread::available_parallelism().map_or(1, usize::from),
    }
    .min(inputs.len())
    .max(1);

    let bar = ctx.bar(inputs.len() as u64, args.json);
    let next = AtomicUsize::new(0);
    let results: Mutex<Vec<Option<FileResult>>> =
        Mutex::new((0..inputs.len()).map(|_| None).collect());
    std::thread::scope(|s| {
        for _ in 0..jobs {
            s.spawn(|| {
                loop {
                    let i = next.fetch_add(1, Ordering::Relaxed);
                    let Some(input) = inputs.get(i) else { break };
                    let r = one(ctx, &config, input, &outputs[i], format);
                    if let Some(e) = &r.error {
                        bar.eprintln(format!("error: {e}"));
                    }
                    results.lock().unwrap_or_else(|p| p.into_inner())[i] = Some(r);
                    bar.tick(&input.display().to_string());
                }
            });
        }
    });
    drop(bar);
    let results: Vec<FileResult> = results
        .into_inner()
        .unwrap_or_else(|p| p.into_inner())
        .into_iter()
        .flatten()
        .collect();
    let failed = results.iter().filter(|r| !r.ok).count();
    let exit_code = if failed == 0 {
        0
    } else if results.iter().any(|r| r.exit_code == 1) {
        1
    } else {
        2
    };
    let summary = Summary {
        files: results.len(),
        succeeded: results.len() - failed,
        failed,
        exit_code,
        results,
    };
    let json = serde_json::to_string_pretty(&summary).internal_err("cannot encode the summary")?;
    let summary_path = dir.join("summary.json");
    std::fs::write(&summary_path, &json)
        .input_err(format!("cannot write {}", summary_path.display()))?;
    if args.json {
        println!(
            "{}",
            serde_json::to_string(&summary).internal_err("cannot encode the summary")?
        );
    } else {
        for r in &summary.results {
            match (&r.report, &r.error) {
                (Some(rep), _) => println!(
                    "{}: {} fragments, {} bonds -> {}",
                    r.input,
                    rep.fragments,
                    rep.bonds,
                    r.output.as_deref().unwrap_or("")
                ),
                (None, Some(e)) => println!("{}: failed: {e}", r.input),
                (None, None) => {}
            }
        }
        println!(
            "{} of {} files fractured; summary in {}",
            summary.succeeded,
            summary.files,
            summary_path.display()
        );
    }
    match exit_code {
        0 => Ok(()),
        1 => Err(CliError::internal(format!(
            "{failed} of {} files failed, one or more internally (see {})",
            summary.files,
            summary_path.display()
        ))),
        _ => Err(CliError::input(format!(
            "{failed} of {} files failed (see {})",
            summary.files,
            summary_path.display()
        ))),
    }
}
