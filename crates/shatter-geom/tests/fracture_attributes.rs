//! Attributes through fracture (`fracture_model`): UVs, normals and colours interpolated
//! exactly at cuts, every fragment of a textured model with UVs and materials, interior
//! UVs continuous across bonds, seams kept, every method.
#![allow(clippy::unwrap_used, clippy::needless_range_loop)]

use std::path::Path;

use proptest::prelude::*;
use shatter_geom::fracture::{
    Fracture, FractureParams, Method, Placement, fracture, fracture_model,
};
use shatter_geom::model::Model;
use shatter_geom::{DVec3, TriMesh, io, shapes};

mod support;

use support::{bary, lerp, tri};

fn voronoi(pieces: usize, seed: u64) -> FractureParams {
    FractureParams::voronoi(pieces, seed)
}

fn slice(pieces: usize, seed: u64) -> FractureParams {
    FractureParams {
        method: Method::Slice {
            pieces,
            planes: None,
        },
        seed,
    }
}

fn tetra(random_vertices: usize, seed: u64) -> FractureParams {
    FractureParams {
        method: Method::Tetra {
            random_vertices,
            skip: 0,
            center: false,
            placement: Placement::Interior,
        },
        seed,
    }
}

fn grid(cells: [u32; 3], seed: u64) -> FractureParams {
    FractureParams {
        method: Method::Grid {
            cells,
            voids: Vec::new(),
        },
        seed,
    }
}

fn every_method(seed: u64) -> Vec<(&'static str, FractureParams)> {
    vec![
        ("voronoi", voronoi(12, seed)),
        ("slice", slice(3, seed)),
        ("tetra", tetra(20, seed)),
        ("grid", grid([3, 2, 2], seed)),
    ]
}

/// A deterministic pseudo-random value in [0, 1) from a few integers.
fn hash01(a: u64, b: u64, c: u64) -> f32 {
    let mut x = a
        .wrapping_mul(0x9E37_79B9_7F4A_7C15)
        .wrapping_add(b.wrapping_mul(0xBF58_476D_1CE4_E5B9))
        .wrapping_add(c.wrapping_mul(0x94D0_49BB_1331_11EB));
    x ^= x >> 31;
    x = x.wrapping_mul(0xD6E8_FEB8_6659_FD93);
    x ^= x >> 29;
    (x >> 40) as f32 / (1u64 << 24) as f32
}

/// `mesh` with unrelated random UVs, normals and colours at every triangle corner (every
/// triangle a chart of its own: any mix-up of source triangles shows) and two materials.
fn scrambled(mesh: TriMesh, salt: u64) -> Model {
    let mut m = Model::from_mesh(mesh);
    let n = m.mesh.triangles.len() as u64;
    let r = |t: u64, k: u64, i: u64| hash01(salt, t * 3 + k, i);
    m.corners.uv = Some(
        (0..n)
            .map(|t| std::array::from_fn(|k| [r(t, k as u64, 0), r(t, k as u64, 1)]))
            .collect(),
    );
    m.corners.normal = Some(
        (0..n)
            .map(|t| {
                std::array::from_fn(|k| {
                    let v = DVec3::new(
                        f64::from(r(t, k as u64, 2)) - 0.5,
                        f64::from(r(t, k as u64, 3)) - 0.5,
                        f64::from(r(t, k as u64, 4)) + 0.5,
                    )
                    .normalize();
                    v.as_vec3().to_array()
                })
            })
            .collect(),
    );
    m.corners.color = Some(
        (0..n)
            .map(|t| std::array::from_fn(|k| [r(t, k as u64, 5), r(t, k as u64, 6), 0.5, 1.0]))
            .collect(),
    );
    m.material = (0..n).map(|t| (t % 2) as u32).collect();
    m.materials
        .push(shatter_geom::model::Material::named("second"));
    m
}

fn closest_on([a, b, c]: [DVec3; 3], p: DVec3) -> f64 {
    // Distance from p to the triangle: inside → to the plane, else to the edges.
    let w = bary([a, b, c], p);
    if w.iter().all(|&x| x >= 0.0) {
        let n = (b - a).cross(c - a).normalize();
        return n.dot(p - a).abs();
    }
    let seg = |u: DVec3, v: DVec3| {
        let t = ((p - u).dot(v - u) / (v - u).length_squared()).clamp(0.0, 1.0);
        (u + (v - u) * t - p).length()
    };
    seg(a, b).min(seg(b, c)).min(seg(c, a))
}

