//! Mitsuba's instancing → native shape groups and instances:
//!
//! ```xml
//! <shape type="shapegroup" id="tree">
//!     <shape type="ply"><string name="filename" value="tree.ply"/></shape>
//! </shape>
//! <shape type="instance">
//!     <ref id="tree"/>
//!     <transform name="to_world"><translate x="4"/></transform>
//! </shape>
//! ```
//!
//! A shape group's shapes become the objects of `[shape_groups.ID]` (an emitter inside one is
//! an error when the scene is built, located at its shape: instanced shapes are not lights);
//! each instance becomes an `[[instances]]` entry naming the group, with its `to_world`.

use super::{Conv, R};
use crate::mitsuba::parse::Element;
use crate::native::model::{GroupDef, InstanceDef};
use crate::native::ItemPath;

impl<'a> Conv<'a, '_> {
    /// `<shape type="shapegroup" id="…">`: its child shapes, kept under the group's id.
    pub(super) fn shapegroup(&mut self, e: &'a Element) -> R<()> {
        let id = self.req_attr(e, "id")?.to_string();
        if self.shape_groups.contains_key(&id) {
            return Err(self.src.error(e.offset_of("id"), format!("shape group `{id}` is defined twice")));
        }
        let at = ItemPath::root().field("shape_groups").field(&id);
        self.origins.push((at.clone(), e.offset));
        // The group's shapes are converted like top-level ones, into their own list.
        let outer_objects = std::mem::take(&mut self.objects);
        let outer_at = std::mem::replace(&mut self.objects_at, at.field("objects"));
        let mut result = Ok(());
        for c in &e.children {
            result = match c.tag.as_str() {
                "shape" if matches!(c.attr("type"), Some("shapegroup" | "instance")) => {
                    Err(self.src.error(c.offset, "a shape group cannot hold shape groups or instances"))
                }
                "shape" => self.shape(c),
                _ => {
                    self.warn(c, &format!("<{}> inside a shape group is ignored", c.tag));
                    Ok(())
                }
            };
            if result.is_err() {
                break;
            }
        }
        let objects = std::mem::replace(&mut self.objects, outer_objects);
        self.objects_at = outer_at;
        result?;
        if objects.is_empty() {
            return Err(self.src.error(e.offset, format!("shape group `{id}` holds no supported shape")));
        }
        self.shape_groups.insert(id, GroupDef { transform: Vec::new(), objects, groups: Vec::new() });
        Ok(())
    }

    /// `<shape type="instance">` with a `<ref id>` to a shape group and a `to_world`.
    pub(super) fn instance(&mut self, e: &'a Element) -> R<()> {
        let refs: Vec<&Element> = e.children.iter().filter(|c| c.tag == "ref").collect();
        let [r] = refs[..] else {
            return Err(self.src.error(e.offset, "an instance needs exactly one <ref id=\"…\"/> to a shape group"));
        };
        let target = self.deref(r)?;
        if target.tag != "shape" || target.attr("type") != Some("shapegroup") {
            return Err(self.src.error(r.offset, "an instance's <ref> must name a <shape type=\"shapegroup\">"));
        }
        let group = self.req_attr(r, "id")?.to_string();
        for c in e.children.iter().filter(|c| c.tag == "bsdf" || c.tag == "emitter") {
            self.warn(c, &format!("<{}> on an instance is ignored (the group's shapes keep their own)", c.tag));
        }
        let transform = self.to_world(e)?;
        let at = ItemPath::root().field("instances").index(self.instances.len());
        self.origins.push((at.clone(), e.offset));
        self.origins.push((at.field("group"), r.offset));
        if let Some(t) = e.children.iter().find(|c| c.tag == "transform" && c.attr("name") == Some("to_world")) {
            for (i, step) in t.children.iter().enumerate() {
                self.origins.push((at.field("transform").index(i), step.offset));
            }
        }
        self.instances.push(InstanceDef { group, transform, material: None });
        Ok(())
    }
}
