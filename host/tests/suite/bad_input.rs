//! Bad input: every float constructor given NaN, ±∞, negative,
//! zero-length or out-of-range values returns its documented error (or
//! its documented clamp), and a draw given a bad mesh, a short
//! cache or depth buffer, a too large target or a projection that does not
//! fit returns the documented `RenderError` and draws nothing. Nothing
//! panics.

use crate::fuzz_scene;

use embedded_graphics::draw_target::DrawTarget;
use embedded_graphics::geometry::Dimensions;
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::{Point, RgbColor, Size};
use embedded_graphics::primitives::Rectangle;
use embedded_graphics::Pixel;
use fixshade::band::Bands;
use fixshade::camera::{Camera, CameraError, Projection};
use fixshade::depth::DepthBuffer;
use fixshade::framebuffer::Framebuffer;
use fixshade::light::{
    unit_from_f32, unit_from_f64, AreaLight, Attenuation, DirectionalLight, LightError, PointLight,
    SpotCone, SpotLight,
};
use fixshade::material::NoSpecular;
use fixshade::mesh::{face_normal, vertex_normals, Bounds, Mesh, MeshError, PackedNormal};
use fixshade::num::WidePoint;
use fixshade::render::{CachedVertex, Flat, Gouraud, PhongShading, RenderError, MAX_TARGET_SIDE};
use fixshade::vector::FormatError;
use fixshade::{Exponent, Mat4, Material, Renderer, Rgb, Unit3, Vec3};
use fixshade_host::scene_desc::{CameraDesc, LightDesc, MeshDesc, SceneDesc};
use fixshade_host::scene_kernel::KernelScene;
use fuzz_scene::CountingTarget;

/// The triangle (−1, −1, 0), (1, −1, 0), (0, 1, 0), exactly: in the box
/// [−2, 2)³, where `q = ±16384` is ±1.
const TRIANGLE: [[i16; 3]; 3] = [[-16384, -16384, 0], [16384, -16384, 0], [0, 16384, 0]];
const BOX2: Bounds = Bounds::from_bits([0; 3], [2 << 24; 3]);
const NON_FINITE: [f32; 3] = [f32::NAN, f32::INFINITY, f32::NEG_INFINITY];

#[test]
fn positions_and_matrices() {
    for bad in NON_FINITE {
        for k in 0..3 {
            let mut v = [1.0f32; 3];
            v[k] = bad;
            assert_eq!(
                Vec3::from_f32(v[0], v[1], v[2]),
                Err(FormatError::NotFinite)
            );
            assert_eq!(
                Vec3::from_f64(v.map(f64::from)),
                Err(FormatError::NotFinite)
            );
        }
        let mut m = [[0.0f32; 4]; 4];
        m[2][3] = bad;
        assert_eq!(Mat4::from_f32(m), Err(FormatError::NotFinite));
    }
    for out in [128.0, -128.0001, 1e6, -1e30, f32::MAX] {
        assert_eq!(
            Vec3::from_f32(out, 0.0, 0.0),
            Err(FormatError::OutOfRange),
            "{out}"
        );
    }
    // The range's edges: −128 is in, 128 is not.
    assert!(Vec3::from_f32(-128.0, 127.99, 0.0).is_ok());
    assert!(Vec3::from_f32(-0.0, 0.0, 1e-30).is_ok());
}

#[test]
fn normals_and_directions() {
    // Zero length: an error from the float constructor ...
    assert_eq!(unit_from_f32([0.0; 3]), Err(LightError::ZeroDirection));
    assert_eq!(unit_from_f32([-0.0; 3]), Err(LightError::ZeroDirection));
    for bad in NON_FINITE {
        assert_eq!(unit_from_f32([1.0, bad, 0.0]), Err(LightError::NotFinite));
        assert_eq!(
            DirectionalLight::new([bad, 0.0, 1.0]),
            Err(LightError::NotFinite)
        );
    }
    assert_eq!(
        DirectionalLight::new([0.0; 3]),
        Err(LightError::ZeroDirection)
    );
    // ... but any non-zero finite length works, tiny or huge.
    for v in [
        [1e-300, 0.0, 0.0],
        [f64::MIN_POSITIVE, -f64::MIN_POSITIVE, 0.0],
        [1e300, 1e300, -1e300],
        [f64::MAX, f64::MAX, f64::MAX],
        [5e-324, 0.0, 0.0],
    ] {
        let u = unit_from_f64(v).unwrap_or_else(|e| panic!("{v:?}: {e}"));
        let b = u.to_bits().map(|c| c as i64);
        let len2 = b[0] * b[0] + b[1] * b[1] + b[2] * b[2];
        assert!((len2 - (1 << 28)).abs() < 1 << 16, "{v:?}: {b:?}");
    }
    // A degenerate face has no normal; vertex normals of a mesh made only
    // of degenerate faces are zero (lit by E + A·Ka only).
    let v = Vec3::from_bits(5, 5, 5);
    assert_eq!(face_normal(v, v, v), None);
    let p = [[5i16; 3]; 3];
    let mesh = |i| Mesh::new(&p, Bounds::UNIT, i);
    let (mut sums, mut out) = ([[0i32; 3]; 3], [PackedNormal::X; 3]);
    vertex_normals(&mesh(&[[0, 1, 2]]), &mut sums, &mut out).unwrap();
    assert_eq!(out, [PackedNormal::ZERO; 3]);
    // So does a box of zero extent, and one of any bits: no panic, a
    // degenerate box's faces are degenerate.
    let flat = Mesh::new(&TRIANGLE, Bounds::from_bits([7; 3], [0; 3]), &[[0, 1, 2]]);
    vertex_normals(&flat, &mut sums, &mut out).unwrap();
    assert_eq!(out, [PackedNormal::ZERO; 3]);
    let wild = Bounds::from_bits([i32::MIN, i32::MAX, -1], [u32::MAX, 1, u32::MAX]);
    vertex_normals(
        &Mesh::new(&TRIANGLE, wild, &[[0, 1, 2]]),
        &mut sums,
        &mut out,
    )
    .unwrap();
    assert!(out.iter().all(|n| *n != PackedNormal::ZERO));
    assert_eq!(
        vertex_normals(&mesh(&[[0, 1, 2]]), &mut sums[..2], &mut out),
        Err(MeshError::BufferTooSmall)
    );
    assert_eq!(
        vertex_normals(&mesh(&[[0, 1, 3]]), &mut sums, &mut out),
        Err(MeshError::IndexOutOfRange {
            triangle: 0,
            index: 3
        })
    );
    // Raw normals past ±1 are clamped by the only constructor.
    assert_eq!(
        Unit3::new_clamped(i16::MAX, i16::MIN, 3).to_bits(),
        [1 << 14, -(1 << 14), 3]
    );
}

