//! What a repair did ([`RepairReport`]), its options and its error.

use serde::Serialize;
use thiserror::Error;

use crate::mesh::MeshError;
use crate::model::ModelError;

/// Options of [`repair`](super::repair).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RepairOptions {
    /// Boundary vertices closer than this fraction of the model's bounding-box diagonal
    /// are welded (after the exact weld). Default `1e-6`.
    pub weld_tolerance: f64,
    /// A hole is filled when its patch's area is at most this fraction of its shell's
    /// area; a shell with a larger hole is an open sheet, dropped. Default `0.25` (a
    /// box with one face missing is filled; a flat sheet is not).
    pub max_hole_area: f64,
    /// Closed parts that cross or touch are replaced by their union. Default `true`;
    /// without it, such a model stays as it is (and fracture refuses it).
    pub union: bool,
}

impl Default for RepairOptions {
    fn default() -> Self {
        Self {
            weld_tolerance: 1e-6,
            max_hole_area: 0.25,
            union: true,
        }
    }
}

/// The union step of a repair.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct UnionReport {
    /// Closed shells that went into the union.
    pub shells: usize,
    /// Their triangles.
    pub triangles_before: usize,
    /// The union's triangles.
    pub triangles_after: usize,
    /// Closed shells of the union without volume (below the same limit as the input's,
    /// a millionth of a millionth of the bounding box's), dropped: slivers the rounding
    /// of the union's exact vertices to f64 leaves where parts met face to face.
    pub sliver_shells_dropped: usize,
    /// Coordinates snapped together before the union (within `snap_tolerance`, axis by
    /// axis), so parts meeting face to face a rounding error apart meet on one plane.
    pub snapped_coordinates: usize,
    /// The snapping tolerance (model units).
    pub snap_tolerance: f64,
    /// Pairs of the union's triangles that rounding its exact vertices to `f64` left
    /// touching or crossing (sharing no vertex).
    pub rounding_crossings: usize,
    /// How deep the deepest of them crosses (model units): what the fracture's
    /// validation compares with its tolerance
    /// ([`CROSSING_TOLERANCE`](crate::mesh::CROSSING_TOLERANCE) of the size).
    pub rounding_depth: f64,
}

/// What [`repair`](super::repair) did, with counts. Every field is zero (or `None`) for
/// a model that needed nothing: see [`RepairReport::is_clean`].
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct RepairReport {
    /// Boundary vertices welded within the tolerance.
    pub welded_vertices: usize,
    /// The tolerance used (absolute, in model units).
    pub weld_tolerance: f64,
    /// Zero-area triangles dropped.
    pub degenerate_triangles: usize,
    /// Neighbours of collinear triangles split at their middle corner (T-junctions).
    pub t_junctions_split: usize,
    /// Extra copies of a triangle dropped.
    pub duplicate_triangles: usize,
    /// Triangles dropped in pairs wound opposite ways (zero-thickness walls).
    pub opposite_pairs_dropped: usize,
    /// Triangles flipped to make their shell's winding consistent.
    pub rewound_triangles: usize,
    /// Holes (boundary loops) filled.
    pub holes_filled: usize,
    /// Triangles added by the hole patches.
    pub fill_triangles: usize,
    /// Closed shells that were wound inward, flipped.
    pub inverted_shells: usize,
    /// Shells inside another (cavities), wound inward.
    pub cavities: usize,
    /// Open shells dropped (a hole too large to fill, e.g. a flat sheet).
    pub open_sheets_dropped: usize,
    /// Their triangles.
    pub open_sheet_triangles: usize,
    /// Non-orientable shells dropped.
    pub non_orientable_dropped: usize,
    /// Closed shells enclosing no volume, dropped.
    pub flat_shells_dropped: usize,
    /// The union, when shells crossed or touched.
    pub union: Option<UnionReport>,
    /// Closed shells in the result.
    pub shells: usize,
    /// Volume of the result.
    pub volume: f64,
}

impl RepairReport {
    /// Nothing was repaired: the model was a valid solid as it was (up to the exact
    /// weld, which changes no geometry).
    pub fn is_clean(&self) -> bool {
        self.warnings().is_empty()
    }

