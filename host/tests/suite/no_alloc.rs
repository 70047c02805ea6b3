//! The kernel performs no heap allocation, neither when
//! lighting a vertex nor when rendering a mesh.
//!
//! A counting global allocator wraps `System` and counts, per thread,
//! every `alloc`, `alloc_zeroed`, `realloc` and `dealloc` (tests run in
//! parallel threads; each one only sees its own count). Scenes, meshes and
//! buffers are built before the counted region; the region itself must
//! count zero.

use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::RgbColor;
use fixshade::camera::{Camera, Projection};
use fixshade::depth::DepthBuffer;
use fixshade::framebuffer::Framebuffer;
use fixshade::illumination::{InfiniteViewer, LocalViewer};
use fixshade::light::{
    unit_from_f64, AnyLight, AreaLight, Attenuation, DirectionalLight, PointLight, SpotLight,
};
use fixshade::material::{BlinnPhong, Phong};
use fixshade::mesh::{vertex_normals, Bounds, Mesh, PackedNormal};
use fixshade::render::{CachedVertex, DrawStats, Flat, PhongShading, RenderOptions};
use fixshade::{Exponent, Lighting, Mat4, Material, Renderer, Rgb, Unit3, Vec3};
use fixshade_host::generate;
use fixshade_host::mesh_convert::MeshData;
use fixshade_host::scene_desc::MeshDesc;
use fixshade_host::scene_kernel::KernelScene;
use fixshade_host::standard_scenes::{bunny_mesh, s1, s2, s4};

use crate::heap::counted;

#[track_caller]
fn assert_no_alloc<R>(what: &str, f: impl FnOnce() -> R) -> R {
    let (r, n) = counted(f);
    assert_eq!(n, 0, "{what}: {n} heap events");
    r
}

/// The counter sees allocations at all (else every test here would pass
/// vacuously).
#[test]
fn the_counter_counts() {
    let (v, n) = counted(|| vec![7u8; 100]);
    assert!(n >= 1, "a Vec allocation was not counted");
    let (_, n) = counted(move || drop(v));
    assert!(n >= 1, "a deallocation was not counted");
    let (_, n) = counted(|| std::hint::black_box(3 + 4));
    assert_eq!(n, 0);
}

/// A mesh in the kernel's format (owned, converted outside the counted
/// regions; zero normals where the description has none).
struct KernelMesh {
    positions: Vec<[i16; 3]>,
    bounds: Bounds,
    normals: Vec<PackedNormal>,
    indices: Vec<[u16; 3]>,
}

impl KernelMesh {
    fn from_desc(d: &MeshDesc) -> KernelMesh {
        let data = MeshData::from_desc(d).expect("mesh converts");
        let n = data.positions.len();
        KernelMesh {
            normals: data.normals.unwrap_or(vec![PackedNormal::ZERO; n]),
            positions: data.positions,
            bounds: data.bounds,
            indices: data.indices,
        }
    }

    fn mesh(&self) -> Mesh<'_> {
        Mesh::new(&self.positions, self.bounds, &self.indices).with_normals(&self.normals)
    }
}

const W: u32 = 320;
const H: u32 = 240;

struct Buffers {
    pixels: Vec<u16>,
    depth: Vec<u16>,
    cache: Vec<CachedVertex>,
}

impl Buffers {
    fn new(vertices: usize) -> Buffers {
        Buffers {
            pixels: vec![0; (W * H) as usize],
            depth: vec![0; (W * H) as usize],
            cache: vec![CachedVertex::default(); vertices],
        }
    }

    fn lit_pixels(&self) -> usize {
        self.pixels.iter().filter(|&&p| p != 0).count()
    }
}

fn sphere_camera() -> Camera {
    Camera::look_at([0.0, 0.0, 3.0], [0.0; 3], [0.0, 1.0, 0.0])
        .and_then(|c| c.with_projection(Projection::Perspective { fovy_deg: 60.0 }, 0.1, 10.0))
        .expect("camera")
}

