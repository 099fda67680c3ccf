//! `shatter tetrahedralize`, end to end through the real binary.
#![allow(clippy::unwrap_used)]

mod common;

use common::{Lcg, read_tets, shatter};

type P = [f64; 3];

fn sub(a: P, b: P) -> P {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn signed_volume(a: P, b: P, c: P, d: P) -> f64 {
    let (u, v, w) = (sub(b, a), sub(c, a), sub(d, a));
    (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
        + u[2] * (v[0] * w[1] - v[1] * w[0]))
        / 6.0
}

/// The unit cube's corners, 200 interior points and 3 duplicates (of points 0, 10, 50):
/// the convex hull is the unit cube.
fn cube_points() -> Vec<P> {
    let mut pts = Vec::new();
    for i in 0..8 {
        pts.push([(i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64]);
    }
    let mut rng = Lcg(7);
    for _ in 0..200 {
        pts.push([rng.next_f64(), rng.next_f64(), rng.next_f64()]);
    }
    for i in [0, 10, 50] {
        pts.push(pts[i]);
    }
    pts
}

fn write_points(path: &std::path::Path, pts: &[P]) {
    let mut text = String::from("# x y z\n\n");
    for p in pts {
        text.push_str(&format!("{:?} {:?} {:?}  # point\n", p[0], p[1], p[2]));
    }
    std::fs::write(path, text).unwrap();
}

#[test]
fn input_file_gives_positive_tets_filling_the_hull_and_json_counts_match() {
    let dir = tempfile::tempdir().unwrap();
    let pts = cube_points();
    write_points(&dir.path().join("points.xyz"), &pts);
    let run = shatter(
        dir.path(),
        &[
            "tetrahedralize",
            "--input",
            "points.xyz",
            "--out",
            "tets.txt",
            "--json",
        ],
    )
    .ok();
    let json = run.json();
    let tets = read_tets(&dir.path().join("tets.txt"));
    assert_eq!(json["points"], pts.len());
    assert_eq!(json["unique_points"], pts.len() - 3);
    assert_eq!(json["duplicates"], 3);
    assert_eq!(json["tetrahedra"], tets.len());
    assert!(json["millis"].as_f64().unwrap() >= 0.0);

    let mut used = vec![false; pts.len()];
    let mut total = 0.0;
    for t in &tets {
        for &i in t {
            assert!(i < pts.len(), "index {i} out of range");
            used[i] = true;
        }
        let v = signed_volume(pts[t[0]], pts[t[1]], pts[t[2]], pts[t[3]]);
        assert!(
            v > 0.0,
            "tetrahedron {t:?} is not positively oriented ({v})"
        );
        total += v;
    }
    assert!(
        (total - 1.0).abs() < 1e-9,
        "volumes sum to {total}, hull is 1"
    );
    // Every distinct point is used, duplicates are written as their first occurrence.
    assert!(used[..pts.len() - 3].iter().all(|&u| u));
    assert!(used[pts.len() - 3..].iter().all(|&u| !u));
}

#[test]
fn random_points_json_and_file_agree() {
    let dir = tempfile::tempdir().unwrap();
    for distribution in ["uniform", "ball", "sphere", "gaussian", "grid"] {
        let run = shatter(
            dir.path(),
            &[
                "tetrahedralize",
                "--random",
                "500",
                "--distribution",
                distribution,
                "--seed",
                "3",
                "--out",
                "tets.txt",
                "--json",
            ],
        )
        .ok();
        let json = run.json();
        let tets = read_tets(&dir.path().join("tets.txt"));
        let n = json["points"].as_u64().unwrap() as usize;
        assert!(n > 0, "{distribution}");
        assert_eq!(json["tetrahedra"], tets.len(), "{distribution}");
        assert!(!tets.is_empty(), "{distribution}");
        assert!(tets.iter().flatten().all(|&i| i < n), "{distribution}");
    }
}

#[test]
fn same_seed_same_tetrahedra_other_seed_other_points() {
    let dir = tempfile::tempdir().unwrap();
    let run = |seed: &str, out: &str| {
        shatter(
            dir.path(),
            &[
                "tetrahedralize",
                "--random",
                "300",
                "--seed",
                seed,
                "--out",
                out,
            ],
        )
        .ok();
        std::fs::read_to_string(dir.path().join(out)).unwrap()
    };
    assert_eq!(run("5", "a.txt"), run("5", "b.txt"));
    assert_ne!(run("5", "a.txt"), run("6", "c.txt"));
}

#[test]
fn human_summary_without_json() {
    let dir = tempfile::tempdir().unwrap();
    let run = shatter(dir.path(), &["tetrahedralize", "--random", "100"]).ok();
    assert!(run.stdout.contains("100 points"), "{}", run.stdout);
    assert!(run.stdout.contains("tetrahedra"), "{}", run.stdout);
}

#[test]
fn short_line_names_file_line_and_count() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("points.xyz"),
        "# header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n\n1 1\n",
    )
    .unwrap();
    shatter(dir.path(), &["tetrahedralize", "--input", "points.xyz"])
        .bad_input(&["points.xyz:7: expected 3 coordinates, found 2"]);
}

