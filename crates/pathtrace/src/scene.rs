//! The renderable scene (primitives in a BVH, materials, lights, camera) and the
//! [`SceneBuilder`] that every front end — files, built-in scenes, tests — goes through.

use crate::accel::{Bvh, Intersectable, PrimitiveSet};
use crate::camera::CameraDesc;
use crate::instance::{GroupId, Instance, Instances, ShapeGroup};
use crate::light::{
    AreaLight, DirectionalLight, Emission, EnvironmentLight, Light, LightSet, LightShape, PointLight, RadianceTexture,
    SpotLight,
};
use crate::material::{Blend, Material, Mixture, RoughPlasticAlphaTable};
use crate::math::{Aabb, Ray, Rgb, Transform, Vec3};
use crate::medium::{HomogeneousMedium, MediumBoundary, MediumId};
use crate::primitive_store::{LastTriangle, PrimitiveStore, SceneMesh};
use crate::shape::{with_unit_normals, MeshError, MeshGeometry, PrimHit, Quad, Shape, SurfacePoint, TriangleMesh};
use crate::texture::{ColourSlot, NormalPerturbation, Opacity, PerturbationKind, Texture, TextureBindings, TextureId};
use crate::wide::simd::{F32s, Ms, Vec3s};
use std::sync::Arc;

/// Index of a material in the scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct MaterialId(pub u32);

/// A shape with its material and, if emissive, its light.
#[derive(Clone, Debug, PartialEq)]
pub struct Primitive {
    pub shape: Shape,
    pub material: u32,
    /// Index into the light set, or [`Primitive::NO_LIGHT`].
    pub light: u32,
}

impl Primitive {
    pub const NO_LIGHT: u32 = u32::MAX;
}

impl Intersectable for Primitive {
    #[inline(always)]
    fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<PrimHit> {
        self.shape.intersect(ray, t_min, t_max)
    }
}

/// A ray's closest hit: which primitive, and where along the ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    pub prim: PrimRef,
    pub hit: PrimHit,
}

/// A primitive: in the BVH (shapes first, then each mesh's triangles), one of the unbounded
/// shapes kept beside it, or primitive `prim` of the group placed by `instance`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PrimRef {
    Bounded(u32),
    Unbounded(u32),
    Instance { instance: u32, prim: u32 },
}

/// Everything the integrator needs to know about a hit point.
/// The material is borrowed from the scene: some models carry tables, and copying them per hit
/// would cost time in the path loop.
#[derive(Clone, Copy, Debug)]
pub struct Interaction<'a> {
    pub surface: SurfacePoint,
    pub material: &'a Material,
    /// Index of the material in the scene (for its texture bindings).
    pub material_id: u32,
    pub light: u32,
}

