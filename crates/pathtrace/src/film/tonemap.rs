//! Tone mapping and sRGB encoding: scene-linear radiance → display values.
//!
//! The pipeline for an 8-bit image is: multiply by `2^exposure`, apply the tone curve
//! (giving display-linear values in `[0, 1]`), then encode with the sRGB transfer
//! function and quantise ([`to_srgb8`]). Only `std` and [`Rgb`] are used here.

use std::fmt;
use std::str::FromStr;

use crate::math::Rgb;

/// A tone curve mapping scene-linear values to display-linear values in `[0, 1]`.
///
/// The default is [`ToneMap::Clamp`]: it leaves every value that fits on the display
/// unchanged, so a PNG shows the rendered radiance faithfully (and compares directly
/// with references), and only clips what is brighter than white. [`ToneMap::Aces`]
/// is a creative choice (it darkens mid-tones and changes saturation), so it is opt-in.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum ToneMap {
    /// Clip each channel to `[0, 1]` (also accepted as "linear").
    #[default]
    Clamp,
    /// Narkowicz's fitted ACES filmic curve, per channel (also accepted as "filmic").
    Aces,
}

impl ToneMap {
    /// The names [`ToneMap::from_str`] accepts, canonical names first.
    pub const ACCEPTED_NAMES: [&'static str; 4] = ["clamp", "aces", "linear", "filmic"];

    /// The canonical lowercase name ("clamp" or "aces").
    pub fn name(self) -> &'static str {
        match self {
            ToneMap::Clamp => "clamp",
            ToneMap::Aces => "aces",
        }
    }

    /// Applies the curve to one scene-linear channel value; NaN and negatives give 0.
    pub fn apply(self, x: f32) -> f32 {
        if x.is_nan() || x <= 0.0 {
            return 0.0;
        }
        match self {
            ToneMap::Clamp => x.min(1.0),
            ToneMap::Aces => aces_narkowicz(x),
        }
    }
}

/// Krzysztof Narkowicz, "ACES Filmic Tone Mapping Curve" (blog post, January 2016):
/// f(x) = x(2.51x + 0.03) / (x(2.43x + 0.59) + 0.14), clamped to [0, 1]. His fit is
/// pre-exposed (1 maps to about 0.8). Requires x > 0.
fn aces_narkowicz(x: f32) -> f32 {
    const A: f64 = 2.51;
    const B: f64 = 0.03;
    const C: f64 = 2.43;
    const D: f64 = 0.59;
    const E: f64 = 0.14;
    // Same curve with numerator and denominator divided by x, in f64, so huge (even
    // infinite) inputs neither overflow to inf/inf nor give NaN; the limit is A/C > 1.
    let x = f64::from(x.min(f32::MAX));
    let y = (A * x + B) / (C * x + D + E / x);
    y.clamp(0.0, 1.0) as f32
}

impl fmt::Display for ToneMap {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The error from parsing an unknown tone-map name.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ParseToneMapError {
    /// The name that was not recognised.
    pub input: String,
}

impl fmt::Display for ParseToneMapError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "unknown tone map {:?}: expected one of {}", self.input, ToneMap::ACCEPTED_NAMES.join(", "))
    }
}

impl std::error::Error for ParseToneMapError {}

impl FromStr for ToneMap {
    type Err = ParseToneMapError;

    /// Parses a name case-insensitively: "clamp" or "linear", "aces" or "filmic".
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.trim().to_ascii_lowercase().as_str() {
            "clamp" | "linear" => Ok(ToneMap::Clamp),
            "aces" | "filmic" => Ok(ToneMap::Aces),
            _ => Err(ParseToneMapError { input: s.to_owned() }),
        }
    }
}

/// How to turn scene-linear radiance into display values.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ToneMapSettings {
    /// Exposure in stops: radiance is multiplied by `2^exposure` before the curve.
    pub exposure: f32,
    /// The tone curve.
    pub tone_map: ToneMap,
}

impl ToneMapSettings {
    /// The linear multiplier `2^exposure`.
    pub fn exposure_scale(&self) -> f32 {
        self.exposure.exp2()
    }
}

/// Maps scene-linear `rgb` to display-linear values in `[0, 1]`: exposure, then the
/// curve per channel. NaN and negative channels (and a NaN exposure) give 0.
pub fn tone_map(rgb: Rgb, settings: &ToneMapSettings) -> Rgb {
    let scale = settings.exposure_scale();
    rgb.map(|c| settings.tone_map.apply(c * scale))
}

