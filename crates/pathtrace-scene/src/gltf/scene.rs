//! The glTF node hierarchy as a native scene: each mesh primitive an object referencing the
//! glTF file's part (its world matrix as the transform), the first camera (or the one named by
//! `-D camera=NAME`), and `KHR_lights_punctual` lights.

use super::document::Opened;
use super::geometry::first_parts;
use super::material;
use super::num;
use crate::native::model::{
    CameraSection, LightDef, MaterialDef, MeshNormals, Num3, ObjectDef, ProjectionName, SceneFile, ShapeDef,
    TransformStep, Triple,
};
use gltf::khr_lights_punctual::Kind;
use pathtrace::math::{Mat4, Vec3};

fn n3(v: Vec3) -> Num3 {
    [num(v.x), num(v.y), num(v.z)]
}

fn matrix_step(m: &Mat4) -> TransformStep {
    // Native matrices are row-major.
    TransformStep::Matrix(m.transpose().to_cols_array().map(num))
}

/// Converts the document's default scene (or its first, or every root node when it has none).
pub fn convert(o: &Opened, file_name: &str, camera_name: Option<&str>) -> Result<(SceneFile, Vec<String>), String> {
    // Replaced by the scene's camera when it has one: the glTF default view, from +z.
    let camera =
        CameraSection { up: Some(n3(Vec3::Y)), ..CameraSection::pinhole(n3(Vec3::new(0.0, 0.0, 3.0)), n3(Vec3::ZERO)) };
    let file = SceneFile {
        render: Default::default(),
        camera,
        materials: Default::default(),
        media: Default::default(),
        objects: Vec::new(),
        groups: Vec::new(),
        shape_groups: Default::default(),
        instances: Vec::new(),
        lights: Vec::new(),
    };
    let mut c = Converter { file_name, file, warnings: Vec::new(), first: first_parts(&o.doc) };
    let roots: Vec<gltf::Node> = match o.doc.default_scene().or_else(|| o.doc.scenes().next()) {
        Some(s) => s.nodes().collect(),
        None => {
            let children: std::collections::HashSet<usize> =
                o.doc.nodes().flat_map(|n| n.children().map(|c| c.index()).collect::<Vec<_>>()).collect();
            o.doc.nodes().filter(|n| !children.contains(&n.index())).collect()
        }
    };
    let mut cameras = Vec::new();
    let mut stack: Vec<(gltf::Node, Mat4, usize)> = roots.into_iter().rev().map(|n| (n, Mat4::IDENTITY, 0)).collect();
    while let Some((node, parent, depth)) = stack.pop() {
        if depth > 256 {
            return Err(format!("nodes[{}]: the node hierarchy is deeper than 256 (a cycle?)", node.index()));
        }
        let world = parent * Mat4::from_cols_array_2d(&node.transform().matrix());
        if !world.is_finite() {
            return Err(format!("nodes[{}]: its transform is not finite", node.index()));
        }
        if let Some(mesh) = node.mesh() {
            c.mesh(&node, &mesh, &world);
        }
        if let Some(cam) = node.camera() {
            cameras.push((cam, world, node.index()));
        }
        if let Some(light) = node.light() {
            c.light(&light, &world, node.index());
        }
        for child in node.children().collect::<Vec<_>>().into_iter().rev() {
            stack.push((child, world, depth + 1));
        }
    }
    let chosen = match camera_name {
        Some(name) => Some(
            cameras
                .iter()
                .find(|(cam, _, n)| {
                    cam.name() == Some(name) || o.doc.nodes().nth(*n).and_then(|n| n.name()) == Some(name)
                })
                .ok_or_else(|| format!("no camera named `{name}`"))?,
        ),
        None => cameras.first(),
    };
    match chosen {
        Some((cam, world, _)) => c.camera(cam, world),
        None => c.warnings.push(format!("{file_name}: the scene has no camera: using the default view")),
    }
    Ok((c.file, c.warnings))
}

struct Converter<'a> {
    file_name: &'a str,
    file: SceneFile,
    warnings: Vec<String>,
    first: Vec<usize>,
}

