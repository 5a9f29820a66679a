//! Mitsuba 0.6's colour elements that Mitsuba 3 no longer reads, rewritten as `<rgb>`:
//!
//! - `<srgb value="r, g, b">` or `value="#rrggbb"`: an sRGB-encoded colour (0.6's
//!   `Spectrum::fromSRGB`), decoded to linear sRGB with the IEC 61966-2-1 transfer function
//!   (v ≤ 0.04045: v / 12.92, else ((v + 0.055) / 1.055)^2.4). Exact: no warning.
//! - `<blackbody temperature="4500K" scale="s">`: Planck's law in W·m⁻²·sr⁻¹·nm⁻¹ times `scale`
//!   (0.6's units). Mitsuba 3's RGB variants cannot evaluate a black body ("not implemented for
//!   non-spectral modes"), so the spectrum is converted to linear sRGB as Mitsuba 3 converts any
//!   sampled spectrum (spectrum.rs), with a warning naming the substitution.
//! - the 0.6-only `intent` attribute of `<rgb>`, `<srgb>` and `<spectrum>` (reflectance or
//!   illuminant upsampling in spectral builds) has no effect on RGB rendering and is removed.

use super::super::parse::{Attr, Element, XmlSource};
use super::super::spectrum::{blackbody_samples, spectrum_to_rgb, SpectrumUse};
use crate::native::SceneError;

type R<T> = Result<T, SceneError>;

/// IEC 61966-2-1 sRGB decoding of one channel.
pub fn srgb_to_linear(v: f64) -> f64 {
    if v <= 0.04045 {
        v / 12.92
    } else {
        ((v + 0.055) / 1.055).powf(2.4)
    }
}

/// The encoded channels of an `<srgb>` value: `#rrggbb`, or one or three numbers.
fn srgb_channels(text: &str) -> Result<[f64; 3], String> {
    let t = text.trim();
    if let Some(hex) = t.strip_prefix('#') {
        if hex.len() != 6 || !hex.bytes().all(|b| b.is_ascii_hexdigit()) {
            return Err(format!("`{t}` is not a #rrggbb colour (six hexadecimal digits after `#`)"));
        }
        let byte = |i: usize| u8::from_str_radix(&hex[i..i + 2], 16).map(|b| f64::from(b) / 255.0);
        return Ok([byte(0).unwrap_or(0.0), byte(2).unwrap_or(0.0), byte(4).unwrap_or(0.0)]);
    }
    let v: Vec<f64> = t
        .split(|c: char| c == ',' || c.is_whitespace())
        .filter(|s| !s.is_empty())
        .map(|s| s.parse::<f64>().ok().filter(|x| x.is_finite()))
        .collect::<Option<_>>()
        .ok_or_else(|| format!("`{t}` is not an sRGB colour: give three numbers `r, g, b` or `#rrggbb`"))?;
    match v.as_slice() {
        [s] => Ok([*s; 3]),
        [r, g, b] => Ok([*r, *g, *b]),
        _ => Err(format!("`{t}` has {} numbers: an sRGB colour needs three (or one)", v.len())),
    }
}

/// A number as written into a rewritten element (shortest round-trip form).
fn fmt(x: f64) -> String {
    format!("{x}")
}

/// Rewrites `c` (a child of a `<parent_tag>`) into `<rgb>` if it is `<srgb>` or `<blackbody>`, and drops
/// `intent` attributes.
pub fn upgrade_colour(parent_tag: &str, c: &mut Element, src: &XmlSource, warnings: &mut Vec<String>) -> R<()> {
    if matches!(c.tag.as_str(), "rgb" | "srgb" | "spectrum") {
        c.attrs.retain(|a| a.name != "intent");
    }
    let linear = match c.tag.as_str() {
        "srgb" => {
            let Some(text) = c.attr("value") else {
                return Err(src.error(c.offset, "<srgb> needs a `value` (\"r, g, b\" or \"#rrggbb\")"));
            };
            srgb_channels(text).map_err(|m| src.error(c.offset_of("value"), m))?.map(srgb_to_linear)
        }
        "blackbody" => {
            let kelvin = blackbody_temperature(c, src)?;
            let scale = match c.attr("scale") {
                None => 1.0,
                Some(t) => t.trim().parse::<f64>().ok().filter(|x| x.is_finite() && *x >= 0.0).ok_or_else(|| {
                    src.error(c.offset_of("scale"), format!("<blackbody> scale `{t}` is not a number ≥ 0"))
                })?,
            };
            let usage = if parent_tag == "emitter" { SpectrumUse::Emission } else { SpectrumUse::Reflectance };
            let rgb = spectrum_to_rgb(&blackbody_samples(kelvin), usage).rgb.map(|x| x * scale);
            warnings.push(format!(
                "{}: <blackbody> ({kelvin} K): Mitsuba 3's RGB variants cannot load a black body; using its \
                 spectrum converted to linear sRGB ({}, {}, {})",
                src.location(c.offset),
                fmt(rgb[0]),
                fmt(rgb[1]),
                fmt(rgb[2])
            ));
            rgb
        }
        _ => return Ok(()),
    };
    let at = c.offset_of("value");
    let name = c.attr_full("name").cloned();
    c.tag = "rgb".into();
    c.attrs = name.into_iter().collect();
    c.attrs.push(Attr { name: "value".into(), value: linear.map(fmt).join(", "), offset: at });
    Ok(())
}

/// `temperature="4500K"` or `"4500"`: a positive number of kelvins.
fn blackbody_temperature(c: &Element, src: &XmlSource) -> R<f64> {
    let Some(t) = c.attr("temperature") else {
        return Err(src.error(c.offset, "<blackbody> needs a `temperature` (in kelvins, e.g. \"4500K\")"));
    };
    let digits = t.trim().trim_end_matches(['K', 'k']).trim();
    digits.parse::<f64>().ok().filter(|k| k.is_finite() && *k > 0.0).ok_or_else(|| {
        src.error(
            c.offset_of("temperature"),
            format!("<blackbody> temperature `{t}` is not a positive number of kelvins"),
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_decodes_with_the_iec_curve() {
        assert_eq!(srgb_to_linear(0.0), 0.0);
        assert!((srgb_to_linear(1.0) - 1.0).abs() < 1e-12);
        assert!((srgb_to_linear(0.04) - 0.04 / 12.92).abs() < 1e-12);
        assert!((srgb_to_linear(0.5) - 0.214041).abs() < 1e-6);
        // #b39980 → (179, 153, 128) / 255.
        let c = srgb_channels("#b39980").unwrap().map(srgb_to_linear);
        for (a, b) in c.iter().zip([0.450786, 0.318547, 0.215861]) {
            assert!((a - b).abs() < 1e-6, "{c:?}");
        }
        assert_eq!(srgb_channels("0.5").unwrap(), [0.5; 3]);
        assert_eq!(srgb_channels(" 0.1 0.2, 0.3 ").unwrap(), [0.1, 0.2, 0.3]);
    }

    #[test]
    fn bad_srgb_values_are_named() {
        for bad in ["#b3998", "#b39980ff", "#gg0000", "0.1, 0.2", "red", "0.1, nan, 0.3"] {
            assert!(srgb_channels(bad).is_err(), "{bad}");
        }
        assert!(srgb_channels("#12345").unwrap_err().contains("#rrggbb"));
    }
}
