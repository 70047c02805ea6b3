//! The host scene description, in `f64`, mirroring `SCENE_FORMAT.md`.
//!
//! A [`SceneDesc`] holds everything one render needs: viewport, camera, model
//! transform, mesh, material, lights and render options. It is what the f64
//! reference ([`crate::reference::render`]) consumes, and what host tools
//! convert into the fixed-point kernel's inputs.
//!
//! # Coordinate spaces
//!
//! * Mesh positions and normals are in **object space**; [`SceneDesc::model`]
//!   takes them to world space.
//! * Camera, light positions, light directions and spot axes are in **world
//!   space**. The renderer transforms light positions by the view matrix into
//!   eye space, and directions and spot axes by the view matrix's rotation
//!   (then normalises them); see [`crate::reference::eye_lights`].
//!
//! # Example
//!
//! ```
//! use fixshade_host::generate::sphere;
//! use fixshade_host::scene_desc::{CameraDesc, LightDesc, Projection, SceneDesc};
//!
//! let camera = CameraDesc {
//!     eye: [0.0, 0.0, 3.0],
//!     target: [0.0, 0.0, 0.0],
//!     up: [0.0, 1.0, 0.0],
//!     near: 0.1,
//!     far: 10.0,
//!     projection: Projection::Perspective { fovy_deg: 45.0 },
//! };
//! let mut scene = SceneDesc::new(64, 64, camera, sphere(16, 8, 1.0));
//! scene.lights.push(LightDesc::directional([0.0, 0.0, 1.0]));
//! assert!(scene.validate().is_ok());
//! ```

use std::fmt;

/// Largest accepted viewport width or height, in pixels.
///
/// ```
/// use fixshade_host::scene_desc::{SceneError, MAX_DIMENSION};
/// use fixshade_host::standard_scenes::sphere_scene;
/// let mut s = sphere_scene(MAX_DIMENSION, 1, 12, 6);
/// assert!(s.validate().is_ok());
/// s.height = MAX_DIMENSION + 1;
/// assert!(matches!(s.validate(), Err(SceneError::TooLarge { max: MAX_DIMENSION, .. })));
/// ```
pub const MAX_DIMENSION: u32 = 8192;

/// The most vertices a mesh may have: as many as `u16` indices reach, the
/// kernel's index format.
///
/// ```
/// use fixshade_host::scene_desc::{SceneError, MAX_VERTICES};
/// use fixshade_host::standard_scenes::sphere_scene;
/// let mut s = sphere_scene(8, 8, 12, 6);
/// s.mesh.positions.resize(MAX_VERTICES, [0.0; 3]);
/// s.mesh.normals = None;
/// assert!(s.validate().is_ok());
/// s.mesh.positions.push([0.0; 3]);
/// assert_eq!(s.validate(), Err(SceneError::TooManyVertices { count: MAX_VERTICES + 1 }));
/// assert_eq!(s.validate().unwrap_err().to_string(), "mesh.positions: 65537 vertices, more than 65536");
/// ```
pub const MAX_VERTICES: usize = 65536;

/// The most light samples a shaded point may take, summed over the lights
/// (an area light of `k × k` samples takes `k²`, any other light 1): one
/// area light of 64 × 64, or 64 lights of 8 × 8.
///
/// ```
/// use fixshade_host::scene_desc::{LightDesc, MAX_LIGHT_SAMPLES};
/// use fixshade_host::standard_scenes::sphere_scene;
/// let mut s = sphere_scene(32, 24, 12, 6);
/// let area = |k| LightDesc::Area { center: [0.0, 3.0, 0.0], edge_u: [1.0, 0.0, 0.0],
///     edge_v: [0.0, 0.0, 1.0], samples_k: k, diffuse: [1.0; 3], specular: [1.0; 3],
///     attenuation: [1.0, 0.0, 0.0] };
/// s.lights = vec![area(64)];
/// assert!(s.validate().is_ok());
/// s.lights = vec![area(64); 2];
/// let err = s.validate().unwrap_err().to_string();
/// assert_eq!(err, "lights: 8192 light samples a shaded point, more than 4096");
/// # assert_eq!(MAX_LIGHT_SAMPLES, 4096);
/// ```
pub const MAX_LIGHT_SAMPLES: u64 = 4096;

