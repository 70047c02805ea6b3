//! Host side of the build: writes the standard scenes in kernel formats to
//! `$OUT_DIR/scenes_data.rs` (see firmware/common/codegen.rs), and puts
//! `memory.x` where the linker finds it.

use std::collections::BTreeSet;
use std::fmt::Write as _;
use std::fs;

#[path = "../common/codegen.rs"]
#[allow(dead_code)]
mod codegen;
#[path = "../common/scenes.rs"]
#[allow(dead_code)]
mod scenes;

fn main() {
    let out = codegen::start_build();

    let variants = scenes::variants();
    let mut s = String::from(codegen::PRELUDE);
    let mut meshes = BTreeSet::new();
    for v in &variants {
        if meshes.insert(v.mesh) {
            s.push_str(&codegen::mesh_statics(v.mesh, &v.desc.mesh));
        }
    }
    let mut table = String::new();
    let mut max_vertices = 0;
    for v in &variants {
        let c = codegen::setup(&v.desc);
        max_vertices = max_vertices.max(c.vertices);
        let m = v.mesh.to_uppercase();
        let (w, h) = (v.desc.width, v.desc.height);
        // `DepthBuffer::new` clears the buffer; without a depth test the
        // draw has none (`with_depth` omitted).
        let (depth, depth_arg) = if c.depth {
            (
                format!(
                    "let mut db = DepthBuffer::new(depth, {w}, {h}).map_err(|_| RenderError::DepthTooSmall)?;"
                ),
                Some("&mut db"),
            )
        } else {
            ("let _ = depth;".to_string(), None)
        };
        let _ = write!(
            s,
            "
/// {name}: renders into `fb` ({w} × {h}) after clearing it (and the depth
/// buffer if the scene has a depth test), as the host's `KernelScene` does.
/// Counted between `count::begin` and `count::end`: the renderer's
/// set-up and the draw call.
#[inline(never)]
pub fn render_{name}(fb: &mut Framebuffer, depth: &mut [u16], cache: &mut [CachedVertex]) -> Result<DrawStats, RenderError<Infallible>> {{
    let camera = {camera};
    let material = {material};
    let lights: {lights_type} = {lights};
    let mesh = {m};
    fb.clear(Rgb565::from(RawU16::new({bg})));
    {depth}
    crate::count::begin();
    {draw}
    crate::count::end();
    res
}}
",
            name = v.name,
            camera = c.camera,
            material = c.material,
            lights_type = c.lights_type,
            lights = c.lights,
            bg = c.background,
            draw = codegen::draw(&c, "fb", depth_arg, Some("cache")),
        );
        let _ = writeln!(
            table,
            "    Variant {{ name: \"{0}\", file: \"{0}.bin\\0\", width: {w}, height: {h}, vertices: {1}, render: render_{0} }},",
            v.name, c.vertices
        );
    }
    let _ = write!(
        s,
        "
/// Every frame the firmware renders, standard scenes first.
pub static VARIANTS: [Variant; {}] = [
{table}];

/// The most vertices of any scene (the vertex cache's length).
pub const MAX_VERTICES: usize = {max_vertices};
",
        variants.len()
    );

    // Building blocks of the flash/RAM configurations (src/bin/config.rs):
    // S1's camera and material, its sun, and S4's lamp and spot.
    let s1 = &variants
        .iter()
        .find(|v| v.name == "s1_gouraud")
        .expect("s1")
        .desc;
    let s4 = &variants
        .iter()
        .find(|v| v.name == "s4_phong")
        .expect("s4")
        .desc;
    let c1 = codegen::setup(s1);
    let m = &s1.material;
    let _ = write!(
        s,
        "
/// S1's camera.
pub const S1_CAMERA: Camera = {};
/// S1's material without specular.
pub const S1_MATERIAL: Material = Material::new().with_emission({}).with_ambient({}).with_diffuse({});
/// S1's specular term.
pub const S1_SPECULAR: BlinnPhong = BlinnPhong {{ color: {}, shininess: Exponent::from_bits({}) }};
/// S1's global ambient.
pub const S1_AMBIENT: Rgb = {};
/// S1's sun.
pub const S1_SUN: DirectionalLight = {};
/// S4's point light, moved in front of S1's sphere.
pub const LAMP: PointLight = {};
/// S4's spot, moved in front of S1's sphere.
pub const SPOT: SpotLight = {};
",
        c1.camera,
        codegen::rgb(m.emission),
        codegen::rgb(m.ambient),
        codegen::rgb(m.diffuse),
        codegen::rgb(m.specular),
        fixshade::Exponent::from_f64(m.shininess).expect("n").to_bits(),
        c1.ambient,
        codegen::light(&s1.lights[0]).0,
        codegen::light(&moved(&s4.lights[0], [2.0, 2.0, 2.0])).0,
        codegen::light(&moved(&s4.lights[1], [-2.0, 2.0, 2.0])).0,
    );
    fs::write(out.join("scenes_data.rs"), s).expect("write scenes_data.rs");
}

/// A point or spot light moved to `p` (its spot axis towards the origin).
fn moved(
    l: &fixshade_host::scene_desc::LightDesc,
    p: [f64; 3],
) -> fixshade_host::scene_desc::LightDesc {
    use fixshade_host::scene_desc::LightDesc;
    let mut l = l.clone();
    match &mut l {
        LightDesc::Point { position, .. } => *position = p,
        LightDesc::Spot { position, axis, .. } => {
            *position = p;
            *axis = p.map(|v| -v);
        }
        _ => {}
    }
    l
}
