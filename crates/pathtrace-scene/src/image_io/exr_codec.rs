//! OpenEXR: scene-linear f32 RGB out; the first RGB(A) layer (f16, f32 or u32) in.

use std::io::{Seek, Write};
use std::path::Path;

use exr::prelude::{
    read_first_rgba_layer_from_file, AnyChannel, AnyChannels, FlatSamples, Image as ExrImage, MetaData, SmallVec,
    SpecificChannels, Vec2, WritableImage,
};
use pathtrace::film::Image;
use pathtrace::math::Rgb;

/// Writes `image` as 32-bit float RGB with lossless compression. The caller checks
/// that the image is non-empty and consistent.
pub(crate) fn encode(out: &mut (impl Write + Seek), image: &Image) -> exr::error::UnitResult {
    let width = image.width as usize;
    let channels = SpecificChannels::rgb(|Vec2(x, y): Vec2<usize>| {
        let p = image.pixels.get(y * width + x).copied().unwrap_or_default();
        (p.r, p.g, p.b)
    });
    ExrImage::from_channels((width, image.height as usize), channels).write().to_buffered(out)
}

/// Writes named 32-bit float channels of one `width × height` layer, each row-major from the top
/// left, with lossless compression. The caller checks that every channel has `width × height`
/// values and that the names are distinct.
pub(crate) fn encode_channels(
    out: &mut (impl Write + Seek),
    width: usize,
    height: usize,
    channels: Vec<(String, Vec<f32>)>,
) -> exr::error::UnitResult {
    let list: SmallVec<[AnyChannel<FlatSamples>; 4]> =
        channels.into_iter().map(|(name, values)| AnyChannel::new(name.as_str(), FlatSamples::F32(values))).collect();
    ExrImage::from_channels((width, height), AnyChannels::sort(list)).write().to_buffered(out)
}

/// The pixels being filled in while reading.
struct Pixels {
    width: usize,
    height: usize,
    data: Vec<Rgb>,
}

/// Reads the first layer with R, G and B channels (alpha, if any, is dropped).
pub(crate) fn decode(path: &Path) -> exr::error::Result<(usize, usize, Vec<Rgb>)> {
    let image = read_first_rgba_layer_from_file(
        path,
        |size: Vec2<usize>, _| Pixels {
            width: size.width(),
            height: size.height(),
            data: vec![Rgb::BLACK; size.area()],
        },
        |pixels: &mut Pixels, pos: Vec2<usize>, (r, g, b, _a): (f32, f32, f32, f32)| {
            let i = pos.y() * pixels.width + pos.x();
            if let Some(p) = pixels.data.get_mut(i) {
                *p = Rgb::new(r, g, b);
            }
        },
    )?;
    let pixels = image.layer_data.channel_data.pixels;
    Ok((pixels.width, pixels.height, pixels.data))
}

/// The size the first layer with R, G and B channels declares (its data window), read from the
/// header alone so it can be checked before [`decode`] allocates; `None` if the file has no such
/// layer or no readable header (then [`decode`] reports why).
pub(crate) fn declared_rgb_size(path: &Path) -> Option<(u64, u64)> {
    let meta = MetaData::read_from_file(path, false).ok()?;
    let header = meta.headers.iter().find(|h| has_rgb(h))?;
    Some((header.layer_size.width() as u64, header.layer_size.height() as u64))
}

fn has_rgb(header: &exr::meta::header::Header) -> bool {
    ["R", "G", "B"].iter().all(|want| header.channels.list.iter().any(|c| c.name.to_string() == *want))
}

/// If no layer of the file at `path` has R, G and B channels, the channel names it
/// does have (comma separated); `None` if it has such a layer or cannot be read.
pub(crate) fn missing_rgb_channels(path: &Path) -> Option<String> {
    let meta = MetaData::read_from_file(path, false).ok()?;
    if meta.headers.iter().any(has_rgb) {
        return None;
    }
    let names: Vec<String> =
        meta.headers.iter().flat_map(|h| h.channels.list.iter().map(|c| c.name.to_string())).collect();
    Some(if names.is_empty() { "none".to_owned() } else { names.join(", ") })
}
