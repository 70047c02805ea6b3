//! Scene files, JSON as `SCENE_FORMAT.md`
//! describes them, read into a [`SceneDesc`].
//!
//! Every key of the format is read and every default applied; a key the
//! format does not list is an error, as are missing required keys, values of
//! the wrong type, numbers too large for an `f64` (JSON has no NaN or
//! infinity, but `1e400` would round to infinity), and OBJ files that cannot
//! be read or parsed. Once the file is read, [`SceneDesc::validate`] checks
//! the ranges (index out of range, cutoff outside [0, 90], …).
//!
//! Every error is one line that names where the problem is: the key path
//! (`lights[1].cutoff_deg: …`), the JSON line and column for a syntax error,
//! or the OBJ file and line.
//!
//! ```
//! use std::path::Path;
//! use fixshade_host::scene_file::parse_scene;
//!
//! let json = r#"{
//!     "width": 64, "height": 48,
//!     "camera": {"eye": [0, 0, 3], "target": [0, 0, 0], "up": [0, 1, 0],
//!                "near": 0.1, "far": 10, "fovy_deg": 60},
//!     "mesh": {"generator": "sphere", "segments": [16, 8], "radius": 1},
//!     "lights": [{"type": "directional", "direction": [1, 1, 1]}]
//! }"#;
//! let scene = parse_scene(json, Path::new(".")).unwrap();
//! assert_eq!((scene.width, scene.height), (64, 48));
//! assert_eq!(scene.global_ambient, [0.2; 3]);
//!
//! let bad = json.replace("\"direction\"", "\"dir\"");
//! let err = parse_scene(&bad, Path::new(".")).unwrap_err();
//! assert!(err.to_string().starts_with("lights[0].dir: unknown key"));
//! ```

use std::fmt;
use std::path::{Path, PathBuf};

use serde::de::DeserializeOwned;
use serde::Deserialize;
use serde_json::{Map, Value};

use crate::generate::{self, ObjError, ObjErrorKind, MAX_PLANE_SEGMENTS, MAX_SEGMENTS};
use crate::scene_desc::{
    CameraDesc, LightDesc, MaterialDesc, MeshDesc, Projection, SceneDesc, SceneError, Shading,
    SpecularModel, Viewer, DEFAULT_ATTENUATION, IDENTITY, MAX_VERTICES, WHITE,
};

/// Why a scene file was rejected. `Display` gives one line naming the key
/// path, the JSON position or the OBJ line.
///
/// ```
/// use std::path::Path;
/// use fixshade_host::scene_file::{parse_scene, SceneFileError};
/// let err = parse_scene("{\"width\": 8,", Path::new(".")).unwrap_err();
/// assert!(matches!(err, SceneFileError::Syntax(_)) && err.key().is_none());
/// assert!(err.to_string().contains("line 1 column 12"), "{err}");
/// let err = parse_scene(r#"{"width": -1}"#, Path::new(".")).unwrap_err();
/// assert_eq!(err.to_string(), "width: expected a non-negative integer, found -1");
/// ```
#[derive(Debug)]
pub enum SceneFileError {
    /// The scene file itself could not be read.
    Read {
        /// The scene file.
        path: PathBuf,
        /// The operating system's message.
        message: String,
    },
    /// The text is not JSON (serde_json's message, with line and column).
    Syntax(String),
    /// A key is unknown, missing, or holds a value of the wrong type.
    Key {
        /// The key path, e.g. `lights[1].cutoff_deg` (empty for the top level).
        key: String,
        /// What is wrong.
        message: String,
    },
    /// The OBJ file named by `mesh.obj` could not be read.
    ObjRead {
        /// The OBJ file, as resolved against the scene file's folder.
        path: PathBuf,
        /// The operating system's message.
        message: String,
    },
    /// The OBJ file named by `mesh.obj` is malformed.
    Obj {
        /// The OBJ file, as resolved against the scene file's folder.
        path: PathBuf,
        /// The parser's error, with its line number.
        error: ObjError,
    },
    /// The file was read but the scene is invalid ([`SceneDesc::validate`]).
    Invalid(SceneError),
}

impl SceneFileError {
    /// The key path the error is about, if there is one (`"mesh.obj"` for
    /// OBJ errors; the validator's field for [`SceneFileError::Invalid`] is
    /// only in the message).
    ///
    /// ```
    /// use fixshade_host::scene_file::SceneFileError;
    /// let e = SceneFileError::Key { key: "camera.near".into(), message: "missing".into() };
    /// assert_eq!(e.key(), Some("camera.near"));
    /// ```
    pub fn key(&self) -> Option<&str> {
        match self {
            SceneFileError::Key { key, .. } => Some(key),
            SceneFileError::ObjRead { .. } | SceneFileError::Obj { .. } => Some("mesh.obj"),
            _ => None,
        }
    }
}

impl fmt::Display for SceneFileError {
    /// One line: what the file holds (keys, names, paths, numbers) is
    /// echoed with its control characters escaped ([`one_line`]).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&one_line(&self.raw_message()))
    }
}

impl SceneFileError {
    fn raw_message(&self) -> String {
        match self {
            SceneFileError::Read { path, message } => {
                format!("cannot read {}: {message}", path.display())
            }
            SceneFileError::Syntax(message) => format!("not valid JSON: {message}"),
            SceneFileError::Key { key, message } if key.is_empty() => {
                format!("top level: {message}")
            }
            SceneFileError::Key { key, message } => format!("{key}: {message}"),
            SceneFileError::ObjRead { path, message } => {
                format!("mesh.obj: cannot read {}: {message}", path.display())
            }
            SceneFileError::Obj { path, error } => {
                format!("mesh.obj: {}: {error}", path.display())
            }
            SceneFileError::Invalid(e) => e.to_string(),
        }
    }
}

