//! Host only: meshes converted to the kernel's flash format
//! ([`fixshade::mesh`]), from a [`MeshDesc`] (the generators of
//! [`crate::generate`], an OBJ file through [`read_obj_file`], a
//! scene's mesh), and written as Rust source (`static`s) or as the bytes
//! that [`Mesh::from_bytes`] and [`include_mesh!`](fixshade::include_mesh)
//! read. `src/bin/convert.rs` (`fixshade-convert`) is the command-line front end; the
//! firmware build scripts and [`KernelScene`](crate::scene_kernel::KernelScene)
//! convert their meshes here, and the f64 reference renders the converted
//! mesh dequantised ([`MeshData::to_desc`]), so that kernel and reference
//! draw the same mesh.
//!
//! # Quantisation
//!
//! Per axis, with `min` and `max` the mesh's extremes and `E = max − min`:
//! `lo = ⌊min⌋` on the `I8F24` grid (not below −128), `scale = ⌈(max − lo)
//! · 2¹⁵/65535⌉` on the `U8F24` grid, `offset = lo + scale`, so that
//! `q = −32768` is `lo` and `q = 32767` is at least `max`. Each coordinate
//! takes the nearest of the 65 536 steps of `scale / 2¹⁵`: at most half a
//! step off, `(E + 2⁻²⁴)/131070 + 2⁻⁴⁰`, below `E/65535` for every `E`
//! above `3·2⁻²⁴`. The box's top stays within `I8F24` (the scale is
//! lowered where it would not): every dequantised position is a position
//! a scene may have, and one within `3·2⁻²⁴` of +128 or below −128 is
//! clamped into the range (at most `2.5·2⁻²⁴` off).
//!
//! Normals: [`encode_normal`], the nearest octahedral coordinates;
//! [`decode_normal`] gives back the exact direction the kernel draws.
//!
//! ```
//! use fixshade_host::generate::sphere;
//! use fixshade_host::mesh_convert::MeshData;
//! let desc = sphere(16, 8, 1.0);
//! let data = MeshData::from_desc(&desc).unwrap();
//! let back = data.to_desc(); // what the kernel draws, in f64
//! let err = desc.positions.iter().zip(&back.positions)
//!     .flat_map(|(a, b)| (0..3).map(move |k| (a[k] - b[k]).abs()))
//!     .fold(0.0, f64::max);
//! assert!(err <= 2.0 / 65535.0, "{err}"); // extent 2 on every axis
//! let bytes = data.to_bytes();
//! assert_eq!(bytes.len(), 40 + 10 * 153 + 6 * 224);
//! ```

use std::fmt::{self, Write as _};
use std::string::String;
use std::vec::Vec;

use crate::generate::ObjError;
use crate::scene_desc::{MeshDesc, MAX_VERTICES};
use crate::scene_file::read_obj_file;
use fixshade::mesh::{
    vertex_normals, Bounds, Mesh, MeshError, PackedNormal, FLAG_NORMALS, MAGIC, VERSION,
};
use fixshade::vector::{FormatError, Vec3};

/// Why a mesh could not be converted.
///
/// ```
/// use fixshade_host::mesh_convert::{ConvertError, MeshData};
/// use fixshade_host::scene_desc::MeshDesc;
/// use fixshade::vector::FormatError;
/// let far = MeshDesc { positions: vec![[0.0, 200.0, 0.0]], normals: None, indices: vec![] };
/// let err = MeshData::from_desc(&far).unwrap_err();
/// assert_eq!(err, ConvertError::Position { index: 0, error: FormatError::OutOfRange });
/// assert_eq!(err.to_string(), "position 0: value outside the fixed-point range");
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ConvertError {
    /// A position is not finite or lies outside `I8F24`'s [−128, 128).
    Position {
        /// Its index.
        index: usize,
        /// What is wrong with it.
        error: FormatError,
    },
    /// More than [`MAX_VERTICES`] vertices.
    TooManyVertices(usize),
    /// The normals are not as many as the positions.
    NormalCount {
        /// Positions.
        positions: usize,
        /// Normals.
        normals: usize,
    },
    /// An index names no vertex.
    Mesh(MeshError),
}

