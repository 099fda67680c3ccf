//! Built-in shapes: Unity's vertex counts, closed, outward, with the analytic volume, and
//! the bird's concavity.
#![allow(clippy::unwrap_used)]

use std::collections::HashSet;
use std::f64::consts::PI;

use shatter_geom::{DVec3, TriMesh, shapes};

fn assert_solid(name: &str, m: &TriMesh) {
    let r = m.check();
    assert!(r.is_solid(), "{name}: {r:?}");
    assert_eq!(r.components, 1, "{name}");
    assert_eq!(r.degenerate_triangles, 0, "{name}");
    assert_eq!(m.validate_solid(), Ok(()), "{name}");
    // Genus 0 (torus: genus 1): Euler characteristic of the welded mesh.
    let edges = 3 * r.triangles / 2;
    let euler = r.vertices as i64 - edges as i64 + r.triangles as i64;
    assert_eq!(euler, if name == "torus" { 0 } else { 2 }, "{name}");
}

#[test]
fn every_builtin_is_a_closed_outward_solid() {
    for name in shapes::NAMES {
        let m = shapes::by_name(name).unwrap();
        assert_solid(name, &m);
    }
    assert!(shapes::by_name("teapot").is_none());
}

#[test]
fn unity_vertex_counts() {
    let counts = |m: TriMesh| (m.positions.len(), m.triangles.len());
    assert_eq!(counts(shapes::cube()), (24, 12));
    assert_eq!(counts(shapes::capsule()).0, 550);
    assert_eq!(counts(shapes::cylinder()), (88, 80));
    let (v, t) = counts(shapes::bird());
    assert_eq!(t, 1394);
    assert!((950..=966).contains(&v), "bird has {v} vertices");
}

#[test]
fn unity_sizes() {
    let size = |m: TriMesh| {
        let (lo, hi) = m.bounds().unwrap();
        hi - lo
    };
    assert_eq!(size(shapes::cube()), DVec3::ONE);
    assert_eq!(size(shapes::cylinder()), DVec3::new(1.0, 2.0, 1.0));
    let capsule = size(shapes::capsule());
    assert_eq!(capsule.y, 2.0);
    assert!((capsule.x - 1.0).abs() < 1e-12);
}

#[test]
fn volumes_match_the_analytic_shapes() {
    assert_eq!(shapes::cube().volume(), 1.0);
    // The cylinder is a prism over a regular 20-gon: exact.
    let prism = 2.0 * 0.5 * 20.0 * 0.25 * (2.0 * PI / 20.0).sin();
    assert!((shapes::cylinder().volume() - prism).abs() < 1e-12);
    // Inscribed tessellations: a little under the smooth volume.
    let capsule = PI * 0.25 * 1.0 + 4.0 / 3.0 * PI * 0.125;
    let v = shapes::capsule().volume();
    assert!(
        v < capsule && v > 0.97 * capsule,
        "capsule {v} vs {capsule}"
    );
    let ball = 4.0 / 3.0 * PI * 0.125;
    let coarse = shapes::sphere(16, 8).volume();
    let fine = shapes::sphere(256, 128).volume();
    assert!(coarse < fine && fine < ball);
    assert!((ball - fine) < 1e-3 * ball);
    let ring = 2.0 * PI * PI * 0.5 * 0.04;
    let t = shapes::torus(0.5, 0.2, 256, 128).volume();
    assert!(t < ring && ring - t < 1e-3 * ring, "torus {t} vs {ring}");
}

#[test]
fn sphere_and_torus_counts_follow_their_parameters() {
    for (s, r) in [(3, 2), (8, 5), (31, 17)] {
        let m = shapes::sphere(s, r);
        assert_eq!(m.positions.len(), 2 + (s + 1) * (r - 1));
        assert_eq!(m.triangles.len(), 2 * s * (r - 1));
        assert_solid("sphere", &m);
        let t = shapes::torus(1.0, 0.3, s, r.max(3));
        assert_eq!(t.triangles.len(), 2 * s * r.max(3));
        assert_solid("torus", &t);
    }
}

