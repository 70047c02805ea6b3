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
///
/// ```
/// use fixshade_host::standard_scenes::{s1, HEIGHT, WIDTH};
/// assert_eq!(WIDTH * 3, HEIGHT * 4); // 320 × 240, 4:3
/// assert_eq!(s1(WIDTH, HEIGHT).width, WIDTH);
/// ```
pub const WIDTH: u32 = 320;
/// The standard size of the report's frames.
///
/// ```
/// use fixshade_host::standard_scenes::{s2, HEIGHT, WIDTH};
/// let quad = s2(WIDTH, HEIGHT).mesh; // as wide as the viewport's aspect ratio
/// assert_eq!(quad.positions[1], [WIDTH as f64 / HEIGHT as f64, 1.0, 0.0]);
/// ```
pub const HEIGHT: u32 = 240;

/// The bunny, shipped in tests/data.
///
/// ```
/// let bunny = fixshade_host::standard_scenes::bunny_mesh();
/// assert_eq!((bunny.positions.len(), bunny.indices.len()), (1839, 3674));
/// assert!(bunny.normals.is_none()); // the renderers derive them
/// ```
pub fn bunny_mesh() -> MeshDesc {
    generate::load_obj(include_str!("../tests/data/bunny.obj")).expect("bunny parses")
}

/// The sphere scene of S1 and S3 with `lon × lat` segments: Gouraud,
/// depth and culling, one directional light towards (1, 1, 1), Blinn–Phong,
/// infinite viewer.
///
/// ```
/// use fixshade_host::{reference::render, scene_desc::*, standard_scenes::sphere_scene};
/// let s = sphere_scene(32, 32, 12, 6);
/// assert_eq!(s.mesh.indices.len(), 12 * (2 * 6 - 2));
/// assert_eq!((s.shading, s.specular_model), (Shading::Gouraud, SpecularModel::Blinn));
/// assert!(s.depth && s.cull && s.viewer == Viewer::Infinite);
/// assert_eq!(s.lights, [LightDesc::directional([1.0, 1.0, 1.0])]);
/// let frame = render(&s).unwrap();
/// let (lit, dark) = (frame.pixel(20, 12).unwrap(), frame.pixel(12, 20).unwrap());
/// assert!(lit[0] > dark[0]); // brighter towards the upper right, where the light is
/// assert_eq!(frame.pixel(0, 0), None);
/// ```
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
///
/// ```
/// use fixshade_host::scene_desc::{LightDesc, Shading, Viewer};
/// use fixshade_host::standard_scenes::s4;
/// let s = s4(64, 48);
/// assert!(matches!(s.lights[..], [LightDesc::Point { .. }, LightDesc::Spot { .. }]));
/// assert_eq!((s.shading, s.viewer), (Shading::Phong, Viewer::Local));
/// assert_eq!(s.mesh.indices.len(), 3674);
/// assert!(s.validate().is_ok());
/// ```
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
///
/// ```
/// use fixshade_host::standard_scenes::{s1, sphere_scene};
/// let s = s1(64, 48);
/// assert_eq!(s, sphere_scene(64, 48, 48, 24));
/// assert_eq!(s.mesh.indices.len(), 48 * (2 * 24 - 2)); // 2208 triangles
/// ```
pub fn s1(width: u32, height: u32) -> SceneDesc {
    sphere_scene(width, height, 48, 24)
}

/// S3: the sphere 192 × 96.
///
/// ```
/// use fixshade_host::standard_scenes::{s3, HEIGHT, WIDTH};
/// let s = s3(WIDTH, HEIGHT);
/// assert_eq!(s.mesh.indices.len(), 36_480); // 192 · (2 · 96 − 2)
/// assert_eq!(s.mesh.positions.len(), 193 * 97);
/// ```
pub fn s3(width: u32, height: u32) -> SceneDesc {
    sphere_scene(width, height, 192, 96)
}

/// S2: a quad covering the whole viewport, red, green, blue and white at
/// its corners, Gouraud, no depth test (see the module docs).
///
/// ```
/// use fixshade_host::{reference::render, standard_scenes::s2};
/// let frame = render(&s2(8, 6)).unwrap();
/// assert_eq!(frame.covered_count(), 8 * 6); // the whole viewport
/// let near = |x, y, want: [f64; 3]| {
///     frame.pixel(x, y).unwrap().iter().zip(want).all(|(c, w)| (c - w).abs() < 0.2)
/// };
/// assert!(near(0, 0, [1.0, 0.0, 0.0]) && near(7, 0, [0.0, 1.0, 0.0]));
/// assert!(near(7, 5, [0.0, 0.0, 1.0]) && near(0, 5, [1.0, 1.0, 1.0]));
/// ```
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
///
/// ```
/// use fixshade_host::standard_scenes::{all, HEIGHT, WIDTH};
/// let scenes = all();
/// let names: Vec<_> = scenes.iter().map(|(name, _)| *name).collect();
/// assert_eq!(names, ["S1", "S2", "S3", "S4"]);
/// assert!(scenes.iter().all(|(_, s)| (s.width, s.height) == (WIDTH, HEIGHT)));
/// assert!(scenes.iter().all(|(_, s)| s.validate().is_ok()));
/// ```
pub fn all() -> [(&'static str, SceneDesc); 4] {
    [
        ("S1", s1(WIDTH, HEIGHT)),
        ("S2", s2(WIDTH, HEIGHT)),
        ("S3", s3(WIDTH, HEIGHT)),
        ("S4", s4(WIDTH, HEIGHT)),
    ]
}
