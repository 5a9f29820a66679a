//! glTF textures as native textures: the image (a file next to the glTF by its URI, or an image
//! embedded in a buffer view or a `data:` URI, named `scene.glb#images[N]`, see
//! [`super::images`]), its sampler's wrap and magnification filter, and `KHR_texture_transform`
//! on every slot (normal textures included). Only TEXCOORD_0 is read: a texture on another set
//! is an error the caller turns into a warning.

use super::images::reference;
use super::num;
use crate::native::model::{TextureDef, Triple, UvRows};

/// `KHR_texture_transform`'s parameters (the extension's defaults when absent).
struct Transform {
    offset: [f32; 2],
    rotation: f32,
    scale: [f32; 2],
    tex_coord: Option<u32>,
}

impl Transform {
    const NONE: Self = Self { offset: [0.0, 0.0], rotation: 0.0, scale: [1.0, 1.0], tex_coord: None };

    fn of_info(t: Option<gltf::texture::TextureTransform>) -> Self {
        t.map_or(Self::NONE, |t| Self {
            offset: t.offset(),
            rotation: t.rotation(),
            scale: t.scale(),
            tex_coord: t.tex_coord(),
        })
    }

    /// From the extension's JSON (the `gltf` crate parses it for `textureInfo`s only, not for
    /// a `normalTexture`); a malformed member is an error.
    fn of_json(v: Option<&serde_json::Value>) -> Result<Self, String> {
        let Some(v) = v else { return Ok(Self::NONE) };
        let bad = |what: &str| format!("KHR_texture_transform: `{what}` is not a valid value");
        let pair = |key: &str, default: [f32; 2]| -> Result<[f32; 2], String> {
            match v.get(key) {
                None => Ok(default),
                Some(p) => match p.as_array().map(|a| a.iter().map(serde_json::Value::as_f64).collect::<Vec<_>>()) {
                    Some(a) if a.len() == 2 && a.iter().all(Option::is_some) => {
                        Ok([a[0].unwrap_or(0.0) as f32, a[1].unwrap_or(0.0) as f32])
                    }
                    _ => Err(bad(key)),
                },
            }
        };
        let rotation = match v.get("rotation") {
            None => 0.0,
            Some(r) => r.as_f64().ok_or_else(|| bad("rotation"))? as f32,
        };
        let tex_coord = match v.get("texCoord") {
            None => None,
            Some(c) => Some(c.as_u64().and_then(|c| u32::try_from(c).ok()).ok_or_else(|| bad("texCoord"))?),
        };
        Ok(Self { offset: pair("offset", [0.0, 0.0])?, rotation, scale: pair("scale", [1.0, 1.0])?, tex_coord })
    }

    /// The matrix M = T·R·S (offset, rotation, scale; the extension's specification) as uv
    /// rows: glTF's uv convention (v down from the image's top row) is ours.
    fn to_uv(&self) -> UvRows {
        let (s, c) = self.rotation.sin_cos();
        let [sx, sy] = self.scale;
        [[c * sx, s * sy, self.offset[0]], [-s * sx, c * sy, self.offset[1]]].map(|r| r.map(num))
    }

    /// The texture coordinate set read: the transform's override, else the slot's own.
    fn check_set(&self, slot_set: u32) -> Result<(), String> {
        match self.tex_coord.unwrap_or(slot_set) {
            0 => Ok(()),
            n => Err(format!("TEXCOORD_{n} is not read (only TEXCOORD_0)")),
        }
    }
}

/// A colour texture (sRGB-decoded) from `info` of the glTF file `file_name` times `factor`
/// (glTF's baseColorFactor; 1 for an emissive texture, whose factor scales the radiance), or
/// why not.
pub fn colour_texture(info: &gltf::texture::Info, file_name: &str, factor: Triple) -> Result<TextureDef, String> {
    let t = Transform::of_info(info.texture_transform());
    t.check_set(info.tex_coord())?;
    let (filename, nearest, clamp) = image(&info.texture(), file_name);
    Ok(TextureDef::Bitmap { filename, raw: false, nearest, clamp, to_uv: t.to_uv(), alpha: false, factor })
}

/// One linear channel of `info`'s image times `factor` (glTF's metallic-roughness texture:
/// roughness in green, metallic in blue), `squared` after filtering for a roughness's α.
pub fn channel_texture(
    info: &gltf::texture::Info,
    file_name: &str,
    channel: u8,
    factor: f32,
    squared: bool,
) -> Result<TextureDef, String> {
    let t = Transform::of_info(info.texture_transform());
    t.check_set(info.tex_coord())?;
    let (filename, nearest, clamp) = image(&info.texture(), file_name);
    Ok(TextureDef::Channel { filename, channel, factor: num(factor), squared, nearest, clamp, to_uv: t.to_uv() })
}

/// A normal texture (read raw: its texels are directions) with its `KHR_texture_transform`,
/// or why not.
pub fn normal_texture(n: &gltf::material::NormalTexture, file_name: &str) -> Result<TextureDef, String> {
    let t = Transform::of_json(n.extension_value("KHR_texture_transform"))?;
    t.check_set(n.tex_coord())?;
    let (filename, nearest, clamp) = image(&n.texture(), file_name);
    Ok(TextureDef::Bitmap { filename, raw: true, nearest, clamp, to_uv: t.to_uv(), alpha: false, factor: Triple::ONE })
}

/// The image's native filename (a file next to the glTF, or a reference to the embedded image)
/// and its sampler's nearest filter and clamp.
fn image(texture: &gltf::Texture, file_name: &str) -> (String, bool, bool) {
    let source = texture.source();
    let filename = match source.source() {
        gltf::image::Source::Uri { uri, .. } if !uri.starts_with("data:") => super::document::percent_decode(uri),
        _ => reference(file_name, source.index()),
    };
    let sampler = texture.sampler();
    let clamp = sampler.wrap_s() == gltf::texture::WrappingMode::ClampToEdge;
    let nearest = sampler.mag_filter() == Some(gltf::texture::MagFilter::Nearest);
    (filename, nearest, clamp)
}
