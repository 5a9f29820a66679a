//! `[[objects]]` (a shape, its material and its transform list) and `[[groups]]` (a transform
//! list over nested objects and groups: the scene graph).
//!
//! Objects are read into a flat [`RawObject`] (so a wrongly typed value is reported at its own
//! position), then checked into an [`ObjectDef`] whose shape matches its `type`.

use super::transform::TransformStep;
use super::values::{Num, Num3};
use serde::{Deserialize, Serialize};

/// The shapes, as named by `type`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum ShapeType {
    Sphere,
    Plane,
    Quad,
    Box,
    Triangle,
    Mesh,
    Disk,
}

/// An object's geometry, in its local frame (before the transform list).
#[derive(Clone, Debug, PartialEq)]
pub enum ShapeDef {
    /// A sphere.
    Sphere { center: Num3, radius: Num },
    /// An infinite plane through `point` facing `normal` (cannot emit).
    Plane { point: Num3, normal: Num3 },
    /// The parallelogram q + s·u + t·v, s, t ∈ [0, 1]; its front faces along u × v.
    Quad { q: Num3, u: Num3, v: Num3 },
    /// The axis-aligned box [min, max] as six outward-facing quads.
    Box { min: Num3, max: Num3 },
    /// The round disk of `radius` around `center`, its front facing along `normal` (an ellipse
    /// after a non-uniform scale).
    Disk { center: Num3, normal: Num3, radius: Num },
    /// The triangle abc; its front faces along (b − a) × (c − a).
    Triangle { a: Num3, b: Num3, c: Num3 },
    /// Triangles from an OBJ, PLY or Mitsuba `.serialized` file; the path is relative to the scene
    /// file's folder. `part` picks one part by index (an OBJ material group, a serialized shape);
    /// without it, all parts are used. `flip_v` replaces each texture coordinate v by 1 − v
    /// (what Mitsuba does to OBJ files, its `flip_tex_coords`).
    /// `normals` chooses the shading normals (default [`MeshNormals::Smooth`], Mitsuba 3's rule).
    Mesh { file: String, part: Option<u32>, flip_v: bool, normals: MeshNormals },
}

/// Where a mesh's shading normals come from (the mesh's `normals` field).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum MeshNormals {
    /// The file's normals where it has them, else smooth normals computed from the faces
    /// (angle-weighted, after the transform): what Mitsuba 3 does unless `face_normals` is true.
    #[default]
    Smooth,
    /// Flat shading: the faces' own normals (Mitsuba's `face_normals = true`).
    Face,
    /// The file's normals where it has them, else flat shading.
    File,
    /// Smooth normals computed from the faces, ignoring any in the file.
    Computed,
}

/// One object: a shape, the name of its material, and its transform list.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(try_from = "RawObject", into = "RawObject")]
pub struct ObjectDef {
    /// The geometry.
    pub shape: ShapeDef,
    /// Name of a `[materials.NAME]` entry.
    pub material: String,
    /// Steps applied in order (empty: identity).
    pub transform: Vec<TransformStep>,
    /// The `[media.NAME]` inside the object (behind its surface normals), if any.
    pub interior: Option<String>,
    /// The `[media.NAME]` outside the object (in front of its normals), if any.
    pub exterior: Option<String>,
    /// Turn the surface normals over (Mitsuba's `flip_normals`): the front of one-sided
    /// materials and lights, and the side media call exterior, become the other side.
    pub flip_normals: bool,
}

/// A group: its transform list applies to everything inside it, after their own transforms.
#[derive(Clone, Debug, Default, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct GroupDef {
    /// Steps applied in order, after each member's own transform.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub transform: Vec<TransformStep>,
    /// Objects in the group.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub objects: Vec<ObjectDef>,
    /// Nested groups.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub groups: Vec<GroupDef>,
}

