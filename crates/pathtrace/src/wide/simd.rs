//! Eight-lane vectors (one path per lane) as plain arrays with lane-wise loops.
//!
//! Why arrays and not `std::arch`: every operation is a fixed eight-iteration loop over
//! `[f32; 8]`, which LLVM turns into single 256-bit instructions when the caller is compiled
//! for AVX2 (the render loop is, chosen at run time; see `render/tile.rs`) and into pairs of
//! 128-bit instructions in the portable build. The code stays safe, portable and bit-identical
//! across both builds (no fused multiply-adds are formed in either).

use std::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Not, Sub};

/// Number of lanes.
pub const LANES: usize = 8;

/// Eight `f32`s.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(C, align(32))]
pub struct F32x8(pub [f32; LANES]);

/// Eight lane conditions: all bits set (true) or clear (false) per lane, as SIMD compares give.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[repr(C, align(32))]
pub struct M8(pub [u32; LANES]);

#[inline(always)]
fn map(a: F32x8, f: impl Fn(f32) -> f32) -> F32x8 {
    let mut out = [0.0; LANES];
    for i in 0..LANES {
        out[i] = f(a.0[i]);
    }
    F32x8(out)
}

#[inline(always)]
fn zip(a: F32x8, b: F32x8, f: impl Fn(f32, f32) -> f32) -> F32x8 {
    let mut out = [0.0; LANES];
    for i in 0..LANES {
        out[i] = f(a.0[i], b.0[i]);
    }
    F32x8(out)
}

#[inline(always)]
fn compare(a: F32x8, b: F32x8, f: impl Fn(f32, f32) -> bool) -> M8 {
    let mut out = [0u32; LANES];
    for i in 0..LANES {
        out[i] = if f(a.0[i], b.0[i]) { u32::MAX } else { 0 };
    }
    M8(out)
}

impl F32x8 {
    pub const ZERO: F32x8 = F32x8([0.0; LANES]);
    pub const ONE: F32x8 = F32x8([1.0; LANES]);

    #[inline(always)]
    pub fn splat(v: f32) -> Self {
        F32x8([v; LANES])
    }

    /// Lane `i` of the result is `f(i)`.
    #[inline(always)]
    pub fn from_fn(f: impl FnMut(usize) -> f32) -> Self {
        F32x8(std::array::from_fn(f))
    }

    /// `a < b ? a : b` per lane (the SIMD min: with a NaN, `b`).
    #[inline(always)]
    pub fn min(self, b: Self) -> Self {
        zip(self, b, |a, b| if a < b { a } else { b })
    }

    /// `a > b ? a : b` per lane (the SIMD max: with a NaN, `b`).
    #[inline(always)]
    pub fn max(self, b: Self) -> Self {
        zip(self, b, |a, b| if a > b { a } else { b })
    }

    #[inline(always)]
    pub fn sqrt(self) -> Self {
        map(self, f32::sqrt)
    }

    #[inline(always)]
    pub fn abs(self) -> Self {
        map(self, f32::abs)
    }

    /// `mask ? a : b` per lane.
    #[inline(always)]
    pub fn select(mask: M8, a: Self, b: Self) -> Self {
        let mut out = [0.0; LANES];
        for i in 0..LANES {
            out[i] = f32::from_bits((a.0[i].to_bits() & mask.0[i]) | (b.0[i].to_bits() & !mask.0[i]));
        }
        F32x8(out)
    }

    #[inline(always)]
    pub fn lt(self, b: Self) -> M8 {
        compare(self, b, |a, b| a < b)
    }

    #[inline(always)]
    pub fn le(self, b: Self) -> M8 {
        compare(self, b, |a, b| a <= b)
    }

    #[inline(always)]
    pub fn gt(self, b: Self) -> M8 {
        compare(self, b, |a, b| a > b)
    }

    #[inline(always)]
    pub fn ge(self, b: Self) -> M8 {
        compare(self, b, |a, b| a >= b)
    }

    /// Finite lanes (neither infinite nor NaN).
    #[inline(always)]
    pub fn is_finite(self) -> M8 {
        let mut out = [0u32; LANES];
        for i in 0..LANES {
            out[i] = if self.0[i].is_finite() { u32::MAX } else { 0 };
        }
        M8(out)
    }
}

macro_rules! binary_op {
    ($trait:ident, $method:ident, $op:tt) => {
        impl $trait for F32x8 {
            type Output = F32x8;
            #[inline(always)]
            fn $method(self, b: F32x8) -> F32x8 {
                zip(self, b, |a, b| a $op b)
            }
        }
        impl $trait<f32> for F32x8 {
            type Output = F32x8;
            #[inline(always)]
            fn $method(self, b: f32) -> F32x8 {
                map(self, |a| a $op b)
            }
        }
        impl $trait<F32x8> for f32 {
            type Output = F32x8;
            #[inline(always)]
            fn $method(self, b: F32x8) -> F32x8 {
                map(b, |b| self $op b)
            }
        }
    };
}

binary_op!(Add, add, +);
binary_op!(Sub, sub, -);
binary_op!(Mul, mul, *);
binary_op!(Div, div, /);

impl Neg for F32x8 {
    type Output = F32x8;
    #[inline(always)]
    fn neg(self) -> F32x8 {
        map(self, |a| -a)
    }
}

impl M8 {
    pub const NONE: M8 = M8([0; LANES]);
    pub const ALL: M8 = M8([u32::MAX; LANES]);

