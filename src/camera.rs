//! The camera: a look-at view and an OpenGL perspective or orthographic
//! projection (SPEC.md 1).
//!
//! The view matrix is `I8F24` like every [`Mat4`]. The projection is kept
//! as its few non-zero coefficients in `Q.24` `i64` (it is applied to
//! eye-space positions, which are `I8F24`, giving clip coordinates in
//! `I40F24`: at most `2³¹ · 2⁷ ≈ 2³⁸` raw for a coefficient below 2⁷).

use crate::mesh::Bounds;
use crate::num::division::div_rem_u64;
use crate::num::widening::mul_i32;
use crate::platform;
use crate::vector::{FormatError, Mat4, Vec3, COORD_FRAC};

/// Why a camera could not be built.
///
/// ```
/// use fixshade::camera::{Camera, CameraError};
/// let up = [0.0, 1.0, 0.0];
/// assert_eq!(Camera::look_at([1.0; 3], [1.0; 3], up), Err(CameraError::Degenerate));
/// assert_eq!(Camera::look_at([f32::NAN, 0.0, 0.0], [0.0; 3], up), Err(CameraError::NotFinite));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CameraError {
    /// A number was NaN or infinite.
    NotFinite,
    /// A position outside the `I8F24` range.
    OutOfRange,
    /// `eye == target`, or `up` parallel to the view direction.
    Degenerate,
    /// `near ≤ 0`, `far ≤ near`, `far ≥ 128` (beyond the `I8F24` range
    /// of eye-space positions), a field of view outside (0°, 180°), a
    /// non-positive orthographic height, or a projection coefficient of
    /// 127 or more (a field of view under about 1°, `far` within 1 % of
    /// `near`, or, at draw time, an extreme aspect ratio).
    BadProjection,
}

impl From<FormatError> for CameraError {
    fn from(e: FormatError) -> Self {
        match e {
            FormatError::NotFinite => CameraError::NotFinite,
            FormatError::OutOfRange => CameraError::OutOfRange,
        }
    }
}

impl core::fmt::Display for CameraError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(match self {
            CameraError::NotFinite => "camera parameter is NaN or infinite",
            CameraError::OutOfRange => "camera position outside [-128, 128)",
            CameraError::Degenerate => "camera eye equals target, or up is parallel to the view",
            CameraError::BadProjection => "bad projection (near, far, field of view or height)",
        })
    }
}

/// Which projection, with its parameters.
///
/// ```
/// use fixshade::camera::{Camera, Projection};
/// let ortho = Projection::Orthographic { height: 2.0 };
/// let cam = Camera::look_at([0.0, 0.0, 3.0], [0.0; 3], [0.0, 1.0, 0.0]).unwrap();
/// let p = cam.with_projection(ortho, 1.0, 5.0).unwrap().projection_for(100, 100).unwrap();
/// // A view volume 2 units high (and, at aspect 1, wide) maps to [-1, 1]: scale 1.
/// assert_eq!((p.sx, p.sy), (1 << 24, 1 << 24));
/// assert!(!p.is_perspective());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Projection {
    /// OpenGL perspective: vertical field of view in degrees.
    Perspective {
        /// Vertical field of view, degrees, in (0, 180).
        fovy_deg: f32,
    },
    /// OpenGL orthographic: the view volume's height in eye units (its
    /// width follows the viewport's aspect ratio).
    Orthographic {
        /// Height of the view volume.
        height: f32,
    },
}

/// A camera: view matrix plus projection parameters.
///
/// ```
/// use fixshade::camera::{Camera, Projection};
/// let cam = Camera::look_at([0.0, 0.0, 3.0], [0.0; 3], [0.0, 1.0, 0.0])
///     .unwrap()
///     .with_projection(Projection::Perspective { fovy_deg: 60.0 }, 0.1, 10.0)
///     .unwrap();
/// let p = cam.projection_for(320, 240).unwrap();
/// assert!(p.is_perspective());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// World → eye.
    pub view: Mat4,
    // Private: `lens` is worked out from them, and they are valid
    // ([`Camera::with_projection`]).
    projection: Projection,
    near: f32,
    far: f32,
    lens: Lens,
}

