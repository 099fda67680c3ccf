//! Every layout: every field written and read back without disturbing the others, and
//! packed records converted to wide unchanged.

use super::*;

/// Writes every field of records 0..3 in any layout and reads them back.
fn fields_do_not_disturb_each_other<S: Store>(mut p: S, max_v: u32, max_t: u32) {
    let (vm, am) = (p.vertex_marker(), p.adjacency_marker());
    assert!(vm > max_v && am > (max_t << 2 | 3));
    for t in 0..3 {
        assert_eq!(p.push(), t);
        p.set_verts(t, [vm; 4]);
        for i in 0..4 {
            p.set_adj(t, i, am);
        }
    }
    let v = [max_v, 0, max_v / 2, vm];
    p.set_verts(1, v);
    p.add_flags(1, 2);
    let a = [max_t << 2 | 3, 0, 5, am];
    for (i, &x) in a.iter().enumerate() {
        p.set_adj(1, i, x);
    }
    // Neighbouring records keep their markers.
    for t in [0, 2] {
        assert_eq!(p.verts(t), [vm; 4]);
        assert_eq!(p.flags(t), 0);
        assert_eq!(p.adjs(t), [am; 4]);
    }
    assert_eq!(p.verts(1), v);
    assert_eq!(p.flags(1), 2);
    assert_eq!(p.adjs(1), a);
    assert!((0..4).all(|i| p.adj(1, i) == a[i]));
    // A whole record, then the vertices alone: that clears the flags, keeps the adjacency.
    let b = [0, max_t << 2 | 3, am, 7];
    p.add_flags(1, 3);
    p.write(1, [vm, max_v, 0, 1], b);
    assert_eq!(
        (p.verts(1), p.adjs(1), p.flags(1)),
        ([vm, max_v, 0, 1], b, 0)
    );
    assert_eq!((p.verts(0), p.adjs(2)), ([vm; 4], [am; 4]));
    p.write(1, v, a);
    p.set_verts(1, [1, 2, 3, 4]);
    assert_eq!(p.flags(1), 0);
    assert_eq!(p.adjs(1), a);
    p.add_flags(1, 3);
    p.clear_flags(1, 1);
    assert_eq!(p.flags(1), 2);
    assert_eq!(p.verts(1), [1, 2, 3, 4]);
}

#[test]
fn narrow_fields_do_not_disturb_each_other() {
    let max_t = <Narrow>::MAX_TETS as u32 - 1;
    fields_do_not_disturb_each_other(Narrow::with_capacity(3), <Narrow>::MAX_POINTS as u32, max_t);
}

#[test]
fn medium_fields_do_not_disturb_each_other() {
    let max_t = Medium::MAX_TETS as u32 - 1;
    assert_eq!(std::mem::size_of::<<Bits27 as Layout>::Rec>(), 27);
    const { assert!(Medium::MAX_POINTS >= 16_000_000 && Medium::MAX_TETS >= 134_000_000) };
    fields_do_not_disturb_each_other(Medium::with_capacity(3), Medium::MAX_POINTS as u32, max_t);
}

#[test]
fn wide_fields_do_not_disturb_each_other() {
    let max_t = Wide::MAX_TETS as u32 - 1;
    fields_do_not_disturb_each_other(Wide::with_capacity(3), (1 << 30) - 2, max_t);
}

#[test]
fn packed_records_convert_to_wide_unchanged() {
    converts_to_wide_unchanged(Narrow::with_capacity(8));
    converts_to_wide_unchanged(Medium::with_capacity(8));
}

fn converts_to_wide_unchanged(mut n: impl Store) {
    for t in 0..7u32 {
        n.push();
        n.set_verts(t, [t, t + 1, t + 2, 100]);
        for i in 0..4 {
            n.set_adj(t, i, n.adjacency_marker());
        }
        n.set_adj(t, 1, t << 2 | 1);
    }
    n.set_verts(6, [n.vertex_marker(); 4]);
    n.add_flags(3, 1);
    let w = Wide::from_store(&n, 0);
    assert_eq!(w.len(), 7);
    for t in 0..6u32 {
        assert_eq!(w.verts(t), [t, t + 1, t + 2, 100]);
        assert_eq!(w.adj(t, 1), t << 2 | 1);
        assert_eq!(w.adj(t, 0), w.adjacency_marker());
        assert_eq!(w.flags(t), u8::from(t == 3));
    }
    assert_eq!(w.verts(6), [w.vertex_marker(); 4]);
}
