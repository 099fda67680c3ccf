//! Every vocabulary type (method, pattern, placement, shape, bond model, material preset):
//! `ALL` round-trips through `Display`/`FromStr` and serde, and a bad word is an error
//! that lists the valid ones.

use std::fmt::Debug;
use std::str::FromStr;

use serde::{Deserialize, Serialize, de::DeserializeOwned};
use shatter_geom::fracture::{MethodKind, Pattern, Placement};
use shatter_geom::shapes::Shape;
use shatter_geom::vocab::UnknownWord;
use shatter_sim::{BondModel, MaterialPreset};

#[derive(Serialize, Deserialize)]
struct Holder<T> {
    word: T,
}

fn check<T>(all: &[T], names: &[&str], what: &str)
where
    T: Copy + PartialEq + Debug + std::fmt::Display + FromStr<Err = UnknownWord>,
    T: Serialize + DeserializeOwned,
{
    assert_eq!(all.len(), names.len());
    for (&v, &name) in all.iter().zip(names) {
        assert_eq!(v.to_string(), name);
        assert_eq!(name.parse::<T>(), Ok(v));
        let text = toml::to_string(&Holder { word: v }).expect("serialises");
        assert_eq!(text.trim(), format!("word = \"{name}\""));
        let back: Holder<T> = toml::from_str(&text).expect("deserialises");
        assert_eq!(back.word, v);
    }
    let err = "no-such-word".parse::<T>().expect_err("not a word");
    let message = err.to_string();
    assert!(
        message.starts_with(&format!("unknown {what} `no-such-word`")),
        "{message}"
    );
    for name in names {
        assert!(message.contains(name), "{message} lacks {name}");
    }
    let bad: Result<Holder<T>, _> = toml::from_str("word = \"no-such-word\"");
    let message = bad.err().map(|e| e.to_string()).unwrap_or_default();
    assert!(
        message.contains(names[0]),
        "serde error lists the words: {message}"
    );
}

#[test]
fn every_vocabulary_round_trips() {
    check(
        MethodKind::ALL,
        &["tetra", "voronoi", "slice", "grid"],
        "method",
    );
    check(
        Pattern::ALL,
        &["uniform", "clustered", "radial", "splinter"],
        "pattern",
    );
    check(Placement::ALL, &["interior", "thesis"], "placement");
    check(
        Shape::ALL,
        &["cube", "capsule", "cylinder", "sphere", "torus", "bird"],
        "shape",
    );
    check(BondModel::ALL, &["clusters", "joints"], "bond model");
    check(
        MaterialPreset::ALL,
        &[
            "glass", "stone", "concrete", "wood", "ceramic", "ice", "brick",
        ],
        "material",
    );
}

#[test]
fn a_scene_with_a_bad_word_names_the_key_and_the_valid_words() {
    let text = "[[objects]]\nshape = \"cube\"\nmethod = \"shred\"\n";
    let err = shatter_sim::scene::Scene::parse(text)
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
    assert!(err.contains("objects[0].method"), "{err}");
    for name in MethodKind::NAMES {
        assert!(err.contains(name), "{err} lacks {name}");
    }
}
