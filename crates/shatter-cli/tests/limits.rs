//! Requests too big for the machine are refused before any work, with the estimate; the
//! estimates are within their stated factor of real runs; over-long and out-of-range
//! values are refused with messages naming the key.
#![allow(clippy::unwrap_used)]

mod common;

use common::shatter;

/// Runs `shatter ARGS` in `dir` with its address space limited to `mib` MiB (`ulimit
/// -v`), so that a run that tried to allocate what it estimates fails instead of
/// succeeding slowly: a refusal under the limit proves nothing was allocated.
fn shatter_limited(dir: &std::path::Path, mib: u64, args: &[&str]) -> common::Run {
    std::process::Command::new("sh")
        .arg("-c")
        .arg(format!("ulimit -v {} && exec \"$0\" \"$@\"", mib * 1024))
        .arg(env!("CARGO_BIN_EXE_shatter"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("sh runs")
        .into()
}

fn machine_has_meminfo() -> bool {
    std::path::Path::new("/proc/meminfo").exists()
}

/// Regression: `tetrahedralize --random 3000000000` used 18 GB within 60 s and ran on.
#[test]
fn three_billion_random_points_are_refused_without_allocating() {
    if !machine_has_meminfo() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    shatter_limited(
        dir.path(),
        512,
        &["tetrahedralize", "--random", "3000000000"],
    )
    .bad_input(&[
        "--random 3000000000: 3,000,000,000 points need about",
        " GB; this machine has ",
        "MemTotal in /proc/meminfo",
        "--no-limits",
    ]);
}

/// Regression: `fracture --pieces 100000000` and `--random-vertices 4000000000` ran
/// until killed.
#[test]
fn huge_fracture_counts_are_refused_without_allocating() {
    if !machine_has_meminfo() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    shatter_limited(
        dir.path(),
        512,
        &["fracture", "--shape", "bird", "--pieces", "100000000"],
    )
    .bad_input(&[
        "--pieces 100000000: 100,000,000 Voronoi cells of a 1,394-triangle mesh need about",
    ]);
    shatter_limited(
        dir.path(),
        512,
        &[
            "fracture",
            "--shape",
            "cube",
            "--method",
            "tetra",
            "--random-vertices",
            "4000000000",
        ],
    )
    .bad_input(&[
        "--random-vertices 4000000000: a tetra fracture of 4,000,000,024 points need about",
    ]);
    shatter_limited(
        dir.path(),
        512,
        &["bench", "delaunay", "--sizes", "1000,5000000000"],
    )
    .bad_input(&["--sizes 5000000000: 5,000,000,000 points need"]);
}

#[test]
fn a_request_over_the_time_limit_is_refused_and_no_limits_lets_the_check_pass() {
    let dir = tempfile::tempdir().unwrap();
    shatter(dir.path(), &["study", "--runs", "100000000", "--out", "s"])
        .bad_input(&["would take about", "years; the limit is 1 hour"]);
    assert!(
        !dir.path().join("s").exists(),
        "the refused study created its folder"
    );
    // --no-limits: the estimate is not checked (a small run, to see it goes through).
    shatter(
        dir.path(),
        &["--no-limits", "tetrahedralize", "--random", "100", "--json"],
    )
    .ok();
}

/// The memory estimate of a Delaunay run and of a fracture is within a factor of two of
/// the peak resident set of a real run at a small size (the process's own few MB
/// included in the measurement).
#[test]
fn memory_estimates_are_within_a_factor_of_two_of_real_runs() {
    if !machine_has_meminfo() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let cases: [&[&str]; 3] = [
        &["tetrahedralize", "--random", "400000", "--json"],
        &[
            "fracture",
            "--shape",
            "cube",
            "--method",
            "tetra",
            "--random-vertices",
            "20000",
            "--json",
        ],
        &["fracture", "--shape", "bird", "--pieces", "1500", "--json"],
    ];
    for args in cases {
        let run = shatter(dir.path(), args).ok();
        let json = run.json();
        let estimate = json["estimate"]["bytes"].as_f64().unwrap();
        let peak = json["peak_rss_bytes"].as_f64().unwrap();
        let ratio = estimate / peak;
        assert!(
            (0.5..=2.0).contains(&ratio),
            "{args:?}: estimate {estimate:.3e} bytes, peak {peak:.3e} bytes (ratio {ratio:.2})"
        );
    }
}

/// Every CLI vector flag takes exactly three numbers.
#[test]
fn over_long_vector_flags_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    shatter(
        dir.path(),
        &["fracture", "--shape", "cube", "--scale", "1,1,1,7"],
    )
    .bad_input(&[
        "--scale",
        "expected 3 comma-separated numbers X,Y,Z, found 4",
    ]);
    shatter(
        dir.path(),
        &[
            "fracture",
            "--shape",
            "cube",
            "--pattern",
            "radial",
            "--impact",
            "0,0,0,0",
        ],
    )
    .bad_input(&["--impact", "found 4"]);
    shatter(
        dir.path(),
        &["shape", "cube", "--out", "c.obj", "--scale", "1,1,1,1"],
    )
    .bad_input(&["found 4"]);
}

/// `study --break-force 1e300` would have become an infinite `f32` break force.
#[test]
fn study_values_beyond_f32_name_the_limit() {
    let dir = tempfile::tempdir().unwrap();
    shatter(
        dir.path(),
        &["study", "--break-force", "1e300", "--out", "s"],
    )
    .bad_input(&[
        "--break-force",
        "too large for the simulation's 32-bit floats",
    ]);
    shatter(dir.path(), &["study", "--speeds", "1,1e40", "--out", "s"])
        .bad_input(&["--speeds", "too large"]);
}

/// Regression: scenes the validator accepted ran until killed or aborted with "memory
/// allocation of 200000000000 bytes failed".
#[test]
fn scenes_too_big_for_the_machine_are_refused_before_building() {
    if !machine_has_meminfo() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        (
            "grid.toml",
            "[[objects]]\nshape = \"cube\"\nmethod = \"grid\"\ngrid = [1000, 1000, 1000]\n",
            "objects[0].grid = [1000, 1000, 1000]: 1,000,000,000 bricks need about",
        ),
        (
            "pieces.toml",
            "[[objects]]\nshape = \"bird\"\nmethod = \"voronoi\"\npieces = 10000000\n",
            "objects[0].pieces = 10000000: 10,000,000 Voronoi cells with rough cut faces need about",
        ),
        (
            "vertices.toml",
            "[[objects]]\nshape = \"cube\"\nmethod = \"tetra\"\nrandom_vertices = 10000000\n",
            "objects[0].random_vertices = 10000000: a tetra fracture of 10,000,024 points with rough cut faces need about",
        ),
        (
            "dt.toml",
            "[world]\ndt = 1e-9\n\n[[objects]]\nshape = \"cube\"\n",
            "steps of 0.000000001 s with 32 fragments would take about",
        ),
        (
            "seconds.toml",
            "[world]\nseconds = 1e9\n\n[[objects]]\nshape = \"cube\"\n",
            "steps of 0.016666668 s with 32 fragments would take about 335 days",
        ),
    ];
    for (name, text, message) in cases {
        std::fs::write(dir.path().join(name), text).unwrap();
        shatter_limited(dir.path(), 1024, &["simulate", name]).bad_input(&[
            name,
            message,
            "--no-limits",
        ]);
    }
    // A command-line run length is checked too.
    std::fs::write(
        dir.path().join("ok.toml"),
        "[[objects]]\nshape = \"cube\"\n",
    )
    .unwrap();
    shatter(dir.path(), &["simulate", "ok.toml", "--seconds", "1e12"])
        .bad_input(&["steps of 0.016666668 s", "years"]);
}

