//! A pass over the directed edges of a piece, undirected edge by undirected edge, with
//! a state per undirected edge and no hash map: the edges are bucketed by their lower
//! vertex (a counting sort, stable), and within a bucket the state sits in a scratch
//! slot of the upper vertex. The edges of one undirected edge come in their
//! [`Piece::edges`] order, so anything decided edge by edge in that order (which edge
//! pairs with which) comes out as a pass over all edges with a map would give it.

use super::Piece;

/// One directed edge of a piece: the element it bounds (triangle `t`, or face
/// `tris.len() + f`), its slot (`0..3` in a triangle, `3` in a face) and its vertices.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) struct Edge {
    /// Triangle index, or `tris.len() + f` for face `f`.
    pub elem: u32,
    /// Edge `k` of a triangle (`tri[k] → tri[k + 1]`); 3 for a face's edge.
    pub slot: u8,
    /// Start vertex.
    pub a: u32,
    /// End vertex.
    pub b: u32,
}

/// Calls `step(state, edge)` for every directed edge of `p`, where `state` is the
/// state of the edge's undirected edge (`S::default()` before its first directed
/// edge); the directed edges of one undirected edge come in [`Piece::edges`] order.
pub(crate) fn for_each_edge<S: Copy + Default>(p: &Piece, mut step: impl FnMut(&mut S, Edge)) {
    let nv = p.pos.len();
    let n = p.tris.len();
    let each = |visit: &mut dyn FnMut(Edge)| {
        for (t, tri) in p.tris.iter().enumerate() {
            for k in 0..3 {
                visit(Edge {
                    elem: t as u32,
                    slot: k as u8,
                    a: tri[k],
                    b: tri[(k + 1) % 3],
                });
            }
        }
        for (f, face) in p.faces.iter().enumerate() {
            for &(a, b) in &face.edges {
                visit(Edge {
                    elem: (n + f) as u32,
                    slot: 3,
                    a,
                    b,
                });
            }
        }
    };
    // Counting sort by the lower vertex (stable: the edges keep their order).
    let mut start = vec![0u32; nv + 1];
    each(&mut |e| start[e.a.min(e.b) as usize + 1] += 1);
    for v in 0..nv {
        start[v + 1] += start[v];
    }
    let mut fill: Vec<u32> = start[..nv].to_vec();
    let mut sorted = vec![Edge::default(); start[nv] as usize];
    each(&mut |e| {
        let at = &mut fill[e.a.min(e.b) as usize];
        sorted[*at as usize] = e;
        *at += 1;
    });
    // The state of undirected edge (v, u) in slot u while bucket v is walked; the
    // stamp (v + 1) tells a slot still holding an earlier bucket's state.
    let mut scratch: Vec<(u32, S)> = vec![(0, S::default()); nv];
    for v in 0..nv {
        for &e in &sorted[start[v] as usize..start[v + 1] as usize] {
            let slot = &mut scratch[e.a.max(e.b) as usize];
            if slot.0 != v as u32 + 1 {
                *slot = (v as u32 + 1, S::default());
            }
            step(&mut slot.1, e);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fracture::kernel::SURFACE;
    use glam::DVec3;

    /// On a tetrahedron every undirected edge sees its two directed edges, the first
    /// as `Piece::edges` lists them first.
    #[test]
    fn a_tetrahedron_pairs_each_edge_with_its_reverse_in_edge_order() {
        let p = Piece {
            pos: vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
            tris: vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]],
            tags: vec![SURFACE; 4],
            faces: Vec::new(),
        };
        let order: Vec<(u32, u32)> = p.edges().map(|(_, _, a, b)| (a, b)).collect();
        let at = |e: &Edge| order.iter().position(|&x| x == (e.a, e.b)).unwrap();
        let mut pairs = Vec::new();
        for_each_edge(&p, |first: &mut Option<Edge>, e| match first.take() {
            Some(f) => pairs.push((f, e)),
            None => *first = Some(e),
        });
        assert_eq!(pairs.len(), 6);
        for (f, e) in &pairs {
            assert_eq!((f.a, f.b), (e.b, e.a));
            assert!(at(f) < at(e));
            for x in [f, e] {
                let tri = p.tris[x.elem as usize];
                let k = x.slot as usize;
                assert_eq!((tri[k], tri[(k + 1) % 3]), (x.a, x.b));
            }
        }
    }
}
