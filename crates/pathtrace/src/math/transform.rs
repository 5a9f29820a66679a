//! 4×4 homogeneous transforms: translate, scale, rotations about x/y/z, composition.

use glam::{Mat3, Mat4, Vec3};

/// An affine transform with its inverse kept alongside (normals use the inverse transpose).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transform {
    pub matrix: Mat4,
    pub inverse: Mat4,
}

/// Why a matrix cannot be a transform.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum InvalidTransform {
    #[error("its entries must be finite numbers")]
    NotFinite,
    #[error("it is singular (it flattens space)")]
    Singular,
    #[error("its axes are almost parallel (it all but flattens space)")]
    NearlyFlat,
    #[error("it scales space by {0:.1e}, beyond single precision (coordinates overflow or vanish)")]
    Overflow(f64),
}

impl Default for Transform {
    fn default() -> Self {
        Self::IDENTITY
    }
}

impl Transform {
    pub const IDENTITY: Transform = Transform { matrix: Mat4::IDENTITY, inverse: Mat4::IDENTITY };

    /// Wraps a matrix; `None` when it is singular or not finite ([`Transform::try_from_matrix`]
    /// says which).
    pub fn from_matrix(matrix: Mat4) -> Option<Self> {
        Self::try_from_matrix(matrix).ok()
    }

    /// Wraps a matrix, or says why it cannot be used: its entries are not finite, it is singular,
    /// or it scales so much that its determinant or inverse overflows single precision (a scale of
    /// 1e30 is not singular, and must not be reported as such).
    pub fn try_from_matrix(matrix: Mat4) -> Result<Self, InvalidTransform> {
        if !matrix.is_finite() {
            return Err(InvalidTransform::NotFinite);
        }
        // In f64 the determinant of any finite f32 matrix is finite, so overflow and a true
        // zero can be told apart.
        let exact = matrix.as_dmat4().determinant();
        // Singular relative to the lengths of its axes (Hadamard's bound |det| ≤ Π |column|), so a
        // scale of 1e-30 or 3e38 along one axis is not taken for a flattening.
        let axes = matrix.as_dmat4();
        let bound = axes.x_axis.truncate().length() * axes.y_axis.truncate().length() * axes.z_axis.truncate().length();
        if exact == 0.0 {
            return Err(InvalidTransform::Singular);
        }
        if exact.abs() < 1e-12 * bound {
            return Err(InvalidTransform::NearlyFlat);
        }
        let det = matrix.determinant();
        let inverse = matrix.inverse();
        if !det.is_finite() || !inverse.is_finite() || det == 0.0 {
            return Err(InvalidTransform::Overflow(exact));
        }
        Ok(Self { matrix, inverse })
    }

    pub fn translate(t: Vec3) -> Self {
        Self { matrix: Mat4::from_translation(t), inverse: Mat4::from_translation(-t) }
    }

    /// Non-uniform scale; `None` if a factor is zero.
    pub fn scale(s: Vec3) -> Option<Self> {
        Self::from_matrix(Mat4::from_scale(s))
    }

    /// Non-uniform scale, or why it cannot be one ([`Transform::try_from_matrix`]).
    pub fn try_scale(s: Vec3) -> Result<Self, InvalidTransform> {
        Self::try_from_matrix(Mat4::from_scale(s))
    }

    /// Rotation about +x by `degrees` (right-handed: y → z).
    pub fn rotate_x(degrees: f32) -> Self {
        Self::rotation(Mat4::from_rotation_x(degrees.to_radians()))
    }

    /// Rotation about +y by `degrees`: x' = x cos θ + z sin θ, z' = -x sin θ + z cos θ.
    pub fn rotate_y(degrees: f32) -> Self {
        Self::rotation(Mat4::from_rotation_y(degrees.to_radians()))
    }

