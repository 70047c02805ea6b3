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
//! use fixshade::generate::{cube, sphere};
//! assert_eq!(cube(2.0).indices.len(), 12);
//! assert_eq!(sphere(48, 24, 1.0).indices.len(), 48 * (2 * 24 - 2));
//! ```

use crate::scene_desc::MeshDesc;
use std::collections::HashMap;
use std::f64::consts::PI;
use std::fmt;

/// Largest segment count accepted by the generators; larger values are clamped.
///
/// ```
/// use fixshade::generate::{sphere, torus, MAX_SEGMENTS};
/// let s = sphere(MAX_SEGMENTS + 100, 2, 1.0); // lon clamped to MAX_SEGMENTS
/// assert_eq!(s.positions.len(), 3 * (MAX_SEGMENTS as usize + 1));
/// assert_eq!(s.indices.len(), MAX_SEGMENTS as usize * 2);
/// let t = torus(1.0, 0.25, u32::MAX, 3); // no u32 overflow either
/// assert_eq!(t.indices.len(), 2 * MAX_SEGMENTS as usize * 3);
/// ```
pub const MAX_SEGMENTS: u32 = 4096;

/// A UV sphere of the given radius centred on the origin.
///
/// `lon` segments around the Y axis (clamped to `3..=`[`MAX_SEGMENTS`]) and
/// `lat` segments from the +Y pole to the −Y pole (clamped to
/// `2..=`[`MAX_SEGMENTS`]). Vertices form a `(lat + 1) × (lon + 1)` grid (the
/// seam column and the pole vertices are duplicated); the degenerate triangles
/// touching the poles are skipped, leaving `lon · (2·lat − 2)` triangles.
/// Normals are the unit directions from the centre (`position / radius` for a
/// positive radius). The point at longitude 0 on the equator is `(0, 0, r)`.
///
/// ```
/// let s = fixshade::generate::sphere(8, 4, 2.0);
/// assert_eq!(s.positions.len(), 9 * 5);
/// assert_eq!(s.indices.len(), 8 * 6);
/// ```
pub fn sphere(lon: u32, lat: u32, radius: f64) -> MeshDesc {
    let lon = lon.clamp(3, MAX_SEGMENTS);
    let lat = lat.clamp(2, MAX_SEGMENTS);
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
    let at = |j: u32, i: u32| j * cols + i;
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
/// let c = fixshade::generate::cube(1.0);
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
        let base = positions.len() as u32;
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
/// `3..=`[`MAX_SEGMENTS`]; `(u + 1) · (v + 1)` vertices (seams duplicated),
/// `2 · u · v` triangles. Normals point away from the tube's centre line.
///
/// ```
/// let t = fixshade::generate::torus(1.0, 0.25, 16, 8);
/// assert_eq!(t.indices.len(), 2 * 16 * 8);
/// ```
pub fn torus(big_r: f64, small_r: f64, u: u32, v: u32) -> MeshDesc {
    let u = u.clamp(3, MAX_SEGMENTS);
    let v = v.clamp(3, MAX_SEGMENTS);
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
    let at = |i: u32, j: u32| i * cols + j;
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
/// let p = fixshade::generate::plane(2.0, 4);
/// assert_eq!((p.positions.len(), p.indices.len()), (25, 32));
/// ```
pub fn plane(size: f64, segments: u32) -> MeshDesc {
    let n = segments.clamp(1, MAX_SEGMENTS);
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
    let at = |i: u32, j: u32| j * cols + i;
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
/// let err = fixshade::generate::load_obj("v 0 0 0\nf 1 2 3\n").unwrap_err();
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
/// use fixshade::generate::{load_obj, ObjErrorKind};
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
    /// More vertices than `u32` indices can address.
    TooManyVertices,
}

impl fmt::Display for ObjError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "line {}: ", self.line)?;
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
            ObjErrorKind::TooManyVertices => write!(f, "too many vertices for u32 indices"),
        }
    }
}

impl std::error::Error for ObjError {}

/// One face vertex as written: position and optional normal index, both
/// already resolved to 0-based (unchecked for positive indices).
#[derive(Clone, Copy)]
struct FaceVertex {
    pos: i64,
    normal: Option<i64>,
}