#[test]
fn colours_shininess_and_coefficients() {
    for bad in NON_FINITE {
        assert_eq!(Rgb::from_f32(bad, 0.0, 0.0), Err(FormatError::NotFinite));
        assert_eq!(Rgb::grey_f32(bad), Err(FormatError::NotFinite));
        assert_eq!(Exponent::from_f32(bad), Err(FormatError::NotFinite));
        assert_eq!(Attenuation::new(1.0, bad, 0.0), Err(LightError::NotFinite));
    }
    for neg in [-1.0, -1e-30, -f32::MAX] {
        assert_eq!(Rgb::from_f32(0.5, neg, 0.5), Err(FormatError::OutOfRange));
        assert_eq!(Exponent::from_f32(neg), Err(FormatError::OutOfRange));
        assert_eq!(Attenuation::new(neg, 0.0, 0.0), Err(LightError::OutOfRange));
    }
    // −0 is 0, not an error.
    assert_eq!(Rgb::from_f32(-0.0, 0.0, 0.0), Ok(Rgb::BLACK));
    assert_eq!(Exponent::from_f32(-0.0), Ok(Exponent::ZERO));
    // Documented clamps: colours at 256, integer exponents at 4096.
    assert_eq!(
        Rgb::from_f32(1e30, 300.0, 256.0).unwrap().to_bits(),
        [256 << 16; 3]
    );
    assert_eq!(Rgb::from_bits(u32::MAX, 0, 0).to_bits()[0], 256 << 16);
    assert_eq!(Exponent::from_int(u16::MAX), Exponent::MAX);
    assert_eq!(Exponent::from_bits(u32::MAX), Exponent::MAX);
    // Float exponents above 4096 are errors, not clamps.
    assert_eq!(Exponent::from_f32(4096.01), Err(FormatError::OutOfRange));
    assert_eq!(Exponent::from_f32(4096.0), Ok(Exponent::MAX));
    // Attenuation constants are U32F32: 2^32 and above are errors.
    assert_eq!(
        Attenuation::new(0.0, 0.0, 4.3e9),
        Err(LightError::OutOfRange)
    );
    assert!(Attenuation::new(1e-6, 1e6, 4.2e9).is_ok());
}

#[test]
fn lights() {
    for bad in NON_FINITE {
        assert_eq!(PointLight::new([0.0, bad, 0.0]), Err(LightError::NotFinite));
        assert_eq!(
            WidePoint::from_f32([bad, 0.0, 0.0]),
            Err(FormatError::NotFinite)
        );
        assert_eq!(
            SpotCone::new([0.0, -1.0, 0.0], bad, 2.0),
            Err(LightError::NotFinite)
        );
        assert_eq!(
            SpotCone::new([0.0, -1.0, 0.0], 30.0, bad),
            Err(LightError::NotFinite)
        );
        assert_eq!(
            SpotCone::new([bad, -1.0, 0.0], 30.0, 2.0),
            Err(LightError::NotFinite)
        );
        assert_eq!(
            AreaLight::new([0.0; 3], [bad, 0.0, 0.0], [0.0, 1.0, 0.0], 2),
            Err(LightError::NotFinite)
        );
    }
    assert_eq!(
        PointLight::new([3e11, 0.0, 0.0]),
        Err(LightError::OutOfRange)
    );
    assert!(PointLight::new([2.7e11, -2.7e11, 1e4]).is_ok());
    for cutoff in [-0.001, 90.001, 180.0, -90.0] {
        assert_eq!(
            SpotCone::new([0.0, -1.0, 0.0], cutoff, 2.0),
            Err(LightError::BadCutoff),
            "{cutoff}"
        );
    }
    for e in [-1.0, -1e-9, 4097.0, 1e9] {
        assert_eq!(
            SpotCone::new([0.0, -1.0, 0.0], 30.0, e),
            Err(LightError::BadExponent),
            "{e}"
        );
    }
    assert_eq!(
        SpotCone::new([0.0; 3], 30.0, 2.0),
        Err(LightError::ZeroDirection)
    );
    assert_eq!(
        SpotLight::new([0.0; 3], [0.0; 3], 30.0, 2.0),
        Err(LightError::ZeroDirection)
    );
    for cutoff in [0.0, 90.0] {
        assert!(SpotCone::new([0.0, -1.0, 0.0], cutoff, 0.0).is_ok());
    }
    for k in [0, 65, 255] {
        assert_eq!(
            AreaLight::new([0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], k),
            Err(LightError::BadSamples)
        );
    }
}

#[test]
fn cameras() {
    let ok = Camera::look_at([0.0, 0.0, 3.0], [0.0; 3], [0.0, 1.0, 0.0]).unwrap();
    for bad in NON_FINITE {
        assert_eq!(
            Camera::look_at([bad, 0.0, 3.0], [0.0; 3], [0.0, 1.0, 0.0]),
            Err(CameraError::NotFinite)
        );
        assert_eq!(
            Camera::look_at([0.0, 0.0, 3.0], [0.0; 3], [0.0, bad, 0.0]),
            Err(CameraError::NotFinite)
        );
        let p = Projection::Perspective { fovy_deg: 60.0 };
        assert_eq!(
            ok.with_projection(p, bad, 10.0),
            Err(CameraError::NotFinite)
        );
        assert_eq!(ok.with_projection(p, 0.1, bad), Err(CameraError::NotFinite));
        // A field of view or a height that is not a number is NotFinite,
        // like a near or far plane that is not.
        assert_eq!(
            ok.with_projection(Projection::Perspective { fovy_deg: bad }, 0.1, 10.0),
            Err(CameraError::NotFinite)
        );
        assert_eq!(
            ok.with_projection(Projection::Orthographic { height: bad }, 0.1, 10.0),
            Err(CameraError::NotFinite)
        );
    }
    // Degenerate frames.
    assert_eq!(
        Camera::look_at([1.0; 3], [1.0; 3], [0.0, 1.0, 0.0]),
        Err(CameraError::Degenerate)
    );
    assert_eq!(
        Camera::look_at([0.0, 3.0, 0.0], [0.0; 3], [0.0, 1.0, 0.0]),
        Err(CameraError::Degenerate)
    );
    assert_eq!(
        Camera::look_at([0.0, 0.0, 3.0], [0.0; 3], [0.0; 3]),
        Err(CameraError::Degenerate)
    );
    assert_eq!(
        Camera::look_at([200.0, 0.0, 3.0], [0.0; 3], [0.0, 1.0, 0.0]),
        Err(CameraError::OutOfRange)
    );
    // Bad projections.
    let persp = |f: f32| Projection::Perspective { fovy_deg: f };
    for (p, near, far) in [
        (persp(0.0), 0.1, 10.0),
        (persp(180.0), 0.1, 10.0),
        (persp(-30.0), 0.1, 10.0),
        (persp(60.0), 0.0, 10.0),
        (persp(60.0), -1.0, 10.0),
        (persp(60.0), 1.0, 1.0),
        (persp(60.0), 2.0, 1.0),
        (persp(60.0), 0.1, 128.0),
        (Projection::Orthographic { height: 0.0 }, 0.1, 10.0),
        (Projection::Orthographic { height: -2.0 }, 0.1, 10.0),
    ] {
        assert_eq!(
            ok.with_projection(p, near, far),
            Err(CameraError::BadProjection),
            "{p:?} {near} {far}"
        );
    }
    // Coefficients that would reach 127: a tiny field of view when the
    // projection is set, an extreme aspect ratio when it is used (at draw
    // time this is RenderError::Camera).
    assert_eq!(
        ok.with_projection(persp(0.5), 0.1, 10.0),
        Err(CameraError::BadProjection)
    );
    let wide = ok.with_projection(persp(60.0), 0.1, 10.0).unwrap();
    assert_eq!(
        wide.projection_for(1, 1000),
        Err(CameraError::BadProjection)
    );
}