/// What of the projection depends on the camera alone, worked out once
/// when the projection is set rather than once a draw: every coefficient
/// but the horizontal scale, which needs the viewport's aspect ratio.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Lens {
    /// `cot(fovy / 2)` (perspective) or 2 over the view volume's height
    /// (orthographic), `Q.32` (below 2³⁹: the vertical scale is it, below
    /// 2⁷): the horizontal scale is `kx / aspect`, in integers.
    kx: u64,
    sy: i32,
    a: i32,
    b: i32,
    /// The near plane's distance, raw `I8F24` (0 for one below 2⁻²⁵).
    near: i32,
    perspective: bool,
}

/// `Camera::look_at`'s projection: 60° perspective, near 0.1, far 10.
const DEFAULT_PROJECTION: (Projection, f32, f32) =
    (Projection::Perspective { fovy_deg: 60.0 }, 0.1, 10.0);
const DEFAULT_LENS: Lens = match Lens::new(DEFAULT_PROJECTION) {
    Ok(l) => l,
    Err(_) => panic!("the default projection is valid"),
};

/// The largest coefficient, raw `Q.24`: [`ProjectionCoeffs::clip`] relies
/// on coefficients below 2⁷.
const COEFF_LIMIT: u32 = 127 << COORD_FRAC;

impl Lens {
    /// Checks a projection and works out its coefficients (`f64`, then
    /// rounded to `Q.24`).
    const fn new((projection, near, far): (Projection, f32, f32)) -> Result<Lens, CameraError> {
        let (ok, param) = match projection {
            Projection::Perspective { fovy_deg } => (fovy_deg > 0.0 && fovy_deg < 180.0, fovy_deg),
            Projection::Orthographic { height } => (height > 0.0, height),
        };
        if !near.is_finite() || !far.is_finite() || !param.is_finite() {
            return Err(CameraError::NotFinite);
        }
        if !ok || near <= 0.0 || far <= near || far >= 128.0 {
            return Err(CameraError::BadProjection);
        }
        let (n, f) = (near as f64, far as f64);
        let lens = match projection {
            Projection::Perspective { fovy_deg } => {
                let half = fovy_deg as f64 * core::f64::consts::PI / 360.0;
                let fl = cos_over_sin(half);
                Lens {
                    kx: q32(fl),
                    sy: q24(fl),
                    a: q24((f + n) / (n - f)),
                    b: q24(2.0 * f * n / (n - f)),
                    near: q24(n),
                    perspective: true,
                }
            }
            Projection::Orthographic { height } => {
                let h = height as f64;
                Lens {
                    kx: q32(2.0 / h),
                    sy: q24(2.0 / h),
                    a: q24(-2.0 / (f - n)),
                    b: q24(-(f + n) / (f - n)),
                    near: q24(n),
                    perspective: false,
                }
            }
        };
        if lens.sy.unsigned_abs() > COEFF_LIMIT
            || lens.a.unsigned_abs() > COEFF_LIMIT
            || lens.b.unsigned_abs() > COEFF_LIMIT
        {
            return Err(CameraError::BadProjection);
        }
        Ok(lens)
    }
}

/// `v` in `Q.24`, rounded half away from zero, saturated to `i32` (NaN
/// to 0).
const fn q24(v: f64) -> i32 {
    let s = v * (1u64 << COORD_FRAC) as f64;
    let s = if s >= 0.0 { s + 0.5 } else { s - 0.5 };
    s as i32
}

/// `v ≥ 0` in `Q.32`, rounded half up, saturated to `u64` (NaN to 0).
const fn q32(v: f64) -> u64 {
    (v * (1u64 << 32) as f64 + 0.5) as u64
}

