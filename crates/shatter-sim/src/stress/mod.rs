//! Structural stress on the bond graph, independent of the physics engine.
//!
//! A [`BondGraph`] holds the fragments (mass, centroid), their bonds (area, centroid,
//! normal) and the anchors (fragments fixed to the world). A [`StressSolver`] carries
//! gravity (and any dynamic forces of the step) through the intact bonds down to the
//! anchors and gives every bond's compression, tension and shear ([`BondStress`]);
//! [`StressLimits`] (per material, see [`crate::Material::limits`]) say which bonds break.
//! Islands without an anchor carry no static load: they fall.
//!
//! The [`crate::World`] uses it in the clusters bond model after the contacts of each step
//! (see `World::step`).
//!
//! ```
//! use glam::DVec3;
//! use shatter_sim::stress::{BondGraph, SolverSettings, StressLimits, StressSolver};
//! use shatter_sim::testing::box_grid_fracture;
//!
//! // A 4 m stone beam of 8 blocks, anchored at its left block only: a cantilever.
//! let fracture = box_grid_fracture([8, 1, 1], [4.0, 0.3, 0.3].into());
//! let mut graph = BondGraph::from_fracture(&fracture, 2600.0, |f| f == 0)?;
//! let mut solver = StressSolver::new(&graph, SolverSettings::default());
//! let broken = vec![false; graph.bonds().len()];
//! solver.solve(&graph, &broken, DVec3::new(0.0, -9.81, 0.0), &[]);
//! // The root bond carries the most: the moment of 3.5 m of beam.
//! let root = solver.stress(0);
//! assert!(root.tension > solver.stress(6).tension * 10.0);
//! let stone = StressLimits { compression: 100e6, tension: 6e6, shear: 12e6 };
//! assert!(solver.overloaded(&stone).is_empty());
//! # Ok::<(), shatter_sim::SimError>(())
//! ```

mod block;
mod graph;
mod limits;
mod local;
mod multigrid;
#[cfg(test)]
mod multigrid_tests;
#[cfg(test)]
mod slicing_tests;
mod solver;
#[cfg(test)]
mod split_tests;
mod spring;
#[cfg(test)]
mod tests;

pub use graph::{BondGraph, GraphBond, Island, Node};
pub use limits::{BondStress, Failure, StressLimits};
pub use solver::{Preconditioner, SolveReport, SolverSettings, StressSolver};

impl BondGraph {
    /// The graph of a fracture: node masses `volume × density`, the bonds' faces, and the
    /// fragments for which `anchored(f)` is true fixed to the world.
    pub fn from_fracture(
        fracture: &shatter_geom::fracture::Fracture,
        density: f64,
        anchored: impl Fn(u32) -> bool,
    ) -> Result<BondGraph, crate::SimError> {
        let nodes = fracture
            .fragments
            .iter()
            .map(|f| Node {
                mass: f.volume * density,
                centroid: f.centroid,
            })
            .collect();
        let bonds = fracture
            .bonds
            .iter()
            .map(|b| GraphBond {
                a: b.a,
                b: b.b,
                area: b.area,
                centroid: b.centroid,
                normal: b.normal,
            })
            .collect();
        let anchors = (0..fracture.fragments.len() as u32).map(anchored).collect();
        BondGraph::new(nodes, bonds, anchors)
    }
}
