//! Host only: a [`SceneDesc`] rendered with the fixed-point kernel, the
//! same scene the f64 reference renders, so that the two can be compared
//! pixel by pixel.
//!
//! [`KernelScene::new`] converts the description once (the mesh to the
//! kernel's flash format through [`mesh_convert`](crate::mesh_convert),
//! lights to [`AnyLight`]); the reference is to render
//! [`KernelScene::reference_scene`], the description with the converted
//! mesh dequantised, so that both draw the same mesh;
//! [`KernelScene::render`] renders it into a framebuffer, choosing the
//! kernel's type parameters (specular model, viewer, shading mode, depth
//! test) from the description's run-time values. A material whose specular
//! colour is black is rendered with [`NoSpecular`](fixshade::material::NoSpecular): it is the same image.

use std::vec;
use std::vec::Vec;

use embedded_graphics::draw_target::DrawTarget;
use embedded_graphics::geometry::{Dimensions, OriginDimensions, Size};
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::primitives::Rectangle;
use embedded_graphics::Pixel;

use crate::mesh_convert::{ConvertError, MeshData};
use crate::scene_desc::{self, LightDesc, SceneDesc, SpecularModel};
use fixshade::band::{Bands, Cached};
use fixshade::camera::{Camera, CameraError, Projection};
use fixshade::color::{Rgb, Shade};
use fixshade::depth::{DepthBand, DepthBuffer, NoDepth};
use fixshade::framebuffer::Framebuffer;
use fixshade::illumination::{InfiniteViewer, LocalViewer, Viewer};
use fixshade::light::LightSet;
use fixshade::light::{
    unit_from_f64, AnyLight, AreaLight, Attenuation, DirectionalLight, LightError, PointLight,
    SpotCone, SpotLight,
};
use fixshade::material::{BlinnPhong, Material, Phong, Specular};
use fixshade::mesh::{Mesh, MeshError};
use fixshade::num::WidePoint;
use fixshade::render::{
    CachedVertex, DrawStats, Flat, Gouraud, PhongShading, RenderError, RenderOptions, ShadingMode,
};
use fixshade::vector::{FormatError, Mat4, Vec3};
use fixshade::Exponent;
use fixshade::{FrameDepth, Renderer, Shaded};

/// The most lights a scene may have here.
///
/// ```
/// use fixshade_host::scene_desc::LightDesc;
/// use fixshade_host::scene_kernel::{KernelScene, KernelSceneError, MAX_LIGHTS};
/// use fixshade_host::standard_scenes::sphere_scene;
/// let mut s = sphere_scene(8, 8, 12, 6);
/// s.lights = vec![LightDesc::point([0.0, 3.0, 0.0]); MAX_LIGHTS];
/// assert!(KernelScene::new(&s).is_ok());
/// s.lights.push(LightDesc::directional([0.0, 0.0, 1.0]));
/// assert_eq!(KernelScene::new(&s).unwrap_err(), KernelSceneError::TooManyLights);
/// ```
pub const MAX_LIGHTS: usize = 64;

/// Why a scene cannot be rendered by the kernel.
///
/// ```
/// use fixshade_host::scene_kernel::{KernelScene, KernelSceneError};
/// use fixshade_host::standard_scenes::sphere_scene;
/// let mut s = sphere_scene(8, 8, 12, 6);
/// s.mesh.positions[0] = [1000.0, 0.0, 0.0]; // beyond I8F24's ±128
/// let err = KernelScene::new(&s).unwrap_err();
/// // Validation refuses what the kernel would, with the same message.
/// assert_eq!(s.validate().unwrap_err().to_string(), err.to_string());
/// assert!(matches!(err, KernelSceneError::Format("mesh.positions", _)));
/// assert!(err.to_string().starts_with("mesh.positions: "));
/// ```
#[derive(Clone, Debug, PartialEq)]
pub enum KernelSceneError {
    /// A value does not fit a kernel format (the field is named).
    Format(&'static str, FormatError),
    /// A light could not be built (its index).
    Light(usize, LightError),
    /// The camera could not be built.
    Camera(CameraError),
    /// A mesh error, found while deriving the vertex normals.
    Mesh(MeshError),
    /// More than [`MAX_LIGHTS`] lights.
    TooManyLights,
    /// The mesh has more vertices than `u16` indices reach.
    TooManyVertices,
}

impl core::fmt::Display for KernelSceneError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            KernelSceneError::Format(what, e) => write!(f, "{what}: {e}"),
            KernelSceneError::Light(i, e) => write!(f, "lights[{i}]: {e}"),
            KernelSceneError::Camera(e) => write!(f, "camera: {e}"),
            KernelSceneError::Mesh(e) => write!(f, "mesh: {e}"),
            KernelSceneError::TooManyLights => write!(f, "lights: more than {MAX_LIGHTS}"),
            KernelSceneError::TooManyVertices => f.write_str("mesh: more than 65536 vertices"),
        }
    }
}

