//! Meshes made for flash: quantised positions, packed normals and `u16`
//! indices, all borrowed from the caller (`static` data, or the bytes of
//! `include_bytes!`), and vertex normals for meshes without them (SPEC.md 4).
//!
//! # Format
//!
//! | item | storage | bytes |
//! | --- | --- | --- |
//! | position | `[i16; 3]`: each a `Q.15` fraction `q / 2¹⁵` of the box | 6 a vertex |
//! | normal (optional) | [`PackedNormal`]: octahedral, two `i16` | 4 a vertex |
//! | triangle | `[u16; 3]` vertex indices | 6 a triangle |
//! | box | [`Bounds`]: per-axis offset (`I8F24`) and scale (`U8F24`) | 24 a mesh |
//!
//! The object-space position of vertex `q` is `offset + scale ∘ q / 2¹⁵`,
//! per axis: the box spans `[offset − scale, offset + scale·(1 − 2⁻¹⁵)]`
//! in 65 536 steps of `scale / 2¹⁵`. The renderer folds the box into the
//! draw's model-view matrix ([`Bounds::fold`]) and feeds the `i16`s to it
//! as they are ([`Mat4::transform_quantised`]): a vertex costs what an
//! `I8F24` one did, and on a Cortex-M0 its products are two 16-bit
//! multiplies instead of four.
//!
//! # Precision
//!
//! Positions: the host converter
//! (`fixshade_host::mesh_convert`, the `fixshade-convert` command) takes the
//! box from the mesh's extent `E` on each axis, `scale ≤ (E + 2⁻²⁴) ·
//! 2¹⁵/65535 + 2⁻²⁴`, and rounds each coordinate to the nearest step:
//! the error is at most half a step, `(E + 2⁻²⁴)/131070 + 2⁻⁴⁰`, which is
//! below `E/65535` for every extent above `3·2⁻²⁴` (a coordinate within
//! `3·2⁻²⁴` of ±128, the `I8F24` range's ends, is clamped into it: at most
//! `2.5·2⁻²⁴` off). Where the kernel takes the model-view matrix times the
//! box, each entry is rounded to `I8F24` once (`2⁻²⁵`), and a quantised
//! coordinate is at most 1 in magnitude: an eye-space position is off by
//! at most `5·2⁻²⁵` (three linear entries, the translation, the final
//! rounding), against `2⁻²⁵` plus the `I8F24` rounding of object
//! positions times the matrix before.
//!
//! Normals: octahedral coordinates in steps of `1/32767`; the direction is
//! the point of the octahedron `|x| + |y| + |z| = 1` they name. Rounding
//! each coordinate moves that point by at most `√6/65534` and the
//! octahedron's points are at least `1/√3` from the origin, so the angle
//! error is at most `3√2/65534 ≈ 6.5·10⁻⁵` radian (0.0037°);
//! `host/tests/suite/mesh_format.rs` measures `6.43·10⁻⁵` over a million directions,
//! the axes and the octahedron's seams included. The renderer transforms
//! the octahedron's point itself and normalises once, to `I2F14`.
//!
//! ```
//! use fixshade::mesh::{Bounds, Mesh, PackedNormal};
//! // A triangle in the box [−1, 1)³, facing +z, all of it `static`.
//! static POSITIONS: [[i16; 3]; 3] = [[-32767, -32767, 0], [32767, -32767, 0], [0, 32767, 0]];
//! static NORMALS: [PackedNormal; 3] = [PackedNormal::Z; 3];
//! static INDICES: [[u16; 3]; 1] = [[0, 1, 2]];
//! static MESH: Mesh = Mesh::new(&POSITIONS, Bounds::UNIT, &INDICES).with_normals(&NORMALS);
//! assert!(MESH.validate().is_ok());
//! assert_eq!(MESH.bounds.position_f64(POSITIONS[2]), [0.0, 32767.0 / 32768.0, 0.0]);
//! ```

use crate::normalize::normalize_len;
use crate::platform;
use crate::vector::{sat_shift24, Mat4, Unit3, Vec3, COORD_FRAC};

/// Why a mesh cannot be drawn or read.
///
/// ```
/// use fixshade::mesh::{vertex_normals, Bounds, Mesh, MeshError, PackedNormal};
/// let p = [[0i16; 3]; 3];
/// let mesh = Mesh::new(&p, Bounds::UNIT, &[[0, 1, 2]]);
/// let (mut sums, mut out) = ([[0; 3]; 3], [PackedNormal::ZERO; 2]); // `out` is one short
/// assert_eq!(vertex_normals(&mesh, &mut sums, &mut out), Err(MeshError::BufferTooSmall));
/// assert_eq!(Mesh::from_bytes(b"OBJ?"), Err(MeshError::BadMagic));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum MeshError {
    /// Triangle `triangle` names a vertex index `index` that is not there.
    IndexOutOfRange {
        /// The triangle's position in the index slice.
        triangle: usize,
        /// The offending index.
        index: u16,
    },
    /// The normals slice is not as long as the positions slice.
    NormalCount,
    /// A caller-provided buffer is shorter than the vertex count.
    BufferTooSmall,
    /// The bytes do not start with [`MAGIC`].
    BadMagic,
    /// The bytes are of a layout version this crate does not read.
    UnsupportedVersion(u16),
    /// The header sets flags this version does not define.
    UnknownFlags(u16),
    /// The header counts more than 65 536 vertices (`u16` indices reach
    /// no further).
    TooManyVertices(u32),
    /// Fewer bytes than the header's counts need.
    Truncated {
        /// Bytes the header and its counts need.
        needed: u64,
        /// Bytes given.
        len: usize,
    },
    /// More bytes than the header's counts need.
    TrailingBytes {
        /// Bytes the header and its counts need.
        needed: u64,
        /// Bytes given.
        len: usize,
    },
    /// The bytes do not start at an even address (see [`Aligned`]).
    Misaligned,
    /// The target is big-endian: the little-endian arrays cannot be
    /// borrowed in place.
    BigEndianTarget,
}

