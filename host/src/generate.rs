//! Mesh generators and a small Wavefront OBJ reader, producing [`MeshDesc`]s
//! in object space.
//!
//! Every generated mesh has unit normals and counter-clockwise front faces
//! seen from outside (or, for [`plane`], from +Z), matching SPEC.md's
//! "front faces are counter-clockwise in NDC".
//!
//! Segment counts are clamped to a sensible range (documented per function)
//! so that no generator panics or overflows its `u32` indices.
//!
//! ```
//! use fixshade_host::generate::{cube, sphere};
//! assert_eq!(cube(2.0).indices.len(), 12);
//! assert_eq!(sphere(48, 24, 1.0).indices.len(), 48 * (2 * 24 - 2));
//! ```

use crate::scene_desc::{MeshDesc, MAX_VERTICES};
use std::collections::HashMap;
use std::f64::consts::PI;
use std::fmt;
use std::io::BufRead;

/// Largest segment count accepted by the generators; larger values are clamped.
///
/// ```
/// use fixshade_host::generate::{sphere, torus, MAX_SEGMENTS};
/// let s = sphere(MAX_SEGMENTS + 100, 2, 1.0); // lon clamped to MAX_SEGMENTS
/// assert_eq!(s.positions.len(), 3 * (MAX_SEGMENTS as usize + 1));
/// assert_eq!(s.indices.len(), MAX_SEGMENTS as usize * 2);
/// let t = torus(1.0, 0.25, u32::MAX, 3); // no u32 overflow either
/// assert_eq!(t.indices.len(), 2 * MAX_SEGMENTS as usize * 3);
/// ```
pub const MAX_SEGMENTS: u32 = 4096;

/// The most segments a [`plane`] side may have: `(n + 1)²` vertices must
/// stay within [`MAX_VERTICES`].
///
/// ```
/// use fixshade_host::generate::{plane, MAX_PLANE_SEGMENTS};
/// use fixshade_host::scene_desc::MAX_VERTICES;
/// assert_eq!(plane(1.0, MAX_PLANE_SEGMENTS).positions.len(), MAX_VERTICES);
/// assert_eq!(plane(1.0, 1000).positions.len(), MAX_VERTICES); // clamped
/// ```
pub const MAX_PLANE_SEGMENTS: u32 = 255;

/// The second side of a `(a + 1) × (b + 1)` vertex grid, lowered so that the
/// grid holds at most [`MAX_VERTICES`] vertices (with `a ≤ MAX_SEGMENTS`,
/// at least 14 remain: `65536 / 4097 − 1`).
///
/// ```
/// use fixshade_host::generate::{fit_grid, MAX_SEGMENTS};
/// assert_eq!(fit_grid(64, 32), 32);
/// assert_eq!(fit_grid(255, 1000), 255); // 256 × 256 = 65536
/// assert_eq!(fit_grid(MAX_SEGMENTS, MAX_SEGMENTS), 14);
/// ```
pub const fn fit_grid(a: u32, b: u32) -> u32 {
    let most = (MAX_VERTICES as u32 / a.saturating_add(1)).saturating_sub(1);
    if b < most {
        b
    } else {
        most
    }
}