/// Checks every surface corner of every fragment against the barycentric value of the
/// input triangle its triangle lies on (any input triangle within rounding of its
/// centroid that matches); returns the number of corners checked.
fn check_interpolation(model: &Model, fr: &Fracture, what: &str) -> usize {
    let size = {
        let p = &model.mesh.positions;
        let lo = p.iter().fold(DVec3::INFINITY, |a, &b| a.min(b));
        let hi = p.iter().fold(DVec3::NEG_INFINITY, |a, &b| a.max(b));
        (hi - lo).length()
    };
    let (uv0, n0, c0) = (
        model.corners.uv.as_ref().unwrap(),
        model.corners.normal.as_ref().unwrap(),
        model.corners.color.as_ref().unwrap(),
    );
    let mut checked = 0;
    for (i, f) in fr.fragments.iter().enumerate() {
        let (uv, nn, cc) = (
            f.corners.uv.as_ref().unwrap(),
            f.corners.normal.as_ref().unwrap(),
            f.corners.color.as_ref().unwrap(),
        );
        for t in 0..f.mesh.triangles.len() {
            if f.interior[t] {
                continue;
            }
            let p = tri(&f.mesh, t);
            let c = (p[0] + p[1] + p[2]) / 3.0;
            let candidates: Vec<usize> = (0..model.mesh.triangles.len())
                .filter(|&s| closest_on(tri(&model.mesh, s), c) <= 1e-9 * size)
                .collect();
            assert!(
                !candidates.is_empty(),
                "{what}: fragment {i} triangle {t} is on no input triangle"
            );
            let matches = |s: usize| {
                let st = tri(&model.mesh, s);
                f.material[t] == model.material[s]
                    && (0..3).all(|k| {
                        let w = bary(st, p[k]);
                        let close = |got: &[f32], want: &[f64], tol: f64| {
                            got.iter()
                                .zip(want)
                                .all(|(&g, &w)| (f64::from(g) - w).abs() <= tol)
                        };
                        let n = DVec3::from_array(lerp(&n0[s], w)).normalize();
                        close(&uv[t][k], &lerp(&uv0[s], w), 1e-5)
                            // (Colours stay in 0..=1: an extrapolated one is clamped.)
                            && close(&cc[t][k], &lerp(&c0[s], w).map(|x| x.clamp(0.0, 1.0)), 1e-5)
                            && close(&nn[t][k], &n.to_array(), 1e-5)
                    })
            };
            assert!(
                candidates.iter().any(|&s| matches(s)),
                "{what}: fragment {i} triangle {t} ({p:?}) does not interpolate input \
                 triangle(s) {candidates:?}: uv {:?}",
                uv[t]
            );
            checked += 3;
        }
    }
    checked
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(12))]

    /// The property: an attribute interpolated at a cut equals the barycentric
    /// value of the input triangle at that point (UVs, normals, colours; slice and
    /// Voronoi, random cuts through a capsule whose every triangle is its own chart).
    #[test]
    fn attributes_at_cuts_are_the_input_triangles_barycentric_values(
        seed in 0u64..1_000, salt in 0u64..1_000, pieces in 2usize..6, voronoi_cut in any::<bool>(),
    ) {
        let model = scrambled(shapes::capsule(), salt);
        let params = if voronoi_cut { voronoi(pieces, seed) } else { slice(pieces, seed) };
        let fr = fracture_model(&model, &params).unwrap();
        prop_assume!(fr.fragments.len() >= 2);
        let checked = check_interpolation(&model, &fr, "capsule");
        prop_assert!(checked > 0);
    }
}

#[test]
fn tetra_surface_faces_take_the_nearest_input_triangles_values() {
    // On a convex mesh the tetrahedra's outer faces lie on the surface: their corners
    // get the barycentric values of the input triangle under the face's centroid.
    let model = scrambled(shapes::cube(), 3);
    let fr = fracture_model(&model, &tetra(10, 1)).unwrap();
    assert!(fr.fragments.len() > 2);
    assert!(check_interpolation(&model, &fr, "tetra cube") > 0);
}

fn corpus(rel: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/corpus")
        .join(rel)
}

