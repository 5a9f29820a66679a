//! Transform lists: `transform = [ {translate = [..]}, {rotate_y = 15}, … ]`, applied in list
//! order (the first step acts on the object first).

use super::values::{vec3, Num, Num3, Triple};
use pathtrace::math::{normalize_robust, InvalidTransform, Transform, Vec3};
use serde::{Deserialize, Serialize};

/// Orientation given as a viewer: the local +z axis points from `from` towards `to`.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct LookAtDef {
    /// Where the local origin goes.
    pub from: Num3,
    /// A point the local +z axis points at.
    pub to: Num3,
    /// Roughly where the local +y axis points (default `[0, 1, 0]`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub up: Option<Num3>,
}

/// One step of a transform list; each is a table with a single key.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize, Serialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum TransformStep {
    /// Move by `[x, y, z]`.
    Translate(Num3),
    /// Scale by one factor or by `[x, y, z]`; factors must be non-zero.
    Scale(Triple),
    /// Rotate about the x axis by degrees (right-handed: y towards z).
    RotateX(Num),
    /// Rotate about the y axis by degrees (right-handed: z towards x).
    RotateY(Num),
    /// Rotate about the z axis by degrees (right-handed: x towards y).
    RotateZ(Num),
    /// A 4×4 affine matrix, 16 numbers in row-major order; the last row must be `0 0 0 1`.
    Matrix([Num; 16]),
    /// Place and orient like a camera; see [`LookAtDef`].
    LookAt(LookAtDef),
}

impl TransformStep {
    /// The engine transform of this step, or why it is invalid.
    pub fn to_transform(&self) -> Result<Transform, String> {
        match self {
            TransformStep::Translate(t) => Ok(Transform::translate(vec3(t))),
            TransformStep::Scale(s) => Transform::try_scale(s.vec3()).map_err(|e| match e {
                InvalidTransform::Singular => "scale factors must be non-zero".to_string(),
                e => format!("invalid scale: {e}"),
            }),
            TransformStep::RotateX(d) => Ok(Transform::rotate_x(d.f32())),
            TransformStep::RotateY(d) => Ok(Transform::rotate_y(d.f32())),
            TransformStep::RotateZ(d) => Ok(Transform::rotate_z(d.f32())),
            TransformStep::Matrix(m) => matrix(m),
            TransformStep::LookAt(l) => look_at(l),
        }
    }
}

fn matrix(m: &[Num; 16]) -> Result<Transform, String> {
    let rows = m.map(Num::f32);
    if rows[12] != 0.0 || rows[13] != 0.0 || rows[14] != 0.0 || rows[15] != 1.0 {
        return Err("the matrix's last row must be 0 0 0 1 (only affine transforms are supported)".into());
    }
    // glam stores columns; the file lists rows, so read it as columns and transpose.
    let mat = pathtrace::math::Mat4::from_cols_array(&rows).transpose();
    Transform::try_from_matrix(mat).map_err(|e| format!("invalid matrix: {e}"))
}

/// The local frame placed at `from` with +z towards `to`, as Mitsuba 3's `Transform4f::look_at`
/// builds it: dir = normalize(to − from), left = normalize(up × dir), up' = dir × left; the
/// matrix columns are (left, up', dir, from).
fn look_at(l: &LookAtDef) -> Result<Transform, String> {
    let (from, to) = (vec3(&l.from), vec3(&l.to));
    let up = l.up.as_ref().map_or(Vec3::Y, vec3);
    if !(to - from).is_finite() {
        return Err("look_at `from` and `to` are too far apart: their distance overflows single precision".into());
    }
    let dir = normalize_robust(to - from).ok_or("look_at `from` and `to` are the same point")?;
    let left = normalize_robust(up.cross(dir)).ok_or("look_at `up` is zero or parallel to `to` − `from`")?;
    let new_up = dir.cross(left);
    let m = pathtrace::math::Mat4::from_cols(left.extend(0.0), new_up.extend(0.0), dir.extend(0.0), from.extend(1.0));
    Transform::try_from_matrix(m).map_err(|e| format!("invalid look_at: {e}"))
}

/// Composes a list of steps in order; on failure, the index of the bad step and why.
pub fn compose(steps: &[TransformStep]) -> Result<Transform, (usize, String)> {
    steps
        .iter()
        .enumerate()
        .try_fold(Transform::IDENTITY, |acc, (i, s)| Ok(acc.then(&s.to_transform().map_err(|e| (i, e))?)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Deserialize)]
    struct List {
        transform: Vec<TransformStep>,
    }

    fn parse(s: &str) -> Vec<TransformStep> {
        toml::from_str::<List>(s).unwrap().transform
    }

    fn close(a: Vec3, b: Vec3) -> bool {
        (a - b).length() < 1e-4
    }

    #[test]
    fn steps_apply_in_list_order() {
        let t = compose(&parse("transform = [{rotate_y = 90}, {translate = [10, 0, 0]}]")).unwrap();
        assert!(close(t.point(Vec3::X), Vec3::new(10.0, 0.0, -1.0)));
        let t = compose(&parse("transform = [{scale = 2}, {scale = [1, 3, 1]}]")).unwrap();
        assert!(close(t.point(Vec3::ONE), Vec3::new(2.0, 6.0, 2.0)));
    }

    #[test]
    fn matrices_are_row_major() {
        let t = compose(&parse("transform = [{matrix = [1,0,0,5, 0,1,0,6, 0,0,1,7, 0,0,0,1]}]")).unwrap();
        assert!(close(t.point(Vec3::ZERO), Vec3::new(5.0, 6.0, 7.0)));
        let bad = parse("transform = [{translate = [0,0,0]}, {matrix = [1,0,0,0, 0,0,0,0, 0,0,1,0, 0,0,0,1]}]");
        assert_eq!(compose(&bad).unwrap_err().0, 1);
    }

    #[test]
    fn look_at_points_local_z_at_the_target() {
        let t = compose(&parse("transform = [{look_at = {from = [1, 2, 3], to = [1, 2, 10]}}]")).unwrap();
        assert!(close(t.point(Vec3::ZERO), Vec3::new(1.0, 2.0, 3.0)));
        assert!(close(t.vector(Vec3::Z), Vec3::Z));
        assert!(close(t.vector(Vec3::Y), Vec3::Y));
        let degenerate = parse("transform = [{look_at = {from = [0, 0, 0], to = [0, 5, 0]}}]");
        assert!(compose(&degenerate).unwrap_err().1.contains("parallel"));
    }

    #[test]
    fn zero_scale_and_unknown_steps_are_rejected() {
        assert!(compose(&parse("transform = [{scale = [1, 0, 1]}]")).is_err());
        assert!(toml::from_str::<List>("transform = [{rotate_w = 1}]").is_err());
    }
}
