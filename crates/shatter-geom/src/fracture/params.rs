//! Fracture parameters.

use glam::DVec3;

crate::vocabulary! {
    /// How the random points of the [`Method::Tetra`] method are placed.
    pub enum Placement: "placement", default Interior {
        /// Uniform inside the mesh (rejection sampling with the winding number).
        Interior = "interior",
        /// The thesis's scheme: pick a random point `p` of the growing list, draw
        /// `d = uniform(0, |p − c|)` and add `c + unit(c − p)·d` (`c` = centre of mass).
        /// A point outside the mesh (possible for concave meshes, e.g. a torus, whose
        /// centre is in the hole) is redrawn.
        Thesis = "thesis",
    }
}

crate::vocabulary! {
    /// Seed distribution of the [`Method::Voronoi`] method.
    pub enum Pattern: "pattern", default Uniform {
        /// Uniform inside the mesh.
        Uniform = "uniform",
        /// Gaussian clusters around a few random centres inside the mesh.
        Clustered = "clustered",
        /// Dense near the impact point and coarser outward (glass).
        Radial = "radial",
        /// Cells stretched along the mesh's longest axis (wood).
        Splinter = "splinter",
    }
}

crate::vocabulary! {
    /// The name of a fracture method, without its parameters: the word of scene files,
    /// the CLI's `--method` and the app's panels. [`Method`] holds each one's parameters.
    ///
    /// ```
    /// use shatter_geom::fracture::{Method, MethodKind};
    /// assert_eq!(Method::default().kind(), MethodKind::Voronoi);
    /// assert_eq!(MethodKind::NAMES, ["tetra", "voronoi", "slice", "grid"]);
    /// ```
    pub enum MethodKind: "method" {
        /// The thesis: Delaunay tetrahedra of surface vertices plus random points.
        Tetra = "tetra",
        /// Voronoi cells of seed points, clipped exactly to the mesh.
        Voronoi = "voronoi",
        /// Random planes slicing the mesh.
        Slice = "slice",
        /// A regular grid of cells along the axes: bricks of a box, or cells clipped to
        /// any other mesh.
        Grid = "grid",
    }
}

/// A fracture method.
#[derive(Debug, Clone, PartialEq)]
pub enum Method {
    /// The thesis's method: a Delaunay tetrahedralization of surface vertices and random
    /// points, each tetrahedron a fragment (slivers merged into a neighbour).
    Tetra {
        /// Number of random points to add.
        random_vertices: usize,
        /// Take every `(skip + 1)`-th surface vertex.
        skip: usize,
        /// Also add the centre of mass.
        center: bool,
        /// Where the random points go.
        placement: Placement,
    },
    /// Voronoi cells of seed points clipped to the mesh.
    Voronoi {
        /// The seeds: generated in a pattern, or given.
        seeds: Seeds,
    },
    /// Cuts by `pieces` planes, each cutting every current piece.
    Slice {
        /// Number of random planes (ignored when `planes` is given).
        pieces: usize,
        /// Explicit planes as `(point, normal)`.
        planes: Option<Vec<(DVec3, DVec3)>>,
    },
    /// The mesh's bounding box cut into `cells[0] × cells[1] × cells[2]` equal boxes along
    /// the axes, each clipped to the mesh: bricks of a box-shaped mesh. Fragments come in
    /// grid order, `x` fastest (fragment `x + nx·(y + ny·z)` for a box without voids).
    Grid {
        /// Cells along x, y and z (each at least 1).
        cells: [u32; 3],
        /// Cells left out, as boxes of cells `[x0, y0, z0, x1, y1, z1]` (`x0 <= x < x1`
        /// and so on): an arch's opening, a bridge's span. The faces that border a
        /// left-out cell are surface, not cuts.
        voids: Vec<[u32; 6]>,
    },
}