    /// Lane `i` is `f(i)`.
    #[inline(always)]
    pub fn from_fn(mut f: impl FnMut(usize) -> bool) -> Self {
        M8(std::array::from_fn(|i| if f(i) { u32::MAX } else { 0 }))
    }

    #[inline(always)]
    pub fn lane(self, i: usize) -> bool {
        self.0[i] != 0
    }

    #[inline(always)]
    pub fn any(self) -> bool {
        self.0.iter().fold(0, |acc, &m| acc | m) != 0
    }

    /// One bit per lane, lane 0 lowest.
    #[inline(always)]
    pub fn bitmask(self) -> u32 {
        let mut bits = 0;
        for i in 0..LANES {
            bits |= (self.0[i] & 1) << i;
        }
        bits
    }
}

impl BitAnd for M8 {
    type Output = M8;
    #[inline(always)]
    fn bitand(self, b: M8) -> M8 {
        M8(std::array::from_fn(|i| self.0[i] & b.0[i]))
    }
}

impl BitOr for M8 {
    type Output = M8;
    #[inline(always)]
    fn bitor(self, b: M8) -> M8 {
        M8(std::array::from_fn(|i| self.0[i] | b.0[i]))
    }
}

impl Not for M8 {
    type Output = M8;
    #[inline(always)]
    fn not(self) -> M8 {
        M8(std::array::from_fn(|i| !self.0[i]))
    }
}

/// Three coordinates of eight vectors.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Vec3x8 {
    pub x: F32x8,
    pub y: F32x8,
    pub z: F32x8,
}

impl Vec3x8 {
    #[inline(always)]
    pub fn splat(v: glam::Vec3) -> Self {
        Self { x: F32x8::splat(v.x), y: F32x8::splat(v.y), z: F32x8::splat(v.z) }
    }

    /// Lane `i` is `f(i)`.
    #[inline(always)]
    pub fn from_fn(f: impl Fn(usize) -> glam::Vec3) -> Self {
        let mut out = Self::default();
        for i in 0..LANES {
            out.set(i, f(i));
        }
        out
    }

    #[inline(always)]
    pub fn lane(&self, i: usize) -> glam::Vec3 {
        glam::Vec3::new(self.x.0[i], self.y.0[i], self.z.0[i])
    }

    #[inline(always)]
    pub fn set(&mut self, i: usize, v: glam::Vec3) {
        self.x.0[i] = v.x;
        self.y.0[i] = v.y;
        self.z.0[i] = v.z;
    }

    /// `x·x' + y·y' + z·z'`, in glam's order.
    #[inline(always)]
    pub fn dot(&self, o: &Self) -> F32x8 {
        self.x * o.x + self.y * o.y + self.z * o.z
    }

    #[inline(always)]
    pub fn length(&self) -> F32x8 {
        self.dot(self).sqrt()
    }

    #[inline(always)]
    pub fn scale(&self, s: F32x8) -> Self {
        Self { x: self.x * s, y: self.y * s, z: self.z * s }
    }

    #[inline(always)]
    pub fn add(&self, o: &Self) -> Self {
        Self { x: self.x + o.x, y: self.y + o.y, z: self.z + o.z }
    }

    #[inline(always)]
    pub fn sub(&self, o: &Self) -> Self {
        Self { x: self.x - o.x, y: self.y - o.y, z: self.z - o.z }
    }

    #[inline(always)]
    pub fn neg(&self) -> Self {
        Self { x: -self.x, y: -self.y, z: -self.z }
    }

    /// Largest absolute coordinate per lane.
    #[inline(always)]
    pub fn max_abs(&self) -> F32x8 {
        self.x.abs().max(self.y.abs()).max(self.z.abs())
    }

    /// `mask ? a : b` per lane.
    #[inline(always)]
    pub fn select(mask: M8, a: &Self, b: &Self) -> Self {
        Self { x: F32x8::select(mask, a.x, b.x), y: F32x8::select(mask, a.y, b.y), z: F32x8::select(mask, a.z, b.z) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lane_ops_match_scalar_ops() {
        let a = F32x8::from_fn(|i| i as f32 - 3.5);
        let b = F32x8::from_fn(|i| 0.25 * i as f32 + 1.0);
        for i in 0..LANES {
            let (x, y) = (a.0[i], b.0[i]);
            assert_eq!((a + b).0[i], x + y);
            assert_eq!((a - b).0[i], x - y);
            assert_eq!((a * b).0[i], x * y);
            assert_eq!((a / b).0[i], x / y);
            assert_eq!(a.min(b).0[i], x.min(y));
            assert_eq!(a.max(b).0[i], x.max(y));
            assert_eq!(a.abs().sqrt().0[i], x.abs().sqrt());
            assert_eq!(a.lt(b).lane(i), x < y);
            assert_eq!(F32x8::select(a.lt(b), a, b).0[i], if x < y { x } else { y });
        }
    }

    #[test]
    fn masks_combine_and_summarise() {
        let m = M8::from_fn(|i| i % 3 == 0);
        assert_eq!(m.bitmask(), 0b0100_1001);
        assert!(m.any());
        assert!(!(m & !m).any());
        assert_eq!((m | !m), M8::ALL);
        let nan = F32x8::splat(f32::NAN);
        assert!(!nan.lt(F32x8::ONE).any() && !nan.ge(F32x8::ONE).any());
        assert_eq!(F32x8::from_fn(|i| if i == 2 { f32::INFINITY } else { 1.0 }).is_finite().bitmask(), 0b1111_1011);
    }
}