/// Why a scene cannot be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BuildError {
    #[error("material id {0} does not exist")]
    UnknownMaterial(u32),
    #[error("degenerate {0}: zero area or radius, or coordinates or an area beyond single precision (3.4e38)")]
    Degenerate(&'static str),
    #[error("an infinite plane cannot be emissive (it has no finite area to sample)")]
    EmissivePlane,
    #[error("an emissive sphere must be scaled uniformly (an ellipsoid's area cannot be sampled)")]
    EmissiveEllipsoid,
    #[error("invalid mesh: {0}")]
    Mesh(#[from] MeshError),
    #[error("the scene has no objects")]
    Empty,
    #[error("the scene has no lights: nothing would be visible (add an emissive material)")]
    NoLights,
    #[error("invalid material parameter: {0}")]
    Material(String),
    #[error("invalid light: {0}")]
    Light(String),
    #[error("invalid instance: {0}")]
    Instance(String),
    #[error("invalid medium: {0}")]
    Medium(String),
}

/// A scene ready to render.
#[derive(Clone, Debug)]
pub struct Scene {
    prims: PrimitiveStore,
    unbounded: Vec<Primitive>,
    bvh: Bvh,
    /// Placed shape groups (two-level); empty in scenes without instances.
    instances: Instances,
    materials: Vec<Material>,
    /// Per material: the textures bound to its colour slots (most are empty).
    bindings: Vec<TextureBindings>,
    /// Per material: the coating tables over α of a rough plastic with a roughness texture.
    plastic_alpha_tables: Vec<Option<Arc<RoughPlasticAlphaTable>>>,
    textures: Vec<Texture>,
    /// Some material has an opacity mask (rays then pass cut-outs: `crate::cutout`).
    cutouts: bool,
    /// Per material id: it scatters from its front only (black from behind, as Mitsuba's BSDFs
    /// outside `twosided`); opaque materials are otherwise shaded on both faces.
    one_sided: Vec<bool>,
    pub lights: LightSet,
    pub camera: CameraDesc,
    /// The participating media, indexed by medium id.
    media: Vec<HomogeneousMedium>,
    /// Per material id: the media its surfaces separate (empty when the scene has no media).
    boundaries: Vec<Option<MediumBoundary>>,
    /// The medium the camera sits in ([`MediumId::NONE`]: vacuum).
    camera_medium: u32,
    /// The scene has media or `null` surfaces: the estimator's media route is needed.
    volumetric: bool,
    /// Some material is `null` (an index-matched boundary that rays cross).
    null_surfaces: bool,
}

impl Scene {
    /// Closest hit with `t ∈ [0, t_max]`.
    #[inline(always)]
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<Hit> {
        let best =
            self.bvh.intersect(&self.prims, ray, 0.0, t_max).map(|(hit, i)| Hit { prim: PrimRef::Bounded(i), hit });
        self.nearer_outside_bvh(ray, best, t_max)
    }

    /// `best` (the BVH's closest hit), or a nearer hit on an infinite plane or an instance.
    #[inline(always)]
    fn nearer_outside_bvh(&self, ray: &Ray, mut best: Option<Hit>, t_max: f32) -> Option<Hit> {
        for (i, p) in self.unbounded.iter().enumerate() {
            let limit = best.map_or(t_max, |b| b.hit.t);
            if let Some(hit) = p.shape.intersect(ray, 0.0, limit) {
                best = Some(Hit { prim: PrimRef::Unbounded(i as u32), hit });
            }
        }
        if !self.instances.is_empty() {
            let limit = best.map_or(t_max, |b| b.hit.t);
            if let Some((hit, instance, prim)) = self.instances.intersect(ray, 0.0, limit) {
                best = Some(Hit { prim: PrimRef::Instance { instance, prim }, hit });
            }
        }
        best
    }

    /// [`Scene::intersect`] for the rays of `active` (lane `i`: from `origin[i]` along
    /// `dir[i]`), bit for bit the same hits, with the BVH traversed by the group of rays
    /// together (see [`Bvh::intersect_lanes`]); `found(i, hit)` is called for each lane that
    /// hits, lowest lane first. (A visitor, not an array of hits: building sixteen `Option<Hit>`s
    /// per group cost 5% of the teapot's render.)
    #[inline(always)]
    pub fn intersect_lanes<const N: usize>(
        &self,
        origin: &Vec3s<N>,
        dir: &Vec3s<N>,
        active: Ms<N>,
        t_max: f32,
        mut found: impl FnMut(usize, Hit),
    ) {
        let nearest = self.bvh.intersect_lanes(&self.prims, origin, dir, active, 0.0, t_max);
        let bvh_only = self.unbounded.is_empty() && self.instances.is_empty();
        for i in active.lanes() {
            let best = nearest[i].map(|(hit, i)| Hit { prim: PrimRef::Bounded(i), hit });
            let best = if bvh_only {
                best
            } else {
                self.nearer_outside_bvh(&Ray::new(origin.lane(i), dir.lane(i)), best, t_max)
            };
            if let Some(hit) = best {
                found(i, hit);
            }
        }
    }

    /// [`Scene::occluded`] for the rays of `active` (lane `i`: from `origin[i]` along `dir[i]`,
    /// up to `t_max[i]`), with the BVH traversed by the group (see [`Bvh::occluded_lanes`]).
    #[inline(always)]
    pub fn occluded_lanes<const N: usize>(
        &self,
        origin: &Vec3s<N>,
        dir: &Vec3s<N>,
        active: Ms<N>,
        t_max: F32s<N>,
    ) -> Ms<N> {
        let blocked = self.bvh.occluded_lanes(&self.prims, origin, dir, active, 0.0, t_max);
        if self.unbounded.is_empty() && self.instances.is_empty() {
            // Nothing outside the BVH: the mask is the bits (one branch-free expansion, where
            // the lane-by-lane questions below were 1.2% of the teapot's render).
            return Ms::from_fn(|i| blocked >> i & 1 != 0);
        }
        Ms::from_fn(|i| {
            if blocked & (1 << i) != 0 {
                return true;
            }
            if !active.lane(i) {
                return false;
            }
            let ray = Ray::new(origin.lane(i), dir.lane(i));
            self.occluded_outside_bvh(&ray, t_max.0[i])
        })
    }

    /// True if an infinite plane or an instance lies on the ray within `[0, t_max]`.
    #[inline(always)]
    fn occluded_outside_bvh(&self, ray: &Ray, t_max: f32) -> bool {
        self.unbounded.iter().any(|p| p.shape.intersect(ray, 0.0, t_max).is_some())
            || (!self.instances.is_empty() && self.instances.occluded(ray, 0.0, t_max))
    }

    /// True if anything lies on the ray within `[0, t_max]`.
    #[inline(always)]
    pub fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        self.unbounded.iter().any(|p| p.shape.intersect(ray, 0.0, t_max).is_some())
            || self.bvh.occluded(&self.prims, ray, 0.0, t_max)
            || (!self.instances.is_empty() && self.instances.occluded(ray, 0.0, t_max))
    }

    /// Surface details of a hit found with `ray`.
    #[inline(always)]
    pub fn interaction(&self, ray: &Ray, hit: &Hit) -> Interaction<'_> {
        let (mut it, normalised) = self.interaction_unless_mesh_normals(ray, hit);
        if !normalised {
            it.surface = with_unit_normals(it.surface);
        }
        it
    }

    /// [`Scene::interaction`], except that a mesh triangle's normals are left for
    /// [`unit_normals`](crate::shape::unit_normals) to finish (the flag is false then): the
    /// estimator normalises a group's together.
    #[inline(always)]
    pub fn interaction_unless_mesh_normals(&self, ray: &Ray, hit: &Hit) -> (Interaction<'_>, bool) {
        self.interaction_unless_mesh_normals_reusing(ray, hit, &mut None)
    }

    /// [`Scene::interaction_unless_mesh_normals`] that reuses the mesh triangle `last` of the
    /// previous hit if this hit is on it (and keeps this hit's there otherwise): for the hits of
    /// a group, in lane order.
    #[inline(always)]
    pub(crate) fn interaction_unless_mesh_normals_reusing(
        &self,
        ray: &Ray,
        hit: &Hit,
        last: &mut Option<LastTriangle>,
    ) -> (Interaction<'_>, bool) {
        let (surface, material, light, normalised) = match hit.prim {
            PrimRef::Bounded(i) => self.prims.surface_unless_mesh_normals_reusing(i, ray, &hit.hit, last),
            PrimRef::Unbounded(i) => {
                let p = &self.unbounded[i as usize];
                (p.shape.surface(ray, &hit.hit, &[]), p.material, p.light, true)
            }
            PrimRef::Instance { instance, prim } => {
                let (surface, material) = self.instances.surface(instance, prim, ray, &hit.hit);
                (surface, material, Primitive::NO_LIGHT, true)
            }
        };
        (
            Interaction { surface, material: &self.materials[material as usize], material_id: material, light },
            normalised,
        )
    }

    /// The materials, indexed by material id.
    pub fn materials(&self) -> &[Material] {
        &self.materials
    }

    /// True if the scene has participating media or index-matched (`null`) surfaces: paths
    /// then take the estimator's media route (`integrator::media`); other scenes never do.
    #[inline(always)]
    pub fn is_volumetric(&self) -> bool {
        self.volumetric
    }

    /// True if some material is `null`: rays cross such surfaces, so a shadow ray's first hit
    /// does not settle whether light gets through.
    #[inline(always)]
    pub fn has_null_surfaces(&self) -> bool {
        self.null_surfaces
    }

    /// The medium `id` (a lane's current medium, never [`MediumId::NONE`]).
    #[inline(always)]
    pub fn medium(&self, id: u32) -> &HomogeneousMedium {
        &self.media[id as usize]
    }

    /// The media, indexed by medium id.
    pub fn media(&self) -> &[HomogeneousMedium] {
        &self.media
    }

    /// The media the surfaces of material `id` separate, if they bound any.
    #[inline(always)]
    pub fn boundary(&self, material: u32) -> Option<MediumBoundary> {
        self.boundaries.get(material as usize).copied().flatten()
    }

    /// The medium the camera's rays start in ([`MediumId::NONE`]: vacuum).
    #[inline(always)]
    pub fn camera_medium(&self) -> u32 {
        self.camera_medium
    }

    /// True if the scene has infinite planes (kept outside the BVH).
    pub fn has_unbounded(&self) -> bool {
        !self.unbounded.is_empty()
    }

    /// True if the scene places shape groups by instances.
    pub fn has_instances(&self) -> bool {
        !self.instances.is_empty()
    }

    /// The bounded primitives as flat polygons and spheres (see
    /// [`PrimitiveStore::small_scene_shapes`]).
    pub(crate) fn small_scene_shapes(&self) -> Option<crate::primitive_store::SmallSceneShapes> {
        self.prims.small_scene_shapes()
    }

    /// True if any material has a texture.
    #[inline(always)]
    pub fn has_textures(&self) -> bool {
        !self.textures.is_empty()
    }

    /// True if the material at a hit has textured colours (then use
    /// [`Scene::textured_material`] instead of `it.material`). Scenes without textures answer
    /// from one flag, so the constant case costs a predictable branch per hit.
    #[inline(always)]
    pub fn is_textured(&self, it: &Interaction) -> bool {
        self.is_material_textured(it.material_id)
    }

    /// True if material `id` has textured colours.
    #[inline(always)]
    pub fn is_material_textured(&self, id: u32) -> bool {
        self.has_textures() && self.bindings.get(id as usize).is_some_and(|b| !b.is_empty())
    }

    /// The material at a hit with its textures evaluated at the hit's uv.
    #[inline(never)]
    pub fn textured_material(&self, it: &Interaction) -> Material {
        let b = self.bindings.get(it.material_id as usize).copied().unwrap_or_default();
        let mut m = *it.material;
        // Roughness first: a rough plastic's base term depends on α (through its tables).
        if let Some(t) = b.roughness {
            let c = self.textures[t.0 as usize].eval(it.surface.uv);
            let table = self.plastic_alpha_tables.get(it.material_id as usize).and_then(Option::as_deref);
            m = match (&m, table) {
                (Material::RoughPlastic(p), Some(table)) => Material::RoughPlastic(p.with_alpha(c.luminance(), table)),
                _ => m.with_colour(ColourSlot::Roughness, c),
            };
        }
        if let Some(t) = b.base {
            m = m.with_colour(ColourSlot::Base, self.textures[t.0 as usize].eval(it.surface.uv));
        }
        if let Some(t) = b.specular {
            m = m.with_colour(ColourSlot::Specular, self.textures[t.0 as usize].eval(it.surface.uv));
        }
        m
    }

    /// A blend's two models at `surface`, each with its own textures applied, mixed by
    /// `b.weight` (the blend's weight at this hit: [`Scene::textured_material`] has applied its
    /// texture, if any).
    #[inline(never)]
    pub fn mixture(&self, b: &Blend, surface: &SurfacePoint) -> Mixture {
        let model = |id: u32| {
            let it = Interaction {
                surface: *surface,
                material: &self.materials[id as usize],
                material_id: id,
                light: Primitive::NO_LIGHT,
            };
            if self.is_textured(&it) {
                self.textured_material(&it)
            } else {
                *it.material
            }
        };
        Mixture { weight: b.weight, bsdfs: b.bsdfs.map(model) }
    }

    /// The normal or bump map of material `id`, if it has one.
    #[inline(always)]
    pub fn normal_perturbation(&self, id: u32) -> Option<&NormalPerturbation> {
        if !self.has_textures() {
            return None;
        }
        self.bindings.get(id as usize).and_then(|b| b.normal.as_ref())
    }

    /// True if material `id` scatters from its front only: seen from behind (the shading
    /// normal facing away from the viewer) it is black.
    #[inline(always)]
    pub fn is_one_sided(&self, id: u32) -> bool {
        self.one_sided.get(id as usize).copied().unwrap_or(false)
    }

    /// True if some material has an opacity mask.
    #[inline(always)]
    pub fn has_cutouts(&self) -> bool {
        self.cutouts
    }

    /// The opacity mask of material `id`, if it has one.
    #[inline(always)]
    pub fn opacity_mask(&self, id: u32) -> Option<&Opacity> {
        if !self.cutouts {
            return None;
        }
        self.bindings.get(id as usize).and_then(|b| b.opacity.as_ref())
    }

    /// The scene's textures, indexed by [`TextureId`].
    pub fn textures(&self) -> &[Texture] {
        &self.textures
    }

    /// The BVH's nodes, one per line.
    pub fn bvh_dump(&self) -> String {
        self.bvh.dump()
    }

    /// Shape of the BVH.
    pub fn bvh_stats(&self) -> crate::accel::BvhStats {
        self.bvh.stats()
    }

    /// Bytes held by the geometry: shapes, meshes (vertices and indices), the BVH, and the
    /// instances with their groups (each group once) and top-level BVH (from capacities;
    /// materials, lights and the camera are not counted).
    pub fn memory_bytes(&self) -> usize {
        self.prims.memory_bytes()
            + self.unbounded.capacity() * std::mem::size_of::<Primitive>()
            + self.bvh.memory_bytes()
            + self.instances.memory_bytes()
    }

    /// Bytes held by the instances alone: their groups (each once), the instance records and
    /// the top-level BVH (included in [`Scene::memory_bytes`]).
    pub fn instance_memory_bytes(&self) -> usize {
        self.instances.memory_bytes()
    }

    /// Number of primitives stored outside groups (shapes, mesh triangles and unbounded
    /// shapes); instanced primitives are counted by [`Scene::instance_count`].
    pub fn primitive_count(&self) -> usize {
        self.prims.len() + self.unbounded.len()
    }

    /// Number of placed shape groups.
    pub fn instance_count(&self) -> usize {
        self.instances.len()
    }

    /// Brute-force closest hit (every primitive tested; every instance tested through its
    /// group's BVH, without the top level), for checking the BVHs.
    pub fn intersect_brute_force(&self, ray: &Ray, t_max: f32) -> Option<Hit> {
        let mut best: Option<Hit> = None;
        for i in 0..self.prims.len() as u32 {
            let limit = best.map_or(t_max, |b| b.hit.t);
            if let Some(hit) = self.prims.intersect_one(i, ray, 0.0, limit) {
                best = Some(Hit { prim: PrimRef::Bounded(i), hit });
            }
        }
        for (i, p) in self.unbounded.iter().enumerate() {
            let limit = best.map_or(t_max, |b| b.hit.t);
            if let Some(hit) = p.shape.intersect(ray, 0.0, limit) {
                best = Some(Hit { prim: PrimRef::Unbounded(i as u32), hit });
            }
        }
        let limit = best.map_or(t_max, |b| b.hit.t);
        if let Some((hit, instance, prim)) = self.instances.intersect_brute_force(ray, 0.0, limit) {
            best = Some(Hit { prim: PrimRef::Instance { instance, prim }, hit });
        }
        best
    }
}