impl core::fmt::Display for MeshError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            MeshError::IndexOutOfRange { triangle, index } => {
                write!(
                    f,
                    "triangle {triangle} uses vertex {index}, which does not exist"
                )
            }
            MeshError::NormalCount => f.write_str("normals and positions differ in count"),
            MeshError::BufferTooSmall => f.write_str("buffer shorter than the vertex count"),
            MeshError::BadMagic => f.write_str("not a fixshade mesh (bad magic)"),
            MeshError::UnsupportedVersion(v) => write!(f, "mesh layout version {v} not supported"),
            MeshError::UnknownFlags(v) => write!(f, "unknown mesh flags {v:#06x}"),
            MeshError::TooManyVertices(n) => write!(f, "{n} vertices, more than 65536"),
            MeshError::Truncated { needed, len } => {
                write!(f, "mesh truncated: {len} bytes, {needed} needed")
            }
            MeshError::TrailingBytes { needed, len } => {
                write!(f, "mesh has trailing bytes: {len} bytes, {needed} expected")
            }
            MeshError::Misaligned => f.write_str("mesh bytes not 2-byte aligned"),
            MeshError::BigEndianTarget => {
                f.write_str("mesh bytes cannot be borrowed on a big-endian target")
            }
        }
    }
}

/// The box of a mesh: object position `= offset + scale ∘ q / 2¹⁵` for the
/// quantised position `q` (each component a `Q.15` fraction in [−1, 1)).
///
/// `offset` is `I8F24` (raw `i32`, [−128, 128)) and `scale` `U8F24` (raw
/// `u32`, [0, 256)), per axis: every box around positions that fit
/// `I8F24` has such an offset and scale (a half-extent reaches 128, beyond
/// `I8F24`). Any bits are a box; none is invalid.
///
/// ```
/// use fixshade::mesh::Bounds;
/// // x in [1, 3), y and z in [−1, 1).
/// let b = Bounds::from_bits([2 << 24, 0, 0], [1 << 24; 3]);
/// assert_eq!(b.position_f64([-32768, 16384, 0]), [1.0, 0.5, 0.0]);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Bounds {
    /// The box's centre on each axis, raw `I8F24`.
    pub offset: [i32; 3],
    /// The box's half-extent on each axis, raw `U8F24`.
    pub scale: [u32; 3],
}

impl Bounds {
    /// The box [−1, 1)³: object positions are the `Q.15` values themselves.
    ///
    /// ```
    /// use fixshade::mesh::Bounds;
    /// assert_eq!(Bounds::UNIT.position_f64([16384, -32768, 0]), [0.5, -1.0, 0.0]);
    /// ```
    pub const UNIT: Bounds = Bounds::from_bits([0; 3], [1 << COORD_FRAC; 3]);

    /// The cube `[−half, half)³` about the origin, for `const` data: `half`
    /// rounded to `2⁻²⁴` and clamped to `[2⁻²⁴, 128]` (NaN is the least).
    ///
    /// ```
    /// use fixshade::mesh::Bounds;
    /// const B: Bounds = Bounds::cube(2.0);
    /// assert_eq!(B, Bounds::from_bits([0; 3], [2 << 24; 3]));
    /// assert_eq!(B.position_f64([-32768, 16384, 0]), [-2.0, 1.0, 0.0]);
    /// assert_eq!(Bounds::cube(1e9), Bounds::cube(128.0));
    /// ```
    pub const fn cube(half: f32) -> Self {
        // `as` saturates (NaN to 0); 128 · 2^24 = 2^31 fits u32.
        let s = (half as f64 * (1u64 << COORD_FRAC) as f64 + 0.5) as u32;
        let s = if s < 1 {
            1
        } else if s > 1 << 31 {
            1 << 31
        } else {
            s
        };
        Bounds::from_bits([0; 3], [s; 3])
    }

    /// A box from raw bits (usable in `const` and `static` data).
    ///
    /// ```
    /// use fixshade::mesh::Bounds;
    /// const B: Bounds = Bounds::from_bits([0, 1 << 24, 0], [2 << 24, 1 << 24, 1 << 23]);
    /// assert_eq!(B.position_f64([16384, 0, 32767]), [1.0, 1.0, 0.5 * 32767.0 / 32768.0]);
    /// ```
    pub const fn from_bits(offset: [i32; 3], scale: [u32; 3]) -> Self {
        Bounds { offset, scale }
    }

