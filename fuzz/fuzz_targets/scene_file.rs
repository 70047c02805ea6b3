//! Arbitrary bytes read as a scene file and an OBJ file: the input is the
//! scene's JSON, then a NUL byte, then the OBJ text (no NUL: no OBJ text).
//! The OBJ text is written as `m.obj` into a scratch folder, so that a scene
//! naming `{"obj": "m.obj"}` reads it; the JSON bytes are written there as
//! `s.json` and read with `load_scene` too (invalid UTF-8 included).
//!
//! Nothing may panic; every error is one line (a scene file error has no
//! control character at all: what the file holds is echoed escaped); a
//! scene that is read passes `validate()`, converts with
//! `KernelScene::new`, and a small one renders; `parse_scene` and
//! `load_scene` agree; an OBJ mesh that is read has every index in range
//! and as many normals as positions, and reading it through a tiny buffer
//! gives the same result.
#![no_main]

use std::io::BufReader;
use std::path::PathBuf;
use std::sync::OnceLock;

use fixshade_host::generate::{load_obj, read_obj, ObjError};
use fixshade_host::scene_desc::{MeshDesc, SceneDesc};
use fixshade_host::scene_file::{load_scene, parse_scene, SceneFileError};
use fixshade_host::scene_kernel::KernelScene;
use libfuzzer_sys::fuzz_target;

/// The scratch folder, one per fuzzing process.
fn dir() -> &'static PathBuf {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let d = std::env::temp_dir().join(format!("fixshade-fuzz-scene-{}", std::process::id()));
        std::fs::create_dir_all(&d).expect("scratch folder");
        d
    })
}

fn check_scene_error(e: &SceneFileError) {
    let msg = e.to_string();
    assert!(
        !msg.chars().any(char::is_control),
        "scene error not one escaped line: {msg:?}"
    );
}

fn check_obj_error(e: &ObjError) {
    let msg = e.to_string();
    assert!(
        !msg.contains('\n') && !msg.contains('\r'),
        "OBJ error not one line: {msg:?}"
    );
}

fn check_scene(scene: &SceneDesc) {
    if let Err(e) = scene.validate() {
        panic!("a scene that was read fails validate(): {e}");
    }
    let k = match KernelScene::new(scene) {
        Ok(k) => k,
        Err(e) => panic!("validation passed but KernelScene::new failed: {e}"),
    };
    // Small frames and few light samples only, to keep runs fast.
    if u64::from(scene.width) * u64::from(scene.height) <= 64 * 64
        && scene.mesh.indices.len() <= 4096
        && scene.light_samples() <= 16
    {
        if let Err(e) = k.render_frame() {
            panic!("validation passed but render_frame failed: {e:?}");
        }
    }
}

fn check_mesh(m: &MeshDesc) {
    let n = m.positions.len();
    assert!(n <= 65536, "{n} positions");
    for tri in &m.indices {
        for &i in tri {
            assert!((i as usize) < n, "index {i} out of range ({n} positions)");
        }
    }
    if let Some(normals) = &m.normals {
        assert_eq!(normals.len(), n, "normals and positions differ in count");
    }
    assert!(m
        .positions
        .iter()
        .chain(m.normals.iter().flatten())
        .all(|p| p.iter().all(|x| x.is_finite())));
}

/// The OBJ reader on raw bytes, through a 7-byte buffer (lines split over
/// many reads).
fn read_obj_small(bytes: &[u8]) -> Result<MeshDesc, ObjError> {
    read_obj(|| Ok(BufReader::with_capacity(7, bytes)))
}

fuzz_target!(|data: &[u8]| {
    let (json, obj) = match data.iter().position(|&b| b == 0) {
        Some(i) => (&data[..i], &data[i + 1..]),
        None => (data, &data[data.len()..]),
    };
    let dir = dir();
    std::fs::write(dir.join("m.obj"), obj).expect("write m.obj");
    let scene_path = dir.join("s.json");
    std::fs::write(&scene_path, json).expect("write s.json");

    // The OBJ reader directly.
    let small = read_obj_small(obj);
    match &small {
        Ok(m) => check_mesh(m),
        Err(e) => check_obj_error(e),
    }
    match std::str::from_utf8(obj) {
        Ok(text) => {
            let r = load_obj(text);
            match &r {
                Ok(m) => check_mesh(m),
                Err(e) => check_obj_error(e),
            }
            assert_eq!(
                r, small,
                "load_obj and read_obj through a small buffer differ"
            );
        }
        Err(_) => assert!(small.is_err(), "an OBJ that is not UTF-8 was read"),
    }

    // The scene reader: from the file (bytes), and from the text.
    let loaded = load_scene(&scene_path);
    match &loaded {
        Ok(s) => check_scene(s),
        Err(e) => check_scene_error(e),
    }
    if let Ok(text) = std::str::from_utf8(json) {
        let parsed = parse_scene(text, dir);
        match &parsed {
            Ok(s) => check_scene(s),
            Err(e) => check_scene_error(e),
        }
        match (&parsed, &loaded) {
            (Ok(a), Ok(b)) => assert_eq!(a, b, "parse_scene and load_scene differ"),
            (Err(a), Err(b)) => assert_eq!(
                a.to_string(),
                b.to_string(),
                "parse_scene and load_scene fail differently"
            ),
            _ => panic!(
                "parse_scene and load_scene disagree: {:?} / {:?}",
                parsed.as_ref().err().map(ToString::to_string),
                loaded.as_ref().err().map(ToString::to_string)
            ),
        }
    } else {
        // The JSON reader must not accept bytes that are not UTF-8... except
        // where JSON allows them: nowhere outside strings, and strings are
        // checked. So a non-UTF-8 scene must be an error.
        assert!(loaded.is_err(), "a scene that is not UTF-8 was read");
    }
});
