//! The real app, in a real window, runs its scripted session: bonds break, screenshots
//! exist and show something.
//!
//! Needs a display (Xvfb + Mesa in CI): run `scripts/app-autotest.sh`, which runs this
//! test with `--ignored` under `xvfb-run`.
#![allow(clippy::unwrap_used)]

use std::fs::File;
use std::io::BufReader;
use std::path::Path;
use std::process::Command;

use serde_json::Value;

/// Mean and variance of the luminance of an RGB(A) 8-bit PNG, and its size.
fn luminance_stats(path: &Path) -> (f64, f64, u32, u32) {
    let file = File::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut reader = png::Decoder::new(BufReader::new(file)).read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!(info.bit_depth, png::BitDepth::Eight);
    let channels = info.color_type.samples();
    assert!(channels >= 3, "{}: not an RGB image", path.display());
    let px: Vec<f64> = buf[..info.buffer_size()]
        .chunks(channels)
        .map(|p| 0.2126 * p[0] as f64 + 0.7152 * p[1] as f64 + 0.0722 * p[2] as f64)
        .collect();
    let n = px.len() as f64;
    let mean = px.iter().sum::<f64>() / n;
    let var = px.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n;
    (mean, var, info.width, info.height)
}

fn read_png(path: &Path) -> Vec<u8> {
    let mut reader = png::Decoder::new(BufReader::new(File::open(path).unwrap()))
        .read_info()
        .unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    buf.truncate(info.buffer_size());
    buf
}

#[test]
#[ignore = "needs a display: run scripts/app-autotest.sh (xvfb-run)"]
fn autotest_session_breaks_bonds_and_saves_screenshots() {
    let dir = std::env::var_os("SHATTER_APP_AUTOTEST_DIR")
        .map(std::path::PathBuf::from)
        .unwrap_or_else(|| std::env::temp_dir().join("shatter-app-autotest"));
    let _ = std::fs::remove_dir_all(&dir);
    let status = Command::new(env!("CARGO_BIN_EXE_shatter-app"))
        .arg("--autotest")
        .arg(&dir)
        .status()
        .expect("run shatter-app");
    assert!(
        status.success(),
        "shatter-app --autotest exited with {status}"
    );

    let state: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("state.json")).unwrap()).unwrap();
    println!("{}", serde_json::to_string_pretty(&state).unwrap());
    let get = |k: &str| {
        state[k]
            .as_u64()
            .unwrap_or_else(|| panic!("no {k} in state.json"))
    };
    assert!(get("bonds_broken") > 0, "the shot broke no bond");
    assert!(get("fragments") > 0);
    assert!(get("bodies") > 0);
    let before = state["before_shot"]["bodies"].as_u64().unwrap();
    assert!(
        get("bodies") > before,
        "the shot split nothing: {before} bodies before, {} after",
        get("bodies")
    );
    // Reset restores the objects: every bond whole again.
    assert_eq!(state["after_reset"]["bonds_broken"].as_u64(), Some(0));
    // The bridge's slab broke off by stress.
    let stress = state["bridge_fallen"]["bonds_broken_by"][1].as_u64();
    assert!(stress.is_some_and(|n| n > 0), "{}", state["bridge_fallen"]);
    // The runtime scene starts as two intact bodies and both are cut.
    assert_eq!(state["runtime_before"]["fragments"].as_u64(), Some(2));
    let cuts = state["runtime"]["runtime_fractures"].as_u64();
    assert!(cuts.is_some_and(|n| n >= 2), "{}", state["runtime"]);
    assert!(state["runtime"]["fragments"].as_u64().unwrap() > 20);
    // The user's textured models (an open, multi-part OBJ repaired, a GLB) load, stand
    // whole, and break.
    assert!(
        state.get("textured_error").is_none(),
        "{}",
        state["textured_error"]
    );
    assert_eq!(state["textured_before"]["bonds_broken"].as_u64(), Some(0));
    assert!(state["textured_before"]["fragments"].as_u64().unwrap() >= 40);
    let broken = state["textured"]["bonds_broken"].as_u64();
    assert!(broken.is_some_and(|n| n > 0), "{}", state["textured"]);

    let shots = state["screenshots"].as_array().unwrap();
    assert!(shots.len() >= 5, "too few screenshots: {shots:?}");
    for name in shots {
        let path = dir.join(name.as_str().unwrap());
        let (mean, var, w, h) = luminance_stats(&path);
        assert!(w >= 640 && h >= 360, "{}: {w}x{h}", path.display());
        // A blank (single-colour) frame has zero variance; a lit scene with panels has
        // sky, ground, shadows and text.
        assert!(
            var > 100.0,
            "{} looks blank (variance {var:.1})",
            path.display()
        );
        assert!(
            (10.0..245.0).contains(&mean),
            "{}: mean {mean:.1}",
            path.display()
        );
    }
    // The shot visibly changed the picture.
    let a = read_png(&dir.join("01_scene.png"));
    let b = read_png(&dir.join("03_after_shot.png"));
    let changed = a
        .iter()
        .zip(&b)
        .filter(|(x, y)| x.abs_diff(**y) > 24)
        .count();
    assert!(
        changed > a.len() / 200,
        "01_scene and 03_after_shot are almost identical ({changed} bytes differ)"
    );
}