    /// The object-space position of quantised position `q`, exactly (an
    /// `f64` holds it: `offset` has 32 bits, `scale · q` 48, and their sum
    /// lies on the grid of `2⁻³⁹` below 2⁹).
    ///
    /// ```
    /// use fixshade::mesh::Bounds;
    /// let b = Bounds::from_bits([-(1 << 24), 0, 0], [3, 0, 0]);
    /// let x = b.position_f64([32767, 0, 0])[0];
    /// assert_eq!(x, -1.0 + 3.0 * 32767.0 * 2f64.powi(-39));
    /// ```
    pub fn position_f64(&self, q: [i16; 3]) -> [f64; 3] {
        let unit = 1.0 / (1u64 << COORD_FRAC) as f64;
        [0, 1, 2].map(|k| {
            let step = self.scale[k] as f64 * unit / 32768.0;
            self.offset[k] as f64 * unit + step * q[k] as f64
        })
    }

    /// `m · B`, where `B` takes a quantised position (as `Q.15` fractions)
    /// to object space: the matrix that takes a mesh's `i16` positions
    /// ([`Mat4::transform_quantised`]) where `m` takes its object positions.
    ///
    /// Each entry is the exact value rounded once to `I8F24` and saturated,
    /// as [`Mat4::mul`]'s: `m[r][c]·scale[c]` (`|m| ≤ 2³¹`, `scale < 2³²`:
    /// below 2⁶³) for the linear part, `Σ m[r][c]·offset[c] + m[r][3]·2²⁴`
    /// for the translation, summed saturating from the translation on (it
    /// at most 2⁵⁵, each product at most 2⁶²: the first sum cannot
    /// saturate, so where one does, at most one product is left, which
    /// leaves the saturated sum and the exact one beyond ±2⁶² on the same
    /// side, and both clamp alike). An entry saturates only
    /// where the box's image leaves eye space: `|m[r][c]|·scale[c] ≥ 128`
    /// puts the box's opposite faces' centres 256 apart on that eye axis,
    /// and a saturated translation puts the box's centre beyond ±128.
    ///
    /// ```
    /// use fixshade::mesh::Bounds;
    /// use fixshade::{Mat4, Vec3};
    /// let b = Bounds::from_bits([1 << 24, 0, 0], [4 << 24; 3]); // x in [−3, 5)
    /// let m = Mat4::translation(Vec3::from_f32(0.0, 0.0, -10.0).unwrap());
    /// let eye = b.fold(&m).transform_quantised([16384, 0, -32768]);
    /// assert_eq!(eye.to_f32(), [3.0, 0.0, -14.0]); // (1 + 4·½, 0, −4) − 10 z
    /// ```
    pub fn fold(&self, m: &Mat4) -> Mat4 {
        let mut out = [[0i32; 4]; 4];
        for (o, row) in out.iter_mut().zip(&m.m) {
            for c in 0..3 {
                o[c] = sat_shift24(row[c] as i64 * self.scale[c] as i64);
            }
            let t = (0..3)
                .map(|c| row[c] as i64 * self.offset[c] as i64)
                .fold((row[3] as i64) << COORD_FRAC, i64::saturating_add);
            o[3] = sat_shift24(t);
        }
        Mat4 { m: out }
    }
}

/// A unit normal in two `i16`: octahedral coordinates `(u, v)` in steps of
/// `1/32767`, the point `(u, v, 1 − |u| − |v|)` of the octahedron
/// `|x| + |y| + |z| = 1`, its lower half folded out over the square's
/// corners. Angle error at most `6.5·10⁻⁵` radian ([module
/// docs](self#precision)).
///
/// `u = −32768` (outside the encoder's ±32767) is [`PackedNormal::ZERO`],
/// the zero normal (lit by `E + A·Ka` only, as SPEC.md has it); any other
/// bits name a direction.
///
/// ```
/// use fixshade::mesh::PackedNormal;
/// use fixshade::Unit3;
/// assert_eq!(PackedNormal::X.to_unit3(), Unit3::X);
/// assert_eq!(PackedNormal::from_vector([0, 0, -7]).to_unit3(), Unit3::Z.neg());
/// assert_eq!(PackedNormal::from_vector([0, 0, 0]), PackedNormal::ZERO);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[repr(C)]
pub struct PackedNormal {
    u: i16,
    v: i16,
}

/// The octahedron's scale: `|x| + |y| + |z|` of every decoded normal.
const OCT_ONE: i32 = 32767;

impl PackedNormal {
    /// +X.
    ///
    /// ```
    /// use fixshade::mesh::PackedNormal;
    /// assert_eq!(PackedNormal::X.octahedron(), [32767, 0, 0]);
    /// ```
    pub const X: PackedNormal = PackedNormal { u: 32767, v: 0 };
    /// +Y.
    ///
    /// ```
    /// use fixshade::mesh::PackedNormal;
    /// assert_eq!(PackedNormal::Y.octahedron(), [0, 32767, 0]);
    /// ```
    pub const Y: PackedNormal = PackedNormal { u: 0, v: 32767 };
    /// +Z.
    ///
    /// ```
    /// use fixshade::mesh::PackedNormal;
    /// assert_eq!(PackedNormal::Z.octahedron(), [0, 0, 32767]);
    /// ```
    pub const Z: PackedNormal = PackedNormal { u: 0, v: 0 };
    /// The zero normal.
    ///
    /// ```
    /// use fixshade::mesh::PackedNormal;
    /// use fixshade::Unit3;
    /// assert_eq!(PackedNormal::ZERO.octahedron(), [0; 3]);
    /// assert_eq!(PackedNormal::ZERO.to_unit3(), Unit3::ZERO);
    /// ```
    pub const ZERO: PackedNormal = PackedNormal {
        u: i16::MIN,
        v: i16::MIN,
    };

