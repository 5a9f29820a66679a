//! Instances: a shape group (a mesh, or any bounded primitives) is built once into its own BVH
//! in object space, and placed many times by instances, each a reference to the group, a
//! transform with its inverse, and an optional material override. A top-level BVH over the
//! instances' world boxes finds the instances a ray may hit; the ray is moved into each one's
//! object space (direction not renormalised, so `t` is the same along both rays) and traced
//! through the group's BVH; the hit surface is moved back (points by the transform, normals by
//! its inverse transpose). See docs/bvh.md, "Instances".

mod group;

pub(crate) use group::Prototype;
pub use group::ShapeGroup;

use std::cell::Cell;

use crate::accel::{Bvh, Packable, PrimitiveSet};
use crate::math::{Aabb, Mat3, Ray, Transform};
use crate::shape::{PrimHit, SurfacePoint};

/// Index of a shape group in a [`crate::SceneBuilder`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct GroupId(pub u32);

/// One placement of a group.
#[derive(Clone, Debug)]
pub(crate) struct Instance {
    pub group: u32,
    pub to_world: Transform,
    /// Material of every primitive of this instance, or [`Instance::OWN_MATERIALS`].
    pub material: u32,
    /// The transform mirrors (negative determinant): winding-defined normals (triangles,
    /// quads, disks) turn over, as they do when the geometry itself is transformed.
    pub mirrors: bool,
}

impl Instance {
    pub const OWN_MATERIALS: u32 = u32::MAX;

    /// The ray in the group's object space: same `t` for the same point.
    #[inline(always)]
    fn local_ray(&self, ray: &Ray) -> Ray {
        let inv = &self.to_world.inverse;
        Ray::new(inv.transform_point3(ray.origin), inv.transform_vector3(ray.dir))
    }
}

/// The groups, their instances and the top-level BVH over the instances' world boxes.
#[derive(Clone, Debug, Default)]
pub(crate) struct Instances {
    groups: Vec<Prototype>,
    instances: Vec<Instance>,
    top: Bvh,
}

/// The top-level BVH's view of the instances: testing one traces its group's BVH, and the
/// primitive of the latest hit is remembered (the BVH keeps only the closest hit so far, and
/// every hit it is given replaces the previous one, so the last one recorded is the closest).
struct Probe<'a> {
    set: &'a Instances,
    inner: Cell<u32>,
}

impl PrimitiveSet for Probe<'_> {
    #[inline(always)]
    fn intersect_one(&self, index: u32, ray: &Ray, t_min: f32, t_max: f32) -> Option<PrimHit> {
        let inst = &self.set.instances[index as usize];
        let proto = &self.set.groups[inst.group as usize];
        let (hit, inner) = proto.bvh.intersect(&proto.prims, &inst.local_ray(ray), t_min, t_max)?;
        self.inner.set(inner);
        Some(hit)
    }
}

/// The same view for shadow rays: "hit" means "occluded".
struct Blocker<'a>(&'a Instances);

impl PrimitiveSet for Blocker<'_> {
    #[inline(always)]
    fn intersect_one(&self, index: u32, ray: &Ray, t_min: f32, t_max: f32) -> Option<PrimHit> {
        let inst = &self.0.instances[index as usize];
        let proto = &self.0.groups[inst.group as usize];
        let blocked = proto.bvh.occluded(&proto.prims, &inst.local_ray(ray), t_min, t_max);
        blocked.then_some(PrimHit { t: t_min, u: 0.0, v: 0.0 })
    }
}

impl Instances {
    /// Builds the top level over `instances` of `groups`.
    pub fn new(groups: Vec<Prototype>, instances: Vec<Instance>) -> Self {
        let bounds: Vec<Aabb> = instances.iter().map(|i| groups[i.group as usize].world_bounds(&i.to_world)).collect();
        let top = Bvh::build(&bounds, &vec![Packable::No; bounds.len()]);
        Self { groups, instances, top }
    }