/// The file form of an object: every field of every shape, checked by [`ObjectDef::try_from`].
#[derive(Clone, Debug, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct RawObject {
    #[serde(rename = "type")]
    kind: Option<ShapeType>,
    material: Option<String>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    transform: Vec<TransformStep>,
    #[serde(skip_serializing_if = "Option::is_none")]
    interior: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    exterior: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    flip_normals: Option<bool>,
    #[serde(skip_serializing_if = "Option::is_none")]
    center: Option<Num3>,
    #[serde(skip_serializing_if = "Option::is_none")]
    radius: Option<Num>,
    #[serde(skip_serializing_if = "Option::is_none")]
    point: Option<Num3>,
    #[serde(skip_serializing_if = "Option::is_none")]
    normal: Option<Num3>,
    #[serde(skip_serializing_if = "Option::is_none")]
    q: Option<Num3>,
    #[serde(skip_serializing_if = "Option::is_none")]
    u: Option<Num3>,
    #[serde(skip_serializing_if = "Option::is_none")]
    v: Option<Num3>,
    #[serde(skip_serializing_if = "Option::is_none")]
    min: Option<Num3>,
    #[serde(skip_serializing_if = "Option::is_none")]
    max: Option<Num3>,
    #[serde(skip_serializing_if = "Option::is_none")]
    a: Option<Num3>,
    #[serde(skip_serializing_if = "Option::is_none")]
    b: Option<Num3>,
    #[serde(skip_serializing_if = "Option::is_none")]
    c: Option<Num3>,
    #[serde(skip_serializing_if = "Option::is_none")]
    file: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    part: Option<u32>,
    #[serde(skip_serializing_if = "Option::is_none")]
    flip_v: Option<bool>,
    #[serde(skip_serializing_if = "Option::is_none")]
    normals: Option<MeshNormals>,
}

/// The geometric fields each shape takes.
fn fields_of(t: ShapeType) -> &'static [&'static str] {
    match t {
        ShapeType::Sphere => &["center", "radius"],
        ShapeType::Plane => &["point", "normal"],
        ShapeType::Quad => &["q", "u", "v"],
        ShapeType::Box => &["min", "max"],
        ShapeType::Triangle => &["a", "b", "c"],
        ShapeType::Mesh => &["file", "part", "flip_v", "normals"],
        ShapeType::Disk => &["center", "normal", "radius"],
    }
}

fn type_name(t: ShapeType) -> &'static str {
    match t {
        ShapeType::Sphere => "sphere",
        ShapeType::Plane => "plane",
        ShapeType::Quad => "quad",
        ShapeType::Box => "box",
        ShapeType::Triangle => "triangle",
        ShapeType::Mesh => "mesh",
        ShapeType::Disk => "disk",
    }
}

impl RawObject {
    fn present(&self) -> Vec<&'static str> {
        let v3 = |o: &Option<Num3>| o.is_some();
        let fields = [
            ("center", v3(&self.center)),
            ("radius", self.radius.is_some()),
            ("point", v3(&self.point)),
            ("normal", v3(&self.normal)),
            ("q", v3(&self.q)),
            ("u", v3(&self.u)),
            ("v", v3(&self.v)),
            ("min", v3(&self.min)),
            ("max", v3(&self.max)),
            ("a", v3(&self.a)),
            ("b", v3(&self.b)),
            ("c", v3(&self.c)),
            ("file", self.file.is_some()),
            ("part", self.part.is_some()),
            ("flip_v", self.flip_v.is_some()),
            ("normals", self.normals.is_some()),
        ];
        fields.iter().filter(|f| f.1).map(|f| f.0).collect()
    }
}

impl TryFrom<RawObject> for ObjectDef {
    type Error = String;