/// A UV sphere of the given radius centred on the origin.
///
/// `lon` segments around the Y axis (clamped to `3..=`[`MAX_SEGMENTS`]) and
/// `lat` segments from the +Y pole to the −Y pole (clamped to
/// `2..=`[`MAX_SEGMENTS`], then lowered by [`fit_grid`] to at most
/// [`MAX_VERTICES`] vertices). Vertices form a `(lat + 1) × (lon + 1)` grid (the
/// seam column and the pole vertices are duplicated); the degenerate triangles
/// touching the poles are skipped, leaving `lon · (2·lat − 2)` triangles.
/// Normals are the unit directions from the centre (`position / radius` for a
/// positive radius). The point at longitude 0 on the equator is `(0, 0, r)`.
///
/// ```
/// let s = fixshade_host::generate::sphere(8, 4, 2.0);
/// assert_eq!(s.positions.len(), 9 * 5);
/// assert_eq!(s.indices.len(), 8 * 6);
/// ```
pub fn sphere(lon: u32, lat: u32, radius: f64) -> MeshDesc {
    let lon = lon.clamp(3, MAX_SEGMENTS);
    let lat = fit_grid(lon, lat.clamp(2, MAX_SEGMENTS));
    let cols = lon + 1;
    let mut positions = Vec::with_capacity(((lat + 1) * cols) as usize);
    let mut normals = Vec::with_capacity(positions.capacity());
    for j in 0..=lat {
        let theta = PI * f64::from(j) / f64::from(lat);
        let (st, ct) = theta.sin_cos();
        for i in 0..=lon {
            let phi = 2.0 * PI * f64::from(i) / f64::from(lon);
            let (sp, cp) = phi.sin_cos();
            let n = [st * sp, ct, st * cp];
            normals.push(n);
            positions.push([radius * n[0], radius * n[1], radius * n[2]]);
        }
    }
    // (lat + 1)·cols ≤ MAX_VERTICES (fit_grid): every index fits u16.
    let at = |j: u32, i: u32| (j * cols + i) as u16;
    let mut indices = Vec::with_capacity((lon * (2 * lat - 2)) as usize);
    for j in 0..lat {
        for i in 0..lon {
            let (tl, tr) = (at(j, i), at(j, i + 1));
            let (bl, br) = (at(j + 1, i), at(j + 1, i + 1));
            if j + 1 < lat {
                indices.push([tl, bl, br]);
            }
            if j > 0 {
                indices.push([tl, br, tr]);
            }
        }
    }
    MeshDesc {
        positions,
        normals: Some(normals),
        indices,
    }
}

/// An axis-aligned cube of edge length `size` centred on the origin: 24
/// vertices (4 per face, each with its face normal) and 12 triangles.
///
/// ```
/// let c = fixshade_host::generate::cube(1.0);
/// assert_eq!((c.positions.len(), c.indices.len()), (24, 12));
/// ```
pub fn cube(size: f64) -> MeshDesc {
    let h = size / 2.0;
    // (normal, u, v) with u × v = normal, so the corners -u-v, +u-v, +u+v, -u+v
    // run counter-clockwise seen from outside.
    let faces: [([f64; 3], [f64; 3], [f64; 3]); 6] = [
        ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]),
        ([-1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0]),
        ([0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]),
        ([0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]),
        ([0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
        ([0.0, 0.0, -1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]),
    ];
    let mut positions = Vec::with_capacity(24);
    let mut normals = Vec::with_capacity(24);
    let mut indices = Vec::with_capacity(12);
    for (n, u, v) in faces {
        let base = positions.len() as u16; // below 24
        for (su, sv) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
            positions.push([
                h * (n[0] + su * u[0] + sv * v[0]),
                h * (n[1] + su * u[1] + sv * v[1]),
                h * (n[2] + su * u[2] + sv * v[2]),
            ]);
            normals.push(n);
        }
        indices.push([base, base + 1, base + 2]);
        indices.push([base, base + 2, base + 3]);
    }
    MeshDesc {
        positions,
        normals: Some(normals),
        indices,
    }
}