fn bunny_camera() -> Camera {
    Camera::look_at([0.0, 5.0, 16.0], [0.0, 4.0, 0.0], [0.0, 1.0, 0.0])
        .and_then(|c| c.with_projection(Projection::Perspective { fovy_deg: 45.0 }, 0.5, 50.0))
        .expect("camera")
}

fn rgb(r: f32, g: f32, b: f32) -> Rgb {
    Rgb::from_f32(r, g, b).expect("colour")
}

/// Every kind of light, as a run-time list.
fn any_lights() -> heapless::Vec<AnyLight, 8> {
    let mut v = heapless::Vec::new();
    let lights = [
        AnyLight::Directional(DirectionalLight::new([1.0, 1.0, 1.0]).expect("light")),
        AnyLight::Point(
            PointLight::new([6.0, 10.0, 8.0])
                .expect("light")
                .with_diffuse(rgb(0.8, 0.7, 0.6))
                .with_attenuation(Attenuation::new(1.0, 0.02, 0.001).expect("att")),
        ),
        AnyLight::Spot(
            SpotLight::new([-6.0, 12.0, 6.0], [0.5, -1.0, -0.5], 25.0, 8.0)
                .expect("spot")
                .with_diffuse(rgb(0.3, 0.4, 0.9)),
        ),
        AnyLight::Area(
            AreaLight::new([0.0, 6.0, 4.0], [2.0, 0.0, 0.0], [0.0, 0.0, 2.0], 3)
                .expect("area")
                .with_diffuse(rgb(0.2, 0.2, 0.2)),
        ),
    ];
    for l in lights {
        v.push(l).expect("capacity");
    }
    v
}

#[test]
fn lighting_shade_does_not_allocate() {
    // Inputs prepared outside the counted region.
    let inputs: Vec<(Vec3, Unit3)> = (0..4000)
        .map(|i| {
            let t = i as f64 * 0.0137;
            let p = [3.0 * t.sin(), 2.0 * (1.7 * t).cos(), -2.0 - (0.3 * t).sin()];
            let n = [t.cos(), (2.3 * t).sin(), 0.5 + (0.7 * t).cos()];
            (
                Vec3::from_f64(p).expect("p"),
                unit_from_f64(n).unwrap_or(Unit3::Z),
            )
        })
        .collect();
    let lights = any_lights();
    let tuple = (
        DirectionalLight::new([0.2, 0.5, 1.0]).expect("light"),
        PointLight::new([1.0, 2.0, 3.0]).expect("light"),
        SpotLight::new([0.0, 3.0, 0.0], [0.0, -1.0, 0.0], 40.0, 4.0).expect("spot"),
    );
    let base = Material::new().with_emission(rgb(0.05, 0.0, 0.0));
    let blinn = base.with_specular(BlinnPhong {
        color: rgb(0.5, 0.5, 0.5),
        shininess: Exponent::from_int(64),
    });
    let phong = base.with_specular(Phong {
        color: rgb(0.7, 0.6, 0.5),
        shininess: Exponent::from_int(1000),
    });
    let ambient = rgb(0.1, 0.1, 0.1);
    let view = sphere_camera().view;

    let sum = assert_no_alloc("Lighting::new + shade", || {
        let a = Lighting::<_, LocalViewer, _>::new(&blinn, ambient, &lights, &view);
        let b = Lighting::<_, InfiniteViewer, _>::new(&phong, ambient, &tuple, &view);
        let c = Lighting::<_, InfiniteViewer, _>::new(&base, ambient, &lights, &Mat4::IDENTITY);
        let mut sum = 0u64;
        for &(p, n) in &inputs {
            for s in [a.shade(p, n), b.shade(p, n), c.shade(p, n)] {
                sum += s.to_bits().iter().map(|&v| v as u64).sum::<u64>();
            }
        }
        sum
    });
    assert!(sum > 0, "nothing was lit");
}

