//! Integer hashing: decorrelated seeds from (seed, pixel, sample, dimension) tuples, and
//! hash-driven permutations for stratification.

/// 64-bit finaliser of SplitMix64 (Steele, Lea & Flood, "Fast splittable pseudorandom number
/// generators", OOPSLA 2014): a bijective mixer with full avalanche. Always inlined, so the
/// lane samplers' loops over it vectorise.
#[inline(always)]
pub fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// The hash of no words, where [`hash_words`] starts.
pub const HASH_START: u64 = 0x6a09_e667_f3bc_c909;

/// Hashes a list of words into one 64-bit value.
#[inline]
pub fn hash_words(words: &[u64]) -> u64 {
    words.iter().fold(HASH_START, |h, &w| hash_word(h, w))
}

/// One step of [`hash_words`]: the hash `h` of some words continued with `w`. Always inlined,
/// so the lane samplers' loops over it vectorise.
#[inline(always)]
pub fn hash_word(h: u64, w: u64) -> u64 {
    mix64(h ^ mix64(w.wrapping_add(0x9e37_79b9_7f4a_7c15)))
}

/// The `index`-th element of a pseudo-random permutation of `0..len`, chosen by `seed`.
///
/// Cycle-walking over a bijective hash on the next power-of-two domain, in the manner of
/// Kensler, "Correlated Multi-Jittered Sampling" (Pixar TM 13-01, 2013): every step below is a
/// bijection on `[0, 2^k)`, so walking until the value falls below `len` yields a permutation.
pub fn permutation_element(index: u32, len: u32, seed: u64) -> u32 {
    debug_assert!(len > 0 && index < len);
    if len == 1 {
        return 0;
    }
    let mask = u32::MAX >> (len - 1).leading_zeros();
    let mut i = index;
    loop {
        i = permutation_step(i, mask, seed);
        if i < len {
            return i;
        }
    }
}

/// [`permutation_element`] in `N` lanes, each with its own seed: the lanes take the hash steps
/// together until every lane's value falls below `len`, a lane that is done keeping its value,
/// so each lane gets exactly [`permutation_element`]'s answer.
#[inline(always)]
pub fn permutation_lanes<const N: usize>(index: &[u32; N], len: u32, seeds: &[u64; N]) -> [u32; N] {
    if len == 1 {
        return [0; N];
    }
    let mask = u32::MAX >> (len - 1).leading_zeros();
    // A loop, not `array::from_fn`: that was compiled out of the SIMD kernels.
    let mut i = [0; N];
    for (l, v) in i.iter_mut().enumerate() {
        *v = permutation_step(index[l], mask, seeds[l]);
    }
    while i.iter().any(|&v| v >= len) {
        for l in 0..N {
            let next = permutation_step(i[l], mask, seeds[l]);
            i[l] = if i[l] >= len { next } else { i[l] };
        }
    }
    i
}

/// One bijective hash step on `[0, mask]` (`mask + 1` a power of two) keyed by `seed`.
#[inline(always)]
fn permutation_step(mut i: u32, mask: u32, seed: u64) -> u32 {
    let s0 = seed as u32;
    let s1 = (seed >> 32) as u32 | 1;
    i ^= s0;
    i &= mask;
    i = i.wrapping_mul(s1 | 1) & mask;
    i ^= (i & mask) >> 4;
    i = i.wrapping_mul(0x9e37_79b9 | 1) & mask;
    i ^= (i & mask) >> 7;
    i = i.wrapping_add(s0 >> 8) & mask;
    i = i.wrapping_mul(0x2c1b_3c6d | 1) & mask;
    i ^= (i & mask) >> 11;
    i
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each lane gets `permutation_element`'s answer for its own index and seed, however many
    /// steps the other lanes need.
    #[test]
    fn permutation_lanes_match_one_at_a_time() {
        for len in [1u32, 2, 3, 7, 17, 100, 1000] {
            for round in 0..50u64 {
                let seeds: [u64; 16] = std::array::from_fn(|l| mix64(round * 16 + l as u64));
                let index: [u32; 16] = std::array::from_fn(|l| (l as u32 * 7 + round as u32) % len);
                let lanes = permutation_lanes(&index, len, &seeds);
                for l in 0..16 {
                    assert_eq!(lanes[l], permutation_element(index[l], len, seeds[l]), "len {len} lane {l}");
                }
            }
        }
    }

    #[test]
    fn permutations_are_bijections() {
        for len in [1u32, 2, 3, 7, 16, 17, 100, 1000] {
            for seed in [0u64, 1, 0xdead_beef_1234_5678] {
                let mut seen = vec![false; len as usize];
                for i in 0..len {
                    let p = permutation_element(i, len, seed) as usize;
                    assert!(!seen[p], "len {len} seed {seed}: {p} repeated");
                    seen[p] = true;
                }
            }
        }
    }

    #[test]
    fn different_seeds_give_different_permutations() {
        let a: Vec<u32> = (0..64).map(|i| permutation_element(i, 64, 1)).collect();
        let b: Vec<u32> = (0..64).map(|i| permutation_element(i, 64, 2)).collect();
        assert_ne!(a, b);
    }
}