/// What the builder has been given, in order (lights are numbered in this order).
#[derive(Clone, Debug)]
enum Entry {
    Shape(Shape, u32),
    Mesh(MeshGeometry, u32),
}

/// Assembles a [`Scene`] from shapes, materials, lights and a camera.
#[derive(Clone, Debug, Default)]
pub struct SceneBuilder {
    materials: Vec<(Material, Option<Emission>)>,
    bindings: Vec<TextureBindings>,
    /// Per material id: front-only scattering (see [`Scene::is_one_sided`]).
    one_sided: Vec<bool>,
    textures: Vec<Texture>,
    entries: Vec<Entry>,
    camera: CameraDesc,
    allow_no_lights: bool,
    /// Lights that are not surfaces (point, spot, directional), in the order added.
    lights_in_space: Vec<Light>,
    environment: Option<EnvironmentLight>,
    groups: Vec<ShapeGroup>,
    /// (group, transform, material override or [`Instance::OWN_MATERIALS`]).
    instances: Vec<(u32, Transform, u32)>,
    media: Vec<HomogeneousMedium>,
    /// Per material id: its medium boundary (materials made by [`SceneBuilder::bounded_material`]).
    boundaries: Vec<Option<MediumBoundary>>,
    /// Bounded copies already made: (material, boundary) → the copy's id.
    bounded: Vec<(u32, MediumBoundary, u32)>,
    camera_medium: Option<MediumId>,
    /// Per material id: the texture scaling its emitted radiance, if any.
    emission_textures: Vec<Option<TextureId>>,
}