impl Camera {
    /// A look-at view (gluLookAt) with a default 60° perspective, near 0.1,
    /// far 10.
    ///
    /// ```
    /// use fixshade::camera::{Camera, CameraError, Projection};
    /// use fixshade::Vec3;
    /// let cam = Camera::look_at([0.0, 0.0, 3.0], [0.0; 3], [0.0, 1.0, 0.0]).unwrap();
    /// assert_eq!(cam.projection(), Projection::Perspective { fovy_deg: 60.0 });
    /// assert_eq!((cam.near(), cam.far()), (0.1, 10.0));
    /// // The target lies straight ahead, 3 units down the eye's −z axis.
    /// assert_eq!(cam.view.transform_point(Vec3::ZERO), Vec3::from_f32(0.0, 0.0, -3.0).unwrap());
    /// // `up` along the view direction leaves the roll undefined.
    /// let err = Camera::look_at([0.0, 0.0, 3.0], [0.0; 3], [0.0, 0.0, 1.0]);
    /// assert_eq!(err, Err(CameraError::Degenerate));
    /// ```
    pub fn look_at(eye: [f32; 3], target: [f32; 3], up: [f32; 3]) -> Result<Camera, CameraError> {
        Camera::look_at_f64(eye.map(f64::from), target.map(f64::from), up.map(f64::from))
    }

    /// As [`Camera::look_at`], from `f64`s.
    ///
    /// ```
    /// use fixshade::camera::{Camera, CameraError};
    /// let up = [0.0, 1.0, 0.0];
    /// let a = Camera::look_at_f64([1.0, 2.0, 3.0], [0.0; 3], up).unwrap();
    /// assert_eq!(Camera::look_at([1.0, 2.0, 3.0], [0.0; 3], [0.0, 1.0, 0.0]), Ok(a));
    /// // An eye 200 units away puts the view's translation outside I8F24.
    /// let far = Camera::look_at_f64([200.0, 0.0, 0.0], [0.0; 3], up);
    /// assert_eq!(far, Err(CameraError::OutOfRange));
    /// ```
    pub fn look_at_f64(
        eye: [f64; 3],
        target: [f64; 3],
        up: [f64; 3],
    ) -> Result<Camera, CameraError> {
        if eye.iter().chain(&target).chain(&up).any(|v| !v.is_finite()) {
            return Err(CameraError::NotFinite);
        }
        let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
        let cross = |a: [f64; 3], b: [f64; 3]| {
            [
                a[1] * b[2] - a[2] * b[1],
                a[2] * b[0] - a[0] * b[2],
                a[0] * b[1] - a[1] * b[0],
            ]
        };
        let unit = |v: [f64; 3]| -> Result<[f64; 3], CameraError> {
            let len = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
            if len.is_nan() || len <= 1e-12 || !len.is_finite() {
                return Err(CameraError::Degenerate);
            }
            Ok([v[0] / len, v[1] / len, v[2] / len])
        };
        let f = unit(sub(target, eye))?;
        let s = unit(cross(f, unit(up)?))?;
        let u = cross(s, f);
        let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let view = Mat4::from_f64([
            [s[0], s[1], s[2], -dot(s, eye)],
            [u[0], u[1], u[2], -dot(u, eye)],
            [-f[0], -f[1], -f[2], dot(f, eye)],
            [0.0, 0.0, 0.0, 1.0],
        ])?;
        Ok(Camera::from_view(view))
    }

    /// A camera with a given view matrix and the default projection.
    ///
    /// ```
    /// use fixshade::camera::Camera;
    /// use fixshade::Mat4;
    /// const CAM: Camera = Camera::from_view(Mat4::IDENTITY);
    /// // The identity view: the eye at the origin looking down −z, y up.
    /// let looking = Camera::look_at([0.0; 3], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]).unwrap();
    /// assert_eq!(CAM, looking);
    /// ```
    pub const fn from_view(view: Mat4) -> Camera {
        let (projection, near, far) = DEFAULT_PROJECTION;
        Camera {
            view,
            projection,
            near,
            far,
            lens: DEFAULT_LENS,
        }
    }