impl fmt::Display for ConvertError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ConvertError::Position { index, error } => write!(f, "position {index}: {error}"),
            ConvertError::TooManyVertices(n) => {
                write!(f, "{n} vertices, more than {MAX_VERTICES}")
            }
            ConvertError::NormalCount { positions, normals } => {
                write!(f, "{normals} normals for {positions} positions")
            }
            ConvertError::Mesh(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for ConvertError {}

/// Why an OBJ file could not be converted ([`MeshData::from_obj_file`]).
///
/// ```
/// use fixshade_host::mesh_convert::{MeshData, ObjFileError};
/// let err = MeshData::from_obj_file("tests/data/no such file.obj").unwrap_err();
/// assert!(matches!(err, ObjFileError::Obj(_)));
/// assert!(err.to_string().starts_with("OBJ: cannot read: "));
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ObjFileError {
    /// The file could not be read or parsed.
    Obj(ObjError),
    /// Its mesh could not be converted.
    Convert(ConvertError),
}

impl fmt::Display for ObjFileError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ObjFileError::Obj(e) => write!(f, "OBJ: {e}"),
            ObjFileError::Convert(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for ObjFileError {}

/// A mesh in the kernel's format, owned: what [`Mesh`] borrows.
///
/// ```
/// use fixshade_host::generate::cube;
/// use fixshade::mesh::PackedNormal;
/// use fixshade_host::mesh_convert::MeshData;
/// let data = MeshData::from_desc(&cube(2.0)).unwrap();
/// let mesh = data.mesh();
/// assert_eq!(mesh.positions[0], [32767, -32768, -32768]); // (1, −1, −1)
/// assert_eq!(mesh.normals.unwrap()[0], PackedNormal::X);
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MeshData {
    /// Quantised positions.
    pub positions: Vec<[i16; 3]>,
    /// Their box.
    pub bounds: Bounds,
    /// Packed normals, or `None`.
    pub normals: Option<Vec<PackedNormal>>,
    /// Triangles.
    pub indices: Vec<[u16; 3]>,
}

/// The raw `I8F24` (or `U8F24`) value of one unit.
const ONE: f64 = (1u64 << 24) as f64;

/// The box of one axis from its values in raw `I8F24` units (each within
/// [−2³¹ − ½, 2³¹ − ½), as [`Vec3::from_f64`] accepts): `(offset, scale)`
/// raw (module docs).
fn axis_box(values: impl Iterator<Item = f64>) -> (i32, u32) {
    let (min, max) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    });
    if min > max {
        return (0, 1 << 24); // no vertex: Bounds::UNIT's
    }
    const TOP: i64 = i32::MAX as i64;
    let lo = (min.floor() as i64).max(i32::MIN as i64);
    // q = 32767 lies at lo + scale·65535/32768 ≥ max. (max − lo)·32768 is
    // exact (a power of two times an f64 difference below 2³³).
    let mut scale = (((max - lo as f64) * 32768.0 / 65535.0).ceil() as i64).max(0);
    // The top within I8F24: lo·32768 + scale·65535 ≤ TOP·32768 (below
    // 2⁴⁸ in magnitude, exact in i64).
    if lo * 32768 + scale * 65535 > TOP * 32768 {
        scale = (TOP - lo) * 32768 / 65535;
    }
    // scale ≤ (2³¹ − 1 − lo)·32768/65535 < 2³² (lo ≥ −2³¹), and offset =
    // lo + scale lies between lo and TOP (scale ≤ (TOP − lo)/2 + 1): both
    // fit their types.
    (
        (lo + scale).clamp(i32::MIN as i64, TOP) as i32,
        scale.min(u32::MAX as i64) as u32,
    )
}

/// The quantised coordinate of `v` (raw `I8F24` units) on an axis with box
/// `(offset, scale)`: the nearest step, clamped to the `i16` range.
fn quantise(v: f64, offset: i32, scale: u32) -> i16 {
    if scale == 0 {
        return 0;
    }
    let q = ((v - offset as f64) * 32768.0 / scale as f64).round();
    q.clamp(i16::MIN as f64, i16::MAX as f64) as i16
}

