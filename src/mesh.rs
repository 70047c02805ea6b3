//! Meshes borrowed from the caller, and vertex normals for meshes without
//! them (SPEC.md 4).
//!
//! A [`Mesh`] is three slices: positions, optional unit normals, and `u16`
//! triangle indices. All can be `static` data in flash.

use crate::normalize::normalize_len;
use crate::vector::{Unit3, Vec3};

/// Why a mesh cannot be drawn.
///
/// ```
/// use fixshade::mesh::{vertex_normals, MeshError};
/// use fixshade::{Unit3, Vec3};
/// let p = [Vec3::ZERO; 3];
/// let (mut sums, mut out) = ([[0; 3]; 3], [Unit3::ZERO; 2]); // `out` is one short
/// let r = vertex_normals(&p, &[[0, 1, 2]], &mut sums, &mut out);
/// assert_eq!(r, Err(MeshError::BufferTooSmall));
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
        }
    }
}

/// A triangle mesh borrowed from the caller. Front faces are
/// counter-clockwise in NDC (SPEC.md 5).
///
/// ```
/// use fixshade::mesh::Mesh;
/// use fixshade::Vec3;
/// static POSITIONS: [Vec3; 3] = [
///     Vec3::from_bits(0, 0, 0),
///     Vec3::from_bits(1 << 24, 0, 0),
///     Vec3::from_bits(0, 1 << 24, 0),
/// ];
/// static INDICES: [[u16; 3]; 1] = [[0, 1, 2]];
/// let mesh = Mesh::new(&POSITIONS, &INDICES);
/// assert!(mesh.validate().is_ok());
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Mesh<'a> {
    /// Object-space positions.
    pub positions: &'a [Vec3],
    /// Unit normals, one per position, or `None` (see [`vertex_normals`]).
    pub normals: Option<&'a [Unit3]>,
    /// Triangles as vertex indices.
    pub indices: &'a [[u16; 3]],
}

impl<'a> Mesh<'a> {
    /// A mesh without normals.
    ///
    /// ```
    /// use fixshade::mesh::Mesh;
    /// use fixshade::Vec3;
    /// let positions = [Vec3::ZERO; 4];
    /// let indices = [[0, 1, 2], [0, 2, 3]];
    /// let mesh = Mesh::new(&positions, &indices);
    /// assert!(mesh.normals.is_none());
    /// assert_eq!((mesh.positions.len(), mesh.indices.len()), (4, 2));
    /// ```
    pub const fn new(positions: &'a [Vec3], indices: &'a [[u16; 3]]) -> Self {
        Mesh {
            positions,
            normals: None,
            indices,
        }
    }

    /// Adds normals.
    ///
    /// ```
    /// use fixshade::mesh::{Mesh, MeshError};
    /// use fixshade::{Unit3, Vec3};
    /// let positions = [Vec3::ZERO; 3];
    /// let normals = [Unit3::Z; 3];
    /// let mesh = Mesh::new(&positions, &[[0, 1, 2]]).with_normals(&normals);
    /// assert_eq!(mesh.normals, Some(&normals[..]));
    /// assert!(mesh.validate().is_ok());
    /// let short = Mesh::new(&positions, &[[0, 1, 2]]).with_normals(&normals[..2]);
    /// assert_eq!(short.validate(), Err(MeshError::NormalCount));
    /// ```
    pub const fn with_normals(mut self, normals: &'a [Unit3]) -> Self {
        self.normals = Some(normals);
        self
    }

    /// Checks every index and the normals' count.
    ///
    /// ```
    /// use fixshade::mesh::{Mesh, MeshError};
    /// use fixshade::Vec3;
    /// let positions = [Vec3::ZERO; 3];
    /// let mesh = Mesh::new(&positions, &[[0, 1, 2], [2, 1, 3]]);
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
        // The largest index first, in one pass the compiler vectorises
        // (callgrind, S3 on x86-64: 0.19 M instructions fewer a frame than
        // the search below alone); the search only for a mesh that fails.
        let largest = self.indices.as_flattened().iter().fold(0, |m, &i| m.max(i));
        if (largest as usize) < count {
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

/// Vertex normals for a mesh without them (SPEC.md 4): the normalised sum
/// of the unit normals of the faces that share each vertex.
///
/// `sums` is scratch space and `out` the result, both at least as long as
/// `positions`. A vertex no face uses, or whose face normals cancel, gets
/// the zero vector (it is then lit by `E + A·Ka` only).
///
/// ```
/// use fixshade::mesh::vertex_normals;
/// use fixshade::{Unit3, Vec3};
/// let p = [Vec3::from_bits(0, 0, 0), Vec3::from_bits(1 << 24, 0, 0), Vec3::from_bits(0, 1 << 24, 0)];
/// let (mut sums, mut out) = ([[0i32; 3]; 3], [Unit3::ZERO; 3]);
/// vertex_normals(&p, &[[0, 1, 2]], &mut sums, &mut out).unwrap();
/// assert_eq!(out[0], Unit3::Z);
/// ```
pub fn vertex_normals(
    positions: &[Vec3],
    indices: &[[u16; 3]],
    sums: &mut [[i32; 3]],
    out: &mut [Unit3],
) -> Result<(), MeshError> {
    let n = positions.len();
    if sums.len() < n || out.len() < n {
        return Err(MeshError::BufferTooSmall);
    }
    Mesh::new(positions, indices).validate()?;
    sums[..n].fill([0; 3]);
    for tri in indices {
        let [a, b, c] = tri.map(|i| i as usize);
        if let Some(f) = face_normal(positions[a], positions[b], positions[c]) {
            let f = f.to_bits();
            for &v in &[a, b, c] {
                for k in 0..3 {
                    sums[v][k] = sums[v][k].saturating_add(f[k] as i32);
                }
            }
        }
    }
    for (o, s) in out[..n].iter_mut().zip(&sums[..n]) {
        *o = normalize_len([s[0] as i64, s[1] as i64, s[2] as i64])
            .map(|(u, _)| u)
            .unwrap_or(Unit3::ZERO);
    }
    Ok(())
}