#[test]
fn vertex_normals_do_not_allocate() {
    let m = KernelMesh::from_desc(&bunny_mesh());
    let mut sums = vec![[0i32; 3]; m.positions.len()];
    let mut out = vec![PackedNormal::ZERO; m.positions.len()];
    let bare = Mesh::new(&m.positions, m.bounds, &m.indices);
    assert_no_alloc("vertex_normals", || {
        vertex_normals(&bare, &mut sums, &mut out).expect("normals")
    });
    let lit = out.iter().filter(|&&n| n != PackedNormal::ZERO).count();
    assert!(lit > m.positions.len() / 2);
}

#[test]
fn sphere_s1_gouraud_with_depth_does_not_allocate() {
    let m = KernelMesh::from_desc(&generate::sphere(48, 24, 1.0));
    let mut b = Buffers::new(m.positions.len());
    let material = Material::new()
        .with_ambient(rgb(1.0, 0.5, 0.2))
        .with_diffuse(rgb(1.0, 0.5, 0.2))
        .with_specular(BlinnPhong {
            color: rgb(0.5, 0.5, 0.5),
            shininess: Exponent::from_int(32),
        });
    let sun = DirectionalLight::new([1.0, 1.0, 1.0]).expect("light");
    let camera = sphere_camera();
    let stats: DrawStats = assert_no_alloc("S1 Gouraud + depth", || {
        let r = Renderer::new(&camera, &material, &sun).with_ambient(rgb(0.1, 0.1, 0.1));
        let mut fb = Framebuffer::new(&mut b.pixels, W, H).expect("fb");
        fb.clear(Rgb565::BLACK);
        let mut depth = DepthBuffer::new(&mut b.depth, W, H).expect("depth");
        depth.clear();
        m.mesh()
            .shaded(&r)
            .with_depth(&mut depth)
            .with_cache(&mut b.cache)
            .draw(&mut fb.canvas())
            .expect("draw")
    });
    assert!(stats.pixels > 10_000, "{stats:?}");
    assert!(b.lit_pixels() > 10_000);
}

#[test]
fn bunny_phong_heapless_lights_does_not_allocate() {
    let desc = bunny_mesh();
    let mut m = KernelMesh::from_desc(&desc);
    let mut sums = vec![[0i32; 3]; m.positions.len()];
    let bare = Mesh::new(&m.positions, m.bounds, &m.indices);
    vertex_normals(&bare, &mut sums, &mut m.normals).expect("normals");
    let mut b = Buffers::new(m.positions.len());
    let material = Material::new()
        .with_ambient(rgb(0.6, 0.6, 0.7))
        .with_diffuse(rgb(0.7, 0.7, 0.8))
        .with_specular(BlinnPhong {
            color: rgb(0.6, 0.6, 0.6),
            shininess: Exponent::from_int(64),
        });
    let lights = any_lights();
    let camera = bunny_camera();
    let stats = assert_no_alloc("bunny Phong + depth, heapless lights", || {
        let r = Renderer::new(&camera, &material, &lights)
            .with_ambient(rgb(0.1, 0.1, 0.1))
            .with_viewer(LocalViewer)
            .with_shading(PhongShading);
        let mut fb = Framebuffer::new(&mut b.pixels, W, H).expect("fb");
        fb.clear(Rgb565::BLACK);
        let mut depth = DepthBuffer::new(&mut b.depth, W, H).expect("depth");
        depth.clear();
        m.mesh()
            .shaded(&r)
            .with_depth(&mut depth)
            .with_cache(&mut b.cache)
            .draw(&mut fb.canvas())
            .expect("draw")
    });
    assert!(stats.pixels > 5_000, "{stats:?}");
    assert!(b.lit_pixels() > 5_000);
}

