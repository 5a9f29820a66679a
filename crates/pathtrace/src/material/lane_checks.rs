//! The check every lane form's tests make: a group of lanes holding different models of one
//! kind gives each lane, bit for bit, what that lane's model gives on its own (its one-lane
//! instance), so lanes never leak into each other.

use super::lanes::{LaneDeltaScattering, LaneScattering, SmoothModel};
use super::BsdfSample;
use crate::math::{Rgb, Vec2, Vec3};
use crate::wide::simd::{F32s, Ms, Vec3s};

/// Reproducible numbers in [0, 1) for the tests' inputs: Marsaglia's xorshift32, top 24 bits.
pub(crate) struct Numbers(u32);

impl Numbers {
    pub fn new(seed: u32) -> Self {
        Numbers(seed)
    }

    pub fn next(&mut self) -> f32 {
        let x = &mut self.0;
        *x ^= *x << 13;
        *x ^= *x >> 17;
        *x ^= *x << 5;
        (*x >> 8) as f32 / (1u32 << 24) as f32
    }

    /// One number per lane.
    pub fn lanes<const N: usize>(&mut self) -> F32s<N> {
        F32s::from_fn(|_| self.next())
    }

    /// A unit direction (x, y in [−½, ½), z in [z0, z0 + z_span)), before normalising: tests
    /// choose how much of it lies below the surface.
    pub fn direction(&mut self, z0: f32, z_span: f32) -> Vec3 {
        Vec3::new(self.next() - 0.5, self.next() - 0.5, z0 + z_span * self.next()).normalize()
    }
}

fn rgb_bits(c: Rgb) -> [u32; 3] {
    c.to_array().map(f32::to_bits)
}

/// A sample as bits, so that NaN and the sign of zero count.
fn sample_bits(s: BsdfSample) -> ([u32; 3], [u32; 3], u32, bool, u32) {
    (s.wi.to_array().map(f32::to_bits), rgb_bits(s.weight), s.pdf.to_bits(), s.delta, s.eta.to_bits())
}

/// For `rounds` groups of N directions `wo`, `wi` from `direction`: lane `i` of `lanes`
/// evaluates (`eval_pdf`) and samples exactly as `model(i)` does alone. `seen` gets each lane's
/// `wo`, one-lane density of `wi` and one-lane sample, for the caller to check that every
/// branch was reached.
pub(crate) fn assert_smooth_lanes_match<const N: usize, M: SmoothModel>(
    lanes: &impl LaneScattering<N>,
    model: impl Fn(usize) -> M,
    numbers: &mut Numbers,
    rounds: usize,
    mut direction: impl FnMut(&mut Numbers) -> Vec3,
    mut seen: impl FnMut(Vec3, f32, Option<BsdfSample>),
) {
    for _ in 0..rounds {
        let wo: [Vec3; N] = std::array::from_fn(|_| direction(numbers));
        let wi: [Vec3; N] = std::array::from_fn(|_| direction(numbers));
        let u = [numbers.lanes::<N>(), numbers.lanes(), numbers.lanes()];
        let (wo_l, wi_l) = (Vec3s::from_fn(|i| wo[i]), Vec3s::from_fn(|i| wi[i]));
        let (f, pdf) = lanes.eval_pdf(&wo_l, &wi_l);
        let s = lanes.sample(&wo_l, u[0], u[1], u[2], Ms::ALL);
        for i in 0..N {
            let m = model(i);
            let (f1, pdf1) = m.eval_pdf(wo[i], wi[i]);
            assert_eq!([f[0].0[i], f[1].0[i], f[2].0[i]].map(f32::to_bits), rgb_bits(f1), "lane {i}");
            assert_eq!(pdf.0[i].to_bits(), pdf1.to_bits(), "lane {i}");
            let one = m.sample(wo[i], u[0].0[i], Vec2::new(u[1].0[i], u[2].0[i]));
            assert_eq!(s.lane(i).map(sample_bits), one.map(sample_bits), "lane {i}");
            seen(wo[i], pdf1, one);
        }
    }
}

/// `assert_smooth_lanes_match` over 300 groups of directions on both sides of the surface, for
/// a model whose every lane evaluates and samples some directions (Lambert-like lobes): at
/// least 1000 one-lane evaluations and samples must be non-zero, so the bits compared are not
/// all a zero's.
pub(crate) fn assert_mixed_lanes_match<const N: usize, M: SmoothModel>(
    lanes: &impl LaneScattering<N>,
    model: impl Fn(usize) -> M,
) {
    let (mut sampled, mut evaluated) = (0, 0);
    let mut numbers = Numbers::new(0x2545_f491);
    assert_smooth_lanes_match(
        lanes,
        model,
        &mut numbers,
        300,
        |n| n.direction(-0.1, 0.7),
        |_, pdf, one| {
            evaluated += usize::from(pdf > 0.0);
            sampled += usize::from(one.is_some());
        },
    );
    assert!(sampled > 1000 && evaluated > 1000, "{sampled} {evaluated}");
}

/// For `rounds` groups of N directions `wo` from `direction`: lane `i` of `lanes` samples
/// exactly as `one_lane(i, wo, u_lobe)` (lane `i`'s model alone). `seen` gets each lane's
/// index, `wo` and one-lane sample.
pub(crate) fn assert_delta_lanes_match<const N: usize>(
    lanes: &impl LaneDeltaScattering<N>,
    one_lane: impl Fn(usize, Vec3, f32) -> Option<BsdfSample>,
    numbers: &mut Numbers,
    rounds: usize,
    mut direction: impl FnMut(&mut Numbers) -> Vec3,
    mut seen: impl FnMut(usize, Vec3, Option<BsdfSample>),
) {
    for _ in 0..rounds {
        let wo: [Vec3; N] = std::array::from_fn(|_| direction(numbers));
        let u = numbers.lanes::<N>();
        let s = lanes.sample(&Vec3s::from_fn(|i| wo[i]), u, Ms::ALL);
        for (i, &wo_i) in wo.iter().enumerate() {
            let one = one_lane(i, wo_i, u.0[i]);
            assert_eq!(s.lane(i).map(sample_bits), one.map(sample_bits), "lane {i}, wo {wo_i:?}");
            seen(i, wo_i, one);
        }
    }
}
