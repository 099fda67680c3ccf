//! Tests of the multigrid preconditioner against the springs it is built from, and of
//! the solver with it against the solver with block Jacobi.

use glam::DVec3;

use super::block::Block6;
use super::local::LocalSprings;
use super::multigrid::Multigrid;
use super::multigrid::real::F64;
use super::solver::springs;
use super::spring::Spring;
use super::*;
use crate::testing::box_grid_fracture;

const G: DVec3 = DVec3::new(0.0, -9.81, 0.0);

/// A wall of `nx × ny × nz` blocks, its bottom row anchored.
fn wall(nx: u32, ny: u32, nz: u32) -> BondGraph {
    let f = box_grid_fracture(
        [nx, ny, nz],
        DVec3::new(0.2 * nx as f64, 0.2 * ny as f64, 0.2 * nz as f64),
    );
    BondGraph::from_fracture(&f, 2400.0, |i| (i / nx).is_multiple_of(ny)).unwrap()
}

/// A reproducible pseudo-random vector (xorshift), entries in [-1, 1].
fn noise(n: usize, seed: u64) -> Vec<(DVec3, DVec3)> {
    let mut s = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
    let mut next = || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    (0..n)
        .map(|_| {
            (
                DVec3::new(next(), next(), next()),
                DVec3::new(next(), next(), next()),
            )
        })
        .collect()
}

fn dot(a: &[(DVec3, DVec3)], b: &[(DVec3, DVec3)]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| x.0.dot(y.0) + x.1.dot(y.1))
        .sum()
}

struct Setup {
    springs: Vec<Spring>,
    local: Vec<u32>,
    free: Vec<u32>,
    pos: Vec<DVec3>,
}

fn setup(graph: &BondGraph) -> Setup {
    let springs = springs(graph, &SolverSettings::default());
    let mut local = vec![u32::MAX; graph.nodes().len()];
    let mut free = Vec::new();
    for (v, &anchored) in graph.anchored().iter().enumerate() {
        if !anchored {
            local[v] = free.len() as u32;
            free.push(v as u32);
        }
    }
    let pos = graph.nodes().iter().map(|n| n.centroid).collect();
    Setup {
        springs,
        local,
        free,
        pos,
    }
}

/// The hierarchy of the setup's free nodes.
fn multigrid(s: &Setup) -> Multigrid<F64> {
    let all: Vec<u32> = (0..s.springs.len() as u32).collect();
    let springs = LocalSprings::new(&s.springs, &all, &s.local, s.free.len());
    let pos: Vec<DVec3> = s.free.iter().map(|&v| s.pos[v as usize]).collect();
    Multigrid::<F64>::new(&springs, &pos)
}

/// `K·x` on the free nodes, straight from the springs (anchored nodes at rest).
fn springs_times(s: &Setup, x: &[(DVec3, DVec3)]) -> Vec<(DVec3, DVec3)> {
    let n = s.pos.len();
    let (mut u, mut t) = (vec![DVec3::ZERO; n], vec![DVec3::ZERO; n]);
    for (i, &v) in s.free.iter().enumerate() {
        (u[v as usize], t[v as usize]) = x[i];
    }
    let (mut qu, mut qt) = (vec![DVec3::ZERO; n], vec![DVec3::ZERO; n]);
    for sp in &s.springs {
        let (f, m) = sp.load(&u, &t);
        let (a, b) = (sp.a as usize, sp.b as usize);
        qu[b] += f;
        qt[b] += sp.rb.cross(f) + m;
        qu[a] -= f;
        qt[a] -= sp.ra.cross(f) + m;
    }
    s.free
        .iter()
        .map(|&v| (qu[v as usize], qt[v as usize]))
        .collect()
}

fn close(a: &[(DVec3, DVec3)], b: &[(DVec3, DVec3)], rel: f64) -> bool {
    let scale = dot(b, b).sqrt().max(1e-300);
    let diff: Vec<_> = a
        .iter()
        .zip(b)
        .map(|(x, y)| (x.0 - y.0, x.1 - y.1))
        .collect();
    dot(&diff, &diff).sqrt() <= rel * scale
}

#[test]
fn the_finest_level_is_the_springs_stiffness_and_coarse_levels_are_its_galerkin_product() {
    let graph = wall(12, 9, 2);
    let s = setup(&graph);
    let mg = multigrid(&s);
    assert!(
        mg.depth() >= 2,
        "a 216-block wall is coarsened ({} levels)",
        mg.depth()
    );
    let x = noise(s.free.len(), 1);
    assert!(close(&mg.times(0, &x), &springs_times(&s, &x), 1e-12));
    // K_c·X = Pᵀ·K·(P·X) on every coarse level.
    for l in 0..mg.depth() - 1 {
        let xc = noise(mg.level_len(l + 1), 2 + l as u64);
        let fine = mg.times(l, &mg.prolong(l, &xc));
        assert!(
            close(&mg.times(l + 1, &xc), &mg.restrict(l, &fine), 1e-10),
            "level {}",
            l + 1
        );
    }
}

