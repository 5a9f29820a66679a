//! Named indices of refraction, usable wherever a scene gives an IOR.
//!
//! The values and names are those of Mitsuba 3's table (`include/mitsuba/render/ior.h`,
//! standard handbook values at ~589 nm), so imported scenes mean the same thing; `glass`
//! and `acrylic` are our short aliases for `bk7` and `acrylic glass`.

const NAMED: &[(&str, f32)] = &[
    ("vacuum", 1.0),
    ("helium", 1.000036),
    ("hydrogen", 1.000132),
    ("air", 1.000277),
    ("carbon dioxide", 1.00045),
    ("water", 1.3330),
    ("acetone", 1.36),
    ("ethanol", 1.361),
    ("carbon tetrachloride", 1.461),
    ("glycerol", 1.4729),
    ("benzene", 1.501),
    ("silicone oil", 1.52045),
    ("bromine", 1.661),
    ("water ice", 1.31),
    ("fused quartz", 1.458),
    ("pyrex", 1.470),
    ("acrylic glass", 1.49),
    ("polypropylene", 1.49),
    ("bk7", 1.5046),
    ("sodium chloride", 1.544),
    ("amber", 1.55),
    ("pet", 1.5750),
    ("diamond", 2.419),
    ("glass", 1.5046),
    ("acrylic", 1.49),
];

/// The index of refraction of a named medium (case-insensitive), or `None`.
pub fn named_ior(name: &str) -> Option<f32> {
    let name = name.trim().to_ascii_lowercase();
    NAMED.iter().find(|(n, _)| *n == name).map(|(_, v)| *v)
}

/// Every accepted name.
pub fn ior_names() -> impl Iterator<Item = &'static str> {
    NAMED.iter().map(|(n, _)| *n)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_resolve_case_insensitively() {
        assert_eq!(named_ior("Water"), Some(1.333));
        assert_eq!(named_ior("glass"), named_ior("bk7"));
        assert_eq!(named_ior("unobtainium"), None);
        assert!(ior_names().all(|n| named_ior(n).is_some_and(|v| v >= 1.0)));
    }
}
