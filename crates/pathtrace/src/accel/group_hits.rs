//! The closest hits of a group's rays, kept as lanes (structure of arrays) while the group walks
//! the tree: a primitive's hits are offered to all of its rays at once. With AVX-512 and groups
//! of 32 the offer is a few mask instructions per 16 rays (`x86::offer_32`), where a loop over
//! the hit lanes took a compare, a branch and five stores per ray: camera rays of one pixel hit
//! the same triangles, so most of a leaf's hits are offered to every ray of the group.

use super::lanes::HitL;
use super::leaf::offer;
use crate::shape::PrimHit;
use crate::wide::simd::{F32s, Ms};

/// Each ray's closest hit so far: distance (the ray's `t_max` before any hit), barycentrics,
/// primitive, and which rays have one.
pub(super) struct GroupHits<const N: usize> {
    pub t: F32s<N>,
    u: F32s<N>,
    v: F32s<N>,
    id: [u32; N],
    found: u32,
}

impl<const N: usize> GroupHits<N> {
    /// No hits yet; every ray reaches `t_max`.
    #[inline(always)]
    pub fn new(t_max: f32) -> Self {
        Self { t: F32s::splat(t_max), u: F32s::ZERO, v: F32s::ZERO, id: [0; N], found: 0 }
    }

    /// Ray `i`'s closest hit so far.
    #[inline(always)]
    pub fn get(&self, i: usize) -> Option<(PrimHit, u32)> {
        (self.found >> i & 1 != 0).then(|| (PrimHit { t: self.t.0[i], u: self.u.0[i], v: self.v.0[i] }, self.id[i]))
    }

    /// Ray `i`'s closest hit becomes `best` (found by a walk of its own, which started from
    /// [`GroupHits::get`] and the ray's `t`), if it has one.
    #[inline(always)]
    pub fn put(&mut self, i: usize, best: Option<(PrimHit, u32)>) {
        if let Some((hit, id)) = best {
            self.t.0[i] = hit.t;
            self.u.0[i] = hit.u;
            self.v.0[i] = hit.v;
            self.id[i] = id;
            self.found |= 1 << i;
        }
    }

    /// Every ray's closest hit.
    #[inline(always)]
    pub fn into_array(self) -> [Option<(PrimHit, u32)>; N] {
        std::array::from_fn(|i| self.get(i))
    }

    /// Offers primitive `id`'s hits `h` to the rays of `lanes` (a bitmask): each keeps the one
    /// that comes first in `leaf::offer`'s order (nearer, or as near and a lower primitive
    /// index). Rays are independent, so all at once gives each ray what one at a time gives.
    #[inline(always)]
    pub fn offer(&mut self, h: &HitL<F32s<N>>, id: u32, lanes: u32) {
        #[cfg(target_arch = "x86_64")]
        if N == 32 && std::arch::is_x86_feature_detected!("avx512f") && std::arch::is_x86_feature_detected!("avx512dq")
        {
            // SAFETY: the CPU was just checked to have AVX-512 F and DQ; N = 32.
            #[allow(unsafe_code)]
            unsafe {
                x86::offer_32(
                    as_32(&mut self.t.0),
                    as_32(&mut self.u.0),
                    as_32(&mut self.v.0),
                    as_32(&mut self.id),
                    &mut self.found,
                    [as_32_ref(&h.t.0), as_32_ref(&h.u.0), as_32_ref(&h.v.0)],
                    as_32_ref(&h.mask.0),
                    id,
                    lanes,
                );
            }
            return;
        }
        let mut hit = h.mask.bitmask() & lanes;
        while hit != 0 {
            let i = hit.trailing_zeros() as usize;
            hit &= hit - 1;
            let (mut t_max, mut best) = (self.t.0[i], self.get(i));
            offer(PrimHit { t: h.t.0[i], u: h.u.0[i], v: h.v.0[i] }, id, &mut t_max, &mut best);
            self.put(i, best);
        }
    }

    /// The least and greatest `t` over the rays of `mask`.
    #[inline(always)]
    pub fn t_range(&self, mask: Ms<N>) -> (f32, f32) {
        (self.t.min_over(mask), self.t.max_over(mask))
    }
}

/// `a` as 32 lanes (called where `N == 32`).
#[inline(always)]
fn as_32<T, const N: usize>(a: &mut [T; N]) -> &mut [T; 32] {
    a.as_mut_slice().try_into().expect("32 lanes")
}

#[inline(always)]
fn as_32_ref<T, const N: usize>(a: &[T; N]) -> &[T; 32] {
    a.as_slice().try_into().expect("32 lanes")
}

#[cfg(target_arch = "x86_64")]
#[allow(unsafe_code)]
mod x86 {
    use std::arch::x86_64::*;