    fn try_from(r: RawObject) -> Result<Self, String> {
        let t = r.kind.ok_or("an object needs a `type` (sphere, plane, quad, box, triangle, mesh, disk)")?;
        let name = type_name(t);
        let wanted = fields_of(t);
        if let Some(extra) = r.present().into_iter().find(|f| !wanted.contains(f)) {
            let ok = wanted.iter().map(|f| format!("`{f}`")).collect::<Vec<_>>().join(", ");
            return Err(format!(
                "`{extra}` is not a field of a {name} (it takes {ok}, `material`, `transform`, `interior`, `exterior`, `flip_normals`)"
            ));
        }
        let missing = |f: &str| format!("a {name} needs `{f}`");
        let need = |v: Option<Num3>, f: &str| v.ok_or_else(|| missing(f));
        let shape = match t {
            ShapeType::Sphere => ShapeDef::Sphere {
                center: need(r.center, "center")?,
                radius: r.radius.ok_or_else(|| missing("radius"))?,
            },
            ShapeType::Plane => ShapeDef::Plane { point: need(r.point, "point")?, normal: need(r.normal, "normal")? },
            ShapeType::Quad => ShapeDef::Quad { q: need(r.q, "q")?, u: need(r.u, "u")?, v: need(r.v, "v")? },
            ShapeType::Box => ShapeDef::Box { min: need(r.min, "min")?, max: need(r.max, "max")? },
            ShapeType::Triangle => ShapeDef::Triangle { a: need(r.a, "a")?, b: need(r.b, "b")?, c: need(r.c, "c")? },
            ShapeType::Disk => ShapeDef::Disk {
                center: need(r.center, "center")?,
                normal: need(r.normal, "normal")?,
                radius: r.radius.ok_or_else(|| missing("radius"))?,
            },
            ShapeType::Mesh => ShapeDef::Mesh {
                file: r.file.ok_or_else(|| missing("file"))?,
                part: r.part,
                flip_v: r.flip_v.unwrap_or(false),
                normals: r.normals.unwrap_or_default(),
            },
        };
        let material =
            r.material.ok_or_else(|| format!("a {name} needs a `material` (the name of a [materials.NAME])"))?;
        let flip_normals = r.flip_normals.unwrap_or(false);
        Ok(ObjectDef {
            shape,
            material,
            transform: r.transform,
            interior: r.interior,
            exterior: r.exterior,
            flip_normals,
        })
    }
}

impl From<ObjectDef> for RawObject {
    fn from(o: ObjectDef) -> Self {
        let mut r = RawObject {
            material: Some(o.material),
            transform: o.transform,
            interior: o.interior,
            exterior: o.exterior,
            flip_normals: o.flip_normals.then_some(true),
            ..Default::default()
        };
        r.kind = Some(match o.shape {
            ShapeDef::Sphere { center, radius } => {
                (r.center, r.radius) = (Some(center), Some(radius));
                ShapeType::Sphere
            }
            ShapeDef::Plane { point, normal } => {
                (r.point, r.normal) = (Some(point), Some(normal));
                ShapeType::Plane
            }
            ShapeDef::Quad { q, u, v } => {
                (r.q, r.u, r.v) = (Some(q), Some(u), Some(v));
                ShapeType::Quad
            }
            ShapeDef::Box { min, max } => {
                (r.min, r.max) = (Some(min), Some(max));
                ShapeType::Box
            }
            ShapeDef::Triangle { a, b, c } => {
                (r.a, r.b, r.c) = (Some(a), Some(b), Some(c));
                ShapeType::Triangle
            }
            ShapeDef::Mesh { file, part, flip_v, normals } => {
                (r.file, r.part, r.flip_v) = (Some(file), part, flip_v.then_some(true));
                r.normals = (normals != MeshNormals::default()).then_some(normals);
                ShapeType::Mesh
            }
            ShapeDef::Disk { center, normal, radius } => {
                (r.center, r.normal, r.radius) = (Some(center), Some(normal), Some(radius));
                ShapeType::Disk
            }
        });
        r
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(s: &str) -> Result<ObjectDef, String> {
        toml::from_str(s).map_err(|e| e.message().to_string())
    }

    #[test]
    fn each_shape_takes_its_own_fields() {
        let s = parse("type = \"sphere\"\ncenter = [0, 1, 0]\nradius = 2\nmaterial = \"m\"").unwrap();
        assert_eq!(s.shape, ShapeDef::Sphere { center: [0.0f32, 1.0, 0.0].map(Num::from), radius: Num::from(2.0) });
        let e = parse("type = \"sphere\"\ncenter = [0, 1, 0]\nradius = 2\nnormal = [0, 1, 0]\nmaterial = \"m\"");
        assert!(e.unwrap_err().contains("`normal` is not a field of a sphere"));
        assert!(parse("type = \"quad\"\nq = [0, 0, 0]\nu = [1, 0, 0]\nmaterial = \"m\"").unwrap_err().contains("`v`"));
        assert!(parse("type = \"box\"\nmin = [0, 0, 0]\nmax = [1, 1, 1]").unwrap_err().contains("material"));
    }

    #[test]
    fn objects_round_trip_through_toml() {
        let o = parse("type = \"mesh\"\nfile = \"a.obj\"\nmaterial = \"m\"\ntransform = [{scale = 2}]").unwrap();
        let back: ObjectDef = toml::from_str(&toml::to_string(&o).unwrap()).unwrap();
        assert_eq!(o, back);
    }
}
