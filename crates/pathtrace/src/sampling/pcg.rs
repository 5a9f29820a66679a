//! PCG32 random numbers (O'Neill, "PCG: A Family of Simple Fast Space-Efficient Statistically
//! Good Algorithms for Random Number Generation", 2014): XSH-RR output on a 64-bit LCG.

/// A small, fast, seedable generator with independent streams.
#[derive(Clone, Debug)]
pub struct Pcg32 {
    state: u64,
    inc: u64,
}

/// The LCG multiplier.
const MULTIPLIER: u64 = 6_364_136_223_846_793_005;

impl Pcg32 {
    /// A generator on stream `stream`, started from `seed`. Always inlined, so the lane
    /// samplers' loop over it vectorises.
    #[inline(always)]
    pub fn new(seed: u64, stream: u64) -> Self {
        let mut rng = Self { state: 0, inc: (stream << 1) | 1 };
        rng.next_u32();
        rng.state = rng.state.wrapping_add(seed);
        rng.next_u32();
        rng
    }

    /// The generator's `(state, increment)`, for the lane samplers, which continue it in SIMD
    /// lanes with [`advance`] and [`output`].
    #[inline(always)]
    pub(crate) fn parts(&self) -> (u64, u64) {
        (self.state, self.inc)
    }

    /// The generator whose [`Pcg32::parts`] are `(state, inc)`.
    #[inline(always)]
    pub(crate) fn from_parts(state: u64, inc: u64) -> Self {
        Self { state, inc }
    }

    #[inline(always)]
    pub fn next_u32(&mut self) -> u32 {
        let old = self.state;
        self.state = advance(old, self.inc);
        output(old)
    }

    /// Uniform in `[0, 1)`: the top 24 bits, so the result is exactly representable and < 1.
    #[inline]
    pub fn next_f32(&mut self) -> f32 {
        unit_f32(self.next_u32())
    }
}

/// The LCG step. These three steps are free functions, always inlined, so the lane samplers
/// (`wide/sampler.rs`) run the same generator in SIMD lanes.
#[inline(always)]
pub(crate) fn advance(state: u64, inc: u64) -> u64 {
    state.wrapping_mul(MULTIPLIER).wrapping_add(inc)
}

/// The XSH-RR output permutation of the state before a step.
#[inline(always)]
pub(crate) fn output(old: u64) -> u32 {
    let xorshifted = (((old >> 18) ^ old) >> 27) as u32;
    let rot = (old >> 59) as u32;
    xorshifted.rotate_right(rot)
}

/// An output as a float in `[0, 1)`: its top 24 bits, so exactly representable and < 1.
#[inline(always)]
pub(crate) fn unit_f32(x: u32) -> f32 {
    (x >> 8) as f32 * (1.0 / 16_777_216.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uniform_floats_are_in_range_and_centred() {
        let mut rng = Pcg32::new(42, 7);
        let n = 100_000;
        let mut sum = 0.0f64;
        for _ in 0..n {
            let x = rng.next_f32();
            assert!((0.0..1.0).contains(&x));
            sum += x as f64;
        }
        let mean = sum / n as f64;
        // Standard error of the mean of U(0,1) is 1/sqrt(12 n) ≈ 0.0009; allow 5σ.
        assert!((mean - 0.5).abs() < 0.0046, "mean {mean}");
    }

    #[test]
    fn streams_differ() {
        let a: Vec<u32> = {
            let mut r = Pcg32::new(1, 1);
            (0..4).map(|_| r.next_u32()).collect()
        };
        let b: Vec<u32> = {
            let mut r = Pcg32::new(1, 2);
            (0..4).map(|_| r.next_u32()).collect()
        };
        assert_ne!(a, b);
    }
}
