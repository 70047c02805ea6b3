//! Scene files: every shipped scene parses, every kind of bad file is
//! rejected with a message naming the key or line, and a scene read from its
//! file renders the same pixels as the same scene built in code.

// The shared helpers import more than this file uses.
#[allow(unused_imports)]
use crate::common;

use std::path::{Path, PathBuf};

use fixshade_host::scene_desc::{LightDesc, Projection, Shading, SpecularModel, Viewer};
use fixshade_host::scene_file::{load_scene, parse_scene, SceneFileError};
use fixshade_host::scene_kernel::KernelScene;
use fixshade_host::standard_scenes;

fn scenes_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/scenes")
}

const SHIPPED: [&str; 5] = ["sphere", "bunny", "spotlight", "shiny", "area"];

/// A small valid scene, edited by the rejection tests.
const BASE: &str = r#"{
  "width": 32,
  "height": 24,
  "camera": {"eye": [0, 0, 3], "target": [0, 0, 0], "up": [0, 1, 0],
             "near": 0.1, "far": 10, "fovy_deg": 60},
  "mesh": {"positions": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "indices": [[0, 1, 2]]},
  "lights": [
    {"type": "directional", "direction": [1, 1, 1]},
    {"type": "spot", "position": [0, 2, 2], "axis": [0, -1, -1], "cutoff_deg": 30, "exponent": 2}
  ]
}"#;

fn parse(json: &str) -> Result<fixshade_host::scene_desc::SceneDesc, SceneFileError> {
    parse_scene(json, &scenes_dir())
}

/// Parses `json` expecting an error whose message starts with `prefix`
/// and contains `needle`; the message must be one line.
fn rejects(json: &str, prefix: &str, needle: &str) {
    let err = parse(json).expect_err("the file must be rejected");
    let msg = err.to_string();
    println!("{msg}");
    assert!(
        msg.starts_with(prefix),
        "`{msg}` should start with `{prefix}`"
    );
    assert!(msg.contains(needle), "`{msg}` should contain `{needle}`");
    assert!(!msg.contains('\n'), "`{msg}` should be one line");
}

#[test]
fn base_scene_parses_with_defaults() {
    let s = parse(BASE).unwrap();
    assert_eq!((s.width, s.height), (32, 24));
    assert_eq!(
        s.camera.projection,
        Projection::Perspective { fovy_deg: 60.0 }
    );
    assert_eq!(s.model, fixshade_host::scene_desc::IDENTITY);
    assert_eq!(s.material, Default::default());
    assert_eq!(s.global_ambient, [0.2; 3]);
    assert_eq!(s.shading, Shading::Gouraud);
    assert_eq!(s.specular_model, SpecularModel::Blinn);
    assert_eq!(s.viewer, Viewer::Infinite);
    assert!(s.cull && s.depth && !s.two_sided && !s.dither);
    assert_eq!(s.background, [0.0; 3]);
    assert_eq!(s.mesh.normals, None);
    match &s.lights[1] {
        LightDesc::Spot {
            diffuse,
            specular,
            attenuation,
            ..
        } => {
            assert_eq!((*diffuse, *specular), ([1.0; 3], [1.0; 3]));
            assert_eq!(*attenuation, [1.0, 0.0, 0.0]);
        }
        other => panic!("expected a spot light, got {other:?}"),
    }
}