    pub fn is_empty(&self) -> bool {
        self.instances.is_empty()
    }

    pub fn len(&self) -> usize {
        self.instances.len()
    }

    /// Closest hit: (hit, instance, primitive of its group).
    ///
    /// Out of line (as `occluded`): the two-level walk is large, and inlined it put three
    /// copies of itself into each copy of the render loop, a fifth of its size, for scenes
    /// that mostly have no instances.
    #[inline(never)]
    pub fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<(PrimHit, u32, u32)> {
        let probe = Probe { set: self, inner: Cell::new(0) };
        let (hit, instance) = self.top.intersect(&probe, ray, t_min, t_max)?;
        Some((hit, instance, probe.inner.get()))
    }

    /// True if any instance blocks the ray within `[t_min, t_max]`.
    #[inline(never)]
    pub fn occluded(&self, ray: &Ray, t_min: f32, t_max: f32) -> bool {
        self.top.occluded(&Blocker(self), ray, t_min, t_max)
    }

    /// Surface (in world space), material and light (none) of a hit on primitive `prim` of
    /// `instance`, found with the world-space `ray`.
    #[inline(always)]
    pub fn surface(&self, instance: u32, prim: u32, ray: &Ray, hit: &PrimHit) -> (SurfacePoint, u32) {
        let inst = &self.instances[instance as usize];
        let proto = &self.groups[inst.group as usize];
        let (local, material, _) = proto.prims.surface(prim, &inst.local_ray(ray), hit);
        let m = &inst.to_world;
        // Normals by the inverse transpose (perpendicular to every transformed tangent);
        // winding-defined fronts turn over under a mirror, as the flattened geometry's do.
        let normal = Mat3::from_mat4(m.inverse).transpose();
        let flip = if inst.mirrors && proto.prims.front_follows_winding(prim) { -1.0 } else { 1.0 };
        let n_geometric = flip * (normal * local.n_geometric).normalize();
        let mut n_shading = (normal * local.n_shading).normalize_or(n_geometric);
        if n_shading.dot(n_geometric) < 0.0 {
            n_shading = -n_shading;
        }
        // ∂p/∂u is a tangent vector: it moves with the matrix (zero stays zero, the fallback).
        let (dpdu, dpdv) = (m.vector(local.dpdu), m.vector(local.dpdv));
        // The mesh's own tangent moves with the matrix too; a mirror reverses the handedness
        // of (n, tangent, bitangent), so the bitangent's sign turns over with it.
        let t = local.vertex_tangent;
        let vertex_tangent =
            if t.w == 0.0 { t } else { m.vector(t.truncate()).extend(if inst.mirrors { -t.w } else { t.w }) };
        let surface =
            SurfacePoint { p: m.point(local.p), n_geometric, n_shading, uv: local.uv, dpdu, dpdv, vertex_tangent };
        let material = if inst.material == Instance::OWN_MATERIALS { material } else { inst.material };
        (surface, material)
    }

    /// World boxes of the instances.
    pub fn bounds(&self) -> Aabb {
        self.top.bounds()
    }

    /// Bytes held: every group once (primitives and BVH), the instances and the top level.
    pub fn memory_bytes(&self) -> usize {
        self.groups.iter().map(Prototype::memory_bytes).sum::<usize>()
            + self.groups.capacity() * std::mem::size_of::<Prototype>()
            + self.instances.capacity() * std::mem::size_of::<Instance>()
            + self.top.memory_bytes()
    }

    /// Closest hit by testing every instance (no top-level BVH), for checks.
    pub fn intersect_brute_force(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<(PrimHit, u32, u32)> {
        let probe = Probe { set: self, inner: Cell::new(0) };
        let mut best = None;
        for i in 0..self.instances.len() as u32 {
            let limit = best.map_or(t_max, |(h, _, _): (PrimHit, u32, u32)| h.t);
            if let Some(hit) = probe.intersect_one(i, ray, t_min, limit) {
                best = Some((hit, i, probe.inner.get()));
            }
        }
        best
    }
}