impl SceneBuilder {
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds a texture, to be bound to materials with [`SceneBuilder::bind_texture`].
    pub fn texture(&mut self, t: Texture) -> TextureId {
        self.textures.push(t);
        TextureId(self.textures.len() as u32 - 1)
    }

    /// Makes `material`'s `slot` colour vary as `texture` (evaluated at each hit's uv). The
    /// material's constant colour in that slot should be the texture's mean (it sets sampling
    /// weights, as in Mitsuba).
    pub fn bind_texture(
        &mut self,
        material: MaterialId,
        slot: ColourSlot,
        texture: TextureId,
    ) -> Result<(), BuildError> {
        self.check_material(material)?;
        let m = &self.materials[material.0 as usize].0;
        if !m.has_slot(slot) {
            return Err(BuildError::Material(format!("a {} material has no {slot:?} colour to texture", m.name())));
        }
        if texture.0 as usize >= self.textures.len() {
            return Err(BuildError::Material(format!("texture id {} does not exist", texture.0)));
        }
        if self.bindings.len() <= material.0 as usize {
            self.bindings.resize(material.0 as usize + 1, TextureBindings::default());
        }
        self.bindings[material.0 as usize].set(slot, texture);
        Ok(())
    }

    /// Tilts `material`'s shading normal by a normal or bump map (whose texture was added with
    /// [`SceneBuilder::texture`]); a second call replaces the first.
    pub fn perturb_normal(&mut self, material: MaterialId, p: NormalPerturbation) -> Result<(), BuildError> {
        self.check_material(material)?;
        if p.texture().0 as usize >= self.textures.len() {
            return Err(BuildError::Material(format!("texture id {} does not exist", p.texture().0)));
        }
        let (name, value) = match p.kind {
            PerturbationKind::NormalMap { strength, .. } => ("normal map strength", strength),
            PerturbationKind::BumpMap { scale, .. } => ("bump map scale", scale),
        };
        if !value.is_finite() {
            return Err(BuildError::Material(format!("{name} {value} must be a finite number")));
        }
        if self.bindings.len() <= material.0 as usize {
            self.bindings.resize(material.0 as usize + 1, TextureBindings::default());
        }
        self.bindings[material.0 as usize].normal = Some(p);
        Ok(())
    }

    /// Makes `material` scatter from its front only (black from behind), as Mitsuba's BSDFs do
    /// unless wrapped in `twosided`. Dielectrics, which have an inside, are refused.
    pub fn set_one_sided(&mut self, material: MaterialId) -> Result<(), BuildError> {
        self.check_material(material)?;
        let m = &self.materials[material.0 as usize].0;
        if !m.is_two_sided() || m.is_null() {
            return Err(BuildError::Material(format!(
                "a {} material cannot be one-sided: it has an inside (light crosses it)",
                m.name()
            )));
        }
        if self.one_sided.len() <= material.0 as usize {
            self.one_sided.resize(material.0 as usize + 1, false);
        }
        self.one_sided[material.0 as usize] = true;
        Ok(())
    }