#[test]
fn the_v_cycle_is_symmetric_and_positive() {
    let graph = wall(14, 10, 2);
    let s = setup(&graph);
    let mg = multigrid(&s);
    for seed in 0..4 {
        let a = noise(s.free.len(), 10 + seed);
        let b = noise(s.free.len(), 20 + seed);
        let (ma, mb) = (mg.apply_alloc(&a), mg.apply_alloc(&b));
        let (ab, ba) = (dot(&ma, &b), dot(&a, &mb));
        assert!(
            (ab - ba).abs() <= 1e-9 * ab.abs().max(ba.abs()),
            "{ab} vs {ba}"
        );
        assert!(dot(&ma, &a) > 0.0);
    }
}

#[test]
fn a_rigid_block_inverse_undoes_its_block() {
    let s = &springs(&wall(2, 2, 1), &SolverSettings::default())[0];
    let (kaa, _, _) = Block6::of_spring(s);
    // A spring's own block is singular along the free rotation about nothing; add the
    // diagonal so it is positive, as a node's sum of springs is.
    let mut k = kaa;
    k.add(&Block6 {
        uu: glam::DMat3::from_diagonal(DVec3::splat(kaa.uu.x_axis.x)),
        ut: glam::DMat3::ZERO,
        tu: glam::DMat3::ZERO,
        tt: glam::DMat3::from_diagonal(DVec3::splat(kaa.tt.x_axis.x + 1.0)),
    });
    let (u, t) = (DVec3::new(0.3, -1.0, 2.0), DVec3::new(-0.5, 0.25, 1.5));
    let (fu, ft) = k.apply(u, t);
    let (bu, bt) = k.inverse().apply(fu, ft);
    assert!((bu - u).length() < 1e-9 && (bt - t).length() < 1e-9);
}

#[test]
fn multigrid_and_block_jacobi_give_the_same_stresses_and_multigrid_needs_far_fewer_iterations() {
    let graph = wall(40, 30, 2);
    let broken = vec![false; graph.bonds().len()];
    let solve = |preconditioner| {
        let settings = SolverSettings {
            preconditioner,
            tolerance: 1e-8,
            max_iterations: 20_000,
            ..SolverSettings::default()
        };
        let mut solver = StressSolver::new(&graph, settings);
        let report = solver.solve(&graph, &broken, G, &[]);
        assert!(report.converged, "{preconditioner:?}: {report:?}");
        (solver, report)
    };
    let (mg, mg_report) = solve(Preconditioner::Multigrid);
    let (bj, bj_report) = solve(Preconditioner::BlockJacobi);
    let mut worst: f64 = 0.0;
    let peak = (0..graph.bonds().len() as u32)
        .map(|b| bj.stress(b).compression.max(bj.stress(b).tension))
        .fold(0.0, f64::max);
    for b in 0..graph.bonds().len() as u32 {
        let (x, y) = (mg.stress(b), bj.stress(b));
        worst = worst
            .max((x.tension - y.tension).abs())
            .max((x.compression - y.compression).abs())
            .max((x.shear - y.shear).abs());
    }
    assert!(
        worst <= 1e-4 * peak,
        "stresses differ by {worst:e} (peak {peak:e})"
    );
    assert!(
        mg_report.iterations * 4 <= bj_report.iterations,
        "multigrid {} iterations, block Jacobi {}",
        mg_report.iterations,
        bj_report.iterations
    );
}

