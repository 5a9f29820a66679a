//! Lane groups (one path per lane; 8 lanes per AVX2 vector, 16 per AVX-512 vector) as plain arrays with
//! lane-wise loops.
//!
//! Why arrays and not `std::arch`: every operation is a fixed N-iteration loop over
//! `[f32; N]`, which LLVM turns into single 256-bit (512-bit) instructions when the caller is
//! compiled for AVX2 (AVX-512) — the render loop is, chosen at run time (see `render/tile.rs`) —
//! and into 128-bit instructions in the portable build. That needs the loops to reach LLVM's loop
//! vectoriser as loops: `.cargo/config.toml` stops LLVM from fully unrolling loops of more than 4
//! iterations first, after which only its SLP vectoriser could rebuild the vectors, and inside the
//! tile functions it left whole routines scalar (docs/benchmarks.md, "Lane loops kept as loops").
//! The code stays safe, portable and bit-identical across both builds (no fused multiply-adds are
//! formed in either).

use std::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Not, Sub};

/// Lanes per group where 256-bit vectors are the widest (AVX2, and the portable build).
pub const LANES_256: usize = 8;
/// Lanes per group on CPUs with AVX-512.
pub const LANES_512: usize = 16;

/// `N` `f32`s, one per lane.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(64))]
pub struct F32s<const N: usize>(pub [f32; N]);

/// `N` lane conditions: all bits set (true) or clear (false) per lane, as SIMD compares give.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(C, align(64))]
pub struct Ms<const N: usize>(pub [u32; N]);

impl<const N: usize> Default for F32s<N> {
    fn default() -> Self {
        Self([0.0; N])
    }
}

impl<const N: usize> Default for Ms<N> {
    fn default() -> Self {
        Self([0; N])
    }
}

#[inline(always)]
fn map<const N: usize>(a: F32s<N>, f: impl Fn(f32) -> f32) -> F32s<N> {
    let mut out = [0.0; N];
    for i in 0..N {
        out[i] = f(a.0[i]);
    }
    F32s(out)
}

#[inline(always)]
fn zip<const N: usize>(a: F32s<N>, b: F32s<N>, f: impl Fn(f32, f32) -> f32) -> F32s<N> {
    let mut out = [0.0; N];
    for i in 0..N {
        out[i] = f(a.0[i], b.0[i]);
    }
    F32s(out)
}

/// `f` folded over the lanes in halves (lanes `i` and `i + N/2`, then `i` and `i + N/4`, …): each
/// step is one vector operation, where a lane-by-lane fold is a chain of `N` scalar ones. The
/// steps are written out because a loop over them, five iterations for 32 lanes, is not
/// unrolled (`.cargo/config.toml` caps full unrolling at 4), and its inner loops would then
/// have unknown lengths. For up to 32 lanes, a power of two.
#[inline(always)]
fn fold_halves<const N: usize>(mut v: [f32; N], f: impl Fn(f32, f32) -> f32) -> f32 {
    const { assert!(N.is_power_of_two() && N <= 32) };
    if N >= 32 {
        for i in 0..16 {
            v[i] = f(v[i], v[i + 16]);
        }
    }
    if N >= 16 {
        for i in 0..8 {
            v[i] = f(v[i], v[i + 8]);
        }
    }
    if N >= 8 {
        for i in 0..4 {
            v[i] = f(v[i], v[i + 4]);
        }
    }
    if N >= 4 {
        for i in 0..2 {
            v[i] = f(v[i], v[i + 2]);
        }
    }
    if N >= 2 {
        v[0] = f(v[0], v[1]);
    }
    v[0]
}

#[inline(always)]
fn compare<const N: usize>(a: F32s<N>, b: F32s<N>, f: impl Fn(f32, f32) -> bool) -> Ms<N> {
    let mut out = [0u32; N];
    for i in 0..N {
        out[i] = if f(a.0[i], b.0[i]) { u32::MAX } else { 0 };
    }
    Ms(out)
}

impl<const N: usize> F32s<N> {
    pub const ZERO: F32s<N> = F32s([0.0; N]);
    pub const ONE: F32s<N> = F32s([1.0; N]);

    #[inline(always)]
    pub fn splat(v: f32) -> Self {
        F32s([v; N])
    }

