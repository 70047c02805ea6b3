//! Host side: writes a scene as Rust source in the kernel's formats, for
//! firmware that cannot run the `std` scene code.
//!
//! Every value is converted exactly as `fixshade_host::scene_kernel::KernelScene`
//! converts it on the host (the same kernel functions on the same `f64`s;
//! meshes by the host converter, `fixshade_host::mesh_convert`), and written as
//! raw bits or mesh bytes, so the device renders from the very inputs the
//! host renders from.

use std::fmt::Write;

use fixshade::camera::Camera;
use fixshade::color::{Rgb, Shade};
use fixshade::light::{unit_from_f64, Attenuation, SpotCone};
use fixshade::num::WidePoint;
use fixshade::{Exponent, Mat4, Unit3};
use fixshade_host::mesh_convert::MeshData;
use fixshade_host::scene_desc::{self, LightDesc, MeshDesc, SceneDesc, Shading, SpecularModel};

/// A firmware build script's common start: puts the crate's `memory.x` on
/// the linker's path, says what reruns the script, sets
/// `fixshade_explicit_draw` under `FIXSHADE_EXPLICIT=1`, and returns
/// `OUT_DIR`.
pub fn start_build() -> std::path::PathBuf {
    let out = std::path::PathBuf::from(std::env::var_os("OUT_DIR").expect("OUT_DIR"));
    std::fs::copy("memory.x", out.join("memory.x")).expect("memory.x");
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rerun-if-changed=memory.x");
    println!("cargo:rerun-if-changed=../common/codegen.rs");
    println!("cargo:rerun-if-changed=../common/scenes.rs");
    println!("cargo:rerun-if-changed=../../src");
    // FIXSHADE_EXPLICIT=1: the build drawn through the kernel's explicit
    // call (scripts/firmware.sh), whose kernel the kernel's build script
    // builds with the same cfg.
    println!("cargo:rerun-if-env-changed=FIXSHADE_EXPLICIT");
    if std::env::var("FIXSHADE_EXPLICIT").is_ok_and(|v| v == "1") {
        println!("cargo:rustc-cfg=fixshade_explicit_draw");
    }
    out
}

/// `Rgb::from_bits(..)` for a colour in `[0, ∞)`.
pub fn rgb(c: [f64; 3]) -> String {
    let b = Rgb::from_f64(c).expect("colour").to_bits();
    format!("Rgb::from_bits({}, {}, {})", b[0], b[1], b[2])
}

fn unit(u: Unit3) -> String {
    let b = u.to_bits();
    format!("Unit3::new_clamped({}, {}, {})", b[0], b[1], b[2])
}

fn mat4(m: &Mat4) -> String {
    format!("Mat4 {{ m: {:?} }}", m.m)
}

fn wide(p: [f64; 3]) -> String {
    let b = WidePoint::from_f64(p).expect("light position").to_bits();
    format!("WidePoint::from_bits({}, {}, {})", b[0], b[1], b[2])
}

fn attenuation(a: [f64; 3]) -> String {
    let c = Attenuation::from_f64(a)
        .expect("attenuation")
        .coefficients();
    format!(
        "Attenuation::from_bits([{}, {}, {}])",
        c[0].to_bits(),
        c[1].to_bits(),
        c[2].to_bits()
    )
}

/// A light as a constant expression, and its type.
pub fn light(l: &LightDesc) -> (String, &'static str) {
    match l {
        LightDesc::Directional {
            direction,
            diffuse,
            specular,
        } => (
            format!(
                "DirectionalLight::from_unit({}).with_diffuse({}).with_specular({})",
                unit(unit_from_f64(*direction).expect("direction")),
                rgb(*diffuse),
                rgb(*specular)
            ),
            "DirectionalLight",
        ),
        LightDesc::Point {
            position,
            diffuse,
            specular,
            attenuation: a,
        } => (point(*position, *diffuse, *specular, *a), "PointLight"),
        LightDesc::Spot {
            position,
            axis,
            cutoff_deg,
            exponent,
            diffuse,
            specular,
            attenuation: a,
        } => {
            let cone = SpotCone::from_f64(*axis, *cutoff_deg, *exponent).expect("cone");
            (
                format!(
                    "SpotLight {{ light: {}, cone: SpotCone {{ axis: {}, delta_cutoff: {}, exponent: Exponent::from_bits({}) }} }}",
                    point(*position, *diffuse, *specular, *a),
                    unit(cone.axis),
                    cone.delta_cutoff,
                    cone.exponent.to_bits()
                ),
                "SpotLight",
            )
        }
        LightDesc::Area { .. } => panic!("area lights are not used by the firmware scenes"),
    }
}