/// The octahedral coordinates of the direction `n` (module docs of
/// [`fixshade::mesh`]), each the nearest step; [`PackedNormal::ZERO`] for a
/// zero or non-finite vector. Any length: `n` is first divided by its
/// largest component.
///
/// ```
/// use fixshade::mesh::PackedNormal;
/// use fixshade_host::mesh_convert::{decode_normal, encode_normal};
/// assert_eq!(encode_normal([0.0, 0.0, 2.0]), PackedNormal::Z);
/// assert_eq!(encode_normal([0.0, -1e300, 0.0]), PackedNormal::from_bits(0, -32767));
/// assert_eq!(encode_normal([0.0; 3]), PackedNormal::ZERO);
/// assert_eq!(encode_normal([f64::NAN, 0.0, 1.0]), PackedNormal::ZERO);
/// let n = decode_normal(encode_normal([1.0, 2.0, -2.0]));
/// assert!((n[1] - 2.0 / 3.0).abs() < 1e-4 && (n[2] + 2.0 / 3.0).abs() < 1e-4);
/// ```
pub fn encode_normal(n: [f64; 3]) -> PackedNormal {
    let m = n.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    if m == 0.0 || n.iter().any(|x| !x.is_finite()) {
        return PackedNormal::ZERO;
    }
    let a = n.map(|x| x.abs() / m);
    let l1 = a[0] + a[1] + a[2];
    let (x, y) = if n[2] >= 0.0 {
        (a[0] / l1, a[1] / l1)
    } else {
        ((a[0] + a[2]) / l1, (a[1] + a[2]) / l1)
    };
    let q = |t: f64| (t * 32767.0).round().min(32767.0) as i16;
    let (u, v) = (q(x), q(y));
    PackedNormal::from_bits(
        if n[0] < 0.0 { -u } else { u },
        if n[1] < 0.0 { -v } else { v },
    )
}

/// The unit direction a packed normal names, in `f64` (the zero vector for
/// [`PackedNormal::ZERO`]): what the kernel transforms and normalises.
///
/// ```
/// use fixshade::mesh::PackedNormal;
/// use fixshade_host::mesh_convert::decode_normal;
/// assert_eq!(decode_normal(PackedNormal::Y), [0.0, 1.0, 0.0]);
/// assert_eq!(decode_normal(PackedNormal::ZERO), [0.0; 3]);
/// ```
pub fn decode_normal(p: PackedNormal) -> [f64; 3] {
    let o = p.octahedron().map(f64::from);
    let len = (o[0] * o[0] + o[1] * o[1] + o[2] * o[2]).sqrt();
    if len == 0.0 {
        return [0.0; 3];
    }
    o.map(|c| c / len)
}

impl MeshData {
    /// Converts a mesh description (module docs): positions quantised,
    /// normals packed (if any), indices checked.
    ///
    /// ```
    /// use fixshade_host::mesh_convert::{ConvertError, MeshData};
    /// use fixshade::mesh::MeshError;
    /// use fixshade_host::scene_desc::MeshDesc;
    /// let tri = MeshDesc { positions: vec![[0.0; 3]; 3], normals: None, indices: vec![[0, 1, 3]] };
    /// let err = MeshError::IndexOutOfRange { triangle: 0, index: 3 };
    /// assert_eq!(MeshData::from_desc(&tri), Err(ConvertError::Mesh(err)));
    /// ```
    pub fn from_desc(d: &MeshDesc) -> Result<MeshData, ConvertError> {
        if d.positions.len() > MAX_VERTICES {
            return Err(ConvertError::TooManyVertices(d.positions.len()));
        }
        for (index, p) in d.positions.iter().enumerate() {
            Vec3::from_f64(*p).map_err(|error| ConvertError::Position { index, error })?;
        }
        if let Some(n) = &d.normals {
            if n.len() != d.positions.len() {
                return Err(ConvertError::NormalCount {
                    positions: d.positions.len(),
                    normals: n.len(),
                });
            }
        }
        let raw = |k: usize| d.positions.iter().map(move |p| p[k] * ONE);
        let axes = [0, 1, 2].map(|k| axis_box(raw(k)));
        let bounds = Bounds::from_bits(axes.map(|a| a.0), axes.map(|a| a.1));
        let positions = d
            .positions
            .iter()
            .map(|p| [0, 1, 2].map(|k| quantise(p[k] * ONE, axes[k].0, axes[k].1)))
            .collect();
        let data = MeshData {
            positions,
            bounds,
            normals: d
                .normals
                .as_ref()
                .map(|ns| ns.iter().map(|n| encode_normal(*n)).collect()),
            indices: d.indices.clone(),
        };
        data.mesh().validate().map_err(ConvertError::Mesh)?;
        Ok(data)
    }

    /// Reads an OBJ file as a scene's `mesh.obj` is read
    /// ([`read_obj_file`]: a regular file of at most
    /// [`MAX_FILE_BYTES`](crate::scene_file::MAX_FILE_BYTES)) and converts it.
    ///
    /// ```
    /// use fixshade_host::mesh_convert::MeshData;
    /// let data = MeshData::from_obj_file("tests/data/tetrahedron.obj").unwrap();
    /// assert_eq!((data.positions.len(), data.indices.len()), (4, 4));
    /// assert!(MeshData::from_obj_file("tests/data/none.obj").is_err());
    /// assert!(MeshData::from_obj_file("/dev/zero").is_err()); // not a regular file
    /// ```
    pub fn from_obj_file(path: impl AsRef<std::path::Path>) -> Result<MeshData, ObjFileError> {
        let desc = read_obj_file(path.as_ref()).map_err(ObjFileError::Obj)?;
        MeshData::from_desc(&desc).map_err(ObjFileError::Convert)
    }