/// `text` with its control characters (line breaks, tabs, escape
/// sequences) written as Rust escapes, so that what a file holds cannot
/// break an error message over lines.
///
/// ```
/// use fixshade_host::scene_file::one_line;
/// assert_eq!(one_line("a\nb\u{1b}[2J"), "a\\nb\\u{1b}[2J");
/// assert_eq!(one_line("lights[0].tÿpe"), "lights[0].tÿpe");
/// ```
pub fn one_line(text: &str) -> String {
    text.chars()
        .map(|c| {
            if c.is_control() {
                c.escape_default().to_string()
            } else {
                c.to_string()
            }
        })
        .collect()
}

impl std::error::Error for SceneFileError {}

impl From<SceneError> for SceneFileError {
    fn from(e: SceneError) -> Self {
        SceneFileError::Invalid(e)
    }
}

type Result<T> = std::result::Result<T, SceneFileError>;

/// Reads the scene file at `path`; an OBJ mesh is resolved against the
/// file's folder.
///
/// ```
/// let err = fixshade_host::scene_file::load_scene("no/such/scene.json").unwrap_err();
/// assert!(err.to_string().starts_with("cannot read no/such/scene.json"));
/// ```
pub fn load_scene(path: impl AsRef<Path>) -> Result<SceneDesc> {
    let path = path.as_ref();
    let input = open_regular(path).map_err(|e| SceneFileError::Read {
        path: path.to_path_buf(),
        message: e.to_string(),
    })?;
    let base = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    read_scene(input, base, path)
}

/// Parses a scene file's text; `base_dir` is the folder a relative
/// `mesh.obj` path is resolved against. The result has passed
/// [`SceneDesc::validate`].
///
/// ```
/// use std::path::Path;
/// use fixshade_host::{scene_desc::Shading, scene_file::parse_scene};
/// let json = r#"{"width": 8, "height": 8, "shading": "flat", "mesh": MESH,
///   "camera": {"eye": [0, 0, 1], "target": [0, 0, 0], "up": [0, 1, 0], "near": 0.5, "far": 2,
///              "projection": "orthographic", "height": 2}}"#;
/// let tri = r#"{"positions": [[-1, -1, 0], [1, -1, 0], [0, 1, 0]], "indices": [[0, 1, 2]]}"#;
/// let s = parse_scene(&json.replace("MESH", tri), Path::new(".")).unwrap();
/// assert_eq!((s.shading, s.mesh.normals, s.cull), (Shading::Flat, None, true));
/// let obj = json.replace("MESH", r#"{"obj": "m.obj"}"#);
/// let err = parse_scene(&obj, Path::new("no_such_dir")).unwrap_err();
/// assert!(err.to_string().starts_with("mesh.obj: cannot read no_such_dir/m.obj"), "{err}");
/// ```
pub fn parse_scene(json: &str, base_dir: &Path) -> Result<SceneDesc> {
    read_scene(json.as_bytes(), base_dir, Path::new("scene text"))
}

/// Reads a scene from `input` (`path` names it in errors) in one pass: the
/// mesh's arrays go straight into their final types, everything else is
/// kept as JSON values within fixed limits, so that reading takes at most
/// 2.25 bytes of memory per byte of input (`mesh.indices`: 6 bytes a
/// triangle for at least 8 bytes of text, with a vector's growth) plus
/// 16 MiB (positions and normals: at most [`MAX_VERTICES`] of 24 bytes,
/// with growth; the other values).
fn read_scene(input: impl std::io::BufRead, base_dir: &Path, path: &Path) -> Result<SceneDesc> {
    let mut reader = JsonReader::new(input);
    let root = reader.value("", 0).and_then(|v| {
        reader.expect_end()?;
        Ok(v)
    });
    let root = match root {
        Ok(v) => v,
        Err(Stop::Syntax(m)) => return Err(SceneFileError::Syntax(m)),
        Err(Stop::File(e)) => return Err(e),
        Err(Stop::Io(e)) => {
            return Err(SceneFileError::Read {
                path: path.to_path_buf(),
                message: e.to_string(),
            })
        }
    };
    let mut arrays = std::mem::take(&mut reader.arrays);
    let o = Obj::new(
        &root,
        String::new(),
        &[
            "width",
            "height",
            "camera",
            "model",
            "mesh",
            "material",
            "global_ambient",
            "lights",
            "shading",
            "specular_model",
            "viewer",
            "cull",
            "depth",
            "two_sided",
            "dither",
            "background",
        ],
    )?;
    let width = o.req("width", uint)?;
    let height = o.req("height", uint)?;
    let camera = o.req("camera", camera)?;
    let mesh = o.req("mesh", |v, p| mesh(v, p, base_dir, &mut arrays))?;
    let mut scene = SceneDesc::new(width, height, camera, mesh);
    scene.model = o.opt("model", mat4, IDENTITY)?;
    scene.material = o.opt("material", material, MaterialDesc::default())?;
    scene.global_ambient = o.opt("global_ambient", vec3, scene.global_ambient)?;
    scene.lights = o.opt("lights", |v, p| list(v, p, light), Vec::new())?;
    scene.shading = o
        .opt("shading", name::<ShadingName>, ShadingName::Gouraud)?
        .into();
    scene.specular_model = o
        .opt("specular_model", name::<SpecularName>, SpecularName::Blinn)?
        .into();
    scene.viewer = o
        .opt("viewer", name::<ViewerName>, ViewerName::Infinite)?
        .into();
    scene.cull = o.opt("cull", boolean, true)?;
    scene.depth = o.opt("depth", boolean, true)?;
    scene.two_sided = o.opt("two_sided", boolean, false)?;
    scene.dither = o.opt("dither", boolean, false)?;
    scene.background = o.opt("background", vec3, [0.0; 3])?;
    scene.validate()?;
    Ok(scene)
}

