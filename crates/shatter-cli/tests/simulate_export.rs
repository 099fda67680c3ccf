//! `shatter simulate --export RUN.glb --record RUN.csv`, end to end through the real
//! binary: the GLB re-imports with the `gltf` crate with one node per fragment and per
//! projectile and one keyframe per sample; the CSV has a header and one row per step;
//! bad output paths are refused before the run.
#![allow(clippy::unwrap_used)]

mod common;

use std::path::Path;

use common::shatter;
use gltf::animation::util::ReadOutputs;

/// A stone block of 3 × 2 × 2 = 12 bricks dropped from 2 m, a wooden crate of
/// 2 × 2 × 2 = 8 bricks removed after 0.5 s, and two identical balls fired at 0.1 s
/// and 0.3 s that each live 0.3 s.
const SCENE: &str = r#"
[world]
bond_model = "joints"
seconds = 1.0

[[objects]]
name = "block"
shape = "cube"
method = "grid"
grid = [3, 2, 2]
material = "stone"
position = [0.0, 2.0, 0.0]
color = [0.8, 0.2, 0.2]

[[objects]]
name = "crate"
shape = "cube"
method = "grid"
grid = [2, 2, 2]
material = "wood"
position = [3.0, 0.5, 0.0]
last = 0.5

[[projectiles]]
at = 0.1
shape = "sphere"
size = 0.2
speed = 10.0
last = 0.3
from = [-3.0, 0.5, 4.0]
to = [-3.0, 0.5, 0.0]

[[projectiles]]
at = 0.3
shape = "sphere"
size = 0.2
speed = 10.0
last = 0.3
from = [-3.0, 0.5, 4.0]
to = [-3.0, 0.5, 0.0]
"#;

const BLOCK_FRAGMENTS: usize = 12;
const CRATE_FRAGMENTS: usize = 8;
const PROJECTILES: usize = 2;
/// Every node of the file: one per fragment and one per projectile, nothing else (no
/// ground, camera or light).
const NODES: usize = BLOCK_FRAGMENTS + CRATE_FRAGMENTS + PROJECTILES;
/// 45 steps of 1/60 s at the default 30 keyframes a second: the initial state, every
/// second step (2, 4, …, 44) and the last step (45), which is always a keyframe.
const STEPS: usize = 45;
const KEYFRAMES: usize = 1 + 22 + 1;

fn write_scene(dir: &Path) {
    std::fs::write(dir.join("scene.toml"), SCENE).unwrap();
}

/// Per node of an imported file: the keyframe times and the translation, rotation and
/// (when the node is ever hidden) scale at each.
#[derive(Debug, Default, Clone)]
struct Track {
    times: Vec<f32>,
    translations: Vec<[f32; 3]>,
    rotations: Vec<[f32; 4]>,
    scales: Option<Vec<[f32; 3]>>,
}

impl Track {
    fn visible(&self, i: usize) -> bool {
        self.scales.as_ref().is_none_or(|s| s[i] != [0.0; 3])
    }
}

struct Imported {
    names: Vec<String>,
    tracks: Vec<Track>,
    channels: usize,
    /// Per node: its mesh's vertex positions (every primitive).
    positions: Vec<Vec<[f32; 3]>>,
}

fn import(path: &Path) -> Imported {
    let (doc, buffers, _) = gltf::import(path).unwrap();
    let names = doc
        .nodes()
        .map(|n| n.name().unwrap_or("").to_string())
        .collect();
    let mut tracks = vec![Track::default(); doc.nodes().count()];
    let animations: Vec<_> = doc.animations().collect();
    assert_eq!(animations.len(), 1, "one animation");
    let mut channels = 0;
    for channel in animations[0].channels() {
        channels += 1;
        let node = channel.target().node().index();
        let reader = channel.reader(|b| Some(&buffers[b.index()]));
        let times: Vec<f32> = reader.read_inputs().unwrap().collect();
        let track = &mut tracks[node];
        if track.times.is_empty() {
            track.times = times;
        } else {
            assert_eq!(
                track.times, times,
                "node {node}: channels disagree on times"
            );
        }
        match reader.read_outputs().unwrap() {
            ReadOutputs::Translations(t) => track.translations = t.collect(),
            ReadOutputs::Rotations(r) => track.rotations = r.into_f32().collect(),
            ReadOutputs::Scales(s) => track.scales = Some(s.collect()),
            ReadOutputs::MorphTargetWeights(_) => panic!("no morph targets were written"),
        }
    }
    let positions = doc
        .nodes()
        .map(|n| {
            let mesh = n.mesh().unwrap();
            mesh.primitives()
                .flat_map(|p| {
                    let reader = p.reader(|b| Some(&buffers[b.index()]));
                    reader.read_positions().unwrap().collect::<Vec<_>>()
                })
                .collect()
        })
        .collect();
    Imported {
        names,
        tracks,
        channels,
        positions,
    }
}

