//! Scene files: every shipped scene parses, every kind of bad file is
//! rejected with a message naming the key or line, and a scene read from its
//! file renders the same pixels as the same scene built in code.

// The shared helpers import more than this file uses.
#[allow(unused_imports)]
mod common;

use std::path::{Path, PathBuf};

use fixshade::scene_desc::{LightDesc, Projection, Shading, SpecularModel, Viewer};
use fixshade::scene_file::{load_scene, parse_scene, SceneFileError};
use fixshade::scene_kernel::KernelScene;
use fixshade::standard_scenes;

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

fn parse(json: &str) -> Result<fixshade::scene_desc::SceneDesc, SceneFileError> {
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
    assert_eq!(s.model, fixshade::scene_desc::IDENTITY);
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
