//! Parser fuzzing for scene files: random bytes and mutated copies of the shipped scenes.
//! `Scene::parse` must return an error or a scene whose every value is valid, and never
//! panic; the resource estimate of whatever it accepts must not panic either.
#![allow(clippy::unwrap_used)]

use proptest::prelude::*;
use shatter_sim::scene::Scene;

const SCENES: [&str; 5] = [
    include_str!("../../../assets/scenes/default.toml"),
    include_str!("../../../assets/scenes/wall.toml"),
    include_str!("../../../assets/scenes/bird.toml"),
    include_str!("../../../assets/scenes/explosion.toml"),
    include_str!("../../../assets/scenes/thesis_joints.toml"),
];

/// Values and fragments a mutation splices in: edge cases of every kind of value.
const TOKENS: [&str; 24] = [
    "1e300",
    "-1e300",
    "1e-300",
    "nan",
    "inf",
    "-inf",
    "0",
    "-1",
    "99999999999999999999",
    "[0, 1, 0, 99]",
    "[0, 1]",
    "[]",
    "\"\"",
    "\"x\"",
    "[[objects]]\n",
    "[world]\n",
    "[[projectiles]]\nfrom = [0, 0, 0]\nto = [1, 0, 0]\n",
    "=",
    "\n",
    "#",
    "grid = [1000, 1000, 1000]\n",
    "dt = 1e-9\n",
    "pieces = 0\n",
    "{ a = 1 }",
];

/// Checks what `Scene::parse` said about `text`: an error with a message, or a scene
/// whose values are all in their domains.
fn check(text: &str) {
    match Scene::parse(text) {
        Err(e) => assert!(!e.to_string().is_empty()),
        Ok(scene) => {
            let dt = scene.settings.dt;
            assert!(dt.is_finite() && dt > 0.0 && dt <= 0.1, "dt {dt}");
            assert!(scene.settings.gravity.is_finite());
            assert!(scene.seconds.is_finite() && scene.seconds > 0.0);
            for (i, o) in scene.objects.iter().enumerate() {
                o.validate(&format!("objects[{i}]"))
                    .expect("an accepted object is valid");
            }
            for (at, p) in &scene.projectiles {
                assert!(at.is_finite() && *at >= 0.0);
                p.validate("projectile")
                    .expect("an accepted projectile is valid");
            }
            for (at, e) in &scene.explosions {
                assert!(at.is_finite() && *at >= 0.0);
                e.validate("explosion")
                    .expect("an accepted explosion is valid");
            }
            let steps = scene.steps(None, None);
            let estimate = scene.estimate(steps);
            assert!(estimate.total.bytes >= 0.0 && estimate.total.seconds >= 0.0);
        }
    }
}

#[derive(Debug, Clone)]
enum Mutation {
    /// Replace the byte at (position, new byte).
    Flip(usize, u8),
    /// Delete `len` bytes at a position.
    Delete(usize, usize),
    /// Copy `len` bytes from one position to another.
    Duplicate(usize, usize, usize),
    /// Insert a token at a position.
    Insert(usize, usize),
    /// Replace the number or vector after the n-th `=` by a token.
    ReplaceValue(usize, usize),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        (any::<usize>(), any::<u8>()).prop_map(|(p, b)| Mutation::Flip(p, b)),
        (any::<usize>(), 1usize..40).prop_map(|(p, n)| Mutation::Delete(p, n)),
        (any::<usize>(), 1usize..80, any::<usize>())
            .prop_map(|(a, n, b)| Mutation::Duplicate(a, n, b)),
        (any::<usize>(), 0..TOKENS.len()).prop_map(|(p, t)| Mutation::Insert(p, t)),
        (any::<usize>(), 0..TOKENS.len()).prop_map(|(k, t)| Mutation::ReplaceValue(k, t)),
    ]
}

fn apply(text: &mut Vec<u8>, m: &Mutation) {
    let len = text.len().max(1);
    match *m {
        Mutation::Flip(p, b) => {
            if !text.is_empty() {
                let i = p % text.len();
                text[i] = b;
            }
        }
        Mutation::Delete(p, n) => {
            let i = p % len;
            let end = (i + n).min(text.len());
            if i < end {
                text.drain(i..end);
            }
        }
        Mutation::Duplicate(a, n, b) => {
            let i = a % len;
            let end = (i + n).min(text.len());
            let piece: Vec<u8> = text.get(i..end).unwrap_or_default().to_vec();
            let at = b % (text.len() + 1);
            text.splice(at..at, piece);
        }
        Mutation::Insert(p, t) => {
            let at = p % (text.len() + 1);
            text.splice(at..at, TOKENS[t].bytes());
        }
        Mutation::ReplaceValue(k, t) => {
            let equals: Vec<usize> = text
                .iter()
                .enumerate()
                .filter(|(_, b)| **b == b'=')
                .map(|(i, _)| i)
                .collect();
            if let Some(&eq) = equals.get(k % equals.len().max(1)) {
                let end = text[eq..]
                    .iter()
                    .position(|b| *b == b'\n')
                    .map_or(text.len(), |n| eq + n);
                let value = format!(" {}", TOKENS[t].trim_end());
                text.splice(eq + 1..end, value.bytes());
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn random_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..600)) {
        check(&String::from_utf8_lossy(&bytes));
    }

    #[test]
    fn random_key_value_lines_never_panic(
        lines in proptest::collection::vec(
            ("[a-z_]{1,16}", prop::sample::select(TOKENS.to_vec())),
            0..12,
        ),
        header in prop::sample::select(vec!["", "[world]\n", "[[objects]]\n", "[[projectiles]]\n", "[[explosions]]\n"]),
    ) {
        let mut text = header.to_string();
        for (k, v) in lines {
            text.push_str(&format!("{k} = {}\n", v.trim_end()));
        }
        check(&text);
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 1024, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn mutated_shipped_scenes_never_panic(
        scene in 0..SCENES.len(),
        mutations in proptest::collection::vec(mutation(), 1..4),
    ) {
        let mut text = SCENES[scene].as_bytes().to_vec();
        for m in &mutations {
            apply(&mut text, m);
        }
        check(&String::from_utf8_lossy(&text));
    }
}

#[test]
fn the_shipped_scenes_parse_and_are_valid() {
    for text in SCENES {
        assert!(Scene::parse(text).is_ok());
        check(text);
    }
}
