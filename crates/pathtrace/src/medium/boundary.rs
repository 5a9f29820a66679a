//! Which media a surface separates, as Mitsuba 3's shapes carry them: the `interior` medium lies
//! on the side opposite the geometric normal, the `exterior` on the normal's side. A surface
//! with no boundary leaves the path's medium as it is (Mitsuba's `is_medium_transition`).

/// Index of a medium in the scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct MediumId(pub u32);

impl MediumId {
    /// No medium (vacuum): the value a lane's medium holds outside every medium.
    pub const NONE: u32 = u32::MAX;
}

/// The media on the two sides of a surface ([`MediumId::NONE`] for vacuum).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct MediumBoundary {
    pub interior: u32,
    pub exterior: u32,
}

impl MediumBoundary {
    /// The medium a ray leaving the surface along a direction with `cos_to_normal` = d·n_g
    /// enters: the exterior in front of the geometric normal, the interior behind it.
    #[inline]
    pub fn target(&self, cos_to_normal: f32) -> u32 {
        if cos_to_normal > 0.0 {
            self.exterior
        } else {
            self.interior
        }
    }
}
