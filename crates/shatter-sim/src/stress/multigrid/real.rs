//! The precision the multigrid's cycle runs in: `f32` (SIMD vectors, half the memory of
//! `f64`) in the solver, `f64` in tests that check the cycle's algebra exactly.

use std::fmt::Debug;
use std::ops::{Add, AddAssign, Mul, Neg, Sub, SubAssign};

use glam::{DMat3, DVec3, Mat3A, Vec3A};

/// A float type with its 3-vectors and 3×3 matrices.
pub(in crate::stress) trait Real:
    Copy + Debug + Default + Send + Sync + 'static
{
    /// The scalar.
    type S: Copy + Debug + Default + Mul<Self::V, Output = Self::V> + Into<f64>;
    /// A 3-vector.
    type V: Copy
        + Debug
        + Default
        + Add<Output = Self::V>
        + Sub<Output = Self::V>
        + AddAssign
        + SubAssign
        + Neg<Output = Self::V>
        + Mul<Self::S, Output = Self::V>;
    /// A 3×3 matrix.
    type M: Copy + Debug + Default;

    /// The zero vector.
    const ZERO: Self::V;

    fn scalar(s: f64) -> Self::S;
    fn vector(v: DVec3) -> Self::V;
    fn to_f64(v: Self::V) -> DVec3;
    fn matrix(m: DMat3) -> Self::M;
    /// `m·v`.
    fn mv(m: &Self::M, v: Self::V) -> Self::V;
    /// `mᵀ·v`.
    fn mtv(m: &Self::M, v: Self::V) -> Self::V;
}

/// Single precision, SIMD vectors.
#[derive(Debug, Clone, Copy, Default)]
pub(in crate::stress) struct F32;

/// Double precision.
#[cfg(test)]
#[derive(Debug, Clone, Copy, Default)]
pub(in crate::stress) struct F64;

impl Real for F32 {
    type S = f32;
    type V = Vec3A;
    type M = Mat3A;
    const ZERO: Vec3A = Vec3A::ZERO;

    #[inline]
    fn scalar(s: f64) -> f32 {
        s as f32
    }
    #[inline]
    fn vector(v: DVec3) -> Vec3A {
        v.as_vec3().into()
    }
    #[inline]
    fn to_f64(v: Vec3A) -> DVec3 {
        v.as_dvec3()
    }
    #[inline]
    fn matrix(m: DMat3) -> Mat3A {
        Mat3A::from(m.as_mat3())
    }
    #[inline]
    fn mv(m: &Mat3A, v: Vec3A) -> Vec3A {
        m.mul_vec3a(v)
    }
    #[inline]
    fn mtv(m: &Mat3A, v: Vec3A) -> Vec3A {
        m.transpose().mul_vec3a(v)
    }
}

#[cfg(test)]
impl Real for F64 {
    type S = f64;
    type V = DVec3;
    type M = DMat3;
    const ZERO: DVec3 = DVec3::ZERO;

    #[inline]
    fn scalar(s: f64) -> f64 {
        s
    }
    #[inline]
    fn vector(v: DVec3) -> DVec3 {
        v
    }
    #[inline]
    fn to_f64(v: DVec3) -> DVec3 {
        v
    }
    #[inline]
    fn matrix(m: DMat3) -> DMat3 {
        m
    }
    #[inline]
    fn mv(m: &DMat3, v: DVec3) -> DVec3 {
        *m * v
    }
    #[inline]
    fn mtv(m: &DMat3, v: DVec3) -> DVec3 {
        m.transpose() * v
    }
}
