//! Colour parameters that may be textures: `albedo = 0.5`, `albedo = [0.2, 0.3, 0.4]`, or a
//! texture table —
//!
//! ```toml
//! albedo = { type = "checkerboard", color0 = 0.4, color1 = 0.2, scale = 8 }
//! albedo = { type = "bitmap", filename = "textures/wood.jpg", raw = false, to_uv = [[2, 0, 0], [0, 2, 0]] }
//! albedo = { type = "bitmap", filename = "base.png", factor = [0.9, 0.6, 0.3] }
//! alpha_texture = { type = "channel", filename = "mr.png", channel = "g", factor = 0.8, squared = true }
//! ```
//!
//! A `filename` of the form `scene.gltf#images[N]` (or `.glb`) names image N of that glTF file
//! (stored in one of its buffers, a `data:` URI or a file next to it).
//!
//! Tables are read into a flat [`RawTexture`] (unknown fields rejected) and checked into a
//! [`TextureDef`]; `scale` (one number or `[su, sv]`) and `to_uv` (rows `[a, b, tx]`,
//! `[c, d, ty]`) are two spellings of one uv transform, written back as `to_uv`.

use super::values::{Num, Triple, TripleVisitor};
use serde::de::{self, Deserializer, MapAccess, SeqAccess, Visitor};
use serde::{Deserialize, Serialize, Serializer};
use std::fmt;

/// A colour parameter: constant, or a texture.
#[derive(Clone, Debug, PartialEq)]
pub enum Colour {
    /// One colour everywhere.
    Constant(Triple),
    /// A colour that varies with the surface's (u, v).
    Texture(TextureDef),
}

impl Colour {
    /// A constant grey.
    pub fn grey(x: f32) -> Self {
        Colour::Constant(Triple::Splat(Num::from(x)))
    }

    /// The constant colour, if it is one.
    pub fn constant(&self) -> Option<Triple> {
        match self {
            Colour::Constant(t) => Some(*t),
            Colour::Texture(_) => None,
        }
    }
}

impl From<Triple> for Colour {
    fn from(t: Triple) -> Self {
        Colour::Constant(t)
    }
}

/// `[[a, b, tx], [c, d, ty]]`: uv' = [a b; c d]·uv + (tx, ty).
pub type UvRows = [[Num; 3]; 2];

/// The identity uv transform.
pub fn identity_uv() -> UvRows {
    let (o, z) = (Num::from(1.0), Num::from(0.0));
    [[o, z, z], [z, o, z]]
}

/// The texture types.
#[derive(Clone, Debug, PartialEq)]
pub enum TextureDef {
    /// Mitsuba's `checkerboard` (defaults color0 = 0.4, color1 = 0.2).
    Checkerboard { color0: Triple, color1: Triple, to_uv: UvRows },
    /// An image file (PNG, JPEG, EXR, HDR, PFM) relative to the scene file. 8-bit images are
    /// sRGB-decoded unless `raw`; float images are linear. `alpha`: the image's alpha channel
    /// (PNG, JPEG; 1 without one) as a grey texture (`channel = "alpha"`), for opacities.
    /// `factor` (default 1) multiplies every decoded texel: a colour, or one number for an
    /// alpha texture (glTF's baseColorFactor × baseColorTexture, glTF 2.0 §3.9.2).
    Bitmap { filename: String, raw: bool, nearest: bool, clamp: bool, to_uv: UvRows, alpha: bool, factor: Triple },
    /// One channel (`channel` 0, 1, 2 for r, g, b) of an image read raw (linear data, as glTF's
    /// metallic-roughness texture), as a grey texture times `factor`; `squared`: the filtered
    /// value is squared (glTF's roughness r gives α = r²).
    Channel { filename: String, channel: u8, factor: Num, squared: bool, nearest: bool, clamp: bool, to_uv: UvRows },
}