impl std::error::Error for KernelSceneError {}

/// A scene converted to the kernel's formats.
///
/// ```
/// use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
/// use fixshade_host::{scene_kernel::KernelScene, standard_scenes::sphere_scene};
/// let mut s = sphere_scene(16, 8, 12, 6);
/// s.background = [1.0, 0.0, 0.0];
/// let k = KernelScene::new(&s).unwrap();
/// assert_eq!((k.width, k.height), (16, 8));
/// assert_eq!(k.background, Rgb565::RED);
/// ```
#[derive(Clone, Debug)]
pub struct KernelScene {
    /// Viewport width.
    pub width: u32,
    /// Viewport height.
    pub height: u32,
    mesh: MeshData,
    camera: Camera,
    model: Mat4,
    emission: Rgb,
    ambient: Rgb,
    diffuse: Rgb,
    specular: Rgb,
    shininess: Exponent,
    global_ambient: Rgb,
    lights: heapless::Vec<AnyLight, MAX_LIGHTS>,
    /// The description, its mesh replaced by the converted one, dequantised.
    desc: SceneDesc,
    /// Background colour.
    pub background: Rgb565,
}

fn rgb(what: &'static str, c: [f64; 3]) -> Result<Rgb, KernelSceneError> {
    Rgb::from_f64(c).map_err(|e| KernelSceneError::Format(what, e))
}

/// A scene's camera, model, material and lights in kernel formats.
struct Parts {
    camera: Camera,
    model: Mat4,
    /// Emission, ambient, diffuse, specular, global ambient.
    colours: [Rgb; 5],
    shininess: Exponent,
    lights: heapless::Vec<AnyLight, MAX_LIGHTS>,
}

impl Parts {
    fn new(d: &SceneDesc) -> Result<Parts, KernelSceneError> {
        let c = &d.camera;
        let projection = match c.projection {
            scene_desc::Projection::Perspective { fovy_deg } => Projection::Perspective {
                fovy_deg: fovy_deg as f32,
            },
            scene_desc::Projection::Orthographic { height } => Projection::Orthographic {
                height: height as f32,
            },
        };
        let camera = Camera::look_at_f64(c.eye, c.target, c.up)
            .and_then(|cam| cam.with_projection(projection, c.near as f32, c.far as f32))
            .map_err(KernelSceneError::Camera)?;
        let model = Mat4::from_f64(d.model).map_err(|e| KernelSceneError::Format("model", e))?;
        let m = &d.material;
        let mut lights = heapless::Vec::new();
        for (i, l) in d.lights.iter().enumerate() {
            let kl = convert_light(l).map_err(|e| KernelSceneError::Light(i, e))?;
            lights
                .push(kl)
                .map_err(|_| KernelSceneError::TooManyLights)?;
        }
        Ok(Parts {
            camera,
            model,
            colours: [
                rgb("material.emission", m.emission)?,
                rgb("material.ambient", m.ambient)?,
                rgb("material.diffuse", m.diffuse)?,
                rgb("material.specular", m.specular)?,
                rgb("global_ambient", d.global_ambient)?,
            ],
            shininess: Exponent::from_f64(m.shininess)
                .map_err(|e| KernelSceneError::Format("material.shininess", e))?,
            lights,
        })
    }
}

/// What the kernel would refuse to render of a description that is
/// otherwise valid: a value outside a kernel format, too many lights or
/// vertices, a camera or projection that does not fit; checked without
/// converting the mesh ([`SceneDesc::validate`] calls it, so that a scene
/// that passes validation renders).
pub(crate) fn check(d: &SceneDesc) -> Result<(), KernelSceneError> {
    if d.mesh.positions.len() > 65536 {
        return Err(KernelSceneError::TooManyVertices);
    }
    for p in &d.mesh.positions {
        Vec3::from_f64(*p).map_err(|e| KernelSceneError::Format("mesh.positions", e))?;
    }
    let parts = Parts::new(d)?;
    if d.width > 0 && d.height > 0 {
        parts
            .camera
            .projection_for(d.width, d.height)
            .map_err(KernelSceneError::Camera)?;
    }
    Ok(())
}

