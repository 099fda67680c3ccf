//! Malformed `SHATTER_fracture` extensions: each a clear error naming what is wrong,
//! and random damage never a panic.

use serde_json::{Value, json};
use shatter_geom::io::{self, ExportObject, MeshIoError};
use shatter_geom::shapes;

use super::{bird, meta, write};

/// The JSON chunk and binary chunk of a GLB.
pub fn split(glb: &[u8]) -> (Value, Vec<u8>) {
    let len = u32::from_le_bytes(glb[12..16].try_into().unwrap()) as usize;
    let json: Value = serde_json::from_slice(&glb[20..20 + len]).unwrap();
    let rest = &glb[20 + len..];
    let bin = if rest.len() >= 8 {
        rest[8..].to_vec()
    } else {
        Vec::new()
    };
    (json, bin)
}

/// A GLB of `json` and `bin`.
fn join(json: &Value, bin: &[u8]) -> Vec<u8> {
    let mut j = serde_json::to_vec(json).unwrap();
    while !j.len().is_multiple_of(4) {
        j.push(b' ');
    }
    let total = 12 + 8 + j.len() + 8 + bin.len();
    let mut out = Vec::new();
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(j.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&j);
    out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(bin);
    out
}

#[test]
fn every_malformed_extension_is_a_clear_error() {
    let fr = bird(8);
    let glb = write(&fr, &meta());
    let (json, bin) = split(&glb);
    // The untouched file reads, so each failure below is the change's.
    io::parse_fracture(&join(&json, &bin), "ok.glb").unwrap();
    type Edit = fn(&mut Value);
    let cases: &[(&str, Edit, &str)] = &[
        (
            "bond to a missing fragment",
            |j| j["extensions"]["SHATTER_fracture"]["bonds"][0]["b"] = json!(999),
            "bonds[0].b names node 999",
        ),
        (
            "bond a after b",
            |j| {
                let b = &mut j["extensions"]["SHATTER_fracture"]["bonds"][0];
                let (a, bb) = (b["a"].clone(), b["b"].clone());
                b["a"] = bb;
                b["b"] = a;
            },
            "a must come before b",
        ),
        (
            "duplicate bond",
            |j| {
                let bonds = &mut j["extensions"]["SHATTER_fracture"]["bonds"];
                let first = bonds[0].clone();
                bonds.as_array_mut().unwrap().insert(1, first);
            },
            "out of order",
        ),
        (
            "a NaN area (JSON writes null)",
            |j| j["extensions"]["SHATTER_fracture"]["bonds"][1]["area"] = json!(null),
            "bonds[1].area",
        ),
        (
            "a non-unit normal",
            |j| j["extensions"]["SHATTER_fracture"]["bonds"][0]["normal"] = json!([0.0, 2.0, 0.0]),
            "not a unit vector",
        ),
        (
            "a centroid of two numbers",
            |j| j["nodes"][3]["extensions"]["SHATTER_fracture"]["centroid"] = json!([1.0, 2.0]),
            "node 3 extension.centroid",
        ),
        (
            "a NaN volume",
            |j| j["nodes"][1]["extensions"]["SHATTER_fracture"]["volume"] = json!(null),
            "node 1 extension.volume",
        ),
        (
            "a negative volume",
            |j| j["nodes"][1]["extensions"]["SHATTER_fracture"]["volume"] = json!(-1.0),
            "volume is not positive",
        ),
        (
            "inertia of eight numbers",
            |j| j["nodes"][0]["extensions"]["SHATTER_fracture"]["inertia"] = json!(vec![0.0; 8]),
            "inertia",
        ),
        (
            "a missing accessor",
            |j| {
                j["nodes"][2]["extensions"]["SHATTER_fracture"]["convexPieces"]["points"] =
                    json!(100_000)
            },
            "accessor",
        ),
        (
            "counts that do not add up",
            |j| {
                let c = &mut j["nodes"][2]["extensions"]["SHATTER_fracture"]["convexPieces"]["counts"]
                    [0];
                *c = json!(c.as_u64().unwrap() + 1);
            },
            "add up to",
        ),
        (
            "a piece of three points",
            |j| {
                j["nodes"][2]["extensions"]["SHATTER_fracture"]["convexPieces"]["counts"][0] =
                    json!(3)
            },
            "at least 4 points",
        ),
        (
            "a fragment node without its extension",
            |j| {
                j["nodes"][4].as_object_mut().unwrap().remove("extensions");
            },
            "node 4 is a fragment but has no SHATTER_fracture extension",
        ),
        (
            "a fragment list naming a missing node",
            |j| j["extensions"]["SHATTER_fracture"]["fragments"][0] = json!(5000),
            "names node 5000",
        ),
        (
            "a fragment listed twice",
            |j| j["extensions"]["SHATTER_fracture"]["fragments"][1] = json!(0),
            "twice",
        ),
        (
            "an anchor that is no fragment",
            |j| j["extensions"]["SHATTER_fracture"]["anchors"] = json!([5000]),
            "anchors[0] names node 5000",
        ),
        (
            "a newer version",
            |j| j["extensions"]["SHATTER_fracture"]["version"] = json!(2),
            "version 2",
        ),
        (
            "no version",
            |j| {
                j["extensions"]["SHATTER_fracture"]
                    .as_object_mut()
                    .unwrap()
                    .remove("version");
            },
            "no `version`",
        ),
        (
            "a bad interior material",
            |j| j["extensions"]["SHATTER_fracture"]["interiorMaterial"] = json!(9),
            "interiorMaterial is 9",
        ),
        (
            "negative thresholds",
            |j| j["extensions"]["SHATTER_fracture"]["thresholds"]["shear"] = json!(-1.0),
            "thresholds",
        ),
        (
            "a moved fragment",
            |j| j["nodes"][0]["translation"] = json!([1.0, 0.0, 0.0]),
            "transform",
        ),
        (
            "the extension not an object",
            |j| j["extensions"]["SHATTER_fracture"] = json!([1, 2]),
            "not a JSON object",
        ),
    ];
    for (name, edit, expected) in cases {
        let mut j = json.clone();
        edit(&mut j);
        let err = io::parse_fracture(&join(&j, &bin), "bad.glb").unwrap_err();
        assert!(
            matches!(err, MeshIoError::FractureExtension { .. }),
            "{name}: {err:?}"
        );
        let msg = err.to_string();
        assert!(msg.contains(expected), "{name}: {msg}");
        assert!(
            msg.contains("bad.glb") && msg.contains("SHATTER_fracture"),
            "{name}: {msg}"
        );
    }
    // A plain GLB has no extension; a truncated file is a glTF error; neither panics.
    let mut plain = Vec::new();
    io::write_glb(&mut plain, &[ExportObject::new("cube", &shapes::cube())]).unwrap();
    let err = io::parse_fracture(&plain, "plain.glb").unwrap_err();
    assert!(
        matches!(err, MeshIoError::NoFractureExtension { .. }),
        "{err:?}"
    );
    assert!(
        err.to_string().contains("no SHATTER_fracture extension"),
        "{err}"
    );
    for cut in [10, 30, glb.len() / 2, glb.len() - 3] {
        let err = io::parse_fracture(&glb[..cut], "cut.glb").unwrap_err();
        assert!(
            matches!(
                err,
                MeshIoError::Gltf { .. } | MeshIoError::FractureExtension { .. }
            ),
            "{cut}: {err:?}"
        );
    }
}

#[test]
fn random_byte_flips_never_panic() {
    let fr = bird(5);
    let glb = write(&fr, &meta());
    let mut state = 0x2545_F491_4F6C_DD1Du64;
    for _ in 0..400 {
        let mut bytes = glb.clone();
        for _ in 0..4 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let at = (state % bytes.len() as u64) as usize;
            bytes[at] = (state >> 32) as u8;
        }
        // Any answer but a panic.
        let _ = io::parse_fracture(&bytes, "flipped.glb");
    }
}
