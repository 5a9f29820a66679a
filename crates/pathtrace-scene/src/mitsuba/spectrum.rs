//! Spectra given per wavelength (`<spectrum value="400:0.1, 500:0.3, …"/>` or an `.spd` file)
//! converted to linear sRGB the way Mitsuba 3's RGB variants do when they load a scene
//! (src/core/xml.cpp `create_texture_from_spectrum` and src/core/spectrum.cpp
//! `spectrum_list_to_srgb`):
//!
//! - the list is read as a piecewise-linear function of wavelength, zero outside its range;
//! - it is integrated against the CIE 1931 colour-matching functions with 1000 evenly spaced
//!   samples over 360–830 nm: XYZ = Σ x̄ȳz̄(λ) · v(λ) · w(λ) · Δλ, Δλ = 470/1000 nm;
//! - every value is scaled by 1/∫ȳ (`CIE_Y_NORMALIZATION`); a reflectance is further weighted by
//!   the D65 illuminant (scaled by `CIE_D65_NORMALIZATION` so that ∫ȳ·D65 ≈ ∫ȳ), so a flat
//!   reflectance 1 gives white (1, 1, 1) under sRGB's D65 white point; an emitter is not, so a
//!   flat emission spectrum 1 gives Y = 1 but, in sRGB, a slightly purple (1.20, 0.95, 0.91), as
//!   in Mitsuba;
//! - XYZ → linear sRGB with the sRGB/Rec. 709 matrix (IEC 61966-2-1);
//! - reflectances are clamped to [0, 1], emitters to ≥ 0.
//!
//! A single value is a constant: kept as is for reflectances, times xyz_to_srgb(1, 1, 1) for
//! emitters (Mitsuba does the same so that RGB and spectral renders agree).

use super::cie_tables::{CIE_D65_NORMALIZATION, CIE_MAX, CIE_MIN, CIE_STEP, CIE_TABLE, CIE_Y_NORMALIZATION};

/// XYZ → linear sRGB (row-major), IEC 61966-2-1, as in Mitsuba 3's `xyz_to_srgb`.
const XYZ_TO_SRGB: [[f64; 3]; 3] = [
    [3.240478992462158, -1.5371500253677368, -0.49853500723838806],
    [-0.9692559838294983, 1.8759909868240356, 0.04155600070953369],
    [0.05564799904823303, -0.20404300093650818, 1.0573110580444336],
];

/// What a spectrum describes: the two are normalised differently (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SpectrumUse {
    Reflectance,
    Emission,
}

/// An RGB colour converted from a spectrum, and whether it had to be clamped into range.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Converted {
    pub rgb: [f64; 3],
    pub clamped: bool,
}

/// x̄, ȳ, z̄ and D65 at `lambda` (nm), linearly interpolated in the 5 nm tables.
fn cie_at(lambda: f64) -> [f64; 4] {
    let t = ((lambda - CIE_MIN) / CIE_STEP).clamp(0.0, (CIE_TABLE.len() - 1) as f64);
    let i = (t as usize).min(CIE_TABLE.len() - 2);
    let f = t - i as f64;
    let (a, b) = (CIE_TABLE[i], CIE_TABLE[i + 1]);
    std::array::from_fn(|k| a[k] * (1.0 - f) + b[k] * f)
}

/// Linear sRGB of XYZ.
pub fn xyz_to_srgb(xyz: [f64; 3]) -> [f64; 3] {
    XYZ_TO_SRGB.map(|row| row[0] * xyz[0] + row[1] * xyz[1] + row[2] * xyz[2])
}

/// Converts a constant spectrum.
pub fn constant_to_rgb(value: f64, usage: SpectrumUse) -> [f64; 3] {
    match usage {
        SpectrumUse::Reflectance => [value; 3],
        SpectrumUse::Emission => xyz_to_srgb([1.0; 3]).map(|c| c * value),
    }
}

/// Converts `(wavelength nm, value)` pairs (wavelengths increasing, at least two) to linear sRGB.
pub fn spectrum_to_rgb(samples: &[(f64, f64)], usage: SpectrumUse) -> Converted {
    const STEPS: usize = 1000;
    let mut xyz = [0.0f64; 3];
    let (Some(first), Some(last)) = (samples.first(), samples.last()) else {
        return Converted { rgb: [0.0; 3], clamped: false };
    };
    for i in 0..STEPS {
        let lambda = CIE_MIN + (i as f64 / (STEPS - 1) as f64) * (CIE_MAX - CIE_MIN);
        if lambda < first.0 || lambda > last.0 {
            continue;
        }
        // The last sample at or before λ (the interval [k, k+1] that holds it).
        let k = samples.partition_point(|s| s.0 <= lambda).clamp(1, samples.len().max(2) - 1) - 1;
        let ((w0, v0), (w1, v1)) = (samples[k], samples[(k + 1).min(samples.len() - 1)]);
        let v = if w1 > w0 { v0 + (v1 - v0) * (lambda - w0) / (w1 - w0) } else { v0 };
        let cie = cie_at(lambda);
        let weight = match usage {
            SpectrumUse::Reflectance => cie[3] * CIE_D65_NORMALIZATION * CIE_Y_NORMALIZATION,
            SpectrumUse::Emission => CIE_Y_NORMALIZATION,
        };
        for c in 0..3 {
            xyz[c] += cie[c] * v * weight;
        }
    }
    let rgb = xyz_to_srgb(xyz.map(|c| c * (CIE_MAX - CIE_MIN) / STEPS as f64));
    let (lo, hi) = match usage {
        SpectrumUse::Reflectance => (0.0, 1.0),
        SpectrumUse::Emission => (0.0, f64::INFINITY),
    };
    let clamped = rgb.iter().any(|&c| c < lo || c > hi);
    Converted { rgb: rgb.map(|c| c.clamp(lo, hi)), clamped }
}

