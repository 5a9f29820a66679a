//! The native scene model, [`SceneFile`]: what a `.toml` or `.json` scene says, before any
//! geometry is built. One serde model serves both formats; unknown fields are errors everywhere.
//! The field-by-field reference with defaults is docs/scene-format.md.

pub use super::material::{
    EmissionDef, MaterialDef, MaterialKind, MaterialType, NormalDef, NormalPerturbationDef, OpacityDef,
};
pub use super::medium::{MediumDef, MediumType, PhaseDef};
pub use super::object::{GroupDef, MeshNormals, ObjectDef, ShapeDef, ShapeType};
pub use super::optics::{DistributionName, Ior, MetalDef, MetalName, RoughnessDef};
pub use super::texture::{identity_uv, Colour, TextureDef, UvRows};
pub use super::transform::{LookAtDef, TransformStep};
pub use super::values::{FilterName, LightSelectionName, Num, Num3, SamplerName, StrategyName, Triple};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// A whole scene file.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    /// Suggested render settings (command-line options override them).
    #[serde(default)]
    pub render: RenderSection,
    /// The camera (required).
    pub camera: CameraSection,
    /// Materials by name.
    #[serde(default)]
    pub materials: BTreeMap<String, MaterialDef>,
    /// Participating media by name, placed by objects' `interior`/`exterior` and the camera's
    /// `medium`.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub media: BTreeMap<String, MediumDef>,
    /// Top-level objects.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub objects: Vec<ObjectDef>,
    /// Groups of objects sharing a transform.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub groups: Vec<GroupDef>,
    /// Shape groups by name: objects (and nested groups) defined once, in their own space, to
    /// be placed many times by `[[instances]]` without copying their geometry.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub shape_groups: BTreeMap<String, GroupDef>,
    /// Placements of shape groups.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub instances: Vec<InstanceDef>,
    /// Lights that are not surfaces: point and spot lights and the environment (constant or a map).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub lights: Vec<LightDef>,
}

/// `[[instances]]`: one placement of a `[shape_groups.NAME]`.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct InstanceDef {
    /// Name of the shape group placed.
    pub group: String,
    /// Steps applied in order to the whole group (empty: identity).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub transform: Vec<TransformStep>,
    /// A material for every object of the group, instead of their own (must not emit).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub material: Option<String>,
}

/// `[render]`: every field optional; the defaults are the `DEFAULT_*` constants.
#[derive(Clone, Copy, Debug, Default, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct RenderSection {
    /// Image width in pixels (1 to 32768; default 512).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub width: Option<u32>,
    /// Image height in pixels (1 to 32768; default 512, or derived from `camera.aspect`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub height: Option<u32>,
    /// Samples per pixel (at least 1; default 64).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub spp: Option<u32>,
    /// Maximum path segments; -1 (the default) is unlimited.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_depth: Option<i32>,
    /// Path segments after which Russian roulette may end a path (at least 1; default 5).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rr_depth: Option<u32>,
    /// Direction sampling strategy (default `mis`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub strategy: Option<StrategyName>,
    /// Pixel sampler (default `independent`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sampler: Option<SamplerName>,
    /// Random seed (default 0).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub seed: Option<u64>,
    /// Pixel reconstruction filter (default: box of radius 0.5, the pixel itself).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub filter: Option<FilterDef>,
    /// How next-event estimation picks a light: `power` (default) or `uniform`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub light_selection: Option<LightSelectionName>,
}

/// `filter = { type = "tent", radius = 1 }`: a pixel filter sampled by importance.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct FilterDef {
    /// `box`, `tent` or `gaussian`.
    #[serde(rename = "type")]
    pub kind: FilterName,
    /// Half-width in pixels, for `box` (default 0.5) and `tent` (default 1).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub radius: Option<Num>,
    /// Standard deviation in pixels, for `gaussian` (default 0.5; cut off at 4 stddev).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stddev: Option<Num>,
}

