//! Shading normals from files: normalised, or dropped for the whole mesh when any is unusable.

use pathtrace::math::Vec3;

/// Normalises every normal in place. Returns `None` (the mesh is then flat shaded) when any
/// normal has zero or non-finite length, since no direction can be recovered from it; files that
/// store zero normals for unused or degenerate vertices are common, and flat shading is the
/// conservative reading.
pub(crate) fn normalised(mut normals: Vec<Vec3>) -> Option<Vec<Vec3>> {
    for n in &mut normals {
        // Scale by the largest component first so that huge or tiny finite normals do not
        // overflow or underflow when squared.
        let scale = n.abs().max_element();
        if !(scale > 0.0 && scale.is_finite()) {
            return None;
        }
        let m = *n / scale;
        *n = m / m.length();
    }
    Some(normals)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normals_are_normalised_or_dropped() {
        let ns = normalised(vec![Vec3::new(0.0, 2.0, 0.0), Vec3::new(3.0, 0.0, 4.0)]).unwrap();
        assert_eq!(ns, vec![Vec3::Y, Vec3::new(0.6, 0.0, 0.8)]);
        assert_eq!(normalised(vec![Vec3::Y, Vec3::ZERO]), None);
        assert_eq!(normalised(vec![Vec3::new(f32::INFINITY, 0.0, 0.0)]), None);
        let big = normalised(vec![Vec3::new(f32::MAX, 0.0, 0.0), Vec3::new(0.0, 0.0, 1e-40)]).unwrap();
        assert_eq!(big, vec![Vec3::X, Vec3::Z]);
    }
}
