//! What the picture shows: the render itself, or a diagnostic view of it. Each view becomes a
//! linear image for the GPU plus whether the display's exposure and tone curve apply to it.

use pathtrace::film::{FeatureBuffers, Film, Image};
use pathtrace::math::Rgb;

/// The views, in the order the `V` key cycles through them.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ViewMode {
    /// The estimate (each pixel's mean radiance).
    #[default]
    Render,
    /// Per-pixel standard error of the mean, √(s²/n), from the film's Welford statistics.
    StdError,
    /// The albedo feature buffer (first non-specular hit, anti-aliased like the render).
    Albedo,
    /// The shading-normal feature buffer (x, y, z in [-1, 1] mapped to r, g, b in [0, 1]).
    Normals,
    /// The depth feature buffer (first-hit distance), nearest white, farthest dark.
    Depth,
    /// |render − reference| per channel (only with a reference).
    Difference,
}

impl ViewMode {
    pub const ALL: [ViewMode; 6] = [
        ViewMode::Render,
        ViewMode::StdError,
        ViewMode::Albedo,
        ViewMode::Normals,
        ViewMode::Depth,
        ViewMode::Difference,
    ];

    pub fn name(self) -> &'static str {
        match self {
            ViewMode::Render => "render",
            ViewMode::StdError => "std. error",
            ViewMode::Albedo => "albedo",
            ViewMode::Normals => "normals",
            ViewMode::Depth => "depth",
            ViewMode::Difference => "difference",
        }
    }

    /// The next view; the difference view is skipped without a reference.
    pub fn next(self, has_reference: bool) -> ViewMode {
        let i = Self::ALL.iter().position(|&m| m == self).unwrap_or(0);
        let next = Self::ALL[(i + 1) % Self::ALL.len()];
        if next == ViewMode::Difference && !has_reference {
            return next.next(has_reference);
        }
        next
    }

    /// True for views that show the feature buffers.
    pub fn needs_aovs(self) -> bool {
        matches!(self, ViewMode::Albedo | ViewMode::Normals | ViewMode::Depth)
    }

    /// True if exposure and the tone curve apply (radiance-like views); the others are shown as
    /// plain [0, 1] values.
    pub fn is_radiance(self) -> bool {
        matches!(self, ViewMode::Render | ViewMode::StdError | ViewMode::Difference)
    }
}

/// The inputs a view may draw on.
pub struct ViewSources<'a> {
    pub image: &'a Image,
    pub film: Option<&'a Film>,
    pub features: Option<&'a FeatureBuffers>,
    pub reference: Option<&'a Image>,
}

/// The linear image shown for `mode`, or `None` when its inputs are missing.
pub fn view_image(mode: ViewMode, src: &ViewSources) -> Option<Image> {
    match mode {
        ViewMode::Render => Some(src.image.clone()),
        ViewMode::StdError => {
            let mut v = src.film?.variance_image();
            v.pixels.iter_mut().for_each(|p| *p = p.map(|c| c.max(0.0).sqrt()));
            Some(v)
        }
        ViewMode::Albedo => Some(src.features?.albedo()),
        ViewMode::Normals => {
            let mut n = src.features?.normal();
            n.pixels.iter_mut().for_each(|p| *p = p.map(|c| 0.5 * c + 0.5));
            Some(n)
        }
        ViewMode::Depth => Some(normalised_depth(&src.features?.depth())),
        ViewMode::Difference => {
            let r = src.reference?;
            if (r.width, r.height) != (src.image.width, src.image.height) {
                return None;
            }
            let pixels = src.image.pixels.iter().zip(&r.pixels).map(|(a, b)| (*a - *b).map(f32::abs)).collect();
            Some(Image { width: r.width, height: r.height, pixels })
        }
    }
}

/// Depth as brightness: 1 at the nearest hit, falling linearly to 0.1 at the farthest; misses
/// (depth 0) stay black.
fn normalised_depth(depth: &Image) -> Image {
    let hits = depth.pixels.iter().map(|p| p.r).filter(|&d| d > 0.0);
    let (near, far) = hits.fold((f32::INFINITY, 0.0f32), |(n, f), d| (n.min(d), f.max(d)));
    let span = (far - near).max(f32::MIN_POSITIVE);
    let pixels = depth
        .pixels
        .iter()
        .map(|p| if p.r > 0.0 { Rgb::splat(1.0 - 0.9 * (p.r - near) / span) } else { Rgb::BLACK })
        .collect();
    Image { width: depth.width, height: depth.height, pixels }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn image(values: &[f32]) -> Image {
        Image::from_pixels(values.len() as u32, 1, values.iter().map(|&v| Rgb::splat(v)).collect()).unwrap()
    }

    #[test]
    fn cycling_visits_every_view_and_skips_difference_without_a_reference() {
        let mut m = ViewMode::Render;
        let mut seen = vec![m];
        for _ in 0..5 {
            m = m.next(true);
            seen.push(m);
        }
        assert_eq!(seen, ViewMode::ALL);
        assert_eq!(ViewMode::Depth.next(false), ViewMode::Render);
    }

    #[test]
    fn difference_is_the_absolute_error_and_needs_a_matching_reference() {
        let img = image(&[0.5, 1.0, 0.0]);
        let reference = image(&[0.25, 1.5, 0.0]);
        let src = ViewSources { image: &img, film: None, features: None, reference: Some(&reference) };
        assert_eq!(view_image(ViewMode::Difference, &src), Some(image(&[0.25, 0.5, 0.0])));
        let small = image(&[0.0]);
        let src = ViewSources { reference: Some(&small), ..src };
        assert_eq!(view_image(ViewMode::Difference, &src), None);
    }

    #[test]
    fn std_error_is_the_square_root_of_the_films_variance_of_the_mean() {
        let mut film = Film::new(1, 1);
        for v in [1.0, 3.0, 1.0, 3.0] {
            film.add_sample(0, 0, Rgb::splat(v));
        }
        let img = film.image();
        let src = ViewSources { image: &img, film: Some(&film), features: None, reference: None };
        // s² = 4/3 (unbiased), s²/n = 1/3.
        let se = view_image(ViewMode::StdError, &src).unwrap().get(0, 0).r;
        assert!((se - (1.0f32 / 3.0).sqrt()).abs() < 1e-5, "{se}");
    }

    #[test]
    fn depth_maps_near_to_white_far_to_dim_and_misses_to_black() {
        let d = normalised_depth(&image(&[2.0, 4.0, 0.0, 3.0]));
        for (p, want) in d.pixels.iter().zip([1.0, 0.1, 0.0, 0.55]) {
            assert!((p.r - want).abs() < 1e-6, "{} vs {want}", p.r);
        }
    }
}
