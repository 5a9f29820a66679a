//! [`SceneFile`] → [`LoadedScene`] through the engine's `SceneBuilder`: materials by name, the
//! scene graph flattened (an object's own transform first, then each enclosing group's, innermost
//! first), meshes loaded relative to the scene file, and every failure reported at its item.

use super::error::SceneError;
use super::locate::{ItemPath, Locate};
use super::medium::build_medium;
use super::model::{
    CameraSection, Colour, FilterDef, FilterName, GroupDef, InstanceDef, LightDef, MaterialDef, MaterialKind,
    MeshNormals, MetalDef, NormalDef, NormalPerturbationDef, Num, ObjectDef, ProjectionName, RenderSection,
    RoughnessDef, SceneFile, ShapeDef, TextureDef, UvRows,
};
use super::transform::compose;
use super::values::{vec3, Triple};
use crate::{LoadedScene, RenderDefaults};
use pathtrace::film::Image;
use pathtrace::film::{GaussianFilter, PixelFilter};
use pathtrace::light::{DirectionalLight, Emission, EnvMap, EnvironmentLight, PointLight, SpotLight};
use pathtrace::material::{
    metal, Blend, Conductor, Dielectric, Diffuse, Glossy, Lambertian, Material, Microfacet, Mirror, Plastic,
    RoughConductor, RoughDielectric, RoughPlastic, ThinDielectric,
};
use pathtrace::math::{Rgb, Transform, Vec3};
use pathtrace::medium::MediumId;
use pathtrace::scene::{validate_material, BuildError};
use pathtrace::shape::TriangleMesh;
use pathtrace::shape::{Disk, Plane, Quad, Shape, Sphere, Triangle};
use pathtrace::texture::{
    Bitmap, Checkerboard, ColourSlot, FilterType, NormalPerturbation, Opacity, PerturbationKind, Texture, UvTransform,
    WrapMode,
};
use pathtrace::{Camera, CameraDesc, GroupId, Lens, MaterialId, SceneBuilder, ShapeGroup};
use std::collections::BTreeMap;

/// Builds the scene a file describes; `src` locates errors and resolves relative mesh paths.
pub fn build(file: &SceneFile, src: &impl Locate) -> Result<LoadedScene, SceneError> {
    let defaults = render_defaults(&file.render, &file.camera, src)?;
    let mut ctx = Ctx {
        src,
        b: SceneBuilder::new(),
        ids: BTreeMap::new(),
        media: BTreeMap::new(),
        materials: &file.materials,
        group: None,
    };
    // Blends last: they name the materials they mix (which cannot be blends themselves).
    let is_blend = |d: &MaterialDef| matches!(d.kind.sides().0, MaterialKind::Blend { .. });
    let in_order =
        file.materials.iter().filter(|(_, d)| !is_blend(d)).chain(file.materials.iter().filter(|(_, d)| is_blend(d)));
    for (name, def) in in_order {
        let id = ctx.add_material(name, def)?;
        ctx.ids.insert(name.clone(), id);
    }
    let root = ItemPath::root();
    for (name, def) in &file.media {
        let at = root.field("media").field(name);
        let medium =
            build_medium(def).map_err(|(field, e)| src.error_at(&at.field(field), format!("medium `{name}`: {e}")))?;
        let id = ctx.b.medium(medium).map_err(|e| src.error_at(&at, e.to_string()))?;
        ctx.media.insert(name.clone(), id);
    }
    if let Some(name) = &file.camera.medium {
        let id = ctx.medium_id(name, &root.field("camera").field("medium"))?;
        ctx.b
            .camera_medium(Some(id))
            .map_err(|e| src.error_at(&root.field("camera").field("medium"), e.to_string()))?;
    }
    for (i, o) in file.objects.iter().enumerate() {
        ctx.add_object(o, &Transform::IDENTITY, &root.field("objects").index(i))?;
    }
    for (i, g) in file.groups.iter().enumerate() {
        ctx.add_group(g, &Transform::IDENTITY, &root.field("groups").index(i))?;
    }
    let mut group_ids = BTreeMap::new();
    for (name, g) in &file.shape_groups {
        group_ids.insert(name.as_str(), ctx.add_shape_group(name, g)?);
    }
    for (i, inst) in file.instances.iter().enumerate() {
        ctx.add_instance(inst, &group_ids, &root.field("instances").index(i))?;
    }
    for (i, l) in file.lights.iter().enumerate() {
        ctx.add_light(l, &root.field("lights").index(i))?;
    }
    let camera = camera_desc(&file.camera, src)?;
    Camera::new(&camera, defaults.width, defaults.height)
        .map_err(|e| src.error_at(&root.field("camera"), format!("invalid camera: {e}")))?;
    ctx.b.camera(camera);
    let mut scene = ctx.b.build().map_err(|e| match e {
        BuildError::Empty => SceneError::whole_file(src.path(), "the scene has no objects (add an [[objects]] entry)"),
        BuildError::NoLights => src.error_at(
            &root.field("materials"),
            "the scene has no lights: nothing would be visible (give an object an emissive material)",
        ),
        other => SceneError::whole_file(src.path(), other.to_string()),
    })?;
    if let Some(mode) = defaults.light_selection {
        scene.lights.set_selection(mode);
    }
    Ok(LoadedScene { scene, defaults })
}

