//! The `clip` feature: with it a mesh that reaches behind the near plane is
//! clipped and drawn; without it the draw is refused before any pixel is
//! written (`RenderError::NeedsClipping`), and a contained mesh draws the
//! same frame either way. CI runs these tests in both builds
//! (`cargo test -p fixshade --lib --no-default-features`).

use crate::platform;
use crate::prelude::*;
use crate::render::RenderError;

static P: [[i16; 3]; 3] = [[-16384, -16384, 0], [16384, -16384, 0], [0, 16384, 0]];
static N: [PackedNormal; 3] = [PackedNormal::Z; 3];
const MESH: Mesh = Mesh::new(&P, Bounds::cube(2.0), &[[0, 1, 2]]).with_normals(&N);

/// A draw's pixel count, or its error.
type Drawn = Result<u32, RenderError<core::convert::Infallible>>;

/// The frame of the triangle seen from `eye` (looking at the origin, near
/// 0.1), cleared to 0, with the draw's result.
fn draw(eye: [f32; 3]) -> (Drawn, Vec<u16>) {
    let camera = Camera::look_at(eye, [0.0; 3], [0.0, 1.0, 0.0]).unwrap();
    let sun = DirectionalLight::new([0.0, 0.0, 1.0]).unwrap();
    let material = Material::new();
    let renderer = Renderer::new(&camera, &material, &sun);
    let mut px = vec![0u16; 64 * 48];
    let mut fb = Framebuffer::new(&mut px, 64, 48).unwrap();
    let res = MESH.shaded(&renderer).draw(&mut fb).map(|s| s.pixels);
    (res, px)
}

#[test]
fn contained_mesh_draws_in_every_build() {
    let (res, px) = draw([0.0, 0.0, 3.0]);
    let pixels = res.unwrap();
    assert!(pixels > 100, "{pixels}");
    assert_eq!(px.iter().filter(|&&p| p != 0).count() as u32, pixels);
}

#[test]
fn mesh_through_the_near_plane_is_clipped_or_refused() {
    // The eye 0.05 in front of the triangle's plane, beside its centre:
    // its box (the cube of side 2) reaches behind the eye.
    let (res, px) = draw([0.3, 0.2, 0.05]);
    if platform::CLIP {
        assert!(res.unwrap() > 0);
    } else {
        assert_eq!(res, Err(RenderError::NeedsClipping));
        assert!(px.iter().all(|&p| p == 0), "a refused draw wrote pixels");
    }
}