/// Parses a Wavefront OBJ text: `v`, `vn` and `f` lines; every other
/// statement (`vt`, `o`, `g`, `s`, `usemtl`, comments…) is ignored.
///
/// Face vertices may be `i`, `i/j`, `i//k` or `i/j/k`; negative indices count
/// back from the last element defined before the face. Faces with more than
/// three vertices are fanned from their first vertex. If every face vertex
/// has a normal, vertices are re-indexed so that each distinct
/// (position, normal) pair becomes one vertex and `normals` is `Some`
/// (normals as written, not renormalised); otherwise `normals` is `None` and
/// positions keep the file's order. Texture indices are parsed but unused.
///
/// ```
/// let m = fixshade::generate::load_obj(
///     "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n",
/// ).unwrap();
/// assert_eq!(m.indices, vec![[0, 1, 2], [0, 2, 3]]);
/// assert!(m.normals.is_none());
/// ```
pub fn load_obj(text: &str) -> Result<MeshDesc, ObjError> {
    let mut positions: Vec<[f64; 3]> = Vec::new();
    let mut normals: Vec<[f64; 3]> = Vec::new();
    // Faces as (line number, fanned triangles).
    let mut faces: Vec<(usize, [FaceVertex; 3])> = Vec::new();

    for (number, raw) in text.lines().enumerate() {
        let line = number + 1;
        let err = |kind| ObjError { line, kind };
        let content = raw.split('#').next().unwrap_or("");
        let mut tokens = content.split_whitespace();
        match tokens.next() {
            Some("v") => positions.push(parse_xyz(&mut tokens).map_err(err)?),
            Some("vn") => normals.push(parse_xyz(&mut tokens).map_err(err)?),
            Some("f") => {
                let mut verts = Vec::new();
                for t in tokens {
                    verts.push(parse_face_vertex(t, positions.len(), normals.len()).map_err(err)?);
                }
                if verts.len() < 3 {
                    return Err(err(ObjErrorKind::TooFewFaceVertices(verts.len())));
                }
                for k in 1..verts.len() - 1 {
                    faces.push((line, [verts[0], verts[k], verts[k + 1]]));
                }
            }
            _ => {}
        }
    }

    // Check every index now that all elements are known.
    for (line, tri) in &faces {
        for fv in tri {
            check_index("position", fv.pos, positions.len(), *line)?;
            if let Some(n) = fv.normal {
                check_index("normal", n, normals.len(), *line)?;
            }
        }
    }
    let too_many = |line| ObjError {
        line,
        kind: ObjErrorKind::TooManyVertices,
    };
    if positions.len() > u32::MAX as usize {
        return Err(too_many(0));
    }

    let all_normals = !faces.is_empty()
        && faces
            .iter()
            .all(|(_, tri)| tri.iter().all(|fv| fv.normal.is_some()));

    if !all_normals {
        let indices = faces
            .iter()
            .map(|(_, tri)| tri.map(|fv| fv.pos as u32))
            .collect();
        return Ok(MeshDesc {
            positions,
            normals: None,
            indices,
        });
    }

    let mut map: HashMap<(i64, i64), u32> = HashMap::new();
    let mut out_pos = Vec::new();
    let mut out_nrm = Vec::new();
    let mut indices = Vec::with_capacity(faces.len());
    for (line, tri) in &faces {
        let mut out = [0u32; 3];
        for (slot, fv) in out.iter_mut().zip(tri) {
            let n = fv.normal.unwrap_or(0);
            let key = (fv.pos, n);
            *slot = match map.get(&key) {
                Some(&i) => i,
                None => {
                    let i = u32::try_from(out_pos.len()).map_err(|_| too_many(*line))?;
                    out_pos.push(positions[fv.pos as usize]);
                    out_nrm.push(normals[n as usize]);
                    map.insert(key, i);
                    i
                }
            };
        }
        indices.push(out);
    }
    Ok(MeshDesc {
        positions: out_pos,
        normals: Some(out_nrm),
        indices,
    })
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

/// Resolves a 1-based (or negative, relative) OBJ index to 0-based.
fn resolve(index: i64, count: usize) -> Result<i64, ObjErrorKind> {
    match index {
        0 => Err(ObjErrorKind::ZeroIndex),
        i if i > 0 => Ok(i - 1),
        i => {
            let r = count as i64 + i;
            if r < 0 {
                Err(ObjErrorKind::IndexOutOfRange {
                    what: "relative",
                    index: i,
                    count,
                })
            } else {
                Ok(r)
            }
        }
    }
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

fn check_index(what: &'static str, i: i64, count: usize, line: usize) -> Result<(), ObjError> {
    if i >= 0 && (i as usize) < count {
        Ok(())
    } else {
        Err(ObjError {
            line,
            kind: ObjErrorKind::IndexOutOfRange {
                what,
                index: i + 1,
                count,
            },
        })
    }
}