#[test]
fn every_fragment_of_a_textured_model_has_uvs_and_its_materials_by_every_method() {
    for file in ["gltf/BoxTextured.glb", "obj/cube_usemtl.obj"] {
        let model = io::load_model(corpus(file)).unwrap().model;
        // The box has a texture and UVs; the cube six materials and normals.
        assert!(
            model.corners.uv.is_some() || model.materials.len() > 1,
            "{file}"
        );
        for (name, params) in every_method(5) {
            let what = format!("{file} {name}");
            let fr = fracture_model(&model, &params).unwrap();
            assert!(fr.fragments.len() >= 2, "{what}");
            let interior = fr.materials.len() as u32 - 1;
            assert_eq!(
                fr.materials[..interior as usize],
                model.materials[..],
                "{what}"
            );
            assert_eq!(fr.materials[interior as usize].name, "interior");
            let surface_materials: std::collections::BTreeSet<u32> =
                model.material.iter().copied().collect();
            for (i, f) in fr.fragments.iter().enumerate() {
                let n = f.mesh.triangles.len();
                assert!(f.corners.uv.is_some(), "{what} {i}: no UVs");
                assert_eq!(f.corners.normal.is_some(), model.corners.normal.is_some());
                if let Some(uv) = &f.corners.uv {
                    assert_eq!(uv.len(), n, "{what} {i}");
                    assert!(uv.iter().flatten().flatten().all(|x| x.is_finite()));
                }
                if let Some(normal) = &f.corners.normal {
                    assert_eq!(normal.len(), n, "{what} {i}");
                }
                assert_eq!(f.material.len(), n, "{what} {i}");
                for t in 0..n {
                    if f.interior[t] {
                        assert_eq!(f.material[t], interior, "{what} {i} {t}");
                    } else {
                        assert!(surface_materials.contains(&f.material[t]), "{what} {i} {t}");
                    }
                }
            }
            // What a writer makes of it: the GLB keeps the texture and the UVs.
            let names: Vec<String> = (0..fr.fragments.len()).map(|i| format!("f{i}")).collect();
            let objects: Vec<io::ExportObject<'_>> = fr
                .fragments
                .iter()
                .zip(&names)
                .map(|(f, name)| {
                    io::ExportObject::new(name, &f.mesh)
                        .with_interior(&f.interior)
                        .with_materials(&f.material)
                        .with_corners(&f.corners)
                })
                .collect();
            let mut glb = Vec::new();
            io::write_glb_with_materials(&mut glb, &objects, &fr.materials).unwrap();
            let back = io::parse_model(&glb, io::MeshFormat::Glb, "out.glb")
                .unwrap()
                .model;
            assert!(back.corners.uv.is_some(), "{what}: GLB UVs");
            let images = back
                .materials
                .iter()
                .filter(|m| m.base_color_texture.is_some())
                .count();
            let want = model
                .materials
                .iter()
                .filter(|m| m.base_color_texture.is_some())
                .count();
            assert_eq!(images, want, "{what}: textures in the GLB");
        }
    }
}

#[test]
fn interior_uvs_are_continuous_across_bonds() {
    let model = scrambled(shapes::bird(), 1);
    for (name, params) in every_method(2) {
        let fr = fracture_model(&model, &params).unwrap();
        // The bird is about 2 units across.
        let (compared, bonds_seen) = support::interior_uvs_agree(&fr, 1e-9, 1e-5, name);
        assert!(
            bonds_seen * 10 >= fr.bonds.len() * 9 && compared > 0,
            "{name}: compared {compared} points on {bonds_seen} of {} bonds",
            fr.bonds.len()
        );
    }
}

#[test]
fn seams_stay_seams_and_each_side_keeps_its_chart() {
    // The cube's faces are charts of their own (u, v from the face's axes, offset by the
    // face's index): a cube edge is a seam, one position with two UVs.
    let mut model = Model::from_mesh(shapes::cube());
    let chart = |n: DVec3, p: DVec3| -> [f32; 2] {
        let k = if n.x.abs() > 0.5 {
            0
        } else if n.y.abs() > 0.5 {
            1
        } else {
            2
        };
        let side = if n[k] > 0.0 { 0.0 } else { 1.0 };
        let (a, b) = ((k + 1) % 3, (k + 2) % 3);
        [
            (p[a] + 0.5 + 2.0 * k as f64) as f32,
            (p[b] + 0.5 + 2.0 * side) as f32,
        ]
    };
    let face_normal = |p: [DVec3; 3]| (p[1] - p[0]).cross(p[2] - p[0]).normalize();
    model.corners.uv = Some(
        (0..model.mesh.triangles.len())
            .map(|t| {
                let p = tri(&model.mesh, t);
                p.map(|q| chart(face_normal(p), q))
            })
            .collect(),
    );
    for (name, params) in every_method(4) {
        let fr = fracture_model(&model, &params).unwrap();
        let mut uvs_at: std::collections::HashMap<[u64; 3], Vec<[u32; 2]>> = Default::default();
        for f in &fr.fragments {
            let uv = f.corners.uv.as_ref().unwrap();
            for t in 0..f.mesh.triangles.len() {
                if f.interior[t] {
                    continue;
                }
                let p = tri(&f.mesh, t);
                let n = face_normal(p);
                for k in 0..3 {
                    let want = chart(n, p[k]);
                    let got = uv[t][k];
                    assert!(
                        (got[0] - want[0]).abs() < 1e-5 && (got[1] - want[1]).abs() < 1e-5,
                        "{name}: {got:?} at {} on the face of normal {n}, want {want:?}",
                        p[k]
                    );
                    let key = p[k].to_array().map(f64::to_bits);
                    let e = uvs_at.entry(key).or_default();
                    let bits = got.map(f32::to_bits);
                    if !e.contains(&bits) {
                        e.push(bits);
                    }
                }
            }
        }
        // The cube's 8 corners touch 3 faces each: 3 UVs there.
        assert!(
            uvs_at.values().filter(|v| v.len() >= 3).count() >= 8,
            "{name}: seams lost"
        );
    }
}

