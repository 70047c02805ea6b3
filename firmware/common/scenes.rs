//! The scenes the firmware renders, shared by the device's code generator
//! (`firmware/qemu/build.rs`) and the host's reference renderer
//! (`firmware/host`): the standard scenes S1 to S4 at 320 × 240 in their own
//! shading mode, each again in the two other shading modes, S1's
//! sphere seen from inside ([`inside`]) and S1 without culling
//! ([`unculled`]).

use fixshade_host::scene_desc::{SceneDesc, Shading};
use fixshade_host::standard_scenes;

/// One frame the firmware renders.
pub struct Variant {
    /// File name stem (`s1_gouraud` → `s1_gouraud.bin`) and function name.
    pub name: String,
    /// Which mesh (variants of a scene share it).
    pub mesh: &'static str,
    /// The scene.
    pub desc: SceneDesc,
}

/// Every frame, standard ones (the scene's own shading mode) first.
pub fn variants() -> Vec<Variant> {
    let (w, h) = (standard_scenes::WIDTH, standard_scenes::HEIGHT);
    let scenes = [
        ("s1", "sphere48", standard_scenes::s1(w, h)),
        ("s2", "quad", standard_scenes::s2(w, h)),
        ("s3", "sphere192", standard_scenes::s3(w, h)),
        ("s4", "bunny", standard_scenes::s4(w, h)),
    ];
    let name = |s: Shading| match s {
        Shading::Flat => "flat",
        Shading::Gouraud => "gouraud",
        Shading::Phong => "phong",
    };
    let mut out = Vec::new();
    for (id, mesh, desc) in &scenes {
        out.push(Variant {
            name: format!("{id}_{}", name(desc.shading)),
            mesh,
            desc: desc.clone(),
        });
    }
    for (id, mesh, desc) in &scenes {
        for s in [Shading::Flat, Shading::Gouraud, Shading::Phong] {
            if s != desc.shading {
                let mut d = desc.clone();
                d.shading = s;
                out.push(Variant {
                    name: format!("{id}_{}", name(s)),
                    mesh,
                    desc: d,
                });
            }
        }
    }
    out.push(Variant {
        name: "inside_gouraud".into(),
        mesh: "sphere48",
        desc: inside(w, h),
    });
    out.push(Variant {
        name: "unculled_gouraud".into(),
        mesh: "sphere48",
        desc: unculled(w, h),
    });
    out
}

/// S1 with culling off and one side lit: every back face is set up (a
/// positive doubled area, lit as the front) and lost to the depth test
/// behind the front faces, or drawn where none covers it. What runs the
/// lean set-up's triangles of either orientation on the devices (the
/// standard scenes cull theirs, and INSIDE lights both sides, so that its
/// back faces take their own colours).
pub fn unculled(w: u32, h: u32) -> SceneDesc {
    let mut d = standard_scenes::s1(w, h);
    d.cull = false;
    d
}

/// S1's sphere seen from inside with culling off and both sides lit: every
/// triangle the camera sees faces away from it, and the near plane cuts
/// those around the eye. The standard scenes cull their back faces and
/// cross no plane, so this frame is what runs the triangle loop's kept
/// back faces and its hand-over to the rare path (`src/clip.rs`) on the
/// devices.
pub fn inside(w: u32, h: u32) -> SceneDesc {
    let mut d = standard_scenes::s1(w, h);
    d.camera.eye = [0.2, 0.1, 0.95];
    d.cull = false;
    d.two_sided = true;
    d
}

/// What the Cortex-M0 firmware (firmware/microbit, 256 KB of flash, 16 KB
/// of RAM) renders band by band: S1, S2 and S4 in their own shading mode
/// (file names `m0_` and the standard name). S3's mesh (18 721 vertices,
/// 36 480 triangles: 406 KB in the kernel's flash format) does not fit
/// the flash.
pub fn m0_variants() -> Vec<Variant> {
    variants()
        .into_iter()
        .filter(|v| ["s1_gouraud", "s2_gouraud", "s4_phong"].contains(&v.name.as_str()))
        .map(|v| Variant {
            name: format!("m0_{}", v.name),
            ..v
        })
        .collect()
}