impl TextureDef {
    /// The image file it reads, if any (for edits such as rebasing paths).
    pub fn filename_mut(&mut self) -> Option<&mut String> {
        match self {
            TextureDef::Checkerboard { .. } => None,
            TextureDef::Bitmap { filename, .. } | TextureDef::Channel { filename, .. } => Some(filename),
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
enum TextureType {
    Checkerboard,
    Bitmap,
    Channel,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
enum FilterType {
    Bilinear,
    Nearest,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
enum Channel {
    Rgb,
    Alpha,
    R,
    G,
    B,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
enum WrapMode {
    Repeat,
    Clamp,
}

/// `scale = 8` or `scale = [8, 4]`.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize, Serialize)]
#[serde(untagged, expecting = "a number or [su, sv]")]
enum Scale {
    One(Num),
    Two([Num; 2]),
}

/// The file form of a texture table.
#[derive(Clone, Debug, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct RawTexture {
    #[serde(rename = "type")]
    kind: Option<TextureType>,
    #[serde(skip_serializing_if = "Option::is_none")]
    color0: Option<Triple>,
    #[serde(skip_serializing_if = "Option::is_none")]
    color1: Option<Triple>,
    #[serde(skip_serializing_if = "Option::is_none")]
    filename: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    raw: Option<bool>,
    #[serde(skip_serializing_if = "Option::is_none")]
    filter_type: Option<FilterType>,
    #[serde(skip_serializing_if = "Option::is_none")]
    wrap_mode: Option<WrapMode>,
    #[serde(skip_serializing_if = "Option::is_none")]
    channel: Option<Channel>,
    /// One number, or `[r, g, b]` for a colour bitmap.
    #[serde(skip_serializing_if = "Option::is_none")]
    factor: Option<Triple>,
    #[serde(skip_serializing_if = "Option::is_none")]
    squared: Option<bool>,
    #[serde(skip_serializing_if = "Option::is_none")]
    scale: Option<Scale>,
    #[serde(skip_serializing_if = "Option::is_none")]
    to_uv: Option<UvRows>,
}

impl TryFrom<RawTexture> for TextureDef {
    type Error = String;

    fn try_from(r: RawTexture) -> Result<Self, String> {
        let kind = r.kind.ok_or("a texture needs a `type` (checkerboard or bitmap)")?;
        let to_uv = match (r.scale, r.to_uv) {
            (Some(_), Some(_)) => return Err("give either `scale` or `to_uv`, not both".into()),
            (None, Some(rows)) => rows,
            (Some(s), None) => {
                let (su, sv) = match s {
                    Scale::One(x) => (x, x),
                    Scale::Two([a, b]) => (a, b),
                };
                let mut rows = identity_uv();
                (rows[0][0], rows[1][1]) = (su, sv);
                rows
            }
            (None, None) => identity_uv(),
        };
        let non_negative = |t: Option<Triple>, name: &str| -> Result<(), String> {
            match t {
                Some(t) if t.vec3().min_element() < 0.0 => Err(format!("`{name}` must be ≥ 0")),
                _ => Ok(()),
            }
        };
        match kind {
            TextureType::Checkerboard if r.factor.is_some() || r.squared.is_some() => {
                Err("`factor` and `squared` are parameters of bitmap and channel textures".into())
            }
            TextureType::Bitmap if r.squared.is_some() => Err("`squared` is a parameter of a channel texture".into()),
            TextureType::Checkerboard => {
                if let Some(f) = [("filename", r.filename.is_some()), ("raw", r.raw.is_some())]
                    .iter()
                    .chain(&[("filter_type", r.filter_type.is_some()), ("wrap_mode", r.wrap_mode.is_some())])
                    .chain(&[("channel", r.channel.is_some())])
                    .find(|f| f.1)
                {
                    return Err(format!("`{}` is not a parameter of a checkerboard texture", f.0));
                }
                non_negative(r.color0, "color0")?;
                non_negative(r.color1, "color1")?;
                Ok(TextureDef::Checkerboard {
                    color0: r.color0.unwrap_or(Triple::Splat(Num::from(0.4))),
                    color1: r.color1.unwrap_or(Triple::Splat(Num::from(0.2))),
                    to_uv,
                })
            }
            TextureType::Bitmap => {
                if r.color0.is_some() || r.color1.is_some() {
                    return Err("`color0` and `color1` are parameters of a checkerboard texture, not a bitmap".into());
                }
                if matches!(r.channel, Some(Channel::R | Channel::G | Channel::B)) {
                    return Err("a single colour channel is a `channel` texture, not a bitmap".into());
                }
                let filename = r.filename.ok_or("a bitmap texture needs a `filename`")?;
                let alpha = r.channel == Some(Channel::Alpha);
                if alpha && matches!(r.factor, Some(Triple::Each(_))) {
                    return Err("an alpha texture's `factor` is one number (it multiplies the alpha)".into());
                }
                non_negative(r.factor, "factor")?;
                Ok(TextureDef::Bitmap {
                    filename,
                    raw: r.raw.unwrap_or(false),
                    nearest: r.filter_type == Some(FilterType::Nearest),
                    clamp: r.wrap_mode == Some(WrapMode::Clamp),
                    to_uv,
                    alpha,
                    factor: r.factor.unwrap_or(Triple::ONE),
                })
            }
            TextureType::Channel => {
                if r.color0.is_some() || r.color1.is_some() || r.raw.is_some() {
                    return Err("a channel texture takes no `color0`, `color1` or `raw` (it reads raw data)".into());
                }
                let filename = r.filename.ok_or("a channel texture needs a `filename`")?;
                let channel = match r.channel {
                    Some(Channel::R) => 0,
                    Some(Channel::G) => 1,
                    Some(Channel::B) => 2,
                    _ => return Err("a channel texture needs `channel` = \"r\", \"g\" or \"b\"".into()),
                };
                let factor = match r.factor {
                    None => Num::from(1.0),
                    Some(Triple::Splat(x)) => x,
                    Some(Triple::Each(_)) => return Err("a channel texture's `factor` is one number".into()),
                };
                if factor.get() < 0.0 {
                    return Err("`factor` must be ≥ 0".into());
                }
                Ok(TextureDef::Channel {
                    filename,
                    channel,
                    factor,
                    squared: r.squared.unwrap_or(false),
                    nearest: r.filter_type == Some(FilterType::Nearest),
                    clamp: r.wrap_mode == Some(WrapMode::Clamp),
                    to_uv,
                })
            }
        }
    }
}

impl From<&TextureDef> for RawTexture {
    fn from(t: &TextureDef) -> Self {
        let mut r = RawTexture::default();
        let to_uv = match t {
            TextureDef::Checkerboard { color0, color1, to_uv } => {
                (r.kind, r.color0, r.color1) = (Some(TextureType::Checkerboard), Some(*color0), Some(*color1));
                to_uv
            }
            TextureDef::Bitmap { filename, raw, nearest, clamp, to_uv, alpha, factor } => {
                (r.kind, r.filename) = (Some(TextureType::Bitmap), Some(filename.clone()));
                r.channel = alpha.then_some(Channel::Alpha);
                r.factor = (*factor != Triple::ONE).then_some(*factor);
                r.raw = raw.then_some(true);
                r.filter_type = nearest.then_some(FilterType::Nearest);
                r.wrap_mode = clamp.then_some(WrapMode::Clamp);
                to_uv
            }
            TextureDef::Channel { filename, channel, factor, squared, nearest, clamp, to_uv } => {
                (r.kind, r.filename) = (Some(TextureType::Channel), Some(filename.clone()));
                r.channel = Some([Channel::R, Channel::G, Channel::B][(*channel).min(2) as usize]);
                r.factor = (factor.get() != 1.0).then_some(Triple::Splat(*factor));
                r.squared = squared.then_some(true);
                r.filter_type = nearest.then_some(FilterType::Nearest);
                r.wrap_mode = clamp.then_some(WrapMode::Clamp);
                to_uv
            }
        };
        r.to_uv = (*to_uv != identity_uv()).then_some(*to_uv);
        r
    }
}

impl Serialize for Colour {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            Colour::Constant(t) => t.serialize(s),
            Colour::Texture(t) => RawTexture::from(t).serialize(s),
        }
    }
}

struct ColourVisitor;

impl<'de> Visitor<'de> for ColourVisitor {
    type Value = Colour;
    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a number, an array of three numbers, or a texture table")
    }
    fn visit_f64<E: de::Error>(self, x: f64) -> Result<Colour, E> {
        TripleVisitor.visit_f64(x).map(Colour::Constant)
    }
    fn visit_i64<E: de::Error>(self, x: i64) -> Result<Colour, E> {
        TripleVisitor.visit_i64(x).map(Colour::Constant)
    }
    fn visit_u64<E: de::Error>(self, x: u64) -> Result<Colour, E> {
        TripleVisitor.visit_u64(x).map(Colour::Constant)
    }
    fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<Colour, A::Error> {
        TripleVisitor.visit_seq(seq).map(Colour::Constant)
    }
    fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<Colour, A::Error> {
        let raw = RawTexture::deserialize(de::value::MapAccessDeserializer::new(map))?;
        TextureDef::try_from(raw).map(Colour::Texture).map_err(de::Error::custom)
    }
}

impl<'de> Deserialize<'de> for Colour {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(ColourVisitor)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(s: &str) -> Result<Colour, String> {
        #[derive(Deserialize)]
        struct W {
            c: Colour,
        }
        toml::from_str::<W>(s).map(|w| w.c).map_err(|e| e.to_string())
    }

    #[test]
    fn constants_and_textures_parse() {
        assert_eq!(parse("c = 0.5").unwrap(), Colour::grey(0.5));
        let Colour::Texture(TextureDef::Checkerboard { color0, color1, to_uv }) =
            parse("c = { type = \"checkerboard\", scale = [8, 4] }").unwrap()
        else {
            panic!()
        };
        assert_eq!((color0.vec3().x, color1.vec3().x), (0.4, 0.2));
        assert_eq!((to_uv[0][0].get(), to_uv[1][1].get(), to_uv[0][1].get()), (8.0, 4.0, 0.0));
        let Colour::Texture(TextureDef::Bitmap { filename, raw, nearest, clamp, .. }) =
            parse("c = { type = \"bitmap\", filename = \"a.png\", raw = true, filter_type = \"nearest\" }").unwrap()
        else {
            panic!()
        };
        assert_eq!((filename.as_str(), raw, nearest, clamp), ("a.png", true, true, false));
    }

    #[test]
    fn bad_tables_are_located_and_explained() {
        let e = parse("c = { type = \"bitmap\" }").unwrap_err();
        assert!(e.contains("needs a `filename`") && e.contains("line 1"), "{e}");
        let e = parse("c = { type = \"checkerboard\",\n  colour0 = 1 }").unwrap_err();
        assert!(e.contains("unknown field `colour0`") && e.contains("line 2"), "{e}");
        assert!(parse("c = { type = \"checkerboard\", scale = 2, to_uv = [[1, 0, 0], [0, 1, 0]] }")
            .unwrap_err()
            .contains("not both"));
        assert!(parse("c = { type = \"checkerboard\", color0 = -1 }").unwrap_err().contains("≥ 0"));
        assert!(parse("c = { type = \"bitmap\", filename = \"a.png\", wrap_mode = \"mirror\" }")
            .unwrap_err()
            .contains("unknown variant"));
        assert!(parse("c = { type = \"noise\" }").unwrap_err().contains("unknown variant"));
        assert!(parse("c = { type = \"channel\", filename = \"a.png\" }").unwrap_err().contains("`channel`"));
        assert!(parse("c = { type = \"bitmap\", filename = \"a.png\", channel = \"g\" }")
            .unwrap_err()
            .contains("channel` texture"));
        assert!(parse("c = { type = \"checkerboard\", factor = 2 }").unwrap_err().contains("factor"));
        assert!(parse("c = { type = \"bitmap\", filename = \"a.png\", squared = true }")
            .unwrap_err()
            .contains("`squared`"));
        assert!(parse("c = { type = \"channel\", filename = \"a.png\", channel = \"r\", factor = [1, 1, 1] }")
            .unwrap_err()
            .contains("one number"));
        assert!(parse("c = { type = \"channel\", filename = \"a.png\", channel = \"r\", factor = -1 }")
            .unwrap_err()
            .contains("≥ 0"));
    }

    #[test]
    fn bitmap_factors_parse_with_default_one() {
        let factor = |text: &str| match parse(text) {
            Ok(Colour::Texture(TextureDef::Bitmap { factor, alpha, .. })) => (factor, alpha),
            other => panic!("{other:?}"),
        };
        assert_eq!(factor("c = { type = \"bitmap\", filename = \"a.png\" }"), (Triple::ONE, false));
        let (f, _) = factor("c = { type = \"bitmap\", filename = \"a.png\", factor = [0.9, 0.6, 0.3] }");
        assert_eq!(f.vec3().to_array(), [0.9, 0.6, 0.3]);
        let (f, alpha) = factor("c = { type = \"bitmap\", filename = \"a.png\", channel = \"alpha\", factor = 0.7 }");
        assert!(matches!(f, Triple::Splat(x) if x.get() == 0.7) && alpha, "{f:?}");
        // 1 is the default: not written back.
        let t = factor("c = { type = \"bitmap\", filename = \"a.png\", factor = 1 }").0;
        assert_eq!(t, Triple::ONE);
        let Colour::Texture(def) = parse("c = { type = \"bitmap\", filename = \"a.png\", factor = 1 }").unwrap() else {
            panic!()
        };
        assert!(!serde_json::to_string(&RawTexture::from(&def)).unwrap().contains("factor"));
    }

    /// Bad factors are errors that name the line of the texture (or of the bad number).
    #[test]
    fn bad_bitmap_factors_are_located() {
        for (text, expected) in [
            ("factor = -0.5", "`factor` must be ≥ 0"),
            ("factor = [0.5, -0.1, 1]", "`factor` must be ≥ 0"),
            ("factor = nan", "NaN is not allowed"),
            ("factor = [0.5, 0.5]", "three numbers"),
            ("factor = [1, 1, 1, 1]", "three numbers"),
            ("factor = \"red\"", "a number or an array of three numbers"),
            ("channel = \"alpha\", factor = [1, 0.5, 1]", "one number"),
        ] {
            let e = parse(&format!("\n\nc = {{ type = \"bitmap\", filename = \"a.png\", {text} }}")).unwrap_err();
            assert!(e.contains(expected) && e.contains("line 3"), "{text}: {e}");
        }
    }

    #[test]
    fn textures_round_trip_through_toml_and_json() {
        for text in [
            "c = { type = \"checkerboard\", color0 = [1, 0, 0], scale = 8 }",
            "c = { type = \"bitmap\", filename = \"t.exr\", wrap_mode = \"clamp\", to_uv = [[1, 2, 3], [4, 5, 6]] }",
            "c = [0.1, 0.2, 0.3]",
            "c = { type = \"bitmap\", filename = \"b.png\", factor = [0.9, 0.6, 0.3] }",
            "c = { type = \"bitmap\", filename = \"b.png\", channel = \"alpha\", factor = 0.7, raw = true }",
            "c = { type = \"channel\", filename = \"s.glb#images[2]\", channel = \"g\", factor = 0.5, squared = true }",
        ] {
            let c = parse(text).unwrap();
            let json = serde_json::to_string(&c).unwrap();
            assert_eq!(serde_json::from_str::<Colour>(&json).unwrap(), c, "{json}");
            let toml_text = toml::to_string(&std::collections::BTreeMap::from([("c", &c)])).unwrap();
            assert_eq!(parse(&toml_text).unwrap(), c, "{toml_text}");
        }
    }
}