    /// Lane `i` of the result is `f(i)`.
    #[inline(always)]
    pub fn from_fn(mut f: impl FnMut(usize) -> f32) -> Self {
        // A loop, not `array::from_fn`: that was compiled out of line, as a baseline-SSE
        // function called from inside the AVX kernels.
        let mut out = [0.0; N];
        for (i, o) in out.iter_mut().enumerate() {
            *o = f(i);
        }
        F32s(out)
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

    /// `f` applied to every lane (a loop the compiler vectorises when `f` has no branches or
    /// calls).
    #[inline(always)]
    pub fn map_lanes(self, f: impl Fn(f32) -> f32) -> Self {
        map(self, f)
    }

    #[inline(always)]
    pub fn sqrt(self) -> Self {
        map(self, f32::sqrt)
    }

    /// The magnitude of `self` with the sign of `sign` per lane (`f32::copysign`).
    #[inline(always)]
    pub fn copysign(self, sign: Self) -> Self {
        zip(self, sign, f32::copysign)
    }

    #[inline(always)]
    pub fn floor(self) -> Self {
        map(self, f32::floor)
    }

    #[inline(always)]
    pub fn abs(self) -> Self {
        map(self, f32::abs)
    }

    /// `f32::signum` per lane: ±1 by the sign bit (zeros included), NaN kept.
    #[inline(always)]
    pub fn signum(self) -> Self {
        map(self, f32::signum)
    }

    /// `mask ? a : b` per lane.
    #[inline(always)]
    pub fn select(mask: Ms<N>, a: Self, b: Self) -> Self {
        let mut out = [0.0; N];
        for i in 0..N {
            out[i] = f32::from_bits((a.0[i].to_bits() & mask.0[i]) | (b.0[i].to_bits() & !mask.0[i]));
        }
        F32s(out)
    }

    #[inline(always)]
    pub fn eq(self, b: Self) -> Ms<N> {
        compare(self, b, |a, b| a == b)
    }

    #[inline(always)]
    pub fn lt(self, b: Self) -> Ms<N> {
        compare(self, b, |a, b| a < b)
    }

    #[inline(always)]
    pub fn le(self, b: Self) -> Ms<N> {
        compare(self, b, |a, b| a <= b)
    }

    #[inline(always)]
    pub fn gt(self, b: Self) -> Ms<N> {
        compare(self, b, |a, b| a > b)
    }

    #[inline(always)]
    pub fn ge(self, b: Self) -> Ms<N> {
        compare(self, b, |a, b| a >= b)
    }

    /// The least lane of `mask` (+∞ without one), compared with `<` as [`F32s::min`] does.
    #[inline(always)]
    pub fn min_over(self, mask: Ms<N>) -> f32 {
        fold_halves(Self::select(mask, self, Self::splat(f32::INFINITY)).0, |a, b| if a < b { a } else { b })
    }

    /// The greatest lane of `mask` (−∞ without one), compared with `>` as [`F32s::max`] does.
    #[inline(always)]
    pub fn max_over(self, mask: Ms<N>) -> f32 {
        fold_halves(Self::select(mask, self, Self::splat(f32::NEG_INFINITY)).0, |a, b| if a > b { a } else { b })
    }

    /// Finite lanes (neither infinite nor NaN).
    #[inline(always)]
    pub fn is_finite(self) -> Ms<N> {
        let mut out = [0u32; N];
        for i in 0..N {
            out[i] = if self.0[i].is_finite() { u32::MAX } else { 0 };
        }
        Ms(out)
    }
}

macro_rules! binary_op {
    ($trait:ident, $method:ident, $op:tt) => {
        impl<const N: usize> $trait for F32s<N> {
            type Output = F32s<N>;
            #[inline(always)]
            fn $method(self, b: F32s<N>) -> F32s<N> {
                zip(self, b, |a, b| a $op b)
            }
        }
        impl<const N: usize> $trait<f32> for F32s<N> {
            type Output = F32s<N>;
            #[inline(always)]
            fn $method(self, b: f32) -> F32s<N> {
                map(self, |a| a $op b)
            }
        }
        impl<const N: usize> $trait<F32s<N>> for f32 {
            type Output = F32s<N>;
            #[inline(always)]
            fn $method(self, b: F32s<N>) -> F32s<N> {
                map(b, |b| self $op b)
            }
        }
    };
}

binary_op!(Add, add, +);
binary_op!(Sub, sub, -);
binary_op!(Mul, mul, *);
binary_op!(Div, div, /);

impl<const N: usize> Neg for F32s<N> {
    type Output = F32s<N>;
    #[inline(always)]
    fn neg(self) -> F32s<N> {
        map(self, |a| -a)
    }
}

impl<const N: usize> Ms<N> {
    pub const NONE: Ms<N> = Ms([0; N]);
    pub const ALL: Ms<N> = Ms([u32::MAX; N]);