    /// One warning per repair, with its counts.
    ///
    /// ```
    /// use shatter_geom::mesh::repair::RepairReport;
    /// let r = RepairReport { holes_filled: 1, fill_triangles: 30, ..Default::default() };
    /// assert_eq!(r.warnings(), vec!["filled 1 hole with 30 triangles".to_string()]);
    /// ```
    pub fn warnings(&self) -> Vec<String> {
        let mut out = Vec::new();
        let s = |n: usize| if n == 1 { "" } else { "s" };
        if self.welded_vertices > 0 {
            out.push(format!(
                "welded {} boundary vertices within {:e} (cracks)",
                self.welded_vertices, self.weld_tolerance
            ));
        }
        if self.degenerate_triangles > 0 {
            let n = self.degenerate_triangles;
            let split = if self.t_junctions_split > 0 {
                format!(
                    " ({} neighbours split at T-junctions)",
                    self.t_junctions_split
                )
            } else {
                String::new()
            };
            out.push(format!("dropped {n} degenerate triangle{}{split}", s(n)));
        }
        if self.duplicate_triangles > 0 {
            let n = self.duplicate_triangles;
            out.push(format!("dropped {n} duplicate triangle{}", s(n)));
        }
        if self.opposite_pairs_dropped > 0 {
            out.push(format!(
                "dropped {} triangles in pairs wound opposite ways (zero-thickness walls)",
                self.opposite_pairs_dropped
            ));
        }
        if self.rewound_triangles > 0 {
            let n = self.rewound_triangles;
            out.push(format!(
                "flipped {n} triangle{} to make their shell's winding consistent",
                s(n)
            ));
        }
        if self.holes_filled > 0 {
            let n = self.holes_filled;
            out.push(format!(
                "filled {n} hole{} with {} triangles",
                s(n),
                self.fill_triangles
            ));
        }
        if self.inverted_shells > 0 {
            let n = self.inverted_shells;
            out.push(format!("flipped {n} shell{} that were wound inward", s(n)));
        }
        if self.cavities > 0 {
            let n = self.cavities;
            out.push(format!(
                "{n} shell{} inside another: a cavity, wound inward",
                s(n)
            ));
        }
        if self.open_sheets_dropped > 0 {
            let n = self.open_sheets_dropped;
            out.push(format!(
                "dropped {n} open sheet{} ({} triangle{}) enclosing no volume",
                s(n),
                self.open_sheet_triangles,
                s(self.open_sheet_triangles)
            ));
        }
        if self.non_orientable_dropped > 0 {
            let n = self.non_orientable_dropped;
            out.push(format!("dropped {n} non-orientable surface{}", s(n)));
        }
        if self.flat_shells_dropped > 0 {
            let n = self.flat_shells_dropped;
            out.push(format!(
                "dropped {n} closed shell{} enclosing no volume",
                s(n)
            ));
        }
        if let Some(u) = &self.union {
            out.push(format!(
                "{} closed shells cross or touch: replaced by their union ({} triangles, was {})",
                u.shells, u.triangles_after, u.triangles_before
            ));
            if u.snapped_coordinates > 0 {
                out.push(format!(
                    "snapped {} coordinates within {:e} before the union (parts meeting face \
                     to face)",
                    u.snapped_coordinates, u.snap_tolerance
                ));
            }
            if u.rounding_crossings > 0 {
                let n = u.rounding_crossings;
                out.push(format!(
                    "{n} pair{} of the union's triangles touch or cross after rounding, by at \
                     most {:e}",
                    s(n),
                    u.rounding_depth
                ));
            }
            if u.sliver_shells_dropped > 0 {
                let n = u.sliver_shells_dropped;
                out.push(format!(
                    "dropped {n} sliver shell{} without volume left by the union",
                    s(n)
                ));
            }
        }
        out
    }
}

/// Why a model cannot be repaired into a solid.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum RepairError {
    /// The model's parts do not fit together.
    #[error(transparent)]
    Model(#[from] ModelError),
    /// No triangles, a non-finite position or an index out of range.
    #[error(transparent)]
    Mesh(#[from] MeshError),
    /// Nothing with a volume is left; `found` says what there was, e.g. "12 open sheets".
    #[error("{found} and no closed part")]
    NoSolid {
        /// What was found instead.
        found: String,
    },
    /// The union of crossing parts failed.
    #[error("{0}")]
    Union(String),
}