/// The scene description and its conversion: NaN, negative and zero
/// values are rejected by `validate`; where a description is converted
/// anyway, a zero or NaN normal becomes the zero normal (lit by `E + A·Ka`)
/// and non-finite values are errors.
#[test]
fn scene_descriptions() {
    let cam = CameraDesc {
        eye: [0.0, 0.0, 3.0],
        target: [0.0; 3],
        up: [0.0, 1.0, 0.0],
        near: 0.1,
        far: 10.0,
        projection: fixshade_host::scene_desc::Projection::Perspective { fovy_deg: 60.0 },
    };
    let tri = MeshDesc {
        positions: vec![[-1.0, -1.0, 0.0], [1.0, -1.0, 0.0], [0.0, 1.0, 0.0]],
        normals: Some(vec![[0.0; 3], [f64::NAN, 0.0, 1.0], [0.0, 0.0, 1.0]]),
        indices: vec![[0, 1, 2]],
    };
    let base = SceneDesc::new(16, 16, cam, tri);
    let mut bad: Vec<(&str, SceneDesc)> = Vec::new();
    let mut s = base.clone();
    s.material.shininess = -1.0;
    bad.push(("negative shininess", s));
    let mut s = base.clone();
    s.material.shininess = f64::NAN;
    bad.push(("NaN shininess", s));
    let mut s = base.clone();
    s.material.diffuse = [0.5, f64::NAN, 0.5];
    bad.push(("NaN diffuse", s));
    let mut s = base.clone();
    s.lights = vec![LightDesc::Point {
        position: [0.0, 0.0, 1.0],
        diffuse: [1.0; 3],
        specular: [1.0; 3],
        attenuation: [1.0, -0.5, 0.0],
    }];
    bad.push(("negative attenuation", s));
    let mut s = base.clone();
    s.lights = vec![LightDesc::directional([0.0; 3])];
    bad.push(("zero light direction", s));
    let mut s = base.clone();
    s.mesh.positions[1][0] = f64::INFINITY;
    bad.push(("infinite position", s));
    let mut s = base.clone();
    s.mesh.indices[0][2] = 3;
    bad.push(("index out of range", s));
    for (what, s) in &bad {
        assert!(s.validate().is_err(), "{what} passed validate");
    }
    // The kernel bridge: NaN positions are a format error, not a panic.
    let (_, inf) = &bad[5];
    assert!(KernelScene::new(inf).is_err());
    // Zero and NaN normals (validate rejects the NaN one) convert to the
    // zero normal, which the reference is given as the zero vector.
    let k = KernelScene::new(&base).unwrap();
    let mesh = k.mesh();
    let n = mesh.normals.unwrap();
    assert_eq!(&n[..2], &[PackedNormal::ZERO, PackedNormal::ZERO]);
    let reference = k.reference_scene().mesh.normals.as_ref().unwrap();
    assert_eq!(reference[..2], [[0.0; 3], [0.0; 3]]);
}

/// A triangle drawn with zero normals gets `E + A·Ka` only, which is what
/// the reference gives for a zero normal (N·L = 0).
#[test]
fn zero_normals_light_ambient_only() {
    let camera = Camera::look_at([0.0, 0.0, 3.0], [0.0; 3], [0.0, 1.0, 0.0]).unwrap();
    let idx = [[0u16, 1, 2]];
    let zero = [PackedNormal::ZERO; 3];
    let mesh = Mesh::new(&TRIANGLE, BOX2, &idx).with_normals(&zero);
    let m = Material::new().with_emission(Rgb::from_f32(0.1, 0.0, 0.0).unwrap());
    let sun = DirectionalLight::new([0.0, 0.0, 1.0]).unwrap();
    let ambient = Rgb::grey_f32(0.5).unwrap();
    let r = Renderer::new(&camera, &m, &sun)
        .with_ambient(ambient)
        .with_shading(PhongShading);
    let expect = r.lighting().ambient().to_rgb565();
    let mut px = vec![0u16; 32 * 32];
    let mut fb = Framebuffer::new(&mut px, 32, 32).unwrap();
    let mut cache = [CachedVertex::default(); 3];
    mesh.shaded(&r)
        .with_cache(&mut cache)
        .draw(&mut fb)
        .unwrap();
    assert_eq!(fb.pixel(16, 16), Some(expect));
    // 0.1 + 0.5·0.2 = 0.2 red, 0.1 green and blue.
    use embedded_graphics::pixelcolor::RgbColor;
    assert_eq!((expect.r(), expect.g(), expect.b()), (6, 6, 3));
}

