//! Value types of the native format for optical constants: an index of refraction given as a
//! number or a medium's name, a named metal, and a microfacet distribution's name. Names are
//! checked while deserialising, so an unknown one is reported at its own position.

use pathtrace::material::{ior_names, metal_names, named_ior, MicrofacetKind};
use serde::de::{self, Deserializer, Visitor};
use serde::{Deserialize, Serialize, Serializer};
use std::fmt;

use super::values::Num;

/// An index of refraction: a positive number, or a name from the engine's table (`water`,
/// `bk7`, `diamond`, … — Mitsuba's names), resolved when read; written back as the number.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ior(pub Num);

impl Serialize for Ior {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        self.0.serialize(s)
    }
}

impl<'de> Deserialize<'de> for Ior {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl Visitor<'_> for V {
            type Value = Ior;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("an index of refraction (a positive number or a name such as \"water\")")
            }
            fn visit_f64<E: de::Error>(self, x: f64) -> Result<Ior, E> {
                match Num::new(x) {
                    Some(n) if x > 0.0 => Ok(Ior(n)),
                    _ => Err(E::custom(format!("an index of refraction must be a positive number, not {x}"))),
                }
            }
            fn visit_i64<E: de::Error>(self, x: i64) -> Result<Ior, E> {
                self.visit_f64(x as f64)
            }
            fn visit_u64<E: de::Error>(self, x: u64) -> Result<Ior, E> {
                self.visit_f64(x as f64)
            }
            fn visit_str<E: de::Error>(self, s: &str) -> Result<Ior, E> {
                named_ior(s).map(|v| Ior(Num::from(v))).ok_or_else(|| {
                    let known = ior_names().collect::<Vec<_>>().join(", ");
                    E::custom(format!("unknown index of refraction `{s}` (known: {known})"))
                })
            }
        }
        d.deserialize_any(V)
    }
}

/// A conductor from the engine's table of metals (Mitsuba's names: `Au`, `Cu`, `Cu2O`, `a-C`,
/// …, and `none` for a perfect mirror).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MetalName(pub &'static str);

impl Serialize for MetalName {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.0)
    }
}

impl MetalName {
    /// The table's entry for `s`, or an error listing the known names.
    pub fn parse(s: &str) -> Result<MetalName, String> {
        metal_names().find(|n| *n == s).map(MetalName).ok_or_else(|| {
            let known = metal_names().collect::<Vec<_>>().join(", ");
            format!("unknown metal `{s}` (known: {known})")
        })
    }
}

impl<'de> Deserialize<'de> for MetalName {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl Visitor<'_> for V {
            type Value = MetalName;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a metal's name (e.g. \"Au\", \"Cu\", \"Al\", \"none\")")
            }
            fn visit_str<E: de::Error>(self, s: &str) -> Result<MetalName, E> {
                MetalName::parse(s).map_err(E::custom)
            }
        }
        d.deserialize_str(V)
    }
}

/// A microfacet distribution by name: `ggx` or `beckmann`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DistributionName(pub MicrofacetKind);

impl Serialize for DistributionName {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.0.name())
    }
}

impl<'de> Deserialize<'de> for DistributionName {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl Visitor<'_> for V {
            type Value = DistributionName;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a microfacet distribution (ggx or beckmann)")
            }
            fn visit_str<E: de::Error>(self, s: &str) -> Result<DistributionName, E> {
                s.parse().map(DistributionName).map_err(E::custom)
            }
        }
        d.deserialize_str(V)
    }
}

/// Surface roughness of a microfacet material: the distribution and its α along the two
/// tangent directions (equal for isotropic roughness).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RoughnessDef {
    pub distribution: MicrofacetKind,
    pub alpha_u: Num,
    pub alpha_v: Num,
}

/// Where a conductor's complex index of refraction comes from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MetalDef {
    /// A named metal from the table.
    Named(MetalName),
    /// Explicit η and k per channel.
    Custom { eta: super::values::Triple, k: super::values::Triple },
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn iors_take_numbers_or_names() {
        assert_eq!(serde_json::from_str::<Ior>("1.33").unwrap().0.get(), 1.33);
        assert!((serde_json::from_str::<Ior>("\"water\"").unwrap().0.get() - 1.333).abs() < 1e-6);
        assert!(serde_json::from_str::<Ior>("\"unobtainium\"").unwrap_err().to_string().contains("unknown index"));
        assert!(serde_json::from_str::<Ior>("0").is_err());
    }

    #[test]
    fn metals_and_distributions_are_checked() {
        assert_eq!(serde_json::from_str::<MetalName>("\"Au\"").unwrap().0, "Au");
        assert!(serde_json::from_str::<MetalName>("\"gold\"").unwrap_err().to_string().contains("unknown metal"));
        assert_eq!(serde_json::from_str::<DistributionName>("\"ggx\"").unwrap().0, MicrofacetKind::Ggx);
        assert!(serde_json::from_str::<DistributionName>("\"phong\"").is_err());
    }
}
