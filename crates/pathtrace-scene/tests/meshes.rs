//! OBJ and PLY loading: every feature on small hand-written files, the meshes in
//! ../shared/scenes when present, and a corpus of truncated and mutated files that must never
//! panic.

mod common;
#[path = "meshes/files.rs"]
mod files;
#[path = "meshes/fuzz.rs"]
mod fuzz;
#[path = "meshes/obj.rs"]
mod obj;
#[path = "meshes/ply.rs"]
mod ply;