/// A mesh without UVs: every fragment still has them. A surface triangle's are the box
/// projection of the object's frame, written out here on its own: along the coordinate
/// axis `k` its face is most along, `uv = ((p − lo)[k+1], (p − lo)[k+2]) / extent`, with
/// `lo` the low corner of the input's bounds and `extent` its largest side.
#[test]
fn a_bare_mesh_gets_materials_and_box_projected_uvs_and_no_other_attributes() {
    let bird = shapes::bird();
    let lo = bird
        .positions
        .iter()
        .fold(DVec3::splat(f64::INFINITY), |a, &p| a.min(p));
    let hi = bird
        .positions
        .iter()
        .fold(DVec3::splat(f64::NEG_INFINITY), |a, &p| a.max(p));
    let extent = (hi - lo).max_element();
    for (name, params) in every_method(0) {
        let fr = fracture(&bird, &params).unwrap();
        assert_eq!(fr.materials.len(), 2, "{name}");
        let mut surface = 0;
        for f in &fr.fragments {
            assert!(f.corners.normal.is_none() && f.corners.color.is_none());
            let want: Vec<u32> = f.interior.iter().map(|&i| u32::from(i)).collect();
            assert_eq!(f.material, want, "{name}");
            let uv = f.corners.uv.as_ref().expect("every fragment has UVs");
            assert_eq!(uv.len(), f.mesh.triangles.len());
            for (t, tri) in f.mesh.triangles.iter().enumerate() {
                if f.interior[t] {
                    continue;
                }
                // The face's own normal picks the same axis as its input triangle's
                // unless the two are within rounding of a tie: only clear faces count.
                let p = tri.map(|i| f.mesh.positions[i as usize]);
                let n = (p[1] - p[0]).cross(p[2] - p[0]).normalize_or_zero().abs();
                let mut axes = [0usize, 1, 2];
                axes.sort_by(|&a, &b| n[b].total_cmp(&n[a]));
                if n[axes[0]] - n[axes[1]] < 0.2 {
                    continue;
                }
                let k = axes[0];
                for c in 0..3 {
                    let d = p[c] - lo;
                    let want = [d[(k + 1) % 3] / extent, d[(k + 2) % 3] / extent];
                    for j in 0..2 {
                        assert!(
                            (f64::from(uv[t][c][j]) - want[j]).abs() < 1e-5,
                            "{name}: {:?} vs {want:?}",
                            uv[t][c]
                        );
                    }
                }
                surface += 1;
            }
        }
        assert!(
            surface > 100,
            "{name}: only {surface} surface triangles checked"
        );
    }
}

#[test]
fn a_model_whose_attributes_do_not_fit_is_refused() {
    let mut model = Model::from_mesh(shapes::cube());
    model.corners.uv = Some(vec![[[0.0; 2]; 3]; 3]);
    let err = fracture_model(&model, &voronoi(4, 0)).unwrap_err();
    assert!(
        err.to_string()
            .contains("uv has 3 entries for 12 triangles"),
        "{err}"
    );
}

#[test]
fn interior_faces_have_flat_outward_normals() {
    let model = scrambled(shapes::cylinder(), 9);
    for (name, params) in every_method(7) {
        let fr = fracture_model(&model, &params).unwrap();
        for f in &fr.fragments {
            let normals = f.corners.normal.as_ref().unwrap();
            for t in 0..f.mesh.triangles.len() {
                let p = tri(&f.mesh, t);
                let flat = (p[1] - p[0]).cross(p[2] - p[0]);
                if !f.interior[t] || flat.length() < 1e-9 {
                    continue;
                }
                for n in normals[t] {
                    let n = DVec3::new(n[0].into(), n[1].into(), n[2].into());
                    assert!((n.length() - 1.0).abs() < 1e-5);
                    assert!(
                        n.dot(flat.normalize()) > 1.0 - 1e-6,
                        "{name}: {n} vs {flat}"
                    );
                }
            }
        }
    }
}
