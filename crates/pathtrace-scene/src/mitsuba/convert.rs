//! The element tree → a native [`SceneFile`]. What the native model cannot express is replaced by
//! the nearest thing it can, and each replacement is named in a warning.

use super::parse::{Element, XmlSource};
use super::spectrum::{check_samples, constant_to_rgb, parse_spd, spectrum_to_rgb, SpectrumUse};
use crate::native::model::{
    CameraSection, Colour, EmissionDef, FilterDef, FilterName, GroupDef, InstanceDef, LightDef, LightSelectionName,
    LookAtDef, MaterialDef, MaterialKind, MediumDef, MeshNormals, Num, Num3, ObjectDef, ProjectionName, RenderSection,
    SamplerName, SceneFile, ShapeDef, TransformStep, Triple,
};
use crate::native::{ItemPath, SceneError};
use pathtrace::light::LightSelection;
use pathtrace::math::{Transform, Vec3};
use pathtrace::sampling::SamplerKind;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

mod blend;
mod bsdf;
mod instance;
mod medium;
mod wrappers;

use wrappers::Wrappers;
mod texture;

type R<T> = Result<T, SceneError>;

/// Mitsuba 3's default `rr_depth` for its path tracers (`MonteCarloIntegrator`).
const MITSUBA_RR_DEPTH: u32 = 5;

/// Where each item of the converted model came from: (item, byte offset in the XML), so errors
/// found while building point at the element that caused them.
pub type Origins = Vec<(ItemPath, usize)>;

/// Converts a parsed `<scene>`; warnings are appended to `warnings`.
pub fn convert(src: &XmlSource, root: &Element, warnings: &mut Vec<String>) -> R<SceneFile> {
    convert_located(src, root, warnings).map(|(file, _)| file)
}

/// [`convert`], also returning where each object, material, light and setting came from.
pub fn convert_located(src: &XmlSource, root: &Element, warnings: &mut Vec<String>) -> R<(SceneFile, Origins)> {
    let mut c = Conv {
        src,
        warnings,
        ids: BTreeMap::new(),
        search: Vec::new(),
        materials: BTreeMap::new(),
        bsdf_names: BTreeMap::new(),
        objects: Vec::new(),
        objects_at: ItemPath::root().field("objects"),
        shape_groups: BTreeMap::new(),
        instances: Vec::new(),
        lights: Vec::new(),
        media: BTreeMap::new(),
        medium_names: BTreeMap::new(),
        origins: vec![(ItemPath::root(), root.offset)],
    };
    collect_ids(root, &mut c.ids);
    let dir = src.path.parent().map(Path::to_path_buf).unwrap_or_default();
    c.search.push(dir.clone());
    let mut render = RenderSection::default();
    let mut camera = None;
    let mut integrator_seen = false;
    for e in &root.children {
        match e.tag.as_str() {
            "default" => {}
            "path" => {
                let v = c.req_attr(e, "value")?;
                let p = dir.join(v);
                if !p.is_dir() {
                    return Err(src.error(e.offset_of("value"), format!("<path>: folder `{}` not found", p.display())));
                }
                c.search.push(p);
            }
            "integrator" => {
                integrator_seen = true;
                c.integrator(e, &mut render)?;
            }
            "sensor" => {
                if camera.is_some() {
                    c.warn(e, "only the first <sensor> is used");
                } else {
                    let mut sensor = c.sensor(e, &mut render)?;
                    sensor.medium = c.sensor_medium(e)?;
                    camera = Some(sensor);
                    c.origins.push((ItemPath::root().field("camera"), e.offset));
                    c.origins.push((ItemPath::root().field("render"), e.offset));
                }
            }
            "bsdf" | "texture" | "spectrum" | "rgb" | "medium" => {} // used through <ref>
            // A sensor's parts, used through <ref> (unreferenced, Mitsuba ignores them too).
            "sampler" | "film" | "rfilter" if e.attr("id").is_some() => {}
            "shape" => c.shape(e)?,
            "emitter" => c.top_emitter(e)?,
            other => c.warn(e, &format!("<{other}> is not supported and is skipped")),
        }
    }
    if !integrator_seen {
        render.max_depth = Some(-1);
    }
    // Mitsuba picks emitters in proportion to their `sampling_weight`, 1 unless given: uniformly
    // (a whole emissive mesh counting as one). The same rule renders its scenes with its noise;
    // power selection starves the small lights of scenes such as Veach's MIS test (5.5× the
    // relative MSE of Mitsuba at equal samples: docs/benchmarks.md).
    render.light_selection = Some(LightSelectionName(LightSelection::Uniform));
    c.warn_sampling_weights(root);
    let Some(camera) = camera else {
        return Err(src.error(root.offset, "the scene has no <sensor>: a perspective sensor is required"));
    };
    let file = SceneFile {
        render,
        camera,
        materials: c.materials,
        media: c.media,
        objects: c.objects,
        groups: Vec::new(),
        shape_groups: c.shape_groups,
        instances: c.instances,
        lights: c.lights,
    };
    Ok((file, c.origins))
}

fn collect_ids<'a>(e: &'a Element, ids: &mut BTreeMap<String, &'a Element>) {
    if e.tag != "ref" {
        if let Some(id) = e.attr("id") {
            ids.entry(id.to_string()).or_insert(e);
        }
    }
    for c in &e.children {
        collect_ids(c, ids);
    }
}

struct Conv<'a, 'w> {
    src: &'a XmlSource,
    warnings: &'w mut Vec<String>,
    ids: BTreeMap<String, &'a Element>,
    search: Vec<PathBuf>,
    materials: BTreeMap<String, MaterialDef>,
    /// Material names already made for `<bsdf id>` elements (by offset).
    bsdf_names: BTreeMap<usize, String>,
    objects: Vec<ObjectDef>,
    /// Where `objects` will sit in the model (the top level, or a shape group's objects).
    objects_at: ItemPath,
    /// `<shape type="shapegroup">` by id, and `<shape type="instance">` placements.
    shape_groups: BTreeMap<String, GroupDef>,
    instances: Vec<InstanceDef>,
    /// Point lights and the environment.
    lights: Vec<LightDef>,
    /// Participating media, and the names made for `<medium>` elements (by offset).
    media: BTreeMap<String, MediumDef>,
    medium_names: BTreeMap<usize, String>,
    origins: Origins,
}

