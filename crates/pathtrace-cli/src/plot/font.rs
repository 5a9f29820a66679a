//! The embedded font. plotters' `ab_glyph` backend looks fonts up by family name in a registry
//! of its own; registering DejaVu Sans there under "sans-serif" once makes every plot's text
//! independent of the fonts installed on the machine.

use plotters::style::FontStyle;
use std::sync::OnceLock;

/// The family name plots ask for (also what SVG viewers fall back to).
pub const FAMILY: &str = "sans-serif";

/// Registers the embedded font; later calls do nothing. Fails only if the embedded TTF
/// could not be parsed, which would be a packaging bug.
pub fn ensure_registered() -> Result<(), String> {
    static REGISTERED: OnceLock<Result<(), String>> = OnceLock::new();
    REGISTERED
        .get_or_init(|| {
            for (style, bytes) in [
                (FontStyle::Normal, dejavu::sans::regular()),
                (FontStyle::Bold, dejavu::sans::bold()),
                (FontStyle::Italic, dejavu::sans::oblique()),
                (FontStyle::Oblique, dejavu::sans::oblique()),
            ] {
                plotters::style::register_font(FAMILY, style, bytes)
                    .map_err(|_| "the embedded DejaVu Sans font is not a valid TTF".to_string())?;
            }
            Ok(())
        })
        .clone()
}