/// The most light evaluations a scene may ask for in a frame, counted as
/// its light samples ([`SceneDesc::light_samples`]) times its pixels,
/// vertices and triangles (a bound on what flat, Gouraud and Phong shading
/// evaluate): 2²⁸, a frame of 320 × 240 pixels with 3 400 samples. Each
/// evaluation is some hundreds of instructions in the kernel and in the
/// reference, so a frame stays within about a minute on a desktop.
///
/// ```
/// use fixshade_host::scene_desc::{LightDesc, MAX_LIGHT_EVALUATIONS};
/// use fixshade_host::standard_scenes::sphere_scene;
/// let mut s = sphere_scene(1024, 1024, 12, 6);
/// s.lights = vec![LightDesc::Area { center: [0.0, 3.0, 0.0], edge_u: [1.0, 0.0, 0.0],
///     edge_v: [0.0, 0.0, 1.0], samples_k: 64, diffuse: [1.0; 3], specular: [1.0; 3],
///     attenuation: [1.0, 0.0, 0.0] }];
/// let err = s.validate().unwrap_err().to_string();
/// assert!(err.starts_with("lights: 4096 light samples at 1048"), "{err}");
/// assert!(err.ends_with(&format!("more than {MAX_LIGHT_EVALUATIONS}")));
/// ```
pub const MAX_LIGHT_EVALUATIONS: u64 = 1 << 28;

/// Largest accepted `samples_k` of an area light (it expands to `k²` point lights).
///
/// ```
/// use fixshade_host::scene_desc::*;
/// use fixshade_host::standard_scenes::sphere_scene;
/// let mut s = sphere_scene(8, 8, 12, 6);
/// let area = |samples_k| LightDesc::Area {
///     center: [0.0, 2.0, 0.0], edge_u: [1.0, 0.0, 0.0], edge_v: [0.0, 0.0, 1.0], samples_k,
///     diffuse: WHITE, specular: WHITE, attenuation: DEFAULT_ATTENUATION,
/// };
/// s.lights = vec![area(MAX_AREA_SAMPLES)];
/// assert!(s.validate().is_ok());
/// s.lights = vec![area(MAX_AREA_SAMPLES + 1)];
/// assert!(s.validate().unwrap_err().to_string().starts_with("lights[0].samples_k"));
/// ```
pub const MAX_AREA_SAMPLES: u32 = 64;

/// Default light attenuation `[c0, c1, c2]`: no attenuation.
///
/// ```
/// use fixshade_host::scene_desc::{LightDesc, DEFAULT_ATTENUATION};
/// let [c0, c1, c2] = DEFAULT_ATTENUATION;
/// for d in [0.0, 1.0, 1e6] {
///     assert_eq!(1.0 / (c0 + c1 * d + c2 * d * d), 1.0); // full intensity at any distance
/// }
/// let point = LightDesc::point([0.0, 2.0, 0.0]);
/// assert!(matches!(point, LightDesc::Point { attenuation: DEFAULT_ATTENUATION, .. }));
/// ```
pub const DEFAULT_ATTENUATION: [f64; 3] = [1.0, 0.0, 0.0];

/// Default light intensity (diffuse and specular): white.
///
/// ```
/// use fixshade_host::scene_desc::{LightDesc, WHITE};
/// let LightDesc::Directional { diffuse, specular, .. } = LightDesc::directional([0.0, 0.0, 1.0])
/// else { unreachable!() };
/// assert_eq!((diffuse, specular), (WHITE, WHITE));
/// ```
pub const WHITE: [f64; 3] = [1.0, 1.0, 1.0];

/// The 4 × 4 identity matrix (the default model transform).
///
/// ```
/// use fixshade_host::scene_desc::IDENTITY;
/// use fixshade_host::standard_scenes::sphere_scene;
/// let mut s = sphere_scene(8, 8, 12, 6); // built with `SceneDesc::new`
/// assert_eq!(s.model, IDENTITY);
/// s.model[3] = [0.0, 0.0, 1.0, 1.0]; // no longer affine
/// assert!(s.validate().is_err());
/// ```
pub const IDENTITY: [[f64; 4]; 4] = [
    [1.0, 0.0, 0.0, 0.0],
    [0.0, 1.0, 0.0, 0.0],
    [0.0, 0.0, 1.0, 0.0],
    [0.0, 0.0, 0.0, 1.0],
];

/// A complete scene: viewport, camera, model, mesh, material, lights, options.
///
/// Build one with [`SceneDesc::new`] (which fills every optional field with the
/// defaults of `SCENE_FORMAT.md`) and adjust the public fields.
///
/// ```
/// use fixshade_host::reference::render;
/// use fixshade_host::standard_scenes::sphere_scene;
/// let mut scene = sphere_scene(16, 16, 12, 6); // a unit sphere, 3 units in front of the eye
/// let full = render(&scene).unwrap().covered_count();
/// for i in 0..3 {
///     scene.model[i][i] = 0.5; // half size
/// }
/// assert!(scene.validate().is_ok());
/// assert!(render(&scene).unwrap().covered_count() < full);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct SceneDesc {
    /// Viewport width in pixels (0 gives an empty frame; at most [`MAX_DIMENSION`]).
    pub width: u32,
    /// Viewport height in pixels (0 gives an empty frame; at most [`MAX_DIMENSION`]).
    pub height: u32,
    /// The camera (world space).
    pub camera: CameraDesc,
    /// Model transform, row-major, applied to column vectors (`p_world = model · p`).
    /// Must be affine (bottom row `[0, 0, 0, 1]`) with an invertible 3 × 3 part.
    pub model: [[f64; 4]; 4],
    /// The mesh, in object space.
    pub mesh: MeshDesc,
    /// The surface material.
    pub material: MaterialDesc,
    /// Global ambient intensity `A` (SPEC.md section 3); non-negative.
    pub global_ambient: [f64; 3],
    /// Lights, in world space.
    pub lights: Vec<LightDesc>,
    /// Shading mode.
    pub shading: Shading,
    /// Specular model.
    pub specular_model: SpecularModel,
    /// Local or infinite viewer.
    pub viewer: Viewer,
    /// Back-face culling.
    pub cull: bool,
    /// Depth test.
    pub depth: bool,
    /// Two-sided lighting (negated normal on back faces).
    pub two_sided: bool,
    /// Ordered dithering to RGB565 (the reference ignores it: it never quantises).
    pub dither: bool,
    /// Clear colour, in [0, 1] (the reference does not store it in its frame).
    pub background: [f64; 3],
}