fn point(p: [f64; 3], d: [f64; 3], s: [f64; 3], a: [f64; 3]) -> String {
    format!(
        "PointLight {{ position: {}, diffuse: {}, specular: {}, attenuation: {} }}",
        wide(p),
        rgb(d),
        rgb(s),
        attenuation(a)
    )
}

/// A scene's mesh in the kernel's flash format, converted by the host
/// converter exactly as `KernelScene::new` converts it (normals derived by
/// the kernel's `vertex_normals` where the description has none).
pub fn mesh_data(m: &MeshDesc) -> MeshData {
    let mut data = MeshData::from_desc(m).expect("mesh");
    data.derive_normals().expect("normals");
    data
}

/// The converter's Rust source for a mesh: `pub static {NAME}` (the
/// `Mesh`) over `{NAME}_POSITIONS`, `{NAME}_NORMALS`, `{NAME}_INDICES`.
pub fn mesh_statics(name: &str, m: &MeshDesc) -> String {
    mesh_data(m).to_rust(name)
}

/// The converter's bytes for a mesh, for `fixshade::include_mesh!`.
pub fn mesh_bytes(m: &MeshDesc) -> Vec<u8> {
    mesh_data(m).to_bytes()
}

/// A scene's set-up in kernel types, as Rust source.
pub struct Setup {
    /// The camera, a constant expression (its projection worked out by
    /// the compiler).
    pub camera: String,
    /// The model matrix.
    pub model: String,
    /// The material, built at run time (`with_specular` is not `const`).
    pub material: String,
    /// The light tuple.
    pub lights: String,
    /// The light tuple's type.
    pub lights_type: String,
    /// `InfiniteViewer` or `LocalViewer`.
    pub viewer: &'static str,
    /// `Flat`, `Gouraud` or `PhongShading`.
    pub shading: &'static str,
    /// `RenderOptions { .. }`.
    pub options: String,
    /// Global ambient.
    pub ambient: String,
    /// Background, raw RGB565.
    pub background: u16,
    /// Whether the scene has a depth test.
    pub depth: bool,
    /// Vertex count.
    pub vertices: usize,
}

/// Converts a scene as `KernelScene::new` and `KernelScene::render` do.
pub fn setup(d: &SceneDesc) -> Setup {
    let c = &d.camera;
    let projection = match c.projection {
        scene_desc::Projection::Perspective { fovy_deg } => format!(
            "Projection::Perspective {{ fovy_deg: f32::from_bits({:#x}) }}",
            (fovy_deg as f32).to_bits()
        ),
        scene_desc::Projection::Orthographic { height } => format!(
            "Projection::Orthographic {{ height: f32::from_bits({:#x}) }}",
            (height as f32).to_bits()
        ),
    };
    let view = Camera::look_at_f64(c.eye, c.target, c.up)
        .expect("camera")
        .view;
    let camera = format!(
        "const {{ match Camera::from_view({}).with_projection({projection}, f32::from_bits({:#x}), f32::from_bits({:#x})) {{ Ok(c) => c, Err(_) => panic!(\"camera\") }} }}",
        mat4(&view),
        (c.near as f32).to_bits(),
        (c.far as f32).to_bits()
    );
    let model = mat4(&Mat4::from_f64(d.model).expect("model"));
    let m = &d.material;
    let mut material = format!(
        "Material::new().with_emission({}).with_ambient({}).with_diffuse({})",
        rgb(m.emission),
        rgb(m.ambient),
        rgb(m.diffuse)
    );
    if !Rgb::from_f64(m.specular).expect("specular").is_black() {
        let kind = match d.specular_model {
            SpecularModel::Blinn => "BlinnPhong",
            SpecularModel::Phong => "Phong",
        };
        let n = Exponent::from_f64(m.shininess)
            .expect("shininess")
            .to_bits();
        let _ = write!(
            material,
            ".with_specular({kind} {{ color: {}, shininess: Exponent::from_bits({n}) }})",
            rgb(m.specular)
        );
    }
    let lights: Vec<(String, &str)> = d.lights.iter().map(light).collect();
    let bg = Shade::from_bits(
        (d.background[0].clamp(0.0, 1.0) * 65536.0 + 0.5) as u32,
        (d.background[1].clamp(0.0, 1.0) * 65536.0 + 0.5) as u32,
        (d.background[2].clamp(0.0, 1.0) * 65536.0 + 0.5) as u32,
    )
    .to_rgb565();
    use embedded_graphics::pixelcolor::raw::{RawData, RawU16};
    Setup {
        camera,
        model,
        material,
        lights: format!(
            "({})",
            lights.iter().map(|l| l.0.clone() + ",").collect::<String>()
        ),
        lights_type: format!(
            "({})",
            lights
                .iter()
                .map(|l| l.1.to_string() + ",")
                .collect::<String>()
        ),
        viewer: match d.viewer {
            scene_desc::Viewer::Infinite => "InfiniteViewer",
            scene_desc::Viewer::Local => "LocalViewer",
        },
        shading: match d.shading {
            Shading::Flat => "Flat",
            Shading::Gouraud => "Gouraud",
            Shading::Phong => "PhongShading",
        },
        options: format!(
            "RenderOptions {{ cull: {}, two_sided: {}, dither: {} }}",
            d.cull, d.two_sided, d.dither
        ),
        ambient: rgb(d.global_ambient),
        background: RawU16::from(bg).into_inner(),
        depth: d.depth,
        vertices: d.mesh.positions.len(),
    }
}

