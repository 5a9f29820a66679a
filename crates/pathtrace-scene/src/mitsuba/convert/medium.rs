//! Mitsuba's participating media → `[media.NAME]`: `<medium type="homogeneous">` with `sigma_t`,
//! `albedo`, `scale` and a `<phase>` (`isotropic` or `hg`), defined at the top level (used by
//! `<ref>`) or nested; placed by a shape's `interior`/`exterior` and inside a `<sensor>`.

use super::{num, Conv, R};
use crate::mitsuba::parse::Element;
use crate::native::model::{MediumDef, PhaseDef, Triple};
use crate::native::ItemPath;

impl<'a> Conv<'a, '_> {
    /// The `(interior, exterior)` media of a `<shape>`: `<medium name="interior">` children or
    /// `<ref name="interior" id="..."/>`.
    pub(super) fn shape_media(&mut self, shape: &'a Element) -> R<(Option<String>, Option<String>)> {
        let mut sides = [None, None];
        for (side, slot) in ["interior", "exterior"].into_iter().zip(&mut sides) {
            let Some(c) = shape.children.iter().find(|c| c.attr("name") == Some(side)) else { continue };
            let m = self.deref(c)?;
            if m.tag != "medium" {
                return Err(self.src.error(c.offset, format!("`{side}` must be a <medium>, not <{}>", m.tag)));
            }
            *slot = self.medium(m)?;
        }
        let [interior, exterior] = sides;
        Ok((interior, exterior))
    }

    /// The medium a `<sensor>` sits in: a `<medium>` child or a `<ref>` to one.
    pub(super) fn sensor_medium(&mut self, sensor: &'a Element) -> R<Option<String>> {
        for c in sensor.children.iter().filter(|c| c.tag == "medium" || c.tag == "ref") {
            let m = self.deref(c)?;
            if m.tag == "medium" {
                return self.medium(m);
            }
        }
        Ok(None)
    }

    /// The name of the `[media.NAME]` made for `<medium>` element `e` (once per element);
    /// `None`, with a warning, for types other than `homogeneous`.
    fn medium(&mut self, e: &'a Element) -> R<Option<String>> {
        if let Some(name) = self.medium_names.get(&e.offset) {
            return Ok(Some(name.clone()));
        }
        let ty = self.req_attr(e, "type")?;
        if ty != "homogeneous" {
            self.warn(e, &format!("medium `{ty}` is not supported (only homogeneous): the shape bounds no medium"));
            return Ok(None);
        }
        let sigma_t = self.color(e, "sigma_t")?;
        let albedo = self.color(e, "albedo")?;
        let scale = self.float(e, "scale")?;
        for (name, flag) in [("sample_emitters", "samples emitters"), ("has_spectral_extinction", "is chromatic")] {
            if self.boolean(e, name)? == Some(false) {
                self.warn(e, &format!("`{name}` = false is ignored: the medium {flag} (the image's mean is the same)"));
            }
        }
        let phase = match e.children.iter().find(|c| c.tag == "phase") {
            None => None,
            Some(p) => Some(self.phase(p)?),
        };
        let def = MediumDef {
            kind: None,
            sigma_t: sigma_t.or(Some(Triple::Splat(num(MediumDef::DEFAULT_SIGMA_T)))),
            albedo: albedo.or(Some(Triple::Splat(num(MediumDef::DEFAULT_ALBEDO)))),
            sigma_a: None,
            sigma_s: None,
            scale: scale.map(num),
            phase,
        };
        let base = e.attr("id").unwrap_or("medium").to_string();
        let name = if self.media.contains_key(&base) {
            (2..).map(|i| format!("{base}-{i}")).find(|n| !self.media.contains_key(n)).unwrap_or_default()
        } else {
            base
        };
        self.media.insert(name.clone(), def);
        self.origins.push((ItemPath::root().field("media").field(&name), e.offset));
        self.medium_names.insert(e.offset, name.clone());
        Ok(Some(name))
    }

    /// `<phase type="isotropic"/>` or `<phase type="hg">` with `g` (default 0.8).
    fn phase(&mut self, p: &'a Element) -> R<PhaseDef> {
        let p = self.deref(p)?;
        Ok(match self.req_attr(p, "type")? {
            "isotropic" => PhaseDef::Isotropic,
            "hg" => PhaseDef::Hg { g: Some(num(self.float(p, "g")?.unwrap_or(PhaseDef::DEFAULT_G))) },
            other => {
                self.warn(p, &format!("phase function `{other}` is not supported: using isotropic"));
                PhaseDef::Isotropic
            }
        })
    }
}