#[test]
fn every_key_is_read() {
    let json = r#"{
      "width": 8, "height": 6,
      "camera": {"eye": [0, 0, 3], "target": [0, 0, 0], "up": [0, 1, 0], "near": 0.5,
                 "far": 9, "projection": "orthographic", "height": 2.5},
      "model": [[2, 0, 0, 1], [0, 2, 0, 0], [0, 0, 2, 0], [0, 0, 0, 1]],
      "mesh": {"positions": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "indices": [[0, 1, 2]],
               "normals": [[0, 0, 1], [0, 0, 1], [0, 0, 1]]},
      "material": {"emission": [0.1, 0, 0], "ambient": [0.3, 0.3, 0.3],
                   "diffuse": [0.5, 0.6, 0.7], "specular": [1, 1, 1], "shininess": 12.5},
      "global_ambient": [0.05, 0.05, 0.05],
      "lights": [
        {"type": "point", "position": [1, 2, 3], "diffuse": [2, 2, 2], "specular": [0, 0, 0],
         "attenuation": [1, 0.1, 0.01]},
        {"type": "area", "center": [0, 3, 0], "edge_u": [1, 0, 0], "edge_v": [0, 0, 1],
         "samples_k": 3}
      ],
      "shading": "phong", "specular_model": "phong", "viewer": "local",
      "cull": false, "depth": false, "two_sided": true, "dither": true,
      "background": [0, 0, 0.5]
    }"#;
    let s = parse(json).unwrap();
    assert_eq!(
        s.camera.projection,
        Projection::Orthographic { height: 2.5 }
    );
    assert_eq!(s.camera.near, 0.5);
    assert_eq!(s.model[0], [2.0, 0.0, 0.0, 1.0]);
    assert_eq!(s.mesh.normals.as_ref().map(Vec::len), Some(3));
    assert_eq!(s.material.emission, [0.1, 0.0, 0.0]);
    assert_eq!(s.material.shininess, 12.5);
    assert_eq!(s.global_ambient, [0.05; 3]);
    assert_eq!(
        s.lights[0],
        LightDesc::Point {
            position: [1.0, 2.0, 3.0],
            diffuse: [2.0; 3],
            specular: [0.0; 3],
            attenuation: [1.0, 0.1, 0.01],
        }
    );
    assert!(matches!(
        s.lights[1],
        LightDesc::Area {
            samples_k: 3,
            attenuation: [1.0, 0.0, 0.0],
            ..
        }
    ));
    assert_eq!(
        (s.shading, s.specular_model, s.viewer),
        (Shading::Phong, SpecularModel::Phong, Viewer::Local)
    );
    assert!(!s.cull && !s.depth && s.two_sided && s.dither);
    assert_eq!(s.background, [0.0, 0.0, 0.5]);
}

#[test]
fn every_shipped_scene_parses_and_renders() {
    for name in SHIPPED {
        let path = scenes_dir().join(format!("{name}.json"));
        let scene = load_scene(&path).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!((scene.width, scene.height), (320, 240), "{name}");
        assert!(!scene.lights.is_empty(), "{name}: no lights");
        let frame = KernelScene::new(&scene)
            .unwrap_or_else(|e| panic!("{name}: {e}"))
            .render_frame()
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        let drawn = frame.covered.iter().filter(|&&c| c).count();
        assert!(drawn > 5_000, "{name}: only {drawn} pixels drawn");
    }
}

#[test]
fn no_unlisted_scene_files() {
    // Every shipped scene is covered by the tests above.
    let mut found: Vec<String> = std::fs::read_dir(scenes_dir())
        .unwrap()
        .filter_map(|e| {
            let p = e.ok()?.path();
            (p.extension()? == "json").then(|| p.file_stem().unwrap().to_string_lossy().into())
        })
        .collect();
    found.sort();
    let mut expected: Vec<String> = SHIPPED.iter().map(|s| s.to_string()).collect();
    expected.sort();
    assert_eq!(found, expected);
}

#[test]
fn sphere_file_matches_s1_in_code() {
    let from_file = load_scene(scenes_dir().join("sphere.json")).unwrap();
    let in_code = standard_scenes::s1(320, 240);
    assert_eq!(from_file, in_code);
    let a = KernelScene::new(&from_file)
        .unwrap()
        .render_frame()
        .unwrap();
    let b = KernelScene::new(&in_code).unwrap().render_frame().unwrap();
    assert_eq!(a.pixels, b.pixels);
    assert_eq!(a.covered, b.covered);
}

#[test]
fn bunny_file_matches_s4_in_code() {
    let from_file = load_scene(scenes_dir().join("bunny.json")).unwrap();
    let in_code = standard_scenes::s4(320, 240);
    assert_eq!(from_file, in_code);
    let a = KernelScene::new(&from_file)
        .unwrap()
        .render_frame()
        .unwrap();
    let b = KernelScene::new(&in_code).unwrap().render_frame().unwrap();
    assert_eq!(a.pixels, b.pixels);
    assert_eq!(a.covered, b.covered);
}

#[test]
fn shipped_scene_against_reference() {
    // The file path gives the same kernel-versus-reference figures as code.
    let scene = load_scene(scenes_dir().join("sphere.json")).unwrap();
    let (e, _) = common::kernel_vs_reference(&scene);
    common::assert_within_bound("sphere.json", &e);
}

