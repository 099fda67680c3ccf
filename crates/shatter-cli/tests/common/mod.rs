//! Helpers shared by the integration tests: run the real `shatter` binary.
#![allow(dead_code, clippy::unwrap_used)]

use std::path::Path;
use std::process::{Command, Output};

/// The result of one run of the binary.
pub struct Run {
    pub code: i32,
    pub stdout: String,
    pub stderr: String,
}

impl Run {
    /// Parses stdout as one JSON value.
    pub fn json(&self) -> serde_json::Value {
        serde_json::from_str(self.stdout.trim()).unwrap_or_else(|e| {
            panic!(
                "stdout is not JSON ({e}):\n{}\nstderr:\n{}",
                self.stdout, self.stderr
            )
        })
    }

    /// Asserts success and returns self.
    pub fn ok(self) -> Self {
        assert_eq!(
            self.code, 0,
            "expected success\nstdout:\n{}\nstderr:\n{}",
            self.stdout, self.stderr
        );
        self
    }

    /// Asserts exit code 2 (bad input) with a message containing every `needle`, and no
    /// panic.
    pub fn bad_input(self, needles: &[&str]) -> Self {
        assert_eq!(
            self.code, 2,
            "expected exit code 2\nstdout:\n{}\nstderr:\n{}",
            self.stdout, self.stderr
        );
        assert!(!self.stderr.contains("panicked"), "panic:\n{}", self.stderr);
        for needle in needles {
            assert!(
                self.stderr.contains(needle),
                "stderr lacks {needle:?}:\n{}",
                self.stderr
            );
        }
        self
    }
}

impl From<Output> for Run {
    /// A finished process's exit code (-1 when killed by a signal) and its output.
    fn from(out: Output) -> Self {
        Run {
            code: out.status.code().unwrap_or(-1),
            stdout: String::from_utf8_lossy(&out.stdout).into_owned(),
            stderr: String::from_utf8_lossy(&out.stderr).into_owned(),
        }
    }
}

/// Runs `shatter ARGS` in `dir`.
pub fn shatter(dir: &Path, args: &[&str]) -> Run {
    shatter_env(dir, args, &[])
}

/// Runs `shatter ARGS` in `dir` with the environment variables `env` set.
pub fn shatter_env(dir: &Path, args: &[&str], env: &[(&str, &str)]) -> Run {
    Command::new(env!("CARGO_BIN_EXE_shatter"))
        .args(args)
        .current_dir(dir)
        .envs(env.iter().copied())
        .output()
        .unwrap()
        .into()
}

/// A deterministic pseudo-random number in [0, 1) (64-bit LCG, high bits).
pub struct Lcg(pub u64);

impl Lcg {
    pub fn next_f64(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Reads a `TETS.txt` file: one `a b c d` per line.
pub fn read_tets(path: &Path) -> Vec<[usize; 4]> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .map(|l| {
            let v: Vec<usize> = l.split_whitespace().map(|x| x.parse().unwrap()).collect();
            assert_eq!(v.len(), 4, "line {l:?}");
            [v[0], v[1], v[2], v[3]]
        })
        .collect()
}

/// Re-imports a mesh file written by shatter with the library's own loader.
pub fn reimport(path: &Path) -> shatter_geom::TriMesh {
    shatter_geom::io::load_mesh(path)
        .unwrap_or_else(|e| panic!("cannot re-import {}: {e}", path.display()))
}

/// A unit right tetrahedron as OBJ text (1-based faces); `inward` flips every face.
pub fn tetrahedron_obj(inward: bool) -> String {
    let faces = [[1, 3, 2], [1, 2, 4], [1, 4, 3], [2, 3, 4]];
    let mut s = String::from("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n");
    for [a, b, c] in faces {
        if inward {
            s.push_str(&format!("f {a} {c} {b}\n"));
        } else {
            s.push_str(&format!("f {a} {b} {c}\n"));
        }
    }
    s
}

/// Relative difference of two volumes.
pub fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs().max(1e-300)
}
