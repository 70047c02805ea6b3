//! Arbitrary bytes → a small scene built with the kernel API → rendered
//! twice (`Shaded::draw` into a counting `DrawTarget`, and into a guarded
//! `Framebuffer` through its fast path), with these properties asserted:
//!
//! * nothing panics or overflows (the callers build with overflow checks);
//! * no pixel outside the target is sent, and the framebuffer's memory
//!   past `width × height` is untouched;
//! * a bad mesh, a mesh without normals shaded smoothly, a short cache or
//!   depth buffer, a too large target and a projection that does not fit
//!   give exactly the documented
//!   `RenderError`, in the documented order, and nothing is drawn;
//! * both paths give the same result and the same pixels, and the number
//!   of pixels sent is the number `DrawStats::pixels` reports.
//!
//! Shared by the `cargo fuzz` target (`fuzz/fuzz_targets/render.rs`, by
//! `#[path]`), `tests/fuzz_regressions.rs` and `tests/properties.rs`.
#![allow(dead_code)]

use core::convert::Infallible;

use embedded_graphics::draw_target::DrawTarget;
use embedded_graphics::geometry::{Dimensions, Point, Size};
use embedded_graphics::pixelcolor::raw::RawU16;
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::RawData;
use embedded_graphics::primitives::{PointsIter, Rectangle};
use embedded_graphics::Pixel;
use fixshade::camera::{Camera, Projection};
use fixshade::depth::DepthBuffer;
use fixshade::framebuffer::Framebuffer;
use fixshade::illumination::{InfiniteViewer, LocalViewer, Viewer};
use fixshade::light::{
    AnyLight, AreaLight, Attenuation, DirectionalLight, PointLight, SpotCone, SpotLight,
};
use fixshade::material::{BlinnPhong, NoSpecular, Phong, Specular};
use fixshade::mesh::{Bounds, Mesh, MeshError, PackedNormal};
use fixshade::num::WidePoint;
use fixshade::render::{
    CachedVertex, DrawStats, Flat, Gouraud, PhongShading, RenderError, RenderOptions, ShadingMode,
    MAX_TARGET_SIDE,
};
use fixshade::vector::normal_matrix;
use fixshade::{Exponent, Mat4, Material, Renderer, Rgb, Unit3, Vec3};
use fixshade_host::mesh_convert::MeshData;
use fixshade_host::scene_desc::MeshDesc;

// ---------------------------------------------------------------------------
// A target that counts
// ---------------------------------------------------------------------------

/// A `DrawTarget` that keeps the last colour written to each pixel, counts
/// writes, and counts (without storing) every write outside its bounding
/// box, which may start anywhere.
pub struct CountingTarget {
    pub origin: Point,
    pub width: u32,
    pub height: u32,
    pub pixels: Vec<u16>,
    pub writes: u64,
    pub outside: u64,
}

impl CountingTarget {
    pub fn new(width: u32, height: u32) -> Self {
        Self::with_origin(Point::zero(), width, height)
    }

    pub fn with_origin(origin: Point, width: u32, height: u32) -> Self {
        CountingTarget {
            origin,
            width,
            height,
            pixels: vec![BACKGROUND; width as usize * height as usize],
            writes: 0,
            outside: 0,
        }
    }

    fn put(&mut self, p: Point, c: Rgb565) {
        self.writes += 1;
        let (x, y) = (
            p.x as i64 - self.origin.x as i64,
            p.y as i64 - self.origin.y as i64,
        );
        if x < 0 || y < 0 || x >= self.width as i64 || y >= self.height as i64 {
            self.outside += 1;
        } else {
            self.pixels[y as usize * self.width as usize + x as usize] =
                RawU16::from(c).into_inner();
        }
    }

    /// Pixels that are not the background.
    pub fn drawn(&self) -> usize {
        self.pixels.iter().filter(|&&p| p != BACKGROUND).count()
    }

    pub fn at(&self, x: u32, y: u32) -> u16 {
        self.pixels[y as usize * self.width as usize + x as usize]
    }
}

/// The colour both targets start with (coverage is judged by write counts,
/// not by this colour, which a scene may also produce).
pub const BACKGROUND: u16 = 0x0841;