    /// Sets the projection and the near and far planes.
    ///
    /// ```
    /// use fixshade::camera::{Camera, CameraError, Projection};
    /// let cam = Camera::look_at([0.0, 0.0, 3.0], [0.0; 3], [0.0, 1.0, 0.0]).unwrap();
    /// let p = Projection::Perspective { fovy_deg: 45.0 };
    /// let c = cam.with_projection(p, 0.5, 20.0).unwrap();
    /// assert_eq!((c.projection(), c.near(), c.far()), (p, 0.5, 20.0));
    /// // A field of view under about 1° (coefficients of 127 and more).
    /// let tiny = Projection::Perspective { fovy_deg: 0.5 };
    /// assert_eq!(cam.with_projection(tiny, 1.0, 3.0), Err(CameraError::BadProjection));
    /// assert_eq!(cam.with_projection(p, 2.0, 1.0), Err(CameraError::BadProjection));
    /// assert_eq!(cam.with_projection(p, 0.0, 1.0), Err(CameraError::BadProjection));
    /// let wide = Projection::Perspective { fovy_deg: 180.0 };
    /// assert_eq!(cam.with_projection(wide, 0.1, 1.0), Err(CameraError::BadProjection));
    /// assert_eq!(cam.with_projection(p, f32::NAN, 1.0), Err(CameraError::NotFinite));
    /// let nan = Projection::Perspective { fovy_deg: f32::NAN };
    /// assert_eq!(cam.with_projection(nan, 0.1, 1.0), Err(CameraError::NotFinite));
    /// let inf = Projection::Orthographic { height: f32::INFINITY };
    /// assert_eq!(cam.with_projection(inf, 0.1, 1.0), Err(CameraError::NotFinite));
    /// assert_eq!(cam.with_projection(p, 0.1, 128.0), Err(CameraError::BadProjection));
    /// ```
    pub const fn with_projection(
        mut self,
        projection: Projection,
        near: f32,
        far: f32,
    ) -> Result<Camera, CameraError> {
        self.lens = match Lens::new((projection, near, far)) {
            Ok(lens) => lens,
            Err(e) => return Err(e),
        };
        self.projection = projection;
        self.near = near;
        self.far = far;
        Ok(self)
    }

    /// The projection.
    pub const fn projection(&self) -> Projection {
        self.projection
    }

    /// The near plane's distance.
    pub const fn near(&self) -> f32 {
        self.near
    }

    /// The far plane's distance.
    pub const fn far(&self) -> f32 {
        self.far
    }

    /// The projection's coefficients for a viewport of `width × height`
    /// pixels (aspect = width / height; a zero size counts as 1).
    ///
    /// All but the horizontal scale were worked out when the projection
    /// was set; errors with [`CameraError::BadProjection`] where that scale
    /// would reach 127 in value (an extreme aspect ratio):
    /// [`ProjectionCoeffs::clip`] relies on coefficients below 2⁷.
    ///
    /// ```
    /// use fixshade::camera::{Camera, CameraError, Projection};
    /// let cam = Camera::look_at([0.0, 0.0, 3.0], [0.0; 3], [0.0, 1.0, 0.0]).unwrap();
    /// let right = Projection::Perspective { fovy_deg: 90.0 };
    /// let square = cam.with_projection(right, 1.0, 3.0).unwrap();
    /// let p = square.projection_for(200, 100).unwrap();
    /// // cot(45°) = 1 vertically, halved horizontally by the aspect ratio 2.
    /// assert!((p.sy - (1 << 24)).abs() <= 1 && (p.sx - (1 << 23)).abs() <= 1);
    /// assert_eq!(square.projection_for(0, 0), square.projection_for(1, 1));
    /// assert_eq!(square.projection_for(1, 1000), Err(CameraError::BadProjection));
    /// ```
    pub fn projection_for(&self, width: u32, height: u32) -> Result<ProjectionCoeffs, CameraError> {
        // Both sides below 2²⁴ (their ratio kept to 2⁻²³), so that
        // `kx·h` is below 2⁶³; no float at draw time.
        let (mut w, mut h) = (width.max(1) as u64, height.max(1) as u64);
        while w.max(h) >= 1 << 24 {
            (w, h) = ((w >> 1).max(1), (h >> 1).max(1));
        }
        let l = &self.lens;
        // kx·h/w from Q.32 to Q.24, rounded half up.
        let sx = div_rem_u64(l.kx * h + (w << 7), w << 8).0;
        if sx > COEFF_LIMIT as u64 {
            return Err(CameraError::BadProjection);
        }
        Ok(ProjectionCoeffs {
            sx: sx as i32,
            sy: l.sy,
            tx: 0,
            ty: 0,
            a: l.a,
            b: l.b,
            perspective: l.perspective,
        })
    }