fn camera_desc(c: &CameraSection, src: &impl Locate) -> Result<CameraDesc, SceneError> {
    let at = |field: &str| ItemPath::root().field("camera").field(field);
    let projection = c.projection.unwrap_or_default();
    // Each projection's own fields, refused on the others so a typo'd `type` is not silent.
    let own: &[&str] = match projection {
        ProjectionName::Perspective => &[],
        ProjectionName::Thinlens => &["aperture_radius", "focus_distance"],
        ProjectionName::Orthographic => &["height"],
    };
    for (name, v) in
        [("aperture_radius", c.aperture_radius), ("focus_distance", c.focus_distance), ("height", c.height)]
    {
        if v.is_some() && !own.contains(&name) {
            let kind = if name == "height" { "orthographic" } else { "thinlens" };
            return Err(src.error_at(&at(name), format!("`{name}` belongs to a `type = \"{kind}\"` camera")));
        }
    }
    let look_from = vec3(&c.look_from);
    let look_at = vec3(&c.look_at);
    let lens = match projection {
        ProjectionName::Perspective => Lens::Pinhole,
        ProjectionName::Thinlens => {
            let Some(aperture_radius) = c.aperture_radius else {
                return Err(src.error_at(&at("type"), "a thinlens camera needs `aperture_radius` (scene units)"));
            };
            let focus_distance = c.focus_distance.map_or((look_at - look_from).length(), |v| v.f32());
            Lens::ThinLens { aperture_radius: aperture_radius.f32(), focus_distance }
        }
        ProjectionName::Orthographic => {
            let Some(height) = c.height else {
                return Err(src.error_at(&at("type"), "an orthographic camera needs `height` (scene units)"));
            };
            Lens::Orthographic { height: height.f32() }
        }
    };
    Ok(CameraDesc {
        look_from,
        look_at,
        up: c.up.as_ref().map_or(Vec3::Y, vec3),
        vfov_degrees: c.vfov.map_or(CameraSection::DEFAULT_VFOV, |v| v.f32()),
        focal_length: c.focal_length.map_or(CameraSection::DEFAULT_FOCAL_LENGTH, |v| v.f32()),
        lens,
    })
}

/// Render settings with defaults filled in. With `camera.aspect` (= width / height) and not both
/// sizes given, the missing size is derived from the given (or default) one, rounded.
fn render_defaults(r: &RenderSection, c: &CameraSection, src: &impl Locate) -> Result<RenderDefaults, SceneError> {
    let at = |field: &str| ItemPath::root().field("render").field(field);
    let max = RenderSection::MAX_SIZE;
    for (name, v) in [("width", r.width), ("height", r.height)] {
        if v.is_some_and(|v| !(1..=max).contains(&v)) {
            return Err(src.error_at(&at(name), format!("{name} must be from 1 to {max} pixels")));
        }
    }
    if r.spp == Some(0) {
        return Err(src.error_at(&at("spp"), "spp must be at least 1"));
    }
    if r.max_depth.is_some_and(|d| d < -1) {
        return Err(src.error_at(&at("max_depth"), "max_depth must be ≥ 0, or -1 for unlimited"));
    }
    if r.rr_depth == Some(0) {
        return Err(src.error_at(&at("rr_depth"), "rr_depth must be at least 1 (the segments before Russian roulette)"));
    }
    let (dw, dh) = (RenderSection::DEFAULT_WIDTH, RenderSection::DEFAULT_HEIGHT);
    let (width, height) = match (r.width, r.height, c.aspect) {
        (w, h, None) => (w.unwrap_or(dw), h.unwrap_or(dh)),
        (_, _, Some(a)) if a.get() <= 0.0 => {
            return Err(src.error_at(&ItemPath::root().field("camera").field("aspect"), "aspect must be positive"));
        }
        (Some(w), Some(h), Some(_)) => (w, h),
        (w, h, Some(a)) => {
            let derive = |x: f64| x.round().clamp(1.0, max as f64) as u32;
            match h {
                Some(h) => (derive(h as f64 * a.get()), h),
                None => {
                    let w = w.unwrap_or(dw);
                    (w, derive(w as f64 / a.get()))
                }
            }
        }
    };
    Ok(RenderDefaults {
        width,
        height,
        spp: r.spp.unwrap_or(RenderSection::DEFAULT_SPP),
        max_depth: r.max_depth.unwrap_or(RenderSection::DEFAULT_MAX_DEPTH),
        rr_depth: r.rr_depth,
        strategy: r.strategy.map(|s| s.0),
        sampler: r.sampler.map(|s| s.0),
        seed: r.seed,
        filter: r.filter.map(|f| pixel_filter(&f)).transpose().map_err(|e| src.error_at(&at("filter"), e))?,
        light_selection: r.light_selection.map(|s| s.0),
    })
}