/// `q · v` for a unit quaternion `[x, y, z, w]`.
fn rotate(q: [f32; 4], v: [f32; 3]) -> [f32; 3] {
    let [x, y, z, w] = q;
    let u = [x, y, z];
    let cross = |a: [f32; 3], b: [f32; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let t = cross(u, v).map(|c| 2.0 * c);
    let ut = cross(u, t);
    [0, 1, 2].map(|k| v[k] + w * t[k] + ut[k])
}

/// World bounding box of `nodes` at keyframe `i`.
fn world_bounds(imp: &Imported, nodes: &[usize], i: usize) -> ([f32; 3], [f32; 3]) {
    let mut lo = [f32::INFINITY; 3];
    let mut hi = [f32::NEG_INFINITY; 3];
    for &n in nodes {
        let t = &imp.tracks[n];
        for &p in &imp.positions[n] {
            let r = rotate(t.rotations[i], p);
            for k in 0..3 {
                let w = r[k] + t.translations[i][k];
                lo[k] = lo[k].min(w);
                hi[k] = hi[k].max(w);
            }
        }
    }
    (lo, hi)
}

/// `shatter simulate scene.toml --steps STEPS <extra> --json` in `dir`, which must
/// succeed; its JSON report.
fn simulate_json(dir: &Path, extra: &[&str]) -> serde_json::Value {
    let steps = STEPS.to_string();
    let mut args = vec!["simulate", "scene.toml", "--steps", &steps];
    args.extend_from_slice(extra);
    args.push("--json");
    shatter(dir, &args).ok().json()
}

#[test]
fn the_export_reimports_with_a_node_per_fragment_and_projectile_and_every_keyframe() {
    let dir = tempfile::tempdir().unwrap();
    write_scene(dir.path());
    let json = simulate_json(dir.path(), &["--export", "run.glb"]);
    assert_eq!(json["export"]["nodes"], NODES, "{json}");
    assert_eq!(
        json["export"]["fragment_nodes"],
        BLOCK_FRAGMENTS + CRATE_FRAGMENTS
    );
    assert_eq!(json["export"]["projectile_nodes"], PROJECTILES);
    assert_eq!(json["export"]["keyframes"], KEYFRAMES);
    assert!(
        json.get("record").is_none(),
        "no --record, no record: {json}"
    );

    let imp = import(&dir.path().join("run.glb"));
    assert_eq!(imp.names.len(), NODES);
    for f in 0..BLOCK_FRAGMENTS {
        assert_eq!(imp.names[f], format!("block/fragment_{f}"));
    }
    for f in 0..CRATE_FRAGMENTS {
        assert_eq!(
            imp.names[BLOCK_FRAGMENTS + f],
            format!("crate/fragment_{f}")
        );
    }
    let p0 = BLOCK_FRAGMENTS + CRATE_FRAGMENTS;
    assert_eq!(imp.names[p0], "projectile_0");
    assert_eq!(imp.names[p0 + 1], "projectile_1");

    // Translation and rotation per node; a scale channel for the nodes hidden at some
    // time: the crate's fragments (removed at 0.5 s) and both projectiles.
    assert_eq!(imp.channels, 2 * NODES + CRATE_FRAGMENTS + PROJECTILES);
    let dt = 1.0f32 / 60.0;
    for (n, track) in imp.tracks.iter().enumerate() {
        assert_eq!(track.times.len(), KEYFRAMES, "node {n} keyframe count");
        assert_eq!(track.translations.len(), KEYFRAMES, "node {n}");
        assert_eq!(track.rotations.len(), KEYFRAMES, "node {n}");
        assert_eq!(track.times[0], 0.0);
        assert!(
            (track.times[1] - 2.0 * dt).abs() < 1e-5,
            "{:?}",
            track.times
        );
        let last = track.times[KEYFRAMES - 1];
        assert!(
            (last - STEPS as f32 * dt).abs() < 1e-4,
            "last keyframe at {last}"
        );
    }

    // The block keeps every fragment and falls from 2 m onto the ground.
    let block: Vec<usize> = (0..BLOCK_FRAGMENTS).collect();
    assert!(block.iter().all(|&n| imp.tracks[n].scales.is_none()));
    let (lo, hi) = world_bounds(&imp, &block, 0);
    for k in 0..3 {
        let (want_lo, want_hi) = ([-0.5, 1.5, -0.5][k], [0.5, 2.5, 0.5][k]);
        assert!(
            (lo[k] - want_lo).abs() < 1e-3 && (hi[k] - want_hi).abs() < 1e-3,
            "block at t = 0 spans {lo:?}..{hi:?}, not the unit cube at (0, 2, 0)"
        );
    }
    let (lo_end, _) = world_bounds(&imp, &block, KEYFRAMES - 1);
    assert!(
        lo_end[1] < 0.2,
        "the block did not fall: lowest point {lo_end:?}"
    );

    // The crate is shown until it is removed at 0.5 s, hidden after.
    for n in BLOCK_FRAGMENTS..p0 {
        let track = &imp.tracks[n];
        for (i, &t) in track.times.iter().enumerate() {
            assert_eq!(track.visible(i), t < 0.5 - 1e-4, "crate node {n} at {t} s");
        }
    }

    // Each ball is shown while it flies: the first from 0.1 s, the second from 0.3 s,
    // each for 0.3 s; it flies towards -z.
    for (k, fired) in [(0usize, 0.1f32), (1, 0.3)] {
        let track = &imp.tracks[p0 + k];
        let shown: Vec<usize> = (0..KEYFRAMES).filter(|&i| track.visible(i)).collect();
        assert!(!shown.is_empty(), "projectile {k} never shown");
        let (first, last) = (track.times[shown[0]], track.times[*shown.last().unwrap()]);
        assert!(
            first >= fired - 1e-4 && first <= fired + 2.0 * dt + 1e-4,
            "projectile {k} first shown at {first}"
        );
        assert!(
            last <= fired + 0.3 + dt + 1e-4 && last >= fired + 0.3 - 2.0 * dt - 1e-4,
            "projectile {k} last shown at {last}"
        );
        assert!(
            shown.windows(2).all(|w| w[1] == w[0] + 1),
            "projectile {k} flickers: {shown:?}"
        );
        let z0 = track.translations[shown[0]][2];
        let z1 = track.translations[*shown.last().unwrap()][2];
        assert!(z1 < z0 - 1.0, "projectile {k} went from z = {z0} to {z1}");
    }
}

#[test]
fn the_record_has_a_header_and_one_row_per_step() {
    let dir = tempfile::tempdir().unwrap();
    write_scene(dir.path());
    let json = simulate_json(dir.path(), &["--record", "run.csv"]);
    assert_eq!(json["record"]["rows"], STEPS, "{json}");
    assert!(json.get("export").is_none());

    // Every cell is a number or a plain column name, so splitting at commas is exact.
    let text = std::fs::read_to_string(dir.path().join("run.csv")).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(
        header,
        [
            "step",
            "time_s",
            "bodies",
            "fragments",
            "bonds_total",
            "bonds_broken",
            "diverged",
            "debris_removed",
            "step_ms",
            "stress_iterations",
            "stress_ms"
        ]
    );
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|c| c.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), STEPS);
    let dt = 1.0 / 60.0;
    for (i, row) in rows.iter().enumerate() {
        assert_eq!(row.len(), header.len());
        assert_eq!(row[0], (i + 1) as f64, "step column");
        assert!(
            (row[1] - (i + 1) as f64 * dt).abs() < 1e-5,
            "time of step {}",
            i + 1
        );
        assert!(row[8] >= 0.0);
        assert!(row[9] >= 0.0 && row[9].fract() == 0.0, "stress iterations");
        assert!(
            row[10] >= 0.0 && row[10] <= row[8],
            "the stress pass is part of the step"
        );
    }
    // Both objects until the crate goes at 0.5 s (step 30), then the block alone.
    let fragments = |step: usize| rows[step - 1][3];
    assert_eq!(fragments(1), (BLOCK_FRAGMENTS + CRATE_FRAGMENTS) as f64);
    assert_eq!(fragments(STEPS), BLOCK_FRAGMENTS as f64);
    // The last row is the state the summary reports.
    let last = &rows[STEPS - 1];
    assert_eq!(last[2], json["bodies"].as_f64().unwrap());
    assert_eq!(last[3], json["fragments"].as_f64().unwrap());
    assert_eq!(last[4], json["bonds_total"].as_f64().unwrap());
    assert_eq!(last[5], json["bonds_broken"].as_f64().unwrap());
}