/// A JSON object being read, with its key path; every key it holds has been
/// checked against the keys allowed there.
struct Obj<'a> {
    map: &'a Map<String, Value>,
    path: String,
}

impl<'a> Obj<'a> {
    fn new(v: &'a Value, path: String, allowed: &[&str]) -> Result<Self> {
        let map = object(v, &path)?;
        let obj = Obj { map, path };
        if let Some(k) = map.keys().find(|k| !allowed.contains(&k.as_str())) {
            return Err(key_error(
                obj.sub(k),
                format!("unknown key (expected one of: {})", allowed.join(", ")),
            ));
        }
        Ok(obj)
    }

    fn sub(&self, key: &str) -> String {
        if self.path.is_empty() {
            key.to_string()
        } else {
            format!("{}.{key}", self.path)
        }
    }

    fn req<T>(&self, key: &str, read: impl FnOnce(&Value, String) -> Result<T>) -> Result<T> {
        match self.map.get(key) {
            Some(v) => read(v, self.sub(key)),
            None => Err(key_error(self.sub(key), "missing required key")),
        }
    }

    fn opt<T>(
        &self,
        key: &str,
        read: impl FnOnce(&Value, String) -> Result<T>,
        default: T,
    ) -> Result<T> {
        match self.map.get(key) {
            Some(v) => read(v, self.sub(key)),
            None => Ok(default),
        }
    }
}

fn key_error(key: String, message: impl Into<String>) -> SceneFileError {
    SceneFileError::Key {
        key,
        message: message.into(),
    }
}

/// "a string", "an array", … for messages about wrong types.
fn kind(v: &Value) -> &'static str {
    match v {
        Value::Null => "null",
        Value::Bool(_) => "a boolean",
        Value::Number(_) => "a number",
        Value::String(_) => "a string",
        Value::Array(_) => "an array",
        Value::Object(_) => "an object",
    }
}

fn wrong_type(path: String, expected: &str, v: &Value) -> SceneFileError {
    key_error(path, format!("expected {expected}, found {}", kind(v)))
}

fn object<'a>(v: &'a Value, path: &str) -> Result<&'a Map<String, Value>> {
    v.as_object()
        .ok_or_else(|| wrong_type(path.to_string(), "an object", v))
}

fn number(v: &Value, path: String) -> Result<f64> {
    match v {
        Value::Number(n) => n.as_f64().ok_or_else(|| {
            key_error(
                path,
                format!("{n} is not a finite number (outside the f64 range)"),
            )
        }),
        _ => Err(wrong_type(path, "a number", v)),
    }
}

fn uint(v: &Value, path: String) -> Result<u32> {
    let bad = |path| key_error(path, format!("expected a non-negative integer, found {v}"));
    match v {
        Value::Number(n) => match n.as_u64() {
            Some(i) => u32::try_from(i)
                .map_err(|_| key_error(path, format!("{i} is too large (at most {})", u32::MAX))),
            None => Err(bad(path)),
        },
        _ => Err(wrong_type(path, "a non-negative integer", v)),
    }
}

fn boolean(v: &Value, path: String) -> Result<bool> {
    v.as_bool()
        .ok_or_else(|| wrong_type(path, "true or false", v))
}

fn string<'a>(v: &'a Value, path: &str) -> Result<&'a str> {
    v.as_str()
        .ok_or_else(|| wrong_type(path.to_string(), "a string", v))
}

fn list<T>(v: &Value, path: String, read: impl Fn(&Value, String) -> Result<T>) -> Result<Vec<T>> {
    let items = v
        .as_array()
        .ok_or_else(|| wrong_type(path.clone(), "an array", v))?;
    items
        .iter()
        .enumerate()
        .map(|(i, item)| read(item, format!("{path}[{i}]")))
        .collect()
}

fn array<T: Copy + Default, const N: usize>(
    v: &Value,
    path: String,
    read: impl Fn(&Value, String) -> Result<T>,
) -> Result<[T; N]> {
    let what = || format!("an array of {N}");
    let items = v
        .as_array()
        .ok_or_else(|| wrong_type(path.clone(), &what(), v))?;
    if items.len() != N {
        return Err(key_error(
            path,
            format!("expected {}, found {} elements", what(), items.len()),
        ));
    }
    let mut out = [T::default(); N];
    for (i, (slot, item)) in out.iter_mut().zip(items).enumerate() {
        *slot = read(item, format!("{path}[{i}]"))?;
    }
    Ok(out)
}

fn vec3(v: &Value, path: String) -> Result<[f64; 3]> {
    array(v, path, number)
}

fn mat4(v: &Value, path: String) -> Result<[[f64; 4]; 4]> {
    array(v, path, |row, p| array(row, p, number))
}

/// A string naming one of a few choices, read through serde so that its
/// message lists the choices.
fn name<T: DeserializeOwned>(v: &Value, path: String) -> Result<T> {
    T::deserialize(v).map_err(|e| key_error(path, e.to_string()))
}