    /// A copy of a borrowed mesh.
    ///
    /// ```
    /// use fixshade::mesh::{Bounds, Mesh};
    /// use fixshade_host::mesh_convert::MeshData;
    /// let p = [[1, 2, 3], [4, 5, 6], [7, 8, 9]];
    /// let data = MeshData::from_mesh(&Mesh::new(&p, Bounds::UNIT, &[[0, 1, 2]]));
    /// assert_eq!(data.positions, p);
    /// ```
    pub fn from_mesh(m: &Mesh) -> MeshData {
        MeshData {
            positions: m.positions.to_vec(),
            bounds: m.bounds,
            normals: m.normals.map(<[PackedNormal]>::to_vec),
            indices: m.indices().to_vec(),
        }
    }

    /// The mesh, borrowed.
    ///
    /// ```
    /// use fixshade_host::generate::plane;
    /// use fixshade_host::mesh_convert::MeshData;
    /// let data = MeshData::from_desc(&plane(2.0, 4)).unwrap();
    /// assert_eq!(data.mesh().indices().len(), 32);
    /// ```
    pub fn mesh(&self) -> Mesh<'_> {
        let m = Mesh::new(&self.positions, self.bounds, &self.indices);
        match &self.normals {
            Some(n) => m.with_normals(n),
            None => m,
        }
    }

    /// Gives a mesh without normals the kernel's vertex normals
    /// ([`vertex_normals`], from the quantised positions); a mesh with
    /// normals keeps them.
    ///
    /// ```
    /// use fixshade_host::generate::sphere;
    /// use fixshade_host::mesh_convert::MeshData;
    /// let mut s = sphere(12, 6, 1.0);
    /// s.normals = None;
    /// let mut data = MeshData::from_desc(&s).unwrap();
    /// data.derive_normals().unwrap();
    /// assert_eq!(data.normals.as_ref().map(Vec::len), Some(s.positions.len()));
    /// ```
    pub fn derive_normals(&mut self) -> Result<(), MeshError> {
        if self.normals.is_none() {
            let n = self.positions.len();
            let (mut sums, mut out) = (vec![[0i32; 3]; n], vec![PackedNormal::ZERO; n]);
            vertex_normals(&self.mesh(), &mut sums, &mut out)?;
            self.normals = Some(out);
        }
        Ok(())
    }

    /// The mesh the kernel draws, in `f64`: positions dequantised exactly
    /// ([`Bounds::position_f64`]), normals decoded ([`decode_normal`]),
    /// for the f64 reference.
    ///
    /// ```
    /// use fixshade_host::generate::torus;
    /// use fixshade_host::mesh_convert::MeshData;
    /// let d = torus(1.0, 0.25, 16, 8);
    /// let back = MeshData::from_desc(&d).unwrap().to_desc();
    /// assert_eq!(back.indices, d.indices);
    /// let n = (back.normals.unwrap()[5], d.normals.unwrap()[5]);
    /// assert!((0..3).all(|k| (n.0[k] - n.1[k]).abs() < 1e-4));
    /// ```
    pub fn to_desc(&self) -> MeshDesc {
        MeshDesc {
            positions: self
                .positions
                .iter()
                .map(|q| self.bounds.position_f64(*q))
                .collect(),
            normals: self
                .normals
                .as_ref()
                .map(|ns| ns.iter().map(|n| decode_normal(*n)).collect()),
            indices: self.indices.clone(),
        }
    }

    /// The byte layout of [`Mesh::from_bytes`], for `include_bytes!`.
    ///
    /// ```
    /// use fixshade_host::generate::cube;
    /// use fixshade_host::mesh_convert::MeshData;
    /// let bytes = MeshData::from_desc(&cube(1.0)).unwrap().to_bytes();
    /// assert_eq!(&bytes[..4], b"FXSM");
    /// assert_eq!(bytes.len(), 40 + 24 * (6 + 4) + 12 * 6);
    /// ```
    pub fn to_bytes(&self) -> Vec<u8> {
        let n = self.positions.len();
        let flags = if self.normals.is_some() {
            FLAG_NORMALS
        } else {
            0
        };
        let mut b = Vec::with_capacity(40 + 10 * n + 6 * self.indices.len());
        b.extend_from_slice(&MAGIC);
        b.extend_from_slice(&VERSION.to_le_bytes());
        b.extend_from_slice(&flags.to_le_bytes());
        // Counts past `u32` saturate: the loader refuses such bytes anyway
        // (more than 65 536 vertices, or fewer bytes than the count needs).
        let n32 = u32::try_from(n).unwrap_or(u32::MAX);
        b.extend_from_slice(&n32.to_le_bytes());
        let t = u32::try_from(self.indices.len()).unwrap_or(u32::MAX);
        b.extend_from_slice(&t.to_le_bytes());
        for o in self.bounds.offset {
            b.extend_from_slice(&o.to_le_bytes());
        }
        for s in self.bounds.scale {
            b.extend_from_slice(&s.to_le_bytes());
        }
        for p in &self.positions {
            p.iter().for_each(|c| b.extend_from_slice(&c.to_le_bytes()));
        }
        for n in self.normals.iter().flatten() {
            n.to_bits()
                .iter()
                .for_each(|c| b.extend_from_slice(&c.to_le_bytes()));
        }
        for t in &self.indices {
            t.iter().for_each(|c| b.extend_from_slice(&c.to_le_bytes()));
        }
        b
    }

    /// Rust source: `static`s `{NAME}_POSITIONS`, `{NAME}_NORMALS` (if
    /// any), `{NAME}_INDICES`, and `{NAME}`, the [`Mesh`] over them, all
    /// with absolute paths (`::fixshade::mesh::…`), for `include!`. `name`
    /// is upper-cased, every character but ASCII letters, digits and `_`
    /// becomes `_`, and a leading digit gets a `_` before it.
    ///
    /// ```
    /// use fixshade_host::mesh_convert::MeshData;
    /// use fixshade_host::scene_desc::MeshDesc;
    /// let tri = MeshDesc { positions: vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], normals: None,
    ///     indices: vec![[0, 1, 2]] };
    /// let src = MeshData::from_desc(&tri).unwrap().to_rust("my tri");
    /// assert!(src.contains("pub static MY_TRI_POSITIONS: [[i16; 3]; 3] = ["));
    /// assert!(src.contains("pub static MY_TRI: ::fixshade::mesh::Mesh<'static> ="));
    /// ```
    pub fn to_rust(&self, name: &str) -> String {
        let mut up: String = name
            .chars()
            .map(|c| {
                if c.is_ascii_alphanumeric() {
                    c.to_ascii_uppercase()
                } else {
                    '_'
                }
            })
            .collect();
        if up.is_empty() || up.starts_with(|c: char| c.is_ascii_digit()) {
            up.insert(0, '_');
        }
        let (n, t) = (self.positions.len(), self.indices.len());
        let mut out = String::new();
        let _ = writeln!(
            out,
            "// Written by fixshade's mesh converter (fixshade_host::mesh_convert): {n} vertices, {t} triangles."
        );
        let _ = writeln!(
            out,
            "\n/// `{up}`'s positions, `Q.15` fractions of its box.\npub static {up}_POSITIONS: [[i16; 3]; {n}] = ["
        );
        for p in &self.positions {
            let _ = writeln!(out, "    [{}, {}, {}],", p[0], p[1], p[2]);
        }
        out.push_str("];\n");
        if let Some(normals) = &self.normals {
            let _ = writeln!(
                out,
                "\n/// `{up}`'s normals, octahedral.\npub static {up}_NORMALS: [::fixshade::mesh::PackedNormal; {n}] = ["
            );
            for v in normals {
                let [a, b] = v.to_bits();
                let _ = writeln!(
                    out,
                    "    ::fixshade::mesh::PackedNormal::from_bits({a}, {b}),"
                );
            }
            out.push_str("];\n");
        }
        let _ = writeln!(
            out,
            "\n/// `{up}`'s triangles.\npub static {up}_INDICES: [[u16; 3]; {t}] = ["
        );
        for i in &self.indices {
            let _ = writeln!(out, "    [{}, {}, {}],", i[0], i[1], i[2]);
        }
        out.push_str("];\n");
        let normals = if self.normals.is_some() {
            format!("\n.with_normals(&{up}_NORMALS)")
        } else {
            String::new()
        };
        let _ = writeln!(
            out,
            "\n/// `{up}`, in its box (offset `I8F24`, scale `U8F24`, raw).\npub static {up}: ::fixshade::mesh::Mesh<'static> = ::fixshade::mesh::Mesh::new(\n    &{up}_POSITIONS,\n    ::fixshade::mesh::Bounds::from_bits({:?}, {:?}),\n    &{up}_INDICES,\n){normals};",
            self.bounds.offset, self.bounds.scale,
        );
        out
    }
}