/// The sRGB transfer function (IEC 61966-2-1): display-linear → encoded, both in
/// `[0, 1]`. Inputs are clamped to `[0, 1]`; NaN gives 0.
pub fn srgb_encode(linear: f32) -> f32 {
    let x = clamp_unit(linear);
    // IEC 61966-2-1: 12.92·x up to 0.0031308, else 1.055·x^(1/2.4) − 0.055.
    if x <= 0.003_130_8 {
        12.92 * x
    } else {
        1.055 * x.powf(1.0 / 2.4) - 0.055
    }
}

/// The inverse sRGB transfer function (IEC 61966-2-1): encoded → display-linear, both
/// in `[0, 1]`. Inputs are clamped to `[0, 1]`; NaN gives 0.
pub fn srgb_decode(encoded: f32) -> f32 {
    let v = clamp_unit(encoded);
    // IEC 61966-2-1: v/12.92 up to 0.04045, else ((v + 0.055)/1.055)^2.4.
    if v <= 0.040_45 {
        v / 12.92
    } else {
        ((v + 0.055) / 1.055).powf(2.4)
    }
}

/// Tone maps `rgb`, encodes it as sRGB and quantises each channel to 8 bits,
/// rounding to nearest.
pub fn to_srgb8(rgb: Rgb, settings: &ToneMapSettings) -> [u8; 3] {
    tone_map(rgb, settings).to_array().map(|c| quantise8(srgb_encode(c)))
}

/// `[0, 1]` → `0..=255`, rounding to nearest.
fn quantise8(v: f32) -> u8 {
    // The `as` cast saturates, and `v` is already in [0, 1].
    (clamp_unit(v) * 255.0).round() as u8
}