/// A draw with a bad mesh, short buffers, a too large target or
/// a projection that does not fit: the documented error, nothing drawn.
#[test]
fn draw_errors() {
    let camera = Camera::look_at([0.0, 0.0, 3.0], [0.0; 3], [0.0, 1.0, 0.0]).unwrap();
    let pos = TRIANGLE;
    let normals = [PackedNormal::Z; 3];
    let good_idx = [[0u16, 1, 2]];
    let bad_idx = [[0u16, 1, 2], [2, 1, 3]];
    let max_idx = [[u16::MAX, 0, 1]];
    let m = Material::new();
    let sun = DirectionalLight::new([0.0, 0.0, 1.0]).unwrap();
    let r = Renderer::new(&camera, &m, &sun);
    let flat = r.with_shading(Flat);
    let phong = r.with_shading(PhongShading);
    let mut cache = [CachedVertex::default(); 3];

    let mut t = CountingTarget::new(32, 32);
    let bad = Mesh::new(&pos, BOX2, &bad_idx).with_normals(&normals);
    assert_eq!(
        bad.shaded(&r).with_cache(&mut cache).draw(&mut t),
        Err(RenderError::Mesh(MeshError::IndexOutOfRange {
            triangle: 1,
            index: 3
        }))
    );
    let bad = Mesh::new(&pos, BOX2, &max_idx);
    assert_eq!(
        bad.shaded(&flat).with_cache(&mut cache).draw(&mut t),
        Err(RenderError::Mesh(MeshError::IndexOutOfRange {
            triangle: 0,
            index: u16::MAX
        }))
    );
    let bad = Mesh::new(&pos, BOX2, &good_idx).with_normals(&normals[..2]);
    assert_eq!(
        bad.shaded(&phong).with_cache(&mut cache).draw(&mut t),
        Err(RenderError::Mesh(MeshError::NormalCount))
    );
    // No positions, an index: out of range too.
    let empty = Mesh::new(&[], BOX2, &good_idx);
    assert!(matches!(
        empty.shaded(&flat).with_cache(&mut cache).draw(&mut t),
        Err(RenderError::Mesh(_))
    ));

    let mesh = Mesh::new(&pos, BOX2, &good_idx).with_normals(&normals);
    assert_eq!(
        mesh.shaded(&r).with_cache(&mut cache[..2]).draw(&mut t),
        Err(RenderError::CacheTooSmall)
    );
    // A depth buffer for fewer rows than the target.
    let mut d = [0u16; 32 * 31];
    let mut short = DepthBuffer::new(&mut d, 32, 31).unwrap();
    assert_eq!(
        mesh.shaded(&r)
            .with_depth(&mut short)
            .with_cache(&mut cache)
            .draw(&mut t),
        Err(RenderError::DepthTooSmall)
    );
    // Or narrower.
    let mut d = [0u16; 32 * 32];
    let mut narrow = DepthBuffer::new(&mut d, 31, 32).unwrap();
    assert_eq!(
        mesh.shaded(&r)
            .with_depth(&mut narrow)
            .with_cache(&mut cache)
            .draw(&mut t),
        Err(RenderError::DepthTooSmall)
    );
    assert_eq!(t.writes, 0, "an error draw drew");

    let mut huge = CountingTarget::new(MAX_TARGET_SIDE + 1, 0);
    assert_eq!(
        mesh.shaded(&r).with_cache(&mut cache).draw(&mut huge),
        Err(RenderError::TargetTooLarge)
    );
    // A projection whose coefficients do not fit this target's aspect.
    let mut thin = CountingTarget::new(1, 4000);
    assert_eq!(
        mesh.shaded(&r).with_cache(&mut cache).draw(&mut thin),
        Err(RenderError::Camera(CameraError::BadProjection))
    );
    // And the error path's pixels are all in place after a good draw.
    let stats = mesh.shaded(&r).with_cache(&mut cache).draw(&mut t).unwrap();
    assert!(stats.pixels > 50 && t.outside == 0);
}

/// Gouraud and Phong shading interpolate vertex normals: a mesh without
/// them is `RenderError::NoNormals` and nothing is drawn, into any output
/// (a `DrawTarget`, a framebuffer, bands), cached or not, with a depth test
/// or not; Flat shading (the face's normal) draws it.
#[test]
fn smooth_shading_without_normals_is_an_error() {
    let camera = Camera::look_at([0.0, 0.0, 3.0], [0.0; 3], [0.0, 1.0, 0.0]).unwrap();
    let idx = [[0u16, 1, 2]];
    let mesh = Mesh::new(&TRIANGLE, BOX2, &idx);
    assert!(mesh.normals.is_none() && mesh.validate().is_ok());
    let m = Material::new();
    let sun = DirectionalLight::new([0.0, 0.0, 1.0]).unwrap();
    let gouraud = Renderer::new(&camera, &m, &sun); // the default
    let phong = gouraud.with_shading(PhongShading);
    let flat = gouraud.with_shading(Flat);
    let mut cache = [CachedVertex::default(); 3];
    const FILL: u16 = 0x1234;

    // A DrawTarget.
    let mut t = CountingTarget::new(32, 32);
    assert_eq!(
        mesh.shaded(&gouraud).draw(&mut t),
        Err(RenderError::NoNormals)
    );
    assert_eq!(
        mesh.shaded(&gouraud).with_cache(&mut cache).draw(&mut t),
        Err(RenderError::NoNormals)
    );
    assert_eq!(
        mesh.shaded(&phong).draw(&mut t),
        Err(RenderError::NoNormals)
    );
    assert_eq!(t.writes, 0, "an error draw drew");

    // A framebuffer (the fast path), with a depth buffer.
    let (mut px, mut z) = ([FILL; 32 * 32], [0u16; 32 * 32]);
    let mut fb = Framebuffer::new(&mut px, 32, 32).unwrap();
    let mut depth = DepthBuffer::new(&mut z, 32, 32).unwrap();
    assert_eq!(
        mesh.shaded(&gouraud)
            .with_depth(&mut depth)
            .with_cache(&mut cache)
            .draw(&mut fb),
        Err(RenderError::NoNormals)
    );
    assert_eq!(
        mesh.shaded(&phong).draw(&mut fb),
        Err(RenderError::NoNormals)
    );
    // Bands (which would clear each band to the background).
    let mut colour = [0u16; 32 * 8];
    let mut zb = [0u16; 32 * 8];
    let mut display = fb.canvas();
    let mut bands = Bands::new(&mut display, &mut colour, 8).with_background(Rgb565::BLUE);
    assert_eq!(
        mesh.shaded(&gouraud)
            .with_depth(&mut fixshade::depth::DepthBand::new(&mut zb))
            .draw(&mut bands),
        Err(RenderError::NoNormals)
    );
    assert_eq!(
        mesh.shaded(&phong).with_cache(&mut cache).draw(&mut bands),
        Err(RenderError::NoNormals)
    );
    assert!(
        fb.as_slice().iter().all(|&p| p == FILL),
        "an error draw drew"
    );
    assert!(
        depth.as_slice().iter().all(|&d| d == u16::MAX),
        "depth written"
    );

    // Flat shading draws the same mesh: every pixel once, the same pixels
    // through each output.
    let stats = mesh
        .shaded(&flat)
        .with_cache(&mut cache)
        .draw(&mut t)
        .unwrap();
    assert!(stats.pixels > 50, "{stats:?}");
    assert_eq!(t.writes, stats.pixels as u64);
    assert_eq!(t.outside, 0);
    let s = mesh
        .shaded(&flat)
        .with_depth(&mut depth)
        .draw(&mut fb)
        .unwrap();
    assert_eq!(s.pixels, stats.pixels);
    let drawn = fb.as_slice().iter().filter(|&&p| p != FILL).count();
    assert_eq!(drawn, stats.pixels as usize);
    let facing = fb.pixel(16, 16).unwrap();
    assert_ne!(facing, Rgb565::new(0, 0, 0), "lit by the sun");
    let mut display = fb.canvas();
    let mut bands = Bands::new(&mut display, &mut colour, 8).with_background(Rgb565::BLUE);
    let s = mesh.shaded(&flat).draw(&mut bands).unwrap();
    assert_eq!(s.pixels, stats.pixels);
    assert_eq!(fb.pixel(16, 16), Some(facing));
    assert_eq!(fb.pixel(0, 0), Some(Rgb565::BLUE));
}