#[test]
fn rejects_unknown_keys() {
    rejects(
        &BASE.replace("\"width\"", "\"widht\": 3, \"width\""),
        "widht: unknown key",
        "expected one of: width, height",
    );
    rejects(
        &BASE.replace("\"near\"", "\"nera\": 1, \"near\""),
        "camera.nera: unknown key",
        "",
    );
    rejects(
        &BASE.replace("\"exponent\"", "\"exponant\": 1, \"exponent\""),
        "lights[1].exponant: unknown key",
        "cutoff_deg",
    );
    // A key valid elsewhere but not for this kind of light.
    rejects(
        &BASE.replace("\"direction\"", "\"cutoff_deg\": 3, \"direction\""),
        "lights[0].cutoff_deg: unknown key",
        "",
    );
    // fovy_deg belongs to perspective cameras only.
    rejects(
        &BASE.replace(
            "\"fovy_deg\": 60",
            "\"projection\": \"orthographic\", \"fovy_deg\": 60, \"height\": 2",
        ),
        "camera.fovy_deg: unknown key",
        "",
    );
    rejects(
        &BASE.replace("\"indices\"", "\"uvs\": [], \"indices\""),
        "mesh.uvs: unknown key",
        "",
    );
    rejects(
        &BASE.replace(
            "\"width\": 32",
            "\"width\": 32, \"material\": {\"shinyness\": 3}",
        ),
        "material.shinyness: unknown key",
        "shininess",
    );
}

#[test]
fn rejects_missing_keys() {
    rejects(
        &BASE.replace("\"height\": 24,", ""),
        "height: missing required key",
        "",
    );
    rejects(
        &BASE.replace("\"near\": 0.1,", ""),
        "camera.near: missing required key",
        "",
    );
    rejects(
        &BASE.replace(", \"fovy_deg\": 60", ""),
        "camera.fovy_deg: missing required key",
        "",
    );
    rejects(
        &BASE.replace(", \"exponent\": 2", ""),
        "lights[1].exponent: missing required key",
        "",
    );
    rejects(
        &BASE.replace("\"type\": \"directional\", ", ""),
        "lights[0].type: missing required key",
        "",
    );
    rejects(
        &BASE.replace(", \"indices\": [[0, 1, 2]]", ""),
        "mesh.indices: missing required key",
        "",
    );
    rejects(
        &BASE.replace("\"width\": 32,", "\"width\": 32, \"mesh\": {\"generator\": \"sphere\", \"radius\": 1},")
            .replace("\"mesh\": {\"positions\": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], \"indices\": [[0, 1, 2]]},", ""),
        "mesh.segments: missing required key",
        "",
    );
}

#[test]
fn rejects_wrong_types() {
    rejects(
        &BASE.replace("\"width\": 32", "\"width\": \"32\""),
        "width: expected a non-negative integer",
        "string",
    );
    rejects(
        &BASE.replace("\"width\": 32", "\"width\": 32.5"),
        "width: expected a non-negative integer",
        "32.5",
    );
    rejects(
        &BASE.replace("\"width\": 32", "\"width\": -1"),
        "width: expected a non-negative integer",
        "",
    );
    rejects(
        &BASE.replace("\"far\": 10", "\"far\": [10]"),
        "camera.far: expected a number",
        "an array",
    );
    rejects(
        &BASE.replace("\"up\": [0, 1, 0]", "\"up\": [0, 1]"),
        "camera.up: expected an array of 3",
        "2 elements",
    );
    rejects(
        &BASE.replace("\"up\": [0, 1, 0]", "\"up\": [0, true, 0]"),
        "camera.up[1]: expected a number",
        "boolean",
    );
    rejects(
        &BASE.replace("\"width\": 32", "\"width\": 32, \"cull\": 1"),
        "cull: expected true or false",
        "",
    );
    rejects(
        &BASE.replace("\"width\": 32", "\"width\": 32, \"shading\": \"smooth\""),
        "shading: unknown variant `smooth`",
        "gouraud",
    );
    rejects(
        &BASE.replace("\"directional\"", "\"sun\""),
        "lights[0].type: unknown variant `sun`",
        "directional",
    );
    rejects(
        &BASE.replace("\"lights\": [", "\"lights\": [3, "),
        "lights[0]: expected an object",
        "a number",
    );
    rejects("[1, 2]", "top level: expected an object", "");
    rejects("{\"width\": 3", "not valid JSON", "line 1");
}

