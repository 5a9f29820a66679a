//! The meshes of the public test scenes in ../shared/scenes (skipped when absent).

use pathtrace_scene::mesh::load_mesh;
use std::path::{Path, PathBuf};

/// ../shared/scenes beside the repository, if present.
fn scenes() -> Option<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/scenes");
    if dir.is_dir() {
        Some(dir)
    } else {
        eprintln!("skipped: {} is absent", dir.display());
        None
    }
}

/// Loads one mesh file that must hold a single part; returns (vertices, triangles).
fn counts(path: &Path) -> (usize, usize, bool, bool) {
    let parts = load_mesh(path).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(parts.len(), 1, "{}", path.display());
    let mesh = &parts[0].1;
    mesh.validate().unwrap();
    (mesh.positions.len(), mesh.indices.len(), mesh.normals.is_some(), mesh.uvs.is_some())
}

#[test]
fn stanford_bunny() {
    let Some(dir) = scenes() else { return };
    let path = dir.join("bunny/common/meshes/bunny.ply");
    let parts = load_mesh(&path).unwrap();
    assert_eq!(parts[0].0, "bunny");
    assert_eq!(counts(&path), (35947, 69451, false, false));
}

#[test]
fn teapot() {
    let Some(dir) = scenes() else { return };
    assert_eq!(counts(&dir.join("teapot-simple/meshes/teapot.ply")), (1177, 2256, false, false));
}

#[test]
fn mitsuba_cornell_box_objs() {
    let Some(dir) = scenes() else { return };
    for wall in ["back", "ceiling", "floor", "greenwall", "luminaire", "redwall"] {
        let path = dir.join(format!("cbox/meshes/cbox_{wall}.obj"));
        let parts = load_mesh(&path).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(parts.len(), 1);
        assert_eq!(parts[0].0, "default");
        assert_eq!((parts[0].1.positions.len(), parts[0].1.indices.len()), (4, 2), "{wall}");
    }
    // The classic box's floor lists unused vertices: the part keeps only the four it uses.
    let floor = load_mesh(&dir.join("cbox-classic/common/meshes/cbox/floor.obj")).unwrap();
    assert_eq!((floor[0].1.positions.len(), floor[0].1.indices.len()), (4, 2));
}

#[test]
fn pbrt_scene_plys_with_normals_and_uvs() {
    let Some(dir) = scenes() else { return };
    let models = dir.join("veach-bidir-pbrt/models");
    assert_eq!(counts(&models.join("Mesh000.ply")), (24, 12, false, true));
    let (_, _, normals, uvs) = counts(&models.join("Mesh001.ply"));
    assert!(normals && uvs);
}

#[test]
fn every_shared_mesh_loads() {
    let Some(dir) = scenes() else { return };
    let mut found = 0;
    let mut stack = vec![dir];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                stack.push(path);
            } else if path.extension().is_some_and(|e| e == "obj" || e == "ply") {
                let parts = load_mesh(&path).unwrap_or_else(|e| panic!("{e}"));
                for (name, mesh) in parts {
                    mesh.validate().unwrap_or_else(|e| panic!("{} {name}: {e}", path.display()));
                }
                found += 1;
            }
        }
    }
    assert!(found >= 30, "found only {found} meshes");
}