/// A torus around the Z axis (the ring lies in the XY plane, so a camera on
/// +Z sees the hole), ring radius `big_r`, tube radius `small_r`.
///
/// `u` segments around the ring and `v` around the tube, each clamped to
/// `3..=`[`MAX_SEGMENTS`] (`v` then lowered by [`fit_grid`] to at most
/// [`MAX_VERTICES`] vertices); `(u + 1) · (v + 1)` vertices (seams duplicated),
/// `2 · u · v` triangles. Normals point away from the tube's centre line.
///
/// ```
/// let t = fixshade_host::generate::torus(1.0, 0.25, 16, 8);
/// assert_eq!(t.indices.len(), 2 * 16 * 8);
/// ```
pub fn torus(big_r: f64, small_r: f64, u: u32, v: u32) -> MeshDesc {
    let u = u.clamp(3, MAX_SEGMENTS);
    let v = fit_grid(u, v.clamp(3, MAX_SEGMENTS));
    let cols = v + 1;
    let mut positions = Vec::with_capacity(((u + 1) * cols) as usize);
    let mut normals = Vec::with_capacity(positions.capacity());
    for i in 0..=u {
        let phi = 2.0 * PI * f64::from(i) / f64::from(u);
        let (sp, cp) = phi.sin_cos();
        for j in 0..=v {
            let theta = 2.0 * PI * f64::from(j) / f64::from(v);
            let (st, ct) = theta.sin_cos();
            let n = [ct * cp, ct * sp, st];
            normals.push(n);
            positions.push([
                big_r * cp + small_r * n[0],
                big_r * sp + small_r * n[1],
                small_r * n[2],
            ]);
        }
    }
    // (u + 1)·cols ≤ MAX_VERTICES (fit_grid): every index fits u16.
    let at = |i: u32, j: u32| (i * cols + j) as u16;
    let mut indices = Vec::with_capacity((2 * u * v) as usize);
    for i in 0..u {
        for j in 0..v {
            indices.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            indices.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    MeshDesc {
        positions,
        normals: Some(normals),
        indices,
    }
}

/// A square of side `size` in the XY plane, centred on the origin, facing +Z
/// (normal `(0, 0, 1)`), split into `segments × segments` quads (clamped to
/// `1..=`[`MAX_SEGMENTS`]), two triangles each.
///
/// ```
/// let p = fixshade_host::generate::plane(2.0, 4);
/// assert_eq!((p.positions.len(), p.indices.len()), (25, 32));
/// ```
pub fn plane(size: f64, segments: u32) -> MeshDesc {
    let n = segments.clamp(1, MAX_PLANE_SEGMENTS);
    let cols = n + 1;
    let mut positions = Vec::with_capacity((cols * cols) as usize);
    for j in 0..=n {
        let y = size * (f64::from(j) / f64::from(n) - 0.5);
        for i in 0..=n {
            let x = size * (f64::from(i) / f64::from(n) - 0.5);
            positions.push([x, y, 0.0]);
        }
    }
    let normals = vec![[0.0, 0.0, 1.0]; positions.len()];
    // cols² ≤ 256² = MAX_VERTICES: every index fits u16.
    let at = |i: u32, j: u32| (j * cols + i) as u16;
    let mut indices = Vec::with_capacity((2 * n * n) as usize);
    for j in 0..n {
        for i in 0..n {
            indices.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            indices.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    MeshDesc {
        positions,
        normals: Some(normals),
        indices,
    }
}

/// Why [`load_obj`] failed, with the 1-based line number.
///
/// ```
/// let err = fixshade_host::generate::load_obj("v 0 0 0\nf 1 2 3\n").unwrap_err();
/// assert_eq!(err.line, 2);
/// assert!(err.to_string().starts_with("line 2:"));
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ObjError {
    /// 1-based line number.
    pub line: usize,
    /// What went wrong.
    pub kind: ObjErrorKind,
}

/// The kinds of [`ObjError`].
///
/// ```
/// use fixshade_host::generate::{load_obj, ObjErrorKind};
/// let kind = |text| load_obj(text).unwrap_err().kind;
/// assert_eq!(kind("v 0 0\n"), ObjErrorKind::MissingCoordinate);
/// assert_eq!(kind("v 0 0 nan\n"), ObjErrorKind::BadNumber("nan".into()));
/// assert_eq!(kind("v 0 0 0\nf 1 1\n"), ObjErrorKind::TooFewFaceVertices(2));
/// assert_eq!(kind("v 0 0 0\nf 1 1 0\n"), ObjErrorKind::ZeroIndex);
/// let out = ObjErrorKind::IndexOutOfRange { what: "position", index: 4, count: 1 };
/// assert_eq!(kind("v 0 0 0\nf 1 1 4\n"), out);
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ObjErrorKind {
    /// A `v` or `vn` line without three numbers.
    MissingCoordinate,
    /// A token that should be a finite number is not.
    BadNumber(String),
    /// A face vertex that is not `i`, `i/j`, `i//k` or `i/j/k` with integers.
    BadFaceVertex(String),
    /// A face with fewer than three vertices.
    TooFewFaceVertices(usize),
    /// Index 0 (OBJ indices are 1-based).
    ZeroIndex,
    /// A position or normal index referring to no element.
    IndexOutOfRange {
        /// `"position"` or `"normal"`.
        what: &'static str,
        /// The index as written.
        index: i64,
        /// How many such elements exist.
        count: usize,
    },
    /// More than [`MAX_VERTICES`] positions, normals or resulting
    /// vertices.
    TooManyVertices,
    /// A line longer than [`MAX_OBJ_LINE`] bytes.
    LineTooLong,
    /// A line that is not UTF-8.
    NotUtf8,
    /// The text could not be read (the operating system's message).
    Read(String),
}

impl fmt::Display for ObjError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        // A read error is the file's, not a line's.
        if !matches!(self.kind, ObjErrorKind::Read(_)) {
            write!(f, "line {}: ", self.line)?;
        }
        match &self.kind {
            ObjErrorKind::MissingCoordinate => write!(f, "expected three coordinates"),
            ObjErrorKind::BadNumber(t) => write!(f, "`{t}` is not a finite number"),
            ObjErrorKind::BadFaceVertex(t) => write!(f, "bad face vertex `{t}`"),
            ObjErrorKind::TooFewFaceVertices(n) => {
                write!(f, "a face needs at least 3 vertices, found {n}")
            }
            ObjErrorKind::ZeroIndex => write!(f, "index 0 (OBJ indices start at 1)"),
            ObjErrorKind::IndexOutOfRange { what, index, count } => {
                write!(f, "{what} index {index} out of range ({count} defined)")
            }
            ObjErrorKind::TooManyVertices => write!(f, "more than {MAX_VERTICES} vertices"),
            ObjErrorKind::LineTooLong => write!(f, "longer than {MAX_OBJ_LINE} bytes"),
            ObjErrorKind::NotUtf8 => write!(f, "not UTF-8 text"),
            ObjErrorKind::Read(m) => write!(f, "cannot read: {m}"),
        }
    }
}

impl std::error::Error for ObjError {}

/// One face vertex as written: position and optional normal index, both
/// resolved to 0-based and checked against the elements defined so far.
#[derive(Clone, Copy)]
struct FaceVertex {
    pos: u16,
    normal: Option<u16>,
}

/// The longest line an OBJ file may have, in bytes (a longer one is an
/// error, found before it is kept whole).
pub const MAX_OBJ_LINE: usize = 64 * 1024;

/// Parses a Wavefront OBJ text: `v`, `vn` and `f` lines; every other
/// statement (`vt`, `o`, `g`, `s`, `usemtl`, comments…) is ignored.
///
/// Face vertices may be `i`, `i/j`, `i//k` or `i/j/k`; an index refers to an
/// element defined before the face, and a negative one counts back from
/// the last of them. Faces with more than three vertices are fanned from
/// their first vertex. If every face vertex has a normal, vertices are
/// re-indexed so that each distinct (position, normal) pair becomes one
/// vertex and `normals` is `Some` (normals as written, not renormalised);
/// otherwise `normals` is `None` and positions keep the file's order.
/// Texture indices are parsed but unused. At most
/// [`MAX_VERTICES`] positions, normals and resulting vertices; lines of at
/// most [`MAX_OBJ_LINE`] bytes.
///
/// ```
/// let m = fixshade_host::generate::load_obj(
///     "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n",
/// ).unwrap();
/// assert_eq!(m.indices, vec![[0, 1, 2], [0, 2, 3]]);
/// assert!(m.normals.is_none());
/// ```
pub fn load_obj(text: &str) -> Result<MeshDesc, ObjError> {
    read_obj(|| Ok(text.as_bytes()))
}

/// As [`load_obj`], reading the text from `open()` twice: once to count the
/// elements, once to read them into vectors of exactly that size. The mesh
/// then takes at most 6 bytes per triangle (as few as 2 bytes of text: a
/// fanned face vertex `1 `) and 24 per position and normal (at least 8
/// bytes of text each), plus, for re-indexed normals, at most
/// [`MAX_VERTICES`] entries of a map and two vectors: below 3 bytes of
/// memory per byte of text, plus 6 MiB.
///
/// ```
/// let obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
/// let m = fixshade_host::generate::read_obj(|| Ok(obj.as_bytes())).unwrap();
/// assert_eq!((m.positions.len(), m.indices.len()), (3, 1));
/// ```
pub fn read_obj<R: BufRead>(
    mut open: impl FnMut() -> std::io::Result<R>,
) -> Result<MeshDesc, ObjError> {
    let io = |line, e: std::io::Error| ObjError {
        line,
        kind: ObjErrorKind::Read(e.to_string()),
    };
    // Pass 1: counts only (errors are found, with their lines, in pass 2).
    let (mut n_pos, mut n_nrm, mut n_tri) = (0usize, 0usize, 0usize);
    // Whether every face vertex names a normal (`i//k`, `i/j/k`).
    let mut all_normals = true;
    let mut buf = Vec::new();
    let mut input = open().map_err(|e| io(0, e))?;
    let mut line = 0;
    while let Some(text) = next_line(&mut input, &mut buf, &mut line)? {
        let mut tokens = text.split('#').next().unwrap_or("").split_whitespace();
        match tokens.next() {
            Some("v") => n_pos += 1,
            Some("vn") => n_nrm += 1,
            Some("f") => {
                let mut n = 0usize;
                for t in tokens {
                    n += 1;
                    all_normals &= t.split('/').nth(2).is_some_and(|k| !k.is_empty());
                }
                n_tri += n.saturating_sub(2);
            }
            _ => {}
        }
    }
    let mut positions: Vec<[f64; 3]> = Vec::with_capacity(n_pos.min(MAX_VERTICES));
    let mut normals: Vec<[f64; 3]> = Vec::with_capacity(n_nrm.min(MAX_VERTICES));
    // Where every face vertex names a normal (the first pass saw), each
    // distinct (position, normal) pair becomes one vertex, numbered in order
    // of first use; otherwise triangles keep the position indices.
    let reindex = all_normals && n_tri > 0;
    let mut map: HashMap<(u16, u16), u16> = HashMap::new();
    let (mut out_pos, mut out_nrm) = (Vec::new(), Vec::new());
    let mut tris: Vec<[u16; 3]> = Vec::with_capacity(n_tri);
    let mut verts: Vec<FaceVertex> = Vec::new();
    let mut input = open().map_err(|e| io(0, e))?;
    let mut line = 0;
    while let Some(text) = next_line(&mut input, &mut buf, &mut line)? {
        let err = |kind| ObjError { line, kind };
        let mut tokens = text.split('#').next().unwrap_or("").split_whitespace();
        match tokens.next() {
            Some("v") => {
                if positions.len() == MAX_VERTICES {
                    return Err(err(ObjErrorKind::TooManyVertices));
                }
                positions.push(parse_xyz(&mut tokens).map_err(err)?);
            }
            Some("vn") => {
                if normals.len() == MAX_VERTICES {
                    return Err(err(ObjErrorKind::TooManyVertices));
                }
                normals.push(parse_xyz(&mut tokens).map_err(err)?);
            }
            Some("f") => {
                verts.clear();
                for t in tokens {
                    verts.push(parse_face_vertex(t, positions.len(), normals.len()).map_err(err)?);
                }
                if verts.len() < 3 {
                    return Err(err(ObjErrorKind::TooFewFaceVertices(verts.len())));
                }
                let mut index = |v: FaceVertex| -> Result<u16, ObjError> {
                    let Some(n) = v.normal.filter(|_| reindex) else {
                        return Ok(v.pos);
                    };
                    if let Some(&i) = map.get(&(v.pos, n)) {
                        return Ok(i);
                    }
                    let i = u16::try_from(out_pos.len())
                        .map_err(|_| err(ObjErrorKind::TooManyVertices))?;
                    out_pos.push(positions[v.pos as usize]);
                    out_nrm.push(normals[n as usize]);
                    map.insert((v.pos, n), i);
                    Ok(i)
                };
                let first = index(verts[0])?;
                let mut prev = index(verts[1])?;
                for &v in &verts[2..] {
                    let next = index(v)?;
                    tris.push([first, prev, next]);
                    prev = next;
                }
            }
            _ => {}
        }
    }
    if !reindex {
        return Ok(MeshDesc {
            positions,
            normals: None,
            indices: tris,
        });
    }
    Ok(MeshDesc {
        positions: out_pos,
        normals: Some(out_nrm),
        indices: tris,
    })
}

/// The next line of `input` (without its line break) as text, counting
/// lines in `line`; `None` at the end. A line longer than
/// [`MAX_OBJ_LINE`] or not UTF-8 is an error.
fn next_line<'b>(
    input: &mut impl BufRead,
    buf: &'b mut Vec<u8>,
    line: &mut usize,
) -> Result<Option<&'b str>, ObjError> {
    buf.clear();
    *line += 1;
    let err = |kind| ObjError { line: *line, kind };
    loop {
        let chunk = input
            .fill_buf()
            .map_err(|e| err(ObjErrorKind::Read(e.to_string())))?;
        if chunk.is_empty() {
            if buf.is_empty() {
                return Ok(None);
            }
            break;
        }
        let (take, done) = match chunk.iter().position(|&b| b == b'\n') {
            Some(i) => (i + 1, true),
            None => (chunk.len(), false),
        };
        if buf.len() + take > MAX_OBJ_LINE + 1 {
            return Err(err(ObjErrorKind::LineTooLong));
        }
        buf.extend_from_slice(&chunk[..take]);
        input.consume(take);
        if done {
            break;
        }
    }
    while buf.last().is_some_and(|&b| b == b'\n' || b == b'\r') {
        buf.pop();
    }
    std::str::from_utf8(buf)
        .map(Some)
        .map_err(|_| err(ObjErrorKind::NotUtf8))
}