    /// Lane `i` is `f(i)`.
    #[inline(always)]
    pub fn from_fn(mut f: impl FnMut(usize) -> bool) -> Self {
        // A loop for the reason given at `F32s::from_fn`.
        let mut out = [0; N];
        for (i, o) in out.iter_mut().enumerate() {
            *o = if f(i) { u32::MAX } else { 0 };
        }
        Ms(out)
    }

    #[inline(always)]
    pub fn lane(self, i: usize) -> bool {
        self.0[i] != 0
    }

    #[inline(always)]
    pub fn any(self) -> bool {
        self.0.iter().fold(0, |acc, &m| acc | m) != 0
    }

    /// The indices of the set lanes, lowest first (walking the bitmask: no branch per lane).
    #[inline(always)]
    pub fn lanes(self) -> impl Iterator<Item = usize> {
        let mut bits = self.bitmask();
        std::iter::from_fn(move || {
            (bits != 0).then(|| {
                let i = bits.trailing_zeros() as usize;
                bits &= bits - 1;
                i
            })
        })
    }

    /// One bit per lane, lane 0 lowest.
    ///
    /// Why the instructions: written as a loop, LLVM's vectoriser splits the compare that feeds
    /// the mask into pieces and ORs shifted lanes together (about 30 instructions in the BVH's
    /// box test, which takes four masks per node); `vmovmskps` reads 8 sign bits at once, and
    /// in AVX-512 code LLVM turns two of them into one `vpmovd2m`. Lanes are all bits set or
    /// clear, so the sign bit is the lane.
    ///
    /// Both ways take the lanes by value: a reference to them passed to the out-of-line
    /// fallback made the mask's memory escape, so LLVM wrote every mask out to the stack and
    /// read it back for its bits (11% of the zoomed teapot's profile sat on those reads).
    #[inline(always)]
    pub fn bitmask(self) -> u32 {
        #[cfg(target_arch = "x86_64")]
        if N == 2 * LANES_512 || N == LANES_512 || N == LANES_256 {
            if std::arch::is_x86_feature_detected!("avx") {
                // SAFETY: the CPU was just checked to have AVX.
                #[allow(unsafe_code)]
                return unsafe { x86::sign_bits(self.0) };
            }
            // Out of line, so that the compare feeding the mask stays whole above.
            return bitmask_out_of_line(self.0);
        }
        bitmask_loop(&self.0)
    }
}

/// [`Ms::bitmask`] as a loop (lane counts other than 8 and 16, and CPUs without AVX).
#[inline(always)]
fn bitmask_loop<const N: usize>(lanes: &[u32; N]) -> u32 {
    let mut bits = 0;
    for (i, &m) in lanes.iter().enumerate() {
        bits |= (m & 1) << i;
    }
    bits
}

/// [`bitmask_loop`] kept out of the SIMD code that calls [`Ms::bitmask`].
#[cfg(target_arch = "x86_64")]
#[cold]
#[inline(never)]
fn bitmask_out_of_line<const N: usize>(lanes: [u32; N]) -> u32 {
    bitmask_loop(&lanes)
}

/// The sign bits of the lanes, 8 at a time (`vmovmskps`), for 8, 16 or 32 lanes (chunks that cover
/// the lanes, shifts within 32 bits).
#[cfg(target_arch = "x86_64")]
#[allow(unsafe_code)]
mod x86 {
    use std::arch::x86_64::{_mm256_loadu_ps, _mm256_movemask_ps};