impl Converter<'_> {
    fn warn(&mut self, msg: String) {
        self.warnings.push(format!("{}: {msg}", self.file_name));
    }

    fn material_name(&mut self, m: Option<gltf::Material>) -> String {
        let name =
            m.as_ref().and_then(|m| m.index()).map_or_else(|| "gltf-default".to_string(), |i| format!("gltf-{i}"));
        if !self.file.materials.contains_key(&name) {
            let mut warnings = Vec::new();
            let mut models = std::collections::BTreeMap::new();
            let def: MaterialDef =
                material::convert(m.as_ref(), self.file_name, &name, &mut models, &mut |w| warnings.push(w));
            warnings.into_iter().for_each(|w| self.warn(w));
            self.file.materials.insert(name.clone(), def);
            self.file.materials.extend(models);
        }
        name
    }

    fn mesh(&mut self, node: &gltf::Node, mesh: &gltf::Mesh, world: &Mat4) {
        for prim in mesh.primitives() {
            if prim.mode() != gltf::mesh::Mode::Triangles {
                let msg =
                    format!("nodes[{}]: primitive mode {:?} is not triangles: skipped", node.index(), prim.mode());
                self.warn(msg);
                continue;
            }
            let material = self.material_name(Some(prim.material()).filter(|m| m.index().is_some()));
            // glTF: without NORMAL, flat normals.
            let normals =
                if prim.get(&gltf::Semantic::Normals).is_some() { MeshNormals::File } else { MeshNormals::Face };
            let part = (self.first[mesh.index()] + prim.index()) as u32;
            let shape = ShapeDef::Mesh { file: self.file_name.to_string(), part: Some(part), flip_v: false, normals };
            self.file.objects.push(ObjectDef {
                shape,
                material,
                transform: vec![matrix_step(world)],
                interior: None,
                exterior: None,
                flip_normals: false,
            });
        }
    }

    fn camera(&mut self, cam: &gltf::Camera, world: &Mat4) {
        let eye = world.transform_point3(Vec3::ZERO);
        let forward = world.transform_vector3(Vec3::NEG_Z).normalize_or_zero();
        let up = world.transform_vector3(Vec3::Y).normalize_or_zero();
        let (vfov, aspect) = match cam.projection() {
            gltf::camera::Projection::Perspective(p) => (p.yfov().to_degrees(), p.aspect_ratio()),
            // xmag and ymag are the view's half-width and half-height (glTF 2.0 §3.10.3).
            gltf::camera::Projection::Orthographic(o) if o.ymag() > 0.0 && o.ymag().is_finite() => {
                let aspect = (o.xmag() > 0.0 && o.xmag().is_finite()).then(|| num(o.xmag() / o.ymag()));
                self.file.camera = CameraSection {
                    projection: Some(ProjectionName::Orthographic),
                    up: Some(n3(up)),
                    height: Some(num(2.0 * o.ymag())),
                    aspect,
                    ..CameraSection::pinhole(n3(eye), n3(eye + forward))
                };
                return;
            }
            gltf::camera::Projection::Orthographic(o) => {
                self.warn(format!(
                    "cameras[{}]: orthographic ymag {} must be a positive number: using a 40° perspective",
                    cam.index(),
                    o.ymag()
                ));
                (40.0, None)
            }
        };
        self.file.camera = CameraSection {
            up: Some(n3(up)),
            vfov: Some(num(vfov)),
            aspect: aspect.map(num),
            ..CameraSection::pinhole(n3(eye), n3(eye + forward))
        };
    }

    fn light(&mut self, light: &gltf::khr_lights_punctual::Light, world: &Mat4, node: usize) {
        let c = light.color().map(|c| c * light.intensity());
        let colour = Triple::Each(c.map(num));
        if light.range().is_some() {
            self.warn(format!("nodes[{node}]: the light's `range` is ignored (lights fall off physically)"));
        }
        let position = world.transform_point3(Vec3::ZERO);
        // glTF lights shine along the node's −z.
        let def = match light.kind() {
            Kind::Point => LightDef::Point { position: n3(position), intensity: colour },
            Kind::Directional => LightDef::Directional {
                irradiance: colour,
                direction: Some(n3(world.transform_vector3(Vec3::NEG_Z))),
                transform: Vec::new(),
            },
            Kind::Spot { inner_cone_angle, outer_cone_angle } => {
                self.warn(format!(
                    "nodes[{node}]: a spot light's smooth glTF falloff is replaced by Mitsuba's linear one"
                ));
                let outer = outer_cone_angle.to_degrees().clamp(1e-3, 90.0);
                let inner = inner_cone_angle.to_degrees().clamp(1e-3, outer);
                // Ours points along local +z: turn it to −z first.
                let flip = TransformStep::RotateY(num(180.0));
                LightDef::Spot {
                    intensity: colour,
                    cutoff_angle: Some(num(outer)),
                    beam_width: Some(num(inner)),
                    transform: vec![flip, matrix_step(world)],
                }
            }
        };
        self.file.lights.push(def);
    }
}