    /// Gives `material` an opacity mask (whose texture was added with [`SceneBuilder::texture`]);
    /// emissive materials cannot have one (their lights would be sampled where the surface is
    /// cut out).
    pub fn set_opacity(&mut self, material: MaterialId, o: Opacity) -> Result<(), BuildError> {
        self.check_material(material)?;
        if o.texture.0 as usize >= self.textures.len() {
            return Err(BuildError::Material(format!("texture id {} does not exist", o.texture.0)));
        }
        if o.cutoff.is_some_and(|c| !c.is_finite()) {
            return Err(BuildError::Material("an alpha cutoff must be a finite number".into()));
        }
        if self.materials[material.0 as usize].1.is_some_and(|e| !e.radiance.is_black()) {
            return Err(BuildError::Material(
                "an emissive material cannot have an opacity mask (its light would shine from the cut-out parts)"
                    .into(),
            ));
        }
        if self.bindings.len() <= material.0 as usize {
            self.bindings.resize(material.0 as usize + 1, TextureBindings::default());
        }
        self.bindings[material.0 as usize].opacity = Some(o);
        Ok(())
    }

    /// Scales `material`'s emitted radiance by `texture` (added with [`SceneBuilder::texture`]),
    /// looked up at each point's (u, v). Only meshes and quads may carry such a material (their
    /// triangles, or the quad, become textured lights, see [`RadianceTexture`]); other shapes are
    /// a build error.
    pub fn set_emission_texture(&mut self, material: MaterialId, texture: TextureId) -> Result<(), BuildError> {
        self.check_material(material)?;
        if texture.0 as usize >= self.textures.len() {
            return Err(BuildError::Material(format!("texture id {} does not exist", texture.0)));
        }
        if self.materials[material.0 as usize].1.is_none() {
            return Err(BuildError::Material("an emission texture needs an emitting material".into()));
        }
        if self.emission_textures.len() <= material.0 as usize {
            self.emission_textures.resize(material.0 as usize + 1, None);
        }
        self.emission_textures[material.0 as usize] = Some(texture);
        Ok(())
    }

    /// Adds a non-emissive material.
    pub fn material(&mut self, m: Material) -> MaterialId {
        self.materials.push((m, None));
        MaterialId(self.materials.len() as u32 - 1)
    }

    /// Adds a pure emitter: black surface with the given emission.
    pub fn emissive(&mut self, e: Emission) -> MaterialId {
        self.material_with_emission(Material::Black, e)
    }

    /// Adds a material that both scatters and emits (as in a furnace test).
    pub fn material_with_emission(&mut self, m: Material, e: Emission) -> MaterialId {
        self.materials.push((m, Some(e)));
        MaterialId(self.materials.len() as u32 - 1)
    }

    pub fn camera(&mut self, c: CameraDesc) -> &mut Self {
        self.camera = c;
        self
    }

    /// Adds a participating medium; its coefficients must be finite and ≥ 0 and a
    /// Henyey–Greenstein g inside (−1, 1).
    pub fn medium(&mut self, m: HomogeneousMedium) -> Result<MediumId, BuildError> {
        m.check().map_err(BuildError::Medium)?;
        self.media.push(m);
        Ok(MediumId(self.media.len() as u32 - 1))
    }

    /// The medium the camera sits in (`None`: vacuum, the default).
    pub fn camera_medium(&mut self, m: Option<MediumId>) -> Result<(), BuildError> {
        if let Some(m) = m {
            self.check_medium(m)?;
        }
        self.camera_medium = m;
        Ok(())
    }

    fn check_medium(&self, m: MediumId) -> Result<(), BuildError> {
        if (m.0 as usize) < self.media.len() {
            Ok(())
        } else {
            Err(BuildError::Medium(format!("medium id {} does not exist", m.0)))
        }
    }

    /// A material id for shapes of `material` that separate `interior` (behind their normals)
    /// from `exterior` (in front): the same scattering, emission and textures, with the
    /// boundary attached. Media belong to shapes, as in Mitsuba; the estimator reads them per
    /// hit through the material id it already has, so primitives stay as they are. Asking
    /// twice for the same pair gives the same id.
    pub fn bounded_material(
        &mut self,
        material: MaterialId,
        interior: Option<MediumId>,
        exterior: Option<MediumId>,
    ) -> Result<MaterialId, BuildError> {
        self.check_material(material)?;
        for m in [interior, exterior].into_iter().flatten() {
            self.check_medium(m)?;
        }
        if interior.is_none() && exterior.is_none() {
            return Ok(material);
        }
        let id = |m: Option<MediumId>| m.map_or(MediumId::NONE, |m| m.0);
        let boundary = MediumBoundary { interior: id(interior), exterior: id(exterior) };
        if let Some(&(_, _, copy)) = self.bounded.iter().find(|(m, b, _)| *m == material.0 && *b == boundary) {
            return Ok(MaterialId(copy));
        }
        let copy = self.materials[material.0 as usize];
        self.materials.push(copy);
        let new = self.materials.len() as u32 - 1;
        if let Some(b) = self.bindings.get(material.0 as usize).cloned() {
            self.bindings.resize(new as usize + 1, TextureBindings::default());
            self.bindings[new as usize] = b;
        }
        if self.one_sided.get(material.0 as usize).copied().unwrap_or(false) {
            self.one_sided.resize(new as usize + 1, false);
            self.one_sided[new as usize] = true;
        }
        self.boundaries.resize(new as usize + 1, None);
        self.boundaries[new as usize] = Some(boundary);
        self.bounded.push((material.0, boundary, new));
        Ok(MaterialId(new))
    }

    /// Adds a point light; its position and intensity must be finite, the intensity ≥ 0.
    pub fn point_light(&mut self, light: PointLight) -> Result<(), BuildError> {
        let i = light.intensity;
        if !light.position.is_finite() || !i.is_finite() || i.r < 0.0 || i.g < 0.0 || i.b < 0.0 {
            return Err(BuildError::Light("a point light needs a finite position and an intensity ≥ 0".into()));
        }
        self.lights_in_space.push(Light::Point(light));
        Ok(())
    }

    /// Adds a spot light ([`SpotLight::new`] has checked its values).
    pub fn spot_light(&mut self, light: SpotLight) -> &mut Self {
        self.lights_in_space.push(Light::Spot(light));
        self
    }