#[derive(Deserialize)]
#[serde(rename_all = "lowercase")]
enum ShadingName {
    Flat,
    Gouraud,
    Phong,
}

impl From<ShadingName> for Shading {
    fn from(s: ShadingName) -> Self {
        match s {
            ShadingName::Flat => Shading::Flat,
            ShadingName::Gouraud => Shading::Gouraud,
            ShadingName::Phong => Shading::Phong,
        }
    }
}

#[derive(Deserialize)]
#[serde(rename_all = "lowercase")]
enum SpecularName {
    Phong,
    Blinn,
}

impl From<SpecularName> for SpecularModel {
    fn from(s: SpecularName) -> Self {
        match s {
            SpecularName::Phong => SpecularModel::Phong,
            SpecularName::Blinn => SpecularModel::Blinn,
        }
    }
}

#[derive(Deserialize)]
#[serde(rename_all = "lowercase")]
enum ViewerName {
    Local,
    Infinite,
}

impl From<ViewerName> for Viewer {
    fn from(s: ViewerName) -> Self {
        match s {
            ViewerName::Local => Viewer::Local,
            ViewerName::Infinite => Viewer::Infinite,
        }
    }
}

#[derive(Deserialize)]
#[serde(rename_all = "lowercase")]
enum ProjectionName {
    Perspective,
    Orthographic,
}

#[derive(Deserialize)]
#[serde(rename_all = "lowercase")]
enum LightType {
    Directional,
    Point,
    Spot,
    Area,
}

#[derive(Deserialize)]
#[serde(rename_all = "lowercase")]
enum GeneratorName {
    Sphere,
    Cube,
    Torus,
    Plane,
}

/// Reads the discriminating key (`type`, `projection`, `generator`) of an
/// object before its other keys are checked.
fn tag<T: DeserializeOwned>(v: &Value, path: &str, key: &str) -> Result<Option<T>> {
    let map = object(v, path)?;
    let sub = if path.is_empty() {
        key.to_string()
    } else {
        format!("{path}.{key}")
    };
    map.get(key).map(|t| name(t, sub)).transpose()
}

fn camera(v: &Value, path: String) -> Result<CameraDesc> {
    let projection = tag(v, &path, "projection")?.unwrap_or(ProjectionName::Perspective);
    let (size_key, allowed): (&str, &[&str]) = match projection {
        ProjectionName::Perspective => (
            "fovy_deg",
            &[
                "eye",
                "target",
                "up",
                "near",
                "far",
                "projection",
                "fovy_deg",
            ],
        ),
        ProjectionName::Orthographic => (
            "height",
            &["eye", "target", "up", "near", "far", "projection", "height"],
        ),
    };
    let o = Obj::new(v, path, allowed)?;
    let size = o.req(size_key, number)?;
    Ok(CameraDesc {
        eye: o.req("eye", vec3)?,
        target: o.req("target", vec3)?,
        up: o.req("up", vec3)?,
        near: o.req("near", number)?,
        far: o.req("far", number)?,
        projection: match projection {
            ProjectionName::Perspective => Projection::Perspective { fovy_deg: size },
            ProjectionName::Orthographic => Projection::Orthographic { height: size },
        },
    })
}

fn material(v: &Value, path: String) -> Result<MaterialDesc> {
    let o = Obj::new(
        v,
        path,
        &["emission", "ambient", "diffuse", "specular", "shininess"],
    )?;
    let d = MaterialDesc::default();
    Ok(MaterialDesc {
        emission: o.opt("emission", vec3, d.emission)?,
        ambient: o.opt("ambient", vec3, d.ambient)?,
        diffuse: o.opt("diffuse", vec3, d.diffuse)?,
        specular: o.opt("specular", vec3, d.specular)?,
        shininess: o.opt("shininess", number, d.shininess)?,
    })
}

fn light(v: &Value, path: String) -> Result<LightDesc> {
    let Some(ty) = tag::<LightType>(v, &path, "type")? else {
        return Err(key_error(format!("{path}.type"), "missing required key"));
    };
    let allowed: &[&str] = match ty {
        LightType::Directional => &["type", "direction", "diffuse", "specular"],
        LightType::Point => &["type", "position", "diffuse", "specular", "attenuation"],
        LightType::Spot => &[
            "type",
            "position",
            "axis",
            "cutoff_deg",
            "exponent",
            "diffuse",
            "specular",
            "attenuation",
        ],
        LightType::Area => &[
            "type",
            "center",
            "edge_u",
            "edge_v",
            "samples_k",
            "diffuse",
            "specular",
            "attenuation",
        ],
    };
    let o = Obj::new(v, path, allowed)?;
    let diffuse = o.opt("diffuse", vec3, WHITE)?;
    let specular = o.opt("specular", vec3, WHITE)?;
    let attenuation = |o: &Obj| o.opt("attenuation", vec3, DEFAULT_ATTENUATION);
    Ok(match ty {
        LightType::Directional => LightDesc::Directional {
            direction: o.req("direction", vec3)?,
            diffuse,
            specular,
        },
        LightType::Point => LightDesc::Point {
            position: o.req("position", vec3)?,
            diffuse,
            specular,
            attenuation: attenuation(&o)?,
        },
        LightType::Spot => LightDesc::Spot {
            position: o.req("position", vec3)?,
            axis: o.req("axis", vec3)?,
            cutoff_deg: o.req("cutoff_deg", number)?,
            exponent: o.req("exponent", number)?,
            diffuse,
            specular,
            attenuation: attenuation(&o)?,
        },
        LightType::Area => LightDesc::Area {
            center: o.req("center", vec3)?,
            edge_u: o.req("edge_u", vec3)?,
            edge_v: o.req("edge_v", vec3)?,
            samples_k: o.req("samples_k", uint)?,
            diffuse,
            specular,
            attenuation: attenuation(&o)?,
        },
    })
}