/// Found here: `Attenuation::new` accepted a negative constant above
/// −2⁻³³ (it rounds to 0 in `U32F32`) although negatives are documented
/// as errors. Fixed in src/light.rs; −0 is still 0.
#[test]
fn tiny_negative_attenuation_is_an_error() {
    for v in [-1e-30, -1e-12, -f32::MIN_POSITIVE] {
        assert_eq!(Attenuation::new(1.0, v, 0.0), Err(LightError::OutOfRange));
        assert_eq!(
            Attenuation::from_f64([v as f64, 0.0, 0.0]),
            Err(LightError::OutOfRange)
        );
    }
    assert!(Attenuation::new(-0.0, -0.0, 1.0).is_ok());
}

/// A small deterministic generator (SplitMix64) for the in-range checks
/// below.
struct Mix(u64);

impl Mix {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in `0..=max` (near enough for test inputs).
    fn upto(&mut self, max: u64) -> u64 {
        self.next() % (max + 1)
    }
}

/// Found by audit: `Gain::parts` shifted `1u32` by 32 (a debug panic) for
/// every gain below 2⁻¹⁶ (`sh = 31`), e.g. `255 · 255` in `Q.32`, which an
/// area light's 1/k² share on a dark material produces. The denominator is
/// now a `u64`: `2³²` there, and the same value as before everywhere else.
/// Every gain `of_product` makes is the `Q.32` product to within half a
/// mantissa unit, with a 16-bit mantissa above 2⁻¹⁶ and the exact product
/// below.
#[test]
fn gain_parts_covers_every_gain() {
    use fixshade::illumination::Gain;
    assert_eq!(Gain::of_product(255, 255).parts(), (65025, 1 << 32));
    assert_eq!(Gain::of_product(1, 1).parts(), (1, 1 << 32));
    assert_eq!(Gain::of_product(0, 12345).parts().0, 0);
    assert_eq!(
        Gain::of_product(1 << 16, 1 << 16).parts(),
        (1 << 15, 1 << 15)
    );
    // Clamped at 256.
    assert_eq!(
        Gain::of_product(u32::MAX, u32::MAX).parts(),
        (1 << 15, 1 << 7)
    );
    let mut rng = Mix(1);
    for i in 0..200_000u32 {
        // Operands of every magnitude: 0 to 2^32 − 1, log-uniform-ish.
        let a = (rng.next() >> rng.upto(63)) as u32;
        let b = (rng.next() >> rng.upto(63)) as u32;
        let b = if i % 4 == 0 { b & 0xFF } else { b };
        let p = (a as u64 * b as u64).min(256 << 32);
        let (mant, den) = Gain::of_product(a, b).parts();
        if p == 0 {
            assert_eq!(mant, 0);
            continue;
        }
        assert!(den.is_power_of_two() && (1 << 6..=1 << 32).contains(&den));
        // mant/den = p/2^32 to within half a unit of mant: |mant·2^32 −
        // p·den| ≤ 2^31.
        let err = (mant as i128) * (1i128 << 32) - (p as i128) * (den as i128);
        assert!(err.abs() <= 1 << 31, "a={a} b={b}: {mant}/{den}");
        if den < 1 << 32 {
            assert!(mant >= 1 << 15, "a={a} b={b}: not normalised");
        } else {
            assert_eq!(mant as u64, p, "a={a} b={b}: not exact");
        }
    }
}

/// Found by audit: `Gain::apply` and `add_light` overflowed (a debug panic)
/// for a factor above the documented 2¹⁵. A factor above 1 is now clamped
/// to 1 (one `min`); in range, `apply` is still `round(mant·x / 2^sh)`
/// (checked against `u64` arithmetic on random gains and factors).
#[test]
fn gain_apply_clamps_the_factor() {
    use fixshade::illumination::{add_light, Gain, Gains, Surface, FACTOR_ONE};
    let g = Gain::of_product(1 << 16, 1 << 16);
    assert_eq!(g.apply(1 << 17), g.apply(FACTOR_ONE));
    assert_eq!(g.apply(u32::MAX), 1 << 16);
    let top = Gain::of_product(u32::MAX, u32::MAX);
    assert_eq!(top.apply(u32::MAX), top.apply(FACTOR_ONE));
    assert_eq!(top.apply(FACTOR_ONE), 256 << 16);

    let ctx = Surface {
        position: Vec3::ZERO,
        normal: Unit3::Z,
        view: Unit3::ZERO,
        shininess: Exponent::ZERO,
    };
    let gains = Gains::new(Rgb::WHITE, Rgb::WHITE, Rgb::WHITE, Rgb::WHITE);
    for sf in [FACTOR_ONE + 1, 1 << 17, u32::MAX] {
        let mut acc = [0u32; 3];
        add_light::<NoSpecular>(&ctx, Unit3::Z, sf, &gains, &mut acc);
        let mut one = [0u32; 3];
        add_light::<NoSpecular>(&ctx, Unit3::Z, FACTOR_ONE, &gains, &mut one);
        assert_eq!(acc, one, "sf = {sf}");
        assert_eq!(acc, [1 << 16; 3]);
    }

    let mut rng = Mix(2);
    for _ in 0..200_000 {
        let a = (rng.next() >> rng.upto(63)) as u32;
        let b = (rng.next() >> rng.upto(63)) as u32;
        let gain = Gain::of_product(a, b);
        let (mant, den) = gain.parts();
        let x = rng.upto(FACTOR_ONE as u64);
        // 2^sh = den / 2; the rounding half is 2^sh / 2 (0 for sh = 0).
        let want = (mant as u64 * x + den / 4) / (den / 2);
        assert_eq!(gain.apply(x as u32) as u64, want, "a={a} b={b} x={x}");
        let over = FACTOR_ONE + 1 + rng.upto((u32::MAX - FACTOR_ONE - 1) as u64) as u32;
        assert_eq!(gain.apply(over), gain.apply(FACTOR_ONE), "x={over}");
    }
}

/// The old `MiniFloat` formulas in `i64`, where they cannot overflow, as
/// `(m, e)`.
fn mini_model(v: u64, frac: i32) -> (u32, i64) {
    if v == 0 {
        return (0, 0);
    }
    let lz = v.leading_zeros();
    (((v << lz) >> 32) as u32, 32 - lz as i64 - frac as i64)
}