/// Barycentric containment of `p` in tetrahedron `t` (all coordinates positive).
fn in_tetrahedron(p: DVec3, t: [DVec3; 4]) -> bool {
    let vol = |a: DVec3, b: DVec3, c: DVec3, d: DVec3| (b - a).dot((c - a).cross(d - a));
    let total = vol(t[0], t[1], t[2], t[3]);
    let parts = [
        vol(p, t[1], t[2], t[3]),
        vol(t[0], p, t[2], t[3]),
        vol(t[0], t[1], p, t[3]),
        vol(t[0], t[1], t[2], p),
    ];
    parts.iter().all(|&v| v / total > 0.0)
}

#[test]
fn bird_is_concave() {
    let bird = shapes::bird();
    let ps = &bird.positions;
    let (lo, hi) = bird.bounds().unwrap();
    // Wing tip (max z), tail corner (min x with z > 0), beak tip (max x), and the lowest
    // point of the belly span a tetrahedron inside the convex hull.
    let by =
        |key: &dyn Fn(&DVec3) -> f64| *ps.iter().max_by(|a, b| key(a).total_cmp(&key(b))).unwrap();
    let wing_tip = by(&|p| p.z);
    let tail = by(&|p| if p.z > 0.2 { -p.x } else { f64::MIN });
    let beak = by(&|p| p.x);
    let belly = by(&|p| -p.y);
    let notch = DVec3::new(-0.7, 0.0, 0.8);
    assert!(in_tetrahedron(notch, [wing_tip, tail, beak, belly]));
    assert!(bird.winding_number(notch).abs() < 1e-9);
    // Wingspan clearly wider than the body.
    assert!(hi.z - lo.z > 2.0 && hi.y - lo.y < 1.0, "{lo} {hi}");
}

#[test]
fn bird_inside_and_outside_by_winding_number() {
    let bird = shapes::bird();
    let inside = [
        DVec3::new(0.0, 0.0, 0.0),    // body
        DVec3::new(0.95, 0.28, 0.0),  // head
        DVec3::new(1.3, 0.25, 0.0),   // beak
        DVec3::new(-1.2, 0.04, 0.1),  // tail
        DVec3::new(-0.2, 0.03, 0.45), // wing root
        DVec3::new(-0.2, 0.0, -0.45), // other wing root
    ];
    for p in inside {
        let w = bird.winding_number(p);
        assert!((w - 1.0).abs() < 1e-9, "{p}: {w}");
    }
    let outside = [
        DVec3::new(-0.7, 0.0, 0.8),  // between wing and tail
        DVec3::new(-0.7, 0.0, -0.8), // same, other side
        DVec3::new(0.7, 0.45, 0.0),  // above the neck
        DVec3::new(0.0, 0.5, 0.5),   // above the wing
        DVec3::new(5.0, 5.0, 5.0),
    ];
    for p in outside {
        let w = bird.winding_number(p);
        assert!(w.abs() < 1e-9, "{p}: {w}");
    }
}

#[test]
fn bird_surface_does_not_cross_itself() {
    // A self-intersecting surface leaves regions of winding number 2 or −1. Sample a
    // lattice through the bounding box: every winding number is 0 or 1.
    let bird = shapes::bird();
    let (lo, hi) = bird.bounds().unwrap();
    let n = 14;
    let mut inside = 0;
    for i in 0..n {
        for j in 0..n {
            for k in 0..n {
                let t = DVec3::new(i as f64 + 0.37, j as f64 + 0.61, k as f64 + 0.29) / n as f64;
                let p = lo + (hi - lo) * t;
                let w = bird.winding_number(p);
                let nearest = w.round();
                assert!(
                    (w - nearest).abs() < 1e-6 && (nearest == 0.0 || nearest == 1.0),
                    "{p}: {w}"
                );
                inside += nearest as usize;
            }
        }
    }
    // The lattice volume fraction inside agrees roughly with the mesh volume.
    let box_volume = (hi - lo).element_product();
    let estimate = inside as f64 / (n * n * n) as f64 * box_volume;
    assert!(
        (estimate - bird.volume()).abs() < 0.3 * bird.volume(),
        "{estimate}"
    );
}