#[test]
fn the_fps_flag_sets_the_keyframe_count_and_clusters_export_the_same_nodes() {
    let dir = tempfile::tempdir().unwrap();
    write_scene(dir.path());
    // (fps, keyframes): 0 keeps every step; 10 keeps steps 0, 6, …, 42 and the last.
    for (fps, keyframes, bonds) in [("0", STEPS + 1, "joints"), ("10", 8 + 1, "clusters")] {
        let json = simulate_json(
            dir.path(),
            &[
                "--bonds", bonds, "--export", "run.glb", "--record", "run.csv", "--fps", fps,
            ],
        );
        assert_eq!(
            json["export"]["keyframes"], keyframes,
            "--fps {fps}: {json}"
        );
        assert_eq!(json["record"]["rows"], STEPS);
        let imp = import(&dir.path().join("run.glb"));
        assert_eq!(imp.names.len(), NODES, "--bonds {bonds}");
        assert!(imp.tracks.iter().all(|t| t.times.len() == keyframes));
        // Cluster bodies map the fragments to the same place as joint bodies.
        let block: Vec<usize> = (0..BLOCK_FRAGMENTS).collect();
        let (lo, hi) = world_bounds(&imp, &block, 0);
        assert!(
            (lo[1] - 1.5).abs() < 1e-3 && (hi[1] - 2.5).abs() < 1e-3,
            "--bonds {bonds}: block spans {lo:?}..{hi:?} at t = 0"
        );
    }
}