fn parse_xyz<'a>(tokens: &mut impl Iterator<Item = &'a str>) -> Result<[f64; 3], ObjErrorKind> {
    let mut v = [0.0; 3];
    for slot in &mut v {
        let t = tokens.next().ok_or(ObjErrorKind::MissingCoordinate)?;
        let x: f64 = t
            .parse()
            .map_err(|_| ObjErrorKind::BadNumber(t.to_string()))?;
        if !x.is_finite() {
            return Err(ObjErrorKind::BadNumber(t.to_string()));
        }
        *slot = x;
    }
    Ok(v)
}

/// Resolves a 1-based (or negative, relative) OBJ index to 0-based,
/// checked against the `count ≤ MAX_VERTICES` elements defined so far (so
/// it fits `u16`).
fn resolve(index: i64, count: usize) -> Result<u16, ObjErrorKind> {
    let out = || ObjErrorKind::IndexOutOfRange {
        what: "relative",
        index,
        count,
    };
    let r = match index {
        0 => return Err(ObjErrorKind::ZeroIndex),
        i if i > 0 => i - 1,
        // |i| ≤ i64::MAX here (i > i64::MIN would not matter: count is small).
        i => (count as i64).checked_add(i).ok_or_else(out)?,
    };
    if r < 0 || r as u64 >= count as u64 {
        return Err(out());
    }
    Ok(r as u16)
}