impl Dimensions for CountingTarget {
    fn bounding_box(&self) -> Rectangle {
        Rectangle::new(self.origin, Size::new(self.width, self.height))
    }
}

impl DrawTarget for CountingTarget {
    type Color = Rgb565;
    type Error = Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(
        &mut self,
        pixels: I,
    ) -> Result<(), Infallible> {
        for Pixel(p, c) in pixels {
            self.put(p, c);
        }
        Ok(())
    }

    fn fill_contiguous<I: IntoIterator<Item = Rgb565>>(
        &mut self,
        area: &Rectangle,
        colors: I,
    ) -> Result<(), Infallible> {
        let mut colors = colors.into_iter();
        for p in area.points() {
            let c = colors
                .next()
                .expect("fill_contiguous: fewer colours than points");
            self.put(p, c);
        }
        Ok(())
    }

    /// Clearing is not drawing: the pixels take the colour, no write is
    /// counted.
    fn clear(&mut self, c: Rgb565) -> Result<(), Infallible> {
        self.pixels.fill(RawU16::from(c).into_inner());
        Ok(())
    }
}

// ---------------------------------------------------------------------------
// Bytes → values
// ---------------------------------------------------------------------------

/// Reads little-endian values; past the end every read is 0.
pub struct Bytes<'a> {
    data: &'a [u8],
    pos: usize,
}

impl<'a> Bytes<'a> {
    pub fn new(data: &'a [u8]) -> Self {
        Bytes { data, pos: 0 }
    }
    pub fn u8(&mut self) -> u8 {
        let b = self.data.get(self.pos).copied().unwrap_or(0);
        self.pos += 1;
        b
    }
    pub fn u16(&mut self) -> u16 {
        u16::from_le_bytes([self.u8(), self.u8()])
    }
    pub fn u32(&mut self) -> u32 {
        u32::from_le_bytes([self.u8(), self.u8(), self.u8(), self.u8()])
    }
    pub fn u64(&mut self) -> u64 {
        (self.u32() as u64) | ((self.u32() as u64) << 32)
    }
    pub fn i8(&mut self) -> i8 {
        self.u8() as i8
    }
    pub fn bool(&mut self) -> bool {
        self.u8() & 1 != 0
    }
    /// Floats that matter: 0, ±tiny, ±1, ±huge, NaN, ±∞, or a small value
    /// from a signed byte (1/16 steps) scaled by a power of two.
    pub fn f32(&mut self) -> f32 {
        const SPECIAL: [f32; 12] = [
            0.0,
            -0.0,
            1.0,
            -1.0,
            1e-7,
            -1e-7,
            127.9,
            -128.0,
            1e30,
            f32::NAN,
            f32::INFINITY,
            f32::NEG_INFINITY,
        ];
        let tag = self.u8();
        if tag < 24 {
            SPECIAL[tag as usize % SPECIAL.len()]
        } else if tag < 32 {
            f32::from_bits(self.u32())
        } else {
            let v = self.i8() as f32 / 16.0;
            v * (1u32 << (tag % 8)) as f32
        }
    }
    /// A coordinate (`I8F24` raw): mostly a few units, sometimes any value.
    pub fn coord(&mut self) -> i32 {
        match self.u8() % 8 {
            0 => self.u32() as i32,
            1 => [i32::MIN, i32::MAX, 0, 1, -1][self.u8() as usize % 5],
            _ => (self.i8() as i32) << 20, // ±8 in 1/16 steps
        }
    }
}

// ---------------------------------------------------------------------------
// The scene
// ---------------------------------------------------------------------------

/// Which specular term.
#[derive(Clone, Copy, Debug)]
pub enum SpecKind {
    None,
    Blinn,
    Phong,
}

