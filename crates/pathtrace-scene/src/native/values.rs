//! The small value types of the native format: finite numbers, "a number or three numbers",
//! and the names of render strategies and samplers. Each rejects bad input while it is being
//! deserialised, so the error carries the location of the offending value.

use pathtrace::integrator::Strategy;
use pathtrace::light::LightSelection;
use pathtrace::math::{Rgb, Vec3};
use pathtrace::sampling::SamplerKind;
use serde::de::{self, Deserializer, SeqAccess, Visitor};
use serde::{Deserialize, Serialize, Serializer};
use std::fmt;

/// A finite number that also fits in an `f32` (the engine's precision). NaN, ±∞ and numbers
/// beyond ±3.4·10³⁸ are rejected.
#[derive(Clone, Copy, Debug, PartialEq, PartialOrd)]
pub struct Num(f64);

impl Num {
    /// Wraps `x` if it is finite and fits in an `f32`.
    pub fn new(x: f64) -> Option<Self> {
        (x.is_finite() && x.abs() <= f32::MAX as f64).then_some(Num(x))
    }

    /// The value in full precision.
    pub fn get(self) -> f64 {
        self.0
    }

    /// The value at the engine's precision.
    pub fn f32(self) -> f32 {
        self.0 as f32
    }

    fn checked<E: de::Error>(x: f64) -> Result<Self, E> {
        Num::new(x).ok_or_else(|| {
            let what = if x.is_nan() { "NaN".to_string() } else { format!("{x}") };
            E::custom(format!("{what} is not allowed here: numbers must be finite and within ±3.4e38"))
        })
    }
}

impl From<f32> for Num {
    fn from(x: f32) -> Self {
        Num::new(x as f64).unwrap_or(Num(0.0))
    }
}

impl Serialize for Num {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_f64(self.0)
    }
}

struct NumVisitor;

impl Visitor<'_> for NumVisitor {
    type Value = Num;
    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a number")
    }
    fn visit_f64<E: de::Error>(self, x: f64) -> Result<Num, E> {
        Num::checked(x)
    }
    fn visit_i64<E: de::Error>(self, x: i64) -> Result<Num, E> {
        Num::checked(x as f64)
    }
    fn visit_u64<E: de::Error>(self, x: u64) -> Result<Num, E> {
        Num::checked(x as f64)
    }
}

impl<'de> Deserialize<'de> for Num {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(NumVisitor)
    }
}

/// Three numbers: a point, a vector or a colour.
pub type Num3 = [Num; 3];

/// Converts three numbers to the engine's vector.
pub fn vec3(v: &Num3) -> Vec3 {
    Vec3::new(v[0].f32(), v[1].f32(), v[2].f32())
}

/// A colour or a scale: either one number for all three channels/axes, or `[x, y, z]`.
/// The written form is kept, so files round-trip as they were written.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Triple {
    /// One number used three times.
    Splat(Num),
    /// Three numbers.
    Each(Num3),
}

impl Triple {
    /// One, three times: the neutral factor.
    pub const ONE: Triple = Triple::Splat(Num(1.0));

    /// The three numbers as a vector.
    pub fn vec3(&self) -> Vec3 {
        match self {
            Triple::Splat(n) => Vec3::splat(n.f32()),
            Triple::Each(v) => vec3(v),
        }
    }

    /// The three numbers as an RGB colour.
    pub fn rgb(&self) -> Rgb {
        let v = self.vec3();
        Rgb::new(v.x, v.y, v.z)
    }
}

impl Serialize for Triple {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            Triple::Splat(n) => n.serialize(s),
            Triple::Each(v) => v.serialize(s),
        }
    }
}

pub(super) struct TripleVisitor;