    /// # Safety
    /// The CPU must have AVX.
    #[inline]
    #[target_feature(enable = "avx")]
    pub(super) unsafe fn sign_bits<const N: usize>(lanes: [u32; N]) -> u32 {
        let mut bits = 0;
        for (k, eight) in lanes.chunks_exact(8).enumerate() {
            // SAFETY: the 32 bytes read are the chunk's 8 lanes.
            bits |= (_mm256_movemask_ps(unsafe { _mm256_loadu_ps(eight.as_ptr().cast()) }) as u32) << (8 * k);
        }
        bits
    }
}

impl<const N: usize> BitAnd for Ms<N> {
    type Output = Ms<N>;
    #[inline(always)]
    fn bitand(self, b: Ms<N>) -> Ms<N> {
        Ms(std::array::from_fn(|i| self.0[i] & b.0[i]))
    }
}

impl<const N: usize> BitOr for Ms<N> {
    type Output = Ms<N>;
    #[inline(always)]
    fn bitor(self, b: Ms<N>) -> Ms<N> {
        Ms(std::array::from_fn(|i| self.0[i] | b.0[i]))
    }
}

impl<const N: usize> Not for Ms<N> {
    type Output = Ms<N>;
    #[inline(always)]
    fn not(self) -> Ms<N> {
        Ms(std::array::from_fn(|i| !self.0[i]))
    }
}

/// Lanes whose RGB value (one lane group per channel) is zero in all three channels:
/// [`crate::math::Rgb::is_black`] per lane.
#[inline(always)]
pub fn rgb_black<const N: usize>(c: &[F32s<N>; 3]) -> Ms<N> {
    let zero = F32s::ZERO;
    c[0].eq(zero) & c[1].eq(zero) & c[2].eq(zero)
}

/// `f` applied to each of three channels (one lane group each).
///
/// Why not `[_; 3]::map`: inside the SIMD kernels LLVM compiled it out of line, as baseline
/// x86-64 code (SSE registers, a `vzeroupper` and a call per use, in the glass materials).
#[inline(always)]
pub fn map_rgb<T, U>(c: [T; 3], mut f: impl FnMut(T) -> U) -> [U; 3] {
    let [r, g, b] = c;
    [f(r), f(g), f(b)]
}

/// The value in `slot`, made by `make` if there is none yet: a group's per-kind lanes (of its
/// materials, of its lights) are set up when a lane first needs them.
///
/// Why not `Option::get_or_insert_with`: inside the SIMD kernels LLVM compiled it out of line,
/// as baseline x86-64 code, once per kind and vertex.
#[inline(always)]
pub fn made<T>(slot: &mut Option<T>, make: impl FnOnce() -> T) -> &mut T {
    if slot.is_none() {
        *slot = Some(make());
    }
    match slot {
        Some(value) => value,
        None => unreachable!("the slot was just filled"),
    }
}

/// Three coordinates of `N` vectors.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Vec3s<const N: usize> {
    pub x: F32s<N>,
    pub y: F32s<N>,
    pub z: F32s<N>,
}

impl<const N: usize> Vec3s<N> {
    #[inline(always)]
    pub fn splat(v: glam::Vec3) -> Self {
        Self { x: F32s::<N>::splat(v.x), y: F32s::<N>::splat(v.y), z: F32s::<N>::splat(v.z) }
    }