    /// A normal from its raw octahedral coordinates (for `static` data).
    ///
    /// ```
    /// use fixshade::mesh::PackedNormal;
    /// const DOWN: PackedNormal = PackedNormal::from_bits(32767, 32767);
    /// assert_eq!(DOWN.octahedron(), [0, 0, -32767]);
    /// ```
    pub const fn from_bits(u: i16, v: i16) -> Self {
        PackedNormal { u, v }
    }

    /// The raw octahedral coordinates.
    ///
    /// ```
    /// use fixshade::mesh::PackedNormal;
    /// assert_eq!(PackedNormal::from_bits(-5, 7).to_bits(), [-5, 7]);
    /// ```
    pub const fn to_bits(self) -> [i16; 2] {
        [self.u, self.v]
    }

    /// The direction as the point of the octahedron `|x| + |y| + |z| =
    /// 32767` (zero for [`PackedNormal::ZERO`]): exact integers, to be
    /// transformed and normalised.
    ///
    /// For any bits, each component is at most 32768 in magnitude and the
    /// three sum to at most `3·2¹⁵` in magnitude (`|u|, |v| ≤ 2¹⁵`); for
    /// the encoder's (`|u|, |v| ≤ 32767`) the sum is exactly 32767.
    ///
    /// ```
    /// use fixshade::mesh::PackedNormal;
    /// // Upper half: (u, v, 1 − |u| − |v|).
    /// assert_eq!(PackedNormal::from_bits(1000, -2000).octahedron(), [1000, -2000, 29767]);
    /// // Lower half, folded: x = ±(1 − |v|), y = ±(1 − |u|).
    /// assert_eq!(PackedNormal::from_bits(30000, -10000).octahedron(), [22767, -2767, -7233]);
    /// ```
    #[inline]
    pub const fn octahedron(self) -> [i32; 3] {
        if self.u == i16::MIN {
            return [0; 3];
        }
        let (u, v) = (self.u as i32, self.v as i32);
        let (au, av) = (u.abs(), v.abs());
        let z = OCT_ONE - au - av;
        if z >= 0 {
            [u, v, z]
        } else {
            let x = OCT_ONE - av;
            let y = OCT_ONE - au;
            [if u < 0 { -x } else { x }, if v < 0 { -y } else { y }, z]
        }
    }

    /// The direction as an `I2F14` unit vector (the kernel's `normalize`
    /// of [`PackedNormal::octahedron`]).
    ///
    /// ```
    /// use fixshade::mesh::PackedNormal;
    /// let n = PackedNormal::from_vector([1, 1, 1]).to_unit3().to_bits();
    /// assert!(n.iter().all(|&c| (c - 9459).abs() <= 1)); // 2^14/√3 = 9459.0…
    /// ```
    pub fn to_unit3(self) -> Unit3 {
        crate::normalize::normalize(self.octahedron()).unwrap_or(Unit3::ZERO)
    }

    /// The octahedral coordinates of the direction of `v`, each rounded to
    /// the nearest step; [`PackedNormal::ZERO`] for the zero vector.
    ///
    /// `u = x/(|x| + |y| + |z|)` and `v` likewise where `z ≥ 0`; below,
    /// `u = ±(|x| + |z|)/(|x| + |y| + |z|)` with `x`'s sign (+ for 0) and `v`
    /// likewise (the octahedron's lower half folded out). Magnitudes below
    /// 2³¹: the sum below 2³³, each numerator times 32767 below 2⁴⁹ in
    /// `u64`; each quotient is at most 32767. Two divisions: meant for
    /// preparing a mesh, not for a frame.
    ///
    /// ```
    /// use fixshade::mesh::PackedNormal;
    /// assert_eq!(PackedNormal::from_vector([0, 0, 1]), PackedNormal::Z);
    /// assert_eq!(PackedNormal::from_vector([3, -1, 0]).to_bits(), [24575, -8192]);
    /// assert_eq!(PackedNormal::from_vector([0, 0, -1]).to_bits(), [32767, 32767]);
    /// ```
    pub fn from_vector(v: [i32; 3]) -> Self {
        let a = v.map(|c| c.unsigned_abs() as u64);
        let l1 = a[0] + a[1] + a[2];
        if l1 == 0 {
            return PackedNormal::ZERO;
        }
        // round(32767·n / l1) for n ≤ l1: at most 32767.
        let q = |n: u64| ((2 * n * OCT_ONE as u64 + l1) / (2 * l1)) as i16;
        let (u, w) = if v[2] >= 0 {
            (q(a[0]), q(a[1]))
        } else {
            (q(a[0] + a[2]), q(a[1] + a[2]))
        };
        PackedNormal {
            u: if v[0] < 0 { -u } else { u },
            v: if v[1] < 0 { -w } else { w },
        }
    }
}