/// The old `MiniFloat::mul` in `i64`.
fn mini_model_mul(a: (u32, i64), b: (u32, i64)) -> (u32, i64) {
    if a.0 == 0 || b.0 == 0 {
        return (0, 0);
    }
    let p = a.0 as u64 * b.0 as u64;
    if p >> 63 == 1 {
        ((p >> 32) as u32, a.1 + b.1 + 32)
    } else {
        ((p >> 31) as u32, a.1 + b.1 + 31)
    }
}

/// Found by audit: `MiniFloat`'s exponent arithmetic overflowed `i32` (a
/// debug panic) in `from_u64` with an extreme `frac`, in `mul` of two huge
/// values and in `to_q32_saturating` near `i32::MAX`. Exponents now stay in
/// [−2²⁹, 2²⁹]: above, the value saturates to `MiniFloat::MAX`; below, it
/// flushes to zero. In range the values are the old ones (checked against
/// the old formulas in `i64` on random inputs).
#[test]
fn minifloat_exponent_saturates() {
    use fixshade::num::MiniFloat;
    assert_eq!(MiniFloat::from_u64(1, i32::MAX), MiniFloat::ZERO);
    assert_eq!(MiniFloat::from_u64(1, i32::MIN), MiniFloat::MAX);
    assert_eq!(MiniFloat::from_u64(u64::MAX, i32::MIN), MiniFloat::MAX);
    assert_eq!(MiniFloat::from_u64(u64::MAX, i32::MAX), MiniFloat::ZERO);
    let a = MiniFloat::from_u64(u64::MAX, -(1 << 30));
    assert_eq!(a, MiniFloat::MAX);
    assert_eq!(a.mul(a), MiniFloat::MAX);
    assert_eq!(a.mul(a).to_q32_saturating(), u64::MAX);
    let t = MiniFloat::from_u64(1, 1 << 30);
    assert_eq!(t.mul(t), MiniFloat::ZERO);
    assert_eq!(t.mul(a).to_q32_saturating(), 0);
    // Just inside the ends.
    let top = MiniFloat::from_u64(1 << 63, -(MiniFloat::E_MAX - 32));
    assert_eq!(
        format!("{top:?}"),
        format!("MiniFloat {{ m: {}, e: {} }}", 1u32 << 31, MiniFloat::E_MAX)
    );
    assert_eq!(top.to_q32_saturating(), u64::MAX);
    let bottom = MiniFloat::from_u64(1 << 63, 32 - MiniFloat::E_MIN);
    assert_eq!(
        format!("{bottom:?}"),
        format!("MiniFloat {{ m: {}, e: {} }}", 1u32 << 31, MiniFloat::E_MIN)
    );
    assert_eq!(bottom.to_q32_saturating(), 0);
    assert_eq!(
        MiniFloat::from_u64(1 << 63, 33 - MiniFloat::E_MIN),
        MiniFloat::ZERO
    );
    // Squaring repeatedly saturates instead of overflowing.
    let mut x = MiniFloat::from_u64(3, 0);
    let mut y = MiniFloat::from_u64(3, 2);
    for _ in 0..64 {
        x = x.mul(x);
        y = y.mul(y).mul(y);
    }
    assert_eq!((x, y), (MiniFloat::MAX, MiniFloat::ZERO));

    let show = |(m, e): (u32, i64)| format!("MiniFloat {{ m: {m}, e: {e} }}");
    let mut rng = Mix(3);
    for _ in 0..200_000 {
        let v = [rng.next() >> rng.upto(63), rng.next() >> rng.upto(63)];
        let f = [0, 1].map(|_| rng.upto(400) as i32 - 200);
        let (a, b) = (
            MiniFloat::from_u64(v[0], f[0]),
            MiniFloat::from_u64(v[1], f[1]),
        );
        let (ma, mb) = (mini_model(v[0], f[0]), mini_model(v[1], f[1]));
        assert_eq!(format!("{a:?}"), show(ma));
        let p = a.mul(b).mul(b);
        let mp = mini_model_mul(mini_model_mul(ma, mb), mb);
        assert_eq!(format!("{p:?}"), show(mp));
        // to_q32 against the exact value m·2^(e+32), saturated.
        let want = if mp.0 == 0 || mp.1 < -96 {
            0
        } else if mp.1 > 0 {
            u64::MAX
        } else {
            let s = mp.1 + 32;
            let w = if s >= 0 {
                (mp.0 as u128) << s
            } else {
                (mp.0 as u128) >> -s
            };
            w.min(u64::MAX as u128) as u64
        };
        assert_eq!(p.to_q32_saturating(), want, "{p:?}");
    }
}

/// The rotation `Mat4::rotation` built before the fix (the range reduction
/// by the nearest multiple of 2π alone), valid below 2³³.
fn old_rotation(axis: u8, angle: f32) -> Mat4 {
    use micromath::F32Ext;
    let tau = 2.0 * core::f32::consts::PI;
    let a = angle - tau * F32Ext::round(angle / tau);
    let (s, c) = (F32Ext::sin(a), F32Ext::cos(a));
    let k = 0.5 * (3.0 - (s * s + c * c));
    let (s, c) = (s * k, c * k);
    let q = |v: f32| (v * (1u32 << 24) as f32) as i32;
    let (s, c, one) = (q(s), q(c), 1 << 24);
    let m = match axis {
        0 => [[one, 0, 0, 0], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, one]],
        1 => [[c, 0, s, 0], [0, one, 0, 0], [-s, 0, c, 0], [0, 0, 0, one]],
        _ => [[c, -s, 0, 0], [s, c, 0, 0], [0, 0, one, 0], [0, 0, 0, one]],
    };
    Mat4 { m }
}

/// The rotation about axis 0 (x), 1 (y) or 2 (z).
fn rotation(axis: u8, angle: f32) -> Mat4 {
    match axis {
        0 => Mat4::rotation_x(angle),
        1 => Mat4::rotation_y(angle),
        _ => Mat4::rotation_z(angle),
    }
}

/// Whether `m` is a rotation about `axis` with entries in [−1, 1]: the
/// identity outside the 2 × 2 block, which is `[[c, −s], [s, c]]` (up to
/// the axis's sign convention) with `c² + s²` within 10⁻⁴ of 1.
fn is_rotation(axis: u8, m: &Mat4) -> bool {
    let one = 1i32 << 24;
    let (i, j) = match axis {
        0 => (1, 2),
        1 => (2, 0),
        _ => (0, 1),
    };
    let (c, s) = (m.m[i][i], m.m[j][i]);
    let mut want = Mat4::IDENTITY.m;
    want[i][i] = c;
    want[j][j] = c;
    want[j][i] = s;
    want[i][j] = -s;
    let (cf, sf) = (c as f64 / one as f64, s as f64 / one as f64);
    m.m == want && c.abs() <= one && s.abs() <= one && (cf * cf + sf * sf - 1.0).abs() < 1e-4
}

