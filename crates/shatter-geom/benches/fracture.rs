//! Criterion benchmarks: fracture (filled in by its module owner).

fn main() {}