/// A triangle mesh borrowed from the caller ([module docs](self) for the
/// format). Front faces are counter-clockwise in NDC (SPEC.md 5).
///
/// ```
/// use fixshade::mesh::{Bounds, Mesh};
/// static POSITIONS: [[i16; 3]; 3] = [[0, 0, 0], [32767, 0, 0], [0, 32767, 0]];
/// static INDICES: [[u16; 3]; 1] = [[0, 1, 2]];
/// let mesh = Mesh::new(&POSITIONS, Bounds::UNIT, &INDICES);
/// assert!(mesh.validate().is_ok());
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Mesh<'a> {
    /// Quantised positions, `Q.15` fractions of `bounds`.
    pub positions: &'a [[i16; 3]],
    /// The box the positions are quantised in.
    pub bounds: Bounds,
    /// Normals, one per position, or `None` (see [`vertex_normals`]).
    pub normals: Option<&'a [PackedNormal]>,
    /// Triangles as vertex indices ([`Mesh::indices`]).
    indices: &'a [[u16; 3]],
    /// The largest index (0 without triangles), found once where the mesh
    /// is made ([`Mesh::new`], at compile time for a `static`), so that a
    /// draw checks every index with one compare ([`Mesh::validate`]).
    /// Invariant: no index is larger. Only `Mesh::new` sets it and
    /// `indices`, both private: the draws' unchecked reads of the vertex
    /// cache rely on it through `validate`.
    top: u16,
}

/// The first bytes of a mesh's byte layout ([`Mesh::from_bytes`]).
///
/// ```
/// assert_eq!(&fixshade::mesh::MAGIC, b"FXSM");
/// ```
pub const MAGIC: [u8; 4] = *b"FXSM";

/// The byte layout's version ([`Mesh::from_bytes`]).
///
/// ```
/// assert_eq!(fixshade::mesh::VERSION, 1);
/// ```
pub const VERSION: u16 = 1;

/// The header's length in bytes ([`Mesh::from_bytes`]); the arrays follow
/// it.
///
/// ```
/// assert_eq!(fixshade::mesh::HEADER_LEN, 40);
/// ```
pub const HEADER_LEN: usize = 40;

/// Header flag: normals follow the positions.
///
/// ```
/// assert_eq!(fixshade::mesh::FLAG_NORMALS, 1);
/// ```
pub const FLAG_NORMALS: u16 = 1;

/// Bytes aligned to 4 (the mesh layout needs 2): wrap `include_bytes!` in
/// it, or use [`include_mesh!`](crate::include_mesh).
///
/// ```
/// use fixshade::mesh::Aligned;
/// static BYTES: &Aligned<[u8]> = &Aligned([1, 2, 3]);
/// assert_eq!(BYTES.0.as_ptr() as usize % 4, 0);
/// ```
#[repr(C, align(4))]
pub struct Aligned<B: ?Sized>(pub B);

/// A [`Mesh`] from a file of its byte layout, included at compile time:
/// `include_mesh!("bunny.fxm")` is `Mesh::from_bytes` of the file's bytes,
/// aligned ([`Aligned`]), a `Result<Mesh<'static>, MeshError>`. The host
/// converter writes such files (the `fixshade-convert` command of the host tools).
///
/// ```
/// # fn main() -> Result<(), fixshade::mesh::MeshError> {
/// let mesh = fixshade::include_mesh!("../tests/data/tetrahedron.fxm")?;
/// assert_eq!((mesh.positions.len(), mesh.indices().len()), (4, 4));
/// # Ok(())
/// # }
/// ```
#[macro_export]
macro_rules! include_mesh {
    ($path:expr) => {{
        static BYTES: &$crate::mesh::Aligned<[u8]> =
            &$crate::mesh::Aligned(*::core::include_bytes!($path));
        $crate::mesh::Mesh::from_bytes(&BYTES.0)
    }};
}

impl<'a> Mesh<'a> {
    /// A mesh without normals.
    ///
    /// ```
    /// use fixshade::mesh::{Bounds, Mesh};
    /// let positions = [[0i16; 3]; 4];
    /// let indices = [[0, 1, 2], [0, 2, 3]];
    /// let mesh = Mesh::new(&positions, Bounds::UNIT, &indices);
    /// assert!(mesh.normals.is_none());
    /// assert_eq!((mesh.positions.len(), mesh.indices().len()), (4, 2));
    /// ```
    ///
    /// It finds the largest index once, a `static` mesh's at compile time,
    /// so that a draw checks the indices with one compare
    /// ([`Mesh::validate`]) instead of a pass over the triangles.
    pub const fn new(positions: &'a [[i16; 3]], bounds: Bounds, indices: &'a [[u16; 3]]) -> Self {
        let mut top = 0u16;
        let mut t = 0;
        while t < indices.len() {
            let [a, b, c] = indices[t];
            // (`Ord::max` is not `const`.)
            let ab = if a > b { a } else { b };
            let abc = if ab > c { ab } else { c };
            top = if abc > top { abc } else { top };
            t += 1;
        }
        Mesh {
            positions,
            bounds,
            normals: None,
            indices,
            top,
        }
    }

