//! Images inside a glTF file, for textures: a texture's `filename` `scene.glb#images[N]` names
//! image N of that file, whether its bytes sit in a buffer view (`.glb` files keep them there),
//! in a `data:` URI (base64) or in a file next to the glTF. Only PNG and JPEG, the formats the
//! glTF 2.0 core allows (§3.8.2), are read.

use super::document::{self, read_uri};
use std::path::Path;

/// `("scene.glb", 3)` for `scene.glb#images[3]` (a `.gltf` or `.glb` file, any case).
pub fn split_reference(filename: &str) -> Option<(&str, usize)> {
    let (file, rest) = filename.rsplit_once("#images[")?;
    let index = rest.strip_suffix(']')?.parse().ok()?;
    super::is_gltf(Path::new(file)).then_some((file, index))
}

/// The reference [`split_reference`] reads.
pub fn reference(file_name: &str, index: usize) -> String {
    format!("{file_name}#images[{index}]")
}

/// The encoded bytes of `images[index]` of the glTF file at `path`, with their format.
pub fn image_bytes(path: &Path, index: usize) -> Result<(Vec<u8>, image::ImageFormat), String> {
    let bytes = std::fs::read(path).map_err(|e| format!("cannot read `{}`: {e}", path.display()))?;
    let opened = document::open(&bytes, path).map_err(|e| format!("`{}`: {e}", path.display()))?;
    let at = format!("`{}`: images[{index}]", path.display());
    let image = opened.doc.images().nth(index).ok_or_else(|| {
        format!("`{}` has {} images: there is no images[{index}]", path.display(), opened.doc.images().count())
    })?;
    let (data, mime) = match image.source() {
        gltf::image::Source::View { view, mime_type } => {
            let buffer = &opened.buffers[view.buffer().index()];
            let end = view.offset().checked_add(view.length()).filter(|&end| end <= buffer.len()).ok_or_else(|| {
                format!(
                    "{at}: buffer view {} (bytes {}..+{}) runs past the end of buffer {} ({} bytes)",
                    view.index(),
                    view.offset(),
                    view.length(),
                    view.buffer().index(),
                    buffer.len()
                )
            })?;
            (buffer[view.offset()..end].to_vec(), Some(mime_type))
        }
        gltf::image::Source::Uri { uri, mime_type } => {
            let dir = path.parent().unwrap_or(Path::new(""));
            // A data: URI states its media type (`data:image/png;base64,…`).
            let stated = uri.strip_prefix("data:").and_then(|r| r.split_once(';')).map(|(m, _)| m);
            (read_uri(uri, dir).map_err(|e| format!("{at}: {e}"))?, mime_type.or(stated.filter(|m| !m.is_empty())))
        }
    };
    let format = match mime {
        Some("image/png") => image::ImageFormat::Png,
        Some("image/jpeg") => image::ImageFormat::Jpeg,
        Some(other) => return Err(format!("{at}: mimeType `{other}` is not image/png or image/jpeg")),
        // A file or data: URI without a mimeType: the bytes say which.
        None => match image::guess_format(&data) {
            Ok(f @ (image::ImageFormat::Png | image::ImageFormat::Jpeg)) => f,
            _ => return Err(format!("{at}: not a PNG or JPEG image")),
        },
    };
    Ok((data, format))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn references_split_back() {
        assert_eq!(split_reference(&reference("a b/scene.glb", 3)), Some(("a b/scene.glb", 3)));
        assert_eq!(split_reference("x.GLTF#images[0]"), Some(("x.GLTF", 0)));
        assert_eq!(split_reference("x.png#images[0]"), None);
        assert_eq!(split_reference("x.glb#images[-1]"), None);
        assert_eq!(split_reference("x.glb#images[2"), None);
        assert_eq!(split_reference("x.glb"), None);
    }
}