#[test]
fn bad_output_paths_are_refused_before_the_run_with_exit_code_2() {
    let dir = tempfile::tempdir().unwrap();
    write_scene(dir.path());
    std::fs::create_dir(dir.path().join("folder")).unwrap();
    let run = |extra: &[&str]| {
        let mut args = vec!["simulate", "scene.toml", "--steps", "5"];
        args.extend_from_slice(extra);
        shatter(dir.path(), &args)
    };
    run(&["--export", "missing/run.glb"]).bad_input(&["missing/run.glb", "does not exist"]);
    run(&["--record", "missing/run.csv"]).bad_input(&["missing/run.csv", "does not exist"]);
    run(&["--export", "folder"]).bad_input(&["folder", "use a .glb file name"]);
    run(&["--record", "folder"]).bad_input(&["folder", "is a directory"]);
    run(&["--export", "run.gltf"]).bad_input(&["run.gltf", ".glb"]);
    run(&["--export", "run.glb", "--record", "./run.glb"]).bad_input(&["same file"]);
    run(&["--record", "scene.toml"]).bad_input(&["scene.toml", "overwrite the scene"]);
    run(&["--export", "run.glb", "--fps=-1"]).bad_input(&["--fps", "-1"]);
    // --fps means nothing without --export (clap's usage error, also exit code 2).
    run(&["--fps", "10"]).bad_input(&["--export"]);
    // A valid output with an invalid one: neither is written.
    run(&["--export", "run.glb", "--record", "missing/run.csv"]).bad_input(&["missing/run.csv"]);
    assert!(!dir.path().join("run.glb").exists());
    // The paths are checked before the scene is read: a missing scene is not what is
    // reported.
    shatter(
        dir.path(),
        &["simulate", "nowhere.toml", "--export", "missing/run.glb"],
    )
    .bad_input(&["missing/run.glb"]);
}
