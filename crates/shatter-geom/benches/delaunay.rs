//! Criterion benchmarks: delaunay (filled in by its module owner).

fn main() {}