    /// Rotation about +z by `degrees` (right-handed: x → y).
    pub fn rotate_z(degrees: f32) -> Self {
        Self::rotation(Mat4::from_rotation_z(degrees.to_radians()))
    }

    fn rotation(m: Mat4) -> Self {
        Self { matrix: m, inverse: m.transpose() }
    }

    /// `self.then(next)` applies `self` first, then `next` (so lists read in application order).
    pub fn then(&self, next: &Transform) -> Transform {
        Transform { matrix: next.matrix * self.matrix, inverse: self.inverse * next.inverse }
    }

    pub fn point(&self, p: Vec3) -> Vec3 {
        self.matrix.transform_point3(p)
    }

    pub fn vector(&self, v: Vec3) -> Vec3 {
        self.matrix.transform_vector3(v)
    }

    /// Transforms a normal by the inverse transpose, which keeps it perpendicular to
    /// transformed tangents; the result is normalised.
    pub fn normal(&self, n: Vec3) -> Vec3 {
        Mat3::from_mat4(self.inverse).transpose().mul_vec3(n).normalize()
    }

    pub fn is_identity(&self) -> bool {
        self.matrix.abs_diff_eq(Mat4::IDENTITY, 0.0)
    }

    /// If the linear part is a rotation times a uniform scale (a similarity), returns the
    /// scale factor: such transforms keep spheres spheres.
    pub fn uniform_scale(&self) -> Option<f32> {
        let l = Mat3::from_mat4(self.matrix);
        let g = l.transpose() * l;
        let s2 = g.x_axis.x;
        let tol = 1e-4 * s2.abs();
        let diag_ok = (g.y_axis.y - s2).abs() <= tol && (g.z_axis.z - s2).abs() <= tol;
        let off_ok = g.x_axis.y.abs() <= tol && g.x_axis.z.abs() <= tol && g.y_axis.z.abs() <= tol;
        (diag_ok && off_ok && s2 > 0.0).then(|| s2.sqrt())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Vec3, b: Vec3) -> bool {
        (a - b).length() < 1e-4
    }

    #[test]
    fn rotate_y_follows_the_documented_convention() {
        let t = Transform::rotate_y(90.0);
        // x' = x cos θ + z sin θ, z' = -x sin θ + z cos θ with θ = 90°: (1,0,0) → (0,0,-1).
        assert!(close(t.point(Vec3::X), -Vec3::Z));
        assert!(close(t.point(Vec3::Z), Vec3::X));
    }

    #[test]
    fn composition_applies_in_list_order() {
        let t = Transform::rotate_y(90.0).then(&Transform::translate(Vec3::new(10.0, 0.0, 0.0)));
        assert!(close(t.point(Vec3::X), Vec3::new(10.0, 0.0, -1.0)));
        assert!(close(t.inverse.transform_point3(t.point(Vec3::new(1.0, 2.0, 3.0))), Vec3::new(1.0, 2.0, 3.0)));
    }

    #[test]
    fn normals_stay_perpendicular_under_non_uniform_scale() {
        let t = Transform::scale(Vec3::new(4.0, 1.0, 1.0)).unwrap().then(&Transform::rotate_z(30.0));
        let tangent = Vec3::new(1.0, -1.0, 0.0);
        let normal = Vec3::new(1.0, 1.0, 0.0).normalize();
        assert!(t.vector(tangent).dot(t.normal(normal)).abs() < 1e-4);
        assert!(t.uniform_scale().is_none());
        let s = Transform::scale(Vec3::splat(2.0)).unwrap().then(&Transform::rotate_x(20.0));
        assert!((s.uniform_scale().unwrap() - 2.0).abs() < 1e-4);
    }

    #[test]
    fn singular_matrices_are_rejected() {
        assert!(Transform::scale(Vec3::new(1.0, 0.0, 1.0)).is_none());
        assert!(Transform::from_matrix(Mat4::from_cols_array(&[f32::NAN; 16])).is_none());
    }
}