/// A decoded scene: everything a draw call needs, in kernel types.
#[derive(Clone, Debug)]
pub struct Scene {
    pub width: u32,
    pub height: u32,
    pub origin: Point,
    pub camera: Camera,
    pub model: Mat4,
    /// Quantised positions and their box.
    pub positions: Vec<[i16; 3]>,
    pub bounds: Bounds,
    pub normals: Option<Vec<PackedNormal>>,
    pub indices: Vec<[u16; 3]>,
    pub emission: Rgb,
    pub ambient: Rgb,
    pub diffuse: Rgb,
    pub ks: Rgb,
    pub shininess: Exponent,
    pub spec: SpecKind,
    pub local_viewer: bool,
    pub global_ambient: Rgb,
    pub lights: heapless::Vec<AnyLight, 4>,
    pub options: RenderOptions,
    /// 0 flat, 1 Gouraud, 2 Phong.
    pub shading: u8,
    pub depth: bool,
    /// Cache slots short of the vertex count (0: enough).
    pub cache_short: usize,
    /// Depth values short of `width × height` (0: enough).
    pub depth_short: usize,
}

/// The largest `width × height` the decoder makes (memory and time per run).
pub const MAX_PIXELS: u64 = 1 << 17;

fn rgb(b: &mut Bytes) -> Rgb {
    match b.u8() % 4 {
        // Anything up to the clamp (and past it: from_bits clamps).
        0 => Rgb::from_bits(b.u32(), b.u32(), b.u32()),
        // Through the float constructor; errors become a fixed grey.
        1 => Rgb::from_f32(b.f32(), b.f32(), b.f32()).unwrap_or(Rgb::grey_f32(0.5).unwrap()),
        _ => Rgb::from_bits(
            (b.u8() as u32) << 9,
            (b.u8() as u32) << 9,
            (b.u8() as u32) << 9,
        ),
    }
}

fn unit(b: &mut Bytes) -> Unit3 {
    match b.u8() % 4 {
        0 => Unit3::new_clamped(b.u16() as i16, b.u16() as i16, b.u16() as i16),
        1 => Unit3::ZERO,
        _ => fixshade::light::unit_from_f32([b.i8() as f32, b.i8() as f32, b.i8() as f32])
            .unwrap_or(Unit3::Z),
    }
}

/// A normal from the bytes [`unit`] reads: any bits (the third `u16`
/// unused), the zero normal, or a unit direction packed.
fn packed_normal(b: &mut Bytes) -> PackedNormal {
    match b.u8() % 4 {
        0 => {
            let n = PackedNormal::from_bits(b.u16() as i16, b.u16() as i16);
            let _ = b.u16();
            n
        }
        1 => PackedNormal::ZERO,
        _ => {
            let u = fixshade::light::unit_from_f32([b.i8() as f32, b.i8() as f32, b.i8() as f32])
                .unwrap_or(Unit3::Z);
            PackedNormal::from_vector(u.to_bits().map(i32::from))
        }
    }
}

/// Raw `I8F24` coordinates quantised by the host converter (every such
/// coordinate is a position it takes).
fn quantised(points: &[[i32; 3]]) -> (Vec<[i16; 3]>, Bounds) {
    let unit = (1u64 << 24) as f64;
    let desc = MeshDesc {
        positions: points.iter().map(|p| p.map(|c| c as f64 / unit)).collect(),
        normals: None,
        indices: Vec::new(),
    };
    let data = MeshData::from_desc(&desc).expect("I8F24 positions convert");
    (data.positions, data.bounds)
}

fn wide(b: &mut Bytes) -> WidePoint {
    match b.u8() % 4 {
        0 => WidePoint::from_bits(b.u64() as i64, b.u64() as i64, b.u64() as i64),
        1 => WidePoint::from_f32([b.f32(), b.f32(), b.f32()]).unwrap_or_default(),
        _ => WidePoint::from_vec3(Vec3::from_bits(b.coord(), b.coord(), b.coord())),
    }
}

fn attenuation(b: &mut Bytes) -> Attenuation {
    match b.u8() % 4 {
        0 => Attenuation::from_bits([0, 1, 2].map(|_| b.u64())),
        1 => Attenuation::new(b.f32(), b.f32(), b.f32()).unwrap_or(Attenuation::NONE),
        _ => Attenuation::NONE,
    }
}

fn exponent(b: &mut Bytes) -> Exponent {
    match b.u8() % 4 {
        0 => Exponent::from_bits(b.u32()),
        1 => Exponent::from_f32(b.f32()).unwrap_or(Exponent::MAX),
        _ => Exponent::from_int(b.u8() as u16),
    }
}