fn mesh(v: &Value, path: String, base_dir: &Path, arrays: &mut MeshArrays) -> Result<MeshDesc> {
    let map = object(v, &path)?;
    if map.contains_key("obj") {
        let o = Obj::new(v, path, &["obj"])?;
        let file = o.req("obj", |v, p| string(v, &p).map(str::to_owned))?;
        obj_file(&base_dir.join(file))
    } else if map.contains_key("generator") {
        generator(v, path)
    } else if map.contains_key("positions") {
        let o = Obj::new(v, path, &["positions", "indices", "normals"])?;
        // An array was read into `arrays`; anything else is a wrong type.
        let points = |given: Option<Vec<[f64; 3]>>| {
            move |v: &Value, p: String| match given {
                Some(a) => Ok(a),
                None => list(v, p, vec3),
            }
        };
        let tris = arrays.indices.take();
        Ok(MeshDesc {
            positions: o.req("positions", points(arrays.positions.take()))?,
            indices: o.req("indices", |v, p| match tris {
                Some(t) => Ok(t),
                None => list(v, p, triangle),
            })?,
            normals: o.opt(
                "normals",
                |v, p| points(arrays.normals.take())(v, p).map(Some),
                None,
            )?,
        })
    } else {
        Err(key_error(
            path,
            "expected one of the keys `obj`, `generator` or `positions`",
        ))
    }
}

/// The OBJ file of `mesh.obj`, read by [`read_obj_file`]: a file that
/// cannot be opened is [`SceneFileError::ObjRead`], one that fails later
/// [`SceneFileError::Obj`] with its line.
fn obj_file(path: &Path) -> Result<MeshDesc> {
    read_obj_file(path).map_err(|error| match error {
        ObjError {
            line: 0,
            kind: ObjErrorKind::Read(message),
        } => SceneFileError::ObjRead {
            path: path.to_path_buf(),
            message,
        },
        error => SceneFileError::Obj {
            path: path.to_path_buf(),
            error,
        },
    })
}

/// Reads the OBJ file at `path` ([`generate::read_obj`], which gives its
/// memory bound) as a scene's `mesh.obj` is read, and as the mesh
/// converter reads its input: a regular file (a device, a FIFO or a folder
/// is refused before it is opened) of at most [`MAX_FILE_BYTES`] (a larger
/// file is refused while it is read). A file that cannot be opened, or is
/// not a regular file, is an error of no line (line 0, shown without it:
/// [`ObjErrorKind::Read`], the operating system's message or `not a
/// regular file`).
///
/// ```
/// use std::path::Path;
/// use fixshade_host::generate::ObjErrorKind;
/// use fixshade_host::scene_file::read_obj_file;
/// let m = read_obj_file(Path::new("tests/data/tetrahedron.obj")).unwrap();
/// assert_eq!((m.positions.len(), m.indices.len()), (4, 4));
/// let err = read_obj_file(Path::new("tests/data")).unwrap_err();
/// assert_eq!(err.line, 0);
/// assert_eq!(err.kind, ObjErrorKind::Read("not a regular file".into()));
/// ```
pub fn read_obj_file(path: &Path) -> std::result::Result<MeshDesc, ObjError> {
    // Opened once per pass of the reader, each time checked again.
    generate::read_obj(|| open_regular(path))
}

/// A segment count in `min..=max` (the generators would clamp anything
/// else; a file must not be silently changed).
fn segments(v: &Value, path: String, min: u32, max: u32) -> Result<u32> {
    let n = uint(v, path.clone())?;
    if (min..=max).contains(&n) {
        Ok(n)
    } else {
        Err(key_error(
            path,
            format!("{n} out of range (must be in {min}..={max})"),
        ))
    }
}

/// Two segment counts whose `(a + 1) × (b + 1)` vertex grid fits
/// [`MAX_VERTICES`].
fn grid(v: &Value, path: String, min: [u32; 2]) -> Result<[u32; 2]> {
    let pair: [u32; 2] = array(v, path.clone(), uint)?;
    for k in 0..2 {
        segments(&v[k], format!("{path}[{k}]"), min[k], MAX_SEGMENTS)?;
    }
    let vertices = (pair[0] as u64 + 1) * (pair[1] as u64 + 1);
    if vertices > MAX_VERTICES as u64 {
        return Err(key_error(
            path,
            format!(
                "{} × {} segments make {vertices} vertices, more than {MAX_VERTICES}",
                pair[0], pair[1]
            ),
        ));
    }
    Ok(pair)
}

/// A size or radius, `> 0`.
fn positive(v: &Value, path: String) -> Result<f64> {
    let x = number(v, path.clone())?;
    if x > 0.0 {
        Ok(x)
    } else {
        Err(key_error(path, format!("{x} out of range (must be > 0)")))
    }
}