/// The seeds of [`Method::Voronoi`]: generated, or given.
///
/// ```
/// use shatter_geom::fracture::{Pattern, Seeds};
/// assert_eq!(Seeds::count(12), Seeds::Pattern { count: 12, pattern: Pattern::Uniform, impact: None });
/// assert_eq!(Seeds::Points(vec![[0.0; 3].into(); 3]).len(), 3);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub enum Seeds {
    /// `count` seeds drawn in `pattern`.
    Pattern {
        /// How many.
        count: usize,
        /// Their distribution.
        pattern: Pattern,
        /// The impact point of [`Pattern::Radial`] (default: a random surface vertex);
        /// the other patterns ignore it.
        impact: Option<DVec3>,
    },
    /// These seeds (e.g. read from a file).
    Points(Vec<DVec3>),
}

impl Seeds {
    /// `count` uniform seeds.
    pub fn count(count: usize) -> Seeds {
        Seeds::Pattern {
            count,
            pattern: Pattern::Uniform,
            impact: None,
        }
    }

    /// The number of seeds (so of cells before any is found empty).
    pub fn len(&self) -> usize {
        match self {
            Seeds::Pattern { count, .. } => *count,
            Seeds::Points(points) => points.len(),
        }
    }

    /// Whether there is no seed.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The generated seeds' pattern; given points have none.
    pub fn pattern(&self) -> Option<Pattern> {
        match self {
            Seeds::Pattern { pattern, .. } => Some(*pattern),
            Seeds::Points(_) => None,
        }
    }
}

impl Method {
    /// The tetra method with `random_vertices` random points placed by `placement`, no
    /// skipped surface vertex and no centre point.
    ///
    /// ```
    /// use shatter_geom::fracture::{Method, MethodKind, Placement};
    /// assert_eq!(Method::tetra(50, Placement::Thesis).kind(), MethodKind::Tetra);
    /// ```
    pub fn tetra(random_vertices: usize, placement: Placement) -> Method {
        Method::Tetra {
            random_vertices,
            skip: 0,
            center: false,
            placement,
        }
    }

    /// The Voronoi method with `count` seeds in `pattern` (no impact point).
    pub fn voronoi(count: usize, pattern: Pattern) -> Method {
        Method::Voronoi {
            seeds: Seeds::Pattern {
                count,
                pattern,
                impact: None,
            },
        }
    }

    /// The method's name.
    pub fn kind(&self) -> MethodKind {
        match self {
            Method::Tetra { .. } => MethodKind::Tetra,
            Method::Voronoi { .. } => MethodKind::Voronoi,
            Method::Slice { .. } => MethodKind::Slice,
            Method::Grid { .. } => MethodKind::Grid,
        }
    }
}

impl Default for Method {
    fn default() -> Self {
        Method::Voronoi {
            seeds: Seeds::count(20),
        }
    }
}

/// Parameters of [`fracture`](super::fracture).
///
/// ```
/// use shatter_geom::fracture::{FractureParams, Method, Placement, Seeds};
/// let params = FractureParams {
///     method: Method::Tetra { random_vertices: 50, skip: 0, center: true, placement: Placement::Thesis },
///     seed: 7,
/// };
/// assert_eq!(params.seed, 7);
/// assert_eq!(FractureParams::default().method, Method::Voronoi { seeds: Seeds::count(20) });
/// ```
#[derive(Debug, Clone, PartialEq, Default)]
pub struct FractureParams {
    /// The method and its parameters.
    pub method: Method,
    /// Random seed: the same seed gives the same fracture.
    pub seed: u64,
}

impl FractureParams {
    /// `pieces` Voronoi cells from uniform random seeds.
    ///
    /// ```
    /// use shatter_geom::fracture::{FractureParams, Method, Seeds};
    /// let p = FractureParams::voronoi(8, 3);
    /// assert_eq!(p.method, Method::Voronoi { seeds: Seeds::count(8) });
    /// assert_eq!(p.seed, 3);
    /// ```
    pub fn voronoi(pieces: usize, seed: u64) -> FractureParams {
        FractureParams {
            method: Method::Voronoi {
                seeds: Seeds::count(pieces),
            },
            seed,
        }
    }
}