impl KernelScene {
    /// Converts a description (which should have passed
    /// [`SceneDesc::validate`]).
    ///
    /// ```
    /// use fixshade_host::{scene_kernel::KernelScene, standard_scenes::sphere_scene};
    /// let mut s = sphere_scene(16, 16, 12, 6);
    /// s.mesh.normals = None; // derived in fixed point
    /// let k = KernelScene::new(&s).unwrap();
    /// let mesh = k.mesh();
    /// assert_eq!(mesh.indices().len(), s.mesh.indices.len());
    /// assert_eq!(mesh.normals.map(|n| n.len()), Some(s.mesh.positions.len()));
    /// ```
    pub fn new(d: &SceneDesc) -> Result<KernelScene, KernelSceneError> {
        let mut mesh = MeshData::from_desc(&d.mesh).map_err(|e| match e {
            ConvertError::Position { error, .. } => {
                KernelSceneError::Format("mesh.positions", error)
            }
            ConvertError::TooManyVertices(_) => KernelSceneError::TooManyVertices,
            ConvertError::NormalCount { .. } => KernelSceneError::Mesh(MeshError::NormalCount),
            ConvertError::Mesh(e) => KernelSceneError::Mesh(e),
        })?;
        // The reference derives its own normals (in f64) where the
        // description has none, from the same quantised positions.
        let desc = SceneDesc {
            mesh: mesh.to_desc(),
            ..d.clone()
        };
        mesh.derive_normals().map_err(KernelSceneError::Mesh)?;
        let parts = Parts::new(d)?;
        Ok(KernelScene {
            width: d.width,
            height: d.height,
            mesh,
            camera: parts.camera,
            model: parts.model,
            emission: parts.colours[0],
            ambient: parts.colours[1],
            diffuse: parts.colours[2],
            specular: parts.colours[3],
            shininess: parts.shininess,
            global_ambient: parts.colours[4],
            lights: parts.lights,
            background: Shade::from_bits(
                (d.background[0].clamp(0.0, 1.0) * 65536.0 + 0.5) as u32,
                (d.background[1].clamp(0.0, 1.0) * 65536.0 + 0.5) as u32,
                (d.background[2].clamp(0.0, 1.0) * 65536.0 + 0.5) as u32,
            )
            .to_rgb565(),
            desc,
        })
    }