fn generator(v: &Value, path: String) -> Result<MeshDesc> {
    let Some(g) = tag::<GeneratorName>(v, &path, "generator")? else {
        return Err(key_error(
            format!("{path}.generator"),
            "missing required key",
        ));
    };
    let allowed: &[&str] = match g {
        GeneratorName::Sphere => &["generator", "segments", "radius"],
        GeneratorName::Cube => &["generator", "size"],
        GeneratorName::Torus => &["generator", "radii", "segments"],
        GeneratorName::Plane => &["generator", "size", "segments"],
    };
    let o = Obj::new(v, path, allowed)?;
    Ok(match g {
        GeneratorName::Sphere => {
            let [lon, lat] = o.req("segments", |v, p| grid(v, p, [3, 2]))?;
            generate::sphere(lon, lat, o.req("radius", positive)?)
        }
        GeneratorName::Cube => generate::cube(o.req("size", positive)?),
        GeneratorName::Torus => {
            let [big, small] = o.req("radii", |v, p| array(v, p, positive))?;
            let [u, w] = o.req("segments", |v, p| grid(v, p, [3, 3]))?;
            generate::torus(big, small, u, w)
        }
        GeneratorName::Plane => {
            let size = o.req("size", positive)?;
            let n = o.req("segments", |v, p| segments(v, p, 1, MAX_PLANE_SEGMENTS))?;
            generate::plane(size, n)
        }
    })
}

// ---------------------------------------------------------------------------
// Reading: a streaming JSON reader with bounded memory
// ---------------------------------------------------------------------------

/// The largest scene or OBJ file read, in bytes: a larger file is refused
/// while it is read (a device such as `/dev/zero` never ends).
///
/// ```
/// assert_eq!(fixshade_host::scene_file::MAX_FILE_BYTES, 64 << 20);
/// ```
pub const MAX_FILE_BYTES: u64 = 64 << 20;

/// Limits of everything in a scene file but the mesh's `positions`,
/// `normals` and `indices`, so that what is kept of it as JSON values stays
/// small whatever the file holds: values, bytes of strings and numbers, and
/// nesting.
const MAX_VALUES: usize = 16 * 1024;
const MAX_TEXT: usize = 256 * 1024;
const MAX_DEPTH: usize = 32;
/// The longest string or number token anywhere (an OBJ path is a string).
const MAX_TOKEN: usize = 4096;

/// Opens `path` for reading if it is a regular file (not a directory, a
/// device or a FIFO, which could block or never end), with its size capped
/// at [`MAX_FILE_BYTES`] while it is read.
fn open_regular(path: &Path) -> std::io::Result<std::io::BufReader<Capped>> {
    use std::io::{Error, ErrorKind};
    // The type is checked before opening: opening a FIFO blocks until a
    // writer comes.
    if !std::fs::metadata(path)?.is_file() {
        return Err(Error::new(ErrorKind::InvalidInput, "not a regular file"));
    }
    let file = std::fs::File::open(path)?;
    if !file.metadata()?.is_file() {
        return Err(Error::new(ErrorKind::InvalidInput, "not a regular file"));
    }
    Ok(std::io::BufReader::new(Capped {
        file,
        left: MAX_FILE_BYTES,
    }))
}

/// A file read up to [`MAX_FILE_BYTES`]; reading past that is an error.
struct Capped {
    file: std::fs::File,
    left: u64,
}

impl std::io::Read for Capped {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        if self.left == 0 {
            let mut probe = [0u8; 1];
            return match self.file.read(&mut probe)? {
                0 => Ok(0),
                _ => Err(std::io::Error::other(format!(
                    "larger than {MAX_FILE_BYTES} bytes"
                ))),
            };
        }
        let n = buf.len().min(self.left.min(usize::MAX as u64) as usize);
        let got = self.file.read(&mut buf[..n])?;
        self.left -= got as u64;
        Ok(got)
    }
}

/// The mesh's large arrays, read element by element into their final types
/// instead of being kept as JSON values.
#[derive(Default)]
struct MeshArrays {
    positions: Option<Vec<[f64; 3]>>,
    normals: Option<Vec<[f64; 3]>>,
    indices: Option<Vec<[u16; 3]>>,
}

/// A pull reader of JSON text (RFC 8259) from a `BufRead`, building
/// `serde_json` values within the limits above, and the mesh's arrays.
struct JsonReader<R> {
    input: R,
    line: u64,
    column: u64,
    values: usize,
    text: usize,
    arrays: MeshArrays,
}

/// Why reading stopped: a syntax error (message with its position), an
/// error about a key, or the input failing.
enum Stop {
    Syntax(String),
    File(SceneFileError),
    Io(std::io::Error),
}

impl From<SceneFileError> for Stop {
    fn from(e: SceneFileError) -> Self {
        Stop::File(e)
    }
}

type Read<T> = std::result::Result<T, Stop>;

impl<R: std::io::BufRead> JsonReader<R> {
    fn new(input: R) -> Self {
        JsonReader {
            input,
            line: 1,
            column: 0,
            values: 0,
            text: 0,
            arrays: MeshArrays::default(),
        }
    }

    fn syntax<T>(&self, what: impl fmt::Display) -> Read<T> {
        Err(Stop::Syntax(format!(
            "{what} at line {} column {}",
            self.line, self.column
        )))
    }

    fn peek(&mut self) -> Read<Option<u8>> {
        let buf = self.input.fill_buf().map_err(Stop::Io)?;
        Ok(buf.first().copied())
    }

    fn bump(&mut self) -> Read<Option<u8>> {
        let b = self.peek()?;
        if let Some(b) = b {
            self.input.consume(1);
            if b == b'\n' {
                self.line += 1;
                self.column = 0;
            } else {
                self.column += 1;
            }
        }
        Ok(b)
    }