fn num(x: f64) -> Num {
    Num::new(x).unwrap_or(Num::from(0.0))
}

/// A colour as a native triple (one number when the channels are equal).
fn rgb_triple(c: [f64; 3]) -> Triple {
    if c[0] == c[1] && c[1] == c[2] {
        Triple::Splat(num(c[0]))
    } else {
        Triple::Each(c.map(num))
    }
}

fn n3(v: Vec3) -> Num3 {
    [num(v.x as f64), num(v.y as f64), num(v.z as f64)]
}

/// An IOR by Mitsuba's name (the engine's table holds Mitsuba's values).
fn named_ior(name: &str) -> Option<f64> {
    pathtrace::material::named_ior(name).map(f64::from)
}

/// Splits a list of numbers separated by commas and/or whitespace.
fn split_numbers(s: &str) -> impl Iterator<Item = &str> {
    s.split(|c: char| c == ',' || c.is_whitespace()).filter(|t| !t.is_empty())
}

impl<'a> Conv<'a, '_> {
    fn warn(&mut self, e: &Element, msg: &str) {
        let at = self.src.location(e.offset);
        self.warnings.push(format!("{at}: {msg}"));
    }

    fn req_attr<'e>(&self, e: &'e Element, name: &str) -> R<&'e str> {
        e.attr(name).ok_or_else(|| self.src.error(e.offset, format!("<{}> needs a `{name}` attribute", e.tag)))
    }

    fn number(&self, e: &Element, attr: &str, text: &str) -> R<f64> {
        let x: f64 = text.trim().parse().map_err(|_| {
            self.src.error(e.offset_of(attr), format!("`{text}` is not a number (in `{attr}` of <{}>)", e.tag))
        })?;
        Num::new(x).map(Num::get).ok_or_else(|| {
            self.src
                .error(e.offset_of(attr), format!("{text} is not allowed: numbers must be finite and within ±3.4e38"))
        })
    }

    fn numbers(&self, e: &Element, attr: &str) -> R<Vec<f64>> {
        let text = self.req_attr(e, attr)?;
        split_numbers(text).map(|t| self.number(e, attr, t)).collect()
    }

    /// A 3-vector from `value="x y z"` / `value="x, y, z"` or `x`/`y`/`z` attributes (missing ones
    /// are `default`).
    fn vec3_of(&self, e: &Element, attr: &str, default: f64) -> R<Vec3> {
        if e.attr(attr).is_some() {
            let v = self.numbers(e, attr)?;
            return match v.as_slice() {
                [s] => Ok(Vec3::splat(*s as f32)),
                [x, y, z] => Ok(Vec3::new(*x as f32, *y as f32, *z as f32)),
                _ => Err(self.src.error(e.offset_of(attr), format!("`{attr}` needs one or three numbers"))),
            };
        }
        let mut out = [default; 3];
        for (i, axis) in ["x", "y", "z"].iter().enumerate() {
            if let Some(t) = e.attr(axis) {
                out[i] = self.number(e, axis, t)?;
            }
        }
        Ok(Vec3::new(out[0] as f32, out[1] as f32, out[2] as f32))
    }

    /// Resolves `<ref id>` children to what they name.
    fn deref(&self, e: &'a Element) -> R<&'a Element> {
        if e.tag != "ref" {
            return Ok(e);
        }
        let id = self.req_attr(e, "id")?;
        self.ids.get(id).copied().ok_or_else(|| self.src.error(e.offset_of("id"), format!("unknown ref id `{id}`")))
    }

    /// The first child of kind `tag` (`film`, `sampler`, `rfilter`), written in place or as a
    /// `<ref id>` to a top-level element of that kind (Mitsuba 3 accepts both).
    fn child_of_kind(&self, e: &'a Element, tag: &str) -> R<Option<&'a Element>> {
        for c in &e.children {
            if c.tag == tag {
                return Ok(Some(c));
            }
            if c.tag == "ref" {
                let target = self.deref(c)?;
                if target.tag == tag {
                    return Ok(Some(target));
                }
            }
        }
        Ok(None)
    }

    /// The child property named `name` (any tag).
    /// Warns about every emitter whose `sampling_weight` is not 1: emitters are picked uniformly.
    fn warn_sampling_weights(&mut self, e: &'a Element) {
        if e.tag == "emitter" {
            if let Some(p) = self.prop(e, "sampling_weight") {
                if self.float(e, "sampling_weight").ok().flatten() != Some(1.0) {
                    self.warn(p, "an emitter's `sampling_weight` is not supported: emitters are picked uniformly");
                }
            }
        }
        for c in &e.children {
            self.warn_sampling_weights(c);
        }
    }

    fn prop(&self, e: &'a Element, name: &str) -> Option<&'a Element> {
        e.children.iter().find(|c| c.attr("name") == Some(name) && c.tag != "ref")
    }

    fn float(&self, e: &'a Element, name: &str) -> R<Option<f64>> {
        let Some(p) = self.prop(e, name) else { return Ok(None) };
        match p.tag.as_str() {
            "float" | "integer" => Ok(Some(self.number(p, "value", self.req_attr(p, "value")?)?)),
            other => Err(self.src.error(p.offset, format!("`{name}` must be a <float> or <integer>, not <{other}>"))),
        }
    }

    fn integer(&self, e: &'a Element, name: &str) -> R<Option<i64>> {
        let Some(p) = self.prop(e, name) else { return Ok(None) };
        let text = self.req_attr(p, "value")?;
        text.trim()
            .parse::<i64>()
            .map(Some)
            .map_err(|_| self.src.error(p.offset_of("value"), format!("`{text}` is not an integer (in `{name}`)")))
    }

    /// [`Self::integer`] within `range`; outside it, an error at the value naming the range (so a
    /// 2^32 sample count is not reported as "must be at least 1" after wrapping).
    fn integer_in(&self, e: &'a Element, name: &str, range: std::ops::RangeInclusive<i64>) -> R<Option<i64>> {
        let Some(n) = self.integer(e, name)? else { return Ok(None) };
        if range.contains(&n) {
            return Ok(Some(n));
        }
        let at = self.prop(e, name).map_or(e.offset, |p| p.offset_of("value"));
        let (lo, hi) = (range.start(), range.end());
        Err(self.src.error(at, format!("`{name}` must be from {lo} to {hi}, got {n}")))
    }

    fn string(&self, e: &'a Element, name: &str) -> R<Option<&'a str>> {
        match self.prop(e, name) {
            None => Ok(None),
            Some(p) => Ok(Some(self.req_attr(p, "value")?)),
        }
    }

    fn boolean(&self, e: &'a Element, name: &str) -> R<Option<bool>> {
        let Some(p) = self.prop(e, name) else { return Ok(None) };
        match self.req_attr(p, "value")?.trim() {
            "true" => Ok(Some(true)),
            "false" => Ok(Some(false)),
            other => Err(self.src.error(p.offset_of("value"), format!("`{other}` is not true or false"))),
        }
    }

    /// A mesh's normals: Mitsuba 3 computes smooth ones for files without normals unless
    /// `face_normals` is true, which also ignores the file's own.
    fn mesh_normals(&self, e: &'a Element) -> R<MeshNormals> {
        let face = self.boolean(e, "face_normals")?.unwrap_or(false);
        Ok(if face { MeshNormals::Face } else { MeshNormals::Smooth })
    }

    /// A colour property: `<rgb>`, `<spectrum>` (approximated when given per wavelength),
    /// `<float>`; a texture or other value gives `None` with a warning.
    fn color(&mut self, e: &'a Element, name: &str) -> R<Option<Triple>> {
        let Some(p) = self.prop(e, name) else {
            // A texture referenced by id: `<ref name="reflectance" id="..."/>`.
            if e.children.iter().any(|c| c.tag == "ref" && c.attr("name") == Some(name)) {
                self.warn(e, &format!("`{name}` is a texture reference: textures are not supported, using 0.5"));
                return Ok(Some(Triple::Splat(num(0.5))));
            }
            return Ok(None);
        };
        match p.tag.as_str() {
            "rgb" | "color" => {
                let v = self.numbers(p, "value")?;
                match v.as_slice() {
                    [s] => Ok(Some(Triple::Splat(num(*s)))),
                    [r, g, b] => Ok(Some(Triple::Each([num(*r), num(*g), num(*b)]))),
                    _ => Err(self.src.error(p.offset_of("value"), "<rgb> needs three numbers (or one)")),
                }
            }
            "float" | "integer" => Ok(Some(Triple::Splat(num(self.number(p, "value", self.req_attr(p, "value")?)?)))),
            "spectrum" => self.spectrum(e, p).map(Some),
            "texture" => {
                self.warn(p, &format!("`{name}`: textures are not supported, using a constant 0.5"));
                Ok(Some(Triple::Splat(num(0.5))))
            }
            other => Err(self.src.error(p.offset, format!("`{name}` must be a colour, not <{other}>"))),
        }
    }

    /// A `<spectrum>`: one constant `value`, `wavelength:value` pairs, or an `.spd` file
    /// (`filename`), converted to linear sRGB as Mitsuba's RGB variants do (see spectrum.rs);
    /// emitters (`<emitter>` parents) are normalised differently from reflectances.
    fn spectrum(&mut self, parent: &Element, p: &Element) -> R<Triple> {
        let usage = if parent.tag == "emitter" { SpectrumUse::Emission } else { SpectrumUse::Reflectance };
        let samples = match (p.attr("value"), p.attr("filename")) {
            (Some(text), _) if !text.contains(':') => {
                let v = self.numbers(p, "value")?;
                return match v.as_slice() {
                    [s] => Ok(rgb_triple(constant_to_rgb(*s, usage))),
                    _ => Err(self
                        .src
                        .error(p.offset_of("value"), "<spectrum> needs one number or wavelength:value pairs")),
                };
            }
            (Some(text), _) => {
                let mut samples = Vec::new();
                for pair in text.split(',').map(str::trim).filter(|t| !t.is_empty()) {
                    let Some((wl, v)) = pair.split_once(':') else {
                        return Err(self.src.error(p.offset_of("value"), format!("`{pair}` is not wavelength:value")));
                    };
                    samples.push((self.number(p, "value", wl)?, self.number(p, "value", v)?));
                }
                samples
            }
            (None, Some(file)) => {
                let at = p.offset_of("filename");
                let path = self
                    .search
                    .iter()
                    .map(|d| d.join(file))
                    .find(|f| f.is_file())
                    .ok_or_else(|| self.src.error(at, format!("spectrum file `{file}` not found")))?;
                let text = std::fs::read_to_string(&path)
                    .map_err(|e| self.src.error(at, format!("cannot read `{}`: {e}", path.display())))?;
                parse_spd(&text)
                    .map_err(|(line, m)| self.src.error(at, format!("`{}` line {line}: {m}", path.display())))?
            }
            (None, None) => return Err(self.src.error(p.offset, "<spectrum> needs a `value` or a `filename`")),
        };
        let at = p.offset_of(if p.attr("value").is_some() { "value" } else { "filename" });
        check_samples(&samples).map_err(|m| self.src.error(at, m))?;
        let converted = spectrum_to_rgb(&samples, usage);
        if converted.clamped {
            self.warn(p, "the spectrum is outside the sRGB gamut: its RGB value is clamped (as Mitsuba does)");
        }
        Ok(rgb_triple(converted.rgb))
    }

    // ---------------------------------------------------------------- transforms

    /// The steps of a `<transform>` in document order (the first acts first).
    fn transform(&self, t: &Element) -> R<Vec<TransformStep>> {
        let mut steps = Vec::new();
        for s in &t.children {
            let step = match s.tag.as_str() {
                "translate" => TransformStep::Translate(n3(self.vec3_of(s, "value", 0.0)?)),
                "scale" => {
                    let v = self.vec3_of(s, "value", 1.0)?;
                    if v.x == v.y && v.y == v.z {
                        TransformStep::Scale(Triple::Splat(num(v.x as f64)))
                    } else {
                        TransformStep::Scale(Triple::Each(n3(v)))
                    }
                }
                "rotate" => {
                    let axis = self.vec3_of(s, "value", 0.0)?;
                    let angle = match s.attr("angle") {
                        Some(a) => self.number(s, "angle", a)?,
                        None => 0.0,
                    };
                    let a = num(angle);
                    let Some(n) = pathtrace::math::normalize_robust(axis) else {
                        return Err(self.src.error(s.offset, "<rotate> needs a non-zero axis"));
                    };
                    if n == Vec3::X {
                        TransformStep::RotateX(a)
                    } else if n == Vec3::Y {
                        TransformStep::RotateY(a)
                    } else if n == Vec3::Z {
                        TransformStep::RotateZ(a)
                    } else {
                        TransformStep::Matrix(rotation_matrix(n, angle))
                    }
                }
                "matrix" => {
                    let v = self.numbers(s, "value")?;
                    let m: [f64; 16] = match v.len() {
                        16 => std::array::from_fn(|i| v[i]),
                        9 => std::array::from_fn(|i| {
                            let (r, c) = (i / 4, i % 4);
                            if r < 3 && c < 3 {
                                v[r * 3 + c]
                            } else if r == c {
                                1.0
                            } else {
                                0.0
                            }
                        }),
                        n => {
                            return Err(self
                                .src
                                .error(s.offset_of("value"), format!("<matrix> needs 16 numbers, not {n}")))
                        }
                    };
                    TransformStep::Matrix(m.map(num))
                }
                "lookat" => {
                    let origin = self.vec3_of(s, "origin", 0.0)?;
                    let target = self.vec3_of(s, "target", 0.0)?;
                    let up = if s.attr("up").is_some() { Some(n3(self.vec3_of(s, "up", 0.0)?)) } else { None };
                    TransformStep::LookAt(LookAtDef { from: n3(origin), to: n3(target), up })
                }
                other => return Err(self.src.error(s.offset, format!("unsupported transform step <{other}>"))),
            };
            step.to_transform().map_err(|e| self.src.error(s.offset, e))?;
            steps.push(step);
        }
        Ok(steps)
    }

    fn to_world(&self, e: &'a Element) -> R<Vec<TransformStep>> {
        match e.children.iter().find(|c| c.tag == "transform" && c.attr("name") == Some("to_world")) {
            Some(t) => self.transform(t),
            None => Ok(Vec::new()),
        }
    }

    // ---------------------------------------------------------------- scene parts

    fn integrator(&mut self, e: &'a Element, render: &mut RenderSection) -> R<()> {
        let ty = self.req_attr(e, "type")?;
        // -1 is unlimited.
        let depth = self.integer_in(e, "max_depth", -1..=i64::from(i32::MAX))?.map(|d| d as i32);
        render.max_depth = Some(match ty {
            // Media are rendered whichever of Mitsuba's path tracers is named (`path` ignores
            // them in Mitsuba; `volpath` and `volpathmis` agree in the mean).
            "path" | "volpath" | "volpathmis" => depth.unwrap_or(-1),
            "direct" => 2,
            other => {
                self.warn(e, &format!("integrator `{other}` is not supported: using a path tracer"));
                depth.unwrap_or(-1)
            }
        });
        // Where Russian roulette starts (positive in Mitsuba, default 5). `path` tests it right
        // after the vertex that made its depth (segment count) k, as ours does: k ≥ rr_depth.
        // `volpath` and `volpathmis` test it at the top of the next iteration with k > rr_depth
        // (src/integrators/volpath.cpp), one vertex later: our rr_depth + 1. The direct
        // integrator has none, nor does our render of it (two segments end every path first).
        let rr = self.integer_in(e, "rr_depth", 1..=i64::from(u32::MAX - 1))?.map(|d| d as u32);
        render.rr_depth = match ty {
            "volpath" | "volpathmis" => Some(rr.unwrap_or(MITSUBA_RR_DEPTH) + 1),
            _ => rr,
        };
        Ok(())
    }

    fn sensor(&mut self, e: &'a Element, render: &mut RenderSection) -> R<CameraSection> {
        let ty = self.req_attr(e, "type")?;
        let projection = match ty {
            "perspective" => ProjectionName::Perspective,
            "thinlens" => ProjectionName::Thinlens,
            "orthographic" => ProjectionName::Orthographic,
            other => {
                self.warn(e, &format!("sensor `{other}` is not supported: using a pinhole perspective camera"));
                ProjectionName::Perspective
            }
        };
        let (mut width, mut height) = (768u32, 576u32);
        if let Some(film) = self.child_of_kind(e, "film")? {
            for (name, slot) in [("width", &mut width), ("height", &mut height)] {
                if let Some(v) = self.integer(film, name)? {
                    *slot = u32::try_from(v)
                        .ok()
                        .filter(|v| (1..=RenderSection::MAX_SIZE).contains(v))
                        .ok_or_else(|| self.src.error(film.offset, format!("film {name} must be from 1 to 32768")))?;
                }
            }
            render.filter = Some(self.rfilter(film)?);
            let at = self.child_of_kind(film, "rfilter")?.unwrap_or(film);
            self.origins.push((ItemPath::root().field("render").field("filter"), at.offset));
        }
        render.width = Some(width);
        render.height = Some(height);
        let mut spp = 4u32;
        if let Some(s) = self.child_of_kind(e, "sampler")? {
            match s.attr("type").unwrap_or("independent") {
                "independent" => {}
                // Mitsuba 3's `multijitter` is a jittered grid whose points are also stratified
                // along each axis (Kensler's correlated multi-jittering); ours is the jittered
                // grid, with the same expected image (making ours multi-jittered changed no
                // measured error: docs/benchmarks.md, "Multi-jittered 2D points").
                "stratified" | "multijitter" => render.sampler = Some(SamplerName(SamplerKind::Stratified)),
                // Mitsuba 0.6's Sobol' sampler (the default of Bitterli's scenes) and Mitsuba 3's
                // `ldsampler` (a scrambled, padded (0, 2)-sequence): ours is an Owen-scrambled,
                // padded Sobol' (0, 2)-sequence; the expected image is the same.
                "sobol" | "ldsampler" => render.sampler = Some(SamplerName(SamplerKind::Sobol)),
                other @ ("halton" | "hammersley") => {
                    self.warn(s, &format!("sampler `{other}` is not supported: using sobol"));
                    render.sampler = Some(SamplerName(SamplerKind::Sobol));
                }
                other => {
                    self.warn(s, &format!("sampler `{other}` is not supported: using stratified"));
                    render.sampler = Some(SamplerName(SamplerKind::Stratified));
                }
            }
            if let Some(n) = self.integer_in(s, "sample_count", 1..=i64::from(u32::MAX))? {
                spp = n as u32;
            }
        }
        render.spp = Some(spp);
        // Without `fov`, Mitsuba reads `focal_length` (default "50mm") as a lens on a 35 mm film
        // (36 × 24 mm), measured along the film's diagonal.
        let (fov, axis) = match self.float(e, "fov")? {
            Some(f) => (f, self.string(e, "fov_axis")?.unwrap_or("x")),
            None => {
                let text = self.string(e, "focal_length")?.unwrap_or("50mm");
                let mm = text.trim().trim_end_matches("mm");
                let at = self.prop(e, "focal_length").unwrap_or(e);
                let f = self.number(at, "value", mm)?;
                if f <= 0.0 {
                    return Err(self.src.error(at.offset_of("value"), "focal_length must be positive"));
                }
                (2.0 * (36f64.hypot(24.0) / (2.0 * f)).atan().to_degrees(), "diagonal")
            }
        };
        if !(fov > 0.0 && fov < 180.0) {
            return Err(self.src.error(e.offset, format!("fov must be in (0, 180) degrees, not {fov}")));
        }
        let (w, h) = (width as f64, height as f64);
        let half = (fov.to_radians() / 2.0).tan();
        let vertical_half = match axis {
            "x" => half * h / w,
            "y" => half,
            "smaller" if w < h => half * h / w,
            "smaller" => half,
            "larger" if w > h => half * h / w,
            "larger" => half,
            "diagonal" => half * h / (w * w + h * h).sqrt(),
            other => {
                let at = self.prop(e, "fov_axis").map_or(e.offset, |p| p.offset_of("value"));
                return Err(self
                    .src
                    .error(at, format!("unknown fov_axis `{other}` (x, y, smaller, larger, diagonal)")));
            }
        };
        let vfov = 2.0 * vertical_half.atan().to_degrees();
        let steps = self.to_world(e)?;
        let mut t = Transform::IDENTITY;
        for s in &steps {
            t = t.then(&s.to_transform().map_err(|m| self.src.error(e.offset, m))?);
        }
        // Mitsuba's camera looks along its local +z with +y up.
        let from = t.point(Vec3::ZERO);
        let mut at = t.point(Vec3::Z);
        if at == from || !at.is_finite() {
            // One unit along +z vanishes next to a far origin (3e38 + 1 == 3e38) or a tiny
            // scale: step instead a distance that f32 resolves at that origin.
            let reach = from.abs().max_element() * f32::EPSILON * 16.0;
            if let Some(forward) = pathtrace::math::normalize_robust(t.vector(Vec3::Z)) {
                at = from + forward * reach.max(1.0);
            }
        }
        let up = t.vector(Vec3::Y);
        let mut camera =
            CameraSection { up: Some(n3(up)), vfov: Some(num(vfov)), ..CameraSection::pinhole(n3(from), n3(at)) };
        match projection {
            ProjectionName::Perspective => {}
            ProjectionName::Thinlens => {
                // Mitsuba requires `aperture_radius`; `focus_distance` defaults to its far clip.
                let Some(radius) = self.float(e, "aperture_radius")? else {
                    return Err(self.src.error(e.offset, "a thinlens sensor needs `aperture_radius`"));
                };
                let focus = self.float(e, "focus_distance")?.unwrap_or(1e4);
                if radius < 0.0 || focus <= 0.0 {
                    return Err(self
                        .src
                        .error(e.offset, "thinlens `aperture_radius` must be ≥ 0 and `focus_distance` positive"));
                }
                camera.projection = Some(projection);
                camera.aperture_radius = Some(num(radius));
                camera.focus_distance = Some(num(focus));
            }
            ProjectionName::Orthographic => {
                // Mitsuba's orthographic view spans camera-space x ∈ [−1, 1] and
                // y ∈ [−1/aspect, 1/aspect], scaled by `to_world`.
                let height = 2.0 * t.vector(Vec3::Y).length() as f64 * h / w;
                if !(height > 0.0 && height.is_finite()) {
                    return Err(self.src.error(e.offset, "orthographic sensor: `to_world` collapses the view"));
                }
                camera.projection = Some(projection);
                camera.height = Some(num(height));
            }
        }
        Ok(camera)
    }

    /// The film's `<rfilter>`; without one, Mitsuba's default: a gaussian of stddev 0.5.
    fn rfilter(&mut self, film: &'a Element) -> R<FilterDef> {
        let default = FilterDef { kind: FilterName::Gaussian, radius: None, stddev: None };
        let Some(f) = self.child_of_kind(film, "rfilter")? else { return Ok(default) };
        let positive = |this: &Self, name: &str, v: Option<f64>| match v {
            Some(x) if x <= 0.0 => Err(this.src.error(f.offset, format!("rfilter `{name}` must be positive"))),
            v => Ok(v.map(num)),
        };
        Ok(match f.attr("type").unwrap_or("box") {
            "box" => FilterDef {
                kind: FilterName::Box,
                radius: positive(self, "radius", self.float(f, "radius")?)?,
                stddev: None,
            },
            "tent" => FilterDef {
                kind: FilterName::Tent,
                radius: positive(self, "radius", self.float(f, "radius")?)?,
                stddev: None,
            },
            "gaussian" => FilterDef {
                kind: FilterName::Gaussian,
                radius: None,
                stddev: positive(self, "stddev", self.float(f, "stddev")?)?,
            },
            other => {
                self.warn(f, &format!("reconstruction filter `{other}` is not supported: using a gaussian"));
                default
            }
        })
    }

    fn unique_name(&self, base: &str) -> String {
        if !self.materials.contains_key(base) {
            return base.to_string();
        }
        (2..).map(|i| format!("{base}-{i}")).find(|n| !self.materials.contains_key(n)).unwrap_or_default()
    }

    /// The scattering part of a `<bsdf>` (after `<ref>`), unwrapping `twosided`, its normal or
    /// bump map, unwrapping `normalmap` and `bumpmap`, and its opacity, unwrapping `mask`.
    /// Mitsuba's opaque BSDFs (`diffuse`, `conductor`, `roughconductor`, `plastic`,
    /// `roughplastic`, and what 0.6 files upgrade to them) reflect from their front only (both
    /// cosines > 0 in the shading frame, e.g. `conductor.cpp`'s `eval`) unless wrapped in
    /// `twosided`: outside one they become one-sided. Dielectrics and `null` are crossed from
    /// either side.
    fn bsdf_kind(&mut self, e: &'a Element) -> R<(MaterialKind, Wrappers)> {
        let mut maps = Wrappers::default();
        let kind = self.bsdf_kind_at(e, 0, &mut maps)?;
        let kind = match kind {
            MaterialKind::Diffuse { .. }
            | MaterialKind::Lambertian { .. }
            | MaterialKind::Mirror { .. }
            | MaterialKind::Glossy { .. }
            | MaterialKind::Conductor { .. }
            | MaterialKind::RoughConductor { .. }
            | MaterialKind::Plastic { .. }
            | MaterialKind::RoughPlastic { .. }
            | MaterialKind::Blend { .. }
                if !maps.two_sided =>
            {
                MaterialKind::OneSided(Box::new(kind))
            }
            MaterialKind::Diffuse { .. }
            | MaterialKind::Lambertian { .. }
            | MaterialKind::Mirror { .. }
            | MaterialKind::Glossy { .. }
            | MaterialKind::Conductor { .. }
            | MaterialKind::RoughConductor { .. }
            | MaterialKind::Plastic { .. }
            | MaterialKind::RoughPlastic { .. }
            | MaterialKind::Dielectric { .. }
            | MaterialKind::ThinDielectric { .. }
            | MaterialKind::RoughDielectric { .. }
            | MaterialKind::Emissive
            | MaterialKind::Null
            | MaterialKind::Blend { .. }
            | MaterialKind::OneSided(_) => kind,
        };
        Ok((kind, maps))
    }

    fn bsdf_kind_at(&mut self, e: &'a Element, depth: usize, maps: &mut Wrappers) -> R<MaterialKind> {
        if depth > 8 {
            return Err(self.src.error(e.offset, "BSDFs are nested too deeply (a <ref> cycle?)"));
        }
        let ty = self.req_attr(e, "type")?;
        if ty == "normalmap" || ty == "bumpmap" {
            if maps.normal.is_some() {
                return Err(self.src.error(e.offset, "only one `normalmap` or `bumpmap` per material is supported"));
            }
            let (map, nested) = self.normal_wrapper(e, ty)?;
            maps.normal = Some(map);
            return self.bsdf_kind_at(nested, depth + 1, maps);
        }
        if ty == "mask" {
            if maps.opacity.is_some() {
                return Err(self.src.error(e.offset, "only one `mask` per material is supported"));
            }
            let (opacity, nested) = self.mask_wrapper(e)?;
            maps.opacity = Some(opacity);
            return self.bsdf_kind_at(nested, depth + 1, maps);
        }
        let grey = MaterialKind::Lambertian { albedo: Colour::grey(0.5) };
        Ok(match ty {
            "diffuse" => {
                let albedo = self.colour(e, "reflectance")?.unwrap_or(Colour::grey(0.5));
                MaterialKind::Lambertian { albedo }
            }
            "twosided" => {
                maps.two_sided = true;
                let inner = e.children.iter().find(|c| c.tag == "bsdf" || c.tag == "ref");
                match inner {
                    Some(i) => {
                        let i = self.deref(i)?;
                        self.bsdf_kind_at(i, depth + 1, maps)?
                    }
                    None => MaterialKind::Lambertian { albedo: Colour::grey(0.5) },
                }
            }
            "null" => MaterialKind::Null,
            "blendbsdf" => self.blend_bsdf(e, depth)?,
            "dielectric" => {
                let int = self.ior(e, "int_ior", 1.5046)?;
                let ext = self.ior(e, "ext_ior", 1.000277)?;
                let tint = self.colour(e, "specular_transmittance")?.unwrap_or(Colour::grey(1.0));
                MaterialKind::Dielectric { ior: num(int / ext), tint }
            }
            "thindielectric" => {
                let int = self.ior(e, "int_ior", 1.5046)?;
                let ext = self.ior(e, "ext_ior", 1.000277)?;
                let tint = self.colour(e, "specular_transmittance")?.unwrap_or(Colour::grey(1.0));
                MaterialKind::ThinDielectric { ior: num(int / ext), tint }
            }
            other => match self.microfacet_bsdf(e, other)? {
                Some(kind) => {
                    maps.roughness = self.alpha_texture(e, other)?;
                    kind
                }
                None => {
                    self.warn(e, &format!("bsdf `{other}` is not supported: using a grey (0.5) lambertian"));
                    grey
                }
            },
        })
    }

    fn ior(&mut self, e: &'a Element, name: &str, default: f64) -> R<f64> {
        let Some(p) = self.prop(e, name) else { return Ok(default) };
        let v = self.req_attr(p, "value")?;
        let x = match p.tag.as_str() {
            "string" => named_ior(v).ok_or_else(|| {
                self.src.error(p.offset_of("value"), format!("unknown IOR name `{v}` (e.g. bk7, water, air, diamond)"))
            })?,
            _ => self.number(p, "value", v)?,
        };
        if x <= 0.0 {
            return Err(self.src.error(p.offset_of("value"), format!("{name} must be positive")));
        }
        Ok(x)
    }

    /// The material name for a shape: its BSDF (default diffuse 0.5), plus its area emitter.
    fn shape_material(&mut self, shape: &'a Element, label: &str) -> R<String> {
        let mut bsdf = None;
        let mut emitter = None;
        for c in &shape.children {
            if c.tag != "bsdf" && c.tag != "ref" && c.tag != "emitter" {
                continue;
            }
            if c.tag == "ref" && c.attr("name").is_some_and(|n| n != "bsdf" && n != "emitter") {
                continue;
            }
            let d = self.deref(c)?;
            match d.tag.as_str() {
                "bsdf" => bsdf = Some(d),
                "emitter" => emitter = Some(d),
                other => self.warn(c, &format!("a <ref> to <{other}> inside a shape is ignored")),
            }
        }
        let mut emission = None;
        if let Some(em) = emitter {
            let ty = self.req_attr(em, "type")?;
            if ty == "area" {
                // A `bitmap` (or other texture) radiance is looked up at the shape's uv, as
                // Mitsuba's area emitter evaluates `radiance` at the surface interaction.
                emission = Some(match self.colour(em, "radiance")? {
                    Some(Colour::Texture(t)) => EmissionDef {
                        radiance: Triple::Splat(num(1.0)),
                        two_sided: false,
                        texture: Some(Colour::Texture(t)),
                    },
                    Some(Colour::Constant(radiance)) => EmissionDef { radiance, two_sided: false, texture: None },
                    None => EmissionDef { radiance: Triple::Splat(num(1.0)), two_sided: false, texture: None },
                });
            } else {
                self.warn(em, &format!("emitter `{ty}` on a shape is not supported and is skipped"));
            }
        }
        let shared = bsdf.filter(|b| emission.is_none() && b.attr("id").is_some());
        if let Some(b) = shared {
            if let Some(name) = self.bsdf_names.get(&b.offset) {
                return Ok(name.clone());
            }
        }
        let (kind, maps) = match bsdf {
            Some(b) => self.bsdf_kind(b)?,
            // Mitsuba's default BSDF (src/render/shape.cpp): a one-sided diffuse of reflectance
            // 0.5, or of reflectance 0 on an emitting shape.
            None if emission.is_some() => (MaterialKind::Emissive, Wrappers::default()),
            None => {
                let grey = MaterialKind::Lambertian { albedo: Colour::grey(0.5) };
                (MaterialKind::OneSided(Box::new(grey)), Wrappers::default())
            }
        };
        if maps.opacity.is_some() && emission.is_some() {
            return Err(self.src.error(shape.offset, "an emitting shape cannot have a `mask` BSDF (not supported)"));
        }
        let base = match (shared, bsdf.and_then(|b| b.attr("id"))) {
            (Some(b), _) => b.attr("id").unwrap_or("bsdf").to_string(),
            (None, Some(id)) => format!("{label}-{id}"),
            (None, None) => label.to_string(),
        };
        let name = self.unique_name(&base);
        self.materials.insert(
            name.clone(),
            MaterialDef { kind, emission, normal: maps.normal, opacity: maps.opacity, roughness: maps.roughness },
        );
        let at = bsdf.or(emitter).unwrap_or(shape).offset;
        self.origins.push((ItemPath::root().field("materials").field(&name), at));
        if let Some(b) = shared {
            self.bsdf_names.insert(b.offset, name.clone());
        }
        Ok(name)
    }

    /// Finds `file` (a `what`: mesh, environment map) in the search folders.
    fn find_file(&self, e: &Element, file: &str, what: &str) -> R<String> {
        for dir in &self.search {
            let p = dir.join(file);
            if p.is_file() {
                // Relative to the scene's folder, where the native builder looks.
                let base = self.search.first().map(PathBuf::as_path).unwrap_or(Path::new(""));
                let rel = p.strip_prefix(base).map(Path::to_path_buf).unwrap_or(p);
                return Ok(rel.to_string_lossy().into_owned());
            }
        }
        let at = self.prop(e, "filename").map_or(e.offset, |p| p.offset_of("value"));
        Err(self.src.error(at, format!("{what} file `{file}` not found")))
    }

    fn shape(&mut self, e: &'a Element) -> R<()> {
        let ty = self.req_attr(e, "type")?;
        match ty {
            "shapegroup" => return self.shapegroup(e),
            "instance" => return self.instance(e),
            _ => {}
        }
        let label = e.attr("id").map_or_else(|| format!("{ty}{}", self.objects.len()), str::to_string);
        let shape = match ty {
            "obj" | "ply" => {
                let Some(file) = self.string(e, "filename")? else {
                    return Err(self.src.error(e.offset, format!("a {ty} shape needs a `filename` string")));
                };
                // Mitsuba flips v of OBJ texture coordinates unless told not to (not PLY's).
                let flip_v = ty == "obj" && self.boolean(e, "flip_tex_coords")?.unwrap_or(true);
                let normals = self.mesh_normals(e)?;
                ShapeDef::Mesh { file: self.find_file(e, file, "mesh")?, part: None, flip_v, normals }
            }
            "serialized" => {
                let Some(file) = self.string(e, "filename")? else {
                    return Err(self.src.error(e.offset, "a serialized shape needs a `filename` string"));
                };
                let part = self.integer_in(e, "shape_index", 0..=i64::from(u32::MAX))?.unwrap_or(0) as u32;
                let normals = self.mesh_normals(e)?;
                ShapeDef::Mesh { file: self.find_file(e, file, "mesh")?, part: Some(part), flip_v: false, normals }
            }
            "rectangle" => ShapeDef::Quad {
                q: n3(Vec3::new(-1.0, -1.0, 0.0)),
                u: n3(Vec3::new(2.0, 0.0, 0.0)),
                v: n3(Vec3::new(0.0, 2.0, 0.0)),
            },
            "disk" => ShapeDef::Disk { center: n3(Vec3::ZERO), normal: n3(Vec3::Z), radius: num(1.0) },
            "cube" => ShapeDef::Box { min: n3(Vec3::splat(-1.0)), max: n3(Vec3::splat(1.0)) },
            "sphere" => {
                let center = match self.prop(e, "center") {
                    Some(p) => self.vec3_of(p, "value", 0.0)?,
                    None => Vec3::ZERO,
                };
                let radius = self.float(e, "radius")?.unwrap_or(1.0);
                if radius <= 0.0 {
                    return Err(self.src.error(e.offset, "a sphere's radius must be positive"));
                }
                ShapeDef::Sphere { center: n3(center), radius: num(radius) }
            }
            other => {
                self.warn(e, &format!("shape `{other}` is not supported and is skipped"));
                return Ok(());
            }
        };
        // Every Mitsuba shape takes `flip_normals`; the native box (Mitsuba's cube) does not.
        let mut flip_normals = self.boolean(e, "flip_normals")?.unwrap_or(false);
        if flip_normals && matches!(shape, ShapeDef::Box { .. }) {
            self.warn(e, "flip_normals on a `cube` is not supported and is ignored");
            flip_normals = false;
        }
        let transform = self.to_world(e)?;
        let material = self.shape_material(e, &label)?;
        let textured_light = self.materials[&material].emission.as_ref().is_some_and(|m| m.texture.is_some());
        // A turned-over quad or disk is re-parameterised (docs/scene-format.md, `flip_normals`);
        // Mitsuba turns only the normal, so a texture on it would be read mirrored.
        if flip_normals && matches!(shape, ShapeDef::Quad { .. } | ShapeDef::Disk { .. }) {
            let textured = self
                .materials
                .get_mut(&material)
                .is_some_and(|m| m.textures_mut().iter().any(|c| matches!(c, Colour::Texture(_))));
            if textured {
                self.warn(e, &format!("flip_normals on a textured `{ty}` mirrors its texture (Mitsuba's does not)"));
            }
        }
        if textured_light && !matches!(shape, ShapeDef::Mesh { .. } | ShapeDef::Quad { .. }) {
            return Err(self.src.error(
                e.offset,
                format!("a textured area emitter is supported on meshes and rectangles only, not on a `{ty}`"),
            ));
        }
        let item = self.objects_at.index(self.objects.len());
        self.origins.push((item.clone(), e.offset));
        for (field, prop) in [("file", "filename"), ("part", "shape_index")] {
            if let Some(p) = self.prop(e, prop) {
                self.origins.push((item.field(field), p.offset_of("value")));
            }
        }
        if let Some(t) = e.children.iter().find(|c| c.tag == "transform" && c.attr("name") == Some("to_world")) {
            for (i, step) in t.children.iter().enumerate() {
                self.origins.push((item.field("transform").index(i), step.offset));
            }
        }
        let (interior, exterior) = self.shape_media(e)?;
        self.objects.push(ObjectDef { shape, material, transform, interior, exterior, flip_normals });
        Ok(())
    }

    /// Adds the environment, or replaces an earlier one (the renderer has a single environment).
    fn set_environment(&mut self, e: &'a Element, env: LightDef) {
        let is_env = |l: &LightDef| matches!(l, LightDef::Constant { .. } | LightDef::Envmap { .. });
        let existing = self.lights.iter().position(is_env);
        let i = existing.unwrap_or(self.lights.len());
        self.origins.push((ItemPath::root().field("lights").index(i), e.offset));
        match existing {
            Some(i) => {
                let ty = e.attr("type").unwrap_or("");
                self.warn(e, &format!("only one environment is supported: this `{ty}` emitter replaces the first"));
                self.lights[i] = env;
            }
            None => self.lights.push(env),
        }
    }

    fn top_emitter(&mut self, e: &'a Element) -> R<()> {
        let ty = self.req_attr(e, "type")?;
        match ty {
            "point" => {
                let position = match self.prop(e, "position") {
                    Some(p) => self.vec3_of(p, "value", 0.0)?,
                    None => {
                        let steps = self.to_world(e)?;
                        let mut t = Transform::IDENTITY;
                        for s in &steps {
                            t = t.then(&s.to_transform().map_err(|m| self.src.error(e.offset, m))?);
                        }
                        t.point(Vec3::ZERO)
                    }
                };
                let intensity = self.color(e, "intensity")?.unwrap_or(Triple::Splat(num(1.0)));
                self.origins.push((ItemPath::root().field("lights").index(self.lights.len()), e.offset));
                self.lights.push(LightDef::Point { position: n3(position), intensity });
            }
            "spot" => {
                let intensity = self.color(e, "intensity")?.unwrap_or(Triple::Splat(num(1.0)));
                let cutoff_angle = self.float(e, "cutoff_angle")?.map(num);
                let beam_width = self.float(e, "beam_width")?.map(num);
                if self.prop(e, "texture").is_some() {
                    self.warn(e, "a spot light's projected `texture` is not supported and is ignored");
                }
                let transform = self.to_world(e)?;
                self.origins.push((ItemPath::root().field("lights").index(self.lights.len()), e.offset));
                self.lights.push(LightDef::Spot { intensity, cutoff_angle, beam_width, transform });
            }
            "directional" => {
                let irradiance = self.color(e, "irradiance")?.unwrap_or(Triple::Splat(num(1.0)));
                let direction = match self.prop(e, "direction") {
                    Some(p) => Some(n3(self.vec3_of(p, "value", 0.0)?)),
                    None => None,
                };
                let transform = self.to_world(e)?;
                if direction.is_some() && !transform.is_empty() {
                    return Err(self
                        .src
                        .error(e.offset, "a directional emitter takes `direction` or `to_world`, not both"));
                }
                self.origins.push((ItemPath::root().field("lights").index(self.lights.len()), e.offset));
                self.lights.push(LightDef::Directional { irradiance, direction, transform });
            }
            "constant" => {
                let radiance = self.color(e, "radiance")?.unwrap_or(Triple::Splat(num(1.0)));
                self.set_environment(e, LightDef::Constant { radiance });
            }
            "envmap" => {
                let Some(file) = self.string(e, "filename")? else {
                    return Err(self.src.error(e.offset, "an envmap emitter needs a `filename` string"));
                };
                let filename = self.find_file(e, file, "environment map")?;
                let scale = self.float(e, "scale")?.map(num);
                let transform = self.to_world(e)?;
                self.set_environment(e, LightDef::Envmap { filename, scale, transform });
            }
            // Attached to shapes through <ref>.
            "area" if e.attr("id").is_some() => {}
            "area" => self.warn(e, "an area emitter outside a shape emits nothing and is skipped"),
            other => self.warn(e, &format!("emitter `{other}` is not supported and is skipped")),
        }
        Ok(())
    }
}

/// Rotation by `degrees` about the unit axis `n` (right-handed), as a row-major 4×4.
fn rotation_matrix(n: Vec3, degrees: f64) -> [Num; 16] {
    let (s, c) = degrees.to_radians().sin_cos();
    let (x, y, z) = (n.x as f64, n.y as f64, n.z as f64);
    let t = 1.0 - c;
    [
        t * x * x + c,
        t * x * y - s * z,
        t * x * z + s * y,
        0.0,
        t * x * y + s * z,
        t * y * y + c,
        t * y * z - s * x,
        0.0,
        t * x * z - s * y,
        t * y * z + s * x,
        t * z * z + c,
        0.0,
        0.0,
        0.0,
        0.0,
        1.0,
    ]
    .map(num)
}