/// The draw of a generated render function, binding `res`: the draw call
/// as a program writes it, or, built with `--cfg fixshade_explicit_draw`,
/// the same draw as one explicit call of the kernel (src/explicit.rs), the
/// baseline scripts/firmware.sh holds the draw call to. Expects `camera`,
/// `material`, `lights` and `mesh` in scope; `output` is the draw's output
/// argument, `depth` the depth test's binding if the scene has one,
/// `cache` the vertex cache's if the draw keeps its vertices.
pub fn draw(c: &Setup, output: &str, depth: Option<&str>, cache: Option<&str>) -> String {
    let with_depth = depth.map_or(String::new(), |d| format!("\n            .with_depth({d})"));
    let with_cache = cache.map_or(String::new(), |v| format!("\n            .with_cache({v})"));
    let depth = depth.unwrap_or("fixshade::depth::NoDepth");
    let cache = cache.map_or("&mut fixshade::band::Recomputed".to_string(), |v| {
        format!("&mut fixshade::band::Cached({v})")
    });
    format!(
        "#[cfg(not(fixshade_explicit_draw))]
    let res = {{
        let r = fixshade::Renderer::new(&camera, &material, &lights)
            .with_ambient({ambient})
            .with_viewer({viewer})
            .with_shading({shading})
            .with_options({options});
        mesh.shaded(&r)
            .with_model({model}){with_depth}{with_cache}
            .draw({output})
    }};
    #[cfg(fixshade_explicit_draw)]
    let res = fixshade::explicit::draw::<{shading}, {viewer}, _, _, _, _, _>(
        &camera,
        &material,
        &lights,
        {ambient},
        {options},
        &mesh,
        {model},
        {depth},
        {cache},
        {output},
    );",
        ambient = c.ambient,
        viewer = c.viewer,
        shading = c.shading,
        options = c.options,
        model = c.model,
    )
}

/// The `use` lines the generated source needs.
pub const PRELUDE: &str = "#[allow(unused_imports)]
use fixshade::camera::{Camera, Projection};
#[allow(unused_imports)]
use fixshade::illumination::{InfiniteViewer, LocalViewer};
#[allow(unused_imports)]
use fixshade::light::{Attenuation, DirectionalLight, PointLight, SpotCone, SpotLight};
#[allow(unused_imports)]
use fixshade::num::WidePoint;
#[allow(unused_imports)]
use fixshade::material::{BlinnPhong, Phong};
#[allow(unused_imports)]
use fixshade::render::{Flat, Gouraud, PhongShading, RenderOptions};
#[allow(unused_imports)]
use fixshade::{Exponent, Mat4, Material, Rgb, Unit3};
";