    /// The next byte that is not white space, not consumed.
    fn next_token(&mut self) -> Read<Option<u8>> {
        while let Some(b) = self.peek()? {
            if !matches!(b, b' ' | b'\t' | b'\n' | b'\r') {
                return Ok(Some(b));
            }
            self.bump()?;
        }
        Ok(None)
    }

    fn expect_end(&mut self) -> Read<()> {
        match self.next_token()? {
            None => Ok(()),
            Some(_) => {
                self.bump()?;
                self.syntax("trailing characters")
            }
        }
    }

    /// Counts one kept value and `bytes` of kept text against the limits.
    fn keep(&mut self, path: &str, bytes: usize) -> Read<()> {
        self.values += 1;
        self.text += bytes;
        if self.values > MAX_VALUES || self.text > MAX_TEXT {
            return Err(key_error(
                path.to_string(),
                format!(
                    "the scene holds more than {MAX_VALUES} values or {MAX_TEXT} bytes of text \
                     outside mesh.positions, mesh.normals and mesh.indices"
                ),
            )
            .into());
        }
        Ok(())
    }

    /// One JSON value at `path`, kept as a `serde_json` value (within the
    /// limits); at `mesh.positions`, `mesh.normals` and `mesh.indices` an
    /// array is read into [`MeshArrays`] instead and `null` stands in its
    /// place.
    fn value(&mut self, path: &str, depth: usize) -> Read<Value> {
        if depth > MAX_DEPTH {
            return self.syntax(format_args!("nesting deeper than {MAX_DEPTH}"));
        }
        let Some(b) = self.next_token()? else {
            return self.syntax("EOF while parsing a value");
        };
        match b {
            b'{' => self.object(path, depth),
            b'[' => {
                if let Some(kind) = mesh_array(path) {
                    self.mesh_array(path, kind)?;
                    return Ok(Value::Null);
                }
                let mut items = Vec::new();
                if self.open(path, b']')? {
                    return Ok(Value::Array(items));
                }
                loop {
                    let item = self.value(&format!("{path}[{}]", items.len()), depth + 1)?;
                    items.push(item);
                    if self.closes(b']')? {
                        return Ok(Value::Array(items));
                    }
                }
            }
            b'"' => {
                let s = self.string()?;
                self.keep(path, s.len())?;
                Ok(Value::String(s))
            }
            b'-' | b'0'..=b'9' => {
                let n = self.number()?;
                self.keep(path, n.len())?;
                match n.parse::<serde_json::Number>() {
                    Ok(n) => Ok(Value::Number(n)),
                    Err(_) => self.syntax("invalid number"),
                }
            }
            b't' => self.literal("true", Value::Bool(true)),
            b'f' => self.literal("false", Value::Bool(false)),
            b'n' => self.literal("null", Value::Null),
            _ => {
                self.bump()?;
                self.syntax("expected value")
            }
        }
    }

    fn object(&mut self, path: &str, depth: usize) -> Read<Value> {
        let mut map = Map::new();
        if self.open(path, b'}')? {
            return Ok(Value::Object(map));
        }
        loop {
            if self.next_token()? != Some(b'"') {
                self.bump()?;
                return self.syntax("key must be a string");
            }
            let key = self.string()?;
            self.keep(path, key.len())?;
            let sub = if path.is_empty() {
                key.clone()
            } else {
                format!("{path}.{key}")
            };
            if self.next_token()? != Some(b':') {
                self.bump()?;
                return self.syntax("expected `:`");
            }
            self.bump()?;
            let v = self.value(&sub, depth + 1)?;
            if map.insert(key, v).is_some() {
                return Err(key_error(sub, "duplicate key").into());
            }
            if self.closes(b'}')? {
                return Ok(Value::Object(map));
            }
        }
    }

    /// Opens an array or object (its bracket is next), counted as one kept
    /// value: `true` if it is empty (its closing bracket `close` consumed).
    fn open(&mut self, path: &str, close: u8) -> Read<bool> {
        self.keep(path, 0)?;
        self.bump()?;
        let empty = self.next_token()? == Some(close);
        if empty {
            self.bump()?;
        }
        Ok(empty)
    }

    /// After an element of an array or object: `true` at its closing
    /// bracket `close` (consumed), `false` after a comma (consumed).
    fn closes(&mut self, close: u8) -> Read<bool> {
        let next = self.next_token()?;
        self.bump()?;
        match next {
            Some(b',') => Ok(false),
            Some(c) if c == close => Ok(true),
            _ => self.syntax(format_args!("expected `,` or `{}`", close as char)),
        }
    }

    fn literal(&mut self, word: &str, v: Value) -> Read<Value> {
        for &w in word.as_bytes() {
            if self.bump()? != Some(w) {
                return self.syntax("expected value");
            }
        }
        Ok(v)
    }

    /// A number token's text, checked against the JSON grammar.
    fn number(&mut self) -> Read<String> {
        let mut s = String::new();
        while let Some(b) = self.peek()? {
            if !matches!(b, b'-' | b'+' | b'.' | b'e' | b'E' | b'0'..=b'9') {
                break;
            }
            if s.len() == MAX_TOKEN {
                return self.syntax(format_args!("number longer than {MAX_TOKEN} characters"));
            }
            s.push(b as char);
            self.bump()?;
        }
        if !is_json_number(&s) {
            return self.syntax("invalid number");
        }
        Ok(s)
    }

