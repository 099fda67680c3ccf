//! The engine-free bond graph: fragments as nodes (mass, centroid), bonds as faces
//! (area, centroid, normal) between them, and anchors (nodes fixed to the world).

use glam::DVec3;

/// A fragment as the stress solver sees it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Node {
    /// Mass in kg.
    pub mass: f64,
    /// Centre of mass.
    pub centroid: DVec3,
}

/// A bond: the face two fragments share.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GraphBond {
    /// First node.
    pub a: u32,
    /// Second node.
    pub b: u32,
    /// Area of the shared face (m²).
    pub area: f64,
    /// Centroid of the shared face.
    pub centroid: DVec3,
    /// Unit normal of the face, pointing from `a` towards `b`.
    pub normal: DVec3,
}

/// A connected set of nodes joined by intact bonds.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Island {
    /// Its nodes, ascending.
    pub nodes: Vec<u32>,
    /// Its intact bonds, ascending.
    pub bonds: Vec<u32>,
    /// Whether any node is anchored: only then does the island carry a static load; an
    /// island without an anchor is free (it falls as one body).
    pub anchored: bool,
}

/// Nodes, bonds and anchors, independent of any physics engine.
///
/// ```
/// use glam::DVec3;
/// use shatter_sim::stress::{BondGraph, GraphBond, Node};
///
/// // Three blocks in a row; the first is anchored.
/// let node = |x: f64| Node { mass: 10.0, centroid: DVec3::new(x, 0.0, 0.0) };
/// let bond = |a: u32, x: f64| GraphBond {
///     a,
///     b: a + 1,
///     area: 1.0,
///     centroid: DVec3::new(x, 0.0, 0.0),
///     normal: DVec3::X,
/// };
/// let graph = BondGraph::new(
///     vec![node(0.0), node(1.0), node(2.0)],
///     vec![bond(0, 0.5), bond(1, 1.5)],
///     vec![true, false, false],
/// )?;
/// let islands = graph.islands(&[false, true]);
/// assert_eq!(islands.len(), 2);
/// assert!(islands[0].anchored && !islands[1].anchored);
/// # Ok::<(), shatter_sim::SimError>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct BondGraph {
    nodes: Vec<Node>,
    bonds: Vec<GraphBond>,
    anchored: Vec<bool>,
    adjacency: Vec<Vec<u32>>,
}

impl BondGraph {
    /// A graph; every bond's ends must be nodes, masses and areas finite and ≥ 0,
    /// positions finite, and `anchored` one flag per node.
    pub fn new(
        nodes: Vec<Node>,
        bonds: Vec<GraphBond>,
        anchored: Vec<bool>,
    ) -> Result<BondGraph, crate::SimError> {
        let n = nodes.len();
        if anchored.len() != n {
            return Err(crate::SimError::invalid(
                "stress graph anchors",
                format!("{} anchor flags for {n} nodes", anchored.len()),
            ));
        }
        for (i, node) in nodes.iter().enumerate() {
            if !(node.mass.is_finite() && node.mass >= 0.0 && node.centroid.is_finite()) {
                return Err(crate::SimError::invalid(
                    format!("stress graph node {i}"),
                    format!(
                        "mass must be finite and >= 0 and the centroid finite, got {} at {}",
                        node.mass, node.centroid
                    ),
                ));
            }
        }
        let mut adjacency = vec![Vec::new(); n];
        for (i, bond) in bonds.iter().enumerate() {
            let ok = (bond.a as usize) < n
                && (bond.b as usize) < n
                && bond.a != bond.b
                && bond.area.is_finite()
                && bond.area >= 0.0
                && bond.centroid.is_finite()
                && bond.normal.is_finite();
            if !ok {
                return Err(crate::SimError::invalid(
                    format!("stress graph bond {i}"),
                    format!(
                        "needs two distinct nodes below {n}, a finite area >= 0 and a finite \
                         centroid and normal, got {} - {} (area {})",
                        bond.a, bond.b, bond.area
                    ),
                ));
            }
            adjacency[bond.a as usize].push(i as u32);
            adjacency[bond.b as usize].push(i as u32);
        }
        Ok(BondGraph {
            nodes,
            bonds,
            anchored,
            adjacency,
        })
    }

    /// The nodes.
    pub fn nodes(&self) -> &[Node] {
        &self.nodes
    }

    /// The bonds.
    pub fn bonds(&self) -> &[GraphBond] {
        &self.bonds
    }

    /// Per node, whether it is fixed to the world.
    pub fn anchored(&self) -> &[bool] {
        &self.anchored
    }

    /// Per node, the indices of its bonds.
    pub fn adjacency(&self) -> &[Vec<u32>] {
        &self.adjacency
    }

    /// The connected components of the intact bonds (`broken[b]` true: bond `b` is gone;
    /// a short mask counts the missing bonds as intact), ordered by their smallest node.
    pub fn islands(&self, broken: &[bool]) -> Vec<Island> {
        let n = self.nodes.len();
        let mut label = vec![u32::MAX; n];
        let mut islands = Vec::new();
        let mut stack = Vec::new();
        for start in 0..n {
            if label[start] != u32::MAX {
                continue;
            }
            let id = islands.len() as u32;
            let mut island = Island {
                nodes: Vec::new(),
                bonds: Vec::new(),
                anchored: false,
            };
            label[start] = id;
            stack.push(start as u32);
            while let Some(v) = stack.pop() {
                island.nodes.push(v);
                island.anchored |= self.anchored[v as usize];
                for &b in &self.adjacency[v as usize] {
                    if broken.get(b as usize).copied().unwrap_or(false) {
                        continue;
                    }
                    let bond = &self.bonds[b as usize];
                    let other = if bond.a == v { bond.b } else { bond.a };
                    if bond.a == v {
                        island.bonds.push(b);
                    }
                    if label[other as usize] == u32::MAX {
                        label[other as usize] = id;
                        stack.push(other);
                    }
                }
            }
            island.nodes.sort_unstable();
            island.bonds.sort_unstable();
            islands.push(island);
        }
        islands
    }
}