fn point_light(b: &mut Bytes) -> PointLight {
    PointLight {
        position: wide(b),
        diffuse: rgb(b),
        specular: rgb(b),
        attenuation: attenuation(b),
    }
}

fn light(b: &mut Bytes) -> AnyLight {
    match b.u8() % 4 {
        0 => AnyLight::Directional(
            DirectionalLight::from_unit(unit(b))
                .with_diffuse(rgb(b))
                .with_specular(rgb(b)),
        ),
        1 => AnyLight::Point(point_light(b)),
        2 => {
            let light = point_light(b);
            let cone = if b.bool() {
                SpotCone {
                    axis: unit(b),
                    delta_cutoff: b.u32(),
                    exponent: exponent(b),
                }
            } else {
                SpotCone::new(
                    [b.i8() as f32, b.i8() as f32, b.i8() as f32],
                    b.f32(),
                    b.f32(),
                )
                .unwrap_or(SpotCone {
                    axis: Unit3::Z.neg(),
                    delta_cutoff: 1 << 26,
                    exponent: Exponent::from_int(4),
                })
            };
            AnyLight::Spot(SpotLight { light, cone })
        }
        _ => AnyLight::Area(AreaLight {
            center: wide(b),
            edge_u: wide(b),
            edge_v: wide(b),
            // Up to 5 × 5 samples, and 0 (clamped to 1 by `prepare`): a k
            // the clamp takes to 64 costs 4096 lights per pixel, and made
            // the first run's only slow units (25 s, Phong shading).
            samples_k: b.u8() % 6,
            diffuse: rgb(b),
            specular: rgb(b),
            attenuation: attenuation(b),
        }),
    }
}

fn size(b: &mut Bytes) -> (u32, u32) {
    const SPECIAL: [(u32, u32); 12] = [
        (0, 0),
        (1, 1),
        (0, 7),
        (7, 0),
        (40000, 2),
        (2, 40000),
        (4096, 1),
        (1, 4096),
        (MAX_TARGET_SIDE + 1, 0),
        (0, u32::MAX),
        (65535, 1),
        (3, 1),
    ];
    let tag = b.u8();
    if tag < 32 {
        SPECIAL[tag as usize % SPECIAL.len()]
    } else {
        (1 + b.u8() as u32 % 64, 1 + b.u8() as u32 % 64)
    }
}

fn camera(b: &mut Bytes) -> Camera {
    let tag = b.u8();
    match tag % 4 {
        // Any view matrix, any floats: a projection the camera refuses
        // leaves the default one.
        0 => {
            let c = Camera::from_view(Mat4 {
                m: [[0; 4]; 4].map(|r: [i32; 4]| r.map(|_| b.coord())),
            });
            let p = if b.bool() {
                Projection::Perspective { fovy_deg: b.f32() }
            } else {
                Projection::Orthographic { height: b.f32() }
            };
            c.with_projection(p, b.f32(), b.f32()).unwrap_or(c)
        }
        _ => {
            let eye = [
                b.i8() as f32 / 8.0,
                b.i8() as f32 / 8.0,
                b.i8() as f32 / 8.0,
            ];
            let target = [
                b.i8() as f32 / 8.0,
                b.i8() as f32 / 8.0,
                b.i8() as f32 / 8.0,
            ];
            let up = [b.i8() as f32, b.i8() as f32, b.i8() as f32];
            let proj = if b.bool() {
                Projection::Perspective {
                    fovy_deg: [0.5, 1.0, 30.0, 60.0, 90.0, 170.0, 179.99, b.u8() as f32]
                        [b.u8() as usize % 8],
                }
            } else {
                Projection::Orthographic {
                    height: [1e-3, 0.5, 2.0, 8.0, 100.0, b.u8() as f32 / 4.0][b.u8() as usize % 6],
                }
            };
            let near = [1e-4, 1e-2, 0.1, 0.5, 1.0, b.u8() as f32 / 16.0][b.u8() as usize % 6];
            let far = [0.2, 2.0, 10.0, 100.0, 127.9, b.u8() as f32 / 2.0][b.u8() as usize % 6];
            Camera::look_at(eye, target, up)
                .and_then(|c| c.with_projection(proj, near, far))
                .unwrap_or_else(|_| {
                    Camera::look_at([0.0, 0.0, 3.0], [0.0; 3], [0.0, 1.0, 0.0]).unwrap()
                })
        }
    }
}

