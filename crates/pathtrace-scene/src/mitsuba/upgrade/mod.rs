//! Scenes written for Mitsuba 0.6 and older (`<scene version="0.6.0">`, any version below 2.0),
//! upgraded as Mitsuba 3.9.1 upgrades them on load (`upgrade_from_v1` in src/core/parser.cpp):
//! every property name from camelCase to underscore_case (`intIOR` → `int_ior`), a `diffuse`
//! BSDF's `diffuse_reflectance` → `reflectance`, and `uoffset`/`voffset`/`uscale`/`vscale` → a
//! `to_uv` transform (scale · translate). Also accepted: the `<lookAt>` spelling of `<lookat>`.
//!
//! Beyond what Mitsuba 3.9.1 does (it rejects these): `<srgb>` and `<blackbody>` colours become
//! `<rgb>` ([`colours`]), and 0.6 plugins Mitsuba 3 lacks become the nearest supported ones with
//! a warning ([`plugins`]); a tag or plugin neither version knows is a located error.

mod colours;
mod plugins;

use super::parse::{Attr, Element, XmlSource};
use crate::native::SceneError;

/// True when the `version` attribute names a version below 2.0.
pub fn is_v1(root: &Element) -> bool {
    root.attr("version").and_then(|v| v.trim().split('.').next()?.parse::<u32>().ok()).is_some_and(|major| major < 2)
}

/// Mitsuba's `camel_to_underscore_case`: an upper-case letter after a lower-case one starts a
/// new word, and the upper-case letters right after it join that word (`intIOR` → `int_ior`).
fn underscore_case(name: &str) -> String {
    let c: Vec<char> = name.chars().collect();
    let mut out = String::with_capacity(name.len() + 4);
    let mut i = 0;
    while i < c.len() {
        if i > 0 && c[i - 1].is_ascii_lowercase() && c[i].is_ascii_uppercase() {
            out.push('_');
            out.push(c[i].to_ascii_lowercase());
            while i + 1 < c.len() && c[i + 1].is_ascii_uppercase() {
                i += 1;
                out.push(c[i].to_ascii_lowercase());
            }
        } else {
            out.push(c[i]);
        }
        i += 1;
    }
    out
}

/// Upgrades `e` and everything under it in place; substitutions are named in `warnings`.
pub fn upgrade(e: &mut Element, src: &XmlSource, warnings: &mut Vec<String>) -> Result<(), SceneError> {
    if e.tag == "lookAt" {
        e.tag = "lookat".into();
    }
    plugins::check_known(e, src)?;
    let is_diffuse = e.tag == "bsdf" && e.attr("type") == Some("diffuse");
    let parent_tag = e.tag.clone();
    for c in &mut e.children {
        if c.tag == "default" {
            continue;
        }
        if let Some(a) = c.attrs.iter_mut().find(|a| a.name == "name") {
            a.value = underscore_case(&a.value);
            if is_diffuse && a.value == "diffuse_reflectance" {
                a.value = "reflectance".into();
            }
        }
        colours::upgrade_colour(&parent_tag, c, src, warnings)?;
    }
    uv_transform(e);
    for c in &mut e.children {
        upgrade(c, src, warnings)?;
    }
    plugins::upgrade_plugin(e, src, warnings)
}

/// `uoffset`, `voffset`, `uscale`, `vscale` children become `<transform name="to_uv">` with a
/// translate then a scale (Mitsuba: to_uv = scale(s) · translate(offset)).
fn uv_transform(e: &mut Element) {
    let names = ["uoffset", "voffset", "uscale", "vscale"];
    let value = |e: &Element, n: &str| {
        e.children.iter().find(|c| c.attr("name") == Some(n)).and_then(|c| c.attr("value")).map(str::to_string)
    };
    if !e.children.iter().any(|c| c.attr("name").is_some_and(|n| names.contains(&n))) {
        return;
    }
    let [uo, vo, us, vs] = names.map(|n| value(e, n));
    e.children.retain(|c| !c.attr("name").is_some_and(|n| names.contains(&n)));
    let at = e.offset;
    let attr = |name: &str, value: String| Attr { name: name.into(), value, offset: at };
    let el = |tag: &str, attrs: Vec<Attr>| Element { tag: tag.into(), attrs, children: Vec::new(), offset: at };
    let or = |v: Option<String>, d: &str| v.unwrap_or_else(|| d.to_string());
    let translate = el("translate", vec![attr("x", or(uo, "0")), attr("y", or(vo, "0"))]);
    let scale = el("scale", vec![attr("x", or(us, "1")), attr("y", or(vs, "1")), attr("z", "1".into())]);
    let mut t = el("transform", vec![attr("name", "to_uv".into())]);
    t.children = vec![translate, scale];
    e.children.push(t);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn camel_case_becomes_underscore_case_as_in_mitsuba() {
        for (a, b) in [
            ("intIOR", "int_ior"),
            ("extIOR", "ext_ior"),
            ("diffuseReflectance", "diffuse_reflectance"),
            ("specularReflectance", "specular_reflectance"),
            ("sampleCount", "sample_count"),
            ("alphaU", "alpha_u"),
            ("fov", "fov"),
            ("toWorld", "to_world"),
            ("shapeIndex", "shape_index"),
        ] {
            assert_eq!(underscore_case(a), b);
        }
    }
}