/// `[[lights]]`: a light that is not a surface.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(tag = "type", rename_all = "lowercase", deny_unknown_fields)]
pub enum LightDef {
    /// An isotropic point light at `position` with `intensity` in W/sr (seen only by the `mis`
    /// strategy's light sampling).
    Point { position: Num3, intensity: Triple },
    /// A spot light (Mitsuba 3's `spot`): `intensity` in W/sr on its axis, full out to
    /// `beam_width` degrees (default 3/4 of `cutoff_angle`), falling linearly in angle to zero at
    /// `cutoff_angle` degrees (default 20). It sits at the origin of `transform` and points along
    /// its local +z (use a `look_at` step). Seen only by the `mis` strategy's light sampling.
    Spot {
        intensity: Triple,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        cutoff_angle: Option<Num>,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        beam_width: Option<Num>,
        #[serde(default, skip_serializing_if = "Vec::is_empty")]
        transform: Vec<TransformStep>,
    },
    /// A directional light (Mitsuba 3's `directional`): parallel light of `irradiance` W/m²
    /// travelling along `direction`, or without it along the local +z of `transform` (at most one
    /// of the two). Seen only by the `mis` strategy's light sampling.
    Directional {
        irradiance: Triple,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        direction: Option<Num3>,
        #[serde(default, skip_serializing_if = "Vec::is_empty")]
        transform: Vec<TransformStep>,
    },
    /// A constant environment: `radiance` arrives from every direction that leaves the scene.
    Constant { radiance: Triple },
    /// An environment map: a lat-long image (`filename`: EXR, HDR, PFM or PNG, relative to the
    /// scene file) multiplied by `scale` (default 1) and oriented by `transform` (rotations; +y of
    /// the image frame is up), with Mitsuba's `envmap` conventions.
    Envmap {
        filename: String,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        scale: Option<Num>,
        #[serde(default, skip_serializing_if = "Vec::is_empty")]
        transform: Vec<TransformStep>,
    },
}

impl RenderSection {
    /// Default image width.
    pub const DEFAULT_WIDTH: u32 = 512;
    /// Default image height.
    pub const DEFAULT_HEIGHT: u32 = 512;
    /// Default samples per pixel.
    pub const DEFAULT_SPP: u32 = 64;
    /// Default maximum depth (unlimited).
    pub const DEFAULT_MAX_DEPTH: i32 = -1;
    /// Largest accepted width or height.
    pub const MAX_SIZE: u32 = 32768;
}

/// `[camera] type`: how the camera projects the scene.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum ProjectionName {
    /// A pinhole (everything sharp); Mitsuba's `perspective`.
    #[default]
    Perspective,
    /// A thin lens with `aperture_radius` and `focus_distance` (depth of field); Mitsuba's `thinlens`.
    Thinlens,
    /// Parallel rays from a `height`-high view; Mitsuba's `orthographic`.
    Orthographic,
}

/// `[camera]`: a pinhole, thin-lens or orthographic camera.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct CameraSection {
    /// `perspective` (default), `thinlens` or `orthographic`.
    #[serde(default, rename = "type", skip_serializing_if = "Option::is_none")]
    pub projection: Option<ProjectionName>,
    /// Eye position.
    pub look_from: Num3,
    /// Point looked at (centre of the image).
    pub look_at: Num3,
    /// Up direction (default `[0, 1, 0]`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub up: Option<Num3>,
    /// Vertical field of view in degrees, in (0, 180) (default 40).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub vfov: Option<Num>,
    /// Distance to the viewport (default 1; it does not change a pinhole image).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub focal_length: Option<Num>,
    /// Width / height; used only when `render.width` and `render.height` are not both given.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub aspect: Option<Num>,
    /// `thinlens`: radius of the lens disk in scene units (required; 0 is a pinhole).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub aperture_radius: Option<Num>,
    /// `thinlens`: distance from the lens to the plane in focus, along the view direction
    /// (default: the distance from `look_from` to `look_at`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub focus_distance: Option<Num>,
    /// `orthographic`: height of the view in scene units (required); its width follows the
    /// image's aspect.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub height: Option<Num>,
    /// The `[media.NAME]` the camera sits in (default: none, vacuum).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub medium: Option<String>,
}

impl CameraSection {
    /// A pinhole camera at `look_from` looking at `look_at`, every other field at its default.
    pub fn pinhole(look_from: Num3, look_at: Num3) -> Self {
        Self {
            projection: None,
            look_from,
            look_at,
            up: None,
            vfov: None,
            focal_length: None,
            aspect: None,
            aperture_radius: None,
            focus_distance: None,
            height: None,
            medium: None,
        }
    }

    /// Default vertical field of view in degrees.
    pub const DEFAULT_VFOV: f32 = 40.0;
    /// Default focal length.
    pub const DEFAULT_FOCAL_LENGTH: f32 = 1.0;
}