/// The camera: a look-at frame plus a projection, in world space.
///
/// ```
/// use fixshade_host::standard_scenes::sphere_scene;
/// let mut s = sphere_scene(8, 8, 12, 6); // eye at (0, 0, 3) looking at the origin
/// s.camera.up = [0.0, 0.0, 1.0];
/// let err = s.validate().unwrap_err();
/// assert_eq!(err.to_string(), "camera.up: is zero or parallel to the view direction");
/// s.camera.target = s.camera.eye;
/// assert_eq!(s.validate().unwrap_err().to_string(), "camera.target: equals camera.eye");
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct CameraDesc {
    /// Eye position.
    pub eye: [f64; 3],
    /// Point looked at (must differ from `eye`).
    pub target: [f64; 3],
    /// Up vector (must not be parallel to `target − eye`).
    pub up: [f64; 3],
    /// Near plane distance, `> 0`.
    pub near: f64,
    /// Far plane distance, `> near`.
    pub far: f64,
    /// Projection.
    pub projection: Projection,
}

/// The projection of a [`CameraDesc`].
///
/// ```
/// use fixshade_host::scene_desc::Projection;
/// use fixshade_host::standard_scenes::sphere_scene;
/// let mut s = sphere_scene(8, 8, 12, 6);
/// s.camera.projection = Projection::Orthographic { height: 2.5 };
/// assert!(s.validate().is_ok());
/// s.camera.projection = Projection::Perspective { fovy_deg: 180.0 };
/// assert!(s.validate().unwrap_err().to_string().starts_with("camera.fovy_deg"));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Projection {
    /// OpenGL perspective projection with vertical field of view in degrees, in (0, 180).
    Perspective {
        /// Vertical field of view, degrees.
        fovy_deg: f64,
    },
    /// OpenGL orthographic projection; the view volume's height in eye units
    /// (`> 0`); its width follows the viewport's aspect ratio.
    Orthographic {
        /// View volume height, eye units.
        height: f64,
    },
}

/// A triangle mesh in object space.
///
/// ```
/// use fixshade_host::reference::render;
/// use fixshade_host::scene_desc::{MeshDesc, SceneError};
/// use fixshade_host::standard_scenes::sphere_scene;
/// let mut s = sphere_scene(8, 8, 12, 6);
/// s.mesh = MeshDesc::default(); // empty: valid, nothing drawn
/// assert_eq!(render(&s).unwrap().covered_count(), 0);
/// s.mesh = MeshDesc { positions: vec![[0.0; 3]], normals: Some(vec![]), indices: vec![] };
/// assert_eq!(s.validate(), Err(SceneError::NormalCount { positions: 1, normals: 0 }));
/// ```
#[derive(Clone, Debug, PartialEq, Default)]
pub struct MeshDesc {
    /// Vertex positions.
    pub positions: Vec<[f64; 3]>,
    /// Per-vertex normals (same length as `positions`), or `None` to derive
    /// them ([`crate::reference::vertex_normals`]).
    pub normals: Option<Vec<[f64; 3]>>,
    /// Triangles as vertex indices; front faces are counter-clockwise.
    /// `u16`, as the kernel's: a mesh has at most [`MAX_VERTICES`] vertices.
    pub indices: Vec<[u16; 3]>,
}

/// Surface material (SPEC.md section 3: `E`, `Ka`, `Kd`, `Ks`, `n`).
///
/// ```
/// use fixshade_host::scene_desc::MaterialDesc;
/// let m = MaterialDesc::default();
/// assert_eq!(m.diffuse, [0.8, 0.8, 0.8]);
/// assert_eq!(m.shininess, 0.0);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct MaterialDesc {
    /// Emission `E` (default black).
    pub emission: [f64; 3],
    /// Ambient colour `Ka` (default 0.2 grey).
    pub ambient: [f64; 3],
    /// Diffuse colour `Kd` (default 0.8 grey).
    pub diffuse: [f64; 3],
    /// Specular colour `Ks` (default black).
    pub specular: [f64; 3],
    /// Shininess `n ≥ 0` (default 0).
    pub shininess: f64,
}

