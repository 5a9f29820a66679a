//! SIMD helpers shared by the primitive packets: the packet tests are written once over a lane
//! type ([`Lane`]) and run two ways — one ray against four primitives (`glam::Vec4`, lanes =
//! primitives: "structure of arrays" packets, as in Wald et al., "Embree: A Kernel Framework
//! for Efficient CPU Ray Tracing", SIGGRAPH 2014) and one primitive against a group of rays
//! (`F32s<N>`, lanes = rays: packet tracing, Wald et al., "Interactive Rendering with Coherent
//! Ray Tracing", 2001). Both execute the same operations per lane, so every ray gets the same
//! bits either way.

use std::ops::{Add, BitAnd, BitOr, Div, Mul, Not, Sub};

use glam::{BVec4A, Vec3, Vec4};

use crate::math::Ray;
use crate::wide::simd::{F32s, Ms, Vec3s};

/// A SIMD lane type of `f32`s: the operations the packet tests use.
pub(super) trait Lane:
    Copy + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self> + Div<Output = Self>
{
    type Mask: Copy + BitAnd<Output = Self::Mask> + BitOr<Output = Self::Mask> + Not<Output = Self::Mask>;
    fn splat(v: f32) -> Self;
    fn lt(self, o: Self) -> Self::Mask;
    fn le(self, o: Self) -> Self::Mask;
    fn ge(self, o: Self) -> Self::Mask;
    fn gt(self, o: Self) -> Self::Mask;
    /// `a < b ? a : b` per lane, and `a > b ? a : b` (the SIMD instructions' rule: with a NaN,
    /// `b`).
    fn min(self, o: Self) -> Self;
    fn max(self, o: Self) -> Self;
    /// Lanes that are finite and not zero.
    fn finite_nonzero(self) -> Self::Mask;
}

impl Lane for Vec4 {
    type Mask = BVec4A;
    #[inline(always)]
    fn splat(v: f32) -> Self {
        Vec4::splat(v)
    }
    #[inline(always)]
    fn lt(self, o: Self) -> BVec4A {
        self.cmplt(o)
    }
    #[inline(always)]
    fn le(self, o: Self) -> BVec4A {
        self.cmple(o)
    }
    #[inline(always)]
    fn ge(self, o: Self) -> BVec4A {
        self.cmpge(o)
    }
    #[inline(always)]
    fn gt(self, o: Self) -> BVec4A {
        self.cmpgt(o)
    }
    #[inline(always)]
    fn min(self, o: Self) -> Self {
        Vec4::min(self, o)
    }
    #[inline(always)]
    fn max(self, o: Self) -> Self {
        Vec4::max(self, o)
    }
    #[inline(always)]
    fn finite_nonzero(self) -> BVec4A {
        self.cmpne(Vec4::ZERO) & self.is_finite_mask()
    }
}

impl<const N: usize> Lane for F32s<N> {
    type Mask = Ms<N>;
    #[inline(always)]
    fn splat(v: f32) -> Self {
        F32s::splat(v)
    }
    #[inline(always)]
    fn lt(self, o: Self) -> Ms<N> {
        F32s::lt(self, o)
    }
    #[inline(always)]
    fn le(self, o: Self) -> Ms<N> {
        F32s::le(self, o)
    }
    #[inline(always)]
    fn ge(self, o: Self) -> Ms<N> {
        F32s::ge(self, o)
    }
    #[inline(always)]
    fn gt(self, o: Self) -> Ms<N> {
        F32s::gt(self, o)
    }
    #[inline(always)]
    fn min(self, o: Self) -> Self {
        F32s::min(self, o)
    }
    #[inline(always)]
    fn max(self, o: Self) -> Self {
        F32s::max(self, o)
    }
    /// As an integer range test on the magnitude's bits, `1 ≤ |x| ≤ f32::MAX`: written as two
    /// float tests, LLVM merges them into a floating-point class test that it then runs lane
    /// by lane (48 scalar instructions per test in the AVX-512 ray-lane triangle test).
    #[inline(always)]
    fn finite_nonzero(self) -> Ms<N> {
        Ms(self.0.map(|x| {
            let magnitude = x.to_bits() & 0x7fff_ffff;
            if magnitude.wrapping_sub(1) < f32::MAX.to_bits() {
                u32::MAX
            } else {
                0
            }
        }))
    }
}