    /// A string token (the opening quote is next), unescaped.
    fn string(&mut self) -> Read<String> {
        self.bump()?;
        let mut out: Vec<u8> = Vec::new();
        loop {
            if out.len() > MAX_TOKEN {
                return self.syntax(format_args!("string longer than {MAX_TOKEN} bytes"));
            }
            match self.bump()? {
                None => return self.syntax("EOF while parsing a string"),
                Some(b'"') => break,
                Some(b'\\') => {
                    let c = match self.bump()? {
                        Some(b'"') => '"',
                        Some(b'\\') => '\\',
                        Some(b'/') => '/',
                        Some(b'b') => '\u{8}',
                        Some(b'f') => '\u{c}',
                        Some(b'n') => '\n',
                        Some(b'r') => '\r',
                        Some(b't') => '\t',
                        Some(b'u') => self.unicode_escape()?,
                        _ => return self.syntax("invalid escape"),
                    };
                    let mut tmp = [0u8; 4];
                    out.extend_from_slice(c.encode_utf8(&mut tmp).as_bytes());
                }
                Some(b) if b < 0x20 => {
                    return self.syntax("control character in a string");
                }
                Some(b) => out.push(b),
            }
        }
        match String::from_utf8(out) {
            Ok(s) => Ok(s),
            Err(_) => self.syntax("string is not UTF-8"),
        }
    }

    fn hex4(&mut self) -> Read<u32> {
        let mut v = 0;
        for _ in 0..4 {
            let d = match self.bump()? {
                Some(b) => (b as char).to_digit(16),
                None => None,
            };
            match d {
                Some(d) => v = v * 16 + d,
                None => return self.syntax("invalid \\u escape"),
            }
        }
        Ok(v)
    }

    /// The character of a `\uXXXX` escape (a surrogate pair takes two).
    fn unicode_escape(&mut self) -> Read<char> {
        let hi = self.hex4()?;
        let code = if (0xD800..0xDC00).contains(&hi) {
            if self.bump()? != Some(b'\\') || self.bump()? != Some(b'u') {
                return self.syntax("lone surrogate in a \\u escape");
            }
            let lo = self.hex4()?;
            if !(0xDC00..0xE000).contains(&lo) {
                return self.syntax("lone surrogate in a \\u escape");
            }
            0x10000 + ((hi - 0xD800) << 10) + (lo - 0xDC00)
        } else {
            hi
        };
        match char::from_u32(code) {
            Some(c) => Ok(c),
            None => self.syntax("lone surrogate in a \\u escape"),
        }
    }

    /// `mesh.positions`, `mesh.normals` or `mesh.indices`: each element is
    /// read as a small value, converted and dropped.
    fn mesh_array(&mut self, path: &str, kind: MeshArray) -> Read<()> {
        self.bump()?;
        let mut points: Vec<[f64; 3]> = Vec::new();
        let mut tris: Vec<[u16; 3]> = Vec::new();
        let mut n = 0usize;
        if self.next_token()? == Some(b']') {
            self.bump()?;
        } else {
            loop {
                let at = format!("{path}[{n}]");
                let (values, text) = (self.values, self.text);
                let v = self.value(&at, 2)?;
                (self.values, self.text) = (values, text);
                match kind {
                    MeshArray::Positions | MeshArray::Normals => {
                        if n == MAX_VERTICES {
                            return Err(key_error(
                                path.to_string(),
                                format!("more than {MAX_VERTICES} vertices"),
                            )
                            .into());
                        }
                        points.push(vec3(&v, at)?);
                    }
                    MeshArray::Indices => tris.push(triangle(&v, at)?),
                }
                n += 1;
                if self.closes(b']')? {
                    break;
                }
            }
        }
        match kind {
            MeshArray::Positions => self.arrays.positions = Some(points),
            MeshArray::Normals => self.arrays.normals = Some(points),
            MeshArray::Indices => self.arrays.indices = Some(tris),
        }
        Ok(())
    }
}

#[derive(Clone, Copy)]
enum MeshArray {
    Positions,
    Normals,
    Indices,
}

fn mesh_array(path: &str) -> Option<MeshArray> {
    match path {
        "mesh.positions" => Some(MeshArray::Positions),
        "mesh.normals" => Some(MeshArray::Normals),
        "mesh.indices" => Some(MeshArray::Indices),
        _ => None,
    }
}

/// One triangle of `mesh.indices`: three integers below 2¹⁶ (a mesh has at
/// most [`MAX_VERTICES`] vertices).
fn triangle(v: &Value, path: String) -> Result<[u16; 3]> {
    array(v, path, |x, p| {
        let i = uint(x, p.clone())?;
        u16::try_from(i).map_err(|_| {
            key_error(
                p,
                format!("{i} is too large (a mesh has at most {MAX_VERTICES} vertices)"),
            )
        })
    })
}

/// `-? (0 | [1-9][0-9]*) (. [0-9]+)? ([eE] [+-]? [0-9]+)?`
fn is_json_number(s: &str) -> bool {
    let b = s.as_bytes();
    let mut i = 0;
    let digits = |i: &mut usize| {
        let start = *i;
        while *i < b.len() && b[*i].is_ascii_digit() {
            *i += 1;
        }
        *i > start
    };
    if b.first() == Some(&b'-') {
        i += 1;
    }
    if b.get(i) == Some(&b'0') {
        i += 1;
    } else if !digits(&mut i) {
        return false;
    }
    if b.get(i) == Some(&b'.') {
        i += 1;
        if !digits(&mut i) {
            return false;
        }
    }
    if matches!(b.get(i), Some(b'e' | b'E')) {
        i += 1;
        if matches!(b.get(i), Some(b'+' | b'-')) {
            i += 1;
        }
        if !digits(&mut i) {
            return false;
        }
    }
    i == b.len()
}