#[test]
fn bird_is_nearly_mirror_symmetric() {
    // Sections are symmetric about z = 0; only the quads' diagonals are not.
    let bird = shapes::bird();
    let (lo, hi) = bird.bounds().unwrap();
    assert!((lo.z + hi.z).abs() < 1e-12, "{lo} {hi}");
    let c = bird.centroid();
    assert!(c.z.abs() < 1e-3 * (hi.z - lo.z), "{c}");
}

/// Volume of the convex hull of `points` by a small incremental hull with exact
/// orientation tests (test helper, O(n·h)).
fn hull_volume(points: &[DVec3]) -> f64 {
    let c = |p: DVec3| robust::Coord3D {
        x: p.x,
        y: p.y,
        z: p.z,
    };
    // robust::orient3d > 0: d is below the plane of a b c (a b c counter-clockwise seen
    // from above), i.e. d is inside for an outward face.
    let orient = |a: usize, b: usize, cc: usize, d: DVec3| {
        robust::orient3d(c(points[a]), c(points[b]), c(points[cc]), c(d))
    };
    let p0 = 0;
    let far = |from: &dyn Fn(DVec3) -> f64| {
        (0..points.len())
            .max_by(|&i, &j| from(points[i]).total_cmp(&from(points[j])))
            .unwrap()
    };
    let p1 = far(&|p| (p - points[p0]).length());
    let p2 = far(&|p| (points[p1] - points[p0]).cross(p - points[p0]).length());
    let p3 = far(&|p| {
        (points[p1] - points[p0])
            .cross(points[p2] - points[p0])
            .dot(p - points[p0])
            .abs()
    });
    let inside = (points[p0] + points[p1] + points[p2] + points[p3]) / 4.0;
    let mut faces: Vec<[usize; 3]> = [[p0, p1, p2], [p0, p3, p1], [p1, p3, p2], [p2, p3, p0]]
        .into_iter()
        .map(|[a, b, cc]| {
            if orient(a, b, cc, inside) > 0.0 {
                [a, b, cc]
            } else {
                [a, cc, b]
            }
        })
        .collect();
    for (i, &p) in points.iter().enumerate() {
        let visible: Vec<bool> = faces
            .iter()
            .map(|f| orient(f[0], f[1], f[2], p) < 0.0)
            .collect();
        if !visible.contains(&true) {
            continue;
        }
        let edges: HashSet<(usize, usize)> = faces
            .iter()
            .zip(&visible)
            .filter(|&(_, &v)| v)
            .flat_map(|(f, _)| [(f[0], f[1]), (f[1], f[2]), (f[2], f[0])])
            .collect();
        let mut next: Vec<[usize; 3]> = faces
            .iter()
            .zip(&visible)
            .filter(|&(_, &v)| !v)
            .map(|(f, _)| *f)
            .collect();
        for &(a, b) in &edges {
            if !edges.contains(&(b, a)) {
                next.push([a, b, i]);
            }
        }
        faces = next;
    }
    faces
        .iter()
        .map(|f| {
            let [a, b, cc] = f.map(|k| points[k] - inside);
            a.dot(b.cross(cc)) / 6.0
        })
        .sum()
}

#[test]
fn hull_helper_matches_convex_shapes() {
    assert!((hull_volume(&shapes::cube().positions) - 1.0).abs() < 1e-12);
    let s = shapes::sphere(24, 12);
    assert!((hull_volume(&s.positions) - s.volume()).abs() < 1e-12);
    let c = shapes::cylinder();
    assert!((hull_volume(&c.positions) - c.volume()).abs() < 1e-12);
}

#[test]
fn bird_volume_is_well_below_its_convex_hull() {
    let bird = shapes::bird();
    let hull = hull_volume(&bird.positions);
    let ratio = bird.volume() / hull;
    eprintln!(
        "bird volume {}, hull volume {hull}, ratio {ratio}",
        bird.volume()
    );
    assert!(ratio < 0.5, "bird fills {ratio} of its hull");
    // Convex shapes fill their hull exactly; the capsule too.
    let capsule = shapes::capsule();
    assert!((capsule.volume() / hull_volume(&capsule.positions) - 1.0).abs() < 1e-9);
}