/// Found by audit: `Mat4::rotation` of a huge finite angle (from about
/// 1.35·10¹⁰, where `angle / 2π` no longer fits the `i32` micromath's
/// `round` goes through) gave `sin`/`cos` far outside [−1, 1], entries
/// saturated to `i32::MIN` and `-s` overflowed (a debug panic). From 2³³ the
/// angle is now reduced exactly modulo 2π (as an `f32`) first: every finite
/// angle gives a rotation with entries in [−1, 1], the same matrix as its
/// `fmod` remainder, and below 2³³ the same matrix as before.
#[test]
fn rotation_of_any_finite_angle() {
    let tau = (2.0 * core::f32::consts::PI) as f64;
    for axis in 0..3u8 {
        for angle in [27_026_295_000.0, f32::MAX, -f32::MAX, 1e38, -3e12, 8.6e9] {
            let m = rotation(axis, angle);
            assert!(is_rotation(axis, &m), "{angle}: {m:?}");
            let r = ((angle as f64) % tau) as f32;
            assert_eq!(m, rotation(axis, r), "{angle}");
        }
    }
    let mut rng = Mix(4);
    for i in 0..300_000u32 {
        // Every finite f32 bit pattern (NaN/∞ excluded), all magnitudes.
        let bits = rng.next() as u32;
        let angle = f32::from_bits(bits);
        if !angle.is_finite() {
            continue;
        }
        let axis = (i % 3) as u8;
        let m = rotation(axis, angle);
        assert!(is_rotation(axis, &m), "{angle}: {m:?}");
        if angle.abs() < (1u64 << 33) as f32 {
            assert_eq!(m, old_rotation(axis, angle), "{angle}");
        } else {
            let r = ((angle as f64) % tau) as f32;
            assert_eq!(m, rotation(axis, r), "{angle}");
        }
        // Ordinary angles, which the bit patterns rarely hit.
        let small = (rng.next() as i64 as f64 / i64::MAX as f64 * 100.0) as f32;
        assert_eq!(rotation(axis, small), old_rotation(axis, small), "{small}");
        assert!(is_rotation(axis, &rotation(axis, small)));
    }
}

/// Found by audit: `Rgb::scaled` narrowed its `u64` quotient with `as u32`,
/// so `WHITE.scaled(1 << 16, 1)` (2³²) wrapped to black. It now clamps to
/// `RGB_MAX` like every `Rgb` channel; in range the result is unchanged
/// (checked against `u64` arithmetic on random inputs).
#[test]
fn rgb_scaled_clamps() {
    use fixshade::color::RGB_MAX;
    assert_eq!(Rgb::WHITE.scaled(1 << 16, 1).to_bits(), [RGB_MAX; 3]);
    assert_eq!(Rgb::WHITE.scaled(u32::MAX, 1).to_bits(), [RGB_MAX; 3]);
    let max = Rgb::from_bits(RGB_MAX, RGB_MAX, RGB_MAX);
    assert_eq!(max.scaled(u32::MAX, 1).to_bits(), [RGB_MAX; 3]);
    assert_eq!(max.scaled(u32::MAX, u32::MAX).to_bits(), [RGB_MAX; 3]);
    assert_eq!(Rgb::WHITE.scaled(1, 0), Rgb::BLACK);
    let mut rng = Mix(5);
    for _ in 0..200_000 {
        let c = [0, 1, 2].map(|_| rng.upto(RGB_MAX as u64) as u32);
        let num = (rng.next() >> rng.upto(63)) as u32;
        let den = ((rng.next() >> rng.upto(63)) as u32).max(1);
        let got = Rgb::from_bits(c[0], c[1], c[2]).scaled(num, den).to_bits();
        for (g, v) in got.iter().zip(c) {
            let want = (v as u128 * num as u128 + den as u128 / 2) / den as u128;
            assert_eq!(*g as u128, want.min(RGB_MAX as u128), "{v}·{num}/{den}");
        }
    }
}

/// A display that takes every run and discards it (a streaming driver),
/// with its bounding box anywhere on the plane; it counts what it is sent.
struct Discard {
    bb: Rectangle,
    runs: u64,
}

impl Dimensions for Discard {
    fn bounding_box(&self) -> Rectangle {
        self.bb
    }
}

impl DrawTarget for Discard {
    type Color = Rgb565;
    type Error = core::convert::Infallible;
    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(
        &mut self,
        _: I,
    ) -> Result<(), Self::Error> {
        Ok(())
    }
    fn fill_contiguous<I>(&mut self, area: &Rectangle, _: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Rgb565>,
    {
        // Every run lies inside the box (in i64: the box may end at i32::MAX).
        let inside = |at: i32, len: u32, lo: i32, n: u32| {
            at as i64 >= lo as i64 && at as i64 + len as i64 <= lo as i64 + n as i64
        };
        assert!(inside(
            area.top_left.x,
            area.size.width,
            self.bb.top_left.x,
            self.bb.size.width
        ));
        assert!(inside(
            area.top_left.y,
            area.size.height,
            self.bb.top_left.y,
            self.bb.size.height
        ));
        self.runs += 1;
        Ok(())
    }
}

/// The quad (±2, ±2, 0) in the box [−4, 4)³ and its two triangles.
fn full_screen_quad() -> ([[i16; 3]; 4], Bounds, [[u16; 3]; 2]) {
    let p = [(-1, -1), (1, -1), (1, 1), (-1, 1)].map(|(x, y)| [x * 16384, y * 16384, 0]);
    (
        p,
        Bounds::from_bits([0; 3], [4 << 24; 3]),
        [[0, 1, 2], [0, 2, 3]],
    )
}

/// The light of [`facing_renderer`]: from the camera's side.
fn facing_sun() -> DirectionalLight {
    DirectionalLight::new([0.0, 0.0, 1.0]).unwrap()
}

/// A camera looking at the quad of [`full_screen_quad`] from z = 1, lit by
/// `sun`.
fn facing_renderer(sun: &DirectionalLight) -> Renderer<'_, NoSpecular, DirectionalLight> {
    static CAMERA: std::sync::OnceLock<Camera> = std::sync::OnceLock::new();
    let camera =
        CAMERA.get_or_init(|| Camera::look_at([0.0, 0.0, 1.0], [0.0; 3], [0.0, 1.0, 0.0]).unwrap());
    static MATERIAL: Material<NoSpecular> = Material::new();
    Renderer::new(camera, &MATERIAL, sun)
}