    /// The triangles, as vertex indices.
    ///
    /// ```
    /// use fixshade::mesh::{Bounds, Mesh};
    /// let mesh = Mesh::new(&[[0i16; 3]; 3], Bounds::UNIT, &[[0, 1, 2]]);
    /// assert_eq!(mesh.indices(), &[[0, 1, 2]]);
    /// ```
    pub const fn indices(&self) -> &'a [[u16; 3]] {
        self.indices
    }

    /// Adds normals.
    ///
    /// ```
    /// use fixshade::mesh::{Bounds, Mesh, MeshError, PackedNormal};
    /// let positions = [[0i16; 3]; 3];
    /// let normals = [PackedNormal::Z; 3];
    /// let mesh = Mesh::new(&positions, Bounds::UNIT, &[[0, 1, 2]]).with_normals(&normals);
    /// assert_eq!(mesh.normals, Some(&normals[..]));
    /// assert!(mesh.validate().is_ok());
    /// let short = mesh.with_normals(&normals[..2]);
    /// assert_eq!(short.validate(), Err(MeshError::NormalCount));
    /// ```
    pub const fn with_normals(mut self, normals: &'a [PackedNormal]) -> Self {
        self.normals = Some(normals);
        self
    }

    /// Checks every index and the normals' count: the indices by their
    /// largest, which [`Mesh::new`] found (one compare a draw); the
    /// triangles one by one only to name the first that fails.
    ///
    /// ```
    /// use fixshade::mesh::{Bounds, Mesh, MeshError};
    /// let positions = [[0i16; 3]; 3];
    /// let mesh = Mesh::new(&positions, Bounds::UNIT, &[[0, 1, 2], [2, 1, 3]]);
    /// let err = MeshError::IndexOutOfRange { triangle: 1, index: 3 };
    /// assert_eq!(mesh.validate(), Err(err));
    /// ```
    pub fn validate(&self) -> Result<(), MeshError> {
        if let Some(n) = self.normals {
            if n.len() != self.positions.len() {
                return Err(MeshError::NormalCount);
            }
        }
        let count = self.positions.len();
        if self.indices.is_empty() || usize::from(self.top) < count {
            return Ok(());
        }
        for (t, tri) in self.indices.iter().enumerate() {
            for &i in tri {
                if i as usize >= count {
                    return Err(MeshError::IndexOutOfRange {
                        triangle: t,
                        index: i,
                    });
                }
            }
        }
        Ok(())
    }

    /// Borrows a mesh from its byte layout (what the host converter's
    /// `to_bytes` writes, for `include_bytes!`; see [`include_mesh!`]).
    ///
    /// Little-endian; a 40-byte header, then the arrays, no padding:
    ///
    /// | bytes | content |
    /// | --- | --- |
    /// | 0..4 | [`MAGIC`], `FXSM` |
    /// | 4..6 | `u16` layout [`VERSION`], 1 |
    /// | 6..8 | `u16` flags: [`FLAG_NORMALS`] (bit 0), the others 0 |
    /// | 8..12 | `u32` vertex count `n`, at most 65 536 |
    /// | 12..16 | `u32` triangle count `t` |
    /// | 16..28 | [`Bounds::offset`], 3 × `i32` |
    /// | 28..40 | [`Bounds::scale`], 3 × `u32` |
    /// | 40.. | `n` positions, 3 × `i16` each |
    /// | then | if flagged, `n` normals, 2 × `i16` each ([`PackedNormal::to_bits`]) |
    /// | then | `t` triangles, 3 × `u16` each |
    ///
    /// The arrays are borrowed in place, not copied: the bytes must start
    /// at an even address (every array then does: the header and each
    /// element have even lengths). Checked in this order, each failure an
    /// error, never a panic: magic, header length, version, flags, vertex
    /// count, total length (exactly the header's), alignment, byte order
    /// of the target, then [`Mesh::validate`] (every index).
    ///
    /// ```
    /// use fixshade::mesh::{Aligned, Mesh, MeshError};
    /// static BYTES: Aligned<[u8; 40 + 6]> = Aligned(*b"FXSM\x01\x00\x00\x00\x01\x00\x00\x00\
    /// \x00\x00\x00\x00\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\x01\0\0\0\x01\0\0\0\x01\xff\x7f\0\0\0\0");
    /// let mesh = Mesh::from_bytes(&BYTES.0).unwrap();
    /// assert_eq!(mesh.positions, &[[32767, 0, 0]]);
    /// assert_eq!(mesh.bounds.scale, [1 << 24; 3]);
    /// assert_eq!(Mesh::from_bytes(&BYTES.0[..45]), Err(MeshError::Truncated { needed: 46, len: 45 }));
    /// ```
    pub fn from_bytes(bytes: &'a [u8]) -> Result<Mesh<'a>, MeshError> {
        if bytes.len() < MAGIC.len() || bytes[..4] != MAGIC {
            return Err(MeshError::BadMagic);
        }
        let Some(header) = bytes.first_chunk::<HEADER_LEN>() else {
            return Err(MeshError::Truncated {
                needed: HEADER_LEN as u64,
                len: bytes.len(),
            });
        };
        let u16_at = |i: usize| u16::from_le_bytes([header[i], header[i + 1]]);
        let u32_at =
            |i: usize| u32::from_le_bytes([header[i], header[i + 1], header[i + 2], header[i + 3]]);
        let version = u16_at(4);
        if version != VERSION {
            return Err(MeshError::UnsupportedVersion(version));
        }
        let flags = u16_at(6);
        if flags & !FLAG_NORMALS != 0 {
            return Err(MeshError::UnknownFlags(flags));
        }
        let (n, t) = (u32_at(8), u32_at(12));
        if n > 65536 {
            return Err(MeshError::TooManyVertices(n));
        }
        let bounds = Bounds {
            offset: [16, 20, 24].map(|i| u32_at(i) as i32),
            scale: [28, 32, 36].map(u32_at),
        };
        // n ≤ 2^16 and t < 2^32: needed < 40 + 10·2^16 + 6·2^32 < 2^35.
        let has_normals = flags & FLAG_NORMALS != 0;
        let normal_bytes = if has_normals { 4 * n as u64 } else { 0 };
        let needed = HEADER_LEN as u64 + 6 * n as u64 + normal_bytes + 6 * t as u64;
        let len = bytes.len();
        if (len as u64) < needed {
            return Err(MeshError::Truncated { needed, len });
        }
        if len as u64 > needed {
            return Err(MeshError::TrailingBytes { needed, len });
        }
        if !(bytes.as_ptr() as usize).is_multiple_of(2) {
            return Err(MeshError::Misaligned);
        }
        if !platform::little_endian() {
            return Err(MeshError::BigEndianTarget);
        }
        // needed == len: every count below fits `usize` and every array
        // lies within `bytes`.
        let (n, t) = (n as usize, t as usize);
        let (positions, rest) = bytes[HEADER_LEN..].split_at(6 * n);
        let (normals, indices) = rest.split_at(if has_normals { 4 * n } else { 0 });
        // SAFETY (all three): each slice starts at an even address (`bytes`
        // does, and the header and every element have even lengths) and
        // holds exactly `count × size_of::<T>()` bytes; `[i16; 3]`,
        // `PackedNormal` (`repr(C)`, two `i16`) and `[u16; 3]` have
        // alignment 2, no padding and no invalid bit patterns, and the
        // target is little-endian (checked), the layout's byte order. The
        // results borrow `bytes` immutably for `'a`.
        let positions =
            unsafe { core::slice::from_raw_parts(positions.as_ptr().cast::<[i16; 3]>(), n) };
        let indices =
            unsafe { core::slice::from_raw_parts(indices.as_ptr().cast::<[u16; 3]>(), t) };
        let mut mesh = Mesh::new(positions, bounds, indices);
        if has_normals {
            let normals =
                unsafe { core::slice::from_raw_parts(normals.as_ptr().cast::<PackedNormal>(), n) };
            mesh = mesh.with_normals(normals);
        }
        mesh.validate()?;
        Ok(mesh)
    }
}

