//! glTF textures as native image textures: an image stored as a file next to the glTF (a URI),
//! its sampler's wrap and magnification filter, and `KHR_texture_transform`. Images embedded in
//! a buffer or a `data:` URI are not supported yet (the caller falls back to the factor).

use super::document::percent_decode;
use super::num;
use crate::native::model::{TextureDef, UvRows};

/// The `KHR_texture_transform` matrix M = T·R·S (offset, rotation, scale; the extension's
/// specification) as uv rows: glTF's uv convention (v down from the image's top row) is ours.
fn to_uv(t: Option<gltf::texture::TextureTransform>) -> UvRows {
    let (offset, rotation, scale) = t.map_or(([0.0, 0.0], 0.0, [1.0, 1.0]), |t| (t.offset(), t.rotation(), t.scale()));
    let (s, c) = rotation.sin_cos();
    [[c * scale[0], s * scale[1], offset[0]], [-s * scale[0], c * scale[1], offset[1]]].map(|r| r.map(num))
}

/// A colour texture (sRGB-decoded) from `info`, or why not.
pub fn colour_texture(info: &gltf::texture::Info) -> Result<TextureDef, String> {
    if info.texture_transform().and_then(|t| t.tex_coord()).is_some_and(|c| c != 0) {
        return Err("only TEXCOORD_0 is supported".into());
    }
    image_texture(&info.texture(), info.tex_coord(), to_uv(info.texture_transform()), false)
}

/// A normal texture (read raw: its texels are directions), or why not. `KHR_texture_transform`
/// on it is not read (the caller warns).
pub fn normal_texture(n: &gltf::material::NormalTexture) -> Result<TextureDef, String> {
    image_texture(&n.texture(), n.tex_coord(), to_uv(None), true)
}

/// The image file of `texture` with its sampler's options.
fn image_texture(texture: &gltf::Texture, tex_coord: u32, to_uv: UvRows, raw: bool) -> Result<TextureDef, String> {
    if tex_coord != 0 {
        return Err("only TEXCOORD_0 is supported".into());
    }
    let filename = match texture.source().source() {
        gltf::image::Source::Uri { uri, .. } if !uri.starts_with("data:") => percent_decode(uri),
        _ => return Err("images embedded in the file are not supported yet".into()),
    };
    let sampler = texture.sampler();
    let clamp = sampler.wrap_s() == gltf::texture::WrappingMode::ClampToEdge;
    let nearest = sampler.mag_filter() == Some(gltf::texture::MagFilter::Nearest);
    Ok(TextureDef::Bitmap { filename, raw, nearest, clamp, to_uv, alpha: false })
}