    /// Lane `i` is `f(i)`.
    #[inline(always)]
    pub fn from_fn(f: impl Fn(usize) -> glam::Vec3) -> Self {
        let mut out = Self::default();
        for i in 0..N {
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
    pub fn dot(&self, o: &Self) -> F32s<N> {
        self.x * o.x + self.y * o.y + self.z * o.z
    }

    #[inline(always)]
    pub fn length(&self) -> F32s<N> {
        self.dot(self).sqrt()
    }

    /// The unit vectors: times the reciprocal of the length, as glam's `Vec3::normalize`.
    #[inline(always)]
    pub fn normalize(&self) -> Self {
        self.scale(1.0 / self.length())
    }

    #[inline(always)]
    pub fn scale(&self, s: F32s<N>) -> Self {
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
    pub fn max_abs(&self) -> F32s<N> {
        self.x.abs().max(self.y.abs()).max(self.z.abs())
    }

    /// `mask ? a : b` per lane.
    #[inline(always)]
    pub fn select(mask: Ms<N>, a: &Self, b: &Self) -> Self {
        Self {
            x: F32s::<N>::select(mask, a.x, b.x),
            y: F32s::<N>::select(mask, a.y, b.y),
            z: F32s::<N>::select(mask, a.z, b.z),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const N: usize = LANES_256;

    #[test]
    fn extremes_over_a_mask_are_the_masked_lanes_extremes() {
        fn check<const M: usize>() {
            let v = F32s::<M>::from_fn(|i| ((i * 7919) % 31) as f32 - 15.25);
            for pattern in [0u32, 1, 0b1010, 0x8000_0001, 0xffff_ffff, 0x0f0f_f0f0, 1 << (M - 1)] {
                let mask = Ms::<M>::from_fn(|i| pattern >> i & 1 != 0);
                let lanes = || (0..M).filter(|&i| mask.lane(i)).map(|i| v.0[i]);
                assert_eq!(v.min_over(mask), lanes().fold(f32::INFINITY, f32::min), "{M} lanes, {pattern:#x}");
                assert_eq!(v.max_over(mask), lanes().fold(f32::NEG_INFINITY, f32::max), "{M} lanes, {pattern:#x}");
            }
        }
        check::<1>();
        check::<8>();
        check::<16>();
        check::<32>();
    }

    #[test]
    fn lane_ops_match_scalar_ops() {
        let a = F32s::<N>::from_fn(|i| i as f32 - 3.5);
        let b = F32s::<N>::from_fn(|i| 0.25 * i as f32 + 1.0);
        for i in 0..N {
            let (x, y) = (a.0[i], b.0[i]);
            assert_eq!((a + b).0[i], x + y);
            assert_eq!((a - b).0[i], x - y);
            assert_eq!((a * b).0[i], x * y);
            assert_eq!((a / b).0[i], x / y);
            assert_eq!(a.min(b).0[i], x.min(y));
            assert_eq!(a.max(b).0[i], x.max(y));
            assert_eq!(a.abs().sqrt().0[i], x.abs().sqrt());
            assert_eq!(a.lt(b).lane(i), x < y);
            assert_eq!(F32s::<N>::select(a.lt(b), a, b).0[i], if x < y { x } else { y });
        }
    }

    #[test]
    fn masks_combine_and_summarise() {
        let m = Ms::<N>::from_fn(|i| i % 3 == 0);
        assert_eq!(m.bitmask(), 0b0100_1001);
        assert_eq!(m.lanes().collect::<Vec<_>>(), vec![0, 3, 6]);
        assert_eq!(Ms::<N>::NONE.lanes().count(), 0);
        assert!(m.any());
        assert!(!(m & !m).any());
        assert_eq!((m | !m), Ms::<N>::ALL);
        let nan = F32s::<N>::splat(f32::NAN);
        assert!(!nan.lt(F32s::<N>::ONE).any() && !nan.ge(F32s::<N>::ONE).any());
        assert_eq!(F32s::<N>::from_fn(|i| if i == 2 { f32::INFINITY } else { 1.0 }).is_finite().bitmask(), 0b1111_1011);
    }

    /// Every lane count's bitmask (the instructions at 8, 16 and 32 lanes, the loop otherwise) is the
    /// loop's, for every pattern of 8 lanes and random ones of 16 and 32.
    #[test]
    fn bitmasks_of_every_width_agree_with_the_loop() {
        fn check<const W: usize>(bits: u32) {
            let m = Ms::<W>::from_fn(|i| bits >> i & 1 == 1);
            assert_eq!(m.bitmask(), bitmask_loop(&m.0), "{W} lanes, {bits:#b}");
            assert_eq!(m.bitmask(), bits & ((1u64 << W) - 1) as u32);
            assert_eq!(m.any(), m.bitmask() != 0);
        }
        for bits in 0..256 {
            check::<1>(bits);
            check::<4>(bits);
            check::<LANES_256>(bits);
        }
        let mut x = 0x9e37_79b9u32;
        for _ in 0..1000 {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            check::<LANES_512>(x & 0xffff);
        }
        check::<LANES_512>(0xffff);
        check::<LANES_512>(0);
        // The AVX-512 kernel's groups of two vectors.
        check::<{ 2 * LANES_512 }>(x);
        check::<{ 2 * LANES_512 }>(u32::MAX);
        check::<{ 2 * LANES_512 }>(0);
    }
}