    /// [`super::GroupHits::offer`] for 32 rays, 16 per step: the rays to update are one mask,
    /// `hit & (t < t_max | (t == t_max & (none yet | id < best id)))`, and every field is
    /// blended and stored whole (masked stores are not forwarded to the next full loads).
    ///
    /// # Safety
    /// The CPU must have AVX-512 F and DQ.
    #[inline]
    #[target_feature(enable = "avx512f,avx512dq")]
    #[allow(clippy::too_many_arguments)]
    pub(super) unsafe fn offer_32(
        t: &mut [f32; 32],
        u: &mut [f32; 32],
        v: &mut [f32; 32],
        ids: &mut [u32; 32],
        found: &mut u32,
        [ht, hu, hv]: [&[f32; 32]; 3],
        hmask: &[u32; 32],
        id: u32,
        lanes: u32,
    ) {
        let idv = _mm512_set1_epi32(id as i32);
        for o in [0, 16] {
            // SAFETY (all loads and stores): lanes o..o + 16 of 32-lane arrays.
            let hit =
                unsafe { _mm512_movepi32_mask(_mm512_loadu_si512(hmask.as_ptr().add(o).cast())) } & (lanes >> o) as u16;
            if hit == 0 {
                continue;
            }
            let new_t = unsafe { _mm512_loadu_ps(ht.as_ptr().add(o)) };
            let old_t = unsafe { _mm512_loadu_ps(t.as_ptr().add(o)) };
            let old_id = unsafe { _mm512_loadu_si512(ids.as_ptr().add(o).cast()) };
            let nearer = _mm512_cmp_ps_mask::<_CMP_LT_OQ>(new_t, old_t);
            let as_near = _mm512_cmp_ps_mask::<_CMP_EQ_OQ>(new_t, old_t);
            let lower = _mm512_cmplt_epu32_mask(idv, old_id);
            let none = !((*found >> o) as u16);
            let take = hit & (nearer | (as_near & (none | lower)));
            if take == 0 {
                continue;
            }
            unsafe {
                _mm512_storeu_ps(t.as_mut_ptr().add(o), _mm512_mask_blend_ps(take, old_t, new_t));
                let new_u = _mm512_loadu_ps(hu.as_ptr().add(o));
                let old_u = _mm512_loadu_ps(u.as_ptr().add(o));
                _mm512_storeu_ps(u.as_mut_ptr().add(o), _mm512_mask_blend_ps(take, old_u, new_u));
                let new_v = _mm512_loadu_ps(hv.as_ptr().add(o));
                let old_v = _mm512_loadu_ps(v.as_ptr().add(o));
                _mm512_storeu_ps(v.as_mut_ptr().add(o), _mm512_mask_blend_ps(take, old_v, new_v));
                _mm512_storeu_si512(ids.as_mut_ptr().add(o).cast(), _mm512_mask_blend_epi32(take, old_id, idv));
            }
            *found |= u32::from(take) << o;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Hits offered to a group's rays at once (AVX-512's `offer_32` at 32 lanes where the CPU has
    /// it, the loop otherwise) agree with `leaf::offer` ray by ray: distances drawn from a few
    /// values so that ties between primitives, and hits exactly at `t_max`, are common.
    #[test]
    fn lanes_keep_what_one_ray_at_a_time_keeps() {
        offers_agree::<8>();
        offers_agree::<16>();
        offers_agree::<32>();
    }

    fn offers_agree<const N: usize>() {
        let mut state = 0x9e37_79b9_u32;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 17;
            state ^= state << 5;
            state
        };
        for round in 0..200 {
            let t_max = if round % 2 == 0 { 4.0 } else { f32::INFINITY };
            let mut lanes = GroupHits::<N>::new(t_max);
            let mut one: [(f32, Option<(PrimHit, u32)>); N] = [(t_max, None); N];
            for _ in 0..6 {
                // Half the rounds draw ids on both sides of 2³¹, where a signed compare of
                // the ids would go wrong.
                let id = next() % 8 + if round % 4 < 2 { 0 } else { 0x7fff_fffc };
                let h = HitL {
                    mask: Ms(std::array::from_fn(|_| if next() % 3 == 0 { 0 } else { u32::MAX })),
                    t: F32s(std::array::from_fn(|_| [1.0, 2.0, 3.0, 4.0][(next() % 4) as usize])),
                    u: F32s(std::array::from_fn(|_| (next() % 100) as f32 / 100.0)),
                    v: F32s(std::array::from_fn(|_| (next() % 100) as f32 / 100.0)),
                };
                let rays = next();
                lanes.offer(&h, id, rays);
                for (i, (t, best)) in one.iter_mut().enumerate() {
                    if h.mask.0[i] != 0 && rays >> i & 1 != 0 {
                        let hit = PrimHit { t: h.t.0[i], u: h.u.0[i], v: h.v.0[i] };
                        offer(hit, id, t, best);
                    }
                }
            }
            for (i, (t, best)) in one.iter().enumerate() {
                assert_eq!(lanes.get(i), *best, "{N} lanes, round {round}, ray {i}");
                assert_eq!(lanes.t.0[i], *t, "{N} lanes, round {round}, ray {i}");
            }
        }
    }
}
