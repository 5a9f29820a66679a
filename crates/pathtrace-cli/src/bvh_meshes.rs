//! The generated meshes of `pathtrace bench bvh`: a tessellated sphere, a random triangle soup
//! and the Stanford bunny subdivided to larger counts. Each is a list of triangles' vertices.

use pathtrace::math::Vec3;
use pathtrace::sampling::Pcg32;
use pathtrace::shape::TriangleMesh;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// Which generated mesh.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MeshKind {
    Sphere,
    Soup,
    Bunny,
}

impl MeshKind {
    pub fn name(self) -> &'static str {
        match self {
            MeshKind::Sphere => "sphere",
            MeshKind::Soup => "soup",
            MeshKind::Bunny => "bunny",
        }
    }

    pub fn parse(s: &str) -> Result<Self, String> {
        match s.trim() {
            "sphere" => Ok(MeshKind::Sphere),
            "soup" => Ok(MeshKind::Soup),
            "bunny" => Ok(MeshKind::Bunny),
            other => Err(format!("unknown mesh '{other}' (expected sphere, soup or bunny)")),
        }
    }
}

/// The bunny of the shared Mitsuba scenes, relative to the repository (../shared/scenes).
pub fn bunny_path() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/scenes/bunny/common/meshes/bunny.ply")
}

/// Triangles of a UV sphere of radius 1 with about `n` triangles: `s` stacks and `2s` slices
/// give `2s · 2s − 2 · 2s` triangles (one per cell at the poles), so `s ≈ √(n / 4)`.
pub fn sphere(n: usize) -> Vec<[Vec3; 3]> {
    let stacks = ((n as f64 / 4.0).sqrt().round() as usize).max(2);
    let slices = 2 * stacks;
    let vertex = |i: usize, j: usize| {
        let theta = std::f32::consts::PI * i as f32 / stacks as f32;
        let phi = std::f32::consts::TAU * (j % slices) as f32 / slices as f32;
        Vec3::new(theta.sin() * phi.cos(), theta.cos(), theta.sin() * phi.sin())
    };
    let mut tris = Vec::with_capacity(2 * stacks * slices);
    for i in 0..stacks {
        for j in 0..slices {
            let [a, b, c, d] = [vertex(i, j), vertex(i + 1, j), vertex(i + 1, j + 1), vertex(i, j + 1)];
            if i + 1 < stacks {
                tris.push([a, b, c]);
            }
            if i > 0 {
                tris.push([a, c, d]);
            }
        }
    }
    tris
}

/// `n` random triangles in the unit cube: centres uniform, vertices within `2 n^(−1/3)` (about
/// twice the mean spacing) of their centre, so neighbours overlap as n grows.
pub fn soup(n: usize, seed: u64) -> Vec<[Vec3; 3]> {
    let mut rng = Pcg32::new(seed, 17);
    let size = 2.0 * (n.max(1) as f32).powf(-1.0 / 3.0);
    let mut unit = || Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32());
    (0..n)
        .map(|_| {
            let c = unit();
            [0, 1, 2].map(|_| c + size * (unit() - Vec3::splat(0.5)))
        })
        .collect()
}

/// The bunny, midpoint-subdivided (each triangle into four) until it has at least `n`
/// triangles. `Err` if the file is missing or unreadable.
pub fn bunny(n: usize) -> Result<Vec<[Vec3; 3]>, String> {
    let path = bunny_path();
    let parts = pathtrace_scene::mesh::load_mesh(&path).map_err(|e| e.to_string())?;
    let mut mesh = TriangleMesh::default();
    for (_, part) in parts {
        let base = mesh.positions.len() as u32;
        mesh.positions.extend(part.positions);
        mesh.indices.extend(part.indices.iter().map(|t| t.map(|i| i + base)));
    }
    while mesh.indices.len() < n {
        mesh = subdivide(&mesh);
    }
    Ok(mesh.indices.iter().map(|t| t.map(|i| mesh.positions[i as usize])).collect())
}

/// Loop's topology without its smoothing: a vertex at each edge midpoint (shared by the two
/// triangles of the edge, so the mesh stays watertight), four triangles per triangle.
fn subdivide(mesh: &TriangleMesh) -> TriangleMesh {
    let mut positions = mesh.positions.clone();
    let mut midpoints: HashMap<(u32, u32), u32> = HashMap::new();
    let mut midpoint = |a: u32, b: u32| {
        *midpoints.entry((a.min(b), a.max(b))).or_insert_with(|| {
            positions.push(0.5 * (positions[a as usize] + positions[b as usize]));
            positions.len() as u32 - 1
        })
    };
    let mut indices = Vec::with_capacity(4 * mesh.indices.len());
    for &[a, b, c] in &mesh.indices {
        let (ab, bc, ca) = (midpoint(a, b), midpoint(b, c), midpoint(c, a));
        indices.extend([[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]);
    }
    TriangleMesh { positions, indices, ..Default::default() }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_are_near_the_request() {
        // The pole caps make the sphere 2/s short of 4s² (80 for 100, 960 for 1000).
        for (n, tolerance) in [(100, 0.25), (1000, 0.05), (10_000, 0.05)] {
            let s = sphere(n).len();
            assert!((s as f64 / n as f64 - 1.0).abs() < tolerance, "sphere {n}: {s}");
            assert_eq!(soup(n, 1).len(), n);
        }
        // A sphere's vertices lie on the unit sphere.
        assert!(sphere(500).iter().flatten().all(|p| (p.length() - 1.0).abs() < 1e-5));
    }

    #[test]
    fn subdivision_quadruples_and_keeps_the_surface() {
        let mesh = TriangleMesh {
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z],
            indices: vec![[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]],
            ..Default::default()
        };
        let once = subdivide(&mesh);
        assert_eq!(once.indices.len(), 16);
        // 4 vertices + 6 edge midpoints: shared edges get one vertex.
        assert_eq!(once.positions.len(), 10);
        let area = |m: &TriangleMesh| -> f32 {
            m.indices
                .iter()
                .map(|t| {
                    let [a, b, c] = t.map(|i| m.positions[i as usize]);
                    0.5 * (b - a).cross(c - a).length()
                })
                .sum()
        };
        assert!((area(&once) - area(&mesh)).abs() < 1e-5);
    }
}