#[test]
fn rejects_non_finite_numbers() {
    rejects(
        &BASE.replace("\"cutoff_deg\": 30", "\"cutoff_deg\": 1e400"),
        "lights[1].cutoff_deg: ",
        "is not a finite number",
    );
    rejects(
        &BASE.replace("[1, 0, 0], [0, 1, 0]]", "[1, 0, 0], [0, -1e999, 0]]"),
        "mesh.positions[2][1]: ",
        "is not a finite number",
    );
    // JSON has no NaN or Infinity literals: a syntax error with the position.
    rejects(
        &BASE.replace("\"far\": 10", "\"far\": NaN"),
        "not valid JSON",
        "line 5",
    );
    rejects(
        &BASE.replace("\"far\": 10", "\"far\": Infinity"),
        "not valid JSON",
        "line 5",
    );
}

/// A number is at most 4096 characters long and a string 4096 bytes,
/// anywhere in the file (the mesh's arrays too): a bound on the work a
/// token takes, as SCENE_FORMAT.md's limits say. A number of exactly 4096
/// characters is read.
#[test]
fn tokens_are_at_most_4096_characters() {
    let zero = |len: usize| format!("0.{}", "0".repeat(len - 2));
    let scene = parse(&BASE.replace("\"far\": 10", &format!("\"far\": 1{}", zero(4095))))
        .expect("a number of 4096 characters is read");
    assert_eq!(scene.camera.far, 10.0);
    let at = parse(&BASE.replace(
        "[1, 0, 0], [0, 1, 0]]",
        &format!("[1, 0, 0], [0, {}, 0]]", zero(4096)),
    ));
    assert!(at.is_ok(), "{:?}", at.err());
    for len in [4097, 1_000_000] {
        rejects(
            &BASE.replace("\"far\": 10", &format!("\"far\": {}", zero(len))),
            "not valid JSON: number longer than 4096 characters at line 5",
            "",
        );
        rejects(
            &BASE.replace(
                "[1, 0, 0], [0, 1, 0]]",
                &format!("[1, 0, 0], [0, {}, 0]]", zero(len)),
            ),
            "not valid JSON: number longer than 4096 characters at line 6",
            "",
        );
    }
    rejects(
        &BASE.replace("\"directional\"", &format!("\"{}\"", "d".repeat(4097))),
        "not valid JSON: string longer than 4096 bytes",
        "",
    );
}

#[test]
fn rejects_out_of_range_values() {
    rejects(
        &BASE.replace("[[0, 1, 2]]", "[[0, 1, 3]]"),
        "mesh.indices[0]: index 3 out of range",
        "3 vertices",
    );
    rejects(
        &BASE.replace("\"cutoff_deg\": 30", "\"cutoff_deg\": 95"),
        "lights[1].cutoff_deg: 95 out of range",
        "[0, 90]",
    );
    rejects(
        &BASE.replace(
            "\"width\": 32",
            "\"width\": 32, \"material\": {\"diffuse\": [0, 2, 0]}",
        ),
        "material.diffuse: 2 out of range",
        "",
    );
    rejects(
        &BASE.replace("\"width\": 32", "\"width\": 9000"),
        "width: 9000 exceeds the maximum",
        "",
    );
    rejects(
        &BASE.replace("[[0, 1, 2]]", "[[0, 1, 4294967296]]"),
        "mesh.indices[0][2]: 4294967296 is too large",
        "",
    );
    let sphere = |segments: &str| {
        BASE.replace(
            "{\"positions\": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], \"indices\": [[0, 1, 2]]}",
            &format!("{{\"generator\": \"sphere\", \"segments\": {segments}, \"radius\": 1}}"),
        )
    };
    assert!(parse(&sphere("[8, 4]")).is_ok());
    rejects(
        &sphere("[8, 1]"),
        "mesh.segments[1]: 1 out of range",
        "2..=4096",
    );
    rejects(
        &sphere("[2, 4]"),
        "mesh.segments[0]: 2 out of range",
        "3..=4096",
    );
}