/// The RGB (η, k) of a conductor definition.
fn metal_optics(m: MetalDef) -> (Rgb, Rgb) {
    match m {
        // Names were checked against the same table when the file was read.
        MetalDef::Named(name) => {
            let (eta, k) = metal(name.0).unwrap_or(([0.0; 3], [1.0; 3]));
            (Rgb::from_array(eta), Rgb::from_array(k))
        }
        MetalDef::Custom { eta, k } => (eta.rgb(), k.rgb()),
    }
}

fn microfacet(r: RoughnessDef) -> Microfacet {
    Microfacet::new(r.distribution, r.alpha_u.f32(), r.alpha_v.f32())
}

/// Plastics precompute tables from their parameters: check those first.
fn check_coating(albedo: Rgb, specular: Rgb, ior: f32) -> Result<(), String> {
    let unit = |c: Rgb| c.is_finite() && c.r >= 0.0 && c.g >= 0.0 && c.b >= 0.0 && c.max_component() <= 1.0;
    if !unit(albedo) || !unit(specular) {
        return Err("plastic `albedo` and `specular` must be in [0, 1]".into());
    }
    if !pathtrace::scene::IOR_RANGE.contains(&ior) {
        // The same check as the engine's validation, made before the coating's tables are built.
        let range = &pathtrace::scene::IOR_RANGE;
        return Err(format!("plastic ior {ior} must be from {} to {}", range.start(), range.end()));
    }
    Ok(())
}

/// The engine's filter for a `filter` table, with Mitsuba's defaults for missing parameters.
pub fn pixel_filter(f: &FilterDef) -> Result<PixelFilter, String> {
    match (f.kind, f.radius, f.stddev) {
        (FilterName::Gaussian, Some(_), _) => Err("a gaussian filter takes `stddev`, not `radius`".into()),
        (FilterName::Box | FilterName::Tent, _, Some(_)) => Err("only the gaussian filter takes `stddev`".into()),
        (FilterName::Box, r, None) => PixelFilter::with_radius("box", r.map_or(0.5, |r| r.f32())),
        (FilterName::Tent, r, None) => {
            PixelFilter::with_radius("tent", r.map_or(PixelFilter::DEFAULT_TENT_RADIUS, |r| r.f32()))
        }
        (FilterName::Gaussian, None, s) => {
            GaussianFilter::new(s.map_or(PixelFilter::DEFAULT_GAUSSIAN_STDDEV, |s| s.f32())).map(PixelFilter::Gaussian)
        }
    }
}

struct Ctx<'a, L: Locate> {
    src: &'a L,
    b: SceneBuilder,
    ids: BTreeMap<String, MaterialId>,
    /// Media by name.
    media: BTreeMap<String, MediumId>,
    materials: &'a BTreeMap<String, MaterialDef>,
    /// The shape group being filled, while one is read: objects go there, not into the scene.
    group: Option<ShapeGroup>,
}

