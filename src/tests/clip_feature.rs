//! The `clip` feature: with it a mesh that reaches behind the near plane or
//! past the guard band is clipped and drawn; without it the draw is refused
//! before any pixel (or depth, or band) is written
//! (`RenderError::NeedsClipping`). A mesh wholly outside what is drawn draws
//! nothing in either build, and a contained one draws the same frame (CI's
//! firmware run checks S1's frame without the feature against the host's
//! with it). CI runs these tests in both builds (`cargo test -p fixshade
//! --lib --no-default-features`).

use core::convert::Infallible;

use embedded_graphics::draw_target::DrawTarget;
use embedded_graphics::prelude::{OriginDimensions, Pixel, Size};
use embedded_graphics::primitives::Rectangle;

use crate::platform;
use crate::prelude::*;
use crate::render::RenderError;

static P: [[i16; 3]; 3] = [[-16384, -16384, 0], [16384, -16384, 0], [0, 16384, 0]];
static N: [PackedNormal; 3] = [PackedNormal::Z; 3];
const MESH: Mesh = Mesh::new(&P, Bounds::cube(2.0), &[[0, 1, 2]]).with_normals(&N);
const W: u32 = 64;
const H: u32 = 48;

/// A draw's pixel count, or its error.
type Drawn = Result<u32, RenderError<Infallible>>;

/// The triangle moved by `model`, seen from `eye` (looking at the origin,
/// near 0.1) into a frame and a depth buffer cleared to 0 and `u16::MAX`,
/// through the vertex cache: the draw's result, the frame, the depth.
fn draw(eye: [f32; 3], model: Mat4) -> (Drawn, Vec<u16>, Vec<u16>) {
    draw_from(
        Camera::look_at(eye, [0.0; 3], [0.0, 1.0, 0.0]).unwrap(),
        model,
    )
}

/// [`draw`] through `camera`.
fn draw_from(camera: Camera, model: Mat4) -> (Drawn, Vec<u16>, Vec<u16>) {
    let sun = DirectionalLight::new([0.0, 0.0, 1.0]).unwrap();
    let material = Material::new();
    let renderer = Renderer::new(&camera, &material, &sun);
    let (mut px, mut z) = (
        vec![0u16; (W * H) as usize],
        vec![u16::MAX; (W * H) as usize],
    );
    let mut cache = [CachedVertex::default(); 3];
    let mut fb = Framebuffer::new(&mut px, W, H).unwrap();
    let mut depth = DepthBuffer::new(&mut z, W, H).unwrap();
    let res = MESH
        .shaded(&renderer)
        .with_model(model)
        .with_depth(&mut depth)
        .with_cache(&mut cache)
        .draw(&mut fb)
        .map(|s| s.pixels);
    (res, px, z)
}

/// The triangle moved `x` units to the right, seen from 6 units away
/// through a vertical field of 10° (at distance `d` the target's half
/// width is `0.1166·d` units, 32 pixels).
fn beside(x: f32) -> (Drawn, Vec<u16>, Vec<u16>) {
    let narrow = Projection::Perspective { fovy_deg: 10.0 };
    let camera = Camera::look_at([0.0, 0.0, 6.0], [0.0; 3], [0.0, 1.0, 0.0]).unwrap();
    let camera = camera.with_projection(narrow, 0.1, 20.0).unwrap();
    draw_from(
        camera,
        Mat4::translation(Vec3::from_f32(x, 0.0, 0.0).unwrap()),
    )
}

/// A target that counts what is written to it.
struct Counting(usize);

impl OriginDimensions for Counting {
    fn size(&self) -> Size {
        Size::new(W, H)
    }
}

impl DrawTarget for Counting {
    type Color = Rgb565;
    type Error = Infallible;
    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(&mut self, p: I) -> Result<(), Infallible> {
        self.0 += p.into_iter().count();
        Ok(())
    }
    fn fill_contiguous<I>(&mut self, _: &Rectangle, c: I) -> Result<(), Infallible>
    where
        I: IntoIterator<Item = Rgb565>,
    {
        self.0 += c.into_iter().count();
        Ok(())
    }
}

#[test]
fn contained_mesh_draws_in_every_build() {
    let (res, px, z) = draw([0.0, 0.0, 3.0], Mat4::IDENTITY);
    let pixels = res.unwrap();
    assert!(pixels > 100, "{pixels}");
    assert_eq!(px.iter().filter(|&&p| p != 0).count() as u32, pixels);
    assert_eq!(z.iter().filter(|&&d| d != u16::MAX).count() as u32, pixels);
}

#[test]
fn mesh_through_the_near_plane_is_clipped_or_refused() {
    // The eye 0.05 in front of the triangle's plane, beside its centre:
    // its box (the cube of side 2) reaches behind the eye.
    let (res, px, z) = draw([0.3, 0.2, 0.05], Mat4::IDENTITY);
    if platform::CLIP {
        assert!(res.unwrap() > 0);
    } else {
        assert_eq!(res, Err(RenderError::NeedsClipping));
        assert!(px.iter().all(|&p| p == 0), "a refused draw wrote pixels");
        assert!(
            z.iter().all(|&d| d == u16::MAX),
            "a refused draw wrote depths"
        );
    }
}

#[test]
fn mesh_across_the_guard_band_is_clipped_or_refused() {
    // 20 units to the right the box (±2, 4 to 8 units away) spans the
    // band's edge, 1 023 pixels from the centre (from 617 to 1 509), and
    // the triangle, 6 units away, lies inside it off the target.
    let (res, px, _) = beside(20.0);
    if platform::CLIP {
        assert_eq!(res, Ok(0), "off the target");
    } else {
        assert_eq!(res, Err(RenderError::NeedsClipping));
    }
    assert!(px.iter().all(|&p| p == 0));
}

#[test]
fn mesh_wholly_outside_draws_nothing_in_every_build() {
    // Past the guard band's right side (40 units to the right, the box's
    // nearest point 1 303 pixels from the centre), and behind the eye.
    for (res, px, z) in [
        beside(40.0),
        draw(
            [0.0, 0.0, -3.0],
            Mat4::translation(Vec3::from_f32(0.0, 0.0, -8.0).unwrap()),
        ),
    ] {
        assert_eq!(res, Ok(0));
        assert!(px.iter().all(|&p| p == 0) && z.iter().all(|&d| d == u16::MAX));
    }
}

#[test]
fn refused_band_draw_sends_nothing() {
    let camera = Camera::look_at([0.3, 0.2, 0.05], [0.0; 3], [0.0, 1.0, 0.0]).unwrap();
    let sun = DirectionalLight::new([0.0, 0.0, 1.0]).unwrap();
    let material = Material::new();
    let renderer = Renderer::new(&camera, &material, &sun);
    let mut target = Counting(0);
    let mut colour = [0u16; (W * 8) as usize];
    let res = MESH
        .shaded(&renderer)
        .draw(&mut Bands::new(&mut target, &mut colour, 8));
    if platform::CLIP {
        assert!(res.is_ok());
        assert_eq!(target.0, (W * H) as usize, "every band sent");
    } else {
        assert_eq!(res.map(|s| s.pixels), Err(RenderError::NeedsClipping));
        assert_eq!(target.0, 0, "a refused draw sent a band");
    }
}

#[test]
fn needs_clipping_reads_in_one_line() {
    let text = RenderError::<Infallible>::NeedsClipping.to_string();
    assert!(text.contains("clip") && !text.contains('\n'), "{text}");
}