#[test]
fn rejects_bad_obj() {
    let dir = std::env::temp_dir().join(format!("fixshade-scene-file-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("bad.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n").unwrap();
    std::fs::write(dir.join("good.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    let with_obj = |file: &str| {
        BASE.replace(
            "{\"positions\": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], \"indices\": [[0, 1, 2]]}",
            &format!("{{\"obj\": \"{file}\"}}"),
        )
    };
    let good = parse_scene(&with_obj("good.obj"), &dir).unwrap();
    assert_eq!(good.mesh.indices, vec![[0, 1, 2]]);

    let err = parse_scene(&with_obj("bad.obj"), &dir).unwrap_err();
    let msg = err.to_string();
    assert!(msg.starts_with("mesh.obj: "), "{msg}");
    assert!(
        msg.contains("bad.obj: line 4: bad face vertex `x`"),
        "{msg}"
    );
    assert_eq!(err.key(), Some("mesh.obj"));

    let err = parse_scene(&with_obj("missing.obj"), &dir).unwrap_err();
    let msg = err.to_string();
    assert!(msg.starts_with("mesh.obj: cannot read "), "{msg}");
    assert!(msg.contains("missing.obj"), "{msg}");

    rejects(
        &with_obj("x.obj").replace("\"obj\": \"x.obj\"", "\"obj\": 3"),
        "mesh.obj: expected a string",
        "",
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn load_scene_reports_unreadable_file() {
    let err = load_scene("/no/such/dir/scene.json").unwrap_err();
    assert!(matches!(err, SceneFileError::Read { .. }));
    assert!(err
        .to_string()
        .starts_with("cannot read /no/such/dir/scene.json"));
}

#[test]
fn obj_resolves_against_the_scene_file() {
    // bunny.json names ../../tests/data/bunny.obj, relative to its own folder,
    // wherever the process runs.
    let scene = load_scene(scenes_dir().join("bunny.json")).unwrap();
    assert_eq!(scene.mesh, standard_scenes::bunny_mesh());
}

// ---------------------------------------------------------------------------
// Hostile files
// ---------------------------------------------------------------------------

use crate::heap;

/// A scratch folder for this test binary's files (the converter's tests
/// use it too).
pub(crate) fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("fixshade-hostile-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Runs `f` on another thread and fails if it takes more than a minute
/// (a read that blocks would otherwise hang the test run).
fn within_a_minute<T: Send + 'static>(f: impl FnOnce() -> T + Send + 'static) -> T {
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let _ = tx.send(f());
    });
    rx.recv_timeout(std::time::Duration::from_secs(60))
        .expect("the read did not end within a minute")
}

/// A scene or OBJ path naming something that is not a regular file (a
/// device that never ends, a FIFO nobody writes, a folder) is refused at
/// once, before anything is read.
#[test]
fn refuses_what_is_not_a_regular_file() {
    let dir = scratch("irregular");
    let fifo = dir.join("fifo");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    assert!(made.is_ok_and(|s| s.success()), "mkfifo failed");
    for path in [PathBuf::from("/dev/zero"), fifo.clone(), dir.clone()] {
        let p = path.clone();
        let err = within_a_minute(move || load_scene(&p).unwrap_err().to_string());
        assert!(
            err.contains("not a regular file"),
            "{}: {err}",
            path.display()
        );
        let obj = BASE.replace(
            "{\"positions\": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], \"indices\": [[0, 1, 2]]}",
            &format!("{{\"obj\": \"{}\"}}", path.display()),
        );
        let err = within_a_minute(move || parse(&obj).unwrap_err().to_string());
        assert!(err.starts_with("mesh.obj: cannot read "), "{err}");
        assert!(err.contains("not a regular file"), "{err}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// A file longer than `MAX_FILE_BYTES` is refused while it is read, scene
/// and OBJ alike; one of exactly that size is read.
#[test]
fn refuses_files_past_the_size_cap() {
    use fixshade_host::scene_file::MAX_FILE_BYTES;
    let dir = scratch("cap");
    let pad = |extra: u64| {
        let mut text = BASE.as_bytes().to_vec();
        text.resize((MAX_FILE_BYTES + extra) as usize, b' ');
        text
    };
    std::fs::write(dir.join("at.json"), pad(0)).unwrap();
    std::fs::write(dir.join("past.json"), pad(1)).unwrap();
    assert!(load_scene(dir.join("at.json")).is_ok());
    let err = load_scene(dir.join("past.json")).unwrap_err().to_string();
    assert!(
        err.contains(&format!("larger than {MAX_FILE_BYTES} bytes")),
        "{err}"
    );
    let mut obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n".to_vec();
    obj.resize((MAX_FILE_BYTES + 1) as usize, b'\n');
    std::fs::write(dir.join("past.obj"), obj).unwrap();
    let with_obj = BASE.replace(
        "{\"positions\": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], \"indices\": [[0, 1, 2]]}",
        "{\"obj\": \"past.obj\"}",
    );
    let err = parse_scene(&with_obj, &dir).unwrap_err().to_string();
    assert!(err.starts_with("mesh.obj: "), "{err}");
    assert!(
        err.contains(&format!("larger than {MAX_FILE_BYTES} bytes")),
        "{err}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// Reading takes at most the documented memory per byte of input: 2.25
/// bytes per byte of a scene file plus 16 MiB (`read_scene`), 3 bytes per
/// byte of an OBJ file plus 6 MiB (`generate::read_obj`), measured on
/// files of the shapes that cost the most per byte (positions written as
/// short as JSON allows, many short triangles, OBJ polygons fanned from
/// one-digit indices). The heap the reader's result keeps counts too.
#[test]
fn reading_memory_per_byte_of_input() {
    const MIB: usize = 1 << 20;
    let dir = scratch("memory");
    let measure = |path: &Path| {
        let before = heap::reset_peak();
        let scene = load_scene(path);
        let peak = heap::peak() - before;
        (scene, peak)
    };
    // JSON: 65 536 short positions and 1.5 M short triangles (12 MB).
    let mut json = String::from(
        r#"{"width": 32, "height": 24, "camera": {"eye": [0, 0, 3], "target": [0, 0, 0],
        "up": [0, 1, 0], "near": 0.1, "far": 10, "fovy_deg": 60},
        "mesh": {"positions": ["#,
    );
    for i in 0..65536 {
        json.push_str(if i == 0 { "[0,0,0]" } else { ",[0,0,0]" });
    }
    json.push_str(r#"], "indices": ["#);
    for i in 0..1_500_000 {
        json.push_str(if i == 0 { "[0,1,2]" } else { ",[0,1,2]" });
    }
    json.push_str("]}}");
    std::fs::write(dir.join("big.json"), &json).unwrap();
    let (scene, peak) = measure(&dir.join("big.json"));
    let scene = scene.unwrap();
    assert_eq!(scene.mesh.indices.len(), 1_500_000);
    println!("JSON {} bytes: peak {peak} bytes", json.len());
    assert!(
        peak <= json.len() * 9 / 4 + 16 * MIB,
        "JSON: {peak} bytes for {}",
        json.len()
    );

    // OBJ: long fanned polygons of one-digit indices, and short triangles.
    for (name, face, faces) in [
        (
            "fan",
            {
                let mut f = String::from("f 1 2 3");
                for _ in 0..8000 {
                    f.push_str(" 2 3");
                }
                f.push('\n');
                f
            },
            400,
        ),
        ("triangles", "f 1 2 3\n".to_string(), 1_000_000),
    ] {
        let mut obj = String::from("v 0 0 0\nv 1 0 0\nv 0 1 0\n");
        for _ in 0..faces {
            obj.push_str(&face);
        }
        std::fs::write(dir.join(format!("{name}.obj")), &obj).unwrap();
        let scene_text = BASE.replace(
            "{\"positions\": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], \"indices\": [[0, 1, 2]]}",
            &format!("{{\"obj\": \"{name}.obj\"}}"),
        );
        std::fs::write(dir.join(format!("{name}.json")), &scene_text).unwrap();
        let (scene, peak) = measure(&dir.join(format!("{name}.json")));
        assert!(!scene.unwrap().mesh.indices.is_empty());
        println!("OBJ {name} {} bytes: peak {peak} bytes", obj.len());
        assert!(
            peak <= obj.len() * 3 + 6 * MIB,
            "OBJ {name}: {peak} bytes for {}",
            obj.len()
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// A key, a variant name or an OBJ path holding a line break (or another
/// control character) is echoed escaped: the error stays one line.
#[test]
fn echoed_text_is_escaped() {
    rejects(
        &BASE.replace("\"width\": 32", "\"width\": 32, \"a\\nb\\u001b[2J\": 1"),
        "a\\nb\\u{1b}[2J: unknown key",
        "",
    );
    rejects(
        &BASE.replace("\"directional\"", "\"sun\\nset\""),
        "lights[0].type: unknown variant `sun\\nset`",
        "",
    );
    rejects(
        &BASE.replace(
            "{\"positions\": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], \"indices\": [[0, 1, 2]]}",
            "{\"obj\": \"no\\nsuch.obj\"}",
        ),
        "mesh.obj: cannot read ",
        "no\\nsuch.obj",
    );
}

/// The work a scene asks for is bounded: light samples a shaded point
/// (`MAX_LIGHT_SAMPLES`), and light evaluations a frame
/// (`MAX_LIGHT_EVALUATIONS`); both refused naming `lights`, the first
/// before anything is rendered. A 1 KB file of 64 area lights of 4096
/// samples took about 40 minutes a frame.
#[test]
fn refuses_work_past_the_limits() {
    let area = r#"{"type": "area", "center": [0, 3, 0], "edge_u": [1, 0, 0],
        "edge_v": [0, 0, 1], "samples_k": K}"#;
    let lights = |k: u32, n: usize| {
        let one = area.replace('K', &k.to_string());
        format!("\"lights\": [{}]", vec![one; n].join(", "))
    };
    let base_lights = BASE.find("\"lights\"").unwrap();
    let with = |l: String| format!("{}{l}\n}}", &BASE[..base_lights]);
    assert!(parse(&with(lights(64, 1))).is_ok());
    assert!(parse(&with(lights(8, 64))).is_ok());
    rejects(
        &with(lights(64, 64)),
        "lights: 262144 light samples",
        "more than 4096",
    );
    rejects(&with(lights(64, 2)), "lights: 8192 light samples", "");
    // 4096 samples over 1024 × 1024 pixels: past the evaluations a frame.
    let big = with(lights(64, 1))
        .replace("\"width\": 32", "\"width\": 1024")
        .replace("\"height\": 24", "\"height\": 1024");
    rejects(
        &big,
        "lights: 4096 light samples at ",
        "light evaluations a frame",
    );
}

/// What validation passes, the kernel renders: a scene the kernel would
/// refuse (a camera whose view does not fit its formats, a position out of
/// range, too many lights, a projection too narrow for the target) is
/// refused by the reader, naming the key; every scene the reader accepts
/// here renders.
#[test]
fn validation_agrees_with_rendering() {
    rejects(
        &BASE.replace("\"eye\": [0, 0, 3]", "\"eye\": [100, 100, 100]"),
        "camera: ",
        "",
    );
    rejects(
        &BASE.replace("[1, 0, 0], [0, 1, 0]]", "[1000, 0, 0], [0, 1, 0]]"),
        "mesh.positions: ",
        "",
    );
    rejects(&BASE.replace("\"far\": 10", "\"far\": 200"), "camera: ", "");
    let many = format!(
        "\"lights\": [{}]",
        vec!["{\"type\": \"directional\", \"direction\": [1, 1, 1]}"; 65].join(", ")
    );
    let at = BASE.find("\"lights\"").unwrap();
    rejects(
        &format!("{}{many}\n}}", &BASE[..at]),
        "lights: more than 64",
        "",
    );
    for edit in [
        ("\"eye\": [0, 0, 3]", "\"eye\": [60, 60, 60]"),
        ("\"far\": 10", "\"far\": 100"),
        ("\"fovy_deg\": 60", "\"fovy_deg\": 0.5"),
        ("\"width\": 32", "\"width\": 4000"),
    ] {
        let text = BASE.replace(edit.0, edit.1);
        if let Ok(scene) = parse(&text) {
            let k = KernelScene::new(&scene).expect("a valid scene converts");
            k.render_frame().expect("a valid scene renders");
        }
    }
}

/// A key given twice is an error, not the last one winning silently.
#[test]
fn rejects_duplicate_keys() {
    rejects(
        &BASE.replace(
            "\"eye\": [0, 0, 3]",
            "\"eye\": [0, 0, 3], \"eye\": [0, 0, 4]",
        ),
        "camera.eye: duplicate key",
        "",
    );
    rejects(
        &BASE.replace(
            "\"indices\": [[0, 1, 2]]",
            "\"indices\": [[0, 1, 2]], \"indices\": []",
        ),
        "mesh.indices: duplicate key",
        "",
    );
}