#[test]
fn a_budgeted_solve_resumes_where_it_stopped_and_judges_a_hit_when_it_has_converged() {
    let graph = wall(12, 10, 2);
    let broken = vec![false; graph.bonds().len()];
    let whole = |budget| {
        let mut s = StressSolver::new(
            &graph,
            SolverSettings {
                budget,
                ..SolverSettings::default()
            },
        );
        (s.solve(&graph, &broken, G, &[]), s)
    };
    let (free, reference) = whole(None);
    assert!(free.converged && free.iterations > 6, "{free:?}");
    // Three iterations per solve: unfinished solves, then the same answer after the same
    // number of iterations in all (the conjugate gradients resume, not restart).
    let mut sliced = StressSolver::new(
        &graph,
        SolverSettings {
            budget: Some(3),
            ..SolverSettings::default()
        },
    );
    let (mut solves, mut iterations) = (0, 0);
    loop {
        let r = sliced.solve(&graph, &broken, G, &[]);
        assert!(r.iterations <= 3, "{r:?}");
        solves += 1;
        iterations += r.iterations;
        if r.converged {
            break;
        }
        assert!(solves < 1000, "never converged");
    }
    assert_eq!(iterations, free.iterations);
    assert_eq!(solves, free.iterations.div_ceil(3));
    for b in 0..graph.bonds().len() as u32 {
        let (x, y) = (reference.stress(b), sliced.stress(b));
        assert!(
            (x.tension - y.tension).abs() <= 1e-9 * x.tension.max(1.0)
                && (x.compression - y.compression).abs() <= 1e-9 * x.compression.max(1.0),
            "bond {b}: {x:?} vs {y:?}"
        );
    }
    // A hit on an upper block: no bond is judged on the unfinished solves; the hit's
    // forces stay on until they are, and the bond under it is then found overloaded.
    let top = 12 * 8 + 5;
    let hit = [(top, DVec3::new(0.0, 0.0, -4.0e6))];
    let limits = StressLimits {
        compression: 1e12,
        tension: 1e12,
        shear: 1.0e7,
    };
    let first = sliced.solve(&graph, &broken, G, &hit);
    assert!(!first.converged);
    assert!(sliced.overloaded(&limits).is_empty());
    let mut judged = Vec::new();
    for _ in 0..1000 {
        let r = sliced.solve(&graph, &broken, G, &[]);
        if r.converged {
            judged = sliced.overloaded(&limits);
            break;
        }
        assert!(sliced.overloaded(&limits).is_empty());
    }
    assert!(!judged.is_empty(), "the hit was never judged");
    let mut unsliced = StressSolver::new(&graph, SolverSettings::default());
    unsliced.solve(&graph, &broken, G, &[]);
    let once = unsliced.solve(&graph, &broken, G, &hit);
    assert!(once.converged);
    assert_eq!(judged, unsliced.overloaded(&limits));
}

#[test]
fn a_contact_that_presses_every_step_of_a_budgeted_solve_loads_the_bonds_once() {
    // A resting contact is reported at every step. Over the steps an unfinished solve
    // spans, its force must stay one force (not add up), so the sliced solve ends where a
    // single unsliced solve with it ends, and a bond that holds it is not broken.
    let graph = wall(12, 10, 2);
    let broken = vec![false; graph.bonds().len()];
    let press = [(12 * 8 + 5, DVec3::new(0.0, 0.0, -2.0e5))];
    let mut unsliced = StressSolver::new(&graph, SolverSettings::default());
    let once = unsliced.solve(&graph, &broken, G, &press);
    assert!(once.converged && once.iterations > 6, "{once:?}");
    let mut sliced = StressSolver::new(
        &graph,
        SolverSettings {
            budget: Some(2),
            ..SolverSettings::default()
        },
    );
    let mut solves = 0;
    loop {
        let r = sliced.solve(&graph, &broken, G, &press);
        solves += 1;
        if r.converged {
            break;
        }
        assert!(solves < 1000, "never converged");
    }
    assert!(
        solves > 2,
        "the budget did not slice the solve ({solves} solves)"
    );
    let peak = (0..graph.bonds().len() as u32)
        .map(|b| unsliced.stress(b).shear)
        .fold(0.0, f64::max);
    for b in 0..graph.bonds().len() as u32 {
        let (x, y) = (unsliced.stress(b), sliced.stress(b));
        for (p, q) in [
            (x.tension, y.tension),
            (x.compression, y.compression),
            (x.shear, y.shear),
        ] {
            assert!((p - q).abs() <= 1e-4 * peak, "bond {b}: {x:?} sliced {y:?}");
        }
    }
    // A shear limit just over the unsliced peak: nothing breaks either way.
    let limits = StressLimits {
        compression: 1e12,
        tension: 1e12,
        shear: 1.01 * peak,
    };
    assert!(unsliced.overloaded(&limits).is_empty());
    assert!(sliced.overloaded(&limits).is_empty());
    // Two contacts on one node in one step add up; the stronger of two steps wins.
    let mut split = StressSolver::new(&graph, SolverSettings::default());
    let halves = [
        (press[0].0, press[0].1 * 0.5),
        (press[0].0, press[0].1 * 0.5),
    ];
    split.solve(&graph, &broken, G, &halves);
    let b = (0..graph.bonds().len() as u32)
        .max_by(|&p, &q| {
            unsliced
                .stress(p)
                .shear
                .total_cmp(&unsliced.stress(q).shear)
        })
        .unwrap();
    assert!((split.stress(b).shear - unsliced.stress(b).shear).abs() <= 1e-6 * peak);
}