    /// Whether the world's absolute formats resolve a mesh in `bounds`
    /// placed by `model` and seen through this camera on a target `height`
    /// pixels tall, by an estimate of how far the steps of the `I8F24`
    /// positions and matrices (2⁻²⁴ world units) and of the vertex stage
    /// move its pixels. A draw where they would move them by more than
    /// about 1/512 px is refused
    /// ([`RenderError::SceneTooSmall`](crate::render::RenderError::SceneTooSmall)).
    /// Express such a scene in smaller units (larger numbers), nearer the
    /// world's origin.
    ///
    /// It is an estimate, not a proof. The two terms: the roundings of the
    /// view, the model and the box place a point within about
    /// `2⁻²⁴·(4 + 4R + D + T)` world units of where they should (`R` the
    /// box's largest object coordinate, `D` the largest eye coordinate the
    /// box reaches, at least `near`, `T` the largest translation of the
    /// view and the model), seen at distance `D`; and the vertex rows,
    /// scaled to `D`, hold `2⁻²⁶·D`, seen at the box's least depth (at
    /// least `near`). A pixel of the height spans `2·z·tan(fovy/2)/height`
    /// world units at distance `z` (orthographic: `view height/height`).
    /// What it bounds is drift: at 1/512 px an edge pixel in a few hundred
    /// may change its coverage, which is one pixel of a frame of a few
    /// hundred; near its threshold it refuses some scenes that would draw
    /// within the accuracy bound; and it misses small objects near the edge
    /// of a wide view (120° to 150°) far from the world's origin, where a
    /// pixel at the box's depth is smaller than at its sideways reach
    /// (docs/DEPARTURES.md). `host/tests/suite/world_scale.rs` draws
    /// a sphere from 10⁻⁶ to 1 in scale, 0 to 110 units from the origin,
    /// and rods reaching the eye: each is refused or drawn within 1 LSB.
    ///
    /// ```
    /// use fixshade::camera::{Camera, Projection};
    /// use fixshade::mesh::Bounds;
    /// use fixshade::Mat4;
    /// let unit = Camera::look_at([0.0, 0.0, 3.0], [0.0; 3], [0.0, 1.0, 0.0]).unwrap();
    /// assert!(unit.resolves(&Mat4::IDENTITY, &Bounds::UNIT, 240));
    /// // The same scene a thousand times smaller: a micrometre is 17 steps.
    /// let tiny = Camera::look_at([0.0, 0.0, 0.003], [0.0; 3], [0.0, 1.0, 0.0])
    ///     .unwrap()
    ///     .with_projection(Projection::Perspective { fovy_deg: 60.0 }, 1e-4, 0.01)
    ///     .unwrap();
    /// let milli = Mat4::from_f32([
    ///     [1e-3, 0.0, 0.0, 0.0],
    ///     [0.0, 1e-3, 0.0, 0.0],
    ///     [0.0, 0.0, 1e-3, 0.0],
    ///     [0.0, 0.0, 0.0, 1.0],
    /// ])
    /// .unwrap();
    /// assert!(!tiny.resolves(&milli, &Bounds::UNIT, 240));
    /// ```
    pub fn resolves(&self, model: &Mat4, bounds: &Bounds, height: u32) -> bool {
        let world = self.world_reach(model);
        self.resolves_modelview(&self.view.mul(model), world, bounds, height)
    }

