//! Host side of the build: the Cortex-M0 scene in kernel formats, written
//! to `$OUT_DIR/scene.rs` (firmware/common/codegen.rs); `memory.x`.

use std::fmt::Write as _;
use std::path::PathBuf;
use std::{env, fs};

#[path = "../common/codegen.rs"]
#[allow(dead_code)]
mod codegen;
#[path = "../common/scenes.rs"]
#[allow(dead_code)]
mod scenes;

fn main() {
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("OUT_DIR"));
    fs::copy("memory.x", out.join("memory.x")).expect("memory.x");
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rerun-if-changed=memory.x");
    println!("cargo:rerun-if-changed=../common/codegen.rs");
    println!("cargo:rerun-if-changed=../common/scenes.rs");
    println!("cargo:rerun-if-changed=../../src");

    let v = scenes::m0_variants().remove(0);
    let c = codegen::setup(&v.desc);
    assert!(c.depth, "the band renderer here relies on the depth test");
    let mut s = String::from(codegen::PRELUDE);
    s.push_str(&codegen::mesh_statics("mesh", &v.desc.mesh));
    let _ = write!(
        s,
        "
/// File the frame goes to (NUL-terminated).
pub const FILE: &str = \"{name}.bin\\0\";
/// Frame size.
pub const WIDTH: u32 = {w};
/// Frame size.
pub const HEIGHT: u32 = {h};
/// Background, raw RGB565.
pub const BACKGROUND: u16 = {bg};

/// Renders the scene with depth test `D` into `target`.
#[inline(never)]
pub fn render<T, D>(target: &mut T, depth: &mut D, cache: &mut [fixshade::render::CachedVertex])
    -> Result<fixshade::render::DrawStats, fixshade::render::RenderError<T::Error>>
where
    T: embedded_graphics::draw_target::DrawTarget<Color = embedded_graphics::pixelcolor::Rgb565>,
    D: fixshade::depth::DepthTest,
{{
    let camera = {camera};
    let material = {material};
    let lights: {lights_type} = {lights};
    let mesh = fixshade::mesh::Mesh::new(&MESH_P, &MESH_I).with_normals(&MESH_N);
    let r = fixshade::render::Renderer::<_, {viewer}, _>::new(&camera, {model}, &material, {ambient}, &lights, {options});
    r.draw::<{shading}, _, _>(&mesh, target, depth, cache)
}}
",
        name = v.name,
        w = v.desc.width,
        h = v.desc.height,
        bg = c.background,
        camera = c.camera,
        material = c.material,
        lights_type = c.lights_type,
        lights = c.lights,
        viewer = c.viewer,
        model = c.model,
        ambient = c.ambient,
        options = c.options,
        shading = c.shading,
    );
    fs::write(out.join("scene.rs"), s).expect("scene.rs");
}