fn model(b: &mut Bytes) -> Mat4 {
    match b.u8() % 4 {
        0 => Mat4 {
            m: [[0; 4]; 4].map(|r: [i32; 4]| r.map(|_| b.coord())),
        },
        1 => {
            let s = b.i8() as i32;
            let mut m = Mat4::IDENTITY;
            for k in 0..3 {
                m.m[k][k] = s << 20;
            }
            m
        }
        _ => Mat4::translation(Vec3::from_bits(b.coord(), b.coord(), b.coord())),
    }
}

/// Decodes a scene from arbitrary bytes (every byte string is a scene).
pub fn decode(data: &[u8]) -> Scene {
    let mut b = Bytes::new(data);
    let (width, height) = size(&mut b);
    let origin = if b.u8().is_multiple_of(4) {
        Point::new(b.u16() as i16 as i32, b.u16() as i16 as i32)
    } else {
        Point::zero()
    };
    let camera = camera(&mut b);
    let model = model(&mut b);
    let n = b.u8() as usize % 9;
    let points: Vec<[i32; 3]> = (0..n).map(|_| [b.coord(), b.coord(), b.coord()]).collect();
    let (positions, mut bounds) = quantised(&points);
    let normals = match b.u8() % 4 {
        0 => None,
        // A wrong count now and then: MeshError::NormalCount.
        1 => Some(
            (0..(b.u8() as usize % 9))
                .map(|_| packed_normal(&mut b))
                .collect(),
        ),
        _ => Some((0..n).map(|_| packed_normal(&mut b)).collect()),
    };
    let t = b.u8() as usize % 9;
    let bad = b.u8().is_multiple_of(8);
    let indices: Vec<[u16; 3]> = (0..t)
        .map(|_| {
            [0; 3].map(|_: u16| {
                let i = b.u8() as u16;
                if bad {
                    i // possibly out of range
                } else {
                    i % (n.max(1) as u16)
                }
            })
        })
        .collect();
    let spec = match b.u8() % 3 {
        0 => SpecKind::None,
        1 => SpecKind::Blinn,
        _ => SpecKind::Phong,
    };
    let emission = rgb(&mut b);
    let ambient = rgb(&mut b);
    let diffuse = rgb(&mut b);
    let ks = rgb(&mut b);
    let shininess = exponent(&mut b);
    let global_ambient = rgb(&mut b);
    let mut lights = heapless::Vec::new();
    for _ in 0..b.u8() % 5 {
        let _ = lights.push(light(&mut b));
    }
    let flags = b.u8();
    let options = RenderOptions {
        cull: flags & 1 != 0,
        two_sided: flags & 2 != 0,
        dither: flags & 4 != 0,
    };
    let shading = (flags >> 3) % 3;
    let depth = flags & 32 != 0;
    let local_viewer = flags & 64 != 0;
    let short = b.u8();
    let (cache_short, depth_short) = match short % 16 {
        0 => (1 + short as usize / 16, 0),
        1 => (0, 1 + short as usize / 16),
        _ => (0, 0),
    };
    // Last (so that inputs written before it decode as they did): now and
    // then a box of any bits instead of the converter's.
    if b.u8() % 4 == 3 {
        bounds = Bounds::from_bits([0; 3].map(|_: i32| b.coord()), [0; 3].map(|_: u32| b.u32()));
    }
    // Keep memory and time per run bounded: shrink the other side.
    let (mut width, mut height) = (width, height);
    if width as u64 * height as u64 > MAX_PIXELS {
        if width > height {
            height = (MAX_PIXELS / width.max(1) as u64) as u32;
        } else {
            width = (MAX_PIXELS / height.max(1) as u64) as u32;
        }
    }
    Scene {
        width,
        height,
        origin,
        camera,
        model,
        positions,
        bounds,
        normals,
        indices,
        emission,
        ambient,
        diffuse,
        ks,
        shininess,
        spec,
        local_viewer,
        global_ambient,
        lights,
        options,
        shading,
        depth,
        cache_short,
        depth_short,
    }
}