impl Default for MaterialDesc {
    fn default() -> Self {
        MaterialDesc {
            emission: [0.0; 3],
            ambient: [0.2; 3],
            diffuse: [0.8; 3],
            specular: [0.0; 3],
            shininess: 0.0,
        }
    }
}

/// A light, in world space. Intensities are non-negative and may exceed 1.
///
/// ```
/// use fixshade_host::scene_desc::{LightDesc, DEFAULT_ATTENUATION, WHITE};
/// use fixshade_host::standard_scenes::sphere_scene;
/// let mut s = sphere_scene(8, 8, 12, 6); // has one directional light
/// s.lights.push(LightDesc::Spot {
///     position: [0.0, 3.0, 0.0], axis: [0.0, -1.0, 0.0], cutoff_deg: 95.0, exponent: 2.0,
///     diffuse: [2.0; 3], specular: WHITE, attenuation: DEFAULT_ATTENUATION,
/// });
/// let err = s.validate().unwrap_err();
/// assert_eq!(err.to_string(), "lights[1].cutoff_deg: 95 out of range (must be in [0, 90])");
/// ```
#[derive(Clone, Debug, PartialEq)]
pub enum LightDesc {
    /// A light at infinity.
    Directional {
        /// Direction **towards** the light (need not be unit length, must not be zero).
        direction: [f64; 3],
        /// Diffuse intensity `Id`.
        diffuse: [f64; 3],
        /// Specular intensity `Is`.
        specular: [f64; 3],
    },
    /// A point light.
    Point {
        /// Position.
        position: [f64; 3],
        /// Diffuse intensity `Id`.
        diffuse: [f64; 3],
        /// Specular intensity `Is`.
        specular: [f64; 3],
        /// Attenuation `[c0, c1, c2]` (non-negative).
        attenuation: [f64; 3],
    },
    /// A spot light.
    Spot {
        /// Position.
        position: [f64; 3],
        /// The direction the spot shines (must not be zero).
        axis: [f64; 3],
        /// Cutoff angle in degrees, in [0, 90].
        cutoff_deg: f64,
        /// Spot exponent `p ≥ 0`.
        exponent: f64,
        /// Diffuse intensity `Id`.
        diffuse: [f64; 3],
        /// Specular intensity `Is`.
        specular: [f64; 3],
        /// Attenuation `[c0, c1, c2]` (non-negative).
        attenuation: [f64; 3],
    },
    /// A rectangular area light sampled as `k × k` point lights.
    Area {
        /// Centre of the rectangle.
        center: [f64; 3],
        /// First edge vector (full length).
        edge_u: [f64; 3],
        /// Second edge vector (full length).
        edge_v: [f64; 3],
        /// Samples per edge `k`, in `1..=`[`MAX_AREA_SAMPLES`].
        samples_k: u32,
        /// Total diffuse intensity (each sample carries 1/k²).
        diffuse: [f64; 3],
        /// Total specular intensity (each sample carries 1/k²).
        specular: [f64; 3],
        /// Attenuation `[c0, c1, c2]` of every sample (non-negative).
        attenuation: [f64; 3],
    },
}

impl LightDesc {
    /// A white directional light shining from `direction` (towards the light).
    ///
    /// ```
    /// use fixshade_host::scene_desc::LightDesc;
    /// let l = LightDesc::directional([0.0, 1.0, 0.0]);
    /// assert!(matches!(l, LightDesc::Directional { diffuse: [1.0, 1.0, 1.0], .. }));
    /// ```
    pub fn directional(direction: [f64; 3]) -> Self {
        LightDesc::Directional {
            direction,
            diffuse: WHITE,
            specular: WHITE,
        }
    }

    /// A white, unattenuated point light at `position`.
    ///
    /// ```
    /// use fixshade_host::scene_desc::LightDesc;
    /// let l = LightDesc::point([0.0, 2.0, 0.0]);
    /// assert!(matches!(l, LightDesc::Point { attenuation: [1.0, 0.0, 0.0], .. }));
    /// ```
    pub fn point(position: [f64; 3]) -> Self {
        LightDesc::Point {
            position,
            diffuse: WHITE,
            specular: WHITE,
            attenuation: DEFAULT_ATTENUATION,
        }
    }
}

/// Shading mode (SPEC.md section 4).
///
/// ```
/// use std::collections::BTreeSet;
/// use fixshade_host::{reference::render, scene_desc::*, standard_scenes::sphere_scene};
/// let colours = |s: &SceneDesc| -> usize {
///     render(s).unwrap().to_rgb565([0.0; 3]).into_iter().collect::<BTreeSet<_>>().len()
/// };
/// let mut s = sphere_scene(16, 16, 3, 2); // 6 triangles
/// s.shading = Shading::Flat;
/// assert!(colours(&s) <= 6 + 1); // one colour per triangle, and the background
/// s.shading = Shading::Gouraud;
/// assert!(colours(&s) > 7);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum Shading {
    /// One colour per triangle.
    Flat,
    /// Per-vertex lighting, colours interpolated.
    #[default]
    Gouraud,
    /// Per-pixel lighting with interpolated normal and position.
    Phong,
}