fn parse_face_vertex(t: &str, n_pos: usize, n_nrm: usize) -> Result<FaceVertex, ObjErrorKind> {
    let bad = || ObjErrorKind::BadFaceVertex(t.to_string());
    let mut parts = t.split('/');
    let pos_text = parts.next().ok_or_else(bad)?;
    let tex_text = parts.next();
    let nrm_text = parts.next();
    if parts.next().is_some() {
        return Err(bad());
    }
    let pos: i64 = pos_text.parse().map_err(|_| bad())?;
    if let Some(tx) = tex_text {
        if !tx.is_empty() {
            tx.parse::<i64>().map_err(|_| bad())?;
        } else if nrm_text.is_none() {
            // "i/" is not a valid form.
            return Err(bad());
        }
    }
    let normal = match nrm_text {
        Some(nt) => {
            let k: i64 = nt.parse().map_err(|_| bad())?;
            Some(resolve(k, n_nrm).map_err(|e| relabel(e, "normal", k, n_nrm))?)
        }
        None => None,
    };
    let pos = resolve(pos, n_pos).map_err(|e| relabel(e, "position", pos, n_pos))?;
    Ok(FaceVertex { pos, normal })
}

fn relabel(e: ObjErrorKind, what: &'static str, index: i64, count: usize) -> ObjErrorKind {
    match e {
        ObjErrorKind::IndexOutOfRange { .. } => {
            ObjErrorKind::IndexOutOfRange { what, index, count }
        }
        other => other,
    }
}