    /// Adds a directional light ([`DirectionalLight::new`] has checked its values).
    pub fn directional_light(&mut self, light: DirectionalLight) -> &mut Self {
        self.lights_in_space.push(Light::Directional(light));
        self
    }

    /// Sets the environment (radiance arriving from every direction that leaves the scene);
    /// a constant radiance must be finite and ≥ 0 (a map checks its pixels when it is made). A
    /// second call replaces the first.
    pub fn environment(&mut self, env: EnvironmentLight) -> Result<(), BuildError> {
        let l = env.constant_radiance().unwrap_or(Rgb::BLACK);
        if !l.is_finite() || l.r < 0.0 || l.g < 0.0 || l.b < 0.0 {
            return Err(BuildError::Light("an environment's radiance must be finite and ≥ 0".into()));
        }
        self.environment = Some(env);
        Ok(())
    }

    /// Allows building a scene without lights (it renders black); off by default because
    /// that is almost always a mistake in a scene file.
    pub fn allow_no_lights(&mut self, allow: bool) -> &mut Self {
        self.allow_no_lights = allow;
        self
    }

    fn check_material(&self, m: MaterialId) -> Result<(), BuildError> {
        if (m.0 as usize) < self.materials.len() {
            Ok(())
        } else {
            Err(BuildError::UnknownMaterial(m.0))
        }
    }

    /// Adds a shape placed by `transform`.
    pub fn shape(&mut self, shape: Shape, material: MaterialId, transform: &Transform) -> Result<(), BuildError> {
        self.check_material(material)?;
        let placed = shape.transformed(transform).ok_or(BuildError::Degenerate(shape_name(&shape)))?;
        self.entries.push(Entry::Shape(placed, material.0));
        Ok(())
    }

    /// Adds the six quads of the box `[min, max]`, placed by `transform`.
    pub fn add_box(
        &mut self,
        min: Vec3,
        max: Vec3,
        material: MaterialId,
        transform: &Transform,
    ) -> Result<(), BuildError> {
        self.check_material(material)?;
        let faces = Quad::box_faces(min, max, transform).ok_or(BuildError::Degenerate("box"))?;
        self.entries.extend(faces.into_iter().map(|q| Entry::Shape(Shape::Quad(q), material.0)));
        Ok(())
    }

    /// Adds a mesh placed by `transform`, kept in compact form (shared vertices and indices).
    /// Degenerate triangles are skipped (meshes often contain a few); returns how many were
    /// skipped.
    pub fn mesh(
        &mut self,
        mesh: &TriangleMesh,
        material: MaterialId,
        transform: &Transform,
    ) -> Result<usize, BuildError> {
        self.check_material(material)?;
        let (geometry, skipped) = MeshGeometry::new(mesh, transform)?;
        if !geometry.is_empty() {
            self.entries.push(Entry::Mesh(geometry, material.0));
        }
        Ok(skipped)
    }

    /// Adds a shape group to be placed by [`SceneBuilder::instance`]; its materials must
    /// exist.
    pub fn group(&mut self, group: ShapeGroup) -> Result<GroupId, BuildError> {
        for m in group.materials() {
            self.check_material(MaterialId(m))?;
        }
        self.groups.push(group);
        Ok(GroupId(self.groups.len() as u32 - 1))
    }

    /// Places `group` by `transform`, with its own materials or every primitive in `material`.
    /// The group is stored (and its BVH built) once however many instances place it.
    pub fn instance(
        &mut self,
        group: GroupId,
        transform: &Transform,
        material: Option<MaterialId>,
    ) -> Result<(), BuildError> {
        if group.0 as usize >= self.groups.len() {
            return Err(BuildError::Instance(format!("shape group {} does not exist", group.0)));
        }
        if !transform.matrix.is_finite() || !transform.inverse.is_finite() {
            return Err(BuildError::Instance("the transform must be finite and invertible".into()));
        }
        if let Some(m) = material {
            self.check_material(m)?;
        }
        self.instances.push((group.0, *transform, material.map_or(Instance::OWN_MATERIALS, |m| m.0)));
        Ok(())
    }

    /// Builds each instanced group's BVH and the top level over the instances. Instanced
    /// primitives cannot emit: their materials (or an instance's override) must not be
    /// emissive.
    fn build_instances(&mut self) -> Result<Instances, BuildError> {
        if self.instances.is_empty() {
            return Ok(Instances::default());
        }
        let emits = |m: u32| self.materials[m as usize].1.is_some_and(|e| !e.radiance.is_black());
        // Only groups that are placed are built; they are renumbered densely.
        let mut new_index = vec![u32::MAX; self.groups.len()];
        let mut used = Vec::new();
        for &(g, _, material) in &self.instances {
            let emissive = if material == Instance::OWN_MATERIALS {
                self.groups[g as usize].materials().any(emits)
            } else {
                emits(material)
            };
            if emissive {
                return Err(BuildError::Instance(
                    "an instanced shape's material cannot be emissive (instanced shapes are not lights; \
                     override the material or add the emitter as an ordinary object)"
                        .into(),
                ));
            }
            if new_index[g as usize] == u32::MAX {
                new_index[g as usize] = used.len() as u32;
                used.push(g);
            }
        }
        let groups: Vec<_> = used.iter().map(|&g| std::mem::take(&mut self.groups[g as usize]).build()).collect();
        let instances = self
            .instances
            .iter()
            .filter(|&&(g, ..)| !groups[new_index[g as usize] as usize].prims.is_empty())
            .map(|&(g, to_world, material)| Instance {
                group: new_index[g as usize],
                to_world,
                material,
                mirrors: to_world.matrix.determinant() < 0.0,
            })
            .collect();
        Ok(Instances::new(groups, instances))
    }

