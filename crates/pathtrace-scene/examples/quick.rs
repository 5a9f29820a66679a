use std::sync::Arc;
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let strategy = args.get(1).map(|s| s.parse().unwrap()).unwrap_or_default();
    let spp: u32 = args.get(2).map(|s| s.parse().unwrap()).unwrap_or(16);
    let size: u32 = args.get(3).map(|s| s.parse().unwrap()).unwrap_or(256);
    let loaded = pathtrace_scene::builtin::load("cornell-box").unwrap().unwrap();
    let mut settings = pathtrace::RenderSettings { width: size, height: size, spp, ..Default::default() };
    settings.path.strategy = strategy;
    settings.path.max_depth = 8;
    if std::env::var("DUMP").is_ok() {
        println!("{}", loaded.scene.bvh_dump());
    }
    let out = pathtrace::render(Arc::new(loaded.scene), settings).unwrap();
    let p = out.progress;
    let img = out.film.image();
    let m = img.mean();
    println!(
        "{strategy}: {:.3}s {:.2} Msamples/s {:.2} Mrays/s mean {:.4} {:.4} {:.4} dropped {}",
        p.elapsed.as_secs_f64(),
        p.samples_per_second / 1e6,
        p.rays_per_second / 1e6,
        m.r,
        m.g,
        m.b,
        p.dropped_samples
    );
    let mut buf = format!("P3\n{} {}\n255\n", img.width, img.height);
    for px in &img.pixels {
        let e = |x: f32| (pathtrace::film::tonemap::srgb_encode(x.clamp(0.0, 1.0)) * 255.0 + 0.5) as u8;
        buf += &format!("{} {} {}\n", e(px.r), e(px.g), e(px.b));
    }
    std::fs::write(format!("/tmp/quick_{strategy}.ppm"), buf).unwrap();
}
