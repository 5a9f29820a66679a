//! Shape groups: primitives defined once, in their own object space, to be placed many times
//! by instances (see `mod.rs`).
//!
//! ```toml
//! [shape_groups.tree]
//! objects = [{ type = "mesh", file = "tree.ply", material = "bark" }]
//!
//! [[instances]]
//! group = "tree"
//! transform = [{ translate = [4, 0, 0] }]
//! material = "grey"   # optional: replaces every material of the group
//! ```

use crate::accel::Bvh;
use crate::math::{Aabb, Transform, Vec3};
use crate::primitive_store::{PrimitiveStore, SceneMesh};
use crate::scene::{BuildError, MaterialId, Primitive};
use crate::shape::{MeshGeometry, Quad, Shape, TriangleMesh};

/// What a group has been given, in object space.
#[derive(Clone, Debug)]
enum GroupEntry {
    Shape(Shape, u32),
    Mesh(MeshGeometry, u32),
}

/// Primitives defined once and placed by [`crate::SceneBuilder::instance`]. Shapes and meshes
/// are baked into the group's object space by their own transforms, as in the scene; unbounded
/// shapes (planes) cannot be grouped, and emissive materials are rejected when the scene is
/// built (an instanced primitive is never a light).
#[derive(Clone, Debug, Default)]
pub struct ShapeGroup {
    entries: Vec<GroupEntry>,
}

impl ShapeGroup {
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds a shape placed in the group's space by `transform`.
    pub fn shape(&mut self, shape: Shape, material: MaterialId, transform: &Transform) -> Result<(), BuildError> {
        let placed = shape.transformed(transform).ok_or(BuildError::Degenerate("shape in a group"))?;
        if placed.bounds().is_none() {
            return Err(BuildError::Instance("an infinite plane cannot be part of a shape group".into()));
        }
        self.entries.push(GroupEntry::Shape(placed, material.0));
        Ok(())
    }

    /// Adds a mesh placed in the group's space by `transform`; returns how many degenerate
    /// triangles were skipped (as [`crate::SceneBuilder::mesh`]).
    pub fn mesh(
        &mut self,
        mesh: &TriangleMesh,
        material: MaterialId,
        transform: &Transform,
    ) -> Result<usize, BuildError> {
        let (geometry, skipped) = MeshGeometry::new(mesh, transform)?;
        if !geometry.is_empty() {
            self.entries.push(GroupEntry::Mesh(geometry, material.0));
        }
        Ok(skipped)
    }

    /// Adds the six quads of the box `[min, max]`, placed in the group's space by `transform`.
    pub fn add_box(
        &mut self,
        min: Vec3,
        max: Vec3,
        material: MaterialId,
        transform: &Transform,
    ) -> Result<(), BuildError> {
        let faces = Quad::box_faces(min, max, transform).ok_or(BuildError::Degenerate("box"))?;
        self.entries.extend(faces.into_iter().map(|q| GroupEntry::Shape(Shape::Quad(q), material.0)));
        Ok(())
    }

    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// Every material the group's primitives use.
    pub(crate) fn materials(&self) -> impl Iterator<Item = u32> + '_ {
        self.entries.iter().map(|e| match e {
            GroupEntry::Shape(_, m) | GroupEntry::Mesh(_, m) => *m,
        })
    }

    /// Builds the group's own BVH (object space).
    pub(crate) fn build(self) -> Prototype {
        let mut shapes = Vec::new();
        let mut meshes = Vec::new();
        for entry in self.entries {
            match entry {
                GroupEntry::Shape(shape, material) => {
                    shapes.push(Primitive { shape, material, light: Primitive::NO_LIGHT })
                }
                GroupEntry::Mesh(geometry, material) => {
                    meshes.push(SceneMesh { geometry, material, first_light: Primitive::NO_LIGHT })
                }
            }
        }
        let prims = PrimitiveStore::new(shapes, meshes);
        let bvh = Bvh::build(&prims.bounds(), &prims.packables());
        Prototype { prims, bvh }
    }
}

/// A built group: its primitives and their BVH, in object space, shared by every instance.
#[derive(Clone, Debug)]
pub(crate) struct Prototype {
    pub prims: PrimitiveStore,
    pub bvh: Bvh,
}

impl Prototype {
    /// Box of the group's primitives in world space under `to_world` (the eight transformed
    /// corners of the object-space box: conservative, exact for translations and scales).
    pub fn world_bounds(&self, to_world: &Transform) -> Aabb {
        let b = self.bvh.bounds();
        if b.is_empty() {
            return Aabb::EMPTY;
        }
        let corners: [_; 8] = std::array::from_fn(|i| {
            let pick = |bit: usize, lo: f32, hi: f32| if i & bit == 0 { lo } else { hi };
            to_world.point(Vec3::new(pick(1, b.min.x, b.max.x), pick(2, b.min.y, b.max.y), pick(4, b.min.z, b.max.z)))
        });
        Aabb::from_points(&corners)
    }

    pub fn memory_bytes(&self) -> usize {
        self.prims.memory_bytes() + self.bvh.memory_bytes()
    }
}