    /// The largest translation of the view and `model` (raw `I8F24`): the
    /// eye's and the object's distance from the world's origin, which the
    /// model-view product cancels but the roundings of both matrices scale
    /// with.
    pub(crate) fn world_reach(&self, model: &Mat4) -> u64 {
        let t = |m: &Mat4| (0..3).map(|r| m.m[r][3].unsigned_abs()).max().unwrap_or(0);
        t(&self.view).max(t(model)) as u64
    }

    /// [`Camera::resolves`] for the model-view matrix `mv` and the
    /// translations' reach `world` ([`Camera::world_reach`], below 2³¹).
    ///
    /// Ranges (raw `I8F24`): a box coordinate `o` is below 1.5·2³², its
    /// product with an entry (below 2³¹) below 1.5·2⁶³ in `u64`, below 2⁴⁰
    /// once shifted, so `d` is below 2⁴²; the signed depth products are
    /// below 2⁶³ (entry and offset below 2³¹ each), below 2³⁹ shifted, and
    /// the least depth below 2⁴¹; `e` is below 2⁴⁴; `height·sy` is below
    /// 2³²·2³¹, `l` below 2⁴³, and its products saturate (refused: they then
    /// exceed either side, `d·2²⁰` and the least depth's `·2²²` both below
    /// 2⁶⁴). Out of line: once a draw, one copy for every configuration.
    #[inline(never)]
    pub(crate) fn resolves_modelview(
        &self,
        mv: &Mat4,
        world: u64,
        b: &Bounds,
        height: u32,
    ) -> bool {
        // The box's largest coordinate on each axis, object units, and
        // over all axes (`r`); the scene's scale `d`: at least the largest
        // eye coordinate the box reaches (at most that plus the box's own
        // offset's share), and at least `near`.
        let o: [u64; 3] =
            core::array::from_fn(|c| b.offset[c].unsigned_abs() as u64 + b.scale[c] as u64);
        let r = o[0].max(o[1]).max(o[2]);
        let near = self.lens.near as u64;
        let mut d = near;
        for row in &mv.m[..3] {
            let mut reach = row[3].unsigned_abs() as u64;
            for c in 0..3 {
                reach += (row[c].unsigned_abs() as u64 * o[c]) >> COORD_FRAC;
                // Once a draw: one body, not nine.
                platform::keep_loop_rolled();
            }
            d = d.max(reach);
        }
        // The box's least depth −z (its eye z at most `centre + reach`),
        // not nearer than the near plane.
        let z = &mv.m[2];
        let (mut centre, mut reach) = (z[3] as i64, 0i64);
        for ((&m, &off), &scale) in z.iter().zip(&b.offset).zip(&b.scale) {
            centre += (m as i64 * off as i64) >> COORD_FRAC;
            reach += ((m.unsigned_abs() as i64 * scale as i64) >> COORD_FRAC) + 1;
        }
        let nearest = (-(centre + reach)).max(near as i64) as u64;
        let e = (4 << COORD_FRAC) + 4 * r + d + world;
        let l = (height.max(1) as u64 * self.lens.sy.unsigned_abs() as u64).div_ceil(1 << 20);
        if !self.lens.perspective {
            // 2⁻²⁴·(h/2)·(sy/2²⁴)·e/2²⁴ ≤ 2⁻⁹.
            return l.saturating_mul(e) <= 1 << 44;
        }
        // The steps at the scene's scale: 2⁻²⁴·(h/2)·(sy/2²⁴)·e/d ≤ 2⁻⁹;
        // and the vertex rows' precision, 2⁻²⁶ of the box's reach, at its
        // least depth: (h/2)·(sy/2²⁴)·2⁻²⁶·d/nearest ≤ 2⁻⁹.
        l.saturating_mul(e) <= d << 20 && l.saturating_mul(d) <= nearest << 22
    }
}

