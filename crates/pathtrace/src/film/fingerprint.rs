//! Fingerprints that tie a film to the render it belongs to, so that films of different scenes
//! or settings are never merged into one image.
//!
//! The hash is 64-bit FNV-1a (Fowler, Noll & Vo; the parameters of the IETF draft
//! draft-eastlake-fnv): a fixed, documented function, so every machine and build computes the
//! same value (the standard library's hasher may change between Rust releases). It guards
//! against mistakes, not adversaries.

use crate::render::RenderSettings;

const FNV_OFFSET: u64 = 0xcbf2_9ce4_8422_2325;
const FNV_PRIME: u64 = 0x0000_0100_0000_01b3;

/// A running FNV-1a hash.
#[derive(Clone, Copy, Debug)]
pub struct Fnv64(u64);

impl Default for Fnv64 {
    fn default() -> Self {
        Self(FNV_OFFSET)
    }
}

impl Fnv64 {
    pub fn write(&mut self, bytes: &[u8]) -> &mut Self {
        for &b in bytes {
            self.0 = (self.0 ^ u64::from(b)).wrapping_mul(FNV_PRIME);
        }
        self
    }

    /// Writes a length-prefixed field, so that ("ab", "c") and ("a", "bc") differ.
    pub fn field(&mut self, bytes: &[u8]) -> &mut Self {
        self.write(&(bytes.len() as u64).to_le_bytes()).write(bytes)
    }

    pub fn finish(&self) -> u64 {
        self.0
    }
}

/// The key of a render: `scene` (a hash of the scene's source, from the front end that loaded
/// it) and every setting a sample's value depends on — image size, the whole render's spp (the
/// stratified sampler's strata), sampler, filter, seed and path settings. Threads, tiles, waves,
/// the lane count and the sample range do not change a sample, so they are left out.
pub fn render_key(scene: u64, settings: &RenderSettings) -> u64 {
    let s = settings;
    let text = format!(
        "{}x{} spp={} sampler={:?} filter={:?} seed={} path={:?}",
        s.width, s.height, s.spp, s.sampler, s.filter, s.seed, s.path
    );
    Fnv64::default().write(&scene.to_le_bytes()).field(text.as_bytes()).finish()
}

/// The engine build films record: films of different builds may hold different samples.
pub fn engine_build() -> String {
    format!("pathtrace {} {}", env!("CARGO_PKG_VERSION"), std::env::consts::ARCH)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fnv_matches_the_published_test_vectors_and_keys_separate_settings() {
        // From the FNV reference test suite: FNV-1a 64 of "" and of "a".
        assert_eq!(Fnv64::default().finish(), 0xcbf29ce484222325);
        assert_eq!(Fnv64::default().write(b"a").finish(), 0xaf63dc4c8601ec8c);
        let s = RenderSettings::default();
        let k = render_key(1, &s);
        assert_eq!(k, render_key(1, &RenderSettings { threads: 3, tile_size: 8, ..s.clone() }));
        assert_ne!(k, render_key(2, &s));
        assert_ne!(k, render_key(1, &RenderSettings { seed: 1, ..s.clone() }));
        assert_ne!(k, render_key(1, &RenderSettings { spp: 65, ..s }));
    }
}
