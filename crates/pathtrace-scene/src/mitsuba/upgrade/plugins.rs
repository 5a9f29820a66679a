//! Mitsuba 0.6 plugins and tags against Mitsuba 3.9.1's. Mitsuba 3 renames none of them on load:
//! a 0.6 plugin it lacks is an error there. Here each such plugin becomes the nearest one
//! pathtrace reads, with a warning naming the substitution:
//!
//! - films `ldrfilm`, `tiledhdrfilm`, `mfilm` → `hdrfilm` (tone mapping and output options are
//!   dropped: pathtrace writes linear HDR or its own PNG);
//! - integrators `bdpt`, `pssmlt`, `mlt`, `erpt`, `photonmapper`, `ppm`, `sppm`, `vpl`, `ao`,
//!   `field`, `multichannel` → `path` (the same image in the mean, for the estimators that are
//!   unbiased), `volpath_simple` → `volpath`; the wrappers `adaptive` and `irrcache` → the
//!   integrator they wrap;
//! - BSDFs `roughdiffuse` → `diffuse` (Oren–Nayar roughness dropped); `coating` /
//!   `roughcoating` over a `diffuse` → `plastic` / `roughplastic` with the coating's IOR,
//!   roughness and the diffuse reflectance, over anything else → the nested BSDF; `phong` →
//!   `roughplastic` with Beckmann α = √(2 / (exponent + 2)) (the Phong–Beckmann correspondence
//!   of Walter et al. 2007, §5.2) and its `diffuse_reflectance` / `specular_reflectance`;
//! - a `bumpmap` over a 0.6 `scale` texture → the scaled texture with the factor as the
//!   bumpmap's `scale` (Mitsuba 3's form).
//!
//! Other plugins of either version that pathtrace lacks are named in warnings by the converter,
//! as for Mitsuba 3 files. A tag or plugin neither version has is a located error.

use super::super::parse::{Attr, Element, XmlSource};
use crate::native::SceneError;

type R<T> = Result<T, SceneError>;

/// Every element tag of Mitsuba 0.6 and 3.9.1 scene files (`lookAt` is upgraded first).
const TAGS: &[&str] = &[
    "scene",
    "shape",
    "bsdf",
    "texture",
    "emitter",
    "sensor",
    "film",
    "rfilter",
    "sampler",
    "integrator",
    "medium",
    "phase",
    "subsurface",
    "volume",
    "string",
    "integer",
    "float",
    "boolean",
    "point",
    "vector",
    "rgb",
    "srgb",
    "spectrum",
    "blackbody",
    "transform",
    "translate",
    "rotate",
    "scale",
    "lookat",
    "matrix",
    "ref",
    "include",
    "alias",
    "default",
    "path",
    "animation",
];

/// The plugins of each object tag in Mitsuba 0.6 (documentation of 0.5/0.6) and 3.9.1 (src/*).
const PLUGINS: &[(&str, &[&str])] = &[
    (
        "bsdf",
        &[
            "diffuse",
            "roughdiffuse",
            "dielectric",
            "thindielectric",
            "roughdielectric",
            "conductor",
            "roughconductor",
            "plastic",
            "roughplastic",
            "coating",
            "roughcoating",
            "bumpmap",
            "normalmap",
            "phong",
            "ward",
            "mixturebsdf",
            "blendbsdf",
            "mask",
            "twosided",
            "difftrans",
            "hk",
            "irawan",
            "null",
            "hair",
            "measured",
            "measured_polarized",
            "pplastic",
            "principled",
            "principledthin",
            "polarizer",
            "retarder",
            "circular",
        ],
    ),
    (
        "shape",
        &[
            "cube",
            "sphere",
            "cylinder",
            "rectangle",
            "disk",
            "obj",
            "ply",
            "serialized",
            "shapegroup",
            "instance",
            "hair",
            "heightfield",
            "bsplinecurve",
            "linearcurve",
            "sdfgrid",
            "ellipsoids",
            "ellipsoidsmesh",
            "merge",
            "blender",
        ],
    ),
    (
        "emitter",
        &[
            "point",
            "area",
            "spot",
            "directional",
            "collimated",
            "sky",
            "sun",
            "sunsky",
            "envmap",
            "constant",
            "projector",
            "directionalarea",
            "timed_sunsky",
        ],
    ),
    (
        "sensor",
        &[
            "perspective",
            "thinlens",
            "orthographic",
            "telecentric",
            "spherical",
            "irradiancemeter",
            "radiancemeter",
            "fluencemeter",
            "perspective_rdist",
            "batch",
            "distant",
        ],
    ),
    ("film", &["hdrfilm", "ldrfilm", "tiledhdrfilm", "mfilm", "specfilm"]),
    ("rfilter", &["box", "tent", "gaussian", "mitchell", "catmullrom", "lanczos"]),
    (
        "sampler",
        &["independent", "stratified", "ldsampler", "halton", "hammersley", "sobol", "multijitter", "orthogonal"],
    ),
    (
        "integrator",
        &[
            "ao",
            "direct",
            "path",
            "volpath_simple",
            "volpath",
            "volpathmis",
            "bdpt",
            "photonmapper",
            "ppm",
            "sppm",
            "pssmlt",
            "mlt",
            "erpt",
            "ptracer",
            "adaptive",
            "vpl",
            "irrcache",
            "multichannel",
            "field",
            "aov",
            "depth",
            "moment",
            "stokes",
            "prb",
            "prb_basic",
            "prbvolpath",
            "direct_projective",
            "prb_projective",
        ],
    ),
    (
        "texture",
        &[
            "bitmap",
            "checkerboard",
            "gridtexture",
            "scale",
            "vertexcolors",
            "wireframe",
            "curvature",
            "mesh_attribute",
            "volume",
        ],
    ),
    ("medium", &["homogeneous", "heterogeneous"]),
    ("phase", &["isotropic", "hg", "sggx", "microflake", "mixturephase", "rayleigh", "kkay", "blendphase", "tabphase"]),
    ("volume", &["constvolume", "gridvolume", "volcache", "const", "grid"]),
    ("subsurface", &["dipole", "singlescatter"]),
];