/// Regression: `position = [0, 1, 0, 99]` and `gravity = [0, -9.81, 0, 7]` were
/// accepted (the extra number dropped); `break_force = 1e300` said "must be positive,
/// got inf".
#[test]
fn scene_values_are_strict_and_name_their_key() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        (
            "[[objects]]\nshape = \"cube\"\nposition = [0, 1, 0, 99]\n",
            "line 3, column 12: key `position`: expected 3 numbers [x, y, z], found 4",
        ),
        (
            "[world]\ngravity = [0, -9.81, 0, 7]\n",
            "line 2, column 11: key `gravity`: expected 3 numbers [x, y, z], found 4",
        ),
        (
            "[[objects]]\nshape = \"cube\"\nbreak_force = 1e300\n",
            "key `break_force`: 1e300 is too large for the simulation's 32-bit floats (largest magnitude 3.4e38)",
        ),
        (
            "[[objects]]\nmethod = \"grid\"\ngrid = [2, 2, 2, 2]\n",
            "key `grid`: expected 3 integers [x, y, z], found 4",
        ),
    ];
    for (text, message) in cases {
        std::fs::write(dir.path().join("s.toml"), text).unwrap();
        shatter(dir.path(), &["simulate", "s.toml", "--steps", "1"]).bad_input(&[message]);
    }
}

/// Regression: "/etc/passwd: /etc/passwd: unknown mesh format".
#[test]
fn a_bad_mesh_path_is_named_once() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("notes.txt"), "not a mesh").unwrap();
    for text in [
        "[[objects]]\nmesh = \"notes.txt\"\n",
        "[[projectiles]]\nmesh = \"notes.txt\"\nfrom = [0, 1, 5]\nto = [0, 1, 0]\n",
    ] {
        std::fs::write(dir.path().join("s.toml"), text).unwrap();
        let run = shatter(dir.path(), &["simulate", "s.toml", "--steps", "1"])
            .bad_input(&["notes.txt: unknown mesh format"]);
        assert_eq!(run.stderr.matches("notes.txt").count(), 1, "{}", run.stderr);
    }
    let run = shatter(dir.path(), &["fracture", "notes.txt"]).bad_input(&["unknown mesh format"]);
    assert_eq!(run.stderr.matches("notes.txt").count(), 1, "{}", run.stderr);
}

/// Runs `shatter ARGS` in `dir` with `SHATTER_PIN_THREADS` set to `value`.
fn shatter_pinning(dir: &std::path::Path, value: &str, args: &[&str]) -> common::Run {
    common::shatter_env(dir, args, &[("SHATTER_PIN_THREADS", value)])
}

#[test]
fn the_thread_pinning_variable_is_checked_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    let args = ["fracture", "--shape", "cube", "--pieces", "4", "--json"];
    shatter_pinning(dir.path(), "maybe", &args)
        .bad_input(&["SHATTER_PIN_THREADS=maybe", "expected 0"]);
    // Off and on both fracture, with the same fragments.
    let off = shatter_pinning(dir.path(), "0", &args).ok().json();
    let on = shatter_pinning(dir.path(), "1", &args).ok().json();
    assert_eq!(off["fragments"], on["fragments"]);
    assert_eq!(off["bonds"], on["bonds"]);
}