    /// The mesh in the kernel's format.
    ///
    /// ```
    /// use fixshade_host::{scene_kernel::KernelScene, standard_scenes::sphere_scene};
    /// let s = sphere_scene(16, 16, 12, 6);
    /// let k = KernelScene::new(&s).unwrap();
    /// let mesh = k.mesh();
    /// assert!(mesh.validate().is_ok());
    /// let p = mesh.bounds.position_f64(mesh.positions[7]);
    /// assert_eq!(p, k.reference_scene().mesh.positions[7]);
    /// assert!((0..3).all(|i| (p[i] - s.mesh.positions[7][i]).abs() < 2.0 / 65535.0));
    /// assert_eq!(mesh.indices()[7], s.mesh.indices[7]);
    /// ```
    pub fn mesh(&self) -> Mesh<'_> {
        self.mesh.mesh()
    }

    /// The scene as the kernel draws it, for the f64 reference: the
    /// description with its mesh replaced by the converted one,
    /// dequantised ([`MeshData::to_desc`]; normals it had are decoded,
    /// missing ones stay missing, for the reference to derive).
    ///
    /// ```
    /// use fixshade_host::{error_measure::compare, reference::render, scene_kernel::KernelScene};
    /// use fixshade_host::standard_scenes::sphere_scene;
    /// let k = KernelScene::new(&sphere_scene(32, 24, 12, 6)).unwrap();
    /// let frame = k.render_frame().unwrap();
    /// let e = compare(&frame.pixels, &frame.covered, &render(k.reference_scene()).unwrap());
    /// assert!(e.max_error.iter().all(|&m| m <= 1), "{e}");
    /// ```
    pub fn reference_scene(&self) -> &SceneDesc {
        &self.desc
    }

    /// Renders into `target` (after clearing it and `depth` when the scene
    /// has a depth test). `cache` needs one slot per vertex; `depth` one
    /// `u16` per pixel if the scene has a depth test.
    ///
    /// ```
    /// use fixshade::{framebuffer::Framebuffer, render::{CachedVertex, RenderError}};
    /// use fixshade_host::{scene_kernel::KernelScene, standard_scenes::sphere_scene};
    /// let k = KernelScene::new(&sphere_scene(32, 24, 12, 6)).unwrap();
    /// let (mut px, mut depth) = ([0u16; 32 * 24], [0u16; 32 * 24]);
    /// let mut cache = vec![CachedVertex::default(); k.mesh().positions.len()];
    /// let mut fb = Framebuffer::new(&mut px, 32, 24).unwrap();
    /// // Any DrawTarget; here the framebuffer's (`Framebuffer::canvas`).
    /// let stats = k.render(&mut fb.canvas(), &mut depth, &mut cache).unwrap();
    /// assert!(stats.pixels > 100);
    /// assert_eq!(fb.pixel(0, 0), Some(k.background)); // cleared, not drawn
    /// let short = k.render(&mut fb.canvas(), &mut depth[..100], &mut cache);
    /// assert_eq!(short, Err(RenderError::DepthTooSmall));
    /// ```
    pub fn render<T: DrawTarget<Color = Rgb565>>(
        &self,
        target: &mut T,
        depth: &mut [u16],
        cache: &mut [CachedVertex],
    ) -> Result<DrawStats, RenderError<T::Error>> {
        target.clear(self.background).map_err(RenderError::Target)?;
        let size = target.bounding_box().size;
        self.dispatch(&mut TargetDrawer(target), size, depth, cache)
    }

    /// As [`KernelScene::render`], into a [`Framebuffer`] through the
    /// kernel's framebuffer fast path.
    ///
    /// ```
    /// use fixshade::{framebuffer::Framebuffer, render::CachedVertex};
    /// use fixshade_host::{scene_kernel::KernelScene, standard_scenes::sphere_scene};
    /// let k = KernelScene::new(&sphere_scene(32, 24, 12, 6)).unwrap();
    /// let frame = k.render_frame().unwrap(); // through `render`
    /// let (mut px, mut depth) = ([0u16; 32 * 24], [0u16; 32 * 24]);
    /// let mut cache = vec![CachedVertex::default(); k.mesh().positions.len()];
    /// let mut fb = Framebuffer::new(&mut px, 32, 24).unwrap();
    /// let stats = k.render_framebuffer(&mut fb, &mut depth, &mut cache).unwrap();
    /// assert_eq!(fb.as_slice(), &frame.pixels[..]);
    /// assert_eq!(stats, frame.stats);
    /// ```
    pub fn render_framebuffer(
        &self,
        fb: &mut Framebuffer,
        depth: &mut [u16],
        cache: &mut [CachedVertex],
    ) -> Result<DrawStats, RenderError<core::convert::Infallible>> {
        fb.clear(self.background);
        let size = fb.size();
        self.dispatch(&mut FbDrawer(fb), size, depth, cache)
    }

    fn dispatch<W: Drawer>(
        &self,
        out: &mut W,
        size: Size,
        depth: &mut [u16],
        cache: &mut [CachedVertex],
    ) -> Result<DrawStats, RenderError<W::Error>> {
        let blinn = self.desc.specular_model == SpecularModel::Blinn;
        let c = (self.specular, self.shininess);
        if c.0.is_black() {
            self.with_viewer(Material::new(), out, size, depth, cache)
        } else if blinn {
            let s = BlinnPhong {
                color: c.0,
                shininess: c.1,
            };
            self.with_viewer(Material::new().with_specular(s), out, size, depth, cache)
        } else {
            let s = Phong {
                color: c.0,
                shininess: c.1,
            };
            self.with_viewer(Material::new().with_specular(s), out, size, depth, cache)
        }
    }

    fn with_viewer<S: Specular, W: Drawer>(
        &self,
        m: Material<S>,
        out: &mut W,
        size: Size,
        depth: &mut [u16],
        cache: &mut [CachedVertex],
    ) -> Result<DrawStats, RenderError<W::Error>> {
        let m = m
            .with_emission(self.emission)
            .with_ambient(self.ambient)
            .with_diffuse(self.diffuse);
        match self.desc.viewer {
            scene_desc::Viewer::Infinite => self.draw(&m, InfiniteViewer, out, size, depth, cache),
            scene_desc::Viewer::Local => self.draw(&m, LocalViewer, out, size, depth, cache),
        }
    }

    fn draw<S: Specular, V: Viewer, W: Drawer>(
        &self,
        m: &Material<S>,
        viewer: V,
        out: &mut W,
        size: Size,
        depth: &mut [u16],
        cache: &mut [CachedVertex],
    ) -> Result<DrawStats, RenderError<W::Error>> {
        let options = RenderOptions {
            cull: self.desc.cull,
            two_sided: self.desc.two_sided,
            dither: self.desc.dither,
        };
        let r = Renderer::new(&self.camera, m, &self.lights)
            .with_ambient(self.global_ambient)
            .with_viewer(viewer)
            .with_options(options);
        let job = Job {
            mesh: self.mesh(),
            model: self.model,
            size,
            depth,
            has_depth: self.desc.depth,
            cache,
        };
        use scene_desc::Shading as Sh;
        match self.desc.shading {
            Sh::Flat => out.draw_scene(&r.with_shading(Flat), job),
            Sh::Gouraud => out.draw_scene(&r.with_shading(Gouraud), job),
            Sh::Phong => out.draw_scene(&r.with_shading(PhongShading), job),
        }
    }

    /// Renders into `target` band by band ([`Bands`]): bands of `band_height` rows through
    /// `colour` (at least `width × band_height` pixels) and, if the scene
    /// has a depth test, `depth` (as many values). `vertices`: `Some` cache
    /// of one [`CachedVertex`] per vertex ([`Cached`] mode), or `None`
    /// ([`Recomputed`](fixshade::band::Recomputed)). The pixels are those
    /// of [`KernelScene::render`].
    ///
    /// ```
    /// use fixshade::{render::CachedVertex, framebuffer::Framebuffer};
    /// use fixshade_host::{scene_kernel::KernelScene, standard_scenes::sphere_scene};
    /// let k = KernelScene::new(&sphere_scene(32, 24, 12, 6)).unwrap();
    /// let frame = k.render_frame().unwrap(); // through `render`
    /// let mut px = [0u16; 32 * 24];
    /// let mut fb = Framebuffer::new(&mut px, 32, 24).unwrap();
    /// let (mut colour, mut depth) = ([0u16; 32 * 5], [0u16; 32 * 5]); // bands of 5 rows
    /// let mut vertices = vec![CachedVertex::default(); k.mesh().positions.len()];
    /// let cached = Some(&mut vertices[..]);
    /// k.render_bands(&mut fb.canvas(), 5, &mut colour, &mut depth, cached).unwrap();
    /// assert_eq!(fb.as_slice(), &frame.pixels[..]);
    /// k.render_bands(&mut fb.canvas(), 5, &mut colour, &mut depth, None).unwrap();
    /// assert_eq!(fb.as_slice(), &frame.pixels[..]);
    /// ```
    pub fn render_bands<T: DrawTarget<Color = Rgb565>>(
        &self,
        target: &mut T,
        band_height: u32,
        colour: &mut [u16],
        depth: &mut [u16],
        vertices: Option<&mut [CachedVertex]>,
    ) -> Result<DrawStats, RenderError<T::Error>> {
        let mut bands = Bands::new(target, colour, band_height).with_background(self.background);
        self.render_in_bands(&mut bands, depth, vertices)
    }

    /// Renders into `bands`, which the caller builds: the target, the
    /// colour band and its rows, the background (the pixels of
    /// [`KernelScene::render`] are those with [`KernelScene::background`]),
    /// and, with [`Bands::interleaved`], which of the bands this worker
    /// draws. `depth` and `vertices` as for [`KernelScene::render_bands`].
    ///
    /// ```
    /// use fixshade::{band::Bands, framebuffer::Framebuffer, render::CachedVertex};
    /// use fixshade_host::{scene_kernel::KernelScene, standard_scenes::sphere_scene};
    /// let k = KernelScene::new(&sphere_scene(32, 24, 12, 6)).unwrap();
    /// let frame = k.render_frame().unwrap(); // through `render`
    /// let (mut even, mut odd) = ([0u16; 32 * 24], [0u16; 32 * 24]);
    /// for (worker, px) in [(0, &mut even), (1, &mut odd)] {
    ///     let mut fb = Framebuffer::new(px, 32, 24).unwrap();
    ///     let mut display = fb.canvas();
    ///     let (mut colour, mut depth) = ([0u16; 32 * 4], [0u16; 32 * 4]); // bands of 4 rows
    ///     let mut bands = Bands::new(&mut display, &mut colour, 4)
    ///         .with_background(k.background)
    ///         .interleaved(worker, 2);
    ///     k.render_in_bands(&mut bands, &mut depth, None).unwrap();
    /// }
    /// // Rows 0–3 from worker 0, 4–7 from worker 1, 8–11 from worker 0, …
    /// let row = |y: usize| if (y / 4) % 2 == 0 { &even[y * 32..][..32] } else { &odd[y * 32..][..32] };
    /// assert!((0..24).all(|y| row(y) == &frame.pixels[y * 32..][..32]));
    /// ```
    pub fn render_in_bands<T: DrawTarget<Color = Rgb565>>(
        &self,
        bands: &mut Bands<'_, '_, T>,
        depth: &mut [u16],
        vertices: Option<&mut [CachedVertex]>,
    ) -> Result<DrawStats, RenderError<T::Error>> {
        let size = bands.target().bounding_box().size;
        let mut out = BandDrawer { bands, vertices };
        self.dispatch(&mut out, size, depth, &mut [])
    }

    /// Renders into fresh buffers and records which pixels were drawn.
    ///
    /// ```
    /// use fixshade_host::{error_measure::compare, reference::render, scene_kernel::KernelScene};
    /// use fixshade_host::standard_scenes::sphere_scene;
    /// let k = KernelScene::new(&sphere_scene(32, 24, 12, 6)).unwrap();
    /// let frame = k.render_frame().unwrap();
    /// let e = compare(&frame.pixels, &frame.covered, &render(k.reference_scene()).unwrap());
    /// assert!(e.covered_both > 100);
    /// assert!(e.max_error.iter().all(|&m| m <= 1), "{e}"); // the kernel's 1 LSB bound
    /// assert!(e.coverage_mismatch_share <= 0.001, "{e}");
    /// ```
    pub fn render_frame(&self) -> Result<KernelFrame, RenderError<core::convert::Infallible>> {
        let (w, h) = (self.width, self.height);
        let n = w as usize * h as usize;
        let mut pixels = vec![0u16; n];
        let mut covered = vec![false; n];
        let mut depth = vec![0u16; n];
        let mut cache = vec![CachedVertex::default(); self.mesh.positions.len()];
        let stats = {
            let fb = Framebuffer::new(&mut pixels, w, h).map_err(|_| RenderError::CacheTooSmall)?;
            let mut rec = CoverageTarget {
                inner: fb,
                covered: &mut covered,
                width: w,
            };
            self.render(&mut rec, &mut depth, &mut cache)?
        };
        Ok(KernelFrame {
            width: w,
            height: h,
            pixels,
            covered,
            stats,
        })
    }
}