// ---------------------------------------------------------------------------
// Rendering and the checks
// ---------------------------------------------------------------------------

/// What a checked run gives back.
#[derive(Clone, Debug)]
pub struct Report {
    pub result: Result<DrawStats, RenderError<Infallible>>,
    /// Pixels drawn (written at least once).
    pub drawn: usize,
}

/// The error the renderer must give, by the documented order of checks
/// (`Shaded::draw`: mesh, normals for Gouraud and Phong shading, cache,
/// target size, depth, then, for a target that is not empty, camera and
/// the scene's scale; an empty target draws nothing).
pub fn expected_error(s: &Scene) -> Option<RenderError<Infallible>> {
    let mut mesh = Mesh::new(&s.positions, s.bounds, &s.indices);
    mesh.normals = s.normals.as_deref();
    if let Some(ns) = &s.normals {
        if ns.len() != s.positions.len() {
            return Some(RenderError::Mesh(MeshError::NormalCount));
        }
    }
    for (t, tri) in s.indices.iter().enumerate() {
        for &i in tri {
            if i as usize >= s.positions.len() {
                let e = RenderError::Mesh(MeshError::IndexOutOfRange {
                    triangle: t,
                    index: i,
                });
                assert_eq!(mesh.validate().map_err(RenderError::Mesh), Err(e));
                return Some(e);
            }
        }
    }
    // Gouraud and Phong shading interpolate vertex normals (Flat uses the
    // face's).
    if s.shading != 0 && s.normals.is_none() {
        return Some(RenderError::NoNormals);
    }
    if s.cache_short > 0 && !s.positions.is_empty() {
        return Some(RenderError::CacheTooSmall);
    }
    if s.width > MAX_TARGET_SIDE || s.height > MAX_TARGET_SIDE {
        return Some(RenderError::TargetTooLarge);
    }
    if s.depth && s.depth_short > 0 && s.width > 0 && s.height > 0 {
        return Some(RenderError::DepthTooSmall);
    }
    if s.width == 0 || s.height == 0 {
        return None;
    }
    if let Err(e) = s.camera.projection_for(s.width, s.height) {
        return Some(RenderError::Camera(e));
    }
    if !s.camera.resolves(&s.model, &s.bounds, s.height) {
        return Some(RenderError::SceneTooSmall);
    }
    // The lights (a `heapless::Vec`, even an empty one) read normals.
    if normal_matrix(&s.camera.view.mul(&s.model)).is_none() {
        return Some(RenderError::DegenerateModel);
    }
    None
}

/// Both paths' output of one draw.
struct Drawn {
    target: CountingTarget,
    fb: Vec<u16>,
    res_target: Result<DrawStats, RenderError<Infallible>>,
    res_fb: Result<DrawStats, RenderError<Infallible>>,
}

const GUARD: usize = 64;
const GUARD_VALUE: u16 = 0xDEAD;

fn draw_both<S: Specular, V: Viewer, M: ShadingMode>(
    s: &Scene,
    m: Material<S>,
    viewer: V,
    shading: M,
) -> Drawn {
    let r = Renderer::new(&s.camera, &m, &s.lights)
        .with_ambient(s.global_ambient)
        .with_viewer(viewer)
        .with_shading(shading)
        .with_options(s.options);
    let mut mesh = Mesh::new(&s.positions, s.bounds, &s.indices);
    mesh.normals = s.normals.as_deref();
    let n = s.positions.len();
    let px = s.width as usize * s.height as usize;
    let mut cache = vec![CachedVertex::default(); n.saturating_sub(s.cache_short)];
    let mut target = CountingTarget::with_origin(s.origin, s.width, s.height);
    let mut fb = vec![BACKGROUND; px + GUARD];
    fb[px..].fill(GUARD_VALUE);
    let depth_len = px.saturating_sub(s.depth_short);
    let (res_target, res_fb) = if s.depth {
        let mut d1 = vec![0u16; depth_len];
        let mut d2 = vec![0u16; depth_len];
        // DepthBuffer::new refuses a short buffer; a short one is given as
        // a shorter DepthTest through a smaller declared height.
        let a = with_depth(&mut d1, s, |d| {
            mesh.shaded(&r)
                .with_model(s.model)
                .with_depth(d)
                .with_cache(&mut cache)
                .draw(&mut target)
        });
        let b = with_depth(&mut d2, s, |d| {
            let mut f = Framebuffer::new(&mut fb, s.width, s.height).expect("framebuffer");
            mesh.shaded(&r)
                .with_model(s.model)
                .with_depth(d)
                .with_cache(&mut cache)
                .draw(&mut f)
        });
        (a, b)
    } else {
        let a = mesh
            .shaded(&r)
            .with_model(s.model)
            .with_cache(&mut cache)
            .draw(&mut target);
        let mut f = Framebuffer::new(&mut fb, s.width, s.height).expect("framebuffer");
        let b = mesh
            .shaded(&r)
            .with_model(s.model)
            .with_cache(&mut cache)
            .draw(&mut f);
        (a, b)
    };
    assert!(
        fb[px..].iter().all(|&g| g == GUARD_VALUE),
        "framebuffer written past width × height"
    );
    fb.truncate(px);
    Drawn {
        target,
        fb,
        res_target,
        res_fb,
    }
}