/// The unit normal of the triangle `a, b, c` (counter-clockwise seen from
/// the side it points to), or `None` for a degenerate triangle.
///
/// Edge vectors are `I8F24` differences (below 2³² raw); both are shifted
/// right together until they fit 30 bits, so the cross product's terms
/// (below 2⁶⁰) fit `i64`. The shift loses only bits far below the
/// `I2F14` result's precision.
///
/// ```
/// use fixshade::mesh::face_normal;
/// use fixshade::{Unit3, Vec3};
/// let a = Vec3::ZERO;
/// let b = Vec3::from_f32(2.0, 0.0, 0.0).unwrap();
/// let c = Vec3::from_f32(0.0, 3.0, 0.0).unwrap();
/// assert_eq!(face_normal(a, b, c), Some(Unit3::Z)); // counter-clockwise seen from +z
/// assert_eq!(face_normal(a, c, b), Some(Unit3::Z.neg()));
/// let d = Vec3::from_f32(4.0, 0.0, 0.0).unwrap();
/// assert_eq!(face_normal(a, b, d), None); // collinear
/// ```
pub fn face_normal(a: Vec3, b: Vec3, c: Vec3) -> Option<Unit3> {
    let (a, b, c) = (a.to_bits(), b.to_bits(), c.to_bits());
    let mut u = [0, 1, 2].map(|i| b[i] as i64 - a[i] as i64);
    let mut v = [0, 1, 2].map(|i| c[i] as i64 - a[i] as i64);
    let max = u
        .iter()
        .chain(v.iter())
        .map(|x| x.unsigned_abs())
        .max()
        .unwrap_or(0);
    let bits = 64 - max.leading_zeros();
    if bits > 30 {
        let s = bits - 30;
        u = u.map(|x| x >> s);
        v = v.map(|x| x >> s);
    }
    let n = [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ];
    normalize_len(n).map(|(n, _)| n)
}

/// The object-space unit normal of the triangle `a, b, c` of quantised
/// positions in the box of scale `scale`, or `None` for a degenerate one.
///
/// The object-space edges are `scale ∘ (b − a)` and `scale ∘ (c − a)`, so
/// their cross product is `(s_y s_z n_x, s_z s_x n_y, s_x s_y n_z)` for
/// the cross product `n` of the quantised edges: differences below 2¹⁶,
/// `n`'s terms below 2³², `n` below 2³³; the weights below 2⁶⁴; the
/// products below 2⁹⁷ (`i128`), shifted together below 2⁶² for
/// [`normalize_len`] (its direction keeps 20 bits of the largest).
fn quantised_face_normal(scale: [u32; 3], a: [i16; 3], b: [i16; 3], c: [i16; 3]) -> Option<Unit3> {
    let u = [0, 1, 2].map(|i| b[i] as i64 - a[i] as i64);
    let v = [0, 1, 2].map(|i| c[i] as i64 - a[i] as i64);
    let n = [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ];
    let s = scale.map(|x| x as i128);
    let w = [s[1] * s[2], s[2] * s[0], s[0] * s[1]];
    let p = [0, 1, 2].map(|k| n[k] as i128 * w[k]);
    let max = p.iter().map(|x| x.unsigned_abs()).max().unwrap_or(0);
    let shift = (128 - max.leading_zeros()).saturating_sub(62);
    normalize_len(p.map(|x| (x >> shift) as i64)).map(|(n, _)| n)
}