/// The stresses of `solver` and `fresh` agree within the solver's tolerance.
fn same_stresses(graph: &BondGraph, solver: &StressSolver, fresh: &StressSolver) {
    let peak = (0..graph.bonds().len() as u32)
        .map(|b| fresh.stress(b).compression.max(fresh.stress(b).tension))
        .fold(0.0, f64::max);
    for b in 0..graph.bonds().len() as u32 {
        let (x, y) = (fresh.stress(b), solver.stress(b));
        for (p, q) in [
            (x.tension, y.tension),
            (x.compression, y.compression),
            (x.shear, y.shear),
        ] {
            assert!((p - q).abs() <= 1e-3 * peak, "bond {b}: {x:?} kept {y:?}");
        }
    }
}

#[test]
fn an_island_that_loses_a_bond_or_a_block_keeps_its_hierarchy_and_the_same_answer() {
    let graph = wall(12, 10, 2);
    let bonds = graph.bonds().len();
    let mut broken = vec![false; bonds];
    let mut solver = StressSolver::new(&graph, SolverSettings::default());
    let cold = solver.solve(&graph, &broken, G, &[]);
    assert!(cold.converged && cold.hierarchies_built == 1, "{cold:?}");
    // An interior bond between two free blocks: no node is lost.
    let middle = 12 * 2 * 5 + 6;
    let inner = graph
        .bonds()
        .iter()
        .position(|b| b.a == middle || b.b == middle)
        .unwrap();
    broken[inner] = true;
    // The top corner block knocked off: one of 216 free nodes is lost.
    let corner = 12 * 2 * 10 - 1;
    for (k, b) in graph.bonds().iter().enumerate() {
        if b.a == corner || b.b == corner {
            broken[k] = true;
        }
    }
    let kept = solver.solve(&graph, &broken, G, &[]);
    assert!(kept.converged && kept.hierarchies_built == 0, "{kept:?}");
    let mut fresh = StressSolver::new(&graph, SolverSettings::default());
    let report = fresh.solve(&graph, &broken, G, &[]);
    assert_eq!(report.hierarchies_built, 1);
    same_stresses(&graph, &solver, &fresh);
    assert_eq!(solver.stress(inner as u32), BondStress::default());
    // The two end columns cut off (a sixth of the nodes): both parts built afresh.
    for (k, b) in graph.bonds().iter().enumerate() {
        let col = |v: u32| v % 12;
        if (col(b.a) < 2) != (col(b.b) < 2) {
            broken[k] = true;
        }
    }
    let rebuilt = solver.solve(&graph, &broken, G, &[]);
    assert!(
        rebuilt.converged && rebuilt.hierarchies_built >= 1,
        "{rebuilt:?}"
    );
}

#[test]
fn a_hit_on_an_unfinished_solve_is_still_judged_after_a_bond_breaks_elsewhere() {
    let graph = wall(12, 10, 2);
    let mut broken = vec![false; graph.bonds().len()];
    let limits = StressLimits {
        compression: 1e12,
        tension: 1e12,
        shear: 1.0e7,
    };
    let hit = [(12 * 8 + 5, DVec3::new(0.0, 0.0, -4.0e6))];
    let mut unsliced = StressSolver::new(&graph, SolverSettings::default());
    unsliced.solve(&graph, &broken, G, &hit);
    let expected = unsliced.overloaded(&limits);
    assert!(!expected.is_empty());
    let mut sliced = StressSolver::new(
        &graph,
        SolverSettings {
            budget: Some(3),
            ..SolverSettings::default()
        },
    );
    assert!(!sliced.solve(&graph, &broken, G, &hit).converged);
    // A bond far from the hit breaks while the hit's solve is unfinished.
    let far = graph
        .bonds()
        .iter()
        .position(|b| b.a == 12 * 2 * 9 && b.b == 12 * 2 * 9 + 1)
        .unwrap();
    assert!(!expected.iter().any(|(b, _)| *b as usize == far));
    broken[far] = true;
    let mut judged = Vec::new();
    for _ in 0..1000 {
        if sliced.solve(&graph, &broken, G, &[]).converged {
            judged = sliced.overloaded(&limits);
            break;
        }
    }
    let mut fresh = StressSolver::new(&graph, SolverSettings::default());
    fresh.solve(&graph, &broken, G, &hit);
    assert!(
        !judged.is_empty(),
        "the hit was lost when the bonds changed"
    );
    assert_eq!(judged, fresh.overloaded(&limits));
}
