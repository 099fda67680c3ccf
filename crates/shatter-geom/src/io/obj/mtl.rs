//! MTL material libraries: `newmtl`, `Kd`, `d` / `Tr`, `Ns`, `Pm`, `Pr` and `map_Kd`
//! (with its options skipped), mapped onto glTF's metallic-roughness [`Material`].
//!
//! A statement that cannot be read is skipped with a warning; the rest of the library
//! still loads.

use std::path::{Path, PathBuf};

use super::lines::{decode, lines};
use crate::io::WarningKind;
use crate::io::context::ReadContext;
use crate::io::image::ImageCache;
use crate::model::{Material, Texture};

/// Options of `map_*` statements and how many values each takes (`-o`, `-s` and `-t`
/// take one to three numbers: see [`texture_file`]).
const MAP_OPTIONS: [(&str, usize); 11] = [
    ("-blendu", 1),
    ("-blendv", 1),
    ("-bm", 1),
    ("-boost", 1),
    ("-cc", 1),
    ("-clamp", 1),
    ("-imfchan", 1),
    ("-mm", 2),
    ("-texres", 1),
    ("-type", 1),
    ("-colorspace", 1),
];

/// The file name of a `map_Kd` statement's arguments, its options skipped. Windows
/// separators become `/`. `None` if no file name is left.
pub(crate) fn texture_file(args: &str) -> Option<PathBuf> {
    let words: Vec<&str> = args.split_whitespace().collect();
    let mut i = 0;
    while i < words.len() {
        let w = words[i];
        if let Some(&(_, n)) = MAP_OPTIONS.iter().find(|(o, _)| o.eq_ignore_ascii_case(w)) {
            i += 1 + n;
        } else if ["-o", "-s", "-t"].contains(&w) {
            i += 1;
            // One to three numbers.
            for _ in 0..3 {
                match words.get(i) {
                    Some(v) if v.parse::<f64>().is_ok() => i += 1,
                    _ => break,
                }
            }
        } else {
            break;
        }
    }
    let name = words.get(i..)?.join(" ");
    if name.is_empty() {
        return None;
    }
    Some(PathBuf::from(name.replace('\\', "/")))
}

/// The materials defined in the library `path` (already resolved), in order, or `None`
/// (and a warning) when the file cannot be read. `images` shares textures between
/// materials and libraries.
pub(crate) fn read_library(
    cx: &mut ReadContext<'_>,
    path: &Path,
    images: &mut ImageCache,
) -> Option<Vec<Material>> {
    let bytes = match cx.read(path) {
        Ok(b) => b,
        Err(e) => {
            cx.warn(
                WarningKind::MissingFile,
                1,
                format!(
                    "cannot read material library {}: {e}; the geometry loads with default materials",
                    path.display()
                ),
            );
            return None;
        }
    };
    let text = decode(&bytes);
    let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
    let lib = path.display().to_string();
    let mut materials: Vec<Material> = Vec::new();
    let mut bad = 0usize;
    let mut first_bad: Option<(usize, String)> = None;
    for line in lines(&text) {
        let (keyword, rest) = match line.text.split_once(char::is_whitespace) {
            Some((k, r)) => (k, r.trim()),
            None => (&*line.text, ""),
        };
        let mut fail = |why: String| {
            bad += 1;
            if first_bad.is_none() {
                first_bad = Some((line.number, why));
            }
        };
        if keyword == "newmtl" {
            let name = if rest.is_empty() { "unnamed" } else { rest };
            materials.push(Material::named(name));
            continue;
        }
        let Some(current) = materials.last_mut() else {
            // Statements before the first `newmtl` have no material to go to.
            if !keyword.is_empty() {
                fail(format!("'{keyword}' before any newmtl"));
            }
            continue;
        };
        let numbers = || -> Result<Vec<f32>, String> {
            rest.split_whitespace()
                .map(|w| match w.parse::<f32>() {
                    Ok(v) if v.is_finite() => Ok(v),
                    _ => Err(format!("'{keyword}': bad number '{w}'")),
                })
                .collect()
        };
        match keyword.to_ascii_lowercase().as_str() {
            "kd" => match numbers() {
                Ok(v) if v.len() >= 3 => {
                    current.base_color[..3].copy_from_slice(&v[..3]);
                }
                Ok(v) if v.len() == 1 => current.base_color[..3].fill(v[0]),
                Ok(_) => fail("'Kd' needs three numbers".into()),
                Err(e) => fail(e),
            },
            "d" => match numbers() {
                Ok(v) if !v.is_empty() => current.base_color[3] = v[0].clamp(0.0, 1.0),
                Ok(_) => fail("'d' needs a number".into()),
                Err(e) => fail(e),
            },
            "tr" => match numbers() {
                Ok(v) if !v.is_empty() => current.base_color[3] = 1.0 - v[0].clamp(0.0, 1.0),
                Ok(_) => fail("'Tr' needs a number".into()),
                Err(e) => fail(e),
            },
            // Blender's mapping of the specular exponent to roughness.
            "ns" => match numbers() {
                Ok(v) if !v.is_empty() => {
                    current.roughness = 1.0 - (v[0].clamp(0.0, 1000.0) / 1000.0).sqrt();
                }
                Ok(_) => fail("'Ns' needs a number".into()),
                Err(e) => fail(e),
            },
            "pm" => match numbers() {
                Ok(v) if !v.is_empty() => current.metallic = v[0].clamp(0.0, 1.0),
                Ok(_) => fail("'Pm' needs a number".into()),
                Err(e) => fail(e),
            },
            "pr" => match numbers() {
                Ok(v) if !v.is_empty() => current.roughness = v[0].clamp(0.0, 1.0),
                Ok(_) => fail("'Pr' needs a number".into()),
                Err(e) => fail(e),
            },
            "map_kd" => match texture_file(rest) {
                Some(file) => {
                    let full = if file.is_absolute() {
                        file
                    } else {
                        dir.join(file)
                    };
                    let what = format!("{lib}, material '{}'", current.name);
                    if let Some(image) = images.load(cx, &full, &what) {
                        // Like Blender's importer: the texture replaces Kd (glTF would
                        // multiply them, darkening the texture by the usual Kd 0.64).
                        current.base_color_texture = Some(Texture { image });
                    }
                }
                None => fail("'map_Kd' names no file".into()),
            },
            _ => {}
        }
    }
    for m in &mut materials {
        if m.base_color_texture.is_some() {
            m.base_color[..3].fill(1.0);
        }
    }
    if let Some((line, why)) = first_bad {
        cx.warn(
            WarningKind::BadFile,
            bad,
            format!(
                "material library {lib}: skipped {bad} statement{} it could not read (first at line {line}: {why})",
                if bad == 1 { "" } else { "s" }
            ),
        );
    }
    Some(materials)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn map_options_are_skipped() {
        assert_eq!(
            texture_file("-bm 0.5 -o 0.1 0.2 -s 2 2 2 -clamp on wood grain.jpg"),
            Some(PathBuf::from("wood grain.jpg"))
        );
        assert_eq!(
            texture_file(r"textures\brick.png"),
            Some(PathBuf::from("textures/brick.png"))
        );
        assert_eq!(texture_file("-bm 1"), None);
    }
}
