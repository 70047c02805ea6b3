//! Host only: the standard scenes of the error-against-time report, as
//! [`SceneDesc`]s that the kernel and the reference both render.
//!
//! | name | what | measures |
//! | --- | --- | --- |
//! | S1 | UV sphere 48 × 24, Gouraud, depth, culling, one directional light, Blinn–Phong | the typical lit mesh |
//! | S2 | one quad covering the viewport, per-vertex red, green, blue, white, Gouraud, no depth | fill rate |
//! | S3 | S1 with 192 × 96 segments (36 480 triangles) | vertex and set-up cost |
//! | S4 | the Stanford bunny, Phong shading, a point light and a spot light | per-pixel lighting |
//!
//! S2's "per-vertex colours, no lighting" is expressed with the lighting
//! model so that both renderers draw it: three directional lights of
//! intensity √3, red along +X, green along +Y, blue along +Z, a white
//! diffuse material and no ambient; the vertices' normals point along +X,
//! +Y, +Z and (1, 1, 1)/√3, which gives exactly red, green, blue and white
//! (the √3 saturates and is clamped). Four vertices are lit, so the frame
//! measures interpolation and fill.

use std::vec;

use crate::generate;
use crate::scene_desc::{
    CameraDesc, LightDesc, MaterialDesc, MeshDesc, Projection, SceneDesc, Shading, SpecularModel,
    Viewer,
};

/// The standard size of the report's frames.
pub const WIDTH: u32 = 320;
/// The standard size of the report's frames.
pub const HEIGHT: u32 = 240;

/// The bunny, shipped in tests/data.
pub fn bunny_mesh() -> MeshDesc {
    generate::load_obj(include_str!("../tests/data/bunny.obj")).expect("bunny parses")
}

/// The sphere scene of S1 and S3 with `lon × lat` segments: Gouraud,
/// depth and culling, one directional light towards (1, 1, 1), Blinn–Phong,
/// infinite viewer.
pub fn sphere_scene(width: u32, height: u32, lon: u32, lat: u32) -> SceneDesc {
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

/// S1: the sphere 48 × 24.
pub fn s1(width: u32, height: u32) -> SceneDesc {
    sphere_scene(width, height, 48, 24)
}

/// S3: the sphere 192 × 96.
pub fn s3(width: u32, height: u32) -> SceneDesc {
    sphere_scene(width, height, 192, 96)
}

/// S2: a quad covering the whole viewport, red, green, blue and white at
/// its corners, Gouraud, no depth test (see the module docs).
pub fn s2(width: u32, height: u32) -> SceneDesc {
    let aspect = width.max(1) as f64 / height.max(1) as f64;
    let camera = CameraDesc {
        eye: [0.0, 0.0, 1.0],
        target: [0.0; 3],
        up: [0.0, 1.0, 0.0],
        near: 0.5,
        far: 2.0,
        projection: Projection::Orthographic { height: 2.0 },
    };
    let s3 = 1.0 / 3f64.sqrt();
    let mesh = MeshDesc {
        positions: vec![
            [-aspect, 1.0, 0.0],
            [aspect, 1.0, 0.0],
            [aspect, -1.0, 0.0],
            [-aspect, -1.0, 0.0],
        ],
        normals: Some(vec![
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [s3, s3, s3],
        ]),
        indices: vec![[0, 3, 2], [0, 2, 1]],
    };
    let mut s = SceneDesc::new(width, height, camera, mesh);
    s.global_ambient = [0.0; 3];
    s.material = MaterialDesc {
        emission: [0.0; 3],
        ambient: [0.0; 3],
        diffuse: [1.0; 3],
        specular: [0.0; 3],
        shininess: 0.0,
    };
    let k = 3f64.sqrt();
    s.lights = vec![
        LightDesc::Directional {
            direction: [1.0, 0.0, 0.0],
            diffuse: [k, 0.0, 0.0],
            specular: [0.0; 3],
        },
        LightDesc::Directional {
            direction: [0.0, 1.0, 0.0],
            diffuse: [0.0, k, 0.0],
            specular: [0.0; 3],
        },
        LightDesc::Directional {
            direction: [0.0, 0.0, 1.0],
            diffuse: [0.0, 0.0, k],
            specular: [0.0; 3],
        },
    ];
    s.shading = Shading::Gouraud;
    s.depth = false;
    s.cull = false;
    s
}

/// The four standard scenes at the standard size, with their names.
pub fn all() -> [(&'static str, SceneDesc); 4] {
    [
        ("S1", s1(WIDTH, HEIGHT)),
        ("S2", s2(WIDTH, HEIGHT)),
        ("S3", s3(WIDTH, HEIGHT)),
        ("S4", s4(WIDTH, HEIGHT)),
    ]
}