#[test]
fn bunny_tuple_lights_two_sided_without_depth_does_not_allocate() {
    let mut m = KernelMesh::from_desc(&bunny_mesh());
    let mut sums = vec![[0i32; 3]; m.positions.len()];
    let bare = Mesh::new(&m.positions, m.bounds, &m.indices);
    vertex_normals(&bare, &mut sums, &mut m.normals).expect("normals");
    let mut b = Buffers::new(m.positions.len());
    let material = Material::new().with_specular(Phong {
        color: rgb(0.4, 0.4, 0.4),
        shininess: Exponent::from_int(20),
    });
    let lights = (
        PointLight::new([6.0, 10.0, 8.0]).expect("light"),
        SpotLight::new([-6.0, 12.0, 6.0], [0.5, -1.0, -0.5], 25.0, 8.0).expect("spot"),
    );
    let camera = bunny_camera();
    let options = RenderOptions {
        cull: false,
        two_sided: true,
        dither: true,
    };
    let stats = assert_no_alloc("bunny Gouraud, tuple lights, no depth", || {
        let r = Renderer::new(&camera, &material, &lights)
            .with_ambient(rgb(0.1, 0.1, 0.1))
            .with_options(options);
        let mut fb = Framebuffer::new(&mut b.pixels, W, H).expect("fb");
        m.mesh()
            .shaded(&r)
            .with_cache(&mut b.cache)
            .draw(&mut fb.canvas())
            .expect("draw")
    });
    assert!(stats.pixels > 5_000, "{stats:?}");
}

#[test]
fn flat_with_and_without_depth_does_not_allocate() {
    let m = KernelMesh::from_desc(&generate::torus(1.0, 0.4, 32, 16));
    let mut b = Buffers::new(m.positions.len());
    let material = Material::new().with_diffuse(rgb(0.2, 0.9, 0.4));
    let lights = [
        DirectionalLight::new([0.0, 1.0, 1.0]).expect("light"),
        DirectionalLight::new([1.0, -1.0, 0.5]).expect("light"),
    ];
    let camera = Camera::look_at([0.3, 2.0, 3.0], [0.0; 3], [0.0, 1.0, 0.0])
        .and_then(|c| c.with_projection(Projection::Perspective { fovy_deg: 50.0 }, 0.2, 20.0))
        .expect("camera");
    let (with, without) = assert_no_alloc("flat torus, depth and no depth", || {
        let r = Renderer::new(&camera, &material, &lights)
            .with_ambient(rgb(0.1, 0.1, 0.1))
            .with_shading(Flat)
            .with_options(RenderOptions {
                cull: false,
                ..RenderOptions::default()
            });
        let mut fb = Framebuffer::new(&mut b.pixels, W, H).expect("fb");
        let mut depth = DepthBuffer::new(&mut b.depth, W, H).expect("depth");
        depth.clear();
        let with = m
            .mesh()
            .shaded(&r)
            .with_depth(&mut depth)
            .with_cache(&mut b.cache)
            .draw(&mut fb.canvas())
            .expect("draw");
        let without = m
            .mesh()
            .shaded(&r)
            .with_cache(&mut b.cache)
            .draw(&mut fb.canvas())
            .expect("draw");
        (with, without)
    });
    assert!(with.pixels > 5_000, "{with:?}");
    // Without culling or depth every layer is drawn: more pixels.
    assert!(without.pixels > with.pixels, "{with:?} {without:?}");
}

/// The host bridge's `render` (not `render_frame`, which allocates its
/// output by design) on the standard scenes, every shading mode.
#[test]
fn kernel_scene_render_does_not_allocate() {
    for (name, scene) in [("S1", s1(W, H)), ("S2", s2(W, H)), ("S4", s4(W, H))] {
        for shading in [
            fixshade_host::scene_desc::Shading::Flat,
            fixshade_host::scene_desc::Shading::Gouraud,
            fixshade_host::scene_desc::Shading::Phong,
        ] {
            let mut scene = scene.clone();
            scene.shading = shading;
            let k = KernelScene::new(&scene).expect("kernel scene");
            let mut b = Buffers::new(scene.mesh.positions.len());
            let stats = assert_no_alloc(&format!("{name} {shading:?}"), || {
                let mut fb = Framebuffer::new(&mut b.pixels, W, H).expect("fb");
                k.render(&mut fb.canvas(), &mut b.depth, &mut b.cache)
                    .expect("render")
            });
            assert!(stats.pixels > 1_000, "{name} {shading:?}: {stats:?}");
        }
    }
}
