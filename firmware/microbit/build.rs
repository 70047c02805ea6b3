//! Host side of the build: the Cortex-M0 scenes in kernel formats, written
//! to `$OUT_DIR/scene.rs` (firmware/common/codegen.rs); `memory.x`.

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

    let variants = scenes::m0_variants();
    let mut s = String::from(codegen::PRELUDE);
    let mut table = String::new();
    for v in &variants {
        let c = codegen::setup(&v.desc);
        // The mesh as bytes, read in place from flash by `include_mesh!`.
        let file = format!("{}.fxm", v.mesh);
        fs::write(out.join(&file), codegen::mesh_bytes(&v.desc.mesh)).expect("mesh bytes");
        let (depth, depth_arg) = if c.depth {
            (
                "let mut db = fixshade::depth::DepthBand::new(depth);",
                Some("&mut db"),
            )
        } else {
            ("let _ = depth;", None)
        };
        let _ = write!(
            s,
            "
/// Renders `{name}` band by band into `target` (vertices recomputed per band).
#[inline(never)]
pub fn render_{name}(target: &mut super::Stream, colour: &mut [u16], depth: &mut [u16])
    -> Result<fixshade::render::DrawStats, fixshade::render::RenderError<super::StreamError>>
{{
    let camera = {camera};
    let material = {material};
    let lights: {lights_type} = {lights};
    let mesh = fixshade::include_mesh!(concat!(env!(\"OUT_DIR\"), \"/{file}\"))
        .map_err(fixshade::render::RenderError::Mesh)?;
    let mut bands = fixshade::band::Bands::new(target, colour, super::ROWS as u32)
        .with_background(Rgb565::from(RawU16::new({bg})));
    {depth}
    {draw}
    res
}}
",
            name = v.name,
            camera = c.camera,
            material = c.material,
            lights_type = c.lights_type,
            lights = c.lights,
            bg = c.background,
            draw = codegen::draw(&c, "&mut bands", depth_arg, None),
        );
        let _ = writeln!(
            table,
            "    Variant {{ name: \"{0}\", file: \"{0}.bin\\0\", width: {1}, height: {2}, render: render_{0} }},",
            v.name, v.desc.width, v.desc.height
        );
    }
    let _ = write!(
        s,
        "
/// The frames, in order.
pub static VARIANTS: [super::Variant; {}] = [
{table}];
",
        variants.len()
    );
    fs::write(out.join("scene.rs"), s).expect("scene.rs");
}
