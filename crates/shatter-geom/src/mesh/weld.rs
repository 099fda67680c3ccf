//! Welding: merging vertices at identical positions.

use glam::DVec3;

use super::TriMesh;
use crate::util::FastMap;

/// Hash key of a position: the bit patterns of its coordinates, with `-0.0` read as `0.0`
/// so that exactly equal coordinates always share a key.
pub(crate) fn position_key(p: DVec3) -> [u64; 3] {
    [
        (p.x + 0.0).to_bits(),
        (p.y + 0.0).to_bits(),
        (p.z + 0.0).to_bits(),
    ]
}

impl TriMesh {
    /// For each vertex, the index of the first vertex at exactly the same position, and
    /// the number of distinct positions. Welded index `k` is the `k`-th distinct position
    /// in order of first occurrence.
    ///
    /// ```
    /// use shatter_geom::shapes;
    /// let (map, distinct) = shapes::cube().weld_map();
    /// assert_eq!(map.len(), 24);
    /// assert_eq!(distinct, 8);
    /// ```
    pub fn weld_map(&self) -> (Vec<u32>, usize) {
        let mut seen: FastMap<[u64; 3], u32> = FastMap::default();
        seen.reserve(self.positions.len());
        let mut map = Vec::with_capacity(self.positions.len());
        for &p in &self.positions {
            let next = u32::try_from(seen.len()).expect("mesh exceeds u32 vertices");
            map.push(*seen.entry(position_key(p)).or_insert(next));
        }
        (map, seen.len())
    }

    /// The mesh with vertices at exactly equal positions merged (no tolerance). Unity-style
    /// shapes split vertices per face for flat normals and UV seams; topology (closed,
    /// manifold, wound consistently) is only meaningful on the welded mesh. Triangles keep
    /// their order and number, so per-triangle data stays valid; vertices are kept in order
    /// of first occurrence. Triangle indices must be in range (see
    /// [`validate_solid`](TriMesh::validate_solid)); out-of-range indices are kept as they
    /// are.
    ///
    /// ```
    /// use shatter_geom::shapes;
    /// let welded = shapes::cube().welded();
    /// assert_eq!(welded.positions.len(), 8);
    /// assert_eq!(welded.triangles.len(), 12);
    /// ```
    pub fn welded(&self) -> TriMesh {
        let (map, distinct) = self.weld_map();
        let mut positions = vec![DVec3::ZERO; distinct];
        for (i, &m) in map.iter().enumerate() {
            positions[m as usize] = self.positions[i];
        }
        let triangles = self
            .triangles
            .iter()
            .map(|t| t.map(|i| map.get(i as usize).copied().unwrap_or(i)))
            .collect();
        TriMesh::new(positions, triangles)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn negative_zero_welds_with_zero() {
        let m = TriMesh::new(
            vec![DVec3::new(0.0, 1.0, 0.0), DVec3::new(-0.0, 1.0, 0.0)],
            vec![],
        );
        assert_eq!(m.weld_map().1, 1);
    }

    #[test]
    fn close_but_unequal_positions_stay_apart() {
        let m = TriMesh::new(vec![DVec3::ZERO, DVec3::splat(1e-300)], vec![]);
        assert_eq!(m.weld_map().1, 2);
    }
}