/// `√x` in `f64` to the last bit or so: Newton's iteration from a guess
/// made by halving the exponent (no libm in `no_std`; used once per camera).
fn sqrt(x: f64) -> f64 {
    if x.is_nan() || x <= 0.0 || !x.is_finite() {
        return if x == 0.0 { 0.0 } else { f64::NAN };
    }
    let mut g = f64::from_bits((x.to_bits() >> 1) + (1023u64 << 51));
    for _ in 0..6 {
        g = 0.5 * (g + x / g);
    }
    g
}

/// `cos x / sin x` for `x` in (0, π/2), by Taylor series (no libm in
/// `no_std`; evaluated when a projection is set).
const fn cos_over_sin(x: f64) -> f64 {
    let (mut s, mut c) = (0.0, 0.0);
    let (mut ts, mut tc) = (x, 1.0);
    let mut k = 1;
    while k < 20 {
        s += ts;
        c += tc;
        ts *= -x * x / ((2 * k) as f64 * (2 * k + 1) as f64);
        tc *= -x * x / ((2 * k - 1) as f64 * (2 * k) as f64);
        k += 1;
    }
    c / s
}

/// The non-zero coefficients of an OpenGL projection matrix in `Q.24`:
/// `x_c = sx·x + tx`, `y_c = sy·y + ty`, `z_c = a·z + b·w`,
/// `w_c = −z` (perspective) or `1` (orthographic).
///
/// ```
/// use fixshade::camera::{Camera, Projection};
/// let cam = Camera::look_at([0.0, 0.0, 3.0], [0.0; 3], [0.0, 1.0, 0.0]).unwrap();
/// let height2 = Projection::Orthographic { height: 2.0 };
/// let ortho = cam.with_projection(height2, 1.0, 3.0).unwrap();
/// let p = ortho.projection_for(100, 100).unwrap();
/// // a = −2/(far − near) = −1, b = −(far + near)/(far − near) = −2, in Q.24.
/// assert_eq!((p.a, p.b), (-1 << 24, -2 << 24));
/// assert_eq!((p.tx, p.ty, p.perspective), (0, 0, false));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct ProjectionCoeffs {
    /// `P[0][0]`.
    pub sx: i32,
    /// `P[1][1]`.
    pub sy: i32,
    /// `P[0][3]` (0 for a centred view).
    pub tx: i32,
    /// `P[1][3]`.
    pub ty: i32,
    /// `P[2][2]`.
    pub a: i32,
    /// `P[2][3]`.
    pub b: i32,
    /// Perspective (`w_c = −z_e`) or orthographic (`w_c = 1`).
    pub perspective: bool,
}

impl ProjectionCoeffs {
    /// Whether this is a perspective projection.
    ///
    /// ```
    /// use fixshade::camera::{Camera, Projection};
    /// let cam = Camera::look_at([0.0, 0.0, 3.0], [0.0; 3], [0.0, 1.0, 0.0]).unwrap();
    /// assert!(cam.projection_for(64, 64).unwrap().is_perspective());
    /// let ortho = cam.with_projection(Projection::Orthographic { height: 4.0 }, 0.1, 10.0);
    /// let ortho = ortho.unwrap();
    /// assert!(!ortho.projection_for(64, 64).unwrap().is_perspective());
    /// ```
    pub const fn is_perspective(&self) -> bool {
        self.perspective
    }

