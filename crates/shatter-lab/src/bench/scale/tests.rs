#![allow(clippy::unwrap_used)]
use super::*;
use shatter_geom::budget::Limits;

/// A change to the options and the error it gives.
type BadOption = (fn(&mut BenchScaleOptions), &'static str);

fn options(dir: &std::path::Path) -> BenchScaleOptions {
    BenchScaleOptions {
        sizes: vec![200],
        models: vec!["joints".into(), "clusters".into()],
        cases: vec!["shots".into(), "explosion".into(), "landing".into()],
        seconds: 0.1,
        out: dir.to_path_buf(),
        box_colliders: false,
        skip_held_contacts: false,
        enclosed_colliders: false,
        no_contact_speed_cap: false,
    }
}

fn row(case: &str, model: &str, n: usize, seconds: f64) -> ScaleRow {
    let dir = tempfile::tempdir().unwrap();
    let o = BenchScaleOptions {
        sizes: vec![n],
        models: vec![model.into()],
        cases: vec![case.into()],
        seconds,
        ..options(dir.path())
    };
    let mut report = run(&o, &Context::quiet(Limits::none()), true).unwrap();
    assert_eq!(report.rows.len(), 1);
    report.rows.remove(0)
}

#[test]
fn bad_options_are_input_errors_before_any_world_is_built() {
    let dir = tempfile::tempdir().unwrap();
    let ctx = Context::quiet(Limits::none());
    let cases: [BadOption; 7] = [
        (|o| o.seconds = 0.0, "--seconds must be positive, got 0"),
        (
            |o| o.seconds = f64::NAN,
            "--seconds must be positive, got NaN",
        ),
        (|o| o.sizes.clear(), "--sizes: give at least one size"),
        (|o| o.sizes = vec![0], "--sizes: 0 is not in 1..=10,000,000"),
        (
            |o| o.sizes = vec![200, 300, 200],
            "--sizes: 200 is repeated",
        ),
        (
            |o| o.models = vec!["glue".into()],
            "--models: unknown bond model 'glue' (expected one of: clusters, joints)",
        ),
        (
            |o| o.cases = vec!["shots".into(), "rain".into()],
            "--cases: unknown case 'rain' (expected one of: shots, explosion, landing, blast)",
        ),
    ];
    for (change, message) in cases {
        let mut o = options(dir.path());
        change(&mut o);
        assert_eq!(run(&o, &ctx, true).unwrap_err(), LabError::input(message));
    }
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
}

#[test]
fn a_run_over_the_time_limit_is_refused_naming_the_joints_share() {
    let dir = tempfile::tempdir().unwrap();
    let ctx = Context::quiet(Limits {
        memory_bytes: None,
        seconds: Some(3600.0),
        memory_source: "test",
    });
    let o = BenchScaleOptions {
        sizes: vec![2000, 5000, 10_000, 20_000],
        seconds: 60.0,
        ..options(dir.path())
    };
    let LabError::Input(text) = run(&o, &ctx, true).unwrap_err() else {
        panic!("not bad input");
    };
    assert!(
        text.starts_with("24 runs of 3,600 steps (up to 20,000 fragments), the joints model about"),
        "{text}"
    );
    assert!(text.contains("--models clusters leaves it out"), "{text}");
    assert!(text.contains("--no-limits"), "{text}");
    // The default run fits the hour.
    let config = ScaleConfig::new(&BenchScaleOptions { seconds: 2.0, ..o }).unwrap();
    assert!(config.estimate().0.seconds < 3600.0);
}

#[test]
fn the_report_has_a_row_per_case_model_and_size_and_the_plots() {
    let dir = tempfile::tempdir().unwrap();
    let o = BenchScaleOptions {
        sizes: vec![200, 100],
        ..options(dir.path())
    };
    let report = run(&o, &Context::quiet(Limits::none()), true).unwrap();
    assert_eq!(report.steps, 6);
    assert_eq!(report.rows.len(), 3 * 2 * 2);
    let order: Vec<(&str, &str, usize)> = report
        .rows
        .iter()
        .map(|r| (r.case.as_str(), r.model.as_str(), r.requested))
        .collect();
    assert_eq!(order[0], ("shots", "joints", 200));
    assert_eq!(order[1], ("shots", "joints", 100));
    assert_eq!(order[2], ("shots", "clusters", 200));
    assert_eq!(order[11], ("landing", "clusters", 100));
    for r in &report.rows {
        let case = *ScaleCase::ALL.iter().find(|c| c.name() == r.case).unwrap();
        assert_eq!(r.grid, grid_for(case, r.requested));
        assert_eq!(r.fragments, bricks(r.grid));
        assert_eq!(r.steps, 6);
        assert!(r.mean_ms > 0.0 && r.mean_ms <= r.max_ms, "{r:?}");
        #[cfg(target_os = "linux")]
        assert!(r.cpu_mean_ms.unwrap() >= 0.0, "{r:?}");
        assert!(r.bodies >= 1 && r.still_fragments <= r.fragments, "{r:?}");
        assert_eq!(r.diverged, 0, "{r:?}");
    }
    assert!(report.measured_seconds > 0.0 && report.estimated_seconds > 0.0);
    // Mean, worst and (where the thread's CPU time is read) CPU, PNG and SVG each.
    let plots = if cfg!(target_os = "linux") { 6 } else { 4 };
    assert_eq!(report.plots.len(), plots);
    for p in &report.plots {
        assert!(std::fs::metadata(p).unwrap().len() > 0, "{}", p.display());
    }
}

#[test]
fn the_anchored_wall_rests_and_the_falling_block_does_not() {
    // Clusters: the intact anchored wall is one fixed body, nothing of it moves.
    let wall = row("shots", "clusters", 200, 0.1);
    assert_eq!(wall.still_fragments, wall.fragments);
    assert_eq!(wall.bodies, 1);
    // A block in free fall moves every step.
    for model in ["clusters", "joints"] {
        let block = row("landing", model, 64, 0.1);
        assert_eq!(block.still_fragments, 0, "{model}");
        assert_eq!(
            block.sleeping_bodies, 0,
            "a falling block is awake ({model})"
        );
        assert_eq!(block.bonds_broken, 0, "{model}");
    }
}

#[test]
fn the_block_shatters_on_landing() {
    for model in ["clusters", "joints"] {
        let r = row("landing", model, 64, 1.3);
        assert!(r.bonds_broken > 0, "{model}: {r:?}");
        assert!(r.bodies > 1 || model == "joints", "{model}: {r:?}");
        // 78 steps with contacts: many scheduler ticks of CPU.
        #[cfg(target_os = "linux")]
        assert!(r.cpu_mean_ms.unwrap() > 0.0, "{model}: {r:?}");
    }
}

#[test]
fn the_shots_and_the_explosion_break_the_wall() {
    for case in ["shots", "explosion"] {
        let r = row(case, "clusters", 200, 0.6);
        assert!(r.bonds_broken > 0, "{case}: {r:?}");
        assert!(r.bodies > 1, "{case}: {r:?}");
    }
}

#[test]
fn the_blast_frees_the_wall_the_explosion_only_holes() {
    // 1,008 bricks (2.8 m × 1.8 m): the explosion's 1 m reaches the middle; the blast's
    // half diagonal reaches every brick.
    let explosion = row("explosion", "clusters", 1000, 0.3);
    let blast = row("blast", "clusters", 1000, 0.3);
    assert!(
        blast.bodies * 2 > blast.fragments,
        "the blast frees most bricks: {blast:?}"
    );
    assert!(
        blast.bodies > explosion.bodies,
        "{blast:?} against {explosion:?}"
    );
    assert_eq!(blast.diverged, 0, "{blast:?}");
}

#[test]
fn unchanged_counts_fragments_with_the_same_pose_in_both_lists() {
    let at = |x: f32| Pose::from_parts(glam::Vec3::new(x, 0.0, 0.0), glam::Quat::IDENTITY);
    let before = [(0, at(0.0)), (1, at(1.0)), (3, at(3.0))];
    let after = [(1, at(1.0)), (2, at(2.0)), (3, at(3.5))];
    assert_eq!(unchanged(&before, &after), 1);
    assert_eq!(unchanged(&[], &after), 0);
}