fn convert_light(l: &LightDesc) -> Result<AnyLight, LightError> {
    let rgb = |c: [f64; 3]| Rgb::from_f64(c).map_err(LightError::from);
    Ok(match l {
        LightDesc::Directional {
            direction,
            diffuse,
            specular,
        } => AnyLight::Directional(
            DirectionalLight::from_unit(unit_from_f64(*direction)?)
                .with_diffuse(rgb(*diffuse)?)
                .with_specular(rgb(*specular)?),
        ),
        LightDesc::Point {
            position,
            diffuse,
            specular,
            attenuation,
        } => AnyLight::Point(point(*position, *diffuse, *specular, *attenuation)?),
        LightDesc::Spot {
            position,
            axis,
            cutoff_deg,
            exponent,
            diffuse,
            specular,
            attenuation,
        } => AnyLight::Spot(SpotLight {
            light: point(*position, *diffuse, *specular, *attenuation)?,
            cone: SpotCone::from_f64(*axis, *cutoff_deg, *exponent)?,
        }),
        LightDesc::Area {
            center,
            edge_u,
            edge_v,
            samples_k,
            diffuse,
            specular,
            attenuation,
        } => {
            if *samples_k == 0 || *samples_k > AreaLight::MAX_K as u32 {
                return Err(LightError::BadSamples);
            }
            AnyLight::Area(AreaLight {
                center: WidePoint::from_f64(*center)?,
                edge_u: WidePoint::from_f64(*edge_u)?,
                edge_v: WidePoint::from_f64(*edge_v)?,
                samples_k: *samples_k as u8,
                diffuse: rgb(*diffuse)?,
                specular: rgb(*specular)?,
                attenuation: Attenuation::from_f64(*attenuation)?,
            })
        }
    })
}

