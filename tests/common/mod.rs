//! Scenes and comparison helpers shared by the integration tests.
#![allow(dead_code)]

use fixshade::error_measure::{compare, ErrorStats};
use fixshade::generate;
use fixshade::reference;
use fixshade::scene_desc::{
    CameraDesc, LightDesc, MaterialDesc, Projection, SceneDesc, Shading, SpecularModel, Viewer,
};
use fixshade::scene_kernel::{KernelFrame, KernelScene};

/// The bunny, shipped in tests/data.
pub fn bunny_mesh() -> fixshade::scene_desc::MeshDesc {
    generate::load_obj(include_str!("../data/bunny.obj")).expect("bunny parses")
}

/// S1 of the error-against-time issue: sphere 48 × 24, Gouraud, depth and
/// culling, one directional light, Blinn–Phong, infinite viewer.
pub fn s1(width: u32, height: u32, lon: u32, lat: u32) -> SceneDesc {
    let camera = CameraDesc {
        eye: [0.0, 0.0, 3.0],
        target: [0.0; 3],
        up: [0.0, 1.0, 0.0],
        near: 0.1,
        far: 10.0,
        projection: Projection::Perspective { fovy_deg: 60.0 },
    };
    let mut s = SceneDesc::new(width, height, camera, generate::sphere(lon, lat, 1.0));
    s.global_ambient = [0.1; 3];
    s.material = MaterialDesc {
        emission: [0.0; 3],
        ambient: [1.0, 0.5, 0.2],
        diffuse: [1.0, 0.5, 0.2],
        specular: [0.5; 3],
        shininess: 32.0,
    };
    s.lights = vec![LightDesc::Directional {
        direction: [1.0, 1.0, 1.0],
        diffuse: [1.0; 3],
        specular: [1.0; 3],
    }];
    s.shading = Shading::Gouraud;
    s.specular_model = SpecularModel::Blinn;
    s.viewer = Viewer::Infinite;
    s
}

/// S4: the bunny with a point light and a spot light, Phong shading.
pub fn s4(width: u32, height: u32) -> SceneDesc {
    let camera = CameraDesc {
        eye: [0.0, 5.0, 16.0],
        target: [0.0, 4.0, 0.0],
        up: [0.0, 1.0, 0.0],
        near: 0.5,
        far: 50.0,
        projection: Projection::Perspective { fovy_deg: 45.0 },
    };
    let mut s = SceneDesc::new(width, height, camera, bunny_mesh());
    s.global_ambient = [0.1; 3];
    s.material = MaterialDesc {
        emission: [0.0; 3],
        ambient: [0.6, 0.6, 0.7],
        diffuse: [0.7, 0.7, 0.8],
        specular: [0.6; 3],
        shininess: 64.0,
    };
    s.lights = vec![
        LightDesc::Point {
            position: [6.0, 10.0, 8.0],
            diffuse: [0.8, 0.7, 0.6],
            specular: [1.0; 3],
            attenuation: [1.0, 0.02, 0.001],
        },
        LightDesc::Spot {
            position: [-6.0, 12.0, 6.0],
            axis: [0.5, -1.0, -0.5],
            cutoff_deg: 25.0,
            exponent: 8.0,
            diffuse: [0.3, 0.4, 0.9],
            specular: [0.5; 3],
            attenuation: [1.0, 0.0, 0.0],
        },
    ];
    s.shading = Shading::Phong;
    s.specular_model = SpecularModel::Blinn;
    s.viewer = Viewer::Local;
    s
}

/// Renders `scene` with the kernel and the reference and compares them.
pub fn kernel_vs_reference(scene: &SceneDesc) -> (ErrorStats, KernelFrame) {
    scene.validate().expect("valid scene");
    let k = KernelScene::new(scene)
        .expect("kernel scene")
        .render_frame()
        .expect("kernel render");
    let r = reference::render(scene).expect("reference render");
    (compare(&k.pixels, &k.covered, &r), k)
}

/// The bound of SPEC.md 7 as the issues state it: at most 1 LSB per channel
/// on pixels both cover, coverage mismatches at most 0.1% of covered pixels.
pub fn assert_within_bound(name: &str, e: &ErrorStats) {
    println!("{name}: {e}");
    assert!(e.covered_both > 0, "{name}: nothing covered");
    assert!(
        e.max_error.iter().all(|&m| m <= 1),
        "{name}: max error {:?} LSB",
        e.max_error
    );
    assert!(
        e.coverage_mismatch_share <= 0.001,
        "{name}: coverage mismatches {:.4}%",
        100.0 * e.coverage_mismatch_share
    );
}
