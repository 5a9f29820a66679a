//! The low-discrepancy sampler's point set: a padded, Owen-scrambled 2D Sobol' sequence
//! (Burley, "Practical Hash-based Owen Scrambling", JCGT 2020).
//!
//! Every 2D dimension pair uses the first two Sobol' dimensions (van der Corput in base 2, and
//! the Sobol' dimension with primitive polynomial x + 1, whose generator columns are
//! cᵢ = cᵢ₋₁ ⊕ (cᵢ₋₁ ≫ 1)); 1D dimensions use van der Corput. Each dimension gets its own
//! nested uniform (Owen) scramble, and each pixel and dimension its own shuffle of the sample
//! index, also an Owen scramble of the index bits — which permutes indices within every aligned
//! power-of-two block, so the first 2ᵏ samples of any pixel form a (0, k, 2)-net: every
//! elementary interval of area 2⁻ᵏ holds exactly one point.

/// Owen scrambling of a 32-bit fraction by a hash that only lets bits influence less
/// significant ones (computed on the bit-reversed value, where "less significant" becomes
/// "more significant", with the multiply/xor steps of Laine & Karras, "Stratified Sampling for
/// Stochastic Transparency", EGSR 2011). Always inlined, so the lane samplers' loops over it
/// vectorise.
#[inline(always)]
pub fn owen_scramble(x: u32, seed: u32) -> u32 {
    let mut v = x.reverse_bits();
    v = v.wrapping_add(seed);
    v ^= v.wrapping_mul(0x6c50_b47c);
    v ^= v.wrapping_mul(0xb82f_1e52);
    v ^= v.wrapping_mul(0xc7af_e638);
    v ^= v.wrapping_mul(0x8d22_f6e6);
    v.reverse_bits()
}

/// The sample index a pixel's `i`-th sample uses in a dimension with this `seed`. Index bit j
/// of the result depends only on bits j and above of `i`, so `[0, 2ᵏ)` maps one-to-one onto an
/// aligned block `[c·2ᵏ, (c+1)·2ᵏ)`.
#[inline]
pub fn shuffle(i: u32, seed: u32) -> u32 {
    owen_scramble(i, seed)
}

/// Sobol' dimension 0 (van der Corput, base 2) of point `i`, as a 32-bit fraction.
#[inline]
pub fn sobol_dim0(i: u32) -> u32 {
    i.reverse_bits()
}

/// The first generator column of Sobol' dimension 1, c₀ = 2³¹.
pub(crate) const DIM1_FIRST_COLUMN: u32 = 1 << 31;

/// The generator column after `c`: cᵢ = cᵢ₋₁ ⊕ (cᵢ₋₁ ≫ 1) (primitive polynomial x + 1).
#[inline(always)]
pub(crate) const fn dim1_next_column(c: u32) -> u32 {
    c ^ (c >> 1)
}

/// Generator columns of Sobol' dimension 1.
const fn columns() -> [u32; 32] {
    let mut c = [0u32; 32];
    let mut v = DIM1_FIRST_COLUMN;
    let mut i = 0;
    while i < 32 {
        c[i] = v;
        v = dim1_next_column(v);
        i += 1;
    }
    c
}

/// The XOR of the columns selected by each possible byte of the index, for each of its four
/// bytes: four table lookups instead of a loop over 32 bits.
const fn byte_tables() -> [[u32; 256]; 4] {
    let c = columns();
    let mut t = [[0u32; 256]; 4];
    let mut k = 0;
    while k < 4 {
        let mut b = 0;
        while b < 256 {
            let mut v = 0u32;
            let mut bit = 0;
            while bit < 8 {
                if b & (1 << bit) != 0 {
                    v ^= c[8 * k + bit];
                }
                bit += 1;
            }
            t[k][b] = v;
            b += 1;
        }
        k += 1;
    }
    t
}

static DIM1_TABLES: [[u32; 256]; 4] = byte_tables();

/// Sobol' dimension 1 of point `i`, as a 32-bit fraction.
#[inline]
pub fn sobol_dim1(i: u32) -> u32 {
    let [b0, b1, b2, b3] = i.to_le_bytes();
    DIM1_TABLES[0][b0 as usize]
        ^ DIM1_TABLES[1][b1 as usize]
        ^ DIM1_TABLES[2][b2 as usize]
        ^ DIM1_TABLES[3][b3 as usize]
}

/// A 32-bit fraction as a float in `[0, 1)` (the top 24 bits, exactly representable).
#[inline(always)]
pub fn to_unit(v: u32) -> f32 {
    (v >> 8) as f32 * (1.0 / 16_777_216.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// True if every elementary interval of area 1/n (n = 2^k) holds exactly one of the points.
    fn is_net(points: &[(f32, f32)]) -> bool {
        let n = points.len();
        let k = n.trailing_zeros();
        (0..=k).all(|kx| {
            let (nx, ny) = (1usize << kx, 1usize << (k - kx));
            let mut cells = vec![0; n];
            for &(x, y) in points {
                cells[(y * ny as f32) as usize * nx + (x * nx as f32) as usize] += 1;
            }
            cells.iter().all(|&c| c == 1)
        })
    }

    #[test]
    fn table_lookup_matches_the_bitwise_definition() {
        let c = columns();
        for i in [0u32, 1, 2, 3, 255, 256, 12345, 0xdead_beef, u32::MAX] {
            let direct = (0..32).filter(|b| i & (1 << b) != 0).fold(0, |v, b| v ^ c[b]);
            assert_eq!(sobol_dim1(i), direct, "i = {i}");
        }
    }

    #[test]
    fn unscrambled_points_form_nets() {
        for n in [4u32, 16, 64, 256] {
            let pts: Vec<_> = (0..n).map(|i| (to_unit(sobol_dim0(i)), to_unit(sobol_dim1(i)))).collect();
            assert!(is_net(&pts), "n = {n}");
        }
    }

    #[test]
    fn owen_scrambling_and_shuffling_keep_the_net_property() {
        for seed in [1u32, 0xdead_beef, 12345] {
            for n in [16u32, 64, 1024] {
                let pts: Vec<_> = (0..n)
                    .map(|i| {
                        let j = shuffle(i, seed ^ 0x5555);
                        (to_unit(owen_scramble(sobol_dim0(j), seed)), to_unit(owen_scramble(sobol_dim1(j), !seed)))
                    })
                    .collect();
                assert!(is_net(&pts), "seed {seed} n {n}");
            }
        }
    }

    #[test]
    fn shuffling_maps_power_of_two_blocks_onto_aligned_blocks() {
        let n = 64u32;
        let mut seen = vec![false; n as usize];
        let block = shuffle(0, 77) / n;
        for i in 0..n {
            let j = shuffle(i, 77);
            assert_eq!(j / n, block, "leaves the aligned block");
            assert!(!seen[(j % n) as usize], "not one-to-one");
            seen[(j % n) as usize] = true;
        }
    }
}