#[test]
fn word_and_nan_are_refused_with_their_line() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("a.xyz"), "0 0 0\n1 abc 0\n").unwrap();
    shatter(dir.path(), &["tetrahedralize", "--input", "a.xyz"])
        .bad_input(&["a.xyz:2: 'abc' is not a number"]);
    std::fs::write(dir.path().join("b.xyz"), "0 0 0\n1 0 0\n0 0 NaN\n").unwrap();
    shatter(dir.path(), &["tetrahedralize", "--input", "b.xyz"])
        .bad_input(&["b.xyz:3: 'NaN' is not a finite number"]);
}

#[test]
fn missing_and_empty_input_files_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    shatter(dir.path(), &["tetrahedralize", "--input", "nope.xyz"])
        .bad_input(&["nope.xyz", "cannot read"]);
    std::fs::write(dir.path().join("empty.xyz"), "# nothing\n").unwrap();
    shatter(dir.path(), &["tetrahedralize", "--input", "empty.xyz"])
        .bad_input(&["empty.xyz", "no points"]);
}

#[test]
fn degenerate_point_sets_are_refused_by_name() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("flat.xyz"),
        "0 0 0\n1 0 0\n0 1 0\n1 1 0\n2 3 0\n",
    )
    .unwrap();
    shatter(dir.path(), &["tetrahedralize", "--input", "flat.xyz"])
        .bad_input(&["flat.xyz", "coplanar"]);
    std::fs::write(
        dir.path().join("few.xyz"),
        "0 0 0\n1 0 0\n0 1 0\n0 1 0\n0 0 0\n",
    )
    .unwrap();
    shatter(dir.path(), &["tetrahedralize", "--input", "few.xyz"])
        .bad_input(&["few.xyz", "3 distinct points"]);
}

#[test]
fn bad_flags_exit_2() {
    let dir = tempfile::tempdir().unwrap();
    shatter(dir.path(), &["tetrahedralize"]).bad_input(&["--input"]);
    shatter(dir.path(), &["tetrahedralize", "--random", "3"]).bad_input(&["at least 4"]);
    shatter(dir.path(), &["tetrahedralize", "--random", "-5"]).bad_input(&["-5"]);
    shatter(dir.path(), &["tetrahedralize", "--random", "ten"]).bad_input(&["ten"]);
    shatter(
        dir.path(),
        &[
            "tetrahedralize",
            "--random",
            "10",
            "--distribution",
            "cubic",
        ],
    )
    .bad_input(&["cubic"]);
    std::fs::write(dir.path().join("p.xyz"), "0 0 0\n").unwrap();
    shatter(
        dir.path(),
        &["tetrahedralize", "--random", "10", "--input", "p.xyz"],
    )
    .bad_input(&["cannot be used with"]);
}

#[test]
fn unwritable_out_is_refused_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    shatter(
        dir.path(),
        &[
            "tetrahedralize",
            "--random",
            "10",
            "--out",
            "no/such/dir/tets.txt",
        ],
    )
    .bad_input(&["no/such/dir/tets.txt", "does not exist"]);
    shatter(
        dir.path(),
        &["tetrahedralize", "--random", "10", "--out", "."],
    )
    .bad_input(&["is a directory"]);
}