fn point(p: [f64; 3], d: [f64; 3], s: [f64; 3], a: [f64; 3]) -> Result<PointLight, LightError> {
    Ok(PointLight {
        position: WidePoint::from_f64(p)?,
        diffuse: Rgb::from_f64(d)?,
        specular: Rgb::from_f64(s)?,
        attenuation: Attenuation::from_f64(a)?,
    })
}

/// A kernel frame: raw RGB565 pixels, which pixels the kernel drew, and
/// the draw counts.
///
/// ```
/// use embedded_graphics::pixelcolor::IntoStorage;
/// use fixshade_host::{scene_kernel::KernelScene, standard_scenes::sphere_scene};
/// let k = KernelScene::new(&sphere_scene(32, 24, 12, 6)).unwrap();
/// let f = k.render_frame().unwrap();
/// assert_eq!((f.width, f.height, f.pixels.len()), (32, 24, 32 * 24));
/// let covered = f.covered.iter().filter(|&&c| c).count();
/// assert_eq!(covered, f.stats.pixels as usize); // a convex mesh: no pixel sent twice
/// let bg = k.background.into_storage();
/// assert!(f.pixels.iter().zip(&f.covered).all(|(&p, &c)| c || p == bg));
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct KernelFrame {
    /// Width.
    pub width: u32,
    /// Height.
    pub height: u32,
    /// Raw RGB565, row-major.
    pub pixels: Vec<u16>,
    /// `true` where the kernel sent a pixel.
    pub covered: Vec<bool>,
    /// Counts.
    pub stats: DrawStats,
}