/// A located error for a tag or plugin type neither Mitsuba 0.6 nor 3.9.1 has.
pub fn check_known(e: &Element, src: &XmlSource) -> R<()> {
    if !TAGS.contains(&e.tag.as_str()) {
        let hint = match e.tag.as_str() {
            "luminaire" | "camera" => " (Mitsuba 0.3's name: files older than 0.4 are not read)",
            _ => "",
        };
        return Err(src.error(e.offset, format!("unknown element <{}>{hint}", e.tag)));
    }
    let (Some((_, known)), Some(ty)) = (PLUGINS.iter().find(|(t, _)| *t == e.tag), e.attr("type")) else {
        return Ok(());
    };
    if !known.contains(&ty) {
        return Err(src.error(
            e.offset_of("type"),
            format!("unknown {} type `{ty}` (neither Mitsuba 0.6 nor Mitsuba 3 has it)", e.tag),
        ));
    }
    Ok(())
}

/// Renames or rebuilds `e` if it is a 0.6 plugin Mitsuba 3 lacks (see the module docs); its
/// children are upgraded already.
pub fn upgrade_plugin(e: &mut Element, src: &XmlSource, warnings: &mut Vec<String>) -> R<()> {
    let Some(ty) = e.attr("type").map(str::to_string) else { return Ok(()) };
    let mut warn = |e: &Element, msg: String| warnings.push(format!("{}: {msg}", src.location(e.offset)));
    match (e.tag.as_str(), ty.as_str()) {
        ("film", "ldrfilm" | "tiledhdrfilm" | "mfilm") => {
            warn(e, format!("film `{ty}` (Mitsuba 0.6) → `hdrfilm`: its tone-mapping and output options are ignored"));
            set_type(e, "hdrfilm");
        }
        ("integrator", "volpath_simple") => {
            warn(e, "integrator `volpath_simple` (Mitsuba 0.6) → `volpath`".into());
            set_type(e, "volpath");
        }
        ("integrator", "adaptive" | "irrcache") => {
            let Some(inner) = e.children.iter().position(|c| c.tag == "integrator") else {
                return Err(src.error(e.offset, format!("integrator `{ty}` needs a nested <integrator>")));
            };
            warn(e, format!("integrator `{ty}` (Mitsuba 0.6) is not supported: using the integrator it wraps"));
            let inner = e.children.swap_remove(inner);
            *e = inner;
        }
        (
            "integrator",
            "bdpt" | "pssmlt" | "mlt" | "erpt" | "photonmapper" | "ppm" | "sppm" | "vpl" | "ao" | "field",
        )
        | ("integrator", "multichannel") => {
            warn(e, format!("integrator `{ty}` (Mitsuba 0.6) is not supported: using `path` with its max_depth"));
            set_type(e, "path");
            e.children.retain(|c| c.attr("name") == Some("max_depth"));
        }
        ("bsdf", "roughdiffuse") => {
            warn(e, "bsdf `roughdiffuse` (Mitsuba 0.6) → `diffuse`: its roughness is ignored".into());
            set_type(e, "diffuse");
            e.children.retain(|c| !matches!(c.attr("name"), Some("alpha" | "use_fast_approx")));
        }
        ("bsdf", "coating" | "roughcoating") => coating(e, &ty, src, &mut warn)?,
        ("bsdf", "phong") => phong(e, src, &mut warn)?,
        ("bsdf", "bumpmap") => bumpmap_scale(e, src)?,
        _ => {}
    }
    Ok(())
}

fn set_type(e: &mut Element, ty: &str) {
    if let Some(a) = e.attrs.iter_mut().find(|a| a.name == "type") {
        a.value = ty.into();
    }
}

