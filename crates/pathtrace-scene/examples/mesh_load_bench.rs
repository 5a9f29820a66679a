//! Mesh loading speed and memory: the Stanford bunny from ../shared/scenes (when present) and a
//! generated binary PLY of about 10 million triangles.
//!
//! ```sh
//! cargo run --release -p pathtrace-scene --example mesh_load_bench [-- TRIANGLES]
//! ```
//!
//! Prints the median of 3 loads of each file and the process's peak resident memory (VmHWM
//! from /proc/self/status, Linux only).

use pathtrace_scene::mesh::load_mesh;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::time::Instant;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let triangles: u64 = match std::env::args().nth(1) {
        Some(arg) => arg.parse()?,
        None => 10_000_000,
    };
    let bunny = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/scenes/bunny/common/meshes/bunny.ply");
    if bunny.is_file() {
        report("bunny.ply", &bunny)?;
    } else {
        println!("bunny.ply: skipped, {} is absent", bunny.display());
    }
    let dir = std::env::temp_dir().join(format!("pathtrace-mesh-bench-{}", std::process::id()));
    std::fs::create_dir_all(&dir)?;
    let path = dir.join("grid.ply");
    let start = Instant::now();
    let written = write_grid(&path, triangles)?;
    println!("generated {written} triangles in {:.2} s, peak RSS so far {}", start.elapsed().as_secs_f64(), peak_rss());
    let outcome = report("grid.ply", &path);
    std::fs::remove_dir_all(&dir)?;
    outcome
}

/// Loads a file three times and prints the median time and the peak memory.
fn report(name: &str, path: &Path) -> Result<(), Box<dyn std::error::Error>> {
    let size = std::fs::metadata(path)?.len();
    let mut times = Vec::new();
    let mut counts = (0, 0);
    for _ in 0..3 {
        let start = Instant::now();
        let parts = load_mesh(path)?;
        times.push(start.elapsed().as_secs_f64());
        counts = (parts[0].1.positions.len(), parts[0].1.indices.len());
    }
    times.sort_by(f64::total_cmp);
    println!(
        "{name}: {:.1} MB, {} vertices, {} triangles: median load {:.3} s (runs {:.3?}), peak RSS {}",
        size as f64 / 1e6,
        counts.0,
        counts.1,
        times[1],
        times,
        peak_rss()
    );
    Ok(())
}

/// Writes an n×n grid of quads (two triangles each) as a little-endian binary PLY with float
/// positions and uchar/int face lists; returns the triangle count.
fn write_grid(path: &PathBuf, triangles: u64) -> std::io::Result<u64> {
    let n = ((triangles as f64 / 2.0).sqrt().ceil() as u32).max(1);
    let row = n + 1;
    let mut out = BufWriter::with_capacity(1 << 20, std::fs::File::create(path)?);
    let vertices = u64::from(row) * u64::from(row);
    let faces = 2 * u64::from(n) * u64::from(n);
    write!(
        out,
        "ply\nformat binary_little_endian 1.0\nelement vertex {vertices}\nproperty float x\nproperty float y\n\
         property float z\nelement face {faces}\nproperty list uchar int vertex_indices\nend_header\n"
    )?;
    for j in 0..row {
        for i in 0..row {
            let (x, z) = (i as f32 / n as f32, j as f32 / n as f32);
            let y = 0.1 * (x * 20.0).sin() * (z * 20.0).cos();
            for c in [x, y, z] {
                out.write_all(&c.to_le_bytes())?;
            }
        }
    }
    for j in 0..n {
        for i in 0..n {
            let a = (j * row + i) as i32;
            let (b, c, d) = (a + 1, a + row as i32 + 1, a + row as i32);
            for tri in [[a, b, c], [a, c, d]] {
                out.write_all(&[3])?;
                for v in tri {
                    out.write_all(&v.to_le_bytes())?;
                }
            }
        }
    }
    out.flush()?;
    Ok(faces)
}

/// Peak resident set size, from /proc/self/status.
fn peak_rss() -> String {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| s.lines().find(|l| l.starts_with("VmHWM:")).map(|l| l["VmHWM:".len()..].trim().to_string()))
        .unwrap_or_else(|| "unknown".to_string())
}