/// Vertex normals for a mesh without them (SPEC.md 4): the sum of the unit
/// normals of the faces that share each vertex, packed. The faces are
/// those of the quantised positions in object space (the box's scale
/// applied, so a box stretched on one axis tilts them as it should).
///
/// `sums` is scratch space and `out` the result, both at least as long as
/// `mesh.positions`; `mesh.normals` is not read. A vertex no face uses, or
/// whose face normals cancel, gets [`PackedNormal::ZERO`] (it is then lit
/// by `E + A·Ka` only).
///
/// ```
/// use fixshade::mesh::{vertex_normals, Bounds, Mesh, PackedNormal};
/// let p = [[0, 0, 0], [32767, 0, 0], [0, 32767, 0]];
/// let mesh = Mesh::new(&p, Bounds::UNIT, &[[0, 1, 2]]);
/// let (mut sums, mut out) = ([[0i32; 3]; 3], [PackedNormal::ZERO; 3]);
/// vertex_normals(&mesh, &mut sums, &mut out).unwrap();
/// assert_eq!(out, [PackedNormal::Z; 3]);
/// let normals = mesh.with_normals(&out); // ready to draw
/// # assert!(normals.validate().is_ok());
/// ```
pub fn vertex_normals(
    mesh: &Mesh,
    sums: &mut [[i32; 3]],
    out: &mut [PackedNormal],
) -> Result<(), MeshError> {
    let n = mesh.positions.len();
    if sums.len() < n || out.len() < n {
        return Err(MeshError::BufferTooSmall);
    }
    Mesh {
        normals: None,
        ..*mesh
    }
    .validate()?;
    let p = mesh.positions;
    sums[..n].fill([0; 3]);
    for tri in mesh.indices {
        let [a, b, c] = tri.map(|i| i as usize);
        if let Some(f) = quantised_face_normal(mesh.bounds.scale, p[a], p[b], p[c]) {
            let f = f.to_bits();
            for &v in &[a, b, c] {
                for k in 0..3 {
                    sums[v][k] = sums[v][k].saturating_add(f[k] as i32);
                }
            }
        }
    }
    for (o, s) in out[..n].iter_mut().zip(&sums[..n]) {
        *o = PackedNormal::from_vector(*s);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The largest index is found where the mesh is made, at compile time
    /// for a `static`, wherever it lies in a triangle; the check against
    /// the count is made at validation, so a mesh whose positions are
    /// shortened afterwards still fails, naming its first bad triangle.
    #[test]
    fn largest_index_found_when_made() {
        static P: [[i16; 3]; 4] = [[0; 3]; 4];
        static T: [[u16; 3]; 3] = [[0, 1, 2], [3, 0, 1], [1, 2, 0]];
        static M: Mesh = Mesh::new(&P, Bounds::UNIT, &T);
        assert_eq!(M.top, 3);
        assert_eq!(M.validate(), Ok(()));
        let short = Mesh {
            positions: &P[..3],
            ..M
        };
        let err = MeshError::IndexOutOfRange {
            triangle: 1,
            index: 3,
        };
        assert_eq!(short.validate(), Err(err));
        assert_eq!(Mesh::new(&P, Bounds::UNIT, &[]).top, 0);
        for k in 0..3 {
            let mut t = [[1u16; 3]; 3];
            t[1][k] = 9;
            t[2][k] = 5;
            assert_eq!(Mesh::new(&P, Bounds::UNIT, &t).top, 9, "{k}");
        }
    }

    /// Every index is checked against the count at the ends of both
    /// ranges: the last vertex passes, one past it fails with the first
    /// offending triangle, an empty position list fails any index, and a
    /// full `u16` range of positions passes any.
    #[test]
    fn validate_checks_each_index_at_the_edges() {
        let positions = [[0i16; 3]; 65_537];
        for count in [1usize, 2, 3, 255, 256, 257, 32_768, 65_535, 65_536, 65_537] {
            let p = &positions[..count];
            let last = (count - 1).min(65_535) as u16;
            let ok = [[0, last, 0], [last, last, last]];
            assert_eq!(
                Mesh::new(p, Bounds::UNIT, &ok).validate(),
                Ok(()),
                "{count}"
            );
            if count <= 65_535 {
                let bad = count as u16;
                for k in 0..3 {
                    let mut t = [[0u16; 3], [last; 3], [0; 3]];
                    t[2][k] = bad;
                    assert_eq!(
                        Mesh::new(p, Bounds::UNIT, &t).validate(),
                        Err(MeshError::IndexOutOfRange {
                            triangle: 2,
                            index: bad
                        }),
                        "{count} {k}"
                    );
                }
                let worst = [[u16::MAX; 3]];
                assert!(Mesh::new(p, Bounds::UNIT, &worst).validate().is_err());
            }
        }
        let none: [[i16; 3]; 0] = [];
        assert!(Mesh::new(&none, Bounds::UNIT, &[[0, 0, 0]])
            .validate()
            .is_err());
        assert_eq!(Mesh::new(&none, Bounds::UNIT, &[]).validate(), Ok(()));
    }
}