fn float_element(name: &str, value: f64, at: usize) -> Element {
    let attr = |n: &str, v: String| Attr { name: n.into(), value: v, offset: at };
    Element {
        tag: "float".into(),
        attrs: vec![attr("name", name.into()), attr("value", format!("{value}"))],
        children: Vec::new(),
        offset: at,
    }
}

/// `coating` / `roughcoating`: a plastic over a diffuse base, else the base alone.
fn coating(e: &mut Element, ty: &str, src: &XmlSource, warn: &mut impl FnMut(&Element, String)) -> R<()> {
    let Some(i) = e.children.iter().position(|c| c.tag == "bsdf" || c.tag == "ref") else {
        return Err(src.error(e.offset, format!("a `{ty}` BSDF needs a nested <bsdf> (the surface it coats)")));
    };
    let base = &e.children[i];
    if base.tag == "ref" {
        return Err(src.error(
            base.offset,
            format!("a `{ty}` over a <ref> is not supported (Mitsuba 3 has no coating): nest the coated <bsdf> here"),
        ));
    }
    if base.tag == "bsdf" && base.attr("type") == Some("diffuse") {
        let plastic = if ty == "coating" { "plastic" } else { "roughplastic" };
        warn(e, format!("bsdf `{ty}` over `diffuse` (Mitsuba 0.6) → `{plastic}` (its absorbing layer is ignored)"));
        let base = e.children.remove(i);
        let mut reflectance = base.children.into_iter().find(|c| c.attr("name") == Some("reflectance"));
        if let Some(r) = &mut reflectance {
            r.attrs.iter_mut().filter(|a| a.name == "name").for_each(|a| a.value = "diffuse_reflectance".into());
        }
        e.children.retain(|c| !matches!(c.attr("name"), Some("thickness" | "sigma_a")));
        e.children.extend(reflectance);
        set_type(e, plastic);
    } else {
        warn(e, format!("bsdf `{ty}` (Mitsuba 0.6) is not supported: using the BSDF it coats"));
        let base = e.children.remove(i);
        let id = e.attr_full("id").cloned();
        *e = base;
        if let Some(id) = id {
            e.attrs.retain(|a| a.name != "id");
            e.attrs.push(id);
        }
    }
    Ok(())
}

/// `phong` → a Beckmann `roughplastic` of matching width.
fn phong(e: &mut Element, src: &XmlSource, warn: &mut impl FnMut(&Element, String)) -> R<()> {
    let exponent = match e.children.iter().find(|c| c.attr("name") == Some("exponent")) {
        None => 30.0,
        Some(p) => {
            let t = p.attr("value").unwrap_or("");
            t.trim().parse::<f64>().ok().filter(|x| x.is_finite() && *x >= 0.0).ok_or_else(|| {
                src.error(
                    p.offset_of("value"),
                    format!("phong `exponent` `{t}` is not a number ≥ 0 (a texture is not supported)"),
                )
            })?
        }
    };
    let alpha = (2.0 / (exponent + 2.0)).sqrt();
    warn(e, format!("bsdf `phong` (Mitsuba 0.6) → `roughplastic`, Beckmann α = {alpha:.4} (exponent {exponent})"));
    e.children.retain(|c| c.attr("name") != Some("exponent"));
    e.children.push(float_element("alpha", alpha, e.offset));
    let attr = |n: &str, v: &str| Attr { name: n.into(), value: v.into(), offset: e.offset };
    let distribution = Element {
        tag: "string".into(),
        attrs: vec![attr("name", "distribution"), attr("value", "beckmann")],
        children: Vec::new(),
        offset: e.offset,
    };
    e.children.push(distribution);
    set_type(e, "roughplastic");
    Ok(())
}

/// A 0.6 `bumpmap` takes its height through a `scale` texture: `scale`'s factor becomes the
/// bumpmap's `scale` and the texture it scales the height field.
fn bumpmap_scale(e: &mut Element, src: &XmlSource) -> R<()> {
    let Some(i) = e.children.iter().position(|c| c.tag == "texture" && c.attr("type") == Some("scale")) else {
        return Ok(());
    };
    let scaled = e.children.remove(i);
    let factor = match scaled.children.iter().find(|c| c.attr("name") == Some("scale")) {
        None => 1.0,
        Some(p) => {
            let t = p.attr("value").unwrap_or("");
            t.trim()
                .parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| src.error(p.offset_of("value"), format!("bump `scale` `{t}` is not a number")))?
        }
    };
    let Some(inner) = scaled.children.into_iter().find(|c| c.tag == "texture" || c.tag == "ref") else {
        return Err(src.error(scaled.offset, "a `scale` texture needs a nested <texture>"));
    };
    e.children.push(inner);
    e.children.retain(|c| c.attr("name") != Some("scale") || c.tag == "texture");
    e.children.push(float_element("scale", factor, scaled.offset));
    Ok(())
}