/// Spectral radiance of a black body at `kelvin`, in W·m⁻²·sr⁻¹·nm⁻¹, at `lambda_nm` (Planck's
/// law, B = 2hc² / (λ⁵ (e^{hc/(λkT)} − 1)), per nanometre), with the constants Mitsuba 3's
/// `blackbody` spectrum uses (src/spectra/blackbody.cpp; Mitsuba 0.6's `<blackbody>` has the
/// same units).
pub fn blackbody(lambda_nm: f64, kelvin: f64) -> f64 {
    const C: f64 = 2.99792458e8;
    const H: f64 = 6.62607004e-34;
    const K: f64 = 1.38064852e-23;
    let lambda = lambda_nm * 1e-9;
    1e-9 * 2.0 * H * C * C / (lambda.powi(5) * ((H * C / K / (lambda * kelvin)).exp() - 1.0))
}

/// A black body at `kelvin` sampled every nanometre over the colour-matching range, for
/// [`spectrum_to_rgb`] (whose linear interpolation is then exact to well below 0.1 %).
pub fn blackbody_samples(kelvin: f64) -> Vec<(f64, f64)> {
    (CIE_MIN as u32..=CIE_MAX as u32).map(|l| (l as f64, blackbody(l as f64, kelvin))).collect()
}

/// Parses an `.spd` file: one `wavelength value` pair per line, `#` comments.
pub fn parse_spd(text: &str) -> Result<Vec<(f64, f64)>, (usize, String)> {
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let line = line.split('#').next().unwrap_or("").trim();
        if line.is_empty() {
            continue;
        }
        let mut it = line.split_whitespace().map(str::parse::<f64>);
        match (it.next(), it.next(), it.next()) {
            (Some(Ok(w)), Some(Ok(v)), None) if w.is_finite() && v.is_finite() => out.push((w, v)),
            _ => return Err((i + 1, format!("`{line}` is not a `wavelength value` pair"))),
        }
    }
    Ok(out)
}

/// Checks that wavelengths increase strictly and that there are at least two samples.
pub fn check_samples(samples: &[(f64, f64)]) -> Result<(), String> {
    if samples.len() < 2 {
        return Err("a spectrum needs at least two wavelength:value pairs".into());
    }
    if samples.windows(2).any(|w| w[1].0 <= w[0].0) {
        return Err("wavelengths must increase".into());
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    const LIST: [(f64, f64); 4] = [(400.0, 0.1), (500.0, 0.3), (600.0, 0.6), (700.0, 0.9)];

    fn close(a: [f64; 3], b: [f64; 3], tol: f64) -> bool {
        a.iter().zip(b).all(|(x, y)| (x - y).abs() <= tol)
    }

    #[test]
    fn reflectances_match_mitsuba() {
        // Mitsuba 3.9.1 scalar_rgb loads this diffuse reflectance as (0.726577, 0.424956, 0.17397)
        // (read with mi.traverse, recorded in benches/peers/README.md).
        let c = spectrum_to_rgb(&LIST, SpectrumUse::Reflectance);
        assert!(close(c.rgb, [0.726577, 0.424956, 0.17397], 2e-5), "{:?}", c.rgb);
        assert!(!c.clamped);
        // A flat reflectance over the whole range is (almost exactly) grey.
        let flat = spectrum_to_rgb(&[(360.0, 0.5), (830.0, 0.5)], SpectrumUse::Reflectance);
        assert!(close(flat.rgb, [0.499493, 0.499437, 0.499401], 2e-5), "{:?}", flat.rgb);
    }

    #[test]
    fn emitters_match_mitsuba() {
        let c = spectrum_to_rgb(&LIST, SpectrumUse::Emission);
        assert!(close(c.rgb, [0.849361, 0.405349, 0.15115], 2e-5), "{:?}", c.rgb);
        assert!(close(constant_to_rgb(0.5, SpectrumUse::Emission), [0.602397, 0.474146, 0.454458], 2e-5));
        assert_eq!(constant_to_rgb(0.5, SpectrumUse::Reflectance), [0.5; 3]);
    }

    #[test]
    fn black_bodies_match_mitsuba() {
        // Mitsuba 3.9.1 scalar_spectral `blackbody` (temperature 4500) evaluated at 400, 550 and
        // 700 nm: 3929.78, 7091.77, 7435.50.
        for (l, v) in [(400.0, 3929.78125), (550.0, 7091.77392578125), (700.0, 7435.4951171875)] {
            assert!((blackbody(l, 4500.0) / v - 1.0).abs() < 1e-5, "{l}: {}", blackbody(l, 4500.0));
        }
        let s = blackbody_samples(4500.0);
        assert_eq!((s.len(), s[0].0, s[s.len() - 1].0), (471, 360.0, 830.0));
    }

    #[test]
    fn spd_files_parse_and_bad_lists_are_rejected() {
        assert_eq!(parse_spd("# c\n400 0.5\n\n700 1 # x\n").unwrap(), vec![(400.0, 0.5), (700.0, 1.0)]);
        assert_eq!(parse_spd("400 0.5\n500\n").unwrap_err().0, 2);
        assert!(check_samples(&[(400.0, 1.0)]).is_err());
        assert!(check_samples(&[(500.0, 1.0), (400.0, 1.0)]).is_err());
    }
}