impl<'de> Visitor<'de> for TripleVisitor {
    type Value = Triple;
    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a number or an array of three numbers")
    }
    fn visit_f64<E: de::Error>(self, x: f64) -> Result<Triple, E> {
        NumVisitor.visit_f64(x).map(Triple::Splat)
    }
    fn visit_i64<E: de::Error>(self, x: i64) -> Result<Triple, E> {
        NumVisitor.visit_i64(x).map(Triple::Splat)
    }
    fn visit_u64<E: de::Error>(self, x: u64) -> Result<Triple, E> {
        NumVisitor.visit_u64(x).map(Triple::Splat)
    }
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Triple, A::Error> {
        let mut v = [Num(0.0); 3];
        for (i, slot) in v.iter_mut().enumerate() {
            *slot = seq.next_element()?.ok_or_else(|| de::Error::invalid_length(i, &"three numbers"))?;
        }
        if seq.next_element::<de::IgnoredAny>()?.is_some() {
            return Err(de::Error::invalid_length(4, &"three numbers"));
        }
        Ok(Triple::Each(v))
    }
}

impl<'de> Deserialize<'de> for Triple {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(TripleVisitor)
    }
}

/// Serde support for a type named by a string through `FromStr` and a `name()`.
macro_rules! named_choice {
    ($(#[$doc:meta])* $wrapper:ident, $inner:ty, $what:literal) => {
        $(#[$doc])*
        #[derive(Clone, Copy, Debug, PartialEq, Eq)]
        pub struct $wrapper(pub $inner);

        impl Serialize for $wrapper {
            fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                s.serialize_str(self.0.name())
            }
        }

        impl<'de> Deserialize<'de> for $wrapper {
            fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
                struct V;
                impl Visitor<'_> for V {
                    type Value = $wrapper;
                    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                        f.write_str($what)
                    }
                    fn visit_str<E: de::Error>(self, s: &str) -> Result<$wrapper, E> {
                        s.parse::<$inner>().map($wrapper).map_err(E::custom)
                    }
                }
                d.deserialize_str(V)
            }
        }
    };
}

named_choice!(
    /// A path-sampling strategy by name: `mis`, `mis-balance`, `bsdf`, `mixture` or `light`.
    StrategyName,
    Strategy,
    "a strategy name (mis, mis-balance, bsdf, mixture or light)"
);
named_choice!(
    /// A pixel sampler by name: `independent`, `stratified` or `sobol`.
    SamplerName,
    SamplerKind,
    "a sampler name (independent, stratified or sobol)"
);

named_choice!(
    /// A light selection by name: `power` or `uniform`.
    LightSelectionName,
    LightSelection,
    "a light selection (power or uniform)"
);

/// The pixel filters by name: `box`, `tent` or `gaussian`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum FilterName {
    Box,
    Tent,
    Gaussian,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_must_be_finite_and_fit_in_f32() {
        assert!(serde_json::from_str::<Num>("1e39").is_err());
        assert!(toml::from_str::<std::collections::BTreeMap<String, Num>>("x = nan").is_err());
        assert!(toml::from_str::<std::collections::BTreeMap<String, Num>>("x = -inf").is_err());
        assert_eq!(serde_json::from_str::<Num>("2").unwrap().get(), 2.0);
    }

    #[test]
    fn triples_accept_one_or_three_numbers() {
        assert_eq!(serde_json::from_str::<Triple>("0.5").unwrap().vec3(), Vec3::splat(0.5));
        assert_eq!(serde_json::from_str::<Triple>("[1, 2, 3]").unwrap().vec3(), Vec3::new(1.0, 2.0, 3.0));
        assert!(serde_json::from_str::<Triple>("[1, 2]").is_err());
        assert!(serde_json::from_str::<Triple>("[1, 2, 3, 4]").is_err());
        assert!(serde_json::from_str::<Triple>("\"red\"").is_err());
    }

    #[test]
    fn strategy_and_sampler_names_parse() {
        assert_eq!(serde_json::from_str::<StrategyName>("\"bsdf\"").unwrap().0, Strategy::Bsdf);
        assert_eq!(serde_json::from_str::<SamplerName>("\"stratified\"").unwrap().0, SamplerKind::Stratified);
        assert_eq!(serde_json::from_str::<SamplerName>("\"sobol\"").unwrap().0, SamplerKind::Sobol);
        assert!(serde_json::from_str::<SamplerName>("\"halton\"").is_err());
    }
}