/// A framebuffer that also records which pixels were written (through
/// `fill_contiguous`, the only way the renderer writes).
///
/// ```
/// use embedded_graphics::{pixelcolor::Rgb565, prelude::*};
/// use embedded_graphics::primitives::{PrimitiveStyle, Rectangle};
/// use fixshade::framebuffer::Framebuffer;
/// use fixshade_host::scene_kernel::CoverageTarget;
/// let (mut px, mut covered) = ([0u16; 4 * 3], [false; 4 * 3]);
/// let inner = Framebuffer::new(&mut px, 4, 3).unwrap();
/// let mut t = CoverageTarget { inner, covered: &mut covered, width: 4 };
/// let square = Rectangle::new(Point::new(1, 1), Size::new(2, 2));
/// square.into_styled(PrimitiveStyle::with_fill(Rgb565::RED)).draw(&mut t).unwrap();
/// t.clear(Rgb565::BLUE).unwrap(); // not recorded
/// assert_eq!(covered.iter().filter(|&&c| c).count(), 4);
/// assert!(covered[4 + 1] && !covered[0]);
/// ```
pub struct CoverageTarget<'a, 'b> {
    /// The framebuffer.
    pub inner: Framebuffer<'a>,
    /// One flag per pixel.
    pub covered: &'b mut [bool],
    /// Row length.
    pub width: u32,
}

impl OriginDimensions for CoverageTarget<'_, '_> {
    fn size(&self) -> Size {
        self.inner.size()
    }
}

impl DrawTarget for CoverageTarget<'_, '_> {
    type Color = Rgb565;
    type Error = core::convert::Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(
        &mut self,
        pixels: I,
    ) -> Result<(), Self::Error> {
        let bb = self.inner.bounding_box();
        let w = self.width as usize;
        let cov = &mut *self.covered;
        self.inner
            .canvas()
            .draw_iter(pixels.into_iter().inspect(|Pixel(p, _)| {
                if bb.contains(*p) {
                    cov[p.y as usize * w + p.x as usize] = true;
                }
            }))
    }

    fn fill_contiguous<I: IntoIterator<Item = Rgb565>>(
        &mut self,
        area: &Rectangle,
        colors: I,
    ) -> Result<(), Self::Error> {
        let a = area.intersection(&self.inner.bounding_box());
        for p in embedded_graphics::primitives::PointsIter::points(&a) {
            self.covered[p.y as usize * self.width as usize + p.x as usize] = true;
        }
        self.inner.canvas().fill_contiguous(area, colors)
    }

    fn clear(&mut self, color: Rgb565) -> Result<(), Self::Error> {
        self.inner.clear(color);
        Ok(())
    }
}