/// Specular model (SPEC.md section 3).
///
/// ```
/// use fixshade_host::reference::{illuminate, EyeLight, LightingModel};
/// use fixshade_host::scene_desc::{MaterialDesc, SpecularModel, Viewer};
/// let (w, h) = ([1.0; 3], 0.5f64.sqrt()); // the light 45° from the normal, the viewer along it
/// let m = MaterialDesc { diffuse: [0.0; 3], specular: w, shininess: 1.0, ..Default::default() };
/// let lights = [EyeLight::Directional { to_light: [0.0, h, h], diffuse: w, specular: w }];
/// let spec = |specular_model| {
///     let lm = LightingModel { material: &m, global_ambient: [0.0; 3], lights: &lights,
///         specular_model, viewer: Viewer::Infinite };
///     illuminate(&lm, [0.0, 0.0, -1.0], [0.0, 0.0, 1.0])[0]
/// };
/// assert!((spec(SpecularModel::Phong) - h).abs() < 1e-12); // R·V = cos 45°
/// assert!((spec(SpecularModel::Blinn) - 22.5f64.to_radians().cos()).abs() < 1e-12); // N·H
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum SpecularModel {
    /// `max(R·V, 0)^n`.
    Phong,
    /// `max(N·H, 0)^n`.
    #[default]
    Blinn,
}

/// Viewer model (SPEC.md section 2).
///
/// ```
/// use fixshade_host::reference::{illuminate, EyeLight, LightingModel};
/// use fixshade_host::scene_desc::{MaterialDesc, SpecularModel, Viewer};
/// let w = [1.0; 3];
/// let m = MaterialDesc { diffuse: [0.0; 3], specular: w, shininess: 1.0, ..Default::default() };
/// let lights = [EyeLight::Directional { to_light: [0.0, 0.0, 1.0], diffuse: w, specular: w }];
/// let spec = |viewer| {
///     let lm = LightingModel { material: &m, global_ambient: [0.0; 3], lights: &lights,
///         specular_model: SpecularModel::Phong, viewer };
///     illuminate(&lm, [2.0, 0.0, -2.0], [0.0, 0.0, 1.0])[0] // R = N = (0, 0, 1)
/// };
/// assert!((spec(Viewer::Infinite) - 1.0).abs() < 1e-12); // V = (0, 0, 1)
/// assert!((spec(Viewer::Local) - 0.5f64.sqrt()).abs() < 1e-12); // V = normalise(−P)
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum Viewer {
    /// `V` points from the surface point to the eye.
    Local,
    /// `V = (0, 0, 1)`.
    #[default]
    Infinite,
}

impl SceneDesc {
    /// A scene with the given viewport, camera and mesh, and every other field
    /// at its `SCENE_FORMAT.md` default: identity model, default material,
    /// global ambient 0.2 grey, no lights, Gouraud shading, Blinn specular,
    /// infinite viewer, culling and depth test on, one-sided lighting, no
    /// dithering, black background.
    ///
    /// ```
    /// use fixshade_host::generate::cube;
    /// use fixshade_host::scene_desc::*;
    /// let cam = CameraDesc {
    ///     eye: [0.0, 0.0, 5.0], target: [0.0; 3], up: [0.0, 1.0, 0.0],
    ///     near: 0.5, far: 20.0, projection: Projection::Perspective { fovy_deg: 60.0 },
    /// };
    /// let s = SceneDesc::new(32, 16, cam, cube(1.0));
    /// assert_eq!(s.shading, Shading::Gouraud);
    /// assert!(s.cull && s.depth && !s.two_sided);
    /// ```
    pub fn new(width: u32, height: u32, camera: CameraDesc, mesh: MeshDesc) -> Self {
        SceneDesc {
            width,
            height,
            camera,
            model: IDENTITY,
            mesh,
            material: MaterialDesc::default(),
            global_ambient: [0.2; 3],
            lights: Vec::new(),
            shading: Shading::Gouraud,
            specular_model: SpecularModel::Blinn,
            viewer: Viewer::Infinite,
            cull: true,
            depth: true,
            two_sided: false,
            dither: false,
            background: [0.0; 3],
        }
    }

