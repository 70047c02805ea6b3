use fixshade::framebuffer::Framebuffer;
use fixshade::render::CachedVertex;
use fixshade::scene_desc::Shading;
use fixshade::scene_kernel::KernelScene;
use fixshade::standard_scenes;

#[inline(never)]
fn frame(k: &KernelScene, px: &mut [u16], depth: &mut [u16], cache: &mut [CachedVertex]) {
    let mut fb = Framebuffer::new(px, 320, 240).unwrap();
    k.render_framebuffer(&mut fb, depth, cache).unwrap();
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let mut d = match args[1].as_str() {
        "s1" => standard_scenes::s1(320, 240),
        "s2" => standard_scenes::s2(320, 240),
        "s3" => standard_scenes::s3(320, 240),
        _ => standard_scenes::s4(320, 240),
    };
    if args.len() > 2 {
        d.shading = match args[2].as_str() {
            "flat" => Shading::Flat,
            "phong" => Shading::Phong,
            _ => Shading::Gouraud,
        };
    }
    let k = KernelScene::new(&d).unwrap();
    let mut px = vec![0u16; 320 * 240];
    let mut depth = vec![0u16; 320 * 240];
    let mut cache = vec![CachedVertex::default(); d.mesh.positions.len()];
    frame(&k, &mut px, &mut depth, &mut cache);
}