    /// Clip coordinates `[x, y, z, w]` (`I40F24` raw) of an eye-space point.
    /// Coefficients are below 2⁷ in value (2³¹ raw, checked by
    /// [`Camera::projection_for`]) and coordinates below 2³¹ raw, so each
    /// product is below 2⁶² and the sums below 2⁶³.
    ///
    /// ```
    /// use fixshade::camera::{Camera, Projection};
    /// use fixshade::Vec3;
    /// let cam = Camera::look_at([0.0, 0.0, 3.0], [0.0; 3], [0.0, 1.0, 0.0]).unwrap();
    /// let persp = Projection::Perspective { fovy_deg: 90.0 };
    /// let p = cam.with_projection(persp, 1.0, 3.0).unwrap().projection_for(100, 100).unwrap();
    /// // Points on the near and far planes land on z_c = −w_c and z_c = +w_c; w_c = −z_e.
    /// let near = p.clip(Vec3::from_f32(0.0, 0.0, -1.0).unwrap());
    /// assert_eq!((near[2], near[3]), (-1 << 24, 1 << 24));
    /// let far = p.clip(Vec3::from_f32(0.0, 0.0, -3.0).unwrap());
    /// assert_eq!((far[2], far[3]), (3 << 24, 3 << 24));
    /// ```
    #[inline]
    pub fn clip(&self, e: Vec3) -> [i64; 4] {
        let b = e.to_bits();
        let [z, w] = self.depth_clip(b[2]);
        [
            coeff_mul(self.sx, b[0]) + self.tx as i64,
            coeff_mul(self.sy, b[1]) + self.ty as i64,
            z,
            w,
        ]
    }

    /// `[z_c, w_c]` of [`ProjectionCoeffs::clip`] from the eye-space depth
    /// alone (raw `I8F24`): the vertex stage's near-plane test and depth.
    #[inline(always)]
    pub(crate) fn depth_clip(&self, z: i32) -> [i64; 2] {
        let w = if self.perspective {
            -(z as i64)
        } else {
            1i64 << COORD_FRAC
        };
        [coeff_mul(self.a, z) + self.b as i64, w]
    }
}

/// A `Q.24` coefficient times a raw `I8F24` coordinate, rounded to raw
/// units (below 2³⁸ in magnitude).
#[inline(always)]
fn coeff_mul(c: i32, v: i32) -> i64 {
    (mul_i32(c, v) + (1 << (COORD_FRAC - 1))) >> COORD_FRAC
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The extremes of every operand (entries of `i32::MIN`, boxes at the
    /// edge of both formats, the tallest height, both projections) run
    /// without overflow in debug builds; the wildest matrix and box on the
    /// tallest target refuse, and the standard sphere's scene resolves.
    #[test]
    fn resolves_at_the_formats_edges() {
        let edge = Bounds {
            offset: [i32::MIN, i32::MAX, i32::MIN],
            scale: [u32::MAX; 3],
        };
        let wild = Mat4 {
            m: [
                [i32::MIN; 4],
                [i32::MAX; 4],
                [i32::MIN, i32::MAX, i32::MIN, i32::MAX],
                [0; 4],
            ],
        };
        let eye = Camera::look_at([0.0, 0.0, 3.0], [0.0; 3], [0.0, 1.0, 0.0]).unwrap();
        let tiny_ortho = eye
            .with_projection(Projection::Orthographic { height: 0.016 }, 1e-7, 127.0)
            .unwrap();
        let narrow = eye
            .with_projection(Projection::Perspective { fovy_deg: 1.0 }, 1e-7, 127.0)
            .unwrap();
        for cam in [eye, tiny_ortho, narrow] {
            for h in [0, 1, 240, u32::MAX] {
                for (m, b) in [(wild, edge), (Mat4::IDENTITY, edge), (wild, Bounds::UNIT)] {
                    let _ = cam.resolves_modelview(&m, 0, &b, h);
                    let _ = cam.resolves_modelview(&m, u32::MAX as u64, &b, h);
                }
                assert!(!cam.resolves_modelview(&wild, 1 << 31, &edge, u32::MAX));
            }
        }
        // The standard sphere's scene and its tallest target resolve.
        assert!(eye.resolves(&Mat4::IDENTITY, &Bounds::UNIT, 4096));
    }
}