impl<L: Locate> Ctx<'_, L> {
    fn add_material(&mut self, name: &str, def: &MaterialDef) -> Result<MaterialId, SceneError> {
        let at = ItemPath::root().field("materials").field(name);
        // Textured colours enter the material as their mean (Mitsuba's sampling weights use the
        // mean too) and are bound to their slot below.
        let mut bound: Vec<(ColourSlot, Texture)> = Vec::new();
        let mut col = |c: &Colour, slot: ColourSlot, field: &str| -> Result<Rgb, SceneError> {
            match c {
                Colour::Constant(t) => Ok(t.rgb()),
                Colour::Texture(t) => {
                    let tex = self.texture(t, &at.field(field))?;
                    let mean = tex.mean();
                    bound.push((slot, tex));
                    Ok(mean)
                }
            }
        };
        let (base, spec) = (ColourSlot::Base, ColourSlot::Specular);
        let (kind, one_sided) = def.kind.sides();
        let m = match kind {
            MaterialKind::Diffuse { albedo } => Material::Diffuse(Diffuse { albedo: col(albedo, base, "albedo")? }),
            MaterialKind::Lambertian { albedo } => {
                Material::Lambertian(Lambertian { albedo: col(albedo, base, "albedo")? })
            }
            MaterialKind::Mirror { reflectance } => {
                Material::Mirror(Mirror { reflectance: col(reflectance, base, "reflectance")? })
            }
            MaterialKind::Glossy { albedo, exponent } => {
                Material::Glossy(Glossy { albedo: col(albedo, base, "albedo")?, exponent: exponent.f32() })
            }
            MaterialKind::Dielectric { ior, tint } => {
                Material::Dielectric(Dielectric { ior: ior.f32(), tint: col(tint, base, "tint")? })
            }
            MaterialKind::ThinDielectric { ior, tint } => {
                Material::ThinDielectric(ThinDielectric { ior: ior.f32(), tint: col(tint, base, "tint")? })
            }
            MaterialKind::Emissive => Material::Black,
            MaterialKind::Null => Material::Null,
            MaterialKind::Conductor { metal, reflectance } => {
                let (eta, k) = metal_optics(*metal);
                Material::Conductor(Conductor { eta, k, reflectance: col(reflectance, base, "reflectance")? })
            }
            MaterialKind::RoughConductor { metal, reflectance, roughness } => {
                let (eta, k) = metal_optics(*metal);
                let distribution = microfacet(*roughness);
                let reflectance = col(reflectance, base, "reflectance")?;
                Material::RoughConductor(RoughConductor { distribution, eta, k, reflectance })
            }
            MaterialKind::RoughDielectric { ior, tint, roughness } => Material::RoughDielectric(RoughDielectric {
                distribution: microfacet(*roughness),
                ior: ior.f32(),
                tint: col(tint, base, "tint")?,
            }),
            MaterialKind::Plastic { albedo, specular, ior, nonlinear } => {
                let (albedo, specular) = (col(albedo, base, "albedo")?, col(specular, spec, "specular")?);
                check_coating(albedo, specular, ior.f32())
                    .map_err(|e| self.src.error_at(&at, format!("material `{name}`: {e}")))?;
                Material::Plastic(Plastic::new(albedo, specular, ior.f32(), *nonlinear))
            }
            MaterialKind::RoughPlastic { albedo, specular, ior, nonlinear, roughness } => {
                let (albedo, specular) = (col(albedo, base, "albedo")?, col(specular, spec, "specular")?);
                check_coating(albedo, specular, ior.f32())
                    .map_err(|e| self.src.error_at(&at, format!("material `{name}`: {e}")))?;
                let distribution = microfacet(*roughness);
                Material::RoughPlastic(RoughPlastic::new(distribution, albedo, specular, ior.f32(), *nonlinear))
            }
            MaterialKind::OneSided(_) => {
                return Err(self.src.error_at(&at, format!("material `{name}`: `one_sided` is given twice")));
            }
            MaterialKind::Blend { weight, bsdfs } => {
                let mut ids = [0; 2];
                for (k, model) in bsdfs.iter().enumerate() {
                    let bad = |why: &str| {
                        self.src
                            .error_at(&at.field("bsdfs"), format!("material `{name}`: blend model {k} `{model}` {why}"))
                    };
                    let def = self.materials.get(model).ok_or_else(|| {
                        let known: Vec<&str> = self.materials.keys().map(String::as_str).collect();
                        bad(&format!("is not a material of this file (materials: {})", known.join(", ")))
                    })?;
                    if def.kind.sides().1 {
                        return Err(bad("is `one_sided`: give `one_sided` to the blend instead"));
                    }
                    if def.normal.is_some() || def.opacity.is_some() {
                        return Err(bad("has a normal map or opacity: give those to the blend instead"));
                    }
                    let accepted = matches!(
                        def.kind,
                        MaterialKind::Diffuse { .. }
                            | MaterialKind::Lambertian { .. }
                            | MaterialKind::Glossy { .. }
                            | MaterialKind::RoughConductor { .. }
                            | MaterialKind::RoughPlastic { .. }
                    );
                    if !accepted {
                        return Err(bad(
                            "cannot be blended: a blend mixes opaque models without mirror-like lobes (diffuse, \
                             lambertian, glossy, rough_conductor, rough_plastic)",
                        ));
                    }
                    ids[k] = self.material_id(model, &at.field("bsdfs"))?.0;
                }
                // The luminance of a grey w can round a hair past 1 (its weights sum to 1 in f32
                // only approximately); the file's range was checked when it was read.
                let weight = col(weight, base, "weight")?.luminance().clamp(0.0, 1.0);
                Material::Blend(Blend { weight, bsdfs: ids })
            }
        };
        validate_material(&m).map_err(|e| self.src.error_at(&at, format!("material `{name}`: {e}")))?;
        let id = match &def.emission {
            None => self.b.material(m),
            Some(e) => {
                let radiance = e.radiance.rgb();
                if radiance.r < 0.0 || radiance.g < 0.0 || radiance.b < 0.0 {
                    return Err(self.src.error_at(&at, format!("material `{name}`: emitted radiance must be ≥ 0")));
                }
                let id = self.b.material_with_emission(m, Emission { radiance, two_sided: e.two_sided });
                if let Some(Colour::Texture(t)) = &e.texture {
                    let texture = self.texture(t, &at.field("emission_texture"))?;
                    let t = self.b.texture(texture);
                    self.b
                        .set_emission_texture(id, t)
                        .map_err(|e| self.src.error_at(&at, format!("material `{name}`: {e}")))?;
                }
                id
            }
        };
        if one_sided {
            self.b.set_one_sided(id).map_err(|e| self.src.error_at(&at, format!("material `{name}`: {e}")))?;
        }
        for (slot, tex) in bound {
            let t = self.b.texture(tex);
            self.b.bind_texture(id, slot, t).map_err(|e| self.src.error_at(&at, format!("material `{name}`: {e}")))?;
        }
        if let Some(n) = &def.normal {
            self.add_normal_perturbation(id, name, n, &at)?;
        }
        if let Some(c) = &def.roughness {
            let texture = match c {
                Colour::Constant(t) => Texture::Constant(t.rgb()),
                Colour::Texture(t) => self.texture(t, &at.field("alpha_texture"))?,
            };
            let t = self.b.texture(texture);
            self.b
                .bind_texture(id, ColourSlot::Roughness, t)
                .map_err(|e| self.src.error_at(&at, format!("material `{name}`: {e}")))?;
        }
        if let Some(o) = &def.opacity {
            let texture = match &o.texture {
                Colour::Constant(t) => Texture::Constant(t.rgb()),
                Colour::Texture(t) => self.texture(t, &at.field("opacity"))?,
            };
            let opacity = Opacity { texture: self.b.texture(texture), cutoff: o.cutoff.map(Num::f32) };
            self.b.set_opacity(id, opacity).map_err(|e| self.src.error_at(&at, format!("material `{name}`: {e}")))?;
        }
        Ok(id)
    }

    /// Binds a material's normal or bump map. A normal map's texels are directions, not
    /// colours: its bitmap is read raw whatever `raw` says.
    fn add_normal_perturbation(
        &mut self,
        id: MaterialId,
        name: &str,
        n: &NormalPerturbationDef,
        at: &ItemPath,
    ) -> Result<(), SceneError> {
        let texture = |ctx: &Self, c: &Colour, field: &str, force_raw: bool| -> Result<Texture, SceneError> {
            match c {
                Colour::Constant(t) => Ok(Texture::Constant(t.rgb())),
                Colour::Texture(t @ TextureDef::Bitmap { .. }) if force_raw => {
                    let mut raw = t.clone();
                    if let TextureDef::Bitmap { raw: r, .. } = &mut raw {
                        *r = true;
                    }
                    ctx.texture(&raw, &at.field(field))
                }
                Colour::Texture(t) => ctx.texture(t, &at.field(field)),
            }
        };
        let kind = match &n.map {
            NormalDef::Map { texture: c, strength } => {
                let t = texture(self, c, "normal_map", true)?;
                PerturbationKind::NormalMap { texture: self.b.texture(t), strength: strength.f32() }
            }
            NormalDef::Bump { height, scale } => {
                let t = texture(self, height, "bump_map", false)?;
                PerturbationKind::BumpMap { texture: self.b.texture(t), scale: scale.f32() }
            }
        };
        self.b
            .perturb_normal(id, NormalPerturbation { kind, shadowing: n.shadowing })
            .map_err(|e| self.src.error_at(at, format!("material `{name}`: {e}")))
    }

    /// The engine texture a definition describes; a bitmap's file is read relative to the scene
    /// file (8-bit sRGB decoded unless `raw`, float formats linear).
    fn texture(&self, t: &TextureDef, at: &ItemPath) -> Result<Texture, SceneError> {
        let uv = |rows: &UvRows| UvTransform::from_rows(rows.map(|r| r.map(Num::f32)));
        match t {
            TextureDef::Checkerboard { color0, color1, to_uv } => {
                Ok(Texture::Checkerboard(Checkerboard { color0: color0.rgb(), color1: color1.rgb(), to_uv: uv(to_uv) }))
            }
            TextureDef::Bitmap { filename, raw, nearest, clamp, to_uv, alpha, factor } => {
                let mut image = self.texture_image(filename, *raw, *alpha, at)?;
                // glTF 2.0 §3.9.2: base colour = factor × texture (sRGB-decoded), alpha = factor ×
                // texture alpha. Bilinear and nearest lookups are linear in the texels, so scaling
                // every decoded texel once here equals scaling each filtered value.
                if *factor != Triple::ONE {
                    let f = factor.rgb();
                    image.pixels.iter_mut().for_each(|p| *p *= f);
                }
                let mut b = Bitmap::new(image.width, image.height, image.pixels).ok_or_else(|| {
                    self.src.error_at(at, format!("texture `{filename}` has negative or non-finite texels"))
                })?;
                b.filter = if *nearest { FilterType::Nearest } else { FilterType::Bilinear };
                b.wrap = if *clamp { WrapMode::Clamp } else { WrapMode::Repeat };
                b.to_uv = uv(to_uv);
                Ok(Texture::Bitmap(b))
            }
            TextureDef::Channel { filename, channel, factor, squared, nearest, clamp, to_uv } => {
                let image = self.texture_image(filename, true, false, at)?;
                // Scaling a channel commutes with the bilinear blend: done once per texel here.
                let grey = |c: Rgb| Rgb::splat(c.to_array()[(*channel).min(2) as usize] * factor.f32());
                let texels = image.pixels.into_iter().map(grey).collect();
                let mut b = Bitmap::new(image.width, image.height, texels).ok_or_else(|| {
                    self.src.error_at(at, format!("texture `{filename}` has negative or non-finite texels"))
                })?;
                b.filter = if *nearest { FilterType::Nearest } else { FilterType::Bilinear };
                b.wrap = if *clamp { WrapMode::Clamp } else { WrapMode::Repeat };
                b.to_uv = uv(to_uv);
                Ok(if *squared { Texture::Squared(b) } else { Texture::Bitmap(b) })
            }
        }
    }

    /// The texels of a texture's image: a file relative to the scene file (8-bit sRGB decoded
    /// unless `raw`, float formats linear; with `alpha`, the alpha channel), or an image inside a
    /// glTF file (`scene.glb#images[N]`, see [`crate::gltf::images`]).
    fn texture_image(&self, filename: &str, raw: bool, alpha: bool, at: &ItemPath) -> Result<Image, SceneError> {
        let dir = self.src.path().parent().unwrap_or(std::path::Path::new(""));
        let fail = |e: String| self.src.error_at(at, format!("cannot load texture: {e}"));
        if let Some((file, index)) = crate::gltf::images::split_reference(filename) {
            let gltf = dir.join(file);
            let (bytes, format) = crate::gltf::images::image_bytes(&gltf, index).map_err(fail)?;
            let label = std::path::PathBuf::from(filename);
            return crate::image_io::decode_texture(&bytes, &label, format, raw, alpha)
                .map_err(|e| fail(e.to_string()));
        }
        let path = dir.join(filename);
        if alpha { crate::image_io::read_texture_alpha(&path) } else { crate::image_io::read_texture(&path, raw) }
            .map_err(|e| fail(e.to_string()))
    }

    fn add_light(&mut self, l: &LightDef, at: &ItemPath) -> Result<(), SceneError> {
        let result = match l {
            LightDef::Point { position, intensity } => {
                self.b.point_light(PointLight { position: vec3(position), intensity: intensity.rgb() })
            }
            LightDef::Spot { intensity, cutoff_angle, beam_width, transform } => {
                let to_world = self.transform(transform, at)?;
                let cutoff = cutoff_angle.map_or(20.0, Num::f32);
                let beam = beam_width.map_or(SpotLight::default_beam_width(cutoff), Num::f32);
                let spot = SpotLight::new(&to_world, intensity.rgb(), cutoff, beam).ok_or_else(|| {
                    self.src.error_at(
                        at,
                        "a spot light needs an intensity ≥ 0 and 0 < beam_width ≤ cutoff_angle ≤ 180 (degrees)",
                    )
                })?;
                self.b.spot_light(spot);
                Ok(())
            }
            LightDef::Directional { irradiance, direction, transform } => {
                if direction.is_some() && !transform.is_empty() {
                    return Err(self
                        .src
                        .error_at(at, "a directional light takes `direction` or `transform`, not both"));
                }
                let light = match direction {
                    Some(d) => DirectionalLight::new(vec3(d), irradiance.rgb()),
                    None => DirectionalLight::from_transform(&self.transform(transform, at)?, irradiance.rgb()),
                };
                let light = light.ok_or_else(|| {
                    self.src.error_at(at, "a directional light needs an irradiance ≥ 0 and a non-zero direction")
                })?;
                self.b.directional_light(light);
                Ok(())
            }
            LightDef::Constant { radiance } => self.b.environment(EnvironmentLight::constant(radiance.rgb())),
            LightDef::Envmap { filename, scale, transform } => {
                let map = self.env_map(filename, scale.map_or(1.0, Num::f32), transform, at)?;
                self.b.environment(EnvironmentLight::map(map))
            }
        };
        result.map_err(|e| self.src.error_at(at, e.to_string()))
    }

    /// Reads an environment map's image (relative to the scene file) and builds its sampler.
    fn env_map(
        &self,
        file: &str,
        scale: f32,
        steps: &[super::model::TransformStep],
        at: &ItemPath,
    ) -> Result<EnvMap, SceneError> {
        let to_world = self.transform(steps, at)?;
        let dir = self.src.path().parent().unwrap_or(std::path::Path::new(""));
        // Any image a texture may be: PNG and JPEG are sRGB-decoded to linear radiance.
        let image = crate::image_io::read_texture(&dir.join(file), false)
            .map_err(|e| self.src.error_at(&at.field("filename"), format!("cannot load environment map: {e}")))?;
        EnvMap::new(image.width, image.height, image.pixels, scale, to_world).map_err(|e| self.src.error_at(at, e))
    }

    fn add_group(&mut self, g: &GroupDef, outer: &Transform, at: &ItemPath) -> Result<(), SceneError> {
        let t = self.transform(&g.transform, at)?.then(outer);
        for (i, o) in g.objects.iter().enumerate() {
            self.add_object(o, &t, &at.field("objects").index(i))?;
        }
        for (i, inner) in g.groups.iter().enumerate() {
            self.add_group(inner, &t, &at.field("groups").index(i))?;
        }
        Ok(())
    }

    /// Reads `[shape_groups.NAME]` (its objects and nested groups, under its own transform)
    /// into a shape group of the builder.
    fn add_shape_group(&mut self, name: &str, g: &GroupDef) -> Result<GroupId, SceneError> {
        let at = ItemPath::root().field("shape_groups").field(name);
        self.group = Some(ShapeGroup::new());
        let filled = self.add_group(g, &Transform::IDENTITY, &at);
        let group = self.group.take().unwrap_or_default();
        filled?;
        if group.is_empty() {
            return Err(self.src.error_at(&at, format!("shape group `{name}` holds no objects")));
        }
        self.b.group(group).map_err(|e| self.src.error_at(&at, e.to_string()))
    }

    /// Places a shape group (`[[instances]]`).
    fn add_instance(
        &mut self,
        inst: &InstanceDef,
        groups: &BTreeMap<&str, GroupId>,
        at: &ItemPath,
    ) -> Result<(), SceneError> {
        let Some(&group) = groups.get(inst.group.as_str()) else {
            let known: Vec<&str> = groups.keys().copied().collect();
            let known = if known.is_empty() { "none are defined".to_string() } else { known.join(", ") };
            let msg = format!("unknown shape group `{}` (shape groups: {known})", inst.group);
            return Err(self.src.error_at(&at.field("group"), msg));
        };
        let t = self.transform(&inst.transform, at)?;
        let material = match &inst.material {
            None => None,
            Some(name) => {
                let id = self.material_id(name, &at.field("material"))?;
                if self.emits(name) {
                    let msg = format!("material `{name}` emits: instanced shapes cannot be lights");
                    return Err(self.src.error_at(&at.field("material"), msg));
                }
                Some(id)
            }
        };
        self.b.instance(group, &t, material).map_err(|e| self.src.error_at(at, e.to_string()))
    }

    fn material_id(&self, name: &str, at: &ItemPath) -> Result<MaterialId, SceneError> {
        self.ids.get(name).copied().ok_or_else(|| {
            let known: Vec<&str> = self.ids.keys().map(String::as_str).collect();
            let known = if known.is_empty() { "none are defined".to_string() } else { known.join(", ") };
            self.src.error_at(at, format!("unknown material `{name}` (materials: {known})"))
        })
    }

    fn emits(&self, material: &str) -> bool {
        self.materials.get(material).and_then(|m| m.emission.as_ref()).is_some_and(|e| !e.radiance.rgb().is_black())
    }

    /// Adds a shape to the scene, or to the shape group being read.
    fn put_shape(&mut self, shape: Shape, id: MaterialId, t: &Transform) -> Result<(), BuildError> {
        match &mut self.group {
            Some(g) => g.shape(shape, id, t),
            None => self.b.shape(shape, id, t),
        }
    }

    fn put_box(&mut self, min: Vec3, max: Vec3, id: MaterialId, t: &Transform) -> Result<(), BuildError> {
        match &mut self.group {
            Some(g) => g.add_box(min, max, id, t),
            None => self.b.add_box(min, max, id, t),
        }
    }

    fn put_mesh(&mut self, mesh: &TriangleMesh, id: MaterialId, t: &Transform) -> Result<usize, BuildError> {
        match &mut self.group {
            Some(g) => g.mesh(mesh, id, t),
            None => self.b.mesh(mesh, id, t),
        }
    }

    fn transform(&self, steps: &[super::model::TransformStep], at: &ItemPath) -> Result<Transform, SceneError> {
        compose(steps).map_err(|(i, e)| self.src.error_at(&at.field("transform").index(i), e))
    }

    fn medium_id(&self, name: &str, at: &ItemPath) -> Result<MediumId, SceneError> {
        self.media.get(name).copied().ok_or_else(|| {
            let known: Vec<&str> = self.media.keys().map(String::as_str).collect();
            let known =
                if known.is_empty() { "none are defined: add a [media.NAME]".to_string() } else { known.join(", ") };
            self.src.error_at(at, format!("unknown medium `{name}` (media: {known})"))
        })
    }

    /// The material id for an object: its material, with the media it bounds attached.
    fn object_material(&mut self, o: &ObjectDef, at: &ItemPath) -> Result<MaterialId, SceneError> {
        let id = self.material_id(&o.material, &at.field("material"))?;
        if o.interior.is_none() && o.exterior.is_none() {
            return Ok(id);
        }
        let side = if o.interior.is_some() { "interior" } else { "exterior" };
        if self.group.is_some() {
            let msg = "objects of a shape group cannot bound media (place the object outside the group)";
            return Err(self.src.error_at(&at.field(side), msg));
        }
        let lookup = |name: &Option<String>, field: &str| {
            name.as_deref().map(|n| self.medium_id(n, &at.field(field))).transpose()
        };
        let (interior, exterior) = (lookup(&o.interior, "interior")?, lookup(&o.exterior, "exterior")?);
        self.b.bounded_material(id, interior, exterior).map_err(|e| self.src.error_at(&at.field(side), e.to_string()))
    }

    fn add_object(&mut self, o: &ObjectDef, outer: &Transform, at: &ItemPath) -> Result<(), SceneError> {
        let t = self.transform(&o.transform, at)?.then(outer);
        let id = self.object_material(o, at)?;
        let emits = self.emits(&o.material);
        if emits && self.group.is_some() {
            let msg = format!("material `{}` emits: objects of a shape group cannot be lights", o.material);
            return Err(self.src.error_at(&at.field("material"), msg));
        }
        let err = |e: &dyn std::fmt::Display| self.src.error_at(at, e.to_string());
        let degenerate = |what: &str| self.src.error_at(at, format!("degenerate {what}"));
        let shape = match &o.shape {
            ShapeDef::Sphere { center, radius } => {
                if emits && t.uniform_scale().is_none() {
                    return Err(err(&BuildError::EmissiveEllipsoid));
                }
                let sphere = Sphere::new(vec3(center), radius.f32())
                    .ok_or_else(|| degenerate("sphere: the radius must be positive"))?;
                Shape::Sphere(Sphere { inward: o.flip_normals, ..sphere })
            }
            ShapeDef::Plane { point, normal } => {
                if emits {
                    return Err(err(&BuildError::EmissivePlane));
                }
                let normal = if o.flip_normals { -vec3(normal) } else { vec3(normal) };
                Shape::Plane(Plane::new(vec3(point), normal).ok_or_else(|| degenerate("plane: zero normal"))?)
            }
            ShapeDef::Quad { q, u, v } => {
                // Turned over as the same parallelogram from the opposite corner along v
                // (q + v, u, −v): its v coordinate then runs the other way.
                let (q, u, v) = (vec3(q), vec3(u), vec3(v));
                let (q, v) = if o.flip_normals { (q + v, -v) } else { (q, v) };
                Shape::Quad(Quad::new(q, u, v).ok_or_else(|| {
                    if u.cross(v).is_finite() {
                        degenerate("quad: u and v must span an area")
                    } else {
                        degenerate("quad: its area |u × v| overflows single precision (3.4e38)")
                    }
                })?)
            }
            ShapeDef::Disk { center, normal, radius } => {
                let normal = if o.flip_normals { -vec3(normal) } else { vec3(normal) };
                Shape::Disk(
                    Disk::round(vec3(center), normal, radius.f32())
                        .ok_or_else(|| degenerate("disk: the radius must be positive and the normal non-zero"))?,
                )
            }
            ShapeDef::Triangle { a, b, c } => {
                // Turned over by its winding (the front is along (b − a) × (c − a)).
                let (b, c) = if o.flip_normals { (c, b) } else { (b, c) };
                Shape::Triangle(Triangle::new(vec3(a), vec3(b), vec3(c), Triangle::FLAT).ok_or_else(|| {
                    if (vec3(b) - vec3(a)).cross(vec3(c) - vec3(a)).is_finite() {
                        degenerate("triangle: its corners are on one line")
                    } else {
                        degenerate("triangle: its area overflows single precision (3.4e38)")
                    }
                })?)
            }
            ShapeDef::Box { .. } if o.flip_normals => {
                let msg = "`flip_normals` is not supported on a box (use six quads, or a mesh)";
                return Err(self.src.error_at(&at.field("flip_normals"), msg));
            }
            ShapeDef::Box { min, max } => {
                return self.put_box(vec3(min), vec3(max), id, &t).map_err(|_| {
                    degenerate("box: `max` must exceed `min` on every axis and the transform keep it solid")
                });
            }
            ShapeDef::Mesh { file, part, flip_v, normals } => {
                return self.add_mesh(file, *part, (*flip_v, *normals, o.flip_normals), id, &t, at)
            }
        };
        self.put_shape(shape, id, &t).map_err(|e| err(&e))
    }

    fn add_mesh(
        &mut self,
        file: &str,
        part: Option<u32>,
        (flip_v, normals, flip_normals): (bool, MeshNormals, bool),
        id: MaterialId,
        t: &Transform,
        object: &ItemPath,
    ) -> Result<(), SceneError> {
        let at = &object.field("file");
        let dir = self.src.path().parent().unwrap_or(std::path::Path::new(""));
        let path = dir.join(file);
        // The mesh error already names its file (and line or byte offset there).
        let meshes =
            crate::mesh::load_mesh(&path).map_err(|e| self.src.error_at(at, format!("cannot load mesh: {e}")))?;
        let n = meshes.len();
        let chosen = match part {
            None => &meshes[..],
            Some(i) => meshes.get(i as usize..i as usize + 1).ok_or_else(|| {
                self.src.error_at(&object.field("part"), format!("part {i} does not exist: `{file}` has {n} part(s)"))
            })?,
        };
        let (mut triangles, mut skipped) = (0, 0);
        for (_, mesh) in chosen {
            triangles += mesh.indices.len();
            let changed;
            let flip = flip_v && mesh.uvs.is_some();
            let recompute = match normals {
                MeshNormals::Smooth => mesh.normals.is_none(),
                MeshNormals::Computed => true,
                MeshNormals::Face => mesh.normals.is_some(),
                MeshNormals::File => false,
            };
            let mesh = if flip || recompute || flip_normals {
                let mut m = mesh.clone();
                if let (Some(uvs), true) = (&mut m.uvs, flip) {
                    uvs.iter_mut().for_each(|uv| uv.y = 1.0 - uv.y);
                }
                // Before smooth normals are computed: they follow the reversed winding.
                if flip_normals {
                    m.flip_normals();
                }
                if recompute {
                    m.normals = (normals != MeshNormals::Face).then(|| m.smooth_normals(t));
                }
                changed = m;
                &changed
            } else {
                mesh
            };
            skipped += self
                .put_mesh(mesh, id, t)
                .map_err(|e| self.src.error_at(at, format!("mesh `{}`: {e}", path.display())))?;
        }
        // A mesh that adds nothing is a mistake to report here, not an object silently missing
        // (or, when it was the only one, "the scene has no objects" at 1:1).
        if skipped == triangles {
            let why = if triangles == 0 {
                "has no triangles".to_owned()
            } else {
                format!(
                    "has no usable triangles: all {triangles} are degenerate (zero area, or beyond single precision)"
                )
            };
            return Err(self.src.error_at(at, format!("mesh `{file}` {why}")));
        }
        Ok(())
    }
}