    /// Checks every field; the first problem found is returned.
    ///
    /// Rejected: non-finite numbers anywhere; width or height above
    /// [`MAX_DIMENSION`] (0 is fine: an empty frame); `near ≤ 0`, `far ≤ near`;
    /// `eye == target` or `up` parallel to the view direction; `fovy_deg`
    /// outside (0, 180) or orthographic `height ≤ 0`; a model whose bottom row
    /// is not `[0, 0, 0, 1]` or whose 3 × 3 part is singular; normals whose
    /// count differs from the positions'; an index out of range; material
    /// colours or background outside [0, 1]; negative shininess, global
    /// ambient, light intensities or attenuation coefficients; a zero light
    /// direction or spot axis; a cutoff outside [0, 90]; a negative spot
    /// exponent; `samples_k` of 0 or above [`MAX_AREA_SAMPLES`].
    ///
    /// ```
    /// use fixshade_host::generate::cube;
    /// use fixshade_host::scene_desc::*;
    /// let cam = CameraDesc {
    ///     eye: [0.0, 0.0, 5.0], target: [0.0; 3], up: [0.0, 1.0, 0.0],
    ///     near: 0.0, far: 20.0, projection: Projection::Perspective { fovy_deg: 60.0 },
    /// };
    /// let err = SceneDesc::new(32, 16, cam, cube(1.0)).validate().unwrap_err();
    /// assert!(err.to_string().contains("camera.near"));
    /// ```
    pub fn validate(&self) -> Result<(), SceneError> {
        for (field, v) in [("width", self.width), ("height", self.height)] {
            if v > MAX_DIMENSION {
                return Err(SceneError::TooLarge {
                    field: field.into(),
                    value: v,
                    max: MAX_DIMENSION,
                });
            }
        }
        self.validate_camera()?;
        self.validate_model()?;
        self.validate_mesh()?;
        self.validate_material()?;
        finite3("global_ambient", &self.global_ambient)?;
        non_negative3("global_ambient", &self.global_ambient)?;
        finite3("background", &self.background)?;
        unit_range3("background", &self.background)?;
        for (i, light) in self.lights.iter().enumerate() {
            validate_light(i, light)?;
        }
        self.validate_work()?;
        crate::scene_kernel::check(self).map_err(SceneError::Kernel)
    }

    /// The light samples a shaded point takes: `k²` for an area light, 1
    /// for any other (saturating).
    ///
    /// ```
    /// use fixshade_host::scene_desc::LightDesc;
    /// use fixshade_host::standard_scenes::sphere_scene;
    /// let mut s = sphere_scene(8, 8, 12, 6);
    /// s.lights = vec![LightDesc::point([0.0, 2.0, 0.0]); 3];
    /// assert_eq!(s.light_samples(), 3);
    /// ```
    pub fn light_samples(&self) -> u64 {
        self.lights
            .iter()
            .map(|l| match l {
                LightDesc::Area { samples_k, .. } => u64::from(*samples_k).pow(2),
                _ => 1,
            })
            .fold(0u64, u64::saturating_add)
    }

    /// The bound on a frame's work, [`MAX_LIGHT_SAMPLES`] and
    /// [`MAX_LIGHT_EVALUATIONS`].
    fn validate_work(&self) -> Result<(), SceneError> {
        let samples = self.light_samples();
        if samples > MAX_LIGHT_SAMPLES {
            return Err(SceneError::Limit {
                field: "lights".into(),
                message: format!(
                    "{samples} light samples a shaded point, more than {MAX_LIGHT_SAMPLES}"
                ),
            });
        }
        let points = u64::from(self.width) * u64::from(self.height)
            + self.mesh.positions.len() as u64
            + self.mesh.indices.len() as u64;
        let evaluations = points.saturating_mul(samples);
        if evaluations > MAX_LIGHT_EVALUATIONS {
            return Err(SceneError::Limit {
                field: "lights".into(),
                message: format!(
                    "{samples} light samples at {points} points (pixels, vertices and \
                     triangles) make {evaluations} light evaluations a frame, more than \
                     {MAX_LIGHT_EVALUATIONS}"
                ),
            });
        }
        Ok(())
    }

    fn validate_camera(&self) -> Result<(), SceneError> {
        let c = &self.camera;
        finite3("camera.eye", &c.eye)?;
        finite3("camera.target", &c.target)?;
        finite3("camera.up", &c.up)?;
        finite("camera.near", c.near)?;
        finite("camera.far", c.far)?;
        if c.near <= 0.0 {
            return Err(invalid("camera.near", c.near, "must be > 0"));
        }
        if c.far <= c.near {
            return Err(invalid("camera.far", c.far, "must be > camera.near"));
        }
        let f = sub(c.target, c.eye);
        if dot(f, f) == 0.0 {
            return Err(SceneError::Degenerate {
                field: "camera.target".into(),
                reason: "equals camera.eye",
            });
        }
        let s = cross(f, c.up);
        if dot(s, s) == 0.0 {
            return Err(SceneError::Degenerate {
                field: "camera.up".into(),
                reason: "is zero or parallel to the view direction",
            });
        }
        match c.projection {
            Projection::Perspective { fovy_deg } => {
                finite("camera.fovy_deg", fovy_deg)?;
                if fovy_deg <= 0.0 || fovy_deg >= 180.0 {
                    return Err(invalid("camera.fovy_deg", fovy_deg, "must be in (0, 180)"));
                }
            }
            Projection::Orthographic { height } => {
                finite("camera.height", height)?;
                if height <= 0.0 {
                    return Err(invalid("camera.height", height, "must be > 0"));
                }
            }
        }
        Ok(())
    }