    /// Builds the BVH and the light set.
    pub fn build(mut self) -> Result<Scene, BuildError> {
        if self.entries.is_empty() && self.instances.is_empty() {
            return Err(BuildError::Empty);
        }
        for (m, _) in &self.materials {
            validate_material(m)?;
            if let Material::Blend(b) = m {
                check_blend_models(b, |id| self.materials.get(id as usize).map(|(m, _)| m))?;
            }
        }
        let instances = self.build_instances()?;
        let mut shapes = Vec::new();
        let mut meshes = Vec::new();
        let mut unbounded = Vec::new();
        let mut lights = Vec::new();
        // Per area light, the emitter it is part of: each shape entry is one, an emissive mesh's
        // triangles together are one (uniform light selection picks emitters, Mitsuba's rule).
        let mut emitters: Vec<u32> = Vec::new();
        let mut next_emitter = 0u32;
        // One shared copy of each emission texture.
        let emission_texture = |m: u32| -> Option<Arc<Texture>> {
            let id = (*self.emission_textures.get(m as usize)?)?;
            Some(Arc::new(self.textures[id.0 as usize].clone()))
        };
        let emission_textures: Vec<Option<Arc<Texture>>> =
            (0..self.materials.len() as u32).map(emission_texture).collect();
        for entry in self.entries {
            let (Entry::Shape(_, material) | Entry::Mesh(_, material)) = entry;
            let emission = self.materials[material as usize].1.filter(|e| !e.radiance.is_black());
            match entry {
                Entry::Shape(shape, _) => {
                    let light = match emission {
                        Some(e) if emission_textures[material as usize].is_some() => {
                            let (Shape::Quad(q), Some(texture)) = (&shape, &emission_textures[material as usize])
                            else {
                                return Err(BuildError::Material(
                                    "an emission texture is supported on meshes and quads only (they carry the uv)"
                                        .into(),
                                ));
                            };
                            let t = RadianceTexture::on_quad(texture.clone());
                            lights.push(AreaLight::new(LightShape::Quad(*q), e).with_texture(t).expect("a quad light"));
                            lights.len() as u32 - 1
                        }
                        Some(e) => {
                            let light_shape = match &shape {
                                Shape::Quad(q) => LightShape::Quad(*q),
                                Shape::Triangle(t) => LightShape::Triangle(*t),
                                Shape::Sphere(s) => LightShape::Sphere(*s),
                                Shape::Disk(d) => LightShape::Disk(*d),
                                Shape::Plane(_) => return Err(BuildError::EmissivePlane),
                                Shape::Ellipsoid(_) => return Err(BuildError::EmissiveEllipsoid),
                            };
                            lights.push(AreaLight::new(light_shape, e));
                            lights.len() as u32 - 1
                        }
                        None => Primitive::NO_LIGHT,
                    };
                    if light != Primitive::NO_LIGHT {
                        emitters.push(next_emitter);
                        next_emitter += 1;
                    }
                    let prim = Primitive { shape, material, light };
                    if prim.shape.bounds().is_some() {
                        shapes.push(prim);
                    } else {
                        unbounded.push(prim);
                    }
                }
                Entry::Mesh(geometry, _) => {
                    // An emissive mesh is one area light per triangle, sampled by area.
                    let first_light = match emission {
                        Some(e) => {
                            let first = lights.len() as u32;
                            emitters.resize(lights.len() + geometry.len(), next_emitter);
                            next_emitter += 1;
                            for i in 0..geometry.len() as u32 {
                                let light = AreaLight::new(LightShape::Triangle(geometry.triangle(i)), e);
                                lights.push(match &emission_textures[material as usize] {
                                    None => light,
                                    Some(texture) => {
                                        let corner_uv = geometry.corner_uvs(i);
                                        let t = RadianceTexture { texture: texture.clone(), corner_uv };
                                        light.with_texture(t).expect("a mesh light is a triangle")
                                    }
                                });
                            }
                            first
                        }
                        None => Primitive::NO_LIGHT,
                    };
                    meshes.push(SceneMesh { geometry, material, first_light });
                }
            }
        }
        let prims = PrimitiveStore::new(shapes, meshes);
        let bounds = prims.bounds();
        // The environment's selection power needs the scene's size: its bounding sphere.
        let mut scene_box = bounds.iter().fold(None, |acc: Option<Aabb>, &b| Some(acc.map_or(b, |a| a.union(b))));
        if !instances.is_empty() {
            scene_box = Some(scene_box.map_or(instances.bounds(), |a| a.union(instances.bounds())));
        }
        let scene_radius = scene_box.map_or(1.0, |b| 0.5 * b.extent().length());
        // Area lights first, so that a primitive's light id indexes the set.
        let lights: Vec<Light> = lights
            .into_iter()
            .map(Light::Area)
            .chain(self.lights_in_space)
            .chain(self.environment.map(Light::Environment))
            .collect();
        // Lights in space and the environment are each an emitter of their own.
        emitters.extend(next_emitter..next_emitter + (lights.len() - emitters.len()) as u32);
        let lights = LightSet::with_emitters(lights, emitters, scene_radius);
        if lights.is_empty() && !self.allow_no_lights {
            return Err(BuildError::NoLights);
        }
        let bvh = Bvh::build(&bounds, &prims.packables());
        let mut bindings = self.bindings;
        bindings.resize(self.materials.len(), TextureBindings::default());
        let cutouts = bindings.iter().any(|b| b.opacity.is_some());
        // A rough plastic whose α is textured needs its coating tables at every α: built once here.
        let plastic_alpha_tables = self
            .materials
            .iter()
            .zip(&bindings)
            .map(|((m, _), b)| match m {
                Material::RoughPlastic(p) if b.roughness.is_some() => Some(Arc::new(RoughPlasticAlphaTable::new(p))),
                _ => None,
            })
            .collect();
        let mut one_sided = self.one_sided;
        one_sided.resize(self.materials.len(), false);
        let mut boundaries = self.boundaries;
        if !self.media.is_empty() {
            boundaries.resize(self.materials.len(), None);
        } else {
            boundaries.clear();
        }
        let null_surfaces = self.materials.iter().any(|(m, _)| m.is_null());
        let volumetric = !self.media.is_empty() || null_surfaces;
        Ok(Scene {
            prims,
            unbounded,
            bvh,
            instances,
            materials: self.materials.into_iter().map(|(m, _)| m).collect(),
            bindings,
            plastic_alpha_tables,
            textures: self.textures,
            cutouts,
            one_sided,
            lights,
            camera: self.camera,
            media: self.media,
            boundaries,
            camera_medium: self.camera_medium.map_or(MediumId::NONE, |m| m.0),
            volumetric,
            null_surfaces,
        })
    }
}

