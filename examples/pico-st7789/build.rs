//! Host side of the build: the sphere, camera, light and material in kernel
//! formats, written to `$OUT_DIR/scene.rs`; `memory.x` for the linker.

use std::fmt::Write as _;
use std::path::PathBuf;
use std::{env, fs};

#[path = "../../firmware/common/codegen.rs"]
#[allow(dead_code)]
mod codegen;

use fixshade_host::scene_desc::LightDesc;

fn main() {
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("OUT_DIR"));
    fs::copy("memory.x", out.join("memory.x")).expect("memory.x");
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rerun-if-changed=memory.x");
    println!("cargo:rerun-if-changed=../../firmware/common/codegen.rs");

    // S1's scene on a square display, a coarser sphere (flat facets show
    // the rotation), a second, coloured light.
    let mut d = fixshade_host::standard_scenes::sphere_scene(240, 240, 24, 12);
    d.lights.push(LightDesc::Directional {
        direction: [-1.0, -0.3, 0.6],
        diffuse: [0.1, 0.2, 0.5],
        specular: [0.0; 3],
    });
    let c = codegen::setup(&d);
    let m = &d.material;
    let mut s = String::from(codegen::PRELUDE);
    s.push_str(&codegen::mesh_statics("sphere", &d.mesh));
    let _ = write!(
        s,
        "
/// The camera.
pub const CAMERA: Camera = {};
/// The material without its specular term.
pub const MATERIAL: Material = Material::new().with_emission({}).with_ambient({}).with_diffuse({});
/// The specular term.
pub const SPECULAR: BlinnPhong = BlinnPhong {{ color: {}, shininess: Exponent::from_bits({}) }};
/// Global ambient.
pub const AMBIENT: Rgb = {};
/// The sun and a blue fill light.
pub const LIGHTS: (DirectionalLight, DirectionalLight) = {};
",
        c.camera,
        codegen::rgb(m.emission),
        codegen::rgb(m.ambient),
        codegen::rgb(m.diffuse),
        codegen::rgb(m.specular),
        fixshade::Exponent::from_f64(m.shininess)
            .expect("n")
            .to_bits(),
        c.ambient,
        c.lights,
    );
    fs::write(out.join("scene.rs"), s).expect("scene.rs");
}
