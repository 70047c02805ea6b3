//! Host only (feature `scene-file`): scene files, JSON as `SCENE_FORMAT.md`
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
//! use fixshade::scene_file::parse_scene;
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

use crate::generate::{self, ObjError, MAX_SEGMENTS};
use crate::scene_desc::{
    CameraDesc, LightDesc, MaterialDesc, MeshDesc, Projection, SceneDesc, SceneError, Shading,
    SpecularModel, Viewer, DEFAULT_ATTENUATION, IDENTITY, WHITE,
};

/// Why a scene file was rejected. `Display` gives one line naming the key
/// path, the JSON position or the OBJ line.
///
/// ```
/// use std::path::Path;
/// use fixshade::scene_file::{parse_scene, SceneFileError};
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
    /// use fixshade::scene_file::SceneFileError;
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
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SceneFileError::Read { path, message } => {
                write!(f, "cannot read {}: {message}", path.display())
            }
            SceneFileError::Syntax(message) => write!(f, "not valid JSON: {message}"),
            SceneFileError::Key { key, message } if key.is_empty() => {
                write!(f, "top level: {message}")
            }
            SceneFileError::Key { key, message } => write!(f, "{key}: {message}"),
            SceneFileError::ObjRead { path, message } => {
                write!(f, "mesh.obj: cannot read {}: {message}", path.display())
            }
            SceneFileError::Obj { path, error } => {
                write!(f, "mesh.obj: {}: {error}", path.display())
            }
            SceneFileError::Invalid(e) => e.fmt(f),
        }
    }
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
/// let err = fixshade::scene_file::load_scene("no/such/scene.json").unwrap_err();
/// assert!(err.to_string().starts_with("cannot read no/such/scene.json"));
/// ```
pub fn load_scene(path: impl AsRef<Path>) -> Result<SceneDesc> {
    let path = path.as_ref();
    let text = std::fs::read_to_string(path).map_err(|e| SceneFileError::Read {
        path: path.to_path_buf(),
        message: e.to_string(),
    })?;
    let base = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    parse_scene(&text, base)
}

/// Parses a scene file's text; `base_dir` is the folder a relative
/// `mesh.obj` path is resolved against. The result has passed
/// [`SceneDesc::validate`].
///
/// ```
/// use std::path::Path;
/// use fixshade::{scene_desc::Shading, scene_file::parse_scene};
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
    let root: Value =
        serde_json::from_str(json).map_err(|e| SceneFileError::Syntax(e.to_string()))?;
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
    let mesh = o.req("mesh", |v, p| mesh(v, p, base_dir))?;
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

fn mesh(v: &Value, path: String, base_dir: &Path) -> Result<MeshDesc> {
    let map = object(v, &path)?;
    if map.contains_key("obj") {
        let o = Obj::new(v, path, &["obj"])?;
        let file = o.req("obj", |v, p| string(v, &p).map(str::to_owned))?;
        obj_file(&base_dir.join(file))
    } else if map.contains_key("generator") {
        generator(v, path)
    } else if map.contains_key("positions") {
        let o = Obj::new(v, path, &["positions", "indices", "normals"])?;
        Ok(MeshDesc {
            positions: o.req("positions", |v, p| list(v, p, vec3))?,
            indices: o.req("indices", |v, p| list(v, p, |t, q| array(t, q, uint)))?,
            normals: o.opt("normals", |v, p| list(v, p, vec3).map(Some), None)?,
        })
    } else {
        Err(key_error(
            path,
            "expected one of the keys `obj`, `generator` or `positions`",
        ))
    }
}

fn obj_file(path: &Path) -> Result<MeshDesc> {
    let text = std::fs::read_to_string(path).map_err(|e| SceneFileError::ObjRead {
        path: path.to_path_buf(),
        message: e.to_string(),
    })?;
    generate::load_obj(&text).map_err(|error| SceneFileError::Obj {
        path: path.to_path_buf(),
        error,
    })
}

/// A segment count in `min..=MAX_SEGMENTS` (the generators would clamp
/// anything else; a file must not be silently changed).
fn segments(v: &Value, path: String, min: u32) -> Result<u32> {
    let n = uint(v, path.clone())?;
    if (min..=MAX_SEGMENTS).contains(&n) {
        Ok(n)
    } else {
        Err(key_error(
            path,
            format!("{n} out of range (must be in {min}..={MAX_SEGMENTS})"),
        ))
    }
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
            let [lon, lat] = o.req("segments", |v, p| {
                let pair: [u32; 2] = array(v, p.clone(), uint)?;
                segments(&v[0], format!("{p}[0]"), 3)?;
                segments(&v[1], format!("{p}[1]"), 2)?;
                Ok(pair)
            })?;
            generate::sphere(lon, lat, o.req("radius", positive)?)
        }
        GeneratorName::Cube => generate::cube(o.req("size", positive)?),
        GeneratorName::Torus => {
            let [big, small] = o.req("radii", |v, p| array(v, p, positive))?;
            let [u, w] = o.req("segments", |v, p| array(v, p, |x, q| segments(x, q, 3)))?;
            generate::torus(big, small, u, w)
        }
        GeneratorName::Plane => {
            let size = o.req("size", positive)?;
            generate::plane(size, o.req("segments", |v, p| segments(v, p, 1))?)
        }
    })
}