/// A cleared depth buffer over `buf`; where `buf` is short (the scene asks
/// for a short one) it is declared with fewer rows, so the renderer sees a
/// depth test smaller than the target.
fn with_depth<R>(buf: &mut [u16], s: &Scene, f: impl FnOnce(&mut DepthBuffer) -> R) -> R {
    let (w, h) = (s.width, s.height);
    let h = if (buf.len() as u64) < w as u64 * h as u64 {
        (buf.len() as u64 / w.max(1) as u64) as u32
    } else {
        h
    };
    let mut d = DepthBuffer::new(buf, w, h).expect("depth buffer");
    d.clear();
    f(&mut d)
}

fn with_mode<S: Specular, V: Viewer>(s: &Scene, m: Material<S>, viewer: V) -> Drawn {
    match s.shading {
        0 => draw_both(s, m, viewer, Flat),
        1 => draw_both(s, m, viewer, Gouraud),
        _ => draw_both(s, m, viewer, PhongShading),
    }
}

fn with_viewer<S: Specular>(s: &Scene, m: Material<S>) -> Drawn {
    if s.local_viewer {
        with_mode(s, m, LocalViewer)
    } else {
        with_mode(s, m, InfiniteViewer)
    }
}

/// Renders the scene both ways and asserts the properties in the module
/// documentation; panics (with the scene) where one fails.
pub fn check(s: &Scene) -> Report {
    let base = Material::new()
        .with_emission(s.emission)
        .with_ambient(s.ambient)
        .with_diffuse(s.diffuse);
    let d = match s.spec {
        SpecKind::None => with_viewer::<NoSpecular>(s, base),
        SpecKind::Blinn => with_viewer(
            s,
            base.with_specular(BlinnPhong {
                color: s.ks,
                shininess: s.shininess,
            }),
        ),
        SpecKind::Phong => with_viewer(
            s,
            base.with_specular(Phong {
                color: s.ks,
                shininess: s.shininess,
            }),
        ),
    };
    assert_eq!(d.target.outside, 0, "pixels sent outside the target: {s:?}");
    assert_eq!(
        d.res_target, d.res_fb,
        "the DrawTarget and Framebuffer paths disagree: {s:?}"
    );
    match expected_error(s) {
        Some(e) => {
            assert_eq!(d.res_target, Err(e), "wrong error: {s:?}");
            assert_eq!(d.target.writes, 0, "an error draw drew: {s:?}");
        }
        None => {
            let stats = d.res_target.expect("no error expected");
            assert_eq!(
                stats.pixels as u64, d.target.writes,
                "DrawStats::pixels: {s:?}"
            );
            assert_eq!(stats.triangles as usize, s.indices.len());
        }
    }
    assert!(
        d.target.pixels == d.fb,
        "the DrawTarget and Framebuffer paths drew different pixels: {s:?}"
    );
    Report {
        result: d.res_target,
        drawn: d.target.drawn(),
    }
}

/// Decode and check: what the fuzz target runs on each input.
pub fn run(data: &[u8]) -> Report {
    check(&decode(data))
}