/// A target whose bounding box ends past `i32::MAX` is refused with
/// `TargetTooLarge` by a whole-frame draw and a banded one (found by an audit: the
/// points of its last pixels overflowed `embedded-graphics`' arithmetic);
/// one that ends exactly at `i32::MAX` is drawn, every run inside its box.
#[test]
fn targets_ending_past_i32_max() {
    let (p, b, i) = full_screen_quad();
    let mesh = Mesh::new(&p, b, &i);
    let sun = facing_sun();
    let r = facing_renderer(&sun).with_shading(Flat);
    let mut cache = [CachedVertex::default(); 4];
    let mut colour = [0u16; 64 * 8];
    for (corner, ok) in [
        (Point::new(i32::MAX - 63, 0), true),
        (Point::new(0, i32::MAX - 63), true),
        (Point::new(i32::MAX - 62, 0), false),
        (Point::new(0, i32::MAX - 10), false),
        (Point::new(i32::MIN, i32::MIN), true),
    ] {
        let bb = Rectangle::new(corner, Size::new(64, 64));
        let mut t = Discard { bb, runs: 0 };
        let drawn = mesh.shaded(&r).with_cache(&mut cache).draw(&mut t);
        let mut bands = Bands::new(&mut t, &mut colour, 8).with_background(Rgb565::BLACK);
        let banded = mesh.shaded(&r).draw(&mut bands);
        if ok {
            assert!(
                drawn.unwrap().pixels == 64 * 64 && banded.is_ok() && t.runs > 0,
                "{corner:?}"
            );
        } else {
            assert_eq!(drawn, Err(RenderError::TargetTooLarge), "{corner:?}");
            assert_eq!(
                banded.err(),
                Some(RenderError::TargetTooLarge),
                "{corner:?}"
            );
            assert_eq!(t.runs, 0);
        }
    }
}

/// The draw counts saturate: a full-screen quad on a 2¹⁶ × 2¹⁶ target
/// sends 2³² pixels, and `pixels` stays at `u32::MAX` (found by an audit:
/// the `u32` sum overflowed). The quad is 124 units wide, seen from 16
/// under a 150° field of view: a unit quad from 1 would be refused on so
/// tall a target ([`RenderError::SceneTooSmall`]), and is.
#[test]
fn draw_counts_saturate() {
    let (p, b, i) = full_screen_quad();
    let mesh = Mesh::new(&p, b, &i);
    let side = 1 << 16;
    let mut t = Discard {
        bb: Rectangle::new(Point::zero(), Size::new(side, side)),
        runs: 0,
    };
    let mut cache = [CachedVertex::default(); 4];
    let sun = facing_sun();
    let unit = facing_renderer(&sun).with_shading(Flat);
    let e = mesh.shaded(&unit).with_cache(&mut cache).draw(&mut t);
    assert_eq!(e, Err(RenderError::SceneTooSmall));
    assert_eq!(t.runs, 0);
    let camera = Camera::look_at([0.0, 0.0, 16.0], [0.0; 3], [0.0, 1.0, 0.0])
        .and_then(|c| c.with_projection(Projection::Perspective { fovy_deg: 150.0 }, 1.0, 100.0))
        .unwrap();
    let m = Material::new();
    let r = Renderer::new(&camera, &m, &sun).with_shading(Flat);
    let stats = mesh
        .shaded(&r)
        .with_model(
            Mat4::from_f32([
                [31.0, 0.0, 0.0, 0.0],
                [0.0, 31.0, 0.0, 0.0],
                [0.0, 0.0, 0.25, 0.0],
                [0.0, 0.0, 0.0, 1.0],
            ])
            .unwrap(),
        )
        .with_cache(&mut cache)
        .draw(&mut t)
        .unwrap();
    assert_eq!(stats.pixels, u32::MAX);
    assert!(t.runs >= side as u64, "a run or two a row");
}

/// A target whose bounding box grows after its first answer: 16 × 16 on
/// the first call, 64 × 64 on every later one.
struct Growing {
    calls: core::cell::Cell<u32>,
    runs: u64,
}

impl Dimensions for Growing {
    fn bounding_box(&self) -> Rectangle {
        let n = self.calls.get();
        self.calls.set(n + 1);
        let side = if n == 0 { 16 } else { 64 };
        Rectangle::new(Point::zero(), Size::new(side, side))
    }
}

impl DrawTarget for Growing {
    type Color = Rgb565;
    type Error = core::convert::Infallible;
    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(
        &mut self,
        px: I,
    ) -> Result<(), Self::Error> {
        // Every pixel inside the box the draw read first.
        for Pixel(p, _) in px {
            assert!((0..16).contains(&p.x) && (0..16).contains(&p.y), "{p:?}");
        }
        self.runs += 1;
        Ok(())
    }
    fn fill_contiguous<I>(&mut self, area: &Rectangle, c: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Rgb565>,
    {
        let first = Rectangle::new(Point::zero(), Size::new(16, 16));
        assert_eq!(area.intersection(&first), *area, "{area:?}");
        assert_eq!(
            c.into_iter().count() as u32,
            area.size.width * area.size.height
        );
        self.runs += 1;
        Ok(())
    }
}

/// A draw reads the target's box once and keeps to it: a target whose box
/// changes between calls neither panics a draw (the bands were checked
/// against the first box and sliced with the second) nor receives pixels
/// outside the box the draw began with.
#[test]
fn target_box_read_once() {
    let (p, b, i) = full_screen_quad();
    // Gouraud and Phong shading need vertex normals (`RenderError::NoNormals`).
    let normals = [PackedNormal::Z; 4];
    let mesh = Mesh::new(&p, b, &i).with_normals(&normals);
    let sun = facing_sun();
    let r = facing_renderer(&sun);
    let mut cache = [CachedVertex::default(); 4];
    let mut band_cache = [fixshade::render::CachedVertex::default(); 4];
    let mut z = [0u16; 16 * 16];
    for height in [1, 4, 16] {
        let mut colour = [0u16; 16 * 16];
        let colour = &mut colour[..16 * height as usize];
        let mut t = Growing {
            calls: 0.into(),
            runs: 0,
        };
        let mut bands = Bands::new(&mut t, colour, height).with_background(Rgb565::BLACK);
        let s = mesh
            .shaded(&r.with_shading(Gouraud))
            .draw(&mut bands)
            .unwrap();
        assert_eq!((s.pixels, t.runs), (256, 16 / height as u64));
        let mut t = Growing {
            calls: 0.into(),
            runs: 0,
        };
        let mut bands = Bands::new(&mut t, colour, height).with_background(Rgb565::BLACK);
        let mut zb = fixshade::depth::DepthBand::new(&mut z);
        let s = mesh
            .shaded(&r.with_shading(PhongShading))
            .with_depth(&mut zb)
            .with_cache(&mut band_cache)
            .draw(&mut bands)
            .unwrap();
        assert_eq!(s.pixels, 256);
    }
    let mut t = Growing {
        calls: 0.into(),
        runs: 0,
    };
    let s = mesh
        .shaded(&r.with_shading(Flat))
        .with_cache(&mut cache)
        .draw(&mut t)
        .unwrap();
    assert_eq!(s.pixels, 256);
    assert!(t.runs > 0);
}