    fn validate_model(&self) -> Result<(), SceneError> {
        for (r, row) in self.model.iter().enumerate() {
            for (c, v) in row.iter().enumerate() {
                finite(&format!("model[{r}][{c}]"), *v)?;
            }
        }
        if self.model[3] != [0.0, 0.0, 0.0, 1.0] {
            return Err(SceneError::Degenerate {
                field: "model".into(),
                reason: "bottom row must be [0, 0, 0, 1] (affine transform)",
            });
        }
        let m = &self.model;
        let det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
        if det == 0.0 || !det.is_finite() {
            return Err(SceneError::Degenerate {
                field: "model".into(),
                reason: "3x3 part is singular",
            });
        }
        Ok(())
    }

    fn validate_mesh(&self) -> Result<(), SceneError> {
        let mesh = &self.mesh;
        if mesh.positions.len() > MAX_VERTICES {
            return Err(SceneError::TooManyVertices {
                count: mesh.positions.len(),
            });
        }
        for (i, p) in mesh.positions.iter().enumerate() {
            finite3(&format!("mesh.positions[{i}]"), p)?;
        }
        if let Some(normals) = &mesh.normals {
            if normals.len() != mesh.positions.len() {
                return Err(SceneError::NormalCount {
                    positions: mesh.positions.len(),
                    normals: normals.len(),
                });
            }
            for (i, n) in normals.iter().enumerate() {
                finite3(&format!("mesh.normals[{i}]"), n)?;
            }
        }
        let count = mesh.positions.len();
        for (t, tri) in mesh.indices.iter().enumerate() {
            for &index in tri {
                if index as usize >= count {
                    return Err(SceneError::IndexOutOfRange {
                        triangle: t,
                        index: u32::from(index),
                        vertex_count: count,
                    });
                }
            }
        }
        Ok(())
    }

    fn validate_material(&self) -> Result<(), SceneError> {
        let m = &self.material;
        for (name, c) in [
            ("material.emission", &m.emission),
            ("material.ambient", &m.ambient),
            ("material.diffuse", &m.diffuse),
            ("material.specular", &m.specular),
        ] {
            finite3(name, c)?;
            unit_range3(name, c)?;
        }
        finite("material.shininess", m.shininess)?;
        if m.shininess < 0.0 {
            return Err(invalid("material.shininess", m.shininess, "must be >= 0"));
        }
        Ok(())
    }
}

fn validate_light(i: usize, light: &LightDesc) -> Result<(), SceneError> {
    let name = |f: &str| format!("lights[{i}].{f}");
    let check_intensity = |diffuse: &[f64; 3], specular: &[f64; 3]| {
        finite3(&name("diffuse"), diffuse)?;
        non_negative3(&name("diffuse"), diffuse)?;
        finite3(&name("specular"), specular)?;
        non_negative3(&name("specular"), specular)
    };
    let check_attenuation = |a: &[f64; 3]| {
        finite3(&name("attenuation"), a)?;
        non_negative3(&name("attenuation"), a)
    };
    let non_zero = |field: &str, v: &[f64; 3]| {
        finite3(&name(field), v)?;
        if dot(*v, *v) == 0.0 {
            return Err(SceneError::Degenerate {
                field: name(field),
                reason: "must not be the zero vector",
            });
        }
        Ok(())
    };
    match light {
        LightDesc::Directional {
            direction,
            diffuse,
            specular,
        } => {
            non_zero("direction", direction)?;
            check_intensity(diffuse, specular)
        }
        LightDesc::Point {
            position,
            diffuse,
            specular,
            attenuation,
        } => {
            finite3(&name("position"), position)?;
            check_intensity(diffuse, specular)?;
            check_attenuation(attenuation)
        }
        LightDesc::Spot {
            position,
            axis,
            cutoff_deg,
            exponent,
            diffuse,
            specular,
            attenuation,
        } => {
            finite3(&name("position"), position)?;
            non_zero("axis", axis)?;
            finite(&name("cutoff_deg"), *cutoff_deg)?;
            if !(0.0..=90.0).contains(cutoff_deg) {
                return Err(invalid(
                    &name("cutoff_deg"),
                    *cutoff_deg,
                    "must be in [0, 90]",
                ));
            }
            finite(&name("exponent"), *exponent)?;
            if *exponent < 0.0 {
                return Err(invalid(&name("exponent"), *exponent, "must be >= 0"));
            }
            check_intensity(diffuse, specular)?;
            check_attenuation(attenuation)
        }
        LightDesc::Area {
            center,
            edge_u,
            edge_v,
            samples_k,
            diffuse,
            specular,
            attenuation,
        } => {
            finite3(&name("center"), center)?;
            finite3(&name("edge_u"), edge_u)?;
            finite3(&name("edge_v"), edge_v)?;
            if *samples_k == 0 || *samples_k > MAX_AREA_SAMPLES {
                return Err(invalid(
                    &name("samples_k"),
                    f64::from(*samples_k),
                    "must be in 1..=64",
                ));
            }
            check_intensity(diffuse, specular)?;
            check_attenuation(attenuation)
        }
    }
}