/// Lane `k` of `v`, loaded from its place in memory. glam's `Index` for `Vec4` is a `match`
/// on the index, which LLVM kept as a jump table (an indirect jump per read) wherever the index
/// is not a constant: about 4% of the teapot's render-loop instructions (callgrind;
/// docs/benchmarks.md, "Lanes of four-wide vectors read by address").
#[inline(always)]
pub(super) fn lane_of(v: &Vec4, k: usize) -> f32 {
    v.as_ref()[k]
}

/// Three coordinates in lanes, one lane type per axis.
#[derive(Clone, Copy, Debug)]
pub(super) struct Vec3L<L> {
    pub x: L,
    pub y: L,
    pub z: L,
}

/// Three coordinates of four primitives, one `Vec4` per axis.
pub(super) type Vec3x4 = Vec3L<Vec4>;

impl<L: Lane> Vec3L<L> {
    #[inline(always)]
    pub fn splat(v: Vec3) -> Self {
        Self { x: L::splat(v.x), y: L::splat(v.y), z: L::splat(v.z) }
    }

    /// Lane-wise dot product, summed in glam's scalar order `x·x' + y·y' + z·z'` so that each
    /// lane rounds exactly as the scalar shape tests do.
    #[inline(always)]
    pub fn dot(&self, o: &Self) -> L {
        self.x * o.x + self.y * o.y + self.z * o.z
    }

    /// Lane-wise cross product, in glam's scalar operand order (bit-identical lanes).
    #[inline(always)]
    pub fn cross(&self, o: &Self) -> Self {
        Self { x: self.y * o.z - o.y * self.z, y: self.z * o.x - o.z * self.x, z: self.x * o.y - o.x * self.y }
    }

    #[inline(always)]
    pub fn sub(&self, o: &Self) -> Self {
        Self { x: self.x - o.x, y: self.y - o.y, z: self.z - o.z }
    }
}

impl<const N: usize> Vec3L<F32s<N>> {
    #[inline(always)]
    pub fn from_lanes(v: &Vec3s<N>) -> Self {
        Self { x: v.x, y: v.y, z: v.z }
    }
}

impl Vec3x4 {
    /// Packs up to four vectors; missing lanes are zero.
    pub fn gather(vs: &[Vec3]) -> Self {
        let lane = |i: usize, f: fn(&Vec3) -> f32| vs.get(i).map_or(0.0, f);
        let axis = |f: fn(&Vec3) -> f32| Vec4::new(lane(0, f), lane(1, f), lane(2, f), lane(3, f));
        Self { x: axis(|v| v.x), y: axis(|v| v.y), z: axis(|v| v.z) }
    }

    /// Packs `f` of up to four items; missing lanes are zero (no allocation).
    #[inline]
    pub fn gather_with<T>(items: &[T], f: impl Fn(&T) -> Vec3) -> Self {
        let mut v = [Vec3::ZERO; 4];
        for (slot, item) in v.iter_mut().zip(items) {
            *slot = f(item);
        }
        Self::gather(&v[..items.len().min(4)])
    }

    /// Coordinates of lane `k`.
    #[inline(always)]
    pub fn lane(&self, k: usize) -> Vec3 {
        Vec3::new(lane_of(&self.x, k), lane_of(&self.y, k), lane_of(&self.z, k))
    }
}

/// Rays in lanes: one ray broadcast to four lanes ([`RayX4`]), or a group of rays.
#[derive(Clone, Copy, Debug)]
pub(super) struct RayL<L> {
    pub origin: Vec3L<L>,
    pub dir: Vec3L<L>,
}

/// A ray broadcast to four lanes.
pub(super) type RayX4 = RayL<Vec4>;

impl RayX4 {
    #[inline(always)]
    pub fn new(ray: &Ray) -> Self {
        Self { origin: Vec3x4::splat(ray.origin), dir: Vec3x4::splat(ray.dir) }
    }
}

/// The rays of a lane group.
pub(super) type Rays<const N: usize> = RayL<F32s<N>>;

impl<const N: usize> Rays<N> {
    #[inline(always)]
    pub fn from_lanes(origin: &Vec3s<N>, dir: &Vec3s<N>) -> Self {
        Self { origin: Vec3L::from_lanes(origin), dir: Vec3L::from_lanes(dir) }
    }
}

/// Which lanes hit, and where.
#[derive(Clone, Copy, Debug)]
pub(super) struct HitL<L: Lane> {
    pub mask: L::Mask,
    pub t: L,
    pub u: L,
    pub v: L,
}

/// Hits of one ray on four primitives.
pub(super) type HitX4 = HitL<Vec4>;