fn shape_name(s: &Shape) -> &'static str {
    match s {
        Shape::Sphere(_) | Shape::Ellipsoid(_) => "sphere",
        Shape::Plane(_) => "plane",
        Shape::Quad(_) => "quad",
        Shape::Triangle(_) => "triangle",
        Shape::Disk(_) => "disk",
    }
}

/// Checks a material's parameters (albedos in [0, 1], positive ior, …) as [`SceneBuilder::build`]
/// does, so front ends can report a bad material where it is defined.
/// Indices of refraction a material may have: every real material lies between 1 and about 4, and
/// the relative index of an interface between their ratios; beyond these the coating formulas
/// lose all precision (a plastic of ior 1e6 dropped 5.6% of its samples as NaN).
pub const IOR_RANGE: std::ops::RangeInclusive<f32> = 0.01..=100.0;

/// The largest microfacet roughness α: at α = 1 a surface is already as rough as the models
/// describe; at 3e38 a rough plastic dropped 11% of its samples as NaN.
pub const MAX_ALPHA: f32 = 100.0;

fn ior_message(kind: &str, ior: f32) -> String {
    format!(
        "{kind} ior {ior} must be from {} to {} (real materials lie between 1 and 4)",
        IOR_RANGE.start(),
        IOR_RANGE.end()
    )
}

fn too_rough(m: &crate::material::Microfacet) -> bool {
    !(m.alpha_u <= MAX_ALPHA && m.alpha_v <= MAX_ALPHA)
}

fn alpha_message(kind: &str, m: &crate::material::Microfacet) -> String {
    format!(
        "{kind} roughness alpha {} must be from 0 to {MAX_ALPHA} (1 is already fully rough)",
        m.alpha_u.max(m.alpha_v)
    )
}

pub fn validate_material(m: &Material) -> Result<(), BuildError> {
    // One arm per model, no catch-all: a new model does not compile until it says what it checks.
    match m {
        Material::Black | Material::Null => Ok(()),
        Material::Diffuse(d) => check_unit_colour("diffuse albedo", d.albedo),
        Material::Lambertian(d) => check_unit_colour("lambertian albedo", d.albedo),
        Material::Mirror(d) => check_unit_colour("mirror reflectance", d.reflectance),
        Material::Glossy(g) => {
            check_unit_colour("glossy albedo", g.albedo)?;
            if !(g.exponent >= 0.0 && g.exponent.is_finite()) {
                return material_error(format!("glossy exponent {} must be a non-negative number", g.exponent));
            }
            Ok(())
        }
        Material::Dielectric(d) => {
            check_ior("dielectric", d.ior)?;
            check_unit_colour("dielectric tint", d.tint)
        }
        Material::ThinDielectric(d) => {
            check_ior("thindielectric", d.ior)?;
            check_unit_colour("thindielectric tint", d.tint)
        }
        Material::RoughDielectric(d) => {
            check_ior("rough_dielectric", d.ior)?;
            check_unit_colour("rough_dielectric tint", d.tint)?;
            check_roughness("rough_dielectric", &d.distribution)
        }
        Material::Conductor(c) => {
            check_conductor_colours("conductor", c.eta, c.k, c.reflectance)?;
            check_unit_colour("conductor reflectance", c.reflectance)
        }
        Material::RoughConductor(c) => {
            check_conductor_colours("rough_conductor", c.eta, c.k, c.reflectance)?;
            check_unit_colour("rough_conductor reflectance", c.reflectance)?;
            check_roughness("rough_conductor", &c.distribution)
        }
        Material::Plastic(p) => check_ior("plastic", p.ior),
        Material::RoughPlastic(p) => {
            check_ior("rough_plastic", p.ior)?;
            check_roughness("rough_plastic", &p.distribution)
        }
        Material::Blend(b) => {
            if !(0.0..=1.0).contains(&b.weight) {
                return material_error(format!("blend weight {} must be from 0 to 1", b.weight));
            }
            Ok(())
        }
    }
}

/// A blend's two models, found by `model`: they must exist and be opaque models without Dirac
/// lobes ([`Blend::accepts`]).
pub fn check_blend_models<'a>(b: &Blend, model: impl Fn(u32) -> Option<&'a Material>) -> Result<(), BuildError> {
    for (k, &id) in b.bsdfs.iter().enumerate() {
        match model(id) {
            None => return material_error(format!("blend model {k} is material {id}, which does not exist")),
            Some(m) if !Blend::accepts(m) => {
                return material_error(format!(
                    "blend model {k} is a `{}`: a blend mixes opaque models without mirror-like lobes \
                     (black, diffuse, lambertian, glossy, rough_conductor, rough_plastic)",
                    m.name()
                ))
            }
            Some(_) => {}
        }
    }
    Ok(())
}

fn material_error(message: String) -> Result<(), BuildError> {
    Err(BuildError::Material(message))
}

fn colour_ok(c: crate::math::Rgb) -> bool {
    c.is_finite() && c.r >= 0.0 && c.g >= 0.0 && c.b >= 0.0
}

/// A reflectance-like colour: finite, each channel in [0, 1].
fn check_unit_colour(what: &str, c: crate::math::Rgb) -> Result<(), BuildError> {
    if !colour_ok(c) || c.max_component() > 1.0 {
        return material_error(format!("{what} {:?} must be in [0, 1]", c.to_array()));
    }
    Ok(())
}

fn check_conductor_colours(
    kind: &str,
    eta: crate::math::Rgb,
    k: crate::math::Rgb,
    reflectance: crate::math::Rgb,
) -> Result<(), BuildError> {
    if !colour_ok(eta) || !colour_ok(k) || !colour_ok(reflectance) {
        return material_error(format!("{kind} eta, k and reflectance must be ≥ 0"));
    }
    Ok(())
}

fn check_ior(kind: &str, ior: f32) -> Result<(), BuildError> {
    if !IOR_RANGE.contains(&ior) {
        return material_error(ior_message(kind, ior));
    }
    Ok(())
}

fn check_roughness(kind: &str, m: &crate::material::Microfacet) -> Result<(), BuildError> {
    if too_rough(m) {
        return material_error(alpha_message(kind, m));
    }
    Ok(())
}