/// Clamps to `[0, 1]`, sending NaN to 0.
fn clamp_unit(x: f32) -> f32 {
    if x > 0.0 {
        x.min(1.0)
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const CURVES: [ToneMap; 2] = [ToneMap::Clamp, ToneMap::Aces];

    fn close(a: f32, b: f32, tol: f32) -> bool {
        (a - b).abs() <= tol
    }

    #[test]
    fn parse_names_and_aliases() {
        assert_eq!("clamp".parse(), Ok(ToneMap::Clamp));
        assert_eq!("linear".parse(), Ok(ToneMap::Clamp));
        assert_eq!("ACES".parse(), Ok(ToneMap::Aces));
        assert_eq!(" filmic ".parse(), Ok(ToneMap::Aces));
        for t in CURVES {
            assert_eq!(t.to_string().parse(), Ok(t));
        }
    }

    #[test]
    fn parse_error_lists_accepted_names() {
        let err = "reinhard".parse::<ToneMap>().unwrap_err().to_string();
        assert!(err.contains("reinhard"), "{err}");
        for name in ToneMap::ACCEPTED_NAMES {
            assert!(err.contains(name), "{err}");
        }
    }

    #[test]
    fn defaults_are_clamp_and_zero_stops() {
        let s = ToneMapSettings::default();
        assert_eq!(s.tone_map, ToneMap::Clamp);
        assert_eq!(s.exposure, 0.0);
        assert_eq!(s.exposure_scale(), 1.0);
    }

    #[test]
    fn curves_are_monotonic_and_in_unit_range() {
        for t in CURVES {
            let mut prev = t.apply(0.0);
            assert_eq!(prev, 0.0);
            for i in 1..=20_000 {
                let x = i as f32 * 1e-3;
                let y = t.apply(x);
                assert!(y >= prev, "{t} not monotonic at {x}: {y} < {prev}");
                assert!((0.0..=1.0).contains(&y));
                prev = y;
            }
        }
    }

    #[test]
    fn clamp_is_identity_below_one() {
        for x in [0.0, 0.25, 0.5, 0.999, 1.0] {
            assert_eq!(ToneMap::Clamp.apply(x), x);
        }
        assert_eq!(ToneMap::Clamp.apply(7.0), 1.0);
    }

    #[test]
    fn aces_matches_the_published_curve() {
        // Direct evaluation of Narkowicz's formula at moderate x.
        for x in [0.01f32, 0.18, 0.5, 1.0, 2.0] {
            let direct = (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14);
            assert!(close(ToneMap::Aces.apply(x), direct.min(1.0), 1e-6), "{x}");
        }
        // Pre-exposed fit: 1 maps to about 0.8.
        assert!(close(ToneMap::Aces.apply(1.0), 0.8, 0.01));
    }

    #[test]
    fn aces_saturates_for_huge_inputs() {
        for x in [1e6, 1e30, f32::MAX, f32::INFINITY] {
            let y = ToneMap::Aces.apply(x);
            assert!(y <= 1.0 && y > 0.99, "{x} -> {y}");
        }
    }

    #[test]
    fn nan_and_negative_map_to_zero() {
        for t in CURVES {
            for x in [f32::NAN, -1.0, f32::NEG_INFINITY, -0.0] {
                assert_eq!(t.apply(x), 0.0, "{t} {x}");
            }
        }
        let s = ToneMapSettings::default();
        assert_eq!(tone_map(Rgb::new(f32::NAN, -2.0, 0.5), &s), Rgb::new(0.0, 0.0, 0.5));
        assert_eq!(to_srgb8(Rgb::splat(f32::NAN), &s), [0, 0, 0]);
        let nan_exposure = ToneMapSettings { exposure: f32::NAN, tone_map: ToneMap::Aces };
        assert_eq!(tone_map(Rgb::WHITE, &nan_exposure), Rgb::BLACK);
    }

    #[test]
    fn exposure_one_stop_doubles() {
        let s0 = ToneMapSettings::default();
        let s1 = ToneMapSettings { exposure: 1.0, ..s0 };
        let sm1 = ToneMapSettings { exposure: -1.0, ..s0 };
        let c = Rgb::new(0.1, 0.2, 0.4);
        assert_eq!(tone_map(c, &s1), tone_map(c * 2.0, &s0));
        assert_eq!(tone_map(c, &s1), c * 2.0);
        assert_eq!(tone_map(c, &sm1), c * 0.5);
    }

    #[test]
    fn srgb_known_values() {
        assert_eq!(srgb_encode(0.0), 0.0);
        assert!(close(srgb_encode(1.0), 1.0, 1e-6));
        assert!(close(srgb_encode(0.5), 0.735_357, 1e-5));
        assert!(close(srgb_encode(0.18), 0.461_356, 1e-5));
        assert!(close(srgb_encode(0.003_130_8), 0.040_45, 1e-5));
        assert!(close(srgb_decode(0.5), 0.214_041, 1e-5));
        assert!(close(srgb_decode(0.040_45), 0.003_130_8, 1e-6));
    }

    #[test]
    fn srgb_is_continuous_at_the_threshold() {
        let below = srgb_encode(0.003_130_8 - 1e-7);
        let above = srgb_encode(0.003_130_8 + 1e-7);
        assert!(close(below, above, 1e-5));
    }

    #[test]
    fn srgb_encode_is_monotonic_and_clamped() {
        let mut prev = srgb_encode(0.0);
        for i in 1..=10_000 {
            let y = srgb_encode(i as f32 / 10_000.0);
            assert!(y >= prev);
            prev = y;
        }
        assert_eq!(srgb_encode(-1.0), 0.0);
        assert_eq!(srgb_encode(f32::NAN), 0.0);
        assert!(close(srgb_encode(5.0), 1.0, 1e-6));
    }

    #[test]
    fn decode_inverts_encode() {
        for i in 0..=1000 {
            let x = i as f32 / 1000.0;
            assert!(close(srgb_decode(srgb_encode(x)), x, 1e-5), "{x}");
            assert!(close(srgb_encode(srgb_decode(x)), x, 1e-5), "{x}");
        }
    }

    #[test]
    fn srgb8_rounds_to_nearest() {
        let s = ToneMapSettings::default();
        assert_eq!(to_srgb8(Rgb::new(0.0, 1.0, 0.5), &s), [0, 255, 188]);
        // 0.5 encodes to 0.735357 → 187.52 → 188; a value just under 187.5/255 rounds down.
        let v = srgb_decode(187.4 / 255.0);
        assert_eq!(to_srgb8(Rgb::splat(v), &s), [187; 3]);
        assert_eq!(to_srgb8(Rgb::splat(100.0), &s), [255; 3]);
    }
}