/// Why a [`SceneDesc`] was rejected. Every variant's `Display` names the
/// offending field (e.g. `lights[2].cutoff_deg`).
///
/// ```
/// use fixshade_host::scene_desc::SceneError;
/// let e = SceneError::IndexOutOfRange { triangle: 3, index: 9, vertex_count: 4 };
/// assert!(e.to_string().contains("mesh.indices[3]"));
/// ```
#[derive(Clone, Debug, PartialEq)]
pub enum SceneError {
    /// A number is NaN or infinite.
    NonFinite {
        /// The field, e.g. `mesh.positions[7]`.
        field: String,
    },
    /// A width or height above the maximum.
    TooLarge {
        /// `width` or `height`.
        field: String,
        /// The value given.
        value: u32,
        /// The largest accepted value.
        max: u32,
    },
    /// A number outside its accepted range.
    OutOfRange {
        /// The field.
        field: String,
        /// The value given (for vectors, the offending component).
        value: f64,
        /// What the field must satisfy.
        expected: &'static str,
    },
    /// A geometric degeneracy (zero vector, singular matrix, …).
    Degenerate {
        /// The field.
        field: String,
        /// What is wrong.
        reason: &'static str,
    },
    /// `mesh.normals` has a different length from `mesh.positions`.
    NormalCount {
        /// Number of positions.
        positions: usize,
        /// Number of normals.
        normals: usize,
    },
    /// A limit on the work a frame asks for ([`MAX_LIGHT_SAMPLES`],
    /// [`MAX_LIGHT_EVALUATIONS`]).
    Limit {
        /// The key that asks for it.
        field: String,
        /// What exceeds which limit.
        message: String,
    },
    /// The kernel cannot render the scene (a value outside its formats, a
    /// camera or projection that does not fit, …).
    Kernel(crate::scene_kernel::KernelSceneError),
    /// More than [`MAX_VERTICES`] positions.
    TooManyVertices {
        /// How many the mesh has.
        count: usize,
    },
    /// A triangle refers to a vertex that does not exist.
    IndexOutOfRange {
        /// The triangle (position in `mesh.indices`).
        triangle: usize,
        /// The bad index.
        index: u32,
        /// Number of vertices.
        vertex_count: usize,
    },
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SceneError::NonFinite { field } => write!(f, "{field}: not a finite number"),
            SceneError::TooLarge { field, value, max } => {
                write!(f, "{field}: {value} exceeds the maximum {max}")
            }
            SceneError::OutOfRange {
                field,
                value,
                expected,
            } => write!(f, "{field}: {value} out of range ({expected})"),
            SceneError::Degenerate { field, reason } => write!(f, "{field}: {reason}"),
            SceneError::NormalCount { positions, normals } => write!(
                f,
                "mesh.normals: {normals} normals for {positions} positions"
            ),
            SceneError::Limit { field, message } => write!(f, "{field}: {message}"),
            SceneError::Kernel(e) => write!(f, "{e}"),
            SceneError::TooManyVertices { count } => write!(
                f,
                "mesh.positions: {count} vertices, more than {MAX_VERTICES}"
            ),
            SceneError::IndexOutOfRange {
                triangle,
                index,
                vertex_count,
            } => write!(
                f,
                "mesh.indices[{triangle}]: index {index} out of range ({vertex_count} vertices)"
            ),
        }
    }
}

impl std::error::Error for SceneError {}

fn invalid(field: &str, value: f64, expected: &'static str) -> SceneError {
    SceneError::OutOfRange {
        field: field.into(),
        value,
        expected,
    }
}

fn finite(field: &str, v: f64) -> Result<(), SceneError> {
    if v.is_finite() {
        Ok(())
    } else {
        Err(SceneError::NonFinite {
            field: field.into(),
        })
    }
}

fn finite3(field: &str, v: &[f64; 3]) -> Result<(), SceneError> {
    if v.iter().all(|x| x.is_finite()) {
        Ok(())
    } else {
        Err(SceneError::NonFinite {
            field: field.into(),
        })
    }
}

fn non_negative3(field: &str, v: &[f64; 3]) -> Result<(), SceneError> {
    match v.iter().find(|x| **x < 0.0) {
        Some(x) => Err(invalid(field, *x, "must be >= 0")),
        None => Ok(()),
    }
}

fn unit_range3(field: &str, v: &[f64; 3]) -> Result<(), SceneError> {
    match v.iter().find(|x| !(0.0..=1.0).contains(*x)) {
        Some(x) => Err(invalid(field, *x, "must be in [0, 1]")),
        None => Ok(()),
    }
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