/// What [`KernelScene`] draws with a renderer.
struct Job<'j> {
    mesh: Mesh<'j>,
    model: Mat4,
    /// The target's size.
    size: Size,
    /// The depth buffer's storage (the whole frame's or a band's).
    depth: &'j mut [u16],
    /// Whether the scene has a depth test.
    has_depth: bool,
    /// The whole frame's vertex cache.
    cache: &'j mut [CachedVertex],
}

/// Where [`KernelScene`] draws: a whole-frame [`FrameDrawer`], or the band
/// renderer.
trait Drawer {
    type Error;
    /// Draws with a cleared depth buffer over `job.depth` if
    /// `job.has_depth`.
    fn draw_scene<S: Specular, L: LightSet, V: Viewer, M: ShadingMode>(
        &mut self,
        r: &Renderer<S, L, V, M>,
        job: Job,
    ) -> Result<DrawStats, RenderError<Self::Error>>;
}

/// A whole-frame output (a `DrawTarget`, or a framebuffer written in
/// place): one draw call with a depth test of type `D`.
trait FrameDrawer {
    type Error;
    fn draw<S: Specular, L: LightSet, V: Viewer, M: ShadingMode, D: FrameDepth>(
        &mut self,
        shaded: Shaded<'_, '_, Renderer<S, L, V, M>, &mut D, Cached<'_>>,
    ) -> Result<DrawStats, RenderError<Self::Error>>;
}

impl<F: FrameDrawer> Drawer for F {
    type Error = F::Error;
    fn draw_scene<S: Specular, L: LightSet, V: Viewer, M: ShadingMode>(
        &mut self,
        r: &Renderer<S, L, V, M>,
        job: Job,
    ) -> Result<DrawStats, RenderError<Self::Error>> {
        let shaded = job.mesh.shaded(r).with_model(job.model);
        if job.has_depth {
            // Cleared to the far value as made.
            let (w, h) = (job.size.width, job.size.height);
            let mut db =
                DepthBuffer::new(job.depth, w, h).map_err(|_| RenderError::DepthTooSmall)?;
            self.draw(shaded.with_depth(&mut db).with_cache(job.cache))
        } else {
            self.draw(shaded.with_depth(&mut NoDepth).with_cache(job.cache))
        }
    }
}

/// The band renderer into a `DrawTarget`.
struct BandDrawer<'r, 't, 'b, 'c, T> {
    bands: &'r mut Bands<'t, 'b, T>,
    vertices: Option<&'c mut [CachedVertex]>,
}

impl<T: DrawTarget<Color = Rgb565>> Drawer for BandDrawer<'_, '_, '_, '_, T> {
    type Error = T::Error;
    fn draw_scene<S: Specular, L: LightSet, V: Viewer, M: ShadingMode>(
        &mut self,
        r: &Renderer<S, L, V, M>,
        job: Job,
    ) -> Result<DrawStats, RenderError<Self::Error>> {
        let shaded = job.mesh.shaded(r).with_model(job.model);
        let (b, depth) = (&mut *self.bands, job.depth);
        match (job.has_depth, self.vertices.as_deref_mut()) {
            (true, Some(c)) => shaded
                .with_depth(&mut DepthBand::new(depth))
                .with_cache(c)
                .draw(b),
            (true, None) => shaded.with_depth(&mut DepthBand::new(depth)).draw(b),
            (false, Some(c)) => shaded.with_cache(c).draw(b),
            (false, None) => shaded.draw(b),
        }
    }
}

struct TargetDrawer<'t, T>(&'t mut T);

impl<T: DrawTarget<Color = Rgb565>> FrameDrawer for TargetDrawer<'_, T> {
    type Error = T::Error;
    fn draw<S: Specular, L: LightSet, V: Viewer, M: ShadingMode, D: FrameDepth>(
        &mut self,
        shaded: Shaded<'_, '_, Renderer<S, L, V, M>, &mut D, Cached<'_>>,
    ) -> Result<DrawStats, RenderError<T::Error>> {
        shaded.draw(self.0)
    }
}

struct FbDrawer<'t, 'a>(&'t mut Framebuffer<'a>);

impl FrameDrawer for FbDrawer<'_, '_> {
    type Error = core::convert::Infallible;
    fn draw<S: Specular, L: LightSet, V: Viewer, M: ShadingMode, D: FrameDepth>(
        &mut self,
        shaded: Shaded<'_, '_, Renderer<S, L, V, M>, &mut D, Cached<'_>>,
    ) -> Result<DrawStats, RenderError<Self::Error>> {
        shaded.draw(self.0)
    }
}
